const PROBE_ABSORPTION: vec3<f32> = vec3<f32>(0.45, 0.09, 0.05);

struct ProbeIn {
    incident: vec4<f32>,
    normal: vec4<f32>,
    point: vec4<f32>
}

struct ProbeOut {
    refracted: vec4<f32>,
    fresnel_sine_procedural: vec4<f32>,
    procedural: vec4<f32>,
    grid: vec4<f32>,
    hermite: vec4<f32>,
    sun_under: vec4<f32>,
    flat_light: vec4<f32>
}

struct ProbeParams {
    procedural: package_shaders_water_ProceduralWave,
    wave_count: u32,
    size: f32,
    wrap: u32
}

@group(0) @binding(4)
var height: texture_2d<f32>;

@group(0) @binding(0)
var<storage, read> inputs: array<ProbeIn>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = id.x;
    if k >= arrayLength(&inputs) {
        return;
    }
    let inp = inputs[k];
    var o: ProbeOut;
    o.refracted = package_shaders_optics__1refract_dir(inp.incident.xyz, inp.normal.xyz, inp.incident.w);
    let cos_i = -dot(inp.incident.xyz, inp.normal.xyz);
    var s = vec3<f32>(0.0);
    for (var w = 0u; w < params.wave_count; w++) {
        s += package_shaders_water__1sine_wave(waves[w], inp.point.xy);
    }
    o.fresnel_sine_procedural = vec4<f32>(package_shaders_optics__1fresnel_transmittance(cos_i, 1.0, inp.normal.w), s);
    o.procedural = vec4<f32>(package_shaders_water__1procedural_wave(params.procedural, inp.point.xy), 0.0);
    o.grid = vec4<f32>(package_shaders_water__1grid_sample(height, inp.point.xy, params.size, params.wrap != 0u), 0.0);
    o.hermite = vec4<f32>(package_shaders_water__2grid_sample_hermite(patches, inp.point.xy, params.size, params.wrap != 0u), 0.0);
    let toward_sun = package_shaders__1caustics_light__2sun_under_water(-inp.incident.xyz, inp.normal.w);
    o.sun_under = vec4<f32>(toward_sun, 0.0);
    o.flat_light = vec4<f32>(package_shaders__1caustics_light__2flat_water_light(PROBE_ABSORPTION, inp.point.z, toward_sun, inp.normal.xyz), 0.0);
    outputs[k] = o;
}

@group(0) @binding(1)
var<storage, read_write> outputs: array<ProbeOut>;

fn package_shaders__1caustics_light__2flat_water_light(absorption: vec3<f32>, depth: f32, toward_sun: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let cos_t = max(toward_sun.z, 0.001);
    return exp(-absorption * (depth / cos_t)) * (max(dot(n, toward_sun), 0.0) / cos_t);
}

fn package_shaders__1caustics_light__2sun_under_water(to_sun: vec3<f32>, ior: f32) -> vec3<f32> {
    let cos_i = max(to_sun.z, 0.0);
    let cos_t = sqrt(max(1.0 - (1.0 - cos_i * cos_i) / (ior * ior), 0.0));
    return vec3<f32>(to_sun.xy / ior, cos_t);
}

fn package_shaders_optics__1fresnel_transmittance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = min(abs(cos_i_in), 1.0);
    let sin_t = n1 / n2 * sqrt(max(1.0 - cos_i * cos_i, 0.0));
    if sin_t >= 1.0 {
        return 0.0;
    }
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 1.0 - 0.5 * (rs * rs + rp * rp);
}

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

struct package_shaders_water_ProceduralWave {
    origin: vec2<f32>,
    amplitude: f32,
    frequency: f32,
    octave_base: f32,
    speed: f32,
    time: f32,
    octaves: u32
}

struct package_shaders_water_SineWave {
    k: vec2<f32>,
    amplitude: f32,
    phase: f32
}

fn package_shaders_water__1catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

fn package_shaders_water__1grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

fn package_shaders_water__1grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = package_shaders_water__1catmull_rom(f.x);
    let wv = package_shaders_water__1catmull_rom(f.y);
    let n = vec2<i32>(dims);
    var first = vec2<i32>(base) - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    var h = 0.0;
    var hu = 0.0;
    var hv = 0.0;
    for (var a = 0; a < 4; a++) {
        let row = package_shaders_water__1grid_index(first.y, a, n.y, wrap);
        for (var b = 0; b < 4; b++) {
            let s = textureLoad(tex, vec2<i32>(package_shaders_water__1grid_index(first.x, b, n.x, wrap), row), 0).r;
            h += wu[0][b] * wv[0][a] * s;
            hu += wu[1][b] * wv[0][a] * s;
            hv += wu[0][b] * wv[1][a] * s;
        }
    }
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

fn package_shaders_water__1procedural_wave(w: package_shaders_water_ProceduralWave, p: vec2<f32>) -> vec3<f32> {
    let q = p - w.origin;
    let d = length(q);
    var sum_c = 0.0;
    var sum_s = 0.0;
    var f = w.octave_base;
    for (var i = 0u; i < w.octaves; i++) {
        let arg = w.speed * w.time + q.x * q.y * w.frequency / f;
        sum_c += -f * cos(arg);
        sum_s += w.frequency * sin(arg);
        f *= 0.5;
    }
    var radial = vec2<f32>(0.0);
    if d > 0.0 {
        radial = q / d;
    }
    let grad = 2.0 * w.amplitude * (radial * sum_c + d * sum_s * vec2<f32>(q.y, q.x));
    return vec3<f32>(2.0 * w.amplitude * d * sum_c, grad);
}

fn package_shaders_water__1sine_wave(w: package_shaders_water_SineWave, p: vec2<f32>) -> vec3<f32> {
    let arg = dot(w.k, p) + w.phase;
    return vec3<f32>(w.amplitude * sin(arg), w.amplitude * cos(arg) * w.k);
}

fn package_shaders_water__2grid_sample_hermite(patches: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(patches));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let n = vec2<i32>(dims);
    var c0 = vec2<i32>(base);
    var c1 = c0 + 1;
    var keep = vec4<f32>(1.0);
    if wrap {
        c0 = ((c0 % n) + n) % n;
        c1 = select(c0 + 1, c0 + 1 - n, c0 + 1 >= n);
    }
    else {
        keep = vec4<f32>(select(0.0, 1.0, c0.x >= 0 && c0.x < n.x), select(0.0, 1.0, c0.y >= 0 && c0.y < n.y), select(0.0, 1.0, c1.x >= 0 && c1.x < n.x), select(0.0, 1.0, c1.y >= 0 && c1.y < n.y));
        c0 = clamp(c0, vec2<i32>(0), n - 1);
        c1 = clamp(c1, vec2<i32>(0), n - 1);
    }
    let k00 = vec4<f32>(1.0, keep.x, keep.y, keep.x * keep.y);
    let k10 = vec4<f32>(1.0, keep.z, keep.y, keep.z * keep.y);
    let k01 = vec4<f32>(1.0, keep.x, keep.w, keep.x * keep.w);
    let k11 = vec4<f32>(1.0, keep.z, keep.w, keep.z * keep.w);
    let p00 = textureLoad(patches, c0, 0) * k00;
    let p10 = textureLoad(patches, vec2<i32>(c1.x, c0.y), 0) * k10;
    let p01 = textureLoad(patches, vec2<i32>(c0.x, c1.y), 0) * k01;
    let p11 = textureLoad(patches, c1, 0) * k11;
    let bu = package_shaders_water_hermite(f.x);
    let bv = package_shaders_water_hermite(f.y);
    let row0 = bu[0].x * vec2<f32>(p00.x, p00.z) + bu[0].y * vec2<f32>(p10.x, p10.z) + bu[0].z * vec2<f32>(p00.y, p00.w) + bu[0].w * vec2<f32>(p10.y, p10.w);
    let row1 = bu[0].x * vec2<f32>(p01.x, p01.z) + bu[0].y * vec2<f32>(p11.x, p11.z) + bu[0].z * vec2<f32>(p01.y, p01.w) + bu[0].w * vec2<f32>(p11.y, p11.w);
    let drow0 = bu[1].x * vec2<f32>(p00.x, p00.z) + bu[1].y * vec2<f32>(p10.x, p10.z) + bu[1].z * vec2<f32>(p00.y, p00.w) + bu[1].w * vec2<f32>(p10.y, p10.w);
    let drow1 = bu[1].x * vec2<f32>(p01.x, p01.z) + bu[1].y * vec2<f32>(p11.x, p11.z) + bu[1].z * vec2<f32>(p01.y, p01.w) + bu[1].w * vec2<f32>(p11.y, p11.w);
    let h = bv[0].x * row0.x + bv[0].y * row1.x + bv[0].z * row0.y + bv[0].w * row1.y;
    let hu = bv[0].x * drow0.x + bv[0].y * drow1.x + bv[0].z * drow0.y + bv[0].w * drow1.y;
    let hv = bv[1].x * row0.x + bv[1].y * row1.x + bv[1].z * row0.y + bv[1].w * row1.y;
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

fn package_shaders_water_hermite(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = vec4<f32>(2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2, t3 - 2.0 * t2 + t, t3 - t2);
    let dw = vec4<f32>(6.0 * t2 - 6.0 * t, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

@group(0) @binding(3)
var<uniform> params: ProbeParams;

@group(0) @binding(5)
var patches: texture_2d<f32>;

@group(0) @binding(2)
var<storage, read> waves: array<package_shaders_water_SineWave>;
