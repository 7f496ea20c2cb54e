//! The one input every technique's run takes ([`Job`]: a scene as the technique should see it
//! this time) and what it gives back ([`JobOutput`]), for the CPU twins here and the GPU runs of
//! `caustics_gpu` alike, with the view of it the final image reads ([`Caustics`]).
//!
//! The descriptor is written in these terms, so they know no descriptor: what a job does with
//! one ([`Job::note_floor_only`]) is in [`super::describe`].

use glam::DVec3;

use crate::eye::EyeSpaceCaustics;
use crate::grid::Grid;
use crate::map::CausticsMap;
use crate::receivers::LightSpace;
use crate::scene::{Floor, Scene, Water, WaterSource};
use crate::walls::WallMaps;
use crate::water::{Surface, sample_grid};
use crate::{Error, Result};

/// A technique's input: the scene as it stands this time (its water as animated, the sun in
/// `light.direction`, the map size in `caustics.width` x `caustics.height`, the camera an
/// eye-space technique makes its image for, the objects that receive and shadow), the water
/// surface, and the reference's quality.
#[derive(Clone, Copy)]
pub struct Job<'a> {
    /// The scene as the technique should see it this time (water, sun, map size, camera,
    /// objects).
    pub scene: &'a Scene,
    /// The water surface, `None` for the scene's water at the scene's time.
    pub surface: Option<&'a dyn Surface>,
    /// The reference's triangulation cells per map texel along each axis (its quality knob).
    pub cells_per_texel: u32,
}

impl<'a> Job<'a> {
    /// A job on `scene`, with the water surface `surface` (`None`: the scene's water at its time)
    /// and the reference's `cells_per_texel`.
    pub fn new(scene: &'a Scene, surface: Option<&'a dyn Surface>, cells_per_texel: u32) -> Self {
        Job {
            scene,
            surface,
            cells_per_texel,
        }
    }

    /// The map's texels along x and y.
    pub fn size(&self) -> (usize, usize) {
        (
            self.scene.caustics.width as usize,
            self.scene.caustics.height as usize,
        )
    }

    /// The sun's direction of travel.
    pub fn light(&self) -> DVec3 {
        self.scene.light.direction
    }

    /// The scene's floor: its terrain (or the plane z = 0), albedo, walls and deck.
    pub fn floor(&self) -> &'a Floor {
        &self.scene.floor
    }

    /// The water, or an error naming the technique that needs it.
    pub fn water(&self, technique: &str) -> Result<&'a Water> {
        self.scene.water.as_ref().ok_or_else(|| {
            Error::InvalidParameter(format!(
                "scene `{}` has no water: technique `{technique}` computes caustics from a water surface",
                self.scene.name
            ))
        })
    }

    /// `f` of the water surface: the given one, or the scene's water at its time.
    pub fn with_surface<R>(
        &self,
        technique: &str,
        f: impl FnOnce(&Water, &dyn Surface) -> Result<R>,
    ) -> Result<R> {
        let water = self.water(technique)?;
        match self.surface {
            Some(s) => f(water, s),
            None => {
                let owned = water.surface_at(self.scene.time)?;
                f(water, owned.as_ref())
            }
        }
    }
}

/// Where the final image takes the floor's caustics from ([`SceneCaustics::caustics`]; the input
/// of `crate::render::render`).
#[derive(Clone, Copy)]
pub enum Caustics<'a> {
    /// A map of the floor square (every technique but `cascaded`).
    Floor(&'a CausticsMap),
    /// A floor map looked up from a light-space deposit, with the deposit, from which the objects
    /// among its receivers take their light.
    Received(&'a CausticsMap, &'a LightSpace),
    /// An image in the camera's screen space (`cascaded`).
    EyeSpace(&'a EyeSpaceCaustics),
}

/// What a technique made of a scene: a map of the floor square, or, for an eye-space technique
/// (paper 5), an image in the scene camera's screen space. Both light the final image
/// (`crate::render::render`) through [`caustics`](Self::caustics).
#[derive(Clone, Debug)]
pub enum SceneCaustics {
    /// A map of the floor square (every technique but `cascaded`).
    Floor(CausticsMap),
    /// An image in the scene camera's screen space (`cascaded`, paper 5).
    EyeSpace(EyeSpaceCaustics),
}

impl SceneCaustics {
    /// A borrowed view of it, as the final image reads it.
    pub fn caustics(&self) -> Caustics<'_> {
        match self {
            SceneCaustics::Floor(m) => Caustics::Floor(m),
            SceneCaustics::EyeSpace(e) => Caustics::EyeSpace(e),
        }
    }

    /// [`caustics`](Self::caustics), a floor map with `light`, the light-space deposit it was
    /// looked up from, where there is one.
    pub fn with_light<'a>(&'a self, light: Option<&'a LightSpace>) -> Caustics<'a> {
        match (self, light) {
            (SceneCaustics::Floor(m), Some(l)) => Caustics::Received(m, l),
            (c, _) => c.caustics(),
        }
    }

    /// The floor map; `None` for an eye-space image.
    pub fn floor(&self) -> Option<&CausticsMap> {
        match self {
            SceneCaustics::Floor(m) => Some(m),
            SceneCaustics::EyeSpace(_) => None,
        }
    }

    /// The floor map, or an error naming the technique that made an eye-space image instead.
    pub fn into_floor(self, technique: &str) -> Result<CausticsMap> {
        match self {
            SceneCaustics::Floor(m) => Ok(m),
            SceneCaustics::EyeSpace(_) => Err(Error::InvalidParameter(format!(
                "technique `{technique}` computes caustics in the eye camera's screen space, not as a map of the floor square"
            ))),
        }
    }
}

/// What a technique's run on a [`Job`] makes: its floor map or eye-space image, and the walls'
/// maps.
#[derive(Clone, Debug)]
pub struct JobOutput {
    /// The floor map or the eye-space image.
    pub caustics: SceneCaustics,
    /// The light-space deposit the floor map was looked up from, where objects are among the
    /// technique's receivers: their light.
    pub light: Option<LightSpace>,
    /// The pool's walls' maps, from a technique that lights them when the scene's walls are on;
    /// `None` from a floor-only technique.
    pub walls: Option<WallMaps>,
}

impl JobOutput {
    /// The output of a floor technique: its floor map `map` and the walls' maps, if it made them.
    pub fn floor(map: CausticsMap, walls: Option<WallMaps>) -> Self {
        JobOutput {
            caustics: SceneCaustics::Floor(map),
            light: None,
            walls,
        }
    }

    /// The output of a floor technique whose light met receivers: its floor map and the deposit
    /// it was looked up from ([`crate::receivers::received_with_light`]).
    pub fn received(
        (map, light): (CausticsMap, Option<LightSpace>),
        walls: Option<WallMaps>,
    ) -> Self {
        JobOutput {
            light,
            ..Self::floor(map, walls)
        }
    }

    /// What lights the final image: the floor map with its deposit where there is one.
    pub fn lighting(&self) -> Caustics<'_> {
        self.caustics.with_light(self.light.as_ref())
    }
}

/// The height field a grid-based technique reads: a file's own samples, or the surface sampled on
/// the map's lattice.
pub fn heights_for(water: &Water, surface: &dyn Surface, width: usize, height: usize) -> Grid {
    match &water.source {
        WaterSource::HeightField(g) => g.clone(),
        _ => sample_grid(surface, width, height, water.size),
    }
}

/// The heights a bicubic reader sees the water through: a water that is itself a grid read
/// bicubically (the FFT ocean, the ripples) sampled at its own lattice, so that the technique's
/// surface is the water's own; others as [`heights_for`]. Sampled at the map's resolution instead,
/// the 128² ocean is re-interpolated, and its sharpest caustics move (9 % rel. L1 at 60°, deep,
/// 256²; docs/yuksel.md).
pub fn lattice_heights(water: &Water, surface: &dyn Surface, width: usize, height: usize) -> Grid {
    let n = match &water.source {
        WaterSource::Ocean(o) => o.params().resolution,
        WaterSource::Ripple(p) => p.resolution,
        _ => return heights_for(water, surface, width, height),
    };
    sample_grid(surface, n, n, water.size)
}
