// Technique `yuksel`, the scatter variant's shared module (`scatter_tier.wgsl`, `scatter_fill.wgsl`):
// a record's light added into the map's pixels its box covers, in fixed point with integer
// atomics, so that the sum does not depend on the order in which the invocations add. The same
// shares as pass 1 + pass 2, clipped to the same region. CPU twin: `add_record` and `FIXED` in
// caustics-core/src/techniques/yuksel/scatter.rs.

import package::yuksel::common::{YukselRegion, box_share, half_widths, u};

// One fixed-point sum per map pixel, row by row; cleared before the frame's first scatter pass.
@group(0) @binding(2) var<storage, read_write> sums: array<atomic<u32>>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;

// The fixed point of the sums: 2^20 units to flat water's irradiance, so a texel holds up to 4,096
// times it (beyond, the sum wraps, unchecked) and each share is rounded by at most 5e-7 of it.
const FIXED: f32 = 1048576.0;

// Add record `rec` (`yuksel_record`: its box's centre from its pixel's centre, in the level's
// pixels, its packed half-widths, its flux) of the level's pixel `q` into the map pixels its box
// covers that lie in the map and in the region of `q`'s light (the level pixels
// `q - shift + [-N/2, N/2] x [-M/2, M/2]`, as pass 1 gathers them).
fn add_record(rec: vec4<f32>, q: vec2<i32>) {
    if rec.w == 0.0 {
        return;
    }
    let f = i32(1u << region.level);
    let scale = f32(f);
    // The box in map pixels from the centre of map pixel `base`, the first of `q`'s level pixel:
    // offsets a few pixels wide, kept to f32's precision there whatever the map's size (as pass 1
    // counts them); a level's pixel holds the light of 4^level map pixels.
    let base = q * f;
    let c = rec.xy * scale + (scale - 1.0) * 0.5;
    let half = half_widths(rec.z) * scale;
    let w = rec.w * scale * scale;
    let reach = vec2<i32>(i32(region.n / 2u), i32(region.m / 2u));
    let own = q - region.shift;
    let size = vec2<i32>(i32(u.width), i32(u.height));
    let lo = max(base + vec2<i32>(floor(c - half + 0.5)), max((own - reach) * f, vec2<i32>(0)));
    let hi = min(base + vec2<i32>(ceil(c + half - 0.5)), min((own + reach) * f + f - 1, size - 1));
    for (var y = lo.y; y <= hi.y; y++) {
        let ay = box_share(c.y - f32(y - base.y), half.y) * w;
        if ay == 0.0 {
            continue;
        }
        for (var x = lo.x; x <= hi.x; x++) {
            let a = box_share(c.x - f32(x - base.x), half.x) * ay;
            if a > 0.0 {
                atomicAdd(&sums[u32(y) * u.width + u32(x)], u32(a * FIXED + 0.5));
            }
        }
    }
}
