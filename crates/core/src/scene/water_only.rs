//! The common case of a wgpu application that owns its water: a square of water over a flat floor
//! under the sun, described by what the techniques read (its size, depth, index, absorption and
//! edges, the sun, the map's size) and nothing else. The heights are the application's own
//! texture; the scene's water is flat so that nothing here simulates it.

use super::{CausticsSpec, FloorSpec, LightSpec, SceneFile, WaterSpec};

/// Water alone over a flat floor, as a builder: [`WaterOnly::new`] with the square's side and the
/// depth of its rest level above the floor, then whatever differs from the defaults (index 1.333,
/// clear water, edges that wrap, a sun from `[0.3, 0.2, -1]`, a 512² map). `scene()` (in
/// `techniques::registry`, beside the other loaders) checks it as a scene file is checked.
#[derive(Clone, Debug, PartialEq)]
pub struct WaterOnly {
    /// The side of the square `[0, size]²` the water, the floor and the map cover, world units.
    pub size: f64,
    /// The rest level's height above the floor.
    pub depth: f64,
    /// The water's index of refraction.
    pub ior: f64,
    /// Beer-Lambert absorption `K` per RGB channel, per world unit of path.
    pub absorption: [f64; 3],
    /// Whether the heights tile (light leaving one edge enters at the other) or clamp at the edges.
    pub wrap: bool,
    /// The direction sunlight travels (pointing down; need not be normalised).
    pub sun: [f64; 3],
    /// The caustics map's texels along each side.
    pub map: u32,
}

impl WaterOnly {
    /// Water `depth` deep over a square of side `size` (both world units), the rest at their
    /// defaults.
    pub fn new(size: f64, depth: f64) -> WaterOnly {
        WaterOnly {
            size,
            depth,
            ior: super::water_ior(),
            absorption: [0.0; 3],
            wrap: true,
            sun: [0.3, 0.2, -1.0],
            map: 512,
        }
    }

    /// With the water's index of refraction `ior` (at least 1).
    pub fn ior(self, ior: f64) -> WaterOnly {
        WaterOnly { ior, ..self }
    }

    /// With Beer-Lambert absorption `K` per RGB channel, per world unit of path.
    pub fn absorption(self, absorption: [f64; 3]) -> WaterOnly {
        WaterOnly { absorption, ..self }
    }

    /// Heights that clamp at the square's edges instead of tiling.
    pub fn clamped(self) -> WaterOnly {
        WaterOnly {
            wrap: false,
            ..self
        }
    }

    /// With the direction sunlight travels, `sun` (pointing down, z < 0; need not be normalised).
    pub fn sun(self, sun: [f64; 3]) -> WaterOnly {
        WaterOnly { sun, ..self }
    }

    /// With a caustics map of `map` × `map` texels.
    pub fn map(self, map: u32) -> WaterOnly {
        WaterOnly { map, ..self }
    }

    /// The scene file this describes.
    pub fn file(&self) -> SceneFile {
        SceneFile {
            water: Some(WaterSpec {
                heightfield: None,
                heightfield_range: None,
                waves: None,
                procedural: None,
                ocean: None,
                ripple: None,
                size: self.size,
                depth: self.depth,
                ior: self.ior,
                wrap: self.wrap,
                absorption: self.absorption,
            }),
            light: LightSpec {
                direction: Some(self.sun),
                position: None,
                cone: None,
                color: super::white(),
                intensity: 1.0,
            },
            caustics: CausticsSpec {
                resolution: [self.map, self.map],
                ..CausticsSpec::default()
            },
            floor: FloorSpec::default(),
            objects: Vec::new(),
            camera: None,
            time: 0.0,
        }
    }
}
