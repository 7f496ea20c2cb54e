// How the scene looks, shared by every pass that shows it: the daylight sky, the floor's albedo
// patterns and the tone curve. CPU twins: `Sky::radiance` in caustics-core/src/sky.rs, `tone_map`
// in caustics-core/src/render.rs and `Albedo::filtered` in caustics-core/src/scene/mod.rs. The constants
// below are theirs, in one place on this side; the GPU-vs-CPU image test holds the two together.

const ALBEDO_TILES: u32 = 0u;
const ALBEDO_SAND: u32 = 1u;
const ALBEDO_PLAIN: u32 = 2u;
const ALBEDO_IMAGE: u32 = 3u;
const TILE_COLOUR: vec3<f32> = vec3<f32>(0.62, 0.78, 0.82);
const GROUT_COLOUR: vec3<f32> = vec3<f32>(0.18, 0.2, 0.22);

// Preetham et al. 1999's daylight along unit `d` (sky.rs `Sky::radiance`): the Perez function
// `scale (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)` of the view's zenith angle θ and its
// angle γ to the sun (`to_sun`), for the luminance and both chromaticities at once, each
// coefficient a vec3 over (Y, x, y).
fn perez_sky(
    d: vec3<f32>,
    to_sun: vec3<f32>,
    a: vec3<f32>,
    b: vec3<f32>,
    c: vec3<f32>,
    dd: vec3<f32>,
    e: vec3<f32>,
    scale: vec3<f32>,
) -> vec3<f32> {
    let cos_theta = max(d.z, 1e-3);
    let gamma = acos(clamp(dot(d, to_sun), -1.0, 1.0));
    let cos_gamma = cos(gamma);
    return scale * (1.0 + a * exp(b / cos_theta)) * (1.0 + c * exp(dd * gamma) + e * cos_gamma * cos_gamma);
}

// Luminance and chromaticity to linear sRGB (sky.rs `xyy_to_rgb`), negative components clipped.
fn xyy_to_rgb(v: vec3<f32>) -> vec3<f32> {
    let lum = v.x;
    let x = v.y;
    let y = v.z;
    if y <= 0.0 || lum <= 0.0 {
        return vec3<f32>(0.0);
    }
    let xyz = vec3<f32>(x / y * lum, lum, (1.0 - x - y) / y * lum);
    return max(vec3<f32>(
        dot(vec3<f32>(3.2406, -1.5372, -0.4986), xyz),
        dot(vec3<f32>(-0.9689, 1.8758, 0.0415), xyz),
        dot(vec3<f32>(0.0557, -0.2040, 1.0570), xyz),
    ), vec3<f32>(0.0));
}

// scene/mod.rs `SAND_*`.
const SAND_GRAIN: f32 = 0.05;
const SAND_GRAIN_AMPLITUDE: f32 = 0.08;
const SAND_PATCH: f32 = 0.5;
const SAND_PATCH_AMPLITUDE: f32 = 0.06;

// scene/mod.rs `sinc`.
fn sinc(x: f32) -> f32 {
    if abs(x) < 1e-6 {
        return 1.0;
    }
    return sin(x) / x;
}

// scene/mod.rs `NOISE_EXACT_BOX`, `NOISE_POINT`.
const NOISE_EXACT_BOX: f32 = 2.0;
const NOISE_POINT: f32 = 1e-3;

// scene/mod.rs `hat_integral`: the smoothstep hat's integral from -1 to `t`.
fn hat_integral(t: f32) -> f32 {
    let u = min(abs(t), 1.0);
    return 0.5 + sign(t) * (u - u * u * u + 0.5 * u * u * u * u);
}

// scene/mod.rs `hat_box_weights`: the lattice values i0 .. i0 + 4's weights in the box mean over
// [x - a, x + a]; i0 is returned through `first`.
fn hat_box_weights(x: f32, a: f32, first: ptr<function, i32>) -> vec4<f32> {
    let i0 = floor(x - a);
    *first = i32(i0);
    let t = vec4<f32>(x - i0) - vec4<f32>(0.0, 1.0, 2.0, 3.0);
    if a < NOISE_POINT {
        let u = min(abs(t), vec4<f32>(1.0));
        return 1.0 - u * u * (3.0 - 2.0 * u);
    }
    return vec4<f32>(
        hat_integral(t.x + a) - hat_integral(t.x - a),
        hat_integral(t.y + a) - hat_integral(t.y - a),
        hat_integral(t.z + a) - hat_integral(t.z - a),
        hat_integral(t.w + a) - hat_integral(t.w - a),
    ) / (2.0 * a);
}

// scene/mod.rs `value_noise`: smoothstep-interpolated hash01 values on cells `cell` wide, their
// exact mean over the footprint's extent `w` (at most NOISE_EXACT_BOX cells, a wider box's spread
// scaled down from that).
fn value_noise(p: vec2<f32>, cell: f32, seed: i32, w: vec2<f32>) -> f32 {
    let q = p / cell;
    let r = w / cell;
    let exact = min(r, vec2<f32>(NOISE_EXACT_BOX));
    var i0: i32;
    var j0: i32;
    let wx = hat_box_weights(q.x, 0.5 * exact.x, &i0);
    let wy = hat_box_weights(q.y, 0.5 * exact.y, &j0);
    j0 += seed;
    var n = 0.0;
    for (var b = 0; b < 4; b++) {
        if wy[b] == 0.0 {
            continue;
        }
        var row = 0.0;
        for (var a = 0; a < 4; a++) {
            if wx[a] != 0.0 {
                row += wx[a] * (2.0 * hash01(i0 + a, j0 + b) - 1.0);
            }
        }
        n += wy[b] * row;
    }
    let fade = pow(1.0 + r * r, vec2<f32>(-0.25)) / pow(1.0 + exact * exact, vec2<f32>(-0.25));
    return n * fade.x * fade.y;
}

// Linear-RGB albedo of the floor at `p` on a square of side `size`, box-filtered over a
// footprint `extent` wide along x and y (scene/mod.rs `Albedo::filtered`); `image` is read only
// for ALBEDO_IMAGE (linear texels, row 0 at y = 0, nearest texel).
fn floor_albedo(kind: u32, image: texture_2d<f32>, p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    let u = p / size;
    let w = extent / size;
    switch kind {
        case ALBEDO_TILES: {
            // 8 tiles across the square, 4 % grout lines.
            let t = u * 8.0;
            let jx = joint_cover(t.x, w.x * 8.0, 0.04);
            let jy = joint_cover(t.y, w.y * 8.0, 0.04);
            let grout = 1.0 - (1.0 - jx) * (1.0 - jy);
            return TILE_COLOUR * (1.0 - grout) + GROUT_COLOUR * grout;
        }
        case ALBEDO_SAND: {
            let ripple = sin(u.x * 157.0) * sinc(78.5 * w.x) * sin(u.y * 113.0) * sinc(56.5 * w.y) * 0.03;
            let grain = SAND_GRAIN_AMPLITUDE * value_noise(p, SAND_GRAIN, 0, extent)
                + SAND_PATCH_AMPLITUDE * value_noise(p, SAND_PATCH, 7919, extent);
            return vec3<f32>(0.76, 0.68, 0.5) * (1.0 + grain) + vec3<f32>(ripple);
        }
        case ALBEDO_PLAIN: {
            return vec3<f32>(0.7);
        }
        default: {
            let dims = textureDimensions(image);
            let j = min(u32(fract(u.x) * f32(dims.x)), dims.x - 1u);
            let i = min(u32(fract(u.y) * f32(dims.y)), dims.y - 1u);
            return textureLoad(image, vec2<u32>(j, i), 0).rgb;
        }
    }
}

// scene/mod.rs `hash01`: an integer hash to [0, 1) on the same u32 arithmetic.
fn hash01(x: i32, y: i32) -> f32 {
    var h = (bitcast<u32>(x) * 0x8da6b343u) ^ (bitcast<u32>(y) * 0xd8163841u);
    h ^= h >> 16u;
    h *= 0x7feb352du;
    h ^= h >> 15u;
    h *= 0x846ca68bu;
    h ^= h >> 16u;
    return f32(h) / 4294967296.0;
}

// `Deck::code` and the deck's sizes (scene/mod.rs `PAVER`, `JOINT`, `COPING`).
const DECK_STONE: u32 = 0u;
const DECK_CONCRETE: u32 = 1u;
const PAVER: f32 = 0.6;
const JOINT: f32 = 0.01;
const COPING: f32 = 0.3;

// scene/mod.rs `joint_cover`: the share of [x - w/2, x + w/2] (in periods) the joints of width
// `joint` at each period's start cover; the point test for w = 0.
fn joint_integral(x: f32, joint: f32) -> f32 {
    let n = floor(x);
    return n * joint + min(x - n, joint);
}

fn joint_cover(x: f32, w: f32, joint: f32) -> f32 {
    if w <= 1e-4 {
        return select(0.0, 1.0, x - floor(x) < joint);
    }
    return clamp((joint_integral(x + 0.5 * w, joint) - joint_integral(x - 0.5 * w, joint)) / w, 0.0, 1.0);
}

// scene/mod.rs `Deck::albedo`: the coping along the water, the paving beyond, its joints
// box-filtered over a sample's footprint (world units).
fn deck_albedo(kind: u32, p: vec2<f32>, size: f32, footprint: f32) -> vec3<f32> {
    let out = max(max(-p.x, p.x - size), max(-p.y, p.y - size));
    let coping = min(COPING, 0.1 * size);
    if out <= coping {
        if out < min(JOINT, 0.1 * coping) {
            return vec3<f32>(0.30, 0.29, 0.27);
        }
        return vec3<f32>(0.78, 0.76, 0.71);
    }
    if kind == DECK_CONCRETE {
        return vec3<f32>(0.55, 0.55, 0.53);
    }
    let row = floor(p.y / PAVER);
    let x = p.x / PAVER + 0.5 * (row - 2.0 * floor(row / 2.0));
    let col = floor(x);
    let w = footprint / PAVER;
    let joint = JOINT / PAVER;
    let grout = 1.0 - (1.0 - joint_cover(x, w, joint)) * (1.0 - joint_cover(p.y / PAVER, w, joint));
    let shade = 0.85 + 0.3 * hash01(i32(col), i32(row));
    return vec3<f32>(0.60, 0.53, 0.43) * (shade * (1.0 - grout)) + vec3<f32>(0.32, 0.31, 0.29) * grout;
}

// `ToneMap::code` (render.rs): which tone curve `tone_map` applies.
const TONE_ACES: u32 = 0u;
const TONE_AGX: u32 = 1u;
const TONE_NONE: u32 = 2u;

// render.rs `mat3`: a matrix given by its rows times `c`.
fn rows3(r0: vec3<f32>, r1: vec3<f32>, r2: vec3<f32>, c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(r0, c), dot(r1, c), dot(r2, c));
}

// render.rs `tone_curve`: display light in [0, 1] for radiance times the exposure. The matrices
// are render.rs's `ACES_IN`, `ACES_OUT`, `AGX_IN`, `AGX_OUT`, row by row.
fn tone_curve(c: vec3<f32>, curve: u32) -> vec3<f32> {
    var y = c;
    if curve == TONE_ACES {
        let v = rows3(
            vec3<f32>(0.59719, 0.35458, 0.04823),
            vec3<f32>(0.07600, 0.90834, 0.01566),
            vec3<f32>(0.02840, 0.13383, 0.83777),
            c,
        );
        let a = v * (v + 0.0245786) - 0.000090537;
        let b = v * (0.983729 * v + 0.4329510) + 0.238081;
        y = rows3(
            vec3<f32>(1.60475, -0.53108, -0.07367),
            vec3<f32>(-0.10208, 1.10813, -0.00605),
            vec3<f32>(-0.00327, -0.07276, 1.07602),
            a / b,
        );
    } else if curve == TONE_AGX {
        let min_ev = -12.47393;
        let max_ev = 4.026069;
        let v = max(rows3(
            vec3<f32>(0.842479062253094, 0.0784335999999992, 0.0792237451477643),
            vec3<f32>(0.0423282422610123, 0.878468636469772, 0.0791661274605434),
            vec3<f32>(0.0423756549057051, 0.0784336, 0.879142973793104),
            c,
        ), vec3<f32>(1e-10));
        let x = (clamp(log2(v), vec3<f32>(min_ev), vec3<f32>(max_ev)) - min_ev) / (max_ev - min_ev);
        let x2 = x * x;
        let x4 = x2 * x2;
        let s = 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2
            + 0.1191 * x - 0.00232;
        let d = max(rows3(
            vec3<f32>(1.19687900512017, -0.0980208811401368, -0.0990297440797205),
            vec3<f32>(-0.0528968517574562, 1.15190312990417, -0.0989611768448433),
            vec3<f32>(-0.0529716355144438, -0.0980434501171241, 1.15107367264116),
            s,
        ), vec3<f32>(0.0));
        y = pow(d, vec3<f32>(2.2));
    }
    return clamp(y, vec3<f32>(0.0), vec3<f32>(1.0));
}

// render.rs `tone_map`: the tone curve, then the sRGB transfer function, then the 8-bit code as
// the CPU rounds it (`(s * 255 + 0.5) as u8`), returned as code / 255 so that an `rgba8unorm`
// store writes exactly that code.
fn tone_map(c: vec3<f32>, curve: u32) -> vec3<f32> {
    let y = tone_curve(c, curve);
    var s: vec3<f32>;
    for (var k = 0; k < 3; k++) {
        if y[k] <= 0.0031308 {
            s[k] = 12.92 * y[k];
        } else {
            s[k] = 1.055 * pow(y[k], 1.0 / 2.4) - 0.055;
        }
    }
    return floor(s * 255.0 + 0.5) / 255.0;
}
