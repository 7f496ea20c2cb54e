@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = frag.xy / vec2<f32>(f32(package_procedural_common_u.width), f32(package_procedural_common_u.height)) * package_procedural_common_u.size;
    return vec4<f32>(package_procedural_common__1procedural_caustic(p), 1.0);
}

struct package_procedural_common_Procedural {
    sun_x: vec4<f32>,
    sun_y: vec4<f32>,
    sun_z: vec4<f32>,
    up: vec4<f32>,
    absorption: vec4<f32>,
    wave: package_shaders_water_ProceduralWave,
    size: f32,
    depth: f32,
    ior: f32,
    extent: f32,
    width: u32,
    height: u32,
    target_size: u32,
    mesh: u32,
    source: u32,
    wrap: u32,
    _pad0: u32,
    _pad1: u32
}

fn package_procedural_common__1full_screen(v: u32) -> vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}

fn package_procedural_common__1light_lookup(uv: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(package_procedural_common__1light_map));
    let t = (uv / package_procedural_common_u.extent * 0.5 + 0.5) * vec2<f32>(dims) - 0.5;
    let b = floor(t);
    let f = t - b;
    let c = vec2<i32>(b);
    let top = mix(package_procedural_common__1light_texel(c, dims), package_procedural_common__1light_texel(c + vec2<i32>(1, 0), dims), f.x);
    let bottom = mix(package_procedural_common__1light_texel(c + vec2<i32>(0, 1), dims), package_procedural_common__1light_texel(c + vec2<i32>(1, 1), dims), f.x);
    return mix(top, bottom, f.y);
}

@group(0) @binding(2)
var package_procedural_common__1light_map: texture_2d<f32>;

fn package_procedural_common__1light_texel(c: vec2<i32>, dims: vec2<i32>) -> f32 {
    if any(c < vec2<i32>(0)) || any(c >= dims) {
        return 0.0;
    }
    return textureLoad(package_procedural_common__1light_map, c, 0).r;
}

fn package_procedural_common__1procedural_caustic(p: vec2<f32>) -> vec3<f32> {
    let up = package_procedural_common_u.up.xyz;
    let s = p + up.xy * (package_procedural_common_u.depth / up.z);
    let hg = package_procedural_common__1water_at(s);
    let n = package_shaders_optics__2height_field_normal(hg.yz);
    let r = package_shaders_optics__1refract_dir(up, -n, package_procedural_common_u.ior);
    var e = 0.0;
    let z = dot(r.xyz, package_procedural_common_u.sun_z.xyz);
    if r.w != 0.0 && z > 0.0 {
        let uv = vec2<f32>(dot(r.xyz, package_procedural_common_u.sun_x.xyz), dot(r.xyz, package_procedural_common_u.sun_y.xyz)) / z;
        e = package_procedural_common__1light_lookup(uv);
    }
    let d = (package_procedural_common_u.depth + hg.x) / up.z;
    let ground = package_procedural_common_u.absorption.w;
    return (ground + (1.0 - ground) * e) * exp(-package_procedural_common_u.absorption.rgb * d);
}

fn package_procedural_common__1water_at(p: vec2<f32>) -> vec3<f32> {
    if package_procedural_common_u.source == 1u {
        return package_shaders_water__1procedural_wave(package_procedural_common_u.wave, p);
    }
    return package_shaders_water__1grid_sample(package_procedural_common_heights, p, package_procedural_common_u.size, package_procedural_common_u.wrap != 0u);
}

@group(0) @binding(1)
var package_procedural_common_heights: texture_2d<f32>;

@group(0) @binding(0)
var<uniform> package_procedural_common_u: package_procedural_common_Procedural;

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
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

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return package_procedural_common__1full_screen(v);
}
