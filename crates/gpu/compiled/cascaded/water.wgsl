@group(0) @binding(0)
var<uniform> cfg: package_cascaded_common_Cascaded;

@group(0) @binding(2)
var gbuffer: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.res || id.y >= cfg.res {
        return;
    }
    let l = cfg.light.xyz;
    let level = cfg.light.w;
    let o = package_cascaded_common__1ray_origin(cfg, id.y, id.x);
    var s = (level - o.z) / l.z;
    var grad = vec2<f32>(0.0);
    for (var n = 0u; n < package_cascaded_common__1WATER_STEPS; n++) {
        let p = o + l * s;
        let hg = package_shaders_water__1grid_sample(water, p.xy, cfg.e_u.w, cfg.wrap != 0u);
        grad = hg.yz;
        let f = p.z - level - hg.x;
        let df = l.z - dot(hg.yz, l.xy);
        s -= f / df;
    }
    textureStore(gbuffer, vec2<i32>(id.xy), vec4<f32>(s, package_shaders_optics__2height_field_normal(grad)));
}

struct package_cascaded_common_Cascaded {
    light: vec4<f32>,
    e_u: vec4<f32>,
    e_v: vec4<f32>,
    view: vec4<f32>,
    view2: vec4<f32>,
    eye_pos: vec4<f32>,
    eye_fwd: vec4<f32>,
    eye_right: vec4<f32>,
    eye_up: vec4<f32>,
    ior: vec4<f32>,
    absorption: vec4<f32>,
    ramps: vec4<f32>,
    terrain: vec4<f32>,
    post: vec4<f32>,
    fars: vec4<f32>,
    fluxes: vec4<f32>,
    width: u32,
    height: u32,
    res: u32,
    cascade: u32,
    flags: u32,
    wrap: u32,
    walls: u32,
    _pad1: u32
}

const package_cascaded_common__1WATER_STEPS: u32 = 4u;

fn package_cascaded_common__1ray_origin(c: package_cascaded_common_Cascaded, i: u32, j: u32) -> vec3<f32> {
    let u = c.view.x + (f32(j) + 0.5) * c.view.z;
    let v = c.view.y + (f32(i) + 0.5) * c.view.w;
    return c.e_u.xyz * u + c.e_v.xyz * v + c.light.xyz * c.view2.x;
}

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
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

@group(0) @binding(1)
var water: texture_2d<f32>;
