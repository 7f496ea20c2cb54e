@group(0) @binding(3)
var extents: texture_2d<f32>;

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

fn package_yuksel_common__1box_share(c: f32, h: f32) -> f32 {
    return max(min(c + h, 0.5) - max(c - h, -0.5), 0.0) / (2.0 * h);
}

fn package_yuksel_common__1half_widths(packed: f32) -> vec2<f32> {
    return abs(unpack2x16float(bitcast<u32>(packed)));
}

fn package_yuksel_common__1level_size(width: u32, height: u32, level: u32) -> vec2<u32> {
    return vec2<u32>(width >> level, height >> level);
}

fn package_yuksel_common__1level_subsamples(level: u32) -> u32 {
    return min(package_yuksel_common_u.subsamples << level, max(package_yuksel_common_u.subsamples, 8u));
}

fn package_yuksel_common__1pre_texel(xy: vec2<i32>, tile: vec2<u32>) -> vec3<i32> {
    if package_yuksel_common_u.pre_tiles == 0u {
        return vec3<i32>(xy, 0);
    }
    let t = vec2<i32>(tile);
    return vec3<i32>(xy % t, (xy.y / t.y) * i32(package_yuksel_common_u.pre_tiles) + xy.x / t.x);
}

fn package_yuksel_common__1tier_side(packed: f32, k: u32) -> u32 {
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
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;

fn pass1_channels(j: i32, r: i32, count: i32) -> array<f32, 32> {
    var intensity: array<f32, 32>;
    if r >= i32(package_yuksel_common__1level_size(package_yuksel_common_u.width, package_yuksel_common_u.height, region.level).y + region.m) || package_yuksel_common_u.phase >= (1u << region.level) {
        return intensity;
    }
    let scale = f32(1u << region.level);
    let centre = (scale - 1.0) * 0.5;
    let area = scale * scale;
    let jc = j >> region.level;
    let qx = f32(j - (jc << region.level));
    let col0 = region.shift.x - i32(region.n / 2u);
    let row0 = -i32(region.m / 2u) - region.shift.y;
    let base = i32(package_yuksel_common_u.channel_base);
    let last = min(base + count, i32(region.m) + 1);
    let sub = i32(package_yuksel_common__1level_subsamples(region.level));
    let tile = textureDimensions(pre);
    for (var col = 0; col < i32(region.n); col++) {
        let span = textureLoad(extents, vec2<i32>(jc + col, r), 0).xy;
        if (f32(col + col0) + span.y) * scale + centre - qx <= -0.5001 || (f32(col + col0) + span.x) * scale + centre - qx >= 0.5001 {
            continue;
        }
        let first = vec2<i32>((jc + col) * sub, r * sub);
        let at0 = package_yuksel_common__1pre_texel(first, tile);
        let p0 = textureLoad(pre, at0.xy, at0.z, 0);
        let side = i32(package_yuksel_common__1tier_side(p0.z, u32(sub)));
        for (var b = 0; b < side; b++) {
            for (var a = 0; a < side; a++) {
                let at = package_yuksel_common__1pre_texel(first + vec2<i32>(a, b), tile);
                let p = textureLoad(pre, at.xy, at.z, 0);
                let half = package_yuksel_common__1half_widths(p.z) * scale;
                let ax = package_yuksel_common__1box_share((f32(col + col0) + p.x) * scale + centre - qx, half.x);
                if ax == 0.0 {
                    continue;
                }
                let reach = (0.5 + half.y) / scale;
                let mid = p.y + (centre - f32(package_yuksel_common_u.phase)) / scale - f32(row0);
                let lo = max(base, i32(floor(mid - reach)) - 1);
                let hi = min(last, i32(ceil(mid + reach)) + 2);
                for (var k = lo; k < hi; k++) {
                    let ay = package_yuksel_common__1box_share((p.y - f32(k + row0)) * scale + centre - f32(package_yuksel_common_u.phase), half.y);
                    intensity[k - base] += ax * ay * p.w * area;
                }
            }
        }
    }
    return intensity;
}

@group(0) @binding(1)
var pre: texture_2d_array<f32>;

@group(0) @binding(2)
var<storage, read> region: package_yuksel_common_YukselRegion;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}
