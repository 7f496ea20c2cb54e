// FFT ocean, pass 2 of 3: one radix-2 Stockham stage of the inverse FFT, along every row or every
// column at once; log2(N) stages over the rows, then log2(N) over the columns, ping-ponging between
// two storage buffers. CPU twin: the rustfft calls of `Ocean::synthesize`
// (caustics-core/src/water/ocean.rs), rows first.
//
// Stage p (p = 1, 2, 4, …, N/2) merges pairs of length-p transforms into length-2p ones. Butterfly b
// (of N/2) takes u0 = src[b], u1 = src[b + N/2], with k = b mod p, and writes
// dst[2b − k] = u0 + w u1 and dst[2b − k + p] = u0 − w u1, w = e^{+iπ k / p}: the Stockham
// autosort form, which leaves the result in natural order with no bit-reversal pass. The sign is
// the inverse transform's, unnormalised: f(x) = Σ_k F(k) e^{i k·x}, as the series is written.
//
// Each element is a vec4: two complex signals (height, slopes) transformed together.

struct FftStage {
    n: u32,
    // Length of the transforms this stage merges: 1, 2, 4, …, N/2.
    p: u32,
    // 0: along each row (contiguous), 1: along each column (stride N).
    axis: u32,
    _pad: u32,
}

@group(0) @binding(0) var<uniform> stage: FftStage;
// e^{iπ a / N} for a in [0, 2N), computed in f64 on the CPU: exact twiddles, so the error stays at
// O(log N) roundings of the data.
@group(0) @binding(1) var<storage, read> roots: array<vec2<f32>>;
@group(0) @binding(2) var<storage, read> src: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> dst: array<vec4<f32>>;

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

// The storage index of element `pos` of row or column `line`.
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
    // e^{iπ k / p} = roots[k N / p].
    let w = roots[k * (n / p)];
    let u0 = src[element(line, b)];
    let u1 = src[element(line, b + half)];
    let t = vec4<f32>(cmul(u1.xy, w), cmul(u1.zw, w));
    let out = 2u * b - k;
    dst[element(line, out)] = u0 + t;
    dst[element(line, out + p)] = u0 - t;
}
