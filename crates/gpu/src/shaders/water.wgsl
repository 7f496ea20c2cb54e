// Water surfaces shared by every pass: height and exact gradient, packed as vec3(h, dh/dx, dh/dy).
// CPU twins: caustics-core/src/water/{waves,procedural}.rs and grid.rs (tested against them).

// One directional sine wave, frozen in time: h = amplitude * sin(k · p + phase).
struct SineWave {
    k: vec2<f32>,
    amplitude: f32,
    phase: f32,
}

fn sine_wave(w: SineWave, p: vec2<f32>) -> vec3<f32> {
    let arg = dot(w.k, p) + w.phase;
    return vec3<f32>(w.amplitude * sin(arg), w.amplitude * cos(arg) * w.k);
}

// Paper 2's wave function and its gradient (derivation in procedural.rs).
struct ProceduralWave {
    origin: vec2<f32>,
    amplitude: f32,
    frequency: f32,
    octave_base: f32,
    speed: f32,
    time: f32,
    octaves: u32,
}

fn procedural_wave(w: ProceduralWave, p: vec2<f32>) -> vec3<f32> {
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

// Catmull-Rom weights of the taps at -1, 0, 1, 2 and their derivatives.
fn catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

// Tap `k` (0..3) of a row or column of `n` samples from the first tap `first`, periodic or clamped.
// Wrapping, `first` is already in [0, n), so with n >= 3 the taps pass the end at most once and need
// no division each (integer division is slow on some GPUs, and on lavapipe).
fn grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

// Height and gradient of the bicubic interpolant of a height texture covering [0, size]^2, samples
// at texel centres (the scene's convention).
fn grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = catmull_rom(f.x);
    let wv = catmull_rom(f.y);
    let n = vec2<i32>(dims);
    // The first tap's column and row, wrapped once into the grid when periodic.
    var first = vec2<i32>(base) - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    var h = 0.0;
    var hu = 0.0;
    var hv = 0.0;
    for (var a = 0; a < 4; a++) {
        let row = grid_index(first.y, a, n.y, wrap);
        for (var b = 0; b < 4; b++) {
            let s = textureLoad(tex, vec2<i32>(grid_index(first.x, b, n.x, wrap), row), 0).r;
            h += wu[0][b] * wv[0][a] * s;
            hu += wu[1][b] * wv[0][a] * s;
            hv += wu[0][b] * wv[1][a] * s;
        }
    }
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}
