//! The caustics techniques: the registry ([`REGISTRY`], one line per technique, each entry a
//! [`Descriptor`] beside its technique's code), the job every technique takes, and the CPU twin of
//! each (the oracle of its GPU implementation's tests and the fallback where no GPU adapter exists).

pub mod buffers;
pub mod cascaded;
pub mod caustic_triangles;
pub mod describe;
mod job;
pub mod procedural;
pub mod volumes;
pub mod yuksel;

pub use describe::{Descriptor, Spec, canonical, find, floor_only_note, names, reference};
pub use job::{Job, Made, SceneCaustics, heights_for, lattice_heights, water_scene};

/// Names an entry went by before, and the entry each now names: `yuksel-gather` was the scatter,
/// `yuksel`'s default passes since 2026-12-03 (issue 28).
pub const ALIASES: &[(&str, &str)] = &[("yuksel-gather", "yuksel")];

/// Every technique, in one place: the ground truth first, then the papers in order. A new
/// technique adds its entry here (and its GPU implementation one line in `caustics_gpu`'s).
pub const REGISTRY: &[&Descriptor] = &[
    &crate::reference::DESCRIPTOR,
    &yuksel::DESCRIPTOR,
    &yuksel::TARGETS,
    &procedural::DESCRIPTOR,
    &procedural::VERTEX,
    &procedural::SCREEN,
    &procedural::TEXTURE,
    &volumes::DESCRIPTOR,
    &caustic_triangles::DESCRIPTOR,
    &cascaded::DESCRIPTOR,
];

/// The techniques a front end offers for `scene`: every registered technique that computes
/// caustics from what the scene has (its water: floor maps, a technique whose generator may be
/// the water surface, and eye-space images; else its glass objects) and its floor (a terrain
/// rules out those drawn on a flat floor), the reference always (for glass, paper 4's photon
/// tracer), after the others.
pub fn for_scene(scene: &crate::scene::Scene) -> Vec<String> {
    use crate::scene::Material;
    let inputs: &[Input] = if scene.water.is_some() {
        &[Input::Water, Input::GlassOrWater, Input::EyeSpace]
    } else if scene
        .objects
        .iter()
        .any(|o| matches!(o.material, Material::Glass { .. }))
    {
        &[Input::GlassOrWater]
    } else {
        return Vec::new();
    };
    let mut entries: Vec<&Descriptor> = REGISTRY
        .iter()
        .copied()
        .filter(|d| inputs.contains(&d.input) || d.reference)
        .filter(|d| d.flat_floor.is_none() || scene.floor.terrain.is_none())
        .collect();
    // The techniques first, the reference they are judged against after.
    entries.sort_by_key(|d| d.reference);
    entries.iter().map(|d| d.name.to_string()).collect()
}

/// What a technique reads and what it makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// A map of the floor square from the water surface (the minimum scene contract's case).
    Water,
    /// A map of the floor square from the scene's glass objects, or from its water surface where
    /// it has water (caustic-triangles: paper 4's generator is any refracting surface).
    GlassOrWater,
    /// Caustics from the water in the eye camera's screen space, not a floor map.
    EyeSpace,
}

impl Input {
    pub fn describe(self) -> &'static str {
        match self {
            Input::Water => "water -> floor map",
            Input::GlassOrWater => "glass or water -> floor map",
            Input::EyeSpace => "water -> eye space",
        }
    }
}

/// The checks every technique makes of its inputs, with one wording: a map of at least one texel and
/// a light that travels down. Returns the unit light direction.
pub fn check_inputs(width: usize, height: usize, light: glam::DVec3) -> crate::Result<glam::DVec3> {
    if width == 0 || height == 0 {
        return Err(crate::Error::InvalidParameter(format!(
            "caustics map resolution must be at least 1 x 1, got {width} x {height}"
        )));
    }
    if light.z >= 0.0 || !light.is_finite() {
        return Err(crate::Error::InvalidParameter(format!(
            "the light direction {light} must point down (z < 0)"
        )));
    }
    Ok(light.normalize())
}

#[cfg(test)]
mod for_scene_tests {
    use super::for_scene;
    use crate::scene::Scene;

    #[test]
    fn a_scene_offers_the_techniques_that_run_on_it() {
        let names = for_scene(&Scene::builtin("pool").unwrap());
        for n in [
            "reference",
            "yuksel",
            "yuksel-targets",
            "procedural",
            "volumes",
            "cascaded",
        ] {
            assert!(names.iter().any(|x| x == n), "{n} missing from {names:?}");
        }
        assert_eq!(names.last().map(String::as_str), Some("reference"));
        // The water surface is a caustic generator of paper 4 too.
        assert!(names.iter().any(|x| x == "caustic-triangles"));
        // A scene of glass objects offers the techniques whose generators they are.
        let glass = for_scene(&Scene::builtin("glass").unwrap());
        assert_eq!(glass, ["caustic-triangles", "reference"]);
        // Over a terrain, the techniques that follow it.
        let shore = for_scene(&Scene::builtin("shore").unwrap());
        assert_eq!(shore, ["cascaded", "reference"]);
    }
}
