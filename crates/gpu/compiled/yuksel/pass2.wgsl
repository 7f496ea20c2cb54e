@group(0) @binding(1)
var channels: texture_2d_array<f32>;

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let j = i32(frag.x);
    let i = u32(frag.y);
    if (i & ((1u << region.level) - 1u)) != package_yuksel_common_u.phase {
        discard;
    }
    let row = i32(i >> region.level);
    var e = 0.0;
    let m = i32(region.m);
    for (var k = 0; k <= m; k++) {
        let texel = textureLoad(channels, vec2<i32>(j, row + m - k), k / 4, 0);
        e += texel[k % 4];
    }
    return vec4<f32>(e * package_yuksel_common_u.attenuation.rgb, 1.0);
}

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

struct package_yuksel_common_YukselRegion {
    n: u32,
    m: u32,
    shift: vec2<i32>,
    level: u32,
    clamped: u32,
    _pad0: u32,
    _pad1: u32
}

@group(0) @binding(0)
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;

@group(0) @binding(2)
var<storage, read> region: package_yuksel_common_YukselRegion;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}
