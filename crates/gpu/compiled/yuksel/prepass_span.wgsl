@group(0) @binding(4)
var extents_out: texture_storage_2d<rg32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = package_yuksel_common__1level_subsamples(region.level);
    if k == 1u || !package_yuksel_common__2in_prepass_area(id.xy, textureDimensions(tiers), region) {
        return;
    }
    if textureLoad(tiers, vec2<i32>(id.xy), 0).x != k {
        return;
    }
    var span = vec2<f32>(3e38, -3e38);
    let tile = textureDimensions(pre);
    for (var q = 0u; q < k * k; q++) {
        let at = package_yuksel_common__1pre_texel(vec2<i32>(id.xy * k + vec2<u32>(q % k, q / k)), tile);
        let rec = textureLoad(pre, at.xy, at.z, 0);
        span = package_yuksel_common__1span_with(span, rec);
    }
    textureStore(extents_out, vec2<i32>(id.xy), vec4<f32>(span, 0.0, 0.0));
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

fn package_yuksel_common__1prepass_area(n: u32, m: u32, level: u32) -> vec2<u32> {
    return package_yuksel_common__1level_size(package_yuksel_common_u.width, package_yuksel_common_u.height, level) + vec2<u32>(n - 1u, m);
}

fn package_yuksel_common__1span_with(span: vec2<f32>, rec: vec4<f32>) -> vec2<f32> {
    if rec.w == 0.0 {
        return span;
    }
    let half = package_yuksel_common__1half_widths(rec.z).x;
    return vec2<f32>(min(span.x, rec.x - half), max(span.y, rec.x + half));
}

fn package_yuksel_common__2in_prepass_area(p: vec2<u32>, held: vec2<u32>, r: package_yuksel_common_YukselRegion) -> bool {
    let used = min(package_yuksel_common__1prepass_area(r.n, r.m, r.level), held);
    return p.x < used.x && p.y < used.y;
}

@group(0) @binding(0)
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;

@group(0) @binding(1)
var pre: texture_2d_array<f32>;

@group(0) @binding(2)
var<storage, read> region: package_yuksel_common_YukselRegion;

@group(0) @binding(3)
var tiers: texture_2d<u32>;
