@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= package_yuksel_common_u.width || id.y >= package_yuksel_common_u.height {
        return;
    }
    let e = f32(atomicLoad(&package_yuksel_scatter_sums[id.y * package_yuksel_common_u.width + id.x])) / package_yuksel_scatter_FIXED;
    textureStore(map_out, vec2<i32>(id.xy), vec4<f32>(e * package_yuksel_common_u.attenuation.rgb, 1.0));
}

@group(0) @binding(4)
var map_out: texture_storage_2d<rgba32float, write>;

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

struct package_yuksel_common_Yuksel {
    light: vec4<f32>,
    pixel: vec2<f32>,
    centre_offset: vec2<f32>,
    attenuation: vec4<f32>,
    size: f32,
    depth: f32,
    ior: f32,
    fresnel: u32,
    width: u32,
    height: u32,
    n: u32,
    m: u32,
    wrap: u32,
    channel_base: u32,
    subsamples: u32,
    footprint: u32,
    phase: u32,
    split: f32,
    pre_tiles: u32,
    walls: u32,
    receivers: package_shaders_receivers_Receivers
}

@group(0) @binding(0)
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;

const package_yuksel_scatter_FIXED: f32 = 1048576.0;

@group(0) @binding(2)
var<storage, read_write> package_yuksel_scatter_sums: array<atomic<u32>>;
