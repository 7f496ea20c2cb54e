//! What `caustics bake` renders: a caustics map sequence of water that tiles in space and loops in
//! time, for engines that project an animated caustic texture (a light cookie, a decal) instead of
//! computing caustics per frame. The water is made to loop here; the technique then maps a floor
//! square of the water's tile with the light that leaves one edge entering the opposite one
//! (`wrap`), so each map tiles.
//!
//! Looping follows the usual ways: Tessendorf's repeat time for the FFT ocean (every frequency
//! quantised to a multiple of `2π / T`, §4.2 of his notes), and sine waves whose periods divide
//! `T` (each rounded to the nearest `T / n`, and said so). The ripple simulation and paper 2's wave
//! function never return to a state, and are refused.

use glam::DVec3;

use crate::scene::{Scene, Water, WaterSource};
use crate::techniques::cascaded::WATER_IOR_RGB;
use crate::techniques::{Job, SceneCaustics, Spec};
use crate::water::ocean::Ocean;
use crate::{Error, Result};

/// The technique a bake uses by default: the most accurate one, the reference itself, which at
/// [`REFERENCE_CELLS`] cells per texel is also fast enough for an offline bake on the CPU (its
/// error and time per frame against the GPU techniques': docs/bake.md, docs/benchmarks.md
/// "Baking").
pub const DEFAULT_TECHNIQUE: &str = "reference";

/// The reference's triangulation cells per map texel along each axis in a bake: the fewest that
/// keep a frame within 0.1 % relative L1 of the converged map (docs/reference.md has the error and
/// time per cell count).
pub const REFERENCE_CELLS: u32 = 2;

/// The water made to tile and loop with period `period` seconds, and what was changed to make it
/// (one line each, for the user).
pub fn looping_water(water: &Water, period: f64) -> Result<(Water, Vec<String>)> {
    if !(period.is_finite() && period > 0.0) {
        return Err(Error::InvalidParameter(format!(
            "--period {period}: expected a positive number of seconds"
        )));
    }
    let mut notes = Vec::new();
    let source = match &water.source {
        WaterSource::Flat => WaterSource::Flat,
        WaterSource::HeightField(g) => {
            notes.push("the water is a still height field: every frame is the same".into());
            WaterSource::HeightField(g.clone())
        }
        WaterSource::Waves(waves) => WaterSource::Waves(
            waves
                .iter()
                .enumerate()
                .map(|(k, w)| {
                    let looped = w.looping(water.size, period);
                    let (was, now) = (w.period_on(water.size), looped.period_on(water.size));
                    if (was - now).abs() > 1e-9 * now {
                        notes.push(format!(
                            "wave {k}: period {was:.4} s rounded to {now:.4} s ({} cycles in the {period} s loop)",
                            (period / now).round()
                        ));
                    }
                    looped
                })
                .collect(),
        ),
        WaterSource::Ocean(ocean) => {
            let mut params = ocean.params().clone();
            if params.repeat_period != Some(period) {
                notes.push(format!(
                    "the ocean's frequencies quantised to multiples of 2π / {period} s (Tessendorf's repeat time); waves slower than that stand still"
                ));
                params.repeat_period = Some(period);
            }
            WaterSource::Ocean(Box::new(Ocean::new(&params, water.size)?))
        }
        WaterSource::Ripple(_) => {
            return Err(Error::Unavailable(
                "the ripple simulation cannot loop: it evolves from its drops and never returns to a \
                 state. Bake waves or the FFT ocean (the built-in default, or a scene with \
                 [water.waves] or [water.ocean])"
                    .into(),
            ));
        }
        WaterSource::Procedural(_) => {
            return Err(Error::Unavailable(
                "paper 2's procedural wave cannot loop: its phases advance at rates with no common \
                 period. Bake waves or the FFT ocean (the built-in default, or a scene with \
                 [water.waves] or [water.ocean])"
                    .into(),
            ));
        }
    };
    if !water.wrap {
        notes.push("the water wraps at the tile's edges (wrap = true), so the maps tile".into());
    }
    Ok((
        Water {
            source,
            wrap: true,
            ..water.clone()
        },
        notes,
    ))
}

/// The scene a bake maps: `scene`'s water made to loop ([`looping_water`]) over a flat open floor
/// (no walls, terrain or objects: an engine's texture is the light on a plane at the water's
/// depth), with a `width` × `height` map, and the notes on what changed.
pub fn bake_scene(
    scene: &Scene,
    period: f64,
    width: u32,
    height: u32,
) -> Result<(Scene, Vec<String>)> {
    let Some(water) = &scene.water else {
        return Err(Error::Unavailable(format!(
            "scene `{}` has no water to bake",
            scene.name
        )));
    };
    if !scene.light.is_sun() {
        return Err(Error::Unavailable(
            "a baked texture is lit by the sun: the scene's light has a position (a point or spot \
             light)"
                .into(),
        ));
    }
    let (water, mut notes) = looping_water(water, period)?;
    let mut out = scene.clone();
    if out.floor.walls || out.floor.terrain.is_some() || !out.objects.is_empty() {
        notes.push(
            "the floor is mapped as an open plane at the water's depth: walls, terrain and objects left out"
                .into(),
        );
    }
    out.floor.walls = false;
    out.floor.terrain = None;
    out.clear_objects();
    let mut water = water;
    if water.absorption != DVec3::ZERO {
        // Flat water then reads 1 in every channel; the engine colours the light by its own water.
        notes.push("absorption left to the engine: the maps are of clear water".into());
        water.absorption = DVec3::ZERO;
    }
    out.water = Some(water);
    out.caustics.width = width;
    out.caustics.height = height;
    Ok((out, notes))
}

/// The time of frame `k` of `frames` over one loop: frame `frames` would be frame 0 again.
pub fn frame_time(k: u32, frames: u32, period: f64) -> f64 {
    period * k as f64 / frames as f64
}

/// The scenes one frame maps: the bake's scene alone, or with `dispersion` one a colour, its
/// water's index of refraction moved by water's own dispersion (`WATER_IOR_RGB`, the C, D and F
/// lines, about the scene's index: paper 5's ray-based dispersion, §3.6).
pub fn colour_scenes(scene: &Scene, dispersion: bool) -> Vec<Scene> {
    let Some(water) = &scene.water else {
        return vec![scene.clone()];
    };
    if !dispersion {
        return vec![scene.clone()];
    }
    WATER_IOR_RGB
        .iter()
        .map(|n| {
            let mut s = scene.clone();
            s.water.as_mut().expect("checked above").ior = water.ior + n - WATER_IOR_RGB[1];
            s
        })
        .collect()
}

/// One baked frame: per texel, the relative irradiance of each colour (one without dispersion),
/// row 0 at y = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Texels along x, across the water's square.
    pub width: usize,
    /// Texels along y, across the water's square.
    pub height: usize,
    /// One map a colour (red, green, blue with dispersion; one without), each `width · height`
    /// texels row by row; 1 is flat water's irradiance.
    pub channels: Vec<Vec<f32>>,
}

impl Frame {
    /// How well the frame tiles: the mean jump between its first and last column and row (what a
    /// seam would show), and the mean step between neighbours inside; of its middle colour.
    pub fn edge_and_inside(&self) -> (f32, f32) {
        let g = &self.channels[self.channels.len() / 2];
        let (w, h) = (self.width, self.height);
        let at = |i: usize, j: usize| g[i * w + j];
        let (mut edge, mut inside) = (0.0f32, 0.0f32);
        for i in 0..h {
            edge += (at(i, 0) - at(i, w - 1)).abs();
            inside += (1..w).map(|j| (at(i, j) - at(i, j - 1)).abs()).sum::<f32>();
        }
        for j in 0..w {
            edge += (at(0, j) - at(h - 1, j)).abs();
            inside += (1..h).map(|i| (at(i, j) - at(i - 1, j)).abs()).sum::<f32>();
        }
        (
            edge / (w + h) as f32,
            inside / (h * (w - 1) + w * (h - 1)) as f32,
        )
    }

    /// From one map a colour, each map's mean of red, green and blue (the light of its index).
    pub fn from_maps(width: usize, height: usize, maps: &[Vec<[f32; 3]>]) -> Frame {
        Frame {
            width,
            height,
            channels: maps
                .iter()
                .map(|m| m.iter().map(|t| (t[0] + t[1] + t[2]) / 3.0).collect())
                .collect(),
        }
    }
}

/// Frame at `time` of `scenes` ([`colour_scenes`]) through the technique's CPU twin, one run a
/// colour: the bake where there is no GPU, and the oracle of the GPU's.
pub fn cpu_frame(spec: &Spec, scenes: &[Scene], time: f64) -> Result<Frame> {
    let mut maps = Vec::new();
    let (mut width, mut height) = (0, 0);
    for scene in scenes {
        let water = scene.water.as_ref().ok_or_else(|| {
            Error::Unavailable(format!("scene `{}` has no water to bake", scene.name))
        })?;
        let surface = water.surface_at(time)?;
        let job = Job::new(scene, Some(surface.as_ref()), REFERENCE_CELLS);
        let made = spec.run_cpu(&job, &|_, _| {})?;
        let SceneCaustics::Floor(map) = made.caustics else {
            return Err(Error::Unavailable(format!(
                "{} makes no floor map to bake",
                spec.name()
            )));
        };
        (width, height) = (map.width, map.height);
        maps.push(map.texels);
    }
    Ok(Frame::from_maps(width, height, &maps))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ripples_and_the_procedural_wave_are_refused_by_name() {
        for name in ["pool", "underwater"] {
            let scene = Scene::builtin(name).unwrap();
            let mut water = scene.water.clone().unwrap();
            water.source = WaterSource::Ripple(Default::default());
            let e = looping_water(&water, 4.0).unwrap_err().to_string();
            assert!(e.contains("ripple simulation cannot loop"), "{e}");
            water.source = WaterSource::Procedural(Default::default());
            let e = looping_water(&water, 4.0).unwrap_err().to_string();
            assert!(e.contains("procedural wave cannot loop"), "{e}");
        }
    }

    #[test]
    fn the_loop_returns_to_its_first_surface() {
        use glam::DVec2;
        for name in ["pool", "shore"] {
            let scene = Scene::builtin(name).unwrap();
            let (water, notes) = looping_water(scene.water.as_ref().unwrap(), 2.5).unwrap();
            assert!(water.wrap && !notes.is_empty(), "{name}: {notes:?}");
            let (a, b) = (
                water.surface_at(0.3).unwrap(),
                water.surface_at(2.8).unwrap(),
            );
            let c = water.surface_at(1.1).unwrap();
            let mut moved = 0.0f64;
            for p in [DVec2::new(0.1, 0.2), DVec2::new(0.77, 0.4)] {
                let p = p * water.size;
                let d = (a.height(p) - b.height(p)).abs();
                assert!(d < 1e-9 * water.size, "{name}: {d}");
                moved = moved.max((a.height(p) - c.height(p)).abs());
            }
            assert!(moved > 1e-6 * water.size, "{name}: the water stands still");
        }
    }

    /// The CPU twin's frame at the loop's end is its first; the maps tile (the jump across each
    /// edge is like a step inside), their flux is flat water's at every frame, and dispersion
    /// splits the colours on waves and not on flat water.
    #[test]
    fn cpu_frames_loop_tile_keep_their_flux_and_disperse() {
        let spec: Spec = "yuksel".parse().unwrap();
        let (scene, _) = bake_scene(&Scene::builtin("pool").unwrap(), 2.0, 48, 48).unwrap();
        let scenes = colour_scenes(&scene, true);
        let first = cpu_frame(&spec, &scenes, 0.0).unwrap();
        let last = cpu_frame(&spec, &scenes, 2.0).unwrap();
        let worst = first.channels[1]
            .iter()
            .zip(&last.channels[1])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        eprintln!("frame N against frame 0: {worst:.2e}");
        // measured 0 (the waves' phases differ by whole cycles): float precision
        assert!(worst < 1e-6, "frame N differs from frame 0 by {worst}");
        let (edge, inside) = first.edge_and_inside();
        eprintln!("edge jump {edge:.4}, inside step {inside:.4}");
        // measured 0.468 across the edges against 0.478 inside
        assert!(edge < 1.5 * inside, "a seam: {edge} against {inside}");
        let mid = cpu_frame(&spec, &scenes, 0.7).unwrap();
        for f in [&first, &mid] {
            let mean = f.channels[1].iter().sum::<f32>() / f.channels[1].len() as f32;
            eprintln!("flux {mean:.6}");
            // measured 0.999950 and 0.999951
            assert!((mean - 1.0).abs() < 5e-4, "flux {mean}");
        }
        let split = first.channels[0]
            .iter()
            .zip(&first.channels[2])
            .map(|(r, b)| (r - b).abs())
            .fold(0.0f32, f32::max);
        eprintln!("largest red-blue split on waves {split:.4}");
        // measured 0.26
        assert!(split > 0.026, "red and blue alike on waves: {split}");
        let mut flat = scene.clone();
        flat.water.as_mut().unwrap().source = WaterSource::Flat;
        let flat = cpu_frame(&spec, &colour_scenes(&flat, true), 0.0).unwrap();
        let most = flat
            .channels
            .iter()
            .flatten()
            .map(|v| (v - 1.0).abs())
            .fold(0.0f32, f32::max);
        eprintln!("flat water's largest departure from 1: {most:.2e}");
        // measured 0
        assert!(most < 1e-6, "flat water is not 1 in every colour: {most}");
    }

    #[test]
    fn the_default_technique_is_registered_and_maps_the_floor() {
        let d = crate::techniques::find(DEFAULT_TECHNIQUE).expect("registered");
        assert!(
            !d.eye_space() && d.input != crate::techniques::Input::EyeSpace,
            "{}",
            d.name
        );
    }

    /// The baked floor is an open plane: the objects leave the receivers with the scene.
    #[test]
    fn a_bake_leaves_the_objects_out_of_the_receivers() {
        let scene = Scene::builtin("objects").unwrap();
        assert!(scene.floor.solids.is_some());
        let (out, notes) = bake_scene(&scene, 4.0, 32, 32).unwrap();
        assert!(
            out.objects.is_empty() && !out.floor.has_receivers(),
            "{notes:?}"
        );
    }

    #[test]
    fn a_period_must_be_positive() {
        let scene = Scene::builtin("pool").unwrap();
        for p in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(looping_water(scene.water.as_ref().unwrap(), p).is_err());
        }
    }
}
