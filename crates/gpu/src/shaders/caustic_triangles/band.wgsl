// Technique `caustic-triangles` with tiling water as the generator, the copy band pass: the GPU's
// own fit of the band of quads whose refracted light can cross an edge of the square (the quads the
// shifted copies are drawn for), from the heights it reads, so that no frame reads them on the CPU.
// One workgroup reduces the grid's steepest finite-difference slope and its height range, then
// bounds the light's sideways travel `(depth + h_max) tan(θ_t + α)` exactly as the CPU twin
// `water::copy_band` does, one quad wider for f32 rounding: any band at least the light's reach
// draws the same map, so the margin costs a few culled quads and never changes a texel. It also
// writes the indirect draw of the eight shifted copies (`CopyBand.draw`), the vertex count of the
// largest band rectangle as `draw_floor` computes it from a CPU band.

@group(0) @binding(0) var<uniform> w: WaterPhoton;
@group(0) @binding(1) var<uniform> u: CausticTriangles;
@group(0) @binding(2) var heights: texture_2d<f32>;
@group(0) @binding(3) var<storage, read_write> out: CopyBand;

const THREADS: u32 = 256u;
const BIG: f32 = 3.0e38;
const PI: f32 = 3.14159265358979;

var<workgroup> slopes: array<f32, 256>;
var<workgroup> lows: array<f32, 256>;
var<workgroup> highs: array<f32, 256>;

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) t: u32) {
    let dims = textureDimensions(heights);
    let cols = max(dims.x, 1u);
    let rows = max(dims.y, 1u);
    let dx = w.water.y / f32(cols);
    let dy = w.water.y / f32(rows);
    var slope = 0.0;
    var lo = BIG;
    var hi = -BIG;
    for (var k = t; k < dims.x * dims.y; k += THREADS) {
        let i = k / dims.x;
        let j = k % dims.x;
        let h = textureLoad(heights, vec2<u32>(j, i), 0).x;
        let hx = textureLoad(heights, vec2<u32>((j + 1u) % cols, i), 0).x;
        let hy = textureLoad(heights, vec2<u32>(j, (i + 1u) % rows), 0).x;
        slope = max(slope, max(abs(hx - h) / dx, abs(hy - h) / dy));
        lo = min(lo, h);
        hi = max(hi, h);
    }
    slopes[t] = slope;
    lows[t] = lo;
    highs[t] = hi;
    workgroupBarrier();
    for (var s = THREADS / 2u; s > 0u; s /= 2u) {
        if t < s {
            slopes[t] = max(slopes[t], slopes[t + s]);
            lows[t] = min(lows[t], lows[t + s]);
            highs[t] = max(highs[t], highs[t + s]);
        }
        workgroupBarrier();
    }
    if t != 0u {
        return;
    }
    let h_max = highs[0] + 0.25 * (highs[0] - lows[0]);
    let tilt = atan(slopes[0] * 1.25 * sqrt(2.0));
    let zenith = acos(clamp(-w.light.z, -1.0, 1.0));
    let incidence = min(zenith + tilt, 0.5 * PI);
    let refracted = asin(sin(incidence) / w.light.w);
    let lean = refracted + tilt;
    var band = w.lattice;
    // `!(x < limit)` keeps a NaN on the safe side: every quad.
    if lean < radians(89.0) && h_max < BIG && slopes[0] < BIG {
        let reach = max(w.water.x + h_max, 0.0) * tan(lean);
        band = min(u32(ceil(reach / w.water.z)) + 2u, w.lattice);
    }
    out.band = band;
    // The largest rectangle of a shifted copy under this band (CPU: `draw_floor`).
    let c = with_band(u, out);
    var most = 0u;
    for (var k = 0u; k < 9u; k++) {
        if k != 4u {
            let r = copy_rect(c, k);
            most = max(most, (r.y - r.x) * (r.w - r.z));
        }
    }
    let quads = u.p - 1u;
    out.draw = array<u32, 4>(min(6u * most, 6u * quads * quads), 8u, 0u, 0u);
}
