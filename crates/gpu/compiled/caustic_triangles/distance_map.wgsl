struct DistanceMapInfo {
    centre: vec4<f32>,
    cube: u32,
    layers: u32,
    base: u32,
    linear_steps: u32,
    secant_iterations: u32
}

struct Hit {
    d: f32,
    surface: vec4<f32>,
    found: bool
}

const MAX_LAYERS: u32 = 8u;

fn cube_texel_dir(face: u32, row: u32, col: u32, c: u32) -> vec3<f32> {
    let s = (f32(col) + 0.5) / f32(c) * 2.0 - 1.0;
    let t = (f32(row) + 0.5) / f32(c) * 2.0 - 1.0;
    let sign = select(-1.0, 1.0, face % 2u == 0u);
    let a = face / 2u;
    var d = vec3<f32>(s, t, sign);
    if a == 0u {
        d = vec3<f32>(sign, s, t);
    }
    else if a == 1u {
        d = vec3<f32>(t, sign, s);
    }
    return normalize(d);
}

@group(0) @binding(1)
var<storage, read> dm: array<vec4<f32>>;

fn dm_info(c: package__1caustic_triangles_common_CausticTriangles, base: u32) -> DistanceMapInfo {
    return DistanceMapInfo(c.centre, c.cube, c.layers, base, c.linear_steps, c.secant_iterations);
}

fn dm_offset(layer: u32, p: vec3<f32>) -> vec2<f32> {
    let l = p - dmg.centre.xyz;
    let len = length(l);
    let s = dm_sample(layer, l / max(len, 1e-30));
    if s.w == 0.0 {
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(len - abs(s.w), 1.0);
}

fn dm_sample(layer: u32, d: vec3<f32>) -> vec4<f32> {
    let c = f32(dmg.cube);
    let fst = face_st(d);
    let face = u32(fst.x);
    let x = (fst.y + 1.0) * 0.5 * c - 0.5;
    let y = (fst.z + 1.0) * 0.5 * c - 0.5;
    let x0 = u32(clamp(i32(floor(x)), 0, i32(dmg.cube) - 2));
    let y0 = u32(clamp(i32(floor(y)), 0, i32(dmg.cube) - 2));
    let fx = clamp(x - f32(x0), 0.0, 1.0);
    let fy = clamp(y - f32(y0), 0.0, 1.0);
    let q0 = dm_texel(layer, face, y0, x0);
    let q1 = dm_texel(layer, face, y0, x0 + 1u);
    let q2 = dm_texel(layer, face, y0 + 1u, x0);
    let q3 = dm_texel(layer, face, y0 + 1u, x0 + 1u);
    let all_glass = q0.w > 0.0 && q1.w > 0.0 && q2.w > 0.0 && q3.w > 0.0;
    let all_diffuse = q0.w < 0.0 && q1.w < 0.0 && q2.w < 0.0 && q3.w < 0.0;
    var v: vec4<f32>;
    if all_glass || all_diffuse {
        v = q0 * ((1.0 - fx) * (1.0 - fy)) + q1 * (fx * (1.0 - fy)) + q2 * ((1.0 - fx) * fy) + q3 * (fx * fy);
    }
    else if fy >= 0.5 {
        v = select(q2, q3, fx >= 0.5);
    }
    else {
        v = select(q0, q1, fx >= 0.5);
    }
    if v.w == 0.0 {
        return vec4<f32>(0.0);
    }
    let n = v.xyz;
    let len = length(n);
    return vec4<f32>(select(vec3<f32>(0.0), n / len, len > 0.0), v.w);
}

fn dm_texel(layer: u32, face: u32, row: u32, col: u32) -> vec4<f32> {
    return dm[dmg.base + ((layer * 6u + face) * dmg.cube + row) * dmg.cube + col];
}

fn dm_trace(x: vec3<f32>, r: vec3<f32>, d0: f32, d1: f32, inside: bool) -> Hit {
    return dm_trace_mode(x, r, d0, d1, select(0u, 1u, inside));
}

fn dm_trace_mode(x: vec3<f32>, r: vec3<f32>, d0: f32, d1: f32, mode: u32) -> Hit {
    var best: Hit;
    best.found = false;
    if d1 <= d0 {
        return best;
    }
    let steps = max(dmg.linear_steps, 1u);
    let dd = (d1 - d0) / f32(steps);
    let tol = 8.0 / f32(dmg.cube);
    let layers = min(dmg.layers, MAX_LAYERS);
    var prev: array<vec2<f32>, MAX_LAYERS>;
    for (var k = 0u; k < layers; k++) {
        prev[k] = dm_offset(k, x + r * d0);
    }
    for (var step = 1u; step <= steps; step++) {
        let d_hi = d0 + dd * f32(step);
        let d_lo = d_hi - dd;
        for (var k = 0u; k < layers; k++) {
            let cur = dm_offset(k, x + r * d_hi);
            let f_lo = prev[k];
            if f_lo.y != 0.0 && cur.y != 0.0 && ((f_lo.x < 0.0) != (cur.x < 0.0)) {
                let h = secant(k, x, r, vec2<f32>(d_lo, f_lo.x), vec2<f32>(d_hi, cur.x), tol);
                if h.found {
                    let glass = h.surface.w > 0.0;
                    let entering = dot(r, h.surface.xyz) < 0.0;
                    let ok = !glass || (mode == 0u && entering) || (mode == 1u && !entering);
                    if ok && (!best.found || h.d < best.d) {
                        best = h;
                    }
                }
            }
            prev[k] = cur;
        }
        if best.found {
            return best;
        }
    }
    return best;
}

var<private> dmg: DistanceMapInfo;

fn face_st(d: vec3<f32>) -> vec3<f32> {
    let a = abs(d);
    if a.x >= a.y && a.x >= a.z {
        return vec3<f32>(select(1.0, 0.0, d.x >= 0.0), d.y / a.x, d.z / a.x);
    }
    if a.y >= a.z {
        return vec3<f32>(select(3.0, 2.0, d.y >= 0.0), d.z / a.y, d.x / a.y);
    }
    return vec3<f32>(select(5.0, 4.0, d.z >= 0.0), d.x / a.z, d.y / a.z);
}

struct package__1caustic_triangles_common_CausticTriangles {
    centre: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    w: vec4<f32>,
    rect: vec4<f32>,
    floor: vec4<f32>,
    p: u32,
    cube: u32,
    layers: u32,
    depth: u32,
    linear_steps: u32,
    secant_iterations: u32,
    fresnel: u32,
    area_rule: u32,
    width: u32,
    height: u32,
    light_cube: u32,
    dm_base: u32,
    light: vec4<f32>,
    spot: vec4<f32>,
    merge_levels: u32,
    merge_small: f32,
    lattice: u32,
    wrap: u32,
    absorption: vec4<f32>,
    band: u32,
    periodic: u32
}

fn secant(layer: u32, x: vec3<f32>, r: vec3<f32>, lo_in: vec2<f32>, hi_in: vec2<f32>, tol: f32) -> Hit {
    var miss: Hit;
    miss.found = false;
    var d_lo = lo_in.x;
    var f_lo = lo_in.y;
    var d_hi = hi_in.x;
    var f_hi = hi_in.y;
    var d = d_lo + (d_hi - d_lo) * f_lo / (f_lo - f_hi);
    for (var it = 0u; it < dmg.secant_iterations; it++) {
        let o = dm_offset(layer, x + r * d);
        if o.y == 0.0 {
            return miss;
        }
        if (o.x < 0.0) == (f_lo < 0.0) {
            d_lo = d;
            f_lo = o.x;
        }
        else {
            d_hi = d;
            f_hi = o.x;
        }
        if f_lo == f_hi {
            break;
        }
        d = d_lo + (d_hi - d_lo) * f_lo / (f_lo - f_hi);
    }
    let p = x + r * d;
    let l = p - dmg.centre.xyz;
    let len = length(l);
    let s = dm_sample(layer, l / max(len, 1e-30));
    if s.w == 0.0 || abs(len - abs(s.w)) > tol * abs(s.w) {
        return miss;
    }
    return Hit(d, s, true);
}

fn sphere_span(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let oc = o - dmg.centre.xyz;
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - dmg.centre.w * dmg.centre.w);
    if disc <= 0.0 {
        return vec2<f32>(0.0, -1.0);
    }
    let s = sqrt(disc);
    return vec2<f32>(max(-b - s, 0.0), -b + s);
}
