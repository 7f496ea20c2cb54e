const CAUSTICS_MAX_TAPS: f32 = 8.0;

fn caustics_bilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(caustics_dims(map, level));
    let u = p.x / size * dims.x - 0.5;
    let v = p.y / size * dims.y - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    let i = i32(i0);
    let j = i32(j0);
    let a = caustics_texel(map, mips, mips_from, level, i, j, wrap);
    let b = caustics_texel(map, mips, mips_from, level, i, j + 1, wrap);
    let c = caustics_texel(map, mips, mips_from, level, i + 1, j, wrap);
    let d = caustics_texel(map, mips, mips_from, level, i + 1, j + 1, wrap);
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

fn caustics_dims(map: texture_2d<f32>, level: u32) -> vec2<i32> {
    return vec2<i32>(max(textureDimensions(map) >> vec2<u32>(level), vec2<u32>(1u)));
}

fn caustics_filtered(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, size: f32, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    let texels = vec2<f32>(textureDimensions(map)) / size;
    let a = fa * texels;
    let b = fb * texels;
    var long = a;
    var la = length(a);
    if length(b) > la {
        long = b;
        la = length(b);
    }
    var across = 0.0;
    if la > 0.0 {
        across = abs(a.x * b.y - a.y * b.x) / la;
    }
    la = max(la, 1.0);
    across = max(across, 1.0);
    let taps = clamp(ceil(la / across), 1.0, CAUSTICS_MAX_TAPS);
    let width = max(la / taps, across);
    let level = max(log2(width / sqrt(3.0)), 0.0);
    let step = long / texels;
    var sum = vec3<f32>(0.0);
    for (var t = 0.0; t < taps; t += 1.0) {
        let q = p + step * ((t + 0.5) / taps - 0.5);
        let off = q.x < 0.0 || q.y < 0.0 || q.x > size || q.y > size;
        if has_beyond && !wrap && off {
            sum += beyond;
        }
        else {
            sum += caustics_trilinear(map, mips, mips_from, q, level, size, wrap);
        }
    }
    return sum / taps;
}

fn caustics_texel(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, i: i32, j: i32, wrap: bool) -> vec3<f32> {
    let dims = caustics_dims(map, level);
    var c = vec2<i32>(j, i);
    if wrap {
        c = ((c % dims) + dims) % dims;
    }
    else {
        c = clamp(c, vec2<i32>(0), dims - 1);
    }
    if level == 0u {
        return textureLoad(map, c, 0).rgb;
    }
    return textureLoad(mips, c, level - mips_from).rgb;
}

fn caustics_trilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, p: vec2<f32>, level: f32, size: f32, wrap: bool) -> vec3<f32> {
    let dims = textureDimensions(map);
    let last = firstLeadingBit(max(max(dims.x, dims.y), 1u));
    let l0 = min(u32(floor(level)), last);
    var f = level - f32(l0);
    if l0 == last {
        f = 0.0;
    }
    let a = caustics_bilinear(map, mips, mips_from, l0, p, size, wrap);
    if f == 0.0 {
        return a;
    }
    let b = caustics_bilinear(map, mips, mips_from, l0 + 1u, p, size, wrap);
    return a * (1.0 - f) + b * f;
}

fn wall_sample(walls: texture_2d_array<f32>, cols: u32, k: u32, along: f32, z: f32, size: f32, depth: f32) -> vec3<f32> {
    let rows = textureDimensions(walls).y;
    let u = clamp(along / size * f32(cols) - 0.5, 0.0, f32(cols - 1u));
    let v = clamp(z / depth * f32(rows) - 0.5, 0.0, f32(rows - 1u));
    let j0 = u32(floor(u));
    let i0 = u32(floor(v));
    let j1 = min(j0 + 1u, cols - 1u);
    let i1 = min(i0 + 1u, rows - 1u);
    let fu = u - f32(j0);
    let fv = v - f32(i0);
    let layer = i32(k);
    let a = textureLoad(walls, vec2<u32>(j0, i0), layer, 0).rgb;
    let b = textureLoad(walls, vec2<u32>(j1, i0), layer, 0).rgb;
    let c = textureLoad(walls, vec2<u32>(j0, i1), layer, 0).rgb;
    let d = textureLoad(walls, vec2<u32>(j1, i1), layer, 0).rgb;
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}
