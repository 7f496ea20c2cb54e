// Technique `yuksel`, scatter variant, third of three: each map pixel's fixed-point sum into the
// map, with the absorption along the flat-water path (as pass 2 applies it). CPU twin:
// `scatter_resolve` in core's yuksel/scatter.rs.

import package::yuksel::common::u;
import package::yuksel::scatter::{FIXED, sums};

@group(0) @binding(4) var map_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= u.width || id.y >= u.height {
        return;
    }
    let e = f32(atomicLoad(&sums[id.y * u.width + id.x])) / FIXED;
    textureStore(map_out, vec2<i32>(id.xy), vec4<f32>(e * u.attenuation.rgb, 1.0));
}
