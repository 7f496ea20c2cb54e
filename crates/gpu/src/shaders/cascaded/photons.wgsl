// Technique `cascaded`, photon pass (paper §3.4): each light texel's photon refracted (§3.4.1),
// placed by Eq. 3.3 or on the plane through the terrain point (§3.4.2), weighted (§3.4.3), projected
// into the eye and added to its pixel of this cascade's screen-space caustic map (fixed point,
// atomicAdd). Under wavelength dispersion (§3.6) one photon per RGB channel. CPU twin: `photons`.

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var gwater: texture_2d<f32>;
@group(0) @binding(2) var gterrain: texture_2d<f32>;
@group(0) @binding(3) var<storage, read_write> acc: array<atomic<u32>>;

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
    if (cfg.flags & 1u) != 0u {
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

fn splat(ph: Photon, c0: u32, c1: u32, ior: f32) {
    let px = eye_project(cfg, ph.position);
    if px.z <= 0.0 || px.x < 0.0 || px.y < 0.0 || px.x >= f32(cfg.width) || px.y >= f32(cfg.height) {
        return;
    }
    let base = cfg.cascade * cfg.width * cfg.height * 3u;
    let at = base + (u32(px.y) * cfg.width + u32(px.x)) * 3u;
    for (var c = c0; c < c1; c++) {
        let q = u32(photon_weight(ph, ior, c) * cfg.ramps.w + 0.5);
        atomicAdd(&acc[at + c], q);
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
