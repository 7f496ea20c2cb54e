struct SpectrumParams {
    n: u32,
    time: f32,
    dk: f32,
    _pad: u32
}

const TAU: f32 = 6.283185307179586;

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn frequency(a: u32, n: u32) -> i32 {
    if a < n / 2u {
        return i32(a);
    }
    return i32(a) - i32(n);
}

@group(0) @binding(1)
var<storage, read> h0: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = params.n;
    let i = id.y;
    let j = id.x;
    if i >= n || j >= n {
        return;
    }
    let index = i * n + j;
    let modes = h0[index];
    var phase = omega[index] * params.time;
    phase -= TAU * round(phase / TAU);
    let e = vec2<f32>(cos(phase), sin(phase));
    let h = cmul(modes.xy, e) + cmul(modes.zw, vec2<f32>(e.x, -e.y));
    let k = vec2<f32>(f32(frequency(j, n)), f32(frequency(i, n))) * params.dk;
    let i_h = vec2<f32>(-h.y, h.x);
    let slope = i_h * k.x - h * k.y;
    let s = cmul(shift(frequency(i, n), n), shift(frequency(j, n), n));
    spectrum[index] = vec4<f32>(cmul(h, s), cmul(slope, s));
}

@group(0) @binding(2)
var<storage, read> omega: array<f32>;

@group(0) @binding(0)
var<uniform> params: SpectrumParams;

@group(0) @binding(3)
var<storage, read> roots: array<vec2<f32>>;

fn shift(f: i32, n: u32) -> vec2<f32> {
    return roots[u32(f + 2 * i32(n)) % (2u * n)];
}

@group(0) @binding(4)
var<storage, read_write> spectrum: array<vec4<f32>>;
