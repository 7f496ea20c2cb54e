@group(0) @binding(0)
var<uniform> cfg: package_cascaded_common_Cascaded;

@group(0) @binding(2)
var composed: texture_2d<f32>;

@group(0) @binding(1)
var eye: texture_2d<f32>;

fn fetch(x: i32, y: i32, c: u32) -> f32 {
    let p = clamp(vec2<i32>(x, y), vec2<i32>(0), vec2<i32>(i32(cfg.width) - 1, i32(cfg.height) - 1));
    return textureLoad(composed, p, 0)[c];
}

@group(0) @binding(3)
var image: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.width || id.y >= cfg.height {
        return;
    }
    var out = textureLoad(composed, vec2<i32>(id.xy), 0);
    let e = textureLoad(eye, vec2<i32>(id.xy), 0);
    if e.w != 0.0 {
        let f = cfg.eye_pos.xyz + package_cascaded_common__1eye_ray(cfg, f32(id.x) + 0.5, f32(id.y) + 0.5) * e.x;
        let column = max(cfg.light.w - f.z, 0.0);
        for (var n = 0u; n < 2u; n++) {
            let c = n * 2u;
            let shift = select(cfg.post.zw, cfg.post.xy, n == 0u);
            let q = f - vec3<f32>(shift * column, 0.0);
            let p = package_cascaded_common__1eye_project(cfg, q);
            if p.z <= 0.0 {
                continue;
            }
            let uv = p.xy - 0.5;
            let base = floor(uv);
            let t = uv - base;
            let x0 = i32(base.x);
            let y0 = i32(base.y);
            out[c] = (fetch(x0, y0, c) * (1.0 - t.x) + fetch(x0 + 1, y0, c) * t.x) * (1.0 - t.y) + (fetch(x0, y0 + 1, c) * (1.0 - t.x) + fetch(x0 + 1, y0 + 1, c) * t.x) * t.y;
        }
    }
    textureStore(image, vec2<i32>(id.xy), out);
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

fn package_cascaded_common__1eye_project(c: package_cascaded_common_Cascaded, p: vec3<f32>) -> vec3<f32> {
    let v = p - c.eye_pos.xyz;
    let z = dot(v, c.eye_fwd.xyz);
    if z <= 0.0 {
        return vec3<f32>(0.0, 0.0, -1.0);
    }
    let sx = dot(v, c.eye_right.xyz) / z / (c.eye_pos.w * c.eye_fwd.w);
    let sy = dot(v, c.eye_up.xyz) / z / c.eye_pos.w;
    return vec3<f32>((sx + 1.0) * 0.5 * f32(c.width), (1.0 - sy) * 0.5 * f32(c.height), z);
}

fn package_cascaded_common__1eye_ray(c: package_cascaded_common_Cascaded, x: f32, y: f32) -> vec3<f32> {
    let sx = (2.0 * x / f32(c.width) - 1.0) * c.eye_pos.w * c.eye_fwd.w;
    let sy = (1.0 - 2.0 * y / f32(c.height)) * c.eye_pos.w;
    return c.eye_fwd.xyz + c.eye_right.xyz * sx + c.eye_up.xyz * sy;
}
