@group(0) @binding(0)
var<uniform> field: package_water__1water_field_FieldParams;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let p = package_water__1water_field__1field_point(field, id.xy, dims);
    var h = 0.0;
    for (var k = 0u; k < field.wave_count; k++) {
        h += package_shaders_water__1sine_wave(waves[k], p).x;
    }
    textureStore(output, id.xy, vec4<f32>(field.amplitude * h, 0.0, 0.0, 0.0));
}

@group(0) @binding(2)
var output: texture_storage_2d<r32float, write>;

struct package_shaders_water_SineWave {
    k: vec2<f32>,
    amplitude: f32,
    phase: f32
}

fn package_shaders_water__1sine_wave(w: package_shaders_water_SineWave, p: vec2<f32>) -> vec3<f32> {
    let arg = dot(w.k, p) + w.phase;
    return vec3<f32>(w.amplitude * sin(arg), w.amplitude * cos(arg) * w.k);
}

struct package_water__1water_field_FieldParams {
    size: f32,
    grid_size: f32,
    amplitude: f32,
    wave_count: u32,
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32
}

fn package_water__1water_field__1field_point(params: package_water__1water_field_FieldParams, id: vec2<u32>, dims: vec2<u32>) -> vec2<f32> {
    return (vec2<f32>(id) + 0.5) * params.size / vec2<f32>(dims);
}

@group(0) @binding(1)
var<storage, read> waves: array<package_shaders_water_SineWave>;
