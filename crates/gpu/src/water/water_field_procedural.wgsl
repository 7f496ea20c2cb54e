// Water field, paper 2's wave function evaluated exactly at each texel centre. CPU twin:
// `Procedural::height` in caustics-core/src/water/procedural.rs.

import package::shaders::water::{ProceduralWave, procedural_wave};
import package::water::water_field::{FieldParams, field_point};

@group(0) @binding(0) var<uniform> field: FieldParams;
@group(0) @binding(1) var<uniform> wave: ProceduralWave;
@group(0) @binding(2) var output: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let h = procedural_wave(wave, field_point(field, id.xy, dims)).x;
    textureStore(output, id.xy, vec4<f32>(field.amplitude * h, 0.0, 0.0, 0.0));
}
