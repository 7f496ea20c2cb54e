// Level 0 of the pyramid of the water's slope moments (LEAN mapping, Olano and Baker 2010, §3),
// the GPU twin of caustics-core's `SlopePyramid::new` (water/slopes.rs): per texel of the heights'
// lattice, the mean over a 4 x 4 lattice inside it of `h_x`, `h_y`, `h_x²`, `h_y²` and `h_x h_y`,
// the interpolant's gradient read as the final image reads it (`grid_sample_hermite`). The
// gradient at the texel's centre alone misses the slope of the shortest waves.

import package::final_image::water_slopes::SlopeLevel;
import package::shaders::water::grid_sample_hermite;

@group(0) @binding(0) var<uniform> level: SlopeLevel;
// The water's heights in Hermite form (`water_patches.wgsl`).
@group(0) @binding(1) var patches: texture_2d<f32>;
// Five floats a texel: `E[h_x]`, `E[h_y]`, `E[h_x²]`, `E[h_y²]`, `E[h_x h_y]`.
@group(0) @binding(2) var<storage, read_write> moments: array<f32>;

const SUB: u32 = 4u;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= level.cols || id.y >= level.rows {
        return;
    }
    let dx = level.size / f32(level.cols);
    let dy = level.size / f32(level.rows);
    var first = vec4<f32>(0.0);
    var xy = 0.0;
    let w = 1.0 / f32(SUB * SUB);
    for (var a = 0u; a < SUB; a++) {
        for (var b = 0u; b < SUB; b++) {
            let p = vec2<f32>(
                (f32(id.x) + (f32(b) + 0.5) / f32(SUB)) * dx,
                (f32(id.y) + (f32(a) + 0.5) / f32(SUB)) * dy,
            );
            let g = grid_sample_hermite(patches, p, level.size, level.wrap != 0u).yz;
            first += vec4<f32>(g, g * g) * w;
            xy += g.x * g.y * w;
        }
    }
    let k = (level.offset + id.y * level.cols + id.x) * 5u;
    moments[k] = first.x;
    moments[k + 1u] = first.y;
    moments[k + 2u] = first.z;
    moments[k + 3u] = first.w;
    moments[k + 4u] = xy;
}
