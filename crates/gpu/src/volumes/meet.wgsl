// Technique `volumes` over receivers, the meeting pass: where each lattice vertex's refracted ray
// first meets the receivers' heights, as its light-space point and its path in the water. CPU twin:
// `meet_pass` in caustics-core/src/techniques/volumes/illumination.rs.

import package::shaders::receivers::{Receivers, light_space, meet_receivers};
import package::volumes::common::WaterVertex;

@group(0) @binding(0) var<uniform> r: Receivers;
@group(0) @binding(1) var<storage, read> water: array<WaterVertex>;
@group(0) @binding(2) var receiver_heights: texture_2d<f32>;
// (q.x, q.y, path, 1) per lattice vertex, zero where no light leaves it or its ray never lands.
@group(0) @binding(3) var<storage, read_write> hits: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&hits) {
        return;
    }
    let v = water[id.x];
    var hit = vec4<f32>(0.0);
    if v.pos.w > 0.0 {
        let d = meet_receivers(receiver_heights, r, v.pos.xyz, v.dir.xyz);
        if d >= 0.0 {
            hit = vec4<f32>(light_space(v.pos.xyz + v.dir.xyz * d, r.t0.xyz), d, 1.0);
        }
    }
    hits[id.x] = hit;
}
