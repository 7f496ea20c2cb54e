// Technique `cascaded`, photon pass (paper §3.4): each light texel's photon refracted (§3.4.1),
// placed by Eq. 3.3 or on the plane through the terrain point (§3.4.2), weighted (§3.4.3), projected
// into the eye and added to this cascade's screen-space caustic map (fixed point, atomicAdd): into
// its pixel, or (flag bit 3) spread over its footprint, a tent sized from the eye pass. Under
// wavelength dispersion (§3.6) one photon per RGB channel. CPU twin: `photons`, `footprint_side`,
// `splat_footprint`.

import package::cascaded::common::{Cascaded, box_hit, eye_project, ray_origin};
import package::shaders::optics::{fresnel_transmittance, refract_dir};

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var gwater: texture_2d<f32>;
@group(0) @binding(2) var gterrain: texture_2d<f32>;
@group(0) @binding(3) var<storage, read_write> acc: array<atomic<u32>>;
@group(0) @binding(4) var eye: texture_2d<f32>;

// `FOOTPRINT_SUBPIXELS`, `FOOTPRINT_MAX`, `TENT_WEIGHT`.
const SUB: i32 = 64;
const FOOTPRINT_MAX: f32 = 4.0;
const TENT_WEIGHT: u32 = 4096u;

struct Photon {
    position: vec3<f32>,
    cos_i: f32,
    path: f32,
    ok: bool,
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
    let t4 = refract_dir(l, normal, 1.0 / ior);
    if t4.w == 0.0 {
        return ph;
    }
    let t = t4.xyz;
    if cfg.walls != 0u && cfg.terrain.z == 0.0 {
        // Walls: the refracted ray's exact end on the floor or a wall (`box_hit`).
        let s = box_hit(cfg, water, t);
        if s < 0.0 {
            return ph;
        }
        ph.position = water + t * s;
    } else if (cfg.flags & 1u) != 0u {
        ph.position = water + t * ((water.z - terrain.z) / -t.z);
    } else {
        ph.position = water + t * (dot(terrain - water, t) / dot(t, t));
    }
    ph.cos_i = cos_i;
    ph.path = length(ph.position - water);
    ph.ok = true;
    return ph;
}

fn photon_weight(ph: Photon, ior: f32, c: u32) -> f32 {
    if (cfg.flags & 2u) != 0u {
        return fresnel_transmittance(ph.cos_i, 1.0, ior) / cfg.e_v.w * exp(-cfg.absorption[c] * ph.path);
    }
    let d = cfg.light.w - ph.position.z;
    let deep = clamp((cfg.ramps.y - d) / cfg.ramps.y, 0.0, 1.0);
    let shallow = clamp((d - cfg.ramps.x) / cfg.ramps.z, 0.0, 1.0);
    return cfg.absorption.w * deep * shallow;
}

// `footprint_side`: the photons' spacing on the screen around px, per axis (area from the eye pass,
// aspect from the texel's floor parallelogram projected from p); 0 where the pixel sees no floor.
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
    let pa = eye_project(cfg, p + a);
    let pb = eye_project(cfg, p + b);
    if pa.z <= 0.0 || pb.z <= 0.0 {
        return vec2<f32>(min(sqrt(pixels), FOOTPRINT_MAX));
    }
    let da = pa.xy - px;
    let db = pb.xy - px;
    let aspect = clamp((abs(da.x) + abs(db.x)) / max(abs(da.y) + abs(db.y), 1e-6), 1e-3, 1e3);
    return min(vec2<f32>(sqrt(pixels * aspect), sqrt(pixels / aspect)), vec2<f32>(FOOTPRINT_MAX));
}

// `tent_cumulative`: TENT_WEIGHT times the unit tent of half-width h integrated up to t.
fn tent_cumulative(t: i32, h: i32) -> u32 {
    let den = 2 * h * h;
    var num = den;
    if t <= -h {
        num = 0;
    } else if t <= 0 {
        num = (t + h) * (t + h);
    } else if t < h {
        num = den - (h - t) * (h - t);
    }
    return TENT_WEIGHT * u32(num) / u32(den);
}

// `floor(a / SUB)` for negative a too (`div_euclid`).
fn floor_div(a: i32) -> i32 {
    return select(a / SUB, -((-a + SUB - 1) / SUB), a < 0);
}

// `splat_footprint`: the integer weights q[c0..c1] spread over a separable tent of half-widths
// `side`, split over its rows, then each row's pixels, as differences of
// floor(q * cumulative share / TENT_WEIGHT): they add up to q exactly.
fn splat_footprint(base: u32, centre: vec2<f32>, side: vec2<f32>, q: vec3<u32>, c0: u32, c1: u32) {
    let reach = FOOTPRINT_MAX + 1.0;
    if !(centre.x > -reach && centre.y > -reach && centre.x < f32(cfg.width) + reach
        && centre.y < f32(cfg.height) + reach) {
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

fn splat(ph: Photon, c0: u32, c1: u32, ior: f32) {
    let px = eye_project(cfg, ph.position);
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

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.res || id.y >= cfg.res {
        return;
    }
    let l = cfg.light.xyz;
    let o = ray_origin(cfg, id.y, id.x);
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
    } else {
        let ph = place_photon(water, normal, terrain, cfg.ior.w);
        if ph.ok {
            splat(ph, 0u, 3u, cfg.ior.w);
        }
    }
}
