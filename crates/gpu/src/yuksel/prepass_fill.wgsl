// Technique `yuksel`, pre-pass, second of three: the k x k records of each pixel whose tier is k
// (`prepass.wgsl` listed them), made row by row sharing their edges' rays (`yuksel_fill_row`).
// Texel (c, r) is footprint (c % k, r % k) of its pixel.

import package::yuksel::common::{
    YukselRegion, level_subsamples, pre_texel, prepass_area, prepass_level_pixel, u,
};
import package::yuksel::fill::{FILL_GROUP, FILL_STRIDE, fill_listed, fill_row, yuksel_fill_row};

@group(0) @binding(2) var pre_out: texture_storage_2d_array<rgba32float, write>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;
@group(0) @binding(4) var<storage, read> fill_args: array<u32, 4>;
@group(0) @binding(5) var<storage, read> fill_list: array<u32>;

@compute @workgroup_size(FILL_GROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    let area = prepass_area(region.n, region.m, region.level);
    let pixel = u.pixel * f32(1u << region.level);
    let tile = textureDimensions(pre_out);
    for (var entry = id.x; entry < fill_args[3]; entry += FILL_STRIDE) {
        let at = fill_listed(fill_list[entry], area);
        let q = prepass_level_pixel(at, region);
        for (var b = 0u; b < k; b++) {
            yuksel_fill_row(q, b, k, pixel);
            for (var a = 0u; a < k; a++) {
                let texel = pre_texel(vec2<i32>(at * k + vec2<u32>(a, b)), tile);
                textureStore(pre_out, texel.xy, texel.z, fill_row[a]);
            }
        }
    }
}
