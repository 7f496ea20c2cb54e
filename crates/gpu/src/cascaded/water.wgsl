// Technique `cascaded`, water G-buffer pass (paper §3.3 water position + normals, §3.3.1): per light
// texel the light-view depth of the water surface z = level + h and its normal. CPU twin:
// `water_gbuffer`.

import package::cascaded::common::{Cascaded, WATER_STEPS, ray_origin};
import package::shaders::optics::height_field_normal;
import package::shaders::water::grid_sample;

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var water: texture_2d<f32>;
@group(0) @binding(2) var gbuffer: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.res || id.y >= cfg.res {
        return;
    }
    let l = cfg.light.xyz;
    let level = cfg.light.w;
    let o = ray_origin(cfg, id.y, id.x);
    var s = (level - o.z) / l.z;
    var grad = vec2<f32>(0.0);
    for (var n = 0u; n < WATER_STEPS; n++) {
        let p = o + l * s;
        let hg = grid_sample(water, p.xy, cfg.e_u.w, cfg.wrap != 0u);
        grad = hg.yz;
        let f = p.z - level - hg.x;
        let df = l.z - dot(hg.yz, l.xy);
        s -= f / df;
    }
    textureStore(gbuffer, vec2<i32>(id.xy), vec4<f32>(s, height_field_normal(grad)));
}
