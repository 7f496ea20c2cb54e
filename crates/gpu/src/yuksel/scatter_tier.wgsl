// Technique `yuksel`, scatter variant (ours), first of three: one invocation per pixel of the
// level's map and its region's apron finds its tier (`yuksel_tier`) and adds the records of a tier
// below k into the map (`add_record`); a pixel at k is listed for `scatter_fill.wgsl` instead,
// which makes its k x k records sharing their edges' rays, one invocation per listed pixel (so
// that neighbouring invocations do the same work). No pre-pass texture and no render targets: the
// records are added where they are made. CPU twin: `scatter_tier` in core's yuksel/scatter.rs.

import package::yuksel::common::{level_subsamples, prepass_area, prepass_level_pixel, u};
import package::yuksel::fill::{FILL_GROUP, FILL_STRIDE, FillArgs};
import package::yuksel::sample::{tier_records, yuksel_tier};
import package::yuksel::scatter::{add_record, region};

@group(0) @binding(4) var<storage, read_write> fill_args: FillArgs;
// The pixels at k, as indices `row * width + column` into the pre-pass area.
@group(0) @binding(5) var<storage, read_write> fill_list: array<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    let area = prepass_area(region.n, region.m, region.level);
    if id.x >= area.x || id.y >= area.y {
        return;
    }
    let q = prepass_level_pixel(id.xy, region);
    let pixel = u.pixel * f32(1u << region.level);
    let t = yuksel_tier(q.x, q.y, k, pixel, select(0u, 1u, k == 1u));
    if t == k && k > 1u {
        // The list holds every pixel of the largest region's area: it cannot overflow.
        let i = atomicAdd(&fill_args.count, 1u);
        fill_list[min(i, arrayLength(&fill_list) - 1u)] = id.y * area.x + id.x;
        if i % FILL_GROUP == 0u && i < FILL_STRIDE {
            atomicAdd(&fill_args.groups, 1u);
        }
        return;
    }
    for (var r = 0u; r < t * t; r++) {
        add_record(tier_records[r], q);
    }
}
