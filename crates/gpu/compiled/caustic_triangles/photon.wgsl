const INVALID: vec4<f32> = vec4<f32>(0.0, 0.0, -1.0, 0.0);

struct PhotonRay {
    start: vec4<f32>,
    dir: vec3<f32>
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= u.p || id.y >= u.p {
        return;
    }
    package__1caustic_triangles__1distance_map_dmg = package__1caustic_triangles__1distance_map__1dm_info(u, 0u);
    photons[id.y * u.p + id.x] = trace_photon(id.y, id.x);
}

struct package__1caustic_triangles__1distance_map_DistanceMapInfo {
    centre: vec4<f32>,
    cube: u32,
    layers: u32,
    base: u32,
    linear_steps: u32,
    secant_iterations: u32
}

struct package__1caustic_triangles__1distance_map_Hit {
    d: f32,
    surface: vec4<f32>,
    found: bool
}

const package__1caustic_triangles__1distance_map__1MAX_LAYERS: u32 = 8u;

fn package__1caustic_triangles__1distance_map__1dm_info(c: package__1caustic_triangles_common_CausticTriangles, base: u32) -> package__1caustic_triangles__1distance_map_DistanceMapInfo {
    return package__1caustic_triangles__1distance_map_DistanceMapInfo(c.centre, c.cube, c.layers, base, c.linear_steps, c.secant_iterations);
}

fn package__1caustic_triangles__1distance_map__1dm_offset(layer: u32, p: vec3<f32>) -> vec2<f32> {
    let l = p - package__1caustic_triangles__1distance_map_dmg.centre.xyz;
    let len = length(l);
    let s = package__1caustic_triangles__1distance_map__1dm_sample(layer, l / max(len, 1e-30));
    if s.w == 0.0 {
        return vec2<f32>(0.0, 0.0);
    }
    return vec2<f32>(len - abs(s.w), 1.0);
}

fn package__1caustic_triangles__1distance_map__1dm_sample(layer: u32, d: vec3<f32>) -> vec4<f32> {
    let c = f32(package__1caustic_triangles__1distance_map_dmg.cube);
    let fst = package__1caustic_triangles__1distance_map__1face_st(d);
    let face = u32(fst.x);
    let x = (fst.y + 1.0) * 0.5 * c - 0.5;
    let y = (fst.z + 1.0) * 0.5 * c - 0.5;
    let x0 = u32(clamp(i32(floor(x)), 0, i32(package__1caustic_triangles__1distance_map_dmg.cube) - 2));
    let y0 = u32(clamp(i32(floor(y)), 0, i32(package__1caustic_triangles__1distance_map_dmg.cube) - 2));
    let fx = clamp(x - f32(x0), 0.0, 1.0);
    let fy = clamp(y - f32(y0), 0.0, 1.0);
    let q0 = package__1caustic_triangles__1distance_map__1dm_texel(layer, face, y0, x0);
    let q1 = package__1caustic_triangles__1distance_map__1dm_texel(layer, face, y0, x0 + 1u);
    let q2 = package__1caustic_triangles__1distance_map__1dm_texel(layer, face, y0 + 1u, x0);
    let q3 = package__1caustic_triangles__1distance_map__1dm_texel(layer, face, y0 + 1u, x0 + 1u);
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

fn package__1caustic_triangles__1distance_map__1dm_texel(layer: u32, face: u32, row: u32, col: u32) -> vec4<f32> {
    return package__1caustic_triangles__1distance_map_dm[package__1caustic_triangles__1distance_map_dmg.base + ((layer * 6u + face) * package__1caustic_triangles__1distance_map_dmg.cube + row) * package__1caustic_triangles__1distance_map_dmg.cube + col];
}

fn package__1caustic_triangles__1distance_map__1dm_trace(x: vec3<f32>, r: vec3<f32>, d0: f32, d1: f32, inside: bool) -> package__1caustic_triangles__1distance_map_Hit {
    return package__1caustic_triangles__1distance_map__2dm_trace_mode(x, r, d0, d1, select(0u, 1u, inside));
}

fn package__1caustic_triangles__1distance_map__1face_st(d: vec3<f32>) -> vec3<f32> {
    let a = abs(d);
    if a.x >= a.y && a.x >= a.z {
        return vec3<f32>(select(1.0, 0.0, d.x >= 0.0), d.y / a.x, d.z / a.x);
    }
    if a.y >= a.z {
        return vec3<f32>(select(3.0, 2.0, d.y >= 0.0), d.z / a.y, d.x / a.y);
    }
    return vec3<f32>(select(5.0, 4.0, d.z >= 0.0), d.x / a.z, d.y / a.z);
}

fn package__1caustic_triangles__1distance_map__2dm_trace_mode(x: vec3<f32>, r: vec3<f32>, d0: f32, d1: f32, mode: u32) -> package__1caustic_triangles__1distance_map_Hit {
    var best: package__1caustic_triangles__1distance_map_Hit;
    best.found = false;
    if d1 <= d0 {
        return best;
    }
    let steps = max(package__1caustic_triangles__1distance_map_dmg.linear_steps, 1u);
    let dd = (d1 - d0) / f32(steps);
    let tol = 8.0 / f32(package__1caustic_triangles__1distance_map_dmg.cube);
    let layers = min(package__1caustic_triangles__1distance_map_dmg.layers, package__1caustic_triangles__1distance_map__1MAX_LAYERS);
    var prev: array<vec2<f32>, package__1caustic_triangles__1distance_map__1MAX_LAYERS>;
    for (var k = 0u; k < layers; k++) {
        prev[k] = package__1caustic_triangles__1distance_map__1dm_offset(k, x + r * d0);
    }
    for (var step = 1u; step <= steps; step++) {
        let d_hi = d0 + dd * f32(step);
        let d_lo = d_hi - dd;
        for (var k = 0u; k < layers; k++) {
            let cur = package__1caustic_triangles__1distance_map__1dm_offset(k, x + r * d_hi);
            let f_lo = prev[k];
            if f_lo.y != 0.0 && cur.y != 0.0 && ((f_lo.x < 0.0) != (cur.x < 0.0)) {
                let h = package__1caustic_triangles__1distance_map_secant(k, x, r, vec2<f32>(d_lo, f_lo.x), vec2<f32>(d_hi, cur.x), tol);
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

@group(0) @binding(1)
var<storage, read> package__1caustic_triangles__1distance_map_dm: array<vec4<f32>>;

var<private> package__1caustic_triangles__1distance_map_dmg: package__1caustic_triangles__1distance_map_DistanceMapInfo;

fn package__1caustic_triangles__1distance_map_secant(layer: u32, x: vec3<f32>, r: vec3<f32>, lo_in: vec2<f32>, hi_in: vec2<f32>, tol: f32) -> package__1caustic_triangles__1distance_map_Hit {
    var miss: package__1caustic_triangles__1distance_map_Hit;
    miss.found = false;
    var d_lo = lo_in.x;
    var f_lo = lo_in.y;
    var d_hi = hi_in.x;
    var f_hi = hi_in.y;
    var d = d_lo + (d_hi - d_lo) * f_lo / (f_lo - f_hi);
    for (var it = 0u; it < package__1caustic_triangles__1distance_map_dmg.secant_iterations; it++) {
        let o = package__1caustic_triangles__1distance_map__1dm_offset(layer, x + r * d);
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
    let l = p - package__1caustic_triangles__1distance_map_dmg.centre.xyz;
    let len = length(l);
    let s = package__1caustic_triangles__1distance_map__1dm_sample(layer, l / max(len, 1e-30));
    if s.w == 0.0 || abs(len - abs(s.w)) > tol * abs(s.w) {
        return miss;
    }
    return package__1caustic_triangles__1distance_map_Hit(d, s, true);
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

fn package_shaders_optics__1fresnel_transmittance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = min(abs(cos_i_in), 1.0);
    let sin_t = n1 / n2 * sqrt(max(1.0 - cos_i * cos_i, 0.0));
    if sin_t >= 1.0 {
        return 0.0;
    }
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 1.0 - 0.5 * (rs * rs + rp * rp);
}

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

fn photon_ray(i: u32, j: u32) -> PhotonRay {
    let q = u.rect.xy + u.rect.zw * vec2<f32>(f32(j) + 0.5, f32(i) + 0.5);
    let c = u.centre.xyz;
    let radius = u.centre.w;
    if u.light.w == 0.0 {
        let x = c + u.u.xyz * (q.x - dot(c, u.u.xyz)) + u.v.xyz * (q.y - dot(c, u.v.xyz)) - u.w.xyz * radius;
        return PhotonRay(vec4<f32>(x, u.v.w), u.w.xyz);
    }
    let len2 = 1.0 + dot(q, q);
    let d = (u.w.xyz + u.u.xyz * q.x + u.v.xyz * q.y) / sqrt(len2);
    let none = PhotonRay(vec4<f32>(0.0, 0.0, 0.0, -1.0), d);
    if u.spot.w > -2.0 && dot(d, u.spot.xyz) < u.spot.w {
        return none;
    }
    let oc = u.light.xyz - c;
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - radius * radius);
    if disc <= 0.0 {
        return none;
    }
    let t = max(-b - sqrt(disc), 0.0);
    return PhotonRay(vec4<f32>(u.light.xyz + d * t, u.v.w / (len2 * sqrt(len2))), d);
}

@group(0) @binding(2)
var<storage, read_write> photons: array<vec4<f32>>;

fn trace_photon(i: u32, j: u32) -> vec4<f32> {
    let ray = photon_ray(i, j);
    if ray.start.w < 0.0 {
        return INVALID;
    }
    let c = u.centre.xyz;
    let radius = u.centre.w;
    var x = ray.start.xyz;
    var r = ray.dir;
    var inside = false;
    var hit_glass = false;
    var power = ray.start.w;
    var d0 = 0.0;
    var refractions = 0u;
    var tir = 0u;
    let eps = 0.0001 * radius;
    let ior = u.u.w;
    for (var event = 0u; event <= u.depth; event++) {
        var d_floor = 3e38;
        if r.z < 0.0 {
            d_floor = -x.z / r.z;
        }
        let oc = x - c;
        let b = dot(oc, r);
        let disc = b * b - (dot(oc, oc) - radius * radius);
        var d_out = 0.0;
        if disc > 0.0 {
            d_out = -b + sqrt(disc);
        }
        let h = package__1caustic_triangles__1distance_map__1dm_trace(x, r, d0, min(d_out, d_floor), inside);
        if !h.found {
            if !hit_glass || inside || r.z >= 0.0 {
                return INVALID;
            }
            let p = x + r * d_floor;
            return vec4<f32>(p.xy, power, f32(refractions + 64u * tir));
        }
        if h.surface.w < 0.0 || event == u.depth {
            return INVALID;
        }
        hit_glass = true;
        x += r * h.d;
        var n = h.surface.xyz;
        var n1 = 1.0;
        var n2 = ior;
        if inside {
            n = -n;
            n1 = ior;
            n2 = 1.0;
        }
        let cos_i = -dot(r, n);
        let t = package_shaders_optics__1refract_dir(r, n, n1 / n2);
        if t.w != 0.0 {
            if u.fresnel != 0u {
                power *= package_shaders_optics__1fresnel_transmittance(cos_i, n1, n2);
            }
            r = normalize(t.xyz);
            inside = !inside;
            refractions += 1u;
        }
        else {
            r = normalize(r - 2.0 * dot(r, n) * n);
            tir += 1u;
        }
        d0 = eps;
    }
    return INVALID;
}

@group(0) @binding(0)
var<uniform> u: package__1caustic_triangles_common_CausticTriangles;
