// FFT ocean, pass 1 of 3: the spectrum at time t (Tessendorf 2001, §4.3), ready for the inverse FFT.
// CPU twin: `Ocean::spectrum_at`, `Ocean::slopes` and the half-texel shift of `Ocean::synthesize` in
// caustics-core/src/water/ocean.rs.
//
// Each mode writes two complex coefficients, packed in one vec4:
// - xy: h̃(k, t) = h̃0(k) e^{iωt} + conj(h̃0(−k)) e^{−iωt}, whose transform is the height;
// - zw: i k_x h̃ + i (i k_y h̃), whose transform is ∂h/∂x + i ∂h/∂y (both spectra are Hermitian, so
//   one complex FFT carries the two real slopes).
// Both are multiplied by e^{iπ (n + m) / N}, which moves the DFT's samples at (j, i) dx half a texel
// on, to the grid's texel centres ((j + 0.5) dx, (i + 0.5) dx).

struct SpectrumParams {
    n: u32,
    time: f32,
    // 2π / size: the wave number of frequency 1.
    dk: f32,
    _pad: u32,
}

const TAU: f32 = 6.283185307179586;

@group(0) @binding(0) var<uniform> params: SpectrumParams;
// (h̃0(k), conj(h̃0(−k))) per mode, FFT order, row-major.
@group(0) @binding(1) var<storage, read> h0: array<vec4<f32>>;
// ω(k), rad/s, FFT order.
@group(0) @binding(2) var<storage, read> omega: array<f32>;
// e^{iπ a / N} for a in [0, 2N), computed in f64 on the CPU.
@group(0) @binding(3) var<storage, read> roots: array<vec2<f32>>;
@group(0) @binding(4) var<storage, read_write> spectrum: array<vec4<f32>>;

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

// The signed frequency of FFT index a of n: a below n/2, a − n from n/2 on.
fn frequency(a: u32, n: u32) -> i32 {
    if a < n / 2u {
        return i32(a);
    }
    return i32(a) - i32(n);
}

// e^{iπ f / N} for a signed frequency f in [−N/2, N/2).
fn shift(f: i32, n: u32) -> vec2<f32> {
    return roots[u32(f + 2 * i32(n)) % (2u * n)];
}

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
    // ωt reduced to [−π, π] first: GPU sin and cos are only specified to be accurate there.
    var phase = omega[index] * params.time;
    phase -= TAU * round(phase / TAU);
    let e = vec2<f32>(cos(phase), sin(phase));
    let h = cmul(modes.xy, e) + cmul(modes.zw, vec2<f32>(e.x, -e.y));

    let k = vec2<f32>(f32(frequency(j, n)), f32(frequency(i, n))) * params.dk;
    let i_h = vec2<f32>(-h.y, h.x);
    // i k_x h̃ + i (i k_y h̃) = i k_x h̃ − k_y h̃.
    let slope = i_h * k.x - h * k.y;

    let s = cmul(shift(frequency(i, n), n), shift(frequency(j, n), n));
    spectrum[index] = vec4<f32>(cmul(h, s), cmul(slope, s));
}
