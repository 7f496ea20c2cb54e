// Technique `yuksel`, pre-pass, third of three: the span along x of the pixels whose tier is k
// (their records from `prepass_fill.wgsl`), as `prepass.wgsl` writes it for the others.

import package::yuksel::common::{
    YukselRegion, in_prepass_area, level_subsamples, pre_texel, span_with,
};

@group(0) @binding(1) var pre: texture_2d_array<f32>;
@group(0) @binding(2) var<storage, read> region: YukselRegion;
@group(0) @binding(3) var tiers: texture_2d<u32>;
@group(0) @binding(4) var extents_out: texture_storage_2d<rg32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    if k == 1u || !in_prepass_area(id.xy, textureDimensions(tiers), region) {
        return;
    }
    if textureLoad(tiers, vec2<i32>(id.xy), 0).x != k {
        return;
    }
    var span = vec2<f32>(3.0e38, -3.0e38);
    let tile = textureDimensions(pre);
    for (var q = 0u; q < k * k; q++) {
        let at = pre_texel(vec2<i32>(id.xy * k + vec2<u32>(q % k, q / k)), tile);
        let rec = textureLoad(pre, at.xy, at.z, 0);
        span = span_with(span, rec);
    }
    textureStore(extents_out, vec2<i32>(id.xy), vec4<f32>(span, 0.0, 0.0));
}
