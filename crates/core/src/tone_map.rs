//! The final image's tone curve ([`ToneMap`]): a scene's setting (`[camera] tone_map`), so it sits
//! below the scene model; the CPU renderer ([`crate::render`]) and the GPU's final image apply it.

use glam::DVec3;

/// The tone curve of the final image: how linear radiance, after the exposure, becomes display
/// light in [0, 1] before the sRGB transfer function. Both filmic curves roll the highlights off
/// smoothly, so a caustic line several times brighter than the floor around it still reads as a
/// line, not as a flat white area; `none` clips, as a plain linear camera would.
///
/// Chosen per scene (`[camera] tone_map`) or by `caustics render --tone-map`; the GPU twin is
/// `tone_map` in `shaders/shading.wgsl`, selected by [`ToneMap::code`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ToneMap {
    /// ACES, Stephen Hill's fit of the reference rendering transform and the sRGB output
    /// transform (BakingLab's `ACESFitted`): the colour is taken to ACES's AP1 primaries, curved
    /// per channel there and brought back, so bright light desaturates towards white as on film
    /// instead of shifting hue as a per-channel curve on sRGB does. It reaches 1 only at an input
    /// of about 26.
    #[default]
    Aces = 0,
    /// AgX (Troy Sobotka), in its widely used minimal form: an inset of the primaries, a log2
    /// encoding over [-12.47, +4.03] stops, a polynomial fit of the default sigmoid, the outset
    /// back. Softer contrast than ACES and the most even desaturation of highlights.
    Agx = 1,
    /// No curve: display light is the radiance clamped to [0, 1].
    None = 2,
}

impl ToneMap {
    /// The curves' names as scene files and `--tone-map` spell them, in [`ToneMap::code`] order.
    pub const NAMES: [&'static str; 3] = ["aces", "agx", "none"];

    /// The value of `FinalImageUniform::tone_map` (`TONE_*` in `shading.wgsl`).
    pub fn code(self) -> u32 {
        self as u32
    }
}

impl std::str::FromStr for ToneMap {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "aces" => Ok(ToneMap::Aces),
            "agx" => Ok(ToneMap::Agx),
            "none" => Ok(ToneMap::None),
            _ => Err(format!(
                "unknown tone map `{s}`: expected one of {}",
                ToneMap::NAMES.join(", ")
            )),
        }
    }
}

/// `m c` for a matrix given by its rows.
fn mat3(m: &[[f64; 3]; 3], c: DVec3) -> DVec3 {
    DVec3::new(
        m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
        m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
        m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z,
    )
}

/// Linear sRGB to ACES AP1 with the RRT's saturation tweak folded in (Hill's `ACESInputMat`).
const ACES_IN: [[f64; 3]; 3] = [
    [0.59719, 0.35458, 0.04823],
    [0.07600, 0.90834, 0.01566],
    [0.02840, 0.13383, 0.83777],
];
/// The way back, with the ODT's desaturation (Hill's `ACESOutputMat`).
const ACES_OUT: [[f64; 3]; 3] = [
    [1.60475, -0.53108, -0.07367],
    [-0.10208, 1.10813, -0.00605],
    [-0.00327, -0.07276, 1.07602],
];
/// AgX's inset of the primaries.
const AGX_IN: [[f64; 3]; 3] = [
    [0.842479062253094, 0.0784335999999992, 0.0792237451477643],
    [0.0423282422610123, 0.878468636469772, 0.0791661274605434],
    [0.0423756549057051, 0.0784336, 0.879142973793104],
];
/// Its outset.
const AGX_OUT: [[f64; 3]; 3] = [
    [1.19687900512017, -0.0980208811401368, -0.0990297440797205],
    [-0.0528968517574562, 1.15190312990417, -0.0989611768448433],
    [-0.0529716355144438, -0.0980434501171241, 1.15107367264116],
];
const AGX_MIN_EV: f64 = -12.47393;
const AGX_MAX_EV: f64 = 4.026069;

/// Display light in [0, 1] (linear, before the sRGB transfer function) for radiance `c` already
/// multiplied by the exposure.
pub fn tone_curve(c: DVec3, curve: ToneMap) -> DVec3 {
    let y = match curve {
        ToneMap::Aces => {
            let v = mat3(&ACES_IN, c);
            let a = v * (v + 0.0245786) - 0.000090537;
            let b = v * (0.983729 * v + 0.4329510) + 0.238081;
            mat3(&ACES_OUT, a / b)
        }
        ToneMap::Agx => {
            let v = mat3(&AGX_IN, c).max(DVec3::splat(1e-10));
            let l = DVec3::new(v.x.log2(), v.y.log2(), v.z.log2());
            let x = (l.clamp(DVec3::splat(AGX_MIN_EV), DVec3::splat(AGX_MAX_EV)) - AGX_MIN_EV)
                / (AGX_MAX_EV - AGX_MIN_EV);
            let x2 = x * x;
            let x4 = x2 * x2;
            let s = 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x
                + 0.4298 * x2
                + 0.1191 * x
                - 0.00232;
            // The sigmoid's output is encoded for a display of gamma 2.2: back to light.
            let d = mat3(&AGX_OUT, s).max(DVec3::ZERO);
            DVec3::new(d.x.powf(2.2), d.y.powf(2.2), d.z.powf(2.2))
        }
        ToneMap::None => c,
    };
    y.clamp(DVec3::ZERO, DVec3::ONE)
}

/// The tone curve, then the sRGB transfer function, then the 8-bit code.
pub fn tone_map(c: DVec3, curve: ToneMap) -> [u8; 3] {
    let y = tone_curve(c, curve);
    let f = |y: f64| {
        let s = if y <= 0.003_130_8 {
            12.92 * y
        } else {
            1.055 * y.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0 + 0.5) as u8
    };
    [f(y.x), f(y.y), f(y.z)]
}
