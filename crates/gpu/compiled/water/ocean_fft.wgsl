struct FftStage {
    n: u32,
    p: u32,
    axis: u32,
    _pad: u32
}

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

@group(0) @binding(3)
var<storage, read_write> dst: array<vec4<f32>>;

fn element(line: u32, pos: u32) -> u32 {
    if stage.axis == 0u {
        return line * stage.n + pos;
    }
    return pos * stage.n + line;
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = stage.n;
    let half = n / 2u;
    let b = id.x;
    let line = id.y;
    if b >= half || line >= n {
        return;
    }
    let p = stage.p;
    let k = b & (p - 1u);
    let w = roots[k * (n / p)];
    let u0 = src[element(line, b)];
    let u1 = src[element(line, b + half)];
    let t = vec4<f32>(cmul(u1.xy, w), cmul(u1.zw, w));
    let out = 2u * b - k;
    dst[element(line, out)] = u0 + t;
    dst[element(line, out + p)] = u0 - t;
}

@group(0) @binding(1)
var<storage, read> roots: array<vec2<f32>>;

@group(0) @binding(2)
var<storage, read> src: array<vec4<f32>>;

@group(0) @binding(0)
var<uniform> stage: FftStage;
