//! A sum of directional sine waves, `h(p) = Σ a_k sin(k_k · p − ω_k t + φ_k)`, with deep-water
//! dispersion `ω = sqrt(g |k|)` unless a wave states its period. The wave vectors are snapped to the
//! lattice `2π n / size` so that the sum tiles the scene square exactly; periods that divide a
//! loop's length make the sum loop in time (`caustics bake`, [`Wave::looping`]).

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
    /// Seconds per cycle; absent, deep-water dispersion's `2π / sqrt(g |k|)` for the snapped wave
    /// vector (set to make the sum loop: [`Wave::looping`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
}

impl Wave {
    /// The wave vector on a square of side `size`: along `direction`, snapped to the lattice
    /// `2π n / size` (at least one cycle per tile).
    pub fn snapped_k(&self, size: f64) -> DVec2 {
        let dir = DVec2::from(self.direction).normalize_or(DVec2::X);
        let k = dir * TAU / self.wavelength;
        let n = (k * size / TAU).round();
        let n = if n == DVec2::ZERO { dir.signum() } else { n };
        n * TAU / size
    }

    /// Seconds per cycle on a square of side `size`: its own, else deep-water dispersion's.
    pub fn period_on(&self, size: f64) -> f64 {
        self.period
            .unwrap_or_else(|| TAU / (GRAVITY * self.snapped_k(size).length()).sqrt())
    }

    /// This wave with its period rounded to the nearest `loop_period / n` (n ≥ 1 whole cycles per
    /// loop), so that a sum of such waves returns to itself after `loop_period` seconds.
    pub fn looping(&self, size: f64, loop_period: f64) -> Wave {
        let cycles = (loop_period / self.period_on(size)).round().max(1.0);
        Wave {
            period: Some(loop_period / cycles),
            ..self.clone()
        }
    }
}

/// A sum of [`Wave`]s frozen at one instant over a square they tile.
pub struct Waves {
    components: Vec<WaveTerm>,
}

/// One wave frozen at a time: `amplitude · sin(k · p + phase)`.
#[derive(Clone, Copy, Debug)]
pub struct WaveTerm {
    /// Crest height above rest, world units.
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
                let k = w.snapped_k(size);
                let omega = TAU / w.period_on(size);
                WaveTerm {
                    amplitude: w.amplitude,
                    k,
                    phase: w.phase - omega * t,
                }
            })
            .collect();
        Waves { components }
    }

    /// The frozen waves, in the order given to [`Waves::new`].
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
            period: None,
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

    /// A period rounded to divide the loop: the waves at `t + T` are the waves at `t`.
    #[test]
    fn looping_waves_return_after_the_loop() {
        let waves = [
            Wave {
                amplitude: 0.01,
                wavelength: 0.25,
                direction: [1.0, 0.2],
                phase: 0.3,
                period: None,
            },
            Wave {
                amplitude: 0.005,
                wavelength: 0.7,
                direction: [-0.3, 1.0],
                phase: 1.0,
                period: None,
            },
        ];
        let looped: Vec<Wave> = waves.iter().map(|w| w.looping(1.0, 3.0)).collect();
        for (w, l) in waves.iter().zip(&looped) {
            let cycles = 3.0 / l.period.unwrap();
            assert!((cycles - cycles.round()).abs() < 1e-12 && cycles >= 1.0);
            // Rounded by less than half a cycle per loop.
            assert!((3.0 / w.period_on(1.0) - cycles).abs() <= 0.5);
        }
        let (a, b) = (Waves::new(&looped, 1.0, 0.4), Waves::new(&looped, 1.0, 3.4));
        let unlooped = Waves::new(&waves, 1.0, 3.4);
        let p = DVec2::new(0.31, 0.62);
        assert!((a.height(p) - b.height(p)).abs() < 1e-12);
        assert!((a.height(p) - unlooped.height(p)).abs() > 1e-4);
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
