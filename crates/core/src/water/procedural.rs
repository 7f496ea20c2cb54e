//! The wave function of paper 2 (Sánchez-Crespo, "Inexpensive underwater caustics", §"The wave
//! function"), as its Cg listing writes it once its lost line breaks are restored:
//!
//! `z(x, y, t) = 2 A d Σ_{i=0}^{O-1} −f_i cos(S t + x y W / f_i)`, `d = sqrt(x² + y²)`, `f_i = F / 2^i`.
//!
//! The listing's `gradwave` is broken (a stray `;` drops the second term of each derivative), so the
//! gradient here is differentiated afresh. With `c_i = cos(S t + x y W / f_i)`,
//! `s_i = sin(S t + x y W / f_i)` and `Σc = Σ −f_i c_i`:
//!
//! `∂z/∂x = 2A (x / d) Σc + 2 A d Σ W y s_i` (since `∂(−f_i c_i)/∂x = f_i s_i · y W / f_i = W y s_i`),
//! and symmetrically `∂z/∂y = 2A (y / d) Σc + 2 A d Σ W x s_i`. At `d = 0` the first term's limit
//! direction is undefined; there `Σc` multiplies a unit vector of zero length and we take 0.
//!
//! The function is not periodic: it is an aesthetic pattern, used as the paper does.

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::Surface;

/// Parameters with the paper's names and its defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProceduralParams {
    /// Amplitude `A`.
    pub amplitude: f64,
    /// Spatial frequency `W`.
    pub frequency: f64,
    /// Base octave factor `F`.
    pub octave_base: f64,
    /// Speed `S`.
    pub speed: f64,
    /// Octave count `O`.
    pub octaves: u32,
    /// World-space offset of the function's origin, so the pattern can sit where the pool is.
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub origin: [f64; 2],
}

impl Default for ProceduralParams {
    fn default() -> Self {
        ProceduralParams {
            amplitude: 0.01,
            frequency: 10.0,
            octave_base: 1.0,
            speed: 2.0,
            octaves: 5,
            origin: [0.0, 0.0],
        }
    }
}

/// Paper 2's wave function frozen at one instant.
pub struct Procedural {
    /// The function's constants and where its origin sits.
    pub params: ProceduralParams,
    /// The instant, seconds (the `t` of `S t`).
    pub t: f64,
}

impl Procedural {
    fn eval(&self, p: DVec2) -> (f64, DVec2) {
        let q = p - DVec2::from(self.params.origin);
        let (x, y) = (q.x, q.y);
        let d = q.length();
        let ProceduralParams {
            amplitude: a,
            frequency: w,
            octave_base: f,
            speed: s,
            octaves,
            ..
        } = self.params;
        let (mut sum_c, mut sum_s) = (0.0, 0.0);
        for i in 0..octaves {
            let fi = f / (1u64 << i) as f64;
            let arg = s * self.t + x * y * w / fi;
            sum_c += -fi * arg.cos();
            sum_s += w * arg.sin();
        }
        let z = 2.0 * a * d * sum_c;
        let radial = if d > 0.0 { q / d } else { DVec2::ZERO };
        let grad = 2.0 * a * (radial * sum_c + d * sum_s * DVec2::new(y, x));
        (z, grad)
    }
}

impl Surface for Procedural {
    fn height(&self, p: DVec2) -> f64 {
        self.eval(p).0
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.eval(p).1
    }
    fn height_gradient(&self, p: DVec2) -> (f64, DVec2) {
        self.eval(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::water::test_support::assert_gradient_matches_finite_differences;

    #[test]
    fn gradient_matches_finite_differences() {
        let s = Procedural {
            params: ProceduralParams::default(),
            t: 1.3,
        };
        let pts = [
            DVec2::new(0.1, 0.2),
            DVec2::new(-0.4, 0.35),
            DVec2::new(0.9, -0.7),
            DVec2::new(0.02, 0.6),
        ];
        assert_gradient_matches_finite_differences(&s, &pts, 1e-5);
    }
}
