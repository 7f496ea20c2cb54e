// Technique `yuksel`, pre-pass (paper §5), first of three: each pixel's tier, one invocation per
// pixel of the level's map and its region's apron. Pre-pass texels (c, r) with c / k, r / k the
// same hold the records of map pixel (c / k - N/2 + shift.x, r / k - M/2 + shift.y): its k x k
// samples, or with `u.split` its first t x t (`yuksel_tier`: as few as its footprints allow), the
// others left as they were (pass 1 reads t from the first and no more). A pixel below k writes its
// records and its span here; a pixel at k only its tier, listing itself for `prepass_fill.wgsl`
// (one invocation per listed pixel, so that neighbouring invocations do the same work), and
// `prepass_span.wgsl` does the rest. The textures are sized for the largest region; texels beyond this frame's are left alone.

import package::yuksel::common::{
    YukselRegion, in_prepass_area, level_subsamples, pre_texel, prepass_area, prepass_level_pixel,
    span_with, u,
};
import package::yuksel::fill::{FILL_GROUP, FILL_STRIDE, FillArgs};
import package::yuksel::sample::{tier_records, yuksel_tier};

@group(0) @binding(2) var pre_out: texture_storage_2d_array<rgba32float, write>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;
// Per pixel, the span along x its lit records' boxes cover (pixels from its centre; empty where
// none is lit): pass 1 skips a pixel whose span misses its map pixel without reading its records.
@group(0) @binding(4) var extents_out: texture_storage_2d<rg32float, write>;
// Per pixel, its records a side t.
@group(0) @binding(5) var tiers_out: texture_storage_2d<r32uint, write>;
// The pixels at k, for `prepass_fill.wgsl`'s indirect dispatch (`fill.wgsl`).
@group(0) @binding(6) var<storage, read_write> fill_args: FillArgs;
@group(0) @binding(7) var<storage, read_write> fill_list: array<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    if !in_prepass_area(id.xy, textureDimensions(tiers_out), region) {
        return;
    }
    let q = prepass_level_pixel(id.xy, region);
    let pixel = u.pixel * f32(1u << region.level);
    let t = yuksel_tier(q.x, q.y, k, pixel, select(0u, 1u, k == 1u));
    textureStore(tiers_out, vec2<i32>(id.xy), vec4<u32>(t));
    if t == k && k > 1u {
        // The list holds every pixel of the largest region's area: it cannot overflow.
        let area = prepass_area(region.n, region.m, region.level);
        let i = atomicAdd(&fill_args.count, 1u);
        fill_list[min(i, arrayLength(&fill_list) - 1u)] = id.y * area.x + id.x;
        if i % FILL_GROUP == 0u && i < FILL_STRIDE {
            atomicAdd(&fill_args.groups, 1u);
        }
        return;
    }
    let first = vec2<i32>(id.xy * k);
    var span = vec2<f32>(3.0e38, -3.0e38);
    let tile = textureDimensions(pre_out);
    for (var q = 0u; q < t * t; q++) {
        let rec = tier_records[q];
        let at = pre_texel(first + vec2<i32>(i32(q % t), i32(q / t)), tile);
        textureStore(pre_out, at.xy, at.z, rec);
        span = span_with(span, rec);
    }
    textureStore(extents_out, vec2<i32>(id.xy), vec4<f32>(span, 0.0, 0.0));
}
