// Technique `cascaded`, terrain G-buffer pass (paper §3.3 terrain position, §3.3.1): per light texel
// the light-view depth of the terrain under the unrefracted sun ray. CPU twin: `terrain_gbuffer`.

import package::cascaded::common::{Cascaded, ray_origin, terrain_hit};

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var terrain: texture_2d<f32>;
@group(0) @binding(2) var gbuffer: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.res || id.y >= cfg.res {
        return;
    }
    let o = ray_origin(cfg, id.y, id.x);
    let s = terrain_hit(cfg, terrain, o, cfg.light.xyz);
    textureStore(gbuffer, vec2<i32>(id.xy), vec4<f32>(s, 0.0, 0.0, 0.0));
}
