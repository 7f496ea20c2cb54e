// Technique `caustic-triangles` with tiling water as the generator, the copy band pass: the GPU's
// own fit of the band of quads whose refracted light can cross an edge of the square (the quads the
// shifted copies are drawn for), from the heights it reads, so that no frame reads them on the CPU.
// The bound pass (band_bound.wgsl) has reduced the grid's steepest finite-difference slope and its
// height range; one thread bounds the light's sideways travel `(depth + h_max) tan(θ_t + α)` exactly as the CPU twin
// `water::copy_band` does, one quad wider for f32 rounding: any band at least the light's reach
// draws the same map, so the margin costs a few culled quads and never changes a texel. It also
// writes the indirect draw of the eight shifted copies (`CopyBand.draw`), the vertex count of the
// largest band rectangle as `draw_floor` computes it from a CPU band.

import package::caustic_triangles::common::{CausticTriangles, CopyBand, copy_rect, with_band};
import package::caustic_triangles::water_setup::WaterPhoton;
import package::shaders::reduce::unordered;

@group(0) @binding(0) var<uniform> w: WaterPhoton;
@group(0) @binding(1) var<uniform> u: CausticTriangles;
// ordered(slope), ordered(-lo), ordered(hi), or 0 where there was no texel.
@group(0) @binding(2) var<storage, read> bound: array<u32, 4>;
@group(0) @binding(3) var<storage, read_write> out: CopyBand;

const BIG: f32 = 3.0e38;
const PI: f32 = 3.14159265358979;

@compute @workgroup_size(1)
fn main() {
    var slope = 0.0;
    var lo = BIG;
    var hi = -BIG;
    // The three are set together, by every texel.
    if bound[2] != 0u {
        slope = unordered(bound[0]);
        lo = -unordered(bound[1]);
        hi = unordered(bound[2]);
    }
    let h_max = hi + 0.25 * (hi - lo);
    let tilt = atan(slope * 1.25 * sqrt(2.0));
    let zenith = acos(clamp(-w.light.z, -1.0, 1.0));
    let incidence = min(zenith + tilt, 0.5 * PI);
    let refracted = asin(sin(incidence) / w.light.w);
    let lean = refracted + tilt;
    var band = w.lattice;
    // `!(x < limit)` keeps a NaN on the safe side: every quad.
    if lean < radians(89.0) && h_max < BIG && slope < BIG {
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
