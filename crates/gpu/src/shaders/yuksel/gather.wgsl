// Technique `yuksel`, our compute variant: the three passes fused into one. A 14 x 14 tile of the
// level's pixels first refracts every sample its region needs (the tile plus an apron of N/2 columns and
// M/2 rows each side) into workgroup memory, then each pixel gathers the N x (M + 1) samples of its
// region directly (once for each of the k x k samples of a pixel) into each of the map's pixels
// within its level's pixel: no intermediate render targets, no channel budget, and the samples
// shared by neighbouring pixels are refracted once per tile instead of read back through memory.
// Same sums as pass 1 + pass 2 (in another order). The region (its size and its shift along the
// refracted sun) comes from the region pass.

@group(0) @binding(2) var map_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;

// 14, not 16: (14 + 30)² samples of four words fit the 32 KiB of workgroup memory that Metal on
// Apple GPUs and lavapipe give (16 would need 33,856 bytes).
const TILE: u32 = 14u;
// Up to N = 31 and M = 30: (14 + 30) x (14 + 30) samples.
const APRON_MAX: u32 = 30u;
const SPAN: u32 = TILE + APRON_MAX;
var<workgroup> tile_dx: array<f32, 1936>;
var<workgroup> tile_dy: array<f32, 1936>;
var<workgroup> tile_half: array<u32, 1936>;
var<workgroup> tile_w: array<f32, 1936>;

@compute @workgroup_size(14, 14)
fn main(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
    @builtin(local_invocation_id) lid: vec3<u32>,
) {
    let nh = i32(region.n / 2u);
    let mh = i32(region.m / 2u);
    let sx = region.shift.x;
    let sy = region.shift.y;
    let cols = TILE + region.n - 1u;
    let rows = TILE + region.m;
    let origin = vec2<i32>(group.xy * TILE) - vec2<i32>(nh, mh) + region.shift;
    let size = level_size(u.width, u.height, region.level);
    // The dispatch covers the map; at a coarser level, tiles past the level's map have no work.
    if group.x * TILE >= size.x || group.y * TILE >= size.y {
        return;
    }
    let level_pixel = u.pixel * f32(1u << region.level);
    // This thread's pixel of the level's map, and the 2^level x 2^level map pixels in it.
    let pixel = vec2<i32>(group.xy * TILE + lid.xy);
    let inside = pixel.x < i32(size.x) && pixel.y < i32(size.y);
    let f = 1u << region.level;
    let scale = f32(f);
    let centre = (scale - 1.0) * 0.5;
    var e: array<f32, 64>;
    // One of the k x k samples of every pixel at a time, so that workgroup memory holds one
    // sample per pixel of the tile and apron whatever k.
    let sub = level_subsamples(region.level);
    for (var phase = 0u; phase < sub * sub; phase++) {
        let a = phase % sub;
        let b = phase / sub;
        for (var t = local; t < cols * rows; t += TILE * TILE) {
            let c = t % cols;
            let r = t / cols;
            let s = yuksel_sample(origin.x + i32(c), origin.y + i32(r), a, b, sub, level_pixel);
            tile_dx[r * SPAN + c] = s.x;
            tile_dy[r * SPAN + c] = s.y;
            tile_half[r * SPAN + c] = bitcast<u32>(s.z);
            tile_w[r * SPAN + c] = s.w;
        }
        workgroupBarrier();
        if inside {
            for (var dr = -mh; dr <= mh; dr++) {
                let row = u32(i32(lid.y) + mh + dr) * SPAN;
                for (var dc = -nh; dc <= nh; dc++) {
                    let k = row + u32(i32(lid.x) + nh + dc);
                    let half = unpack2x16float(tile_half[k]) * scale;
                    // In map pixels from the centre of the level's pixel's first map pixel.
                    let x = (f32(dc + sx) + tile_dx[k]) * scale + centre;
                    let y = (f32(dr + sy) + tile_dy[k]) * scale + centre;
                    // A level's pixel holds the light of 4^level map pixels.
                    let w = tile_w[k] * scale * scale;
                    for (var q = 0u; q < f * f; q++) {
                        let ax = box_share(x - f32(q % f), half.x);
                        let ay = box_share(y - f32(q / f), half.y);
                        e[q] += ax * ay * w;
                    }
                }
            }
        }
        workgroupBarrier();
    }
    if inside {
        for (var q = 0u; q < f * f; q++) {
            let at = pixel * i32(f) + vec2<i32>(i32(q % f), i32(q / f));
            textureStore(map_out, at, vec4<f32>(e[q] * u.attenuation.rgb, 1.0));
        }
    }
}
