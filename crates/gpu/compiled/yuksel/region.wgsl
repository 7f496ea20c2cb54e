const BIG: f32 = 3e38;

const MAX_LEVEL: u32 = 3u;

const MAX_M: u32 = 30u;

const MAX_N: u32 = 31u;

fn axis_region(lo: f32, hi: f32, limit: u32) -> vec3<i32> {
    if !(abs(lo) < BIG && abs(hi) < BIG) {
        return vec3<i32>(i32(limit), 0, 1);
    }
    let first = i32(-ceil(hi));
    var last = i32(-floor(lo));
    if ((last - first) & 1) == 1 {
        last += 1;
    }
    let len = last - first + 1;
    let centre = (first + last) / 2;
    if len > i32(limit) {
        return vec3<i32>(i32(limit), centre, 1);
    }
    return vec3<i32>(len, centre, 0);
}

@group(0) @binding(1)
var<storage, read> bound: array<u32, 4>;

@compute @workgroup_size(1)
fn main() {
    let l = package_yuksel_common_u.light.xyz;
    let t0 = package_shaders_optics__1refract_dir(l, vec3<f32>(0.0, 0.0, 1.0), package_yuksel_common_u.light.w);
    let flat = t0.xy / -t0.z * package_yuksel_common_u.depth;
    var lo = flat;
    var hi = flat;
    if bound[2] != 0u {
        lo = min(lo, -vec2<f32>(package_shaders_reduce_unordered(bound[0]), package_shaders_reduce_unordered(bound[1])));
        hi = max(hi, vec2<f32>(package_shaders_reduce_unordered(bound[2]), package_shaders_reduce_unordered(bound[3])));
    }
    let margin = (hi - lo) * 0.125;
    let w_lo = lo - margin - flat;
    let w_hi = hi + margin - flat;
    let from_water = package_yuksel_common_u.n == 0u && package_yuksel_common_u.m == 4294967295u;
    var level = 0u;
    loop {
        let pixel = package_yuksel_common_u.pixel * f32(1u << level);
        let d_lo = w_lo / pixel;
        let d_hi = w_hi / pixel;
        var x = vec3<i32>(i32(package_yuksel_common_u.n), 0, 0);
        if package_yuksel_common_u.n == 0u {
            x = axis_region(d_lo.x, d_hi.x, MAX_N);
        }
        var y = vec3<i32>(i32(package_yuksel_common_u.m) + 1, 0, 0);
        if package_yuksel_common_u.m == 4294967295u {
            y = axis_region(d_lo.y, d_hi.y, MAX_M + 1u);
        }
        let clamped = (x.z | y.z) != 0;
        let next = 2u << level;
        if !clamped || !from_water || level == MAX_LEVEL || package_yuksel_common_u.width % next != 0u || package_yuksel_common_u.height % next != 0u {
            out.n = u32(x.x);
            out.m = u32(y.x - 1);
            out.shift = vec2<i32>(x.y, y.y);
            out.level = level;
            out.clamped = u32(clamped);
            return;
        }
        level += 1u;
    }
}

@group(0) @binding(2)
var<storage, read_write> out: package_yuksel_common_YukselRegion;

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn package_shaders_reduce_unordered(u: u32) -> f32 {
    if (u & 2147483648u) != 0u {
        return bitcast<f32>(u & 2147483647u);
    }
    return bitcast<f32>(~u);
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
