@group(0) @binding(0)
var<uniform> field: package_water__1water_field_FieldParams;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let h = package_shaders_water__1procedural_wave(wave, package_water__1water_field__1field_point(field, id.xy, dims)).x;
    textureStore(output, id.xy, vec4<f32>(field.amplitude * h, 0.0, 0.0, 0.0));
}

@group(0) @binding(2)
var output: texture_storage_2d<r32float, write>;

struct package_shaders_water_ProceduralWave {
    origin: vec2<f32>,
    amplitude: f32,
    frequency: f32,
    octave_base: f32,
    speed: f32,
    time: f32,
    octaves: u32
}

fn package_shaders_water__1procedural_wave(w: package_shaders_water_ProceduralWave, p: vec2<f32>) -> vec3<f32> {
    let q = p - w.origin;
    let d = length(q);
    var sum_c = 0.0;
    var sum_s = 0.0;
    var f = w.octave_base;
    for (var i = 0u; i < w.octaves; i++) {
        let arg = w.speed * w.time + q.x * q.y * w.frequency / f;
        sum_c += -f * cos(arg);
        sum_s += w.frequency * sin(arg);
        f *= 0.5;
    }
    var radial = vec2<f32>(0.0);
    if d > 0.0 {
        radial = q / d;
    }
    let grad = 2.0 * w.amplitude * (radial * sum_c + d * sum_s * vec2<f32>(q.y, q.x));
    return vec3<f32>(2.0 * w.amplitude * d * sum_c, grad);
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
var<uniform> wave: package_shaders_water_ProceduralWave;
