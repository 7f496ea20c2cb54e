struct Yuksel {
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
    _pad: u32,
    receivers: package_shaders_receivers_Receivers
}

struct YukselRegion {
    n: u32,
    m: u32,
    shift: vec2<i32>,
    level: u32,
    clamped: u32,
    _pad0: u32,
    _pad1: u32
}

fn box_share(c: f32, h: f32) -> f32 {
    return max(min(c + h, 0.5) - max(c - h, -0.5), 0.0) / (2.0 * h);
}

fn half_widths(packed: f32) -> vec2<f32> {
    return abs(unpack2x16float(bitcast<u32>(packed)));
}

fn in_prepass_area(p: vec2<u32>, held: vec2<u32>, r: YukselRegion) -> bool {
    let used = min(prepass_area(r.n, r.m, r.level), held);
    return p.x < used.x && p.y < used.y;
}

fn level_size(width: u32, height: u32, level: u32) -> vec2<u32> {
    return vec2<u32>(width >> level, height >> level);
}

fn level_subsamples(level: u32) -> u32 {
    return min(u.subsamples << level, max(u.subsamples, 8u));
}

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn pre_texel(xy: vec2<i32>, tile: vec2<u32>) -> vec3<i32> {
    if u.pre_tiles == 0u {
        return vec3<i32>(xy, 0);
    }
    let t = vec2<i32>(tile);
    return vec3<i32>(xy % t, (xy.y / t.y) * i32(u.pre_tiles) + xy.x / t.x);
}

fn prepass_area(n: u32, m: u32, level: u32) -> vec2<u32> {
    return level_size(u.width, u.height, level) + vec2<u32>(n - 1u, m);
}

fn prepass_level_pixel(p: vec2<u32>, r: YukselRegion) -> vec2<i32> {
    return vec2<i32>(p) - vec2<i32>(i32(r.n / 2u), i32(r.m / 2u)) + r.shift;
}

fn span_with(span: vec2<f32>, rec: vec4<f32>) -> vec2<f32> {
    if rec.w == 0.0 {
        return span;
    }
    let half = half_widths(rec.z).x;
    return vec2<f32>(min(span.x, rec.x - half), max(span.y, rec.x + half));
}

fn tier_bits(t: u32, k: u32) -> u32 {
    if t >= k {
        return 0u;
    }
    if t == 1u {
        return 32768u;
    }
    if t == 2u {
        return 2147483648u;
    }
    return 2147516416u;
}

fn tier_side(packed: f32, k: u32) -> u32 {
    let bits = bitcast<u32>(packed) & 2147516416u;
    if bits == 0u {
        return k;
    }
    if bits == 32768u {
        return 1u;
    }
    if bits == 2147483648u {
        return 2u;
    }
    return 4u;
}

@group(0) @binding(0)
var<uniform> u: Yuksel;
