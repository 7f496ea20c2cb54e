// How the scene looks, shared by every pass that shows it: the analytic sky, the floor's albedo
// patterns and the tone curve. CPU twins: `Tracer::sky` and `tone_map` in
// caustics-core/src/render.rs and `Albedo::at` in caustics-core/src/scene/mod.rs. The constants
// below are theirs, in one place on this side; the GPU-vs-CPU image test holds the two together.

const SKY_HORIZON: vec3<f32> = vec3<f32>(0.75, 0.85, 0.95);
const SKY_ZENITH: vec3<f32> = vec3<f32>(0.22, 0.42, 0.78);

const ALBEDO_TILES: u32 = 0u;
const ALBEDO_SAND: u32 = 1u;
const ALBEDO_PLAIN: u32 = 2u;
const ALBEDO_IMAGE: u32 = 3u;
const TILE_COLOUR: vec3<f32> = vec3<f32>(0.62, 0.78, 0.82);
const GROUT_COLOUR: vec3<f32> = vec3<f32>(0.18, 0.2, 0.22);

// x^y for x >= 0 with 0^y = 0 (y > 0): WGSL leaves pow(0, y) to the implementation.
fn pow0(x: f32, y: f32) -> f32 {
    if x <= 0.0 {
        return 0.0;
    }
    return pow(x, y);
}

// Radiance of the sky along unit `d`: a horizon-to-zenith gradient and the sun's glow, scaled by the
// sun's radiance. `sun` is the direction the sunlight travels.
fn sky(d: vec3<f32>, sun: vec3<f32>, sun_radiance: vec3<f32>) -> vec3<f32> {
    let up = max(d.z, 0.0);
    let base = mix(SKY_HORIZON, SKY_ZENITH, pow0(up, 0.6));
    let c = max(dot(d, -sun), 0.0);
    let glow = pow0(c, 400.0) * 40.0 + pow0(c, 12.0) * 0.4;
    return (base * 0.8 + vec3<f32>(glow)) * sun_radiance;
}

// Linear-RGB albedo of the floor at `p` on a square of side `size`; `image` is read only for
// ALBEDO_IMAGE (linear texels, row 0 at y = 0, nearest texel).
fn floor_albedo(kind: u32, image: texture_2d<f32>, p: vec2<f32>, size: f32) -> vec3<f32> {
    let u = p / size;
    switch kind {
        case ALBEDO_TILES: {
            // 8 tiles across the square, 4 % grout lines.
            let t = fract(u * 8.0);
            if t.x < 0.04 || t.y < 0.04 {
                return GROUT_COLOUR;
            }
            return TILE_COLOUR;
        }
        case ALBEDO_SAND: {
            let n = sin(u.x * 157.0) * sin(u.y * 113.0) * 0.03;
            return vec3<f32>(0.76 + n, 0.68 + n, 0.5 + n);
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

// Filmic curve (Narkowicz's ACES fit), then the sRGB transfer function, then the 8-bit code as the
// CPU rounds it (`(s * 255 + 0.5) as u8`), returned as code / 255 so that an `rgba8unorm` store
// writes exactly that code.
fn tone_map(c: vec3<f32>) -> vec3<f32> {
    let y = clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
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
