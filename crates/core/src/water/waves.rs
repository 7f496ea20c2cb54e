//! A sum of directional sine waves, `h(p) = Σ a_k sin(k_k · p − ω_k t + φ_k)`, with deep-water
//! dispersion `ω = sqrt(g |k|)`. The wave vectors are snapped to the lattice `2π n / size` so that the
//! sum tiles the scene square exactly.

use std::f64::consts::TAU;

use glam::DVec2;
use serde::{Deserialize, Serialize};

use super::Surface;

/// One wave as a scene file states it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wave {
    /// Crest height above rest, world units.
    pub amplitude: f64,
    /// Crest-to-crest distance, world units.
    pub wavelength: f64,
    /// Direction of travel in the xy plane (need not be normalised).
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub direction: [f64; 2],
    /// Phase offset, radians.
    #[serde(default)]
    pub phase: f64,
}

pub struct Waves {
    components: Vec<WaveTerm>,
}

/// One wave frozen at a time: `amplitude · sin(k · p + phase)`.
#[derive(Clone, Copy, Debug)]
pub struct WaveTerm {
    pub amplitude: f64,
    /// Wave vector, snapped to the tile's lattice.
    pub k: DVec2,
    /// Phase at the frozen time, `φ − ω t`.
    pub phase: f64,
}

/// Gravity, m/s².
pub const GRAVITY: f64 = 9.81;

impl Waves {
    /// Freeze the waves at time `t` over a square of side `size` (the period they are snapped to).
    pub fn new(waves: &[Wave], size: f64, t: f64) -> Self {
        let components = waves
            .iter()
            .map(|w| {
                let dir = DVec2::from(w.direction).normalize_or(DVec2::X);
                let k = dir * TAU / w.wavelength;
                // Snap to the periodic lattice; keep at least one cycle per tile.
                let n = (k * size / TAU).round();
                let n = if n == DVec2::ZERO { dir.signum() } else { n };
                let k = n * TAU / size;
                let omega = (GRAVITY * k.length()).sqrt();
                WaveTerm {
                    amplitude: w.amplitude,
                    k,
                    phase: w.phase - omega * t,
                }
            })
            .collect();
        Waves { components }
    }

    pub fn terms(&self) -> &[WaveTerm] {
        &self.components
    }
}

impl Surface for Waves {
    fn height(&self, p: DVec2) -> f64 {
        self.components
            .iter()
            .map(|w| w.amplitude * (w.k.dot(p) + w.phase).sin())
            .sum()
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.components
            .iter()
            .map(|w| w.amplitude * (w.k.dot(p) + w.phase).cos() * w.k)
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::water::test_support::assert_gradient_matches_finite_differences;

    fn sample() -> Waves {
        let w = |a, l, d: [f64; 2]| Wave {
            amplitude: a,
            wavelength: l,
            direction: d,
            phase: 0.3,
        };
        Waves::new(
            &[w(0.01, 0.25, [1.0, 0.2]), w(0.005, 0.1, [-0.3, 1.0])],
            1.0,
            0.7,
        )
    }

    #[test]
    fn gradient_is_exact() {
        let pts = [
            DVec2::new(0.1, 0.2),
            DVec2::new(0.77, 0.31),
            DVec2::new(0.5, 0.99),
        ];
        assert_gradient_matches_finite_differences(&sample(), &pts, 1e-6);
    }

    #[test]
    fn tiles_with_the_scene_square() {
        let s = sample();
        for p in [DVec2::new(0.13, 0.4), DVec2::new(0.9, 0.05)] {
            assert!((s.height(p) - s.height(p + DVec2::new(1.0, 0.0))).abs() < 1e-12);
            assert!((s.height(p) - s.height(p + DVec2::new(0.0, -1.0))).abs() < 1e-12);
        }
    }
}
