// Water field, sine waves (and flat water, the sum of none): the sum evaluated exactly at each texel
// centre. CPU twin: `Waves::height` in caustics-core/src/water/waves.rs, whose terms (phases reduced
// mod 2π at this frame's time) the CPU writes into `waves` each frame.

import package::shaders::water::{SineWave, sine_wave};
import package::water::water_field::{FieldParams, field_point};

@group(0) @binding(0) var<uniform> field: FieldParams;
@group(0) @binding(1) var<storage, read> waves: array<SineWave>;
@group(0) @binding(2) var output: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let p = field_point(field, id.xy, dims);
    var h = 0.0;
    for (var k = 0u; k < field.wave_count; k++) {
        h += sine_wave(waves[k], p).x;
    }
    textureStore(output, id.xy, vec4<f32>(field.amplitude * h, 0.0, 0.0, 0.0));
}
