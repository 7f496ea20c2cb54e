// Technique `cascaded`, eye-depth pass (what §3.5.1 samples): per screen pixel the view depth of the
// terrain its ray meets, the floor area it sees at its own scale (the floor hits of the rays through
// its edges' midpoints, see `eye_pass`), the floor's height and that floor's normal z (0: no
// floor). CPU twin: `eye_pass`.

import package::cascaded::common::{Cascaded, eye_ray, receiver_normal, terrain_height, terrain_hit};
import package::shaders::optics::height_field_normal;

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var terrain: texture_2d<f32>;
@group(0) @binding(2) var eye_out: texture_storage_2d<rgba32float, write>;

// The floor hit of the ray through pixel point (px, py), w = 0 where it misses the floor or lies
// at less than half or more than twice the centre's depth zc, or, with walls, on another receiver
// than the centre's normal `own` (`eye_pass`'s `edge`).
fn edge_hit(px: f32, py: f32, zc: f32, own: vec3<f32>) -> vec4<f32> {
    let r = eye_ray(cfg, px, py);
    let len = length(r);
    let s = terrain_hit(cfg, terrain, cfg.eye_pos.xyz, r / len);
    if s < 0.0 {
        return vec4<f32>(0.0);
    }
    let z = s / len;
    if !(z > 0.5 * zc && z < 2.0 * zc) {
        return vec4<f32>(0.0);
    }
    let p = cfg.eye_pos.xyz + r * z;
    if cfg.walls != 0u && any(receiver_normal(cfg, p) != own) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(p, 1.0);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.width || id.y >= cfg.height {
        return;
    }
    let half = cfg.eye_pos.w;
    let pixel = (2.0 * half * cfg.eye_fwd.w / f32(cfg.width)) * (2.0 * half / f32(cfg.height));
    let r = eye_ray(cfg, f32(id.x) + 0.5, f32(id.y) + 0.5);
    let len = length(r);
    let d = r / len;
    let s = terrain_hit(cfg, terrain, cfg.eye_pos.xyz, d);
    var out = vec4<f32>(0.0);
    if s >= 0.0 {
        let zv = s / len;
        let f = cfg.eye_pos.xyz + r * zv;
        let x = f32(id.x);
        let y = f32(id.y);
        let own = receiver_normal(cfg, f);
        let l = edge_hit(x, y + 0.5, zv, own);
        let r = edge_hit(x + 1.0, y + 0.5, zv, own);
        let t = edge_hit(x + 0.5, y, zv, own);
        let b = edge_hit(x + 0.5, y + 1.0, zv, own);
        var area: f32;
        var nz: f32;
        if l.w != 0.0 && r.w != 0.0 && t.w != 0.0 && b.w != 0.0 {
            let c = cross(r.xyz - l.xyz, b.xyz - t.xyz);
            area = length(c);
            nz = abs(c.z / area);
        } else {
            var n = height_field_normal(terrain_height(cfg, terrain, f.xy).yz);
            if cfg.walls != 0u {
                n = own;
            }
            let cos_g = max(abs(dot(d, n)), 1e-4);
            area = zv * zv * pixel / (len * cos_g);
            nz = n.z;
        }
        // A wall's pixels take the wall's own area (its maps are per area of the wall).
        if cfg.walls != 0u && own.z == 0.0 {
            nz = 1.0;
        }
        out = vec4<f32>(zv, area, f.z, max(nz, 1e-6));
    }
    textureStore(eye_out, vec2<i32>(id.xy), out);
}
