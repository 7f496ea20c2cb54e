@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let dims = vec2<f32>(f32(package_procedural_common_u.width), f32(package_procedural_common_u.height));
    let uv = frag.xy / dims;
    let c = textureSampleGrad(target_mips, mip_sampler, uv, vec2<f32>(1.0 / dims.x, 0.0), vec2<f32>(0.0, 1.0 / dims.y));
    return vec4<f32>(c.rgb, 1.0);
}

@group(0) @binding(4)
var mip_sampler: sampler;

struct package_procedural_common_Procedural {
    sun_x: vec4<f32>,
    sun_y: vec4<f32>,
    sun_z: vec4<f32>,
    up: vec4<f32>,
    absorption: vec4<f32>,
    wave: package_shaders_water_ProceduralWave,
    size: f32,
    depth: f32,
    ior: f32,
    extent: f32,
    width: u32,
    height: u32,
    target_size: u32,
    mesh: u32,
    source: u32,
    wrap: u32,
    _pad0: u32,
    _pad1: u32
}

fn package_procedural_common__1full_screen(v: u32) -> vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}

@group(0) @binding(0)
var<uniform> package_procedural_common_u: package_procedural_common_Procedural;

struct package_shaders_water_ProceduralWave {
    origin: vec2<f32>,
    amplitude: f32,
    frequency: f32,
    octave_base: f32,
    speed: f32,
    time: f32,
    octaves: u32
}

@group(0) @binding(3)
var target_mips: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return package_procedural_common__1full_screen(v);
}
