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
// How many records a side each pixel of the tile and apron takes (`yuksel_tier`: 1, 2 or 4 below
// k as their log2, or k, in two bits), and the most of any (its square is the rounds the tile
// needs).
var<workgroup> tiers: array<atomic<u32>, 121>;
var<workgroup> most: atomic<u32>;
var<workgroup> rounds: u32;

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
    let sub = level_subsamples(region.level);
    // Round 0 finds each pixel's records a side t (`yuksel_tier`) and takes its first record;
    // round q its record q (of t x t, where q < t²), so that workgroup memory holds one record per
    // pixel of the tile and apron whatever t.
    for (var t = local; t < 121u; t += TILE * TILE) {
        atomicStore(&tiers[t], 0u);
    }
    if local == 0u {
        atomicStore(&most, 1u);
    }
    workgroupBarrier();
    for (var round = 0u; round < 64u; round++) {
        if round == 1u {
            if local == 0u {
                let side = atomicLoad(&most);
                rounds = side * side;
            }
            if round >= workgroupUniformLoad(&rounds) {
                break;
            }
        } else if round > 1u && round >= workgroupUniformLoad(&rounds) {
            break;
        }
        for (var t = local; t < cols * rows; t += TILE * TILE) {
            let c = t % cols;
            let r = t / cols;
            let pc = origin.x + i32(c);
            let pr = origin.y + i32(r);
            var s = vec4<f32>(0.0, 0.0, bitcast<f32>(pack2x16float(vec2<f32>(0.5))), 0.0);
            if round == 0u {
                let side = yuksel_tier(pc, pr, sub, level_pixel, 1u);
                // t below k is 1, 2 or 4 (codes 0 to 2); k itself (3, 6 and 8 too) is code 3.
                let code = select(countTrailingZeros(side), 3u, side == sub);
                atomicOr(&tiers[t / 16u], code << (2u * (t % 16u)));
                atomicMax(&most, side);
                s = tier_records[0];
            } else {
                let code = (atomicLoad(&tiers[t / 16u]) >> (2u * (t % 16u))) & 3u;
                let side = select(1u << code, sub, code == 3u);
                if round < side * side {
                    let part = yuksel_part(pc, pr, round % side, round / side, side, level_pixel);
                    s = yuksel_record(part, pc, pr, side, sub, level_pixel);
                }
            }
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
                    if tile_w[k] == 0.0 {
                        continue;
                    }
                    let half = abs(unpack2x16float(tile_half[k])) * scale;
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
