@group(0) @binding(3)
var<storage, read_write> hits: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&hits) {
        return;
    }
    let v = water[id.x];
    var hit = vec4<f32>(0.0);
    if v.pos.w > 0.0 {
        let d = package_shaders_receivers__1meet_receivers(receiver_heights, r, v.pos.xyz, v.dir.xyz);
        if d >= 0.0 {
            hit = vec4<f32>(package_shaders_receivers__1light_space(v.pos.xyz + v.dir.xyz * d, r.t0.xyz), d, 1.0);
        }
    }
    hits[id.x] = hit;
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

struct package_volumes_common_WaterVertex {
    pos: vec4<f32>,
    dir: vec4<f32>
}

@group(0) @binding(0)
var<uniform> r: package_shaders_receivers_Receivers;

@group(0) @binding(2)
var receiver_heights: texture_2d<f32>;

@group(0) @binding(1)
var<storage, read> water: array<package_volumes_common_WaterVertex>;
