struct CameraPass {
    position: vec4<f32>,
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    sky: vec4<f32>,
    floor_albedo: vec4<f32>,
    wall_albedo: vec4<f32>,
    light_color: vec4<f32>,
    light: vec4<f32>,
    spot_axis: vec4<f32>,
    floor: vec4<f32>,
    width: u32,
    height: u32,
    generators: u32,
    cube: u32,
    map_width: u32,
    map_height: u32,
    _pad0: u32,
    _pad1: u32
}

const EPS: f32 = 0.0001;

struct SceneHit {
    t: f32,
    normal: vec3<f32>,
    glass: bool,
    floor: bool,
    found: bool,
    generator: u32
}

@group(0) @binding(0)
var<uniform> cam: CameraPass;

@group(0) @binding(4)
var cube_map: texture_2d<f32>;

fn cube_texel(d: vec3<f32>) -> vec3<u32> {
    let fst = package__1caustic_triangles__1distance_map__1face_st(d);
    let c = f32(cam.cube);
    let col = u32(clamp(i32(floor((fst.y + 1.0) * 0.5 * c)), 0, i32(cam.cube) - 1));
    let row = u32(clamp(i32(floor((fst.z + 1.0) * 0.5 * c)), 0, i32(cam.cube) - 1));
    let y = u32(fst.x) * cam.cube + row;
    return vec3<u32>(col, y, y * cam.cube + col);
}

@group(0) @binding(5)
var floor_map: texture_2d<f32>;

@group(0) @binding(2)
var<storage, read> gens: array<package__1caustic_triangles_common_CausticTriangles>;

@group(0) @binding(6)
var<storage, read_write> image: array<vec4<f32>>;

fn irradiance_at(y: vec3<f32>, n: vec3<f32>, on_floor: bool) -> f32 {
    let b = cam.up.w;
    var e = 0.0;
    if cam.sky.w == 0.0 {
        let l = cam.light.xyz;
        let cos = -dot(n, l);
        if cos > 0.0 && !occluded(y + n * EPS, -l) {
            e += cos / -l.z;
        }
        if on_floor {
            let px = (y.xy - cam.floor.xy) / cam.floor.z * vec2<f32>(f32(cam.map_width), f32(cam.map_height));
            let j = floor(px.x);
            let i = floor(px.y);
            if j >= 0.0 && i >= 0.0 && j < f32(cam.map_width) && i < f32(cam.map_height) {
                e += textureLoad(floor_map, vec2<u32>(u32(j), u32(i)), 0).x;
            }
        }
        return e;
    }
    let v = y - cam.light.xyz;
    let dist = length(v);
    let dir = v / dist;
    let k = cube_texel(dir);
    let cos = -dot(n, dir);
    let in_cone = cam.light.w <= -2.0 || dot(dir, cam.spot_axis.xyz) >= cam.light.w;
    if cos > 0.0 && in_cone && dist <= shadow[k.z] * (1.0 + b) {
        e += cam.floor_albedo.w * cos / (dist * dist);
    }
    let c = textureLoad(cube_map, k.xy, 0);
    if c.x > 0.0 {
        let receiver = c.y / c.x;
        if abs(dist - receiver) <= b * receiver {
            e += c.x;
        }
    }
    return e;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cam.width || id.y >= cam.height {
        return;
    }
    let half = cam.position.w;
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(cam.width) - 1.0) * half * cam.forward.w;
    let sy = (1.0 - 2.0 * (f32(id.y) + 0.5) / f32(cam.height)) * half;
    let d = normalize(cam.forward.xyz + cam.right.xyz * sx + cam.up.xyz * sy);
    image[id.y * cam.width + id.x] = vec4<f32>(radiance(cam.position.xyz, d), 1.0);
}

fn nearest(o: vec3<f32>, d: vec3<f32>, mode: u32) -> SceneHit {
    var best: SceneHit;
    best.found = false;
    best.t = 3e38;
    if d.z < 0.0 && o.z > 0.0 {
        best = SceneHit(-o.z / d.z, vec3<f32>(0.0, 0.0, 1.0), false, true, true, 0u);
    }
    for (var g = 0u; g < cam.generators; g++) {
        package__1caustic_triangles__1distance_map_dmg = package__1caustic_triangles__1distance_map__1dm_info(gens[g], gens[g].dm_base);
        let span = package__1caustic_triangles__1distance_map__1sphere_span(o, d);
        if span.y <= 0.0 || span.x >= best.t {
            continue;
        }
        let h = package__1caustic_triangles__1distance_map__2dm_trace_mode(o + d * span.x, d, 0.0, min(span.y, best.t) - span.x, mode);
        if h.found && span.x + h.d < best.t {
            best = SceneHit(span.x + h.d, h.surface.xyz, h.surface.w > 0.0, false, true, g);
        }
    }
    return best;
}

fn occluded(o: vec3<f32>, d: vec3<f32>) -> bool {
    for (var g = 0u; g < cam.generators; g++) {
        package__1caustic_triangles__1distance_map_dmg = package__1caustic_triangles__1distance_map__1dm_info(gens[g], gens[g].dm_base);
        let span = package__1caustic_triangles__1distance_map__1sphere_span(o, d);
        if span.y > 0.0 && package__1caustic_triangles__1distance_map__2dm_trace_mode(o + d * span.x, d, 0.0, span.y - span.x, 0u).found {
            return true;
        }
    }
    return false;
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

fn package__1caustic_triangles__1distance_map__1sphere_span(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let oc = o - package__1caustic_triangles__1distance_map_dmg.centre.xyz;
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - package__1caustic_triangles__1distance_map_dmg.centre.w * package__1caustic_triangles__1distance_map_dmg.centre.w);
    if disc <= 0.0 {
        return vec2<f32>(0.0, -1.0);
    }
    let s = sqrt(disc);
    return vec2<f32>(max(-b - s, 0.0), -b + s);
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

fn radiance(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let h = nearest(o, d, 0u);
    if !h.found {
        return cam.sky.xyz;
    }
    if !h.glass {
        return shade_diffuse(o, d, h);
    }
    let g = gens[h.generator];
    let ior = g.u.w;
    let p = o + d * h.t;
    let n = h.normal;
    let cos_i = max(-dot(d, n), 0.0);
    let reflected = secondary(p, normalize(reflect(d, n)));
    let t = package_shaders_optics__1refract_dir(d, n, 1.0 / ior);
    if t.w == 0.0 {
        return reflected;
    }
    let t_in = package_shaders_optics__1fresnel_transmittance(cos_i, 1.0, ior);
    var x = p;
    var r = normalize(t.xyz);
    package__1caustic_triangles__1distance_map_dmg = package__1caustic_triangles__1distance_map__1dm_info(g, g.dm_base);
    let eps = 0.0001 * package__1caustic_triangles__1distance_map_dmg.centre.w;
    for (var event = 0u; event < g.depth; event++) {
        let span = package__1caustic_triangles__1distance_map__1sphere_span(x, r);
        if span.y <= 0.0 {
            break;
        }
        let hit = package__1caustic_triangles__1distance_map__2dm_trace_mode(x, r, eps, span.y, 1u);
        if !hit.found || hit.surface.w < 0.0 {
            break;
        }
        x += r * hit.d;
        let n_in = -hit.surface.xyz;
        let cos = -dot(r, n_in);
        let out = package_shaders_optics__1refract_dir(r, n_in, ior);
        if out.w != 0.0 {
            let t_out = package_shaders_optics__1fresnel_transmittance(cos, ior, 1.0);
            let through = secondary(x, normalize(out.xyz));
            return reflected * (1.0 - t_in) + through * (t_in * t_out);
        }
        r = normalize(reflect(r, n_in));
    }
    return reflected * (1.0 - t_in);
}

fn secondary(o_in: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let o = o_in + d * EPS;
    let h = nearest(o, d, 2u);
    if !h.found {
        return cam.sky.xyz;
    }
    return shade_diffuse(o, d, h);
}

fn shade_diffuse(o: vec3<f32>, d: vec3<f32>, h: SceneHit) -> vec3<f32> {
    let y = o + d * h.t;
    var n = h.normal;
    if dot(n, d) > 0.0 {
        n = -n;
    }
    var albedo = cam.wall_albedo.xyz;
    if h.floor {
        albedo = cam.floor_albedo.xyz;
    }
    let e = irradiance_at(y, n, h.floor);
    return albedo * (vec3<f32>(cam.right.w) + cam.light_color.xyz * e);
}

@group(0) @binding(3)
var<storage, read> shadow: array<f32>;
