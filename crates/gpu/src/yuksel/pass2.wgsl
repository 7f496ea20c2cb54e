// Technique `yuksel`, pass 2 (paper Fig. 6): map pixel (j, i) of this draw's row phase sums channel
// k of pass-1 row i / 2^level + M - k (the row whose samples gave pixel i that channel; the
// region's shift cancels), then the absorption. The other rows are left to their phases' draws.

import package::yuksel::common::{YukselRegion, u};

@group(0) @binding(1) var channels: texture_2d_array<f32>;
@group(0) @binding(2) var<storage, read> region: YukselRegion;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let j = i32(frag.x);
    let i = u32(frag.y);
    if (i & ((1u << region.level) - 1u)) != u.phase {
        discard;
    }
    let row = i32(i >> region.level);
    var e = 0.0;
    let m = i32(region.m);
    for (var k = 0; k <= m; k++) {
        let texel = textureLoad(channels, vec2<i32>(j, row + m - k), k / 4, 0);
        e += texel[k % 4];
    }
    return vec4<f32>(e * u.attenuation.rgb, 1.0);
}
