struct ProceduralWave {
    origin: vec2<f32>,
    amplitude: f32,
    frequency: f32,
    octave_base: f32,
    speed: f32,
    time: f32,
    octaves: u32
}

struct SineWave {
    k: vec2<f32>,
    amplitude: f32,
    phase: f32
}

fn catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

fn grid_hermite_texel(tex: texture_2d<f32>, c: vec2<i32>, wrap: bool) -> vec4<f32> {
    let n = vec2<i32>(textureDimensions(tex));
    var first = c - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    let x = vec3<i32>(grid_index(first.x, 0, n.x, wrap), grid_index(first.x, 1, n.x, wrap), grid_index(first.x, 2, n.x, wrap));
    let y = vec3<i32>(grid_index(first.y, 0, n.y, wrap), grid_index(first.y, 1, n.y, wrap), grid_index(first.y, 2, n.y, wrap));
    let h = textureLoad(tex, vec2<i32>(x.y, y.y), 0).r;
    let hu = 0.5 * (textureLoad(tex, vec2<i32>(x.z, y.y), 0).r - textureLoad(tex, vec2<i32>(x.x, y.y), 0).r);
    let hv = 0.5 * (textureLoad(tex, vec2<i32>(x.y, y.z), 0).r - textureLoad(tex, vec2<i32>(x.y, y.x), 0).r);
    let huv = 0.25 * (textureLoad(tex, vec2<i32>(x.z, y.z), 0).r - textureLoad(tex, vec2<i32>(x.x, y.z), 0).r - textureLoad(tex, vec2<i32>(x.z, y.x), 0).r + textureLoad(tex, vec2<i32>(x.x, y.x), 0).r);
    return vec4<f32>(h, hu, hv, huv);
}

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

fn grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = catmull_rom(f.x);
    let wv = catmull_rom(f.y);
    let n = vec2<i32>(dims);
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

fn grid_sample_hermite(patches: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(patches));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let n = vec2<i32>(dims);
    var c0 = vec2<i32>(base);
    var c1 = c0 + 1;
    var keep = vec4<f32>(1.0);
    if wrap {
        c0 = ((c0 % n) + n) % n;
        c1 = select(c0 + 1, c0 + 1 - n, c0 + 1 >= n);
    }
    else {
        keep = vec4<f32>(select(0.0, 1.0, c0.x >= 0 && c0.x < n.x), select(0.0, 1.0, c0.y >= 0 && c0.y < n.y), select(0.0, 1.0, c1.x >= 0 && c1.x < n.x), select(0.0, 1.0, c1.y >= 0 && c1.y < n.y));
        c0 = clamp(c0, vec2<i32>(0), n - 1);
        c1 = clamp(c1, vec2<i32>(0), n - 1);
    }
    let k00 = vec4<f32>(1.0, keep.x, keep.y, keep.x * keep.y);
    let k10 = vec4<f32>(1.0, keep.z, keep.y, keep.z * keep.y);
    let k01 = vec4<f32>(1.0, keep.x, keep.w, keep.x * keep.w);
    let k11 = vec4<f32>(1.0, keep.z, keep.w, keep.z * keep.w);
    let p00 = textureLoad(patches, c0, 0) * k00;
    let p10 = textureLoad(patches, vec2<i32>(c1.x, c0.y), 0) * k10;
    let p01 = textureLoad(patches, vec2<i32>(c0.x, c1.y), 0) * k01;
    let p11 = textureLoad(patches, c1, 0) * k11;
    let bu = hermite(f.x);
    let bv = hermite(f.y);
    let row0 = bu[0].x * vec2<f32>(p00.x, p00.z) + bu[0].y * vec2<f32>(p10.x, p10.z) + bu[0].z * vec2<f32>(p00.y, p00.w) + bu[0].w * vec2<f32>(p10.y, p10.w);
    let row1 = bu[0].x * vec2<f32>(p01.x, p01.z) + bu[0].y * vec2<f32>(p11.x, p11.z) + bu[0].z * vec2<f32>(p01.y, p01.w) + bu[0].w * vec2<f32>(p11.y, p11.w);
    let drow0 = bu[1].x * vec2<f32>(p00.x, p00.z) + bu[1].y * vec2<f32>(p10.x, p10.z) + bu[1].z * vec2<f32>(p00.y, p00.w) + bu[1].w * vec2<f32>(p10.y, p10.w);
    let drow1 = bu[1].x * vec2<f32>(p01.x, p01.z) + bu[1].y * vec2<f32>(p11.x, p11.z) + bu[1].z * vec2<f32>(p01.y, p01.w) + bu[1].w * vec2<f32>(p11.y, p11.w);
    let h = bv[0].x * row0.x + bv[0].y * row1.x + bv[0].z * row0.y + bv[0].w * row1.y;
    let hu = bv[0].x * drow0.x + bv[0].y * drow1.x + bv[0].z * drow0.y + bv[0].w * drow1.y;
    let hv = bv[1].x * row0.x + bv[1].y * row1.x + bv[1].z * row0.y + bv[1].w * row1.y;
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

fn hermite(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = vec4<f32>(2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2, t3 - 2.0 * t2 + t, t3 - t2);
    let dw = vec4<f32>(6.0 * t2 - 6.0 * t, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
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

fn sine_wave(w: SineWave, p: vec2<f32>) -> vec3<f32> {
    let arg = dot(w.k, p) + w.phase;
    return vec3<f32>(w.amplitude * sin(arg), w.amplitude * cos(arg) * w.k);
}
