@group(0) @binding(2)
var<storage, read> acc: array<u32>;

fn cascade_value(k: u32, pixel: u32, area: f32) -> vec3<f32> {
    let at = (k * cfg.width * cfg.height + pixel) * 3u;
    let s = cfg.fluxes[k] / (cfg.ramps.w * area);
    return vec3<f32>(f32(acc[at]), f32(acc[at + 1u]), f32(acc[at + 2u])) * s;
}

@group(0) @binding(0)
var<uniform> cfg: package_cascaded_common_Cascaded;

@group(0) @binding(1)
var eye: texture_2d<f32>;

@group(0) @binding(3)
var image: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.width || id.y >= cfg.height {
        return;
    }
    let e = textureLoad(eye, vec2<i32>(id.xy), 0);
    let z = e.x;
    var out = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    var k = 4u;
    for (var n = 0u; n < 4u; n++) {
        if k == 4u && z <= cfg.fars[n] {
            k = n;
        }
    }
    if z > 0.0 && k < 4u {
        var prev = cfg.eye_right.w;
        if k > 0u {
            prev = cfg.fars[k - 1u];
        }
        let far = cfg.fars[k];
        let band = cfg.eye_up.w * (far - prev);
        var b = 0.0;
        if k + 1u < 4u && band > 0.0 && z > far - band {
            b = (z - (far - band)) / band;
        }
        let pixel = id.y * cfg.width + id.x;
        var v = cascade_value(k, pixel, e.y) * (1.0 - b);
        if b > 0.0 {
            v += cascade_value(k + 1u, pixel, e.y) * b;
        }
        out = vec4<f32>(v, f32(k) + b);
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
