const FOOTPRINT_MAX: f32 = 4.0;

struct Photon {
    position: vec3<f32>,
    cos_i: f32,
    path: f32,
    ok: bool
}

const SUB: i32 = 64;

const TENT_WEIGHT: u32 = 4096u;

@group(0) @binding(3)
var<storage, read_write> acc: array<atomic<u32>>;

@group(0) @binding(0)
var<uniform> cfg: package_cascaded_common_Cascaded;

@group(0) @binding(4)
var eye: texture_2d<f32>;

fn floor_div(a: i32) -> i32 {
    return select(a / SUB, -((-a + SUB - 1) / SUB), a < 0);
}

fn footprint_side(p: vec3<f32>, px: vec2<f32>) -> vec2<f32> {
    let x = clamp(i32(floor(px.x)), 0, i32(cfg.width) - 1);
    let y = clamp(i32(floor(px.y)), 0, i32(cfg.height) - 1);
    let e = textureLoad(eye, vec2<i32>(x, y), 0);
    if e.w == 0.0 {
        return vec2<f32>(0.0);
    }
    let pixels = cfg.view2.z / (e.y * e.w);
    let l = cfg.light.xyz;
    let a = cfg.e_u.xyz * cfg.view.z;
    let b = (cfg.e_v.xyz - l * (cfg.e_v.z / l.z)) * cfg.view.w;
    let pa = package_cascaded_common__1eye_project(cfg, p + a);
    let pb = package_cascaded_common__1eye_project(cfg, p + b);
    if pa.z <= 0.0 || pb.z <= 0.0 {
        return vec2<f32>(min(sqrt(pixels), FOOTPRINT_MAX));
    }
    let da = pa.xy - px;
    let db = pb.xy - px;
    let aspect = clamp((abs(da.x) + abs(db.x)) / max(abs(da.y) + abs(db.y), 1e-6), 0.001, 1000.0);
    return min(vec2<f32>(sqrt(pixels * aspect), sqrt(pixels / aspect)), vec2<f32>(FOOTPRINT_MAX));
}

@group(0) @binding(2)
var gterrain: texture_2d<f32>;

@group(0) @binding(1)
var gwater: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.res || id.y >= cfg.res {
        return;
    }
    let l = cfg.light.xyz;
    let o = package_cascaded_common__1ray_origin(cfg, id.y, id.x);
    let gw = textureLoad(gwater, vec2<i32>(id.xy), 0);
    let water = o + l * gw.x;
    let normal = gw.yzw;
    var terrain = o + l * (-o.z / l.z);
    if cfg.terrain.z != 0.0 {
        terrain = o + l * textureLoad(gterrain, vec2<i32>(id.xy), 0).x;
    }
    if (cfg.flags & 4u) != 0u {
        for (var c = 0u; c < 3u; c++) {
            let ph = place_photon(water, normal, terrain, cfg.ior[c]);
            if ph.ok {
                splat(ph, c, c + 1u, cfg.ior[c]);
            }
        }
    }
    else {
        let ph = place_photon(water, normal, terrain, cfg.ior.w);
        if ph.ok {
            splat(ph, 0u, 3u, cfg.ior.w);
        }
    }
}

struct package_cascaded_common_Cascaded {
    light: vec4<f32>,
    e_u: vec4<f32>,
    e_v: vec4<f32>,
    view: vec4<f32>,
    view2: vec4<f32>,
    eye_pos: vec4<f32>,
    eye_fwd: vec4<f32>,
    eye_right: vec4<f32>,
    eye_up: vec4<f32>,
    ior: vec4<f32>,
    absorption: vec4<f32>,
    ramps: vec4<f32>,
    terrain: vec4<f32>,
    post: vec4<f32>,
    fars: vec4<f32>,
    fluxes: vec4<f32>,
    width: u32,
    height: u32,
    res: u32,
    cascade: u32,
    flags: u32,
    wrap: u32,
    walls: u32,
    _pad1: u32
}

fn package_cascaded_common__1box_hit(c: package_cascaded_common_Cascaded, o: vec3<f32>, d: vec3<f32>) -> f32 {
    if d.z >= 0.0 {
        return -1.0;
    }
    var s0 = 0.0;
    if o.z > c.light.w {
        s0 = (c.light.w - o.z) / d.z;
    }
    let p = o + d * s0;
    if !package_cascaded_common__1in_square(c, p) {
        return -1.0;
    }
    let s_floor = -p.z / d.z;
    if package_cascaded_common__1in_square(c, p + d * s_floor) {
        return s0 + s_floor;
    }
    var sx = 3e38;
    var sy = 3e38;
    if d.x > 0.0 {
        sx = (c.e_u.w - p.x) / d.x;
    }
    else if d.x < 0.0 {
        sx = -p.x / d.x;
    }
    if d.y > 0.0 {
        sy = (c.e_u.w - p.y) / d.y;
    }
    else if d.y < 0.0 {
        sy = -p.y / d.y;
    }
    let s = min(sx, sy);
    if s >= 3e38 {
        return -1.0;
    }
    return s0 + s;
}

fn package_cascaded_common__1eye_project(c: package_cascaded_common_Cascaded, p: vec3<f32>) -> vec3<f32> {
    let v = p - c.eye_pos.xyz;
    let z = dot(v, c.eye_fwd.xyz);
    if z <= 0.0 {
        return vec3<f32>(0.0, 0.0, -1.0);
    }
    let sx = dot(v, c.eye_right.xyz) / z / (c.eye_pos.w * c.eye_fwd.w);
    let sy = dot(v, c.eye_up.xyz) / z / c.eye_pos.w;
    return vec3<f32>((sx + 1.0) * 0.5 * f32(c.width), (1.0 - sy) * 0.5 * f32(c.height), z);
}

fn package_cascaded_common__1in_square(c: package_cascaded_common_Cascaded, q: vec3<f32>) -> bool {
    return q.x >= 0.0 && q.y >= 0.0 && q.x <= c.e_u.w && q.y <= c.e_u.w;
}

fn package_cascaded_common__1ray_origin(c: package_cascaded_common_Cascaded, i: u32, j: u32) -> vec3<f32> {
    let u = c.view.x + (f32(j) + 0.5) * c.view.z;
    let v = c.view.y + (f32(i) + 0.5) * c.view.w;
    return c.e_u.xyz * u + c.e_v.xyz * v + c.light.xyz * c.view2.x;
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

fn photon_weight(ph: Photon, ior: f32, c: u32) -> f32 {
    if (cfg.flags & 2u) != 0u {
        return package_shaders_optics__1fresnel_transmittance(ph.cos_i, 1.0, ior) / cfg.e_v.w * exp(-cfg.absorption[c] * ph.path);
    }
    let d = cfg.light.w - ph.position.z;
    let deep = clamp((cfg.ramps.y - d) / cfg.ramps.y, 0.0, 1.0);
    let shallow = clamp((d - cfg.ramps.x) / cfg.ramps.z, 0.0, 1.0);
    return cfg.absorption.w * deep * shallow;
}

fn place_photon(water: vec3<f32>, normal: vec3<f32>, terrain: vec3<f32>, ior: f32) -> Photon {
    var ph: Photon;
    ph.ok = false;
    let l = cfg.light.xyz;
    if terrain.z >= water.z {
        return ph;
    }
    let cos_i = -dot(l, normal);
    if cos_i <= 0.0 {
        return ph;
    }
    let t4 = package_shaders_optics__1refract_dir(l, normal, 1.0 / ior);
    if t4.w == 0.0 {
        return ph;
    }
    let t = t4.xyz;
    if cfg.walls != 0u && cfg.terrain.z == 0.0 {
        let s = package_cascaded_common__1box_hit(cfg, water, t);
        if s < 0.0 {
            return ph;
        }
        ph.position = water + t * s;
    }
    else if (cfg.flags & 1u) != 0u {
        ph.position = water + t * ((water.z - terrain.z) / -t.z);
    }
    else {
        ph.position = water + t * (dot(terrain - water, t) / dot(t, t));
    }
    ph.cos_i = cos_i;
    ph.path = length(ph.position - water);
    ph.ok = true;
    return ph;
}

fn splat(ph: Photon, c0: u32, c1: u32, ior: f32) {
    let px = package_cascaded_common__1eye_project(cfg, ph.position);
    if px.z <= 0.0 {
        return;
    }
    var q = vec3<u32>(0u);
    for (var c = c0; c < c1; c++) {
        q[c] = u32(photon_weight(ph, ior, c) * cfg.ramps.w + 0.5);
    }
    let base = cfg.cascade * cfg.width * cfg.height * 3u;
    if (cfg.flags & 8u) != 0u {
        splat_footprint(base, px.xy, footprint_side(ph.position, px.xy), q, c0, c1);
        return;
    }
    if px.x < 0.0 || px.y < 0.0 || px.x >= f32(cfg.width) || px.y >= f32(cfg.height) {
        return;
    }
    let at = base + (u32(px.y) * cfg.width + u32(px.x)) * 3u;
    for (var c = c0; c < c1; c++) {
        atomicAdd(&acc[at + c], q[c]);
    }
}

fn splat_footprint(base: u32, centre: vec2<f32>, side: vec2<f32>, q: vec3<u32>, c0: u32, c1: u32) {
    let reach = FOOTPRINT_MAX + 1.0;
    if !(centre.x > -reach && centre.y > -reach && centre.x < f32(cfg.width) + reach && centre.y < f32(cfg.height) + reach) {
        return;
    }
    let h_x = clamp(i32(round(side.x * f32(SUB))), 1, i32(FOOTPRINT_MAX) * SUB);
    let h_y = clamp(i32(round(side.y * f32(SUB))), 1, i32(FOOTPRINT_MAX) * SUB);
    let c_x = i32(floor(centre.x * f32(SUB)));
    let c_y = i32(floor(centre.y * f32(SUB)));
    var cum_y = 0u;
    for (var j = floor_div(c_y - h_y); j <= floor_div(c_y + h_y - 1); j++) {
        let next_y = tent_cumulative(SUB * (j + 1) - c_y, h_y);
        let row = q * next_y / TENT_WEIGHT - q * cum_y / TENT_WEIGHT;
        cum_y = next_y;
        if j < 0 || j >= i32(cfg.height) {
            continue;
        }
        var cum_x = 0u;
        for (var i = floor_div(c_x - h_x); i <= floor_div(c_x + h_x - 1); i++) {
            let next_x = tent_cumulative(SUB * (i + 1) - c_x, h_x);
            if i >= 0 && i < i32(cfg.width) {
                let at = base + (u32(j) * cfg.width + u32(i)) * 3u;
                let share = row * next_x / TENT_WEIGHT - row * cum_x / TENT_WEIGHT;
                for (var c = c0; c < c1; c++) {
                    if share[c] != 0u {
                        atomicAdd(&acc[at + c], share[c]);
                    }
                }
            }
            cum_x = next_x;
        }
    }
}

fn tent_cumulative(t: i32, h: i32) -> u32 {
    let den = 2 * h * h;
    var num = den;
    if t <= -h {
        num = 0;
    }
    else if t <= 0 {
        num = (t + h) * (t + h);
    }
    else if t < h {
        num = den - (h - t) * (h - t);
    }
    return TENT_WEIGHT * u32(num) / u32(den);
}
