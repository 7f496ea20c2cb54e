const FIXED: f32 = 1048576.0;

fn add_record(rec: vec4<f32>, q: vec2<i32>) {
    if rec.w == 0.0 {
        return;
    }
    let f = i32(1u << region.level);
    let scale = f32(f);
    let base = q * f;
    let c = rec.xy * scale + (scale - 1.0) * 0.5;
    let half = package_yuksel_common__1half_widths(rec.z) * scale;
    let w = rec.w * scale * scale;
    let reach = vec2<i32>(i32(region.n / 2u), i32(region.m / 2u));
    let own = q - region.shift;
    let size = vec2<i32>(i32(package_yuksel_common_u.width), i32(package_yuksel_common_u.height));
    let lo = max(base + vec2<i32>(floor(c - half + 0.5)), max((own - reach) * f, vec2<i32>(0)));
    let hi = min(base + vec2<i32>(ceil(c + half - 0.5)), min((own + reach) * f + f - 1, size - 1));
    for (var y = lo.y; y <= hi.y; y++) {
        let ay = package_yuksel_common__1box_share(c.y - f32(y - base.y), half.y) * w;
        if ay == 0.0 {
            continue;
        }
        for (var x = lo.x; x <= hi.x; x++) {
            let a = package_yuksel_common__1box_share(c.x - f32(x - base.x), half.x) * ay;
            if a > 0.0 {
                atomicAdd(&sums[u32(y) * package_yuksel_common_u.width + u32(x)], u32(a * FIXED + 0.5));
            }
        }
    }
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
    _pad: u32,
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

@group(0) @binding(0)
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;

@group(0) @binding(3)
var<storage, read> region: package_yuksel_common_YukselRegion;

@group(0) @binding(2)
var<storage, read_write> sums: array<atomic<u32>>;
