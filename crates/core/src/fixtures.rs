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

/// An open floor (no walls) over `terrain`, or the plane `z = 0` without one.
pub fn open_floor(terrain: Option<Grid>) -> crate::scene::Floor {
    crate::scene::Floor {
        terrain,
        solids: None,
        albedo: crate::scene::Albedo::Pattern(Default::default()),
        walls: false,
        deck: Default::default(),
    }
}

/// The plane slope `z = b + a x` over a square of side `size`, `n` samples a side.
pub fn slope(a: f64, b: f64, size: f64, n: usize) -> Grid {
    Grid::from_fn(n, n, |_, j| {
        (b + a * (j as f64 + 0.5) / n as f64 * size) as f32
    })
}

/// The worst relative departure of `map`, flat water's light over the slope `z = b + a x`, from
/// each floor point's cosine against the light over the flat floor's, `n · (−t₀) / −t₀_z`, times
/// `exp(−K d)` along its path to the rest level `d = (depth − z) / −t₀_z`. The 8 texel columns at
/// each x edge are left out: the clamped slope bends there and the light wraps onto it.
pub fn worst_off_the_attenuated_cosine(
    map: &crate::map::CausticsMap,
    (a, b): (f64, f64),
    depth: f64,
    t0: glam::DVec3,
    k: glam::DVec3,
) -> f64 {
    let n = map.width;
    let normal = crate::optics::height_field_normal(glam::DVec2::new(a, 0.0));
    let facing = normal.dot(-t0) / -t0.z;
    let mut worst: f64 = 0.0;
    for (idx, t) in map.texels.iter().enumerate() {
        let j = idx % n;
        if !(8..n - 8).contains(&j) {
            continue;
        }
        let x = (j as f64 + 0.5) / n as f64 * map.size;
        let d = (depth - (b + a * x)) / -t0.z;
        let expect = (-k * d).exp() * facing;
        for c in 0..3 {
            worst = worst.max((t[c] as f64 / expect[c] - 1.0).abs());
        }
    }
    worst
}
