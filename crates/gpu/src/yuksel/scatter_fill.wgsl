// Technique `yuksel`, scatter variant, second of three: the k x k records of each pixel whose tier
// is k (`scatter_tier.wgsl` listed them), made row by row sharing their edges' rays
// (`yuksel_fill_row`), each added into the map where it is made. CPU twin: `scatter_fill` in
// core's yuksel/scatter.rs.

import package::yuksel::common::{level_subsamples, prepass_area, prepass_level_pixel, u};
import package::yuksel::fill::{FILL_GROUP, FILL_STRIDE, fill_listed, fill_row, yuksel_fill_row};
import package::yuksel::scatter::{add_record, region};

@group(0) @binding(4) var<storage, read> fill_args: array<u32, 4>;
@group(0) @binding(5) var<storage, read> fill_list: array<u32>;

@compute @workgroup_size(FILL_GROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    let area = prepass_area(region.n, region.m, region.level);
    let pixel = u.pixel * f32(1u << region.level);
    for (var entry = id.x; entry < fill_args[3]; entry += FILL_STRIDE) {
        let q = prepass_level_pixel(fill_listed(fill_list[entry], area), region);
        for (var b = 0u; b < k; b++) {
            yuksel_fill_row(q, b, k, pixel);
            for (var a = 0u; a < k; a++) {
                add_record(fill_row[a], q);
            }
        }
    }
}
