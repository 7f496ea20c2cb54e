// Technique `yuksel`, our compute variant: the three passes fused into one. A workgroup owns a
// 56 x 56 tile of the map's pixels; it refracts every record whose region can reach the tile (the
// level's pixels of the tile plus an apron of N/2 columns each side and M/2 rows each side, shifted
// by the region's shift) and adds each record's share into the tile's pixels its box covers, in
// workgroup memory: no pre-pass texture, no intermediate render targets, no channel budget. Each
// record costs the pixels its box covers (one to four, mostly), where a gather weighed all
// N x (M + 1) records of the region for every pixel (docs/yuksel.md, "The fused variant"). The
// same shares as pass 1 + pass 2, clipped to the same region, summed in 20-bit fixed point, so
// that the sum does not depend on the order in which the invocations add (integer atomics).

@group(0) @binding(2) var map_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;

// Map pixels a side of a workgroup's tile: a multiple of every level's 2^level (8 at most), and
// 56² words (12,544 bytes) of workgroup memory, within WebGPU's default 16 KiB.
const TILE: u32 = 56u;
// The fixed point of the sums: 2^20 units to flat water's irradiance, so a texel holds up to 4,096
// times it and each record's share is rounded by at most 5e-7 of it.
const FIXED: f32 = 1048576.0;
var<workgroup> sums: array<atomic<u32>, 3136>;

// Add record `rec` (`yuksel_record`: its box's centre from its pixel's centre, in the level's
// pixels, its packed half-widths, its flux) of the level's pixel `q` into the tile whose first map
// pixel is `tile0`, in the map pixels its box covers that lie in the tile, in the map and in the
// region of `q`'s light (the level pixels `q - shift + [-N/2, N/2] x [-M/2, M/2]`, as pass 1 gathers
// them).
fn add_record(rec: vec4<f32>, q: vec2<i32>, tile0: vec2<i32>, size: vec2<i32>) {
    if rec.w == 0.0 {
        return;
    }
    let f = i32(1u << region.level);
    let scale = f32(f);
    // The box in map pixels: centre (from map pixel 0's centre) and half-widths; a level's pixel
    // holds the light of 4^level map pixels.
    let c = (vec2<f32>(q) + rec.xy) * scale + (scale - 1.0) * 0.5;
    let half = half_widths(rec.z) * scale;
    let w = rec.w * scale * scale;
    let reach = vec2<i32>(i32(region.n / 2u), i32(region.m / 2u));
    let own = q - region.shift;
    let lo = max(max(vec2<i32>(floor(c - half + 0.5)), tile0), max((own - reach) * f, vec2<i32>(0)));
    let hi = min(
        min(vec2<i32>(ceil(c + half - 0.5)), tile0 + vec2<i32>(i32(TILE) - 1)),
        min((own + reach) * f + f - 1, size - 1),
    );
    for (var y = lo.y; y <= hi.y; y++) {
        let ay = box_share(c.y - f32(y), half.y) * w;
        if ay == 0.0 {
            continue;
        }
        for (var x = lo.x; x <= hi.x; x++) {
            let a = box_share(c.x - f32(x), half.x) * ay;
            if a > 0.0 {
                let at = u32(y - tile0.y) * TILE + u32(x - tile0.x);
                atomicAdd(&sums[at], u32(a * FIXED + 0.5));
            }
        }
    }
}

@compute @workgroup_size(16, 16)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    let size = vec2<i32>(i32(u.width), i32(u.height));
    let tile0 = vec2<i32>(group.xy * TILE);
    for (var i = local; i < TILE * TILE; i += 256u) {
        atomicStore(&sums[i], 0u);
    }
    workgroupBarrier();
    let f = 1u << region.level;
    // The level's pixels whose region reaches the tile: the tile's own, shifted, plus the apron.
    let first = vec2<i32>(group.xy * (TILE / f)) + region.shift - vec2<i32>(i32(region.n / 2u), i32(region.m / 2u));
    let cols = TILE / f + region.n - 1u;
    let rows = TILE / f + region.m;
    let level_pixel = u.pixel * f32(f);
    let sub = level_subsamples(region.level);
    for (var i = local; i < cols * rows; i += 256u) {
        let q = first + vec2<i32>(i32(i % cols), i32(i / cols));
        // Below k, `yuksel_tier` made the pixel's t x t records; at k only its first, and the
        // others are made here one by one. (Sharing the records of the pixels at k out one per
        // invocation, as the render-target variant's `prepass_fill.wgsl` does, was no faster on
        // lavapipe: 938-944 ms against 816-938 ms on the pool at 640 x 360.)
        let t = yuksel_tier(q.x, q.y, sub, level_pixel, 1u);
        if t < sub {
            for (var r = 0u; r < t * t; r++) {
                add_record(tier_records[r], q, tile0, size);
            }
        } else {
            add_record(tier_records[0], q, tile0, size);
            for (var r = 1u; r < t * t; r++) {
                let part = yuksel_part(q.x, q.y, r % t, r / t, t, level_pixel);
                add_record(yuksel_record(part, q.x, q.y, t, sub, level_pixel), q, tile0, size);
            }
        }
    }
    workgroupBarrier();
    for (var i = local; i < TILE * TILE; i += 256u) {
        let at = tile0 + vec2<i32>(i32(i % TILE), i32(i / TILE));
        if at.x < size.x && at.y < size.y {
            let e = f32(atomicLoad(&sums[i])) / FIXED;
            textureStore(map_out, at, vec4<f32>(e * u.attenuation.rgb, 1.0));
        }
    }
}
