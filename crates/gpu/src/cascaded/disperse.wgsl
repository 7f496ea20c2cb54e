// Technique `cascaded`, post-process dispersion (paper §3.6, designed here): red and blue of each
// pixel are read from the composed image where flat water would have sent green, F - d shift_c with
// d the water column over the pixel's floor point F. CPU twin: `disperse`.

import package::cascaded::common::{Cascaded, eye_project, eye_ray};

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var eye: texture_2d<f32>;
@group(0) @binding(2) var composed: texture_2d<f32>;
@group(0) @binding(3) var image: texture_storage_2d<rgba32float, write>;

fn fetch(x: i32, y: i32, c: u32) -> f32 {
    let p = clamp(vec2<i32>(x, y), vec2<i32>(0), vec2<i32>(i32(cfg.width) - 1, i32(cfg.height) - 1));
    return textureLoad(composed, p, 0)[c];
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.width || id.y >= cfg.height {
        return;
    }
    var out = textureLoad(composed, vec2<i32>(id.xy), 0);
    let e = textureLoad(eye, vec2<i32>(id.xy), 0);
    if e.w != 0.0 {
        let f = cfg.eye_pos.xyz + eye_ray(cfg, f32(id.x) + 0.5, f32(id.y) + 0.5) * e.x;
        let column = max(cfg.light.w - f.z, 0.0);
        for (var n = 0u; n < 2u; n++) {
            let c = n * 2u;
            let shift = select(cfg.post.zw, cfg.post.xy, n == 0u);
            let q = f - vec3<f32>(shift * column, 0.0);
            let p = eye_project(cfg, q);
            if p.z <= 0.0 {
                continue;
            }
            let uv = p.xy - 0.5;
            let base = floor(uv);
            let t = uv - base;
            let x0 = i32(base.x);
            let y0 = i32(base.y);
            out[c] = (fetch(x0, y0, c) * (1.0 - t.x) + fetch(x0 + 1, y0, c) * t.x) * (1.0 - t.y)
                + (fetch(x0, y0 + 1, c) * (1.0 - t.x) + fetch(x0 + 1, y0 + 1, c) * t.x) * t.y;
        }
    }
    textureStore(image, vec2<i32>(id.xy), out);
}
