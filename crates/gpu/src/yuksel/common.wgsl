// Technique `yuksel` (paper 1): the uniform block every pass shares. Mirrors `YukselUniform` in
// yuksel/mod.rs and `YukselSetup` in caustics-core/src/techniques/yuksel/mod.rs.

import package::shaders::receivers::Receivers;

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
    subsamples: u32,          // k: samples per pixel along each axis
    footprint: u32,           // 1: each sample's light on its footprint; 0: a box of its size
    phase: u32,               // pass 1 and 2: the map's rows this draw serves, modulo 2^level
    split: f32,               // misfit above which a pixel takes its k x k samples; < 0: always
    pre_tiles: u32,           // tiles along x of the pre-pass texture's array; 0: one layer
    walls: u32,               // 1: the pool's walls close the square (`yuksel_record`)
    receivers: Receivers,     // what the samples' light meets (t0.w = 0: the plane z = 0)
}

// Every yuksel pass binds the uniform first.
@group(0) @binding(0) var<uniform> u: Yuksel;

// Where texel `xy` of the pre-pass texture (k x k texels per pixel of the level's map and apron)
// lies in its array of tiles `tile` texels each (`PrepassTiling` in yuksel/mod.rs): texel
// `xy % tile` of layer `(y / tile.y) u.pre_tiles + x / tile.x`, so that a map whose pre-pass is
// wider than the device allows (a 2048² map's 8,432 texels against 8,192) still runs. One layer
// (`u.pre_tiles` 0) skips the integer divisions, which cost lavapipe a quarter of the pre-pass.
fn pre_texel(xy: vec2<i32>, tile: vec2<u32>) -> vec3<i32> {
    if u.pre_tiles == 0u {
        return vec3<i32>(xy, 0);
    }
    let t = vec2<i32>(tile);
    return vec3<i32>(xy % t, (xy.y / t.y) * i32(u.pre_tiles) + xy.x / t.x);
}

// The gather region, written by the region pass (`region.wgsl`) and read by every other pass.
// Mirrors `Region` in caustics-core/src/techniques/yuksel/mod.rs: samples at column offsets
// shift.x + [-N/2, N/2] and row offsets shift.y + [-M/2, M/2] from a pixel's own sample, all
// in the pixels of the level's map.
struct YukselRegion {
    n: u32,
    m: u32,
    shift: vec2<i32>,
    level: u32,               // samples of a map 2^level times coarser, light in the map's pixels
    clamped: u32,
    _pad0: u32,
    _pad1: u32,
}

// Samples per pixel along each axis at `level`: k 2^level, at most 8 (or k where it is larger).
// CPU twin: `YukselSetup::subsamples_at` (`MAX_LEVEL_SUBSAMPLES`).
fn level_subsamples(level: u32) -> u32 {
    return min(u.subsamples << level, max(u.subsamples, 8u));
}

// The coarse map's size and pixel at `level`.
fn level_size(width: u32, height: u32, level: u32) -> vec2<u32> {
    return vec2<u32>(width >> level, height >> level);
}

// The pre-pass's pixels for a region of N x M at `level`: the level's map and the region's apron.
fn prepass_area(n: u32, m: u32, level: u32) -> vec2<u32> {
    return level_size(u.width, u.height, level) + vec2<u32>(n - 1u, m);
}

// Whether pixel `p` of the pre-pass's pixels (counted as `prepass_area`) is one of this frame's
// region `r` and one of the `held` that textures sized for the largest region hold.
fn in_prepass_area(p: vec2<u32>, held: vec2<u32>, r: YukselRegion) -> bool {
    let used = min(prepass_area(r.n, r.m, r.level), held);
    return p.x < used.x && p.y < used.y;
}

// The level's pixel (column, row) of pixel `p` of the pre-pass's pixels.
fn prepass_level_pixel(p: vec2<u32>, r: YukselRegion) -> vec2<i32> {
    return vec2<i32>(p) - vec2<i32>(i32(r.n / 2u), i32(r.m / 2u)) + r.shift;
}

// The share of a box of centre `c` and half-width `h` (pixels) in the pixel [-1/2, 1/2]: summed
// over the pixels it covers, exactly 1. With h = 1/2 (the paper's pixel box) the overlap 1 - |c|
// of two pixel squares. CPU twin: `box_share`.
fn box_share(c: f32, h: f32) -> f32 {
    return max(min(c + h, 0.5) - max(c - h, -0.5), 0.0) / (2.0 * h);
}

// A sample's two half-widths, packed by `yuksel_footprint` into one channel.
fn half_widths(packed: f32) -> vec2<f32> {
    return abs(unpack2x16float(bitcast<u32>(packed)));
}

// How many records a side a pixel has in the pre-pass (t of k), in its records' sign bits: none
// for k, x for 1, y for 2, both for 4. CPU twin: `Tier` in core's yuksel/prepass.rs.
fn tier_bits(t: u32, k: u32) -> u32 {
    if t >= k {
        return 0u;
    }
    if t == 1u {
        return 0x8000u;
    }
    if t == 2u {
        return 0x80000000u;
    }
    return 0x80008000u;
}

fn tier_side(packed: f32, k: u32) -> u32 {
    let bits = bitcast<u32>(packed) & 0x80008000u;
    if bits == 0u {
        return k;
    }
    if bits == 0x8000u {
        return 1u;
    }
    if bits == 0x80000000u {
        return 2u;
    }
    return 4u;
}

// `span` (along x, pixels from the pixel's centre) grown to hold record `rec`'s box where it
// carries light. An empty span is (3e38, -3e38).
fn span_with(span: vec2<f32>, rec: vec4<f32>) -> vec2<f32> {
    if rec.w == 0.0 {
        return span;
    }
    let half = half_widths(rec.z).x;
    return vec2<f32>(min(span.x, rec.x - half), max(span.y, rec.x + half));
}
