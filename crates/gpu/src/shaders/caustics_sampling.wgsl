// How a surface reads the caustics maps: the floor map's pyramid over a footprint, and the pool's
// walls' maps. One module for every reader (the final image's passes and bevy_caustics' material
// import it), each passing its own textures: functions of their arguments alone, with no binding
// of their own, so the module imports the same under either package.
//
// The floor map is a box-filter pyramid (caustics-core's `MapPyramid`): level 0 is `map`, level
// L ≥ 1 is mip `L - mips_from` of `mips` (the final image keeps levels 1.. in a texture of their
// own, `mips_from` = 1; a mipmapped map is its own `mips`, `mips_from` = 0). Texels are read by
// hand with textureLoad: an Rgba32Float texture need not be filterable.

// Texels of level `level` (`max(1, size >> level)`, as the pyramid's levels are sized). Derived,
// not queried: lavapipe answered textureDimensions at a level that varies per invocation with
// another level's size (wrong texels near the edges).
fn caustics_dims(map: texture_2d<f32>, level: u32) -> vec2<i32> {
    return vec2<i32>(max(textureDimensions(map) >> vec2<u32>(level), vec2<u32>(1u)));
}

fn caustics_texel(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, i: i32, j: i32, wrap: bool) -> vec3<f32> {
    let dims = caustics_dims(map, level);
    var c = vec2<i32>(j, i);
    if wrap {
        c = ((c % dims) + dims) % dims;
    } else {
        c = clamp(c, vec2<i32>(0), dims - 1);
    }
    if level == 0u {
        return textureLoad(map, c, 0).rgb;
    }
    return textureLoad(mips, c, level - mips_from).rgb;
}

// `CausticsMap::sample` at one level of the pyramid: bilinear between texel centres, clamped or
// wrapped at the edges; `size` is the square the map covers (scene units). The four texels' rows
// and columns are wrapped or clamped once each (as `caustics_texel` would each texel's): integer
// division is dear where a CPU runs the shader.
fn caustics_bilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = caustics_dims(map, level);
    let u = p.x / size * f32(dims.x) - 0.5;
    let v = p.y / size * f32(dims.y) - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    var c0 = vec2<i32>(i32(j0), i32(i0));
    var c1 = c0 + 1;
    if wrap {
        c0 = ((c0 % dims) + dims) % dims;
        c1 = select(c0 + 1, vec2<i32>(0), c0 + 1 == dims);
    } else {
        c0 = clamp(c0, vec2<i32>(0), dims - 1);
        c1 = clamp(c1, vec2<i32>(0), dims - 1);
    }
    var a: vec3<f32>;
    var b: vec3<f32>;
    var c: vec3<f32>;
    var d: vec3<f32>;
    if level == 0u {
        a = textureLoad(map, c0, 0).rgb;
        b = textureLoad(map, vec2<i32>(c1.x, c0.y), 0).rgb;
        c = textureLoad(map, vec2<i32>(c0.x, c1.y), 0).rgb;
        d = textureLoad(map, c1, 0).rgb;
    } else {
        let m = level - mips_from;
        a = textureLoad(mips, c0, m).rgb;
        b = textureLoad(mips, vec2<i32>(c1.x, c0.y), m).rgb;
        c = textureLoad(mips, vec2<i32>(c0.x, c1.y), m).rgb;
        d = textureLoad(mips, c1, m).rgb;
    }
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

// `MapPyramid::trilinear`: between the two levels around `level`, the coarsest alone above it.
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

// map.rs `MAX_TAPS`.
const CAUSTICS_MAX_TAPS: f32 = 8.0;

// `MapPyramid::filtered`: the map's mean over the footprint centred on floor point `p` and
// spanned by `fa`, `fb` (scene units: a pixel's step across the screen), up to CAUSTICS_MAX_TAPS
// trilinear taps along its long axis, each at the level whose box filter has the variance of the
// tap's share of it (`2^L = w / √3`), so far floor shows the caustics' mean instead of shimmering
// with whichever texel a pixel lands on. A map that does not wrap reads `beyond` for the taps off
// its square where `has_beyond`.
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
        } else {
            sum += caustics_trilinear(map, mips, mips_from, q, level, size, wrap);
        }
    }
    return sum / taps;
}

// `WallMap::sample`: wall `k`'s map (layer k of `walls`, its first `cols` columns across the wall's
// `size`, its rows up the water's `depth`) at `along` the wall and height `z`: bilinear between
// texel centres, clamped at the wall's edges.
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

// `EyeSpaceCaustics::sample`: an eye-space image (cascaded's, paper 5: the floor each pixel of
// the camera sees, w < 0 where it sees none) at `s`, the point's position on the image in
// normalised device coordinates (x right, y up, ±1 at the edges). Bilinear over the valid texels
// around it, renormalised; w = 0 where their weight is under 1e-3 (nothing valid near).
fn eye_space_bilinear(eye: texture_2d<f32>, s: vec2<f32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(eye));
    let u = (s.x + 1.0) * 0.5 * f32(dims.x) - 0.5;
    let w = (1.0 - s.y) * 0.5 * f32(dims.y) - 0.5;
    let x0 = floor(u);
    let y0 = floor(w);
    let f = vec2<f32>(u - x0, w - y0);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var dy = 0; dy < 2; dy++) {
        for (var dx = 0; dx < 2; dx++) {
            let c = vec2<i32>(i32(x0) + dx, i32(y0) + dy);
            if any(c < vec2<i32>(0)) || any(c >= dims) {
                continue;
            }
            let t = textureLoad(eye, c, 0);
            if t.w < 0.0 {
                continue;
            }
            let wx = select(1.0 - f.x, f.x, dx == 1);
            let wy = select(1.0 - f.y, f.y, dy == 1);
            sum += t.rgb * (wx * wy);
            weight += wx * wy;
        }
    }
    if weight < 1e-3 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(sum / weight, 1.0);
}
