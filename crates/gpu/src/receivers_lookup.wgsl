// The receivers' lookup (docs/receivers.md): each floor texel's centre on the floor (the terrain's
// bicubic surface, or z = 0) takes a technique's light-space deposit at its light-space point, times
// n . (-t0) / -t0.z, attenuated along the flat-water path to it where the deposit carries no
// absorption of its own, and nothing where the receivers' map lies above it (something nearer the
// light covers it). CPU twin: `lookup` in caustics-core/src/receivers.rs.

import package::shaders::optics::height_field_normal;
import package::shaders::receivers::{Receivers, light_space, receiver_height};
import package::shaders::water::grid_sample;

// Mirrors `LookupUniform` in crates/gpu/src/receivers.rs.
struct Lookup {
    receivers: Receivers,
    floor: vec4<f32>,   // x: side of the square; y: 1 where the light wraps; z: the depth test's bias; w: 1 over a terrain
    absorption: vec4<f32>, // xyz: K, attenuating along the flat-water path to each receiver point (0: the deposit's own); w: the water's depth
}

@group(0) @binding(0) var<uniform> u: Lookup;
@group(0) @binding(1) var deposit: texture_2d<f32>;
@group(0) @binding(2) var heights: texture_2d<f32>;
@group(0) @binding(3) var terrain: texture_2d<f32>;
@group(0) @binding(4) var floor_map: texture_storage_2d<rgba32float, write>;

// The deposit at floor point q, bilinear between texel centres, wrapped or clamped (`CausticsMap::sample`).
fn deposit_at(q: vec2<f32>) -> vec3<f32> {
    let dims = vec2<i32>(textureDimensions(deposit));
    let x = q / u.floor.x * vec2<f32>(dims) - 0.5;
    let c = floor(x);
    let f = x - c;
    let i = vec2<i32>(c);
    var k = array<vec2<i32>, 4>(i, i + vec2<i32>(1, 0), i + vec2<i32>(0, 1), i + vec2<i32>(1, 1));
    var v: array<vec3<f32>, 4>;
    for (var n = 0; n < 4; n++) {
        var t = k[n];
        if u.floor.y != 0.0 {
            t = ((t % dims) + dims) % dims;
        } else {
            t = clamp(t, vec2<i32>(0), dims - 1);
        }
        v[n] = textureLoad(deposit, t, 0).xyz;
    }
    return mix(mix(v[0], v[1], f.x), mix(v[2], v[3], f.x), f.y);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(floor_map);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let size = u.floor.x;
    let c = (vec2<f32>(id.xy) + 0.5) * size / vec2<f32>(dims);
    var hg = vec3<f32>(0.0);
    if u.floor.w != 0.0 {
        hg = grid_sample(terrain, c, size, false);
    }
    let p = vec3<f32>(c, hg.x);
    let t0 = u.receivers.t0.xyz;
    let q = light_space(p, t0);
    var rgb = vec3<f32>(0.0);
    if p.z >= receiver_height(heights, u.receivers, q) - u.floor.z {
        let facing = max(dot(height_field_normal(hg.yz), -t0) / -t0.z, 0.0);
        let path = (u.absorption.w - p.z) / -t0.z;
        rgb = deposit_at(q) * facing * exp(-u.absorption.xyz * path);
    }
    textureStore(floor_map, vec2<i32>(id.xy), vec4<f32>(rgb, 1.0));
}
