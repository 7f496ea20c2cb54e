//! Scenes the tests of several modules share.

use crate::grid::Grid;
use crate::scene::{Scene, Water};

/// The pool with gentle ripples (21-100 cm long), which 128² and 256² photons resolve; the
/// built-in pool's 11 cm wavelets need more photons than these tests afford.
pub fn gentle_pool() -> Scene {
    let mut scene = Scene::builtin("pool").unwrap();
    let old = [
        (0.0040, 0.50, [1.0, 0.25], 0.0),
        (0.0032, 0.36, [-0.4, 1.0], 1.3),
        (0.0025, 0.27, [0.8, -0.7], 2.1),
        (0.0020, 0.21, [0.1, 1.0], 0.4),
        (0.0050, 1.00, [1.0, 0.9], 4.0),
    ];
    scene.water.as_mut().unwrap().source = crate::scene::WaterSource::Waves(
        old.iter()
            .map(
                |&(amplitude, wavelength, direction, phase)| crate::water::waves::Wave {
                    amplitude,
                    wavelength,
                    direction,
                    phase,
                    period: None,
                },
            )
            .collect(),
    );
    scene
}

/// A sand bar across the pool, periodic like the light: a ridge along y whose crest stands 60 % of
/// the way up to the water, its faces up to 31° steep, rippled 10 % along its length.
pub fn sand_bar(water: &Water) -> Grid {
    let n = 128;
    let crest = 0.6 * water.depth;
    Grid::from_fn(n, n, |i, j| {
        let (x, y) = ((j as f64 + 0.5) / n as f64, (i as f64 + 0.5) / n as f64);
        let ridge = 0.5 - 0.5 * (std::f64::consts::TAU * x).cos();
        (crest * ridge * (1.0 + 0.1 * (std::f64::consts::TAU * 2.0 * y).sin()) / 1.1) as f32
    })
}
