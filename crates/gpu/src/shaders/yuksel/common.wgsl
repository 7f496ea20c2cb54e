// Technique `yuksel` (paper 1): the uniform block every pass shares. Mirrors `YukselUniform` in
// yuksel/mod.rs and `YukselSetup` in caustics-core/src/techniques/yuksel.rs.
struct Yuksel {
    light: vec4<f32>,         // xyz: unit direction the light travels; w: eta = 1 / ior
    pixel: vec2<f32>,         // map pixel size, world units
    centre_offset: vec2<f32>, // h L': floor point to illumination centre (Eq. 1)
    attenuation: vec4<f32>,   // rgb: exp(-K d0) per channel; w: T(theta0) (1 without Fresnel)
    size: f32,
    depth: f32,
    ior: f32,
    fresnel: u32,
    width: u32,
    height: u32,
    n: u32,                   // N given (or the paper's); 0: the region pass chooses it
    m: u32,                   // M given; 0xffffffff: the region pass chooses it
    wrap: u32,
    channel_base: u32,        // pass 1: first channel this draw writes
    _pad0: u32,
    _pad1: u32,
}

// The gather region, written by the region pass (`region.wgsl`) and read by every other pass.
// Mirrors `Region` in caustics-core/src/techniques/yuksel.rs: samples at column offsets
// shift.x + [-N/2, N/2] and row offsets shift.y + [-M/2, M/2] from a pixel's own sample, all
// in the pixels of the level's map.
struct YukselRegion {
    n: u32,
    m: u32,
    shift: vec2<i32>,
    level: u32,               // the passes run on a map 2^level times coarser, then upsample.wgsl
    clamped: u32,
    _pad0: u32,
    _pad1: u32,
}

// The coarse map's size and pixel at `level`.
fn level_size(width: u32, height: u32, level: u32) -> vec2<u32> {
    return vec2<u32>(width >> level, height >> level);
}

// The overlap of two pixel-sized squares whose centres are `d` pixels apart along one axis.
fn box_overlap(d: f32) -> f32 {
    return max(0.0, 1.0 - abs(d));
}
