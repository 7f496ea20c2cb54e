// Evaluates the shared WGSL math on a list of inputs, so tests can hold it against the CPU twins.

import package::shaders::caustics_light::{flat_water_light, sun_under_water};
import package::shaders::optics::{fresnel_transmittance, refract_dir};
import package::shaders::water::{
    ProceduralWave, SineWave, grid_sample, grid_sample_hermite, procedural_wave, sine_wave,
};

struct ProbeIn {
    incident: vec4<f32>,   // xyz direction, w = eta
    normal: vec4<f32>,     // xyz normal, w = n2 for the Fresnel test (n1 = 1)
    point: vec4<f32>,      // xy: a point on the water, z: a depth under it
}

struct ProbeOut {
    refracted: vec4<f32>,
    fresnel_sine_procedural: vec4<f32>, // x: Fresnel T, yzw: sum of the sine waves (h, grad)
    procedural: vec4<f32>,              // xyz: paper 2's wave (h, grad)
    grid: vec4<f32>,                    // xyz: bicubic height texture (h, grad)
    hermite: vec4<f32>,                 // xyz: the same from its Hermite form (water_patches.wgsl)
    sun_under: vec4<f32>,               // xyz: sun_under_water for the sun towards -incident
    flat_light: vec4<f32>,              // xyz: flat_water_light on `normal` at depth point.z
}

// probe.rs `PROBE_ABSORPTION`.
const PROBE_ABSORPTION: vec3<f32> = vec3<f32>(0.45, 0.09, 0.05);

struct ProbeParams {
    procedural: ProceduralWave,
    wave_count: u32,
    size: f32,
    wrap: u32,
}

@group(0) @binding(0) var<storage, read> inputs: array<ProbeIn>;
@group(0) @binding(1) var<storage, read_write> outputs: array<ProbeOut>;
@group(0) @binding(2) var<storage, read> waves: array<SineWave>;
@group(0) @binding(3) var<uniform> params: ProbeParams;
@group(0) @binding(4) var height: texture_2d<f32>;
@group(0) @binding(5) var patches: texture_2d<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = id.x;
    if k >= arrayLength(&inputs) {
        return;
    }
    let inp = inputs[k];
    var o: ProbeOut;
    o.refracted = refract_dir(inp.incident.xyz, inp.normal.xyz, inp.incident.w);
    let cos_i = -dot(inp.incident.xyz, inp.normal.xyz);
    var s = vec3<f32>(0.0);
    for (var w = 0u; w < params.wave_count; w++) {
        s += sine_wave(waves[w], inp.point.xy);
    }
    o.fresnel_sine_procedural = vec4<f32>(fresnel_transmittance(cos_i, 1.0, inp.normal.w), s);
    o.procedural = vec4<f32>(procedural_wave(params.procedural, inp.point.xy), 0.0);
    o.grid = vec4<f32>(grid_sample(height, inp.point.xy, params.size, params.wrap != 0u), 0.0);
    o.hermite = vec4<f32>(grid_sample_hermite(patches, inp.point.xy, params.size, params.wrap != 0u), 0.0);
    let toward_sun = sun_under_water(-inp.incident.xyz, inp.normal.w);
    o.sun_under = vec4<f32>(toward_sun, 0.0);
    o.flat_light = vec4<f32>(flat_water_light(PROBE_ABSORPTION, inp.point.z, toward_sun, inp.normal.xyz), 0.0);
    outputs[k] = o;
}
