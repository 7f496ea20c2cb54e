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
    n: u32,
    m: u32,
    wrap: u32,
    channel_base: u32,        // pass 1: first channel this draw writes
    _pad0: u32,
    _pad1: u32,
}

// The overlap of two pixel-sized squares whose centres are `d` pixels apart along one axis.
fn box_overlap(d: f32) -> f32 {
    return max(0.0, 1.0 - abs(d));
}
