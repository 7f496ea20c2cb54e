@group(0) @binding(1)
var heights: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = w.lattice + 1u;
    if id.x >= p || id.y >= p {
        return;
    }
    let k = id.y * p + id.x;
    let s = w.origin.xy + vec2<f32>(f32(id.x), f32(id.y)) * w.water.z;
    let hg = package_shaders_water__1grid_sample(heights, s, w.water.y, w.wrap != 0u);
    let l = w.light.xyz;
    let n = package_shaders_optics__2height_field_normal(hg.yz);
    let cos_i = -dot(l, n);
    let seen = 1.0 + dot(l.xy, hg.yz) / -l.z;
    let t = package_shaders_optics__1refract_dir(l, n, 1.0 / w.light.w);
    if t.w == 0.0 || cos_i <= 0.0 || seen <= 0.0 || t.z >= 0.0 {
        photons[k] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
        paths[k] = 0.0;
        return;
    }
    var fresnel = 1.0;
    if w.fresnel != 0u {
        fresnel = package_shaders_optics__1fresnel_transmittance(cos_i, 1.0, w.light.w) / w.water.w;
    }
    let power = w.water.z * w.water.z * seen * fresnel;
    let z = w.water.x + hg.x;
    if w.receiver == 0u && w.receivers.t0.w != 0.0 {
        let start = vec3<f32>(s, z);
        let d = package_shaders_receivers__1meet_receivers(receiver_heights, w.receivers, start, t.xyz);
        if d < 0.0 {
            photons[k] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
            paths[k] = 0.0;
            return;
        }
        photons[k] = vec4<f32>(package_shaders_receivers__1light_space(start + t.xyz * d, w.receivers.t0.xyz), power, 1.0);
        paths[k] = d;
        return;
    }
    if w.receiver == 0u {
        let d = z / -t.z;
        photons[k] = vec4<f32>(s + t.xy * d, power, 1.0);
        paths[k] = d;
        return;
    }
    let wall = w.receiver - 1u;
    let axis = wall / 2u;
    let plane = select(0.0, w.water.y, wall % 2u == 1u);
    let inward = select(1.0, -1.0, wall % 2u == 1u);
    let toward = -t[axis] * inward;
    let d = (plane - s[axis]) / t[axis];
    let hz = z + t.z * d;
    if toward <= 0.0 || hz < -w.water.y {
        photons[k] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
        paths[k] = 0.0;
        return;
    }
    let along = s[1u - axis] + t[1u - axis] * d;
    let stretch = w.water.y / w.water.x;
    photons[k] = vec4<f32>(along, hz * stretch, power * stretch, 1.0);
    paths[k] = d;
}

struct package__1caustic_triangles__1water_setup_WaterPhoton {
    light: vec4<f32>,
    water: vec4<f32>,
    lattice: u32,
    wrap: u32,
    fresnel: u32,
    receiver: u32,
    receivers: package_shaders_receivers_Receivers,
    origin: vec4<f32>
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

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
}

struct package_shaders_receivers_Bracket {
    a: f32,
    ga: f32,
    b: f32,
    gb: f32,
    kept: i32
}

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn package_shaders_receivers__1light_space(p: vec3<f32>, t0: vec3<f32>) -> vec2<f32> {
    return p.xy + t0.xy * (p.z / -t0.z);
}

fn package_shaders_receivers__1meet_receivers(map: texture_2d<f32>, r: package_shaders_receivers_Receivers, s: vec3<f32>, t: vec3<f32>) -> f32 {
    if t.z >= 0.0 {
        return -1.0;
    }
    let t0 = r.t0.xyz;
    let drift = length(t.xy - t0.xy * (t.z / t0.z));
    let rate = -t.z + r.view.w * drift;
    var g = s.z - package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(s, t0));
    if g <= 0.0 {
        return -1.0;
    }
    let tol = 0.0001 * r.view.z;
    var d = 0.0;
    for (var k = 0; k < 256; k++) {
        let step = max(g / rate, tol);
        let p = s + t * (d + step);
        let g_next = p.z - package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(p, t0));
        if g_next <= 0.0 {
            var br = package_shaders_receivers_Bracket(d, g, d + step, g_next, 0);
            var m = br.b;
            for (var n = 0; n < 24; n++) {
                m = package_shaders_receivers_chord(br);
                let pm = s + t * m;
                let gm = pm.z - package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(pm, t0));
                br = package_shaders_receivers_narrowed(br, m, gm);
                if abs(gm) < tol || br.b - br.a < tol {
                    break;
                }
            }
            return m;
        }
        d += step;
        g = g_next;
        if g < tol {
            return d;
        }
    }
    return d;
}

fn package_shaders_receivers__1receiver_height(map: texture_2d<f32>, r: package_shaders_receivers_Receivers, q: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(map));
    let u = (q - r.view.xy) / r.view.z - 0.5;
    let c = floor(u);
    let f = u - c;
    let i = vec2<i32>(c);
    let a = textureLoad(map, clamp(i, vec2<i32>(0), dims - 1), 0).x;
    let b = textureLoad(map, clamp(i + vec2<i32>(1, 0), vec2<i32>(0), dims - 1), 0).x;
    let d = textureLoad(map, clamp(i + vec2<i32>(0, 1), vec2<i32>(0), dims - 1), 0).x;
    let e = textureLoad(map, clamp(i + vec2<i32>(1, 1), vec2<i32>(0), dims - 1), 0).x;
    return mix(mix(a, b, f.x), mix(d, e, f.x), f.y);
}

fn package_shaders_receivers_chord(br: package_shaders_receivers_Bracket) -> f32 {
    return (br.a * br.gb - br.b * br.ga) / (br.gb - br.ga);
}

fn package_shaders_receivers_narrowed(br: package_shaders_receivers_Bracket, m: f32, gm: f32) -> package_shaders_receivers_Bracket {
    var out = br;
    if gm > 0.0 {
        out.a = m;
        out.ga = gm;
        if br.kept == 1 {
            out.gb *= 0.5;
        }
        out.kept = 1;
    }
    else {
        out.b = m;
        out.gb = gm;
        if br.kept == -1 {
            out.ga *= 0.5;
        }
        out.kept = -1;
    }
    return out;
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

@group(0) @binding(3)
var<storage, read_write> paths: array<f32>;

@group(0) @binding(2)
var<storage, read_write> photons: array<vec4<f32>>;

@group(0) @binding(4)
var receiver_heights: texture_2d<f32>;

@group(0) @binding(0)
var<uniform> w: package__1caustic_triangles__1water_setup_WaterPhoton;
