// Water field, a sampled source (the FFT ocean's height channel, the ripple simulation, a height
// field file) read through the shared bicubic interpolant at each texel centre, wrapped or clamped
// at its edges. CPU twin: `GridSurface::height` (`Grid::sample`) in caustics-core.

import package::shaders::water::grid_sample;
import package::water::water_field::{FieldParams, field_point};

@group(0) @binding(0) var<uniform> field: FieldParams;
// Heights in the red channel, texel (j, i) at ((j + ½), (i + ½)) grid_size / dims.
@group(0) @binding(1) var grid: texture_2d<f32>;
@group(0) @binding(2) var output: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let p = field_point(field, id.xy, dims);
    let h = grid_sample(grid, p, field.grid_size, field.wrap != 0u).x;
    textureStore(output, id.xy, vec4<f32>(field.amplitude * h, 0.0, 0.0, 0.0));
}
