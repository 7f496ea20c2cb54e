//! The scene model shared by every technique: water over a floor (flat or terrain), objects, a sun,
//! a camera, and the chosen caustics technique. A scene is read from TOML ([`SceneFile`], the serde
//! schema, unknown keys rejected) and then checked into a [`Scene`], whose fields are all valid: every
//! problem is reported with the dotted name of the field at fault.
//!
//! The built-in scenes live as TOML beside this file (`scenes/*.toml`) so they double as examples.

mod builtin;
pub mod exact;
mod validate;
mod water_only;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::{Edge, Grid};
use crate::mesh::TriangleMesh;
use crate::water::ocean::{Ocean, OceanParams};
use crate::water::procedural::{Procedural, ProceduralParams};
use crate::water::ripple::{self, RippleParams, Ripples};
use crate::water::waves::{Wave, Waves};
use crate::water::{Flat, GridSurface, Surface};

pub use crate::grid::MAX_RESOLUTION;
pub use builtin::BUILTIN_SCENES;
pub use water_only::WaterOnly;

/// The check of a scene file's `technique` and `[caustics.<name>]` tables, run while the file is
/// read (after its light, water and map size, before its floor). The scene model knows no
/// technique, so its readers (`Scene::*_with`) are given the check; the loaders every front end
/// calls, [`Scene::load`], [`Scene::builtin`], [`Scene::load_or_builtin`] and [`Scene::from_toml`],
/// are the registry's ([`crate::techniques::registry`]) and pass its check.
pub type TechniqueCheck = fn(&CausticsSpec) -> Result<()>;

// ---------------------------------------------------------------------------------------------
// The file schema.

/// A scene file as written: the serde schema of its TOML, unknown keys rejected, not yet checked
/// ([`Scene::from_file_with`] checks it into a [`Scene`]).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// The `[water]` table; absent, a scene without water (the floor under the light, on a unit
    /// square).
    pub water: Option<WaterSpec>,
    /// The `[light]` table: the sun, or a point or spot light.
    pub light: LightSpec,
    /// The `[caustics]` table: the map's size, the technique and its parameter tables.
    #[serde(default)]
    pub caustics: CausticsSpec,
    /// The `[floor]` table: flat at z = 0 or a terrain, its albedo, walls and deck.
    #[serde(default)]
    pub floor: FloorSpec,
    /// The `[[objects]]` in the scene, in file order (`objects[k]` in error messages).
    #[serde(default)]
    pub objects: Vec<ObjectSpec>,
    /// The `[camera]` table; absent, a view of the whole square from above one corner.
    #[serde(default)]
    pub camera: Option<CameraSpec>,
    /// Simulation time at which the water is frozen, seconds.
    #[serde(default)]
    pub time: f64,
}

/// The `[water]` table: the square `[0, size]²` of water whose rest level lies `depth` above the
/// floor plane z = 0, its surface from at most one source (`heightfield`, `waves`, `procedural`,
/// `ocean` or `ripple`; none is still water).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaterSpec {
    /// A height field file: `.npy` float32 (rows, cols), `.exr`, or 16-bit `.png`.
    pub heightfield: Option<PathBuf>,
    /// For 16-bit PNG height fields: the displacements that 0 and 65535 stand for.
    #[serde(default, deserialize_with = "crate::scene::exact::option")]
    pub heightfield_range: Option<[f32; 2]>,
    /// A sum of directional sine waves (`[[water.waves]]`), snapped so that it tiles the square.
    pub waves: Option<Vec<Wave>>,
    /// The procedural wave function of paper 2 (Sánchez-Crespo, "The wave function"), by default
    /// with the paper's constants.
    pub procedural: Option<ProceduralParams>,
    /// A Tessendorf FFT ocean tiling the square.
    pub ocean: Option<OceanParams>,
    /// The interactive ripple simulation (the damped wave equation on a grid), from its initial
    /// drops.
    pub ripple: Option<RippleParams>,
    /// Side of the square `[0, size]²` the water, the floor and the caustics map cover, world
    /// units (default 1).
    #[serde(default = "one")]
    pub size: f64,
    /// Height of the rest level above the floor plane z = 0, world units: a flat pool's depth.
    pub depth: f64,
    /// The water's index of refraction, at least 1 (default 1.333).
    #[serde(default = "water_ior")]
    pub ior: f64,
    /// Whether the surface tiles across the square's edges (the default) or clamps at them; also
    /// the ripple simulation's boundary.
    #[serde(default = "yes")]
    pub wrap: bool,
    /// Absorption coefficient `K` per RGB channel, per world unit of path (Beer-Lambert `exp(-K d)`).
    #[serde(default, deserialize_with = "crate::scene::exact::array")]
    pub absorption: [f64; 3],
}

/// The `[light]` table: the sun (a `direction` alone) or a point light (a `position`; a spot light
/// with a `cone`).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightSpec {
    /// The direction the sunlight travels; need not be normalised; must point down (z < 0).
    /// Required for the sun; with `position`, the axis of a spot light's cone (default straight
    /// down).
    #[serde(default, deserialize_with = "crate::scene::exact::option")]
    pub direction: Option<[f64; 3]>,
    /// A point light at this position instead of the sun (above the floor, z > 0). Only technique
    /// `caustic-triangles` renders it (paper 4, §4: the light cube map); the others refuse it.
    #[serde(default, deserialize_with = "crate::scene::exact::option")]
    pub position: Option<[f64; 3]>,
    /// With `position`: a spot light, lighting the cone of this half-angle (degrees, in (0, 90])
    /// around `direction`.
    #[serde(default)]
    pub cone: Option<f64>,
    /// The light's linear-RGB colour, a factor on its intensity (default white).
    #[serde(default = "white", deserialize_with = "crate::scene::exact::array")]
    pub color: [f64; 3],
    /// The irradiance the sun puts on a surface facing it, or a point light on the floor straight
    /// below it, in the renderer's relative units (default 1; not negative).
    #[serde(default = "one")]
    pub intensity: f64,
}

/// The `[caustics]` table: the caustics map's size, the technique that computes it and, beside
/// them, the techniques' own parameter tables.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CausticsSpec {
    /// Texels of the caustics map along x and y over the water's square (default 256 × 256, at
    /// most [`MAX_RESOLUTION`]).
    #[serde(
        default = "default_resolution",
        deserialize_with = "crate::scene::exact::array"
    )]
    pub resolution: [u32; 2],
    /// The technique that computes the caustics map, by its registry name (`yuksel`,
    /// `procedural`, `volumes`, `caustic-triangles`, `cascaded`, ...; default `reference`, the
    /// physically based reference).
    #[serde(default = "default_technique")]
    pub technique: String,
    /// Per-technique parameter tables, `[caustics.<technique>]`, read by each technique.
    #[serde(flatten)]
    pub params: toml::Table,
}

impl Default for CausticsSpec {
    fn default() -> Self {
        CausticsSpec {
            resolution: default_resolution(),
            technique: default_technique(),
            params: toml::Table::new(),
        }
    }
}

/// The `[floor]` table: the plane z = 0 unless it has a terrain, its albedo, walls and deck.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorSpec {
    /// A terrain instead of the flat floor (open water: no walls, no deck).
    pub terrain: Option<TerrainSpec>,
    /// An albedo image (sRGB PNG) stretched over the floor square.
    pub albedo: Option<PathBuf>,
    /// The built-in albedo pattern, used when no `albedo` image is given (default tiles).
    #[serde(default)]
    pub pattern: FloorPattern,
    /// The four walls of the water's square receive light too, from the floor up to the rest water
    /// level: light that meets a wall stops there instead of wrapping round to the
    /// floor. Only for a flat pool floor (no terrain); off unless asked, so that a scene's floor
    /// map keeps holding all the light.
    #[serde(default)]
    pub walls: bool,
    /// What the deck around a pool is paved with (a pool only: a terrain is open water).
    #[serde(default)]
    pub deck: Deck,
}

/// The deck a pool is sunk into, seen around it and through Snell's window from below; a pale
/// coping stone edges the water on either.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Deck {
    /// Sandstone pavers, 60 cm square in a running bond, each its own shade, with grout joints.
    #[default]
    Stone = 0,
    /// Poured concrete: one pale grey.
    Concrete = 1,
}

/// Sides of the deck's pavers, world units.
pub const PAVER: f64 = 0.6;
/// Width of the grout joint between pavers and of the coping's joint at the water, world units.
pub const JOINT: f64 = 0.01;
/// Width of the coping stone around the water, world units (at most a tenth of the pool's side).
pub const COPING: f64 = 0.3;

/// An integer hash to [0, 1) (the "lowbias32" mix of C. Wellons' hash prospector); the GPU twin is
/// `hash01` in shading.wgsl, on the same u32 arithmetic.
pub fn hash01(x: i32, y: i32) -> f64 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343) ^ (y as u32).wrapping_mul(0xd816_3841);
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    h as f64 / 4_294_967_296.0
}

/// The fraction of `[x − w/2, x + w/2]` (in periods) that joints of width `joint` at the start of
/// each period cover: the box filter of the joints' pulse train, through its integral; the point
/// test itself for `w = 0`.
fn joint_cover(x: f64, w: f64, joint: f64) -> f64 {
    let integral = |x: f64| {
        let n = x.floor();
        n * joint + (x - n).min(joint)
    };
    if w <= 1e-4 {
        return if x - x.floor() < joint { 1.0 } else { 0.0 };
    }
    ((integral(x + 0.5 * w) - integral(x - 0.5 * w)) / w).clamp(0.0, 1.0)
}

impl Deck {
    /// Linear-RGB albedo of the deck at `p` around a pool of side `size` (the water's square
    /// `[0, size]²`): the coping within [`COPING`] of the water (a tenth of the pool's side at
    /// most), the paving beyond, its joints box-filtered over a sample's `footprint` (world
    /// units, 0 for a point) so that far away they fade into the paving's mean instead of
    /// breaking into dots. GPU twin: `deck_albedo` in shading.wgsl.
    pub fn albedo(self, p: DVec2, size: f64, footprint: f64) -> DVec3 {
        let out = (-p.x).max(p.x - size).max(-p.y).max(p.y - size);
        let coping = COPING.min(0.1 * size);
        if out <= coping {
            return if out < JOINT.min(0.1 * coping) {
                DVec3::new(0.30, 0.29, 0.27)
            } else {
                DVec3::new(0.78, 0.76, 0.71)
            };
        }
        match self {
            Deck::Concrete => DVec3::new(0.55, 0.55, 0.53),
            Deck::Stone => {
                let row = (p.y / PAVER).floor();
                let x = p.x / PAVER + 0.5 * row.rem_euclid(2.0);
                let col = x.floor();
                let (w, joint) = (footprint / PAVER, JOINT / PAVER);
                let (jx, jy) = (joint_cover(x, w, joint), joint_cover(p.y / PAVER, w, joint));
                let grout = 1.0 - (1.0 - jx) * (1.0 - jy);
                let shade = 0.85 + 0.3 * hash01(col as i32, row as i32);
                DVec3::new(0.60, 0.53, 0.43) * (shade * (1.0 - grout))
                    + DVec3::new(0.32, 0.31, 0.29) * grout
            }
        }
    }

    /// The code the GPU's final image reads (`DECK_*` in shading.wgsl).
    pub fn code(self) -> u32 {
        self as u32
    }
}

/// The floor's built-in albedo patterns (`[floor] pattern`), laid over the water's square. GPU
/// twin: `floor_albedo` in shading.wgsl.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FloorPattern {
    /// Pale pool tiles with dark grout.
    #[default]
    Tiles,
    /// Sand.
    Sand,
    /// Uniform light grey.
    Plain,
}

/// `[floor.terrain]`: a floor that is not flat, from exactly one of a height field file or a
/// generated beach.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TerrainSpec {
    /// A terrain height field file (same formats and centring as the water's); heights above z = 0.
    pub heightfield: Option<PathBuf>,
    /// For a 16-bit PNG height field: the heights that 0 and 65535 stand for, world units
    /// (default `[0, 1]`).
    #[serde(default, deserialize_with = "crate::scene::exact::option")]
    pub heightfield_range: Option<[f32; 2]>,
    /// A generated beach: the floor rises from `deep` at x = 0 to `shallow` at x = size.
    pub beach: Option<BeachSpec>,
}

/// A generated beach terrain: a smooth ramp across x from `deep` to `shallow` (heights above
/// z = 0, world units), with sand dunes and rocks.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeachSpec {
    /// Floor height at x = 0 (the sea side).
    pub deep: f64,
    /// Floor height at x = size (the shore side).
    pub shallow: f64,
    /// Amplitude of the sand ripples on the slope.
    #[serde(default)]
    pub dunes: f64,
    /// Samples of the generated height grid along each side (2 to [`MAX_RESOLUTION`], default 256).
    #[serde(default = "default_terrain_resolution")]
    pub resolution: usize,
    /// Rocks standing on the slope.
    #[serde(default)]
    pub rocks: Vec<RockSpec>,
}

/// A rounded rock on a generated beach: `height · (1 − (d / radius)²)²` above the slope at
/// distance `d` from its centre, level with the slope at its rim.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RockSpec {
    /// Its centre on the floor, world units.
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub position: [f64; 2],
    /// Radius of its footprint, world units (positive).
    pub radius: f64,
    /// Its height above the slope at its centre, world units (not negative).
    pub height: f64,
}

/// An `[[objects]]` entry: a shape of one material, scaled, turned about the vertical axis and
/// moved by `position`.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    /// What it is: a built-in shape or a mesh file, at its native size.
    pub shape: ShapeSpec,
    /// Centre of the object's base (it rests at this point), world units.
    #[serde(default, deserialize_with = "crate::scene::exact::array")]
    pub position: [f64; 3],
    /// Uniform scale applied to the shape's native size.
    #[serde(default = "one")]
    pub scale: f64,
    /// Rotation about the vertical axis, degrees.
    #[serde(default)]
    pub rotation: f64,
    /// What its surface does to light (default diffuse, albedo 0.8 grey).
    #[serde(default)]
    pub material: MaterialSpec,
}

/// An object's shape, by its table's `kind`: `teapot`, `sphere`, `cuboid` or `mesh`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum ShapeSpec {
    /// The Utah teapot, 1 unit high before scaling.
    Teapot,
    /// A sphere of radius 1 before scaling.
    Sphere,
    /// A box with the given half extents before scaling.
    Cuboid {
        /// Half its sides along x, y and z before scaling, world units (positive).
        #[serde(deserialize_with = "crate::scene::exact::array")]
        half_extents: [f64; 3],
    },
    /// A triangle mesh from an OBJ file.
    Mesh {
        /// The OBJ file, relative to the scene file.
        path: PathBuf,
    },
}

/// An object's material, by its table's `kind`: `diffuse` or `glass`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum MaterialSpec {
    /// A matte (Lambertian) surface.
    Diffuse {
        /// Its linear-RGB albedo.
        #[serde(deserialize_with = "crate::scene::exact::array")]
        color: [f64; 3],
    },
    /// A clear dielectric that reflects and refracts by Fresnel's equations.
    Glass {
        /// Its index of refraction, at least 1.
        ior: f64,
        /// Linear-RGB factor on the light it refracts, at each crossing of its surface (default
        /// white: clear glass).
        #[serde(default, deserialize_with = "crate::scene::exact::option")]
        tint: Option<[f64; 3]>,
    },
}

impl Default for MaterialSpec {
    fn default() -> Self {
        MaterialSpec::Diffuse {
            color: [0.8, 0.8, 0.8],
        }
    }
}

/// The `[camera]` table: the final image's viewpoint, field of view, size and look.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    /// The eye, world coordinates (z up); not under a pool's floor.
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub position: [f64; 3],
    /// The point at the image's centre, world coordinates.
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub target: [f64; 3],
    /// Vertical field of view, degrees, in (1, 170) (default 50).
    #[serde(default = "default_fov")]
    pub fov_y: f64,
    /// The final image's width and height, pixels (default 960 × 540).
    #[serde(
        default = "default_image",
        deserialize_with = "crate::scene::exact::array"
    )]
    pub resolution: [u32; 2],
    /// The final image's exposure: radiance is multiplied by it before the tone curve.
    #[serde(default = "one")]
    pub exposure: f64,
    /// The final image's tone curve: "aces" (the default), "agx" or "none".
    #[serde(default)]
    pub tone_map: crate::tone_map::ToneMap,
}

fn one() -> f64 {
    1.0
}
fn yes() -> bool {
    true
}
fn water_ior() -> f64 {
    1.333
}
fn white() -> [f64; 3] {
    [1.0, 1.0, 1.0]
}
fn default_resolution() -> [u32; 2] {
    [256, 256]
}
fn default_technique() -> String {
    "reference".into()
}
fn default_terrain_resolution() -> usize {
    256
}
fn default_fov() -> f64 {
    50.0
}
fn default_image() -> [u32; 2] {
    [960, 540]
}

// ---------------------------------------------------------------------------------------------
// The validated scene.

/// A scene whose every field has been checked: positive sizes, a downward sun, finite height fields.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The scene's name: its file's stem or its built-in name, shown in titles and messages.
    pub name: String,
    /// The water; `None` for a scene without it (the floor under the light, on a unit square).
    pub water: Option<Water>,
    /// The light: the sun, or a point or spot light.
    pub light: Light,
    /// The caustics map's size and technique, with the technique's parameter tables.
    pub caustics: CausticsSettings,
    /// The floor: the plane z = 0 or a terrain, its albedo, walls and deck.
    pub floor: Floor,
    /// The objects in and around the water, their meshes in world coordinates.
    pub objects: Vec<Object>,
    /// The final image's camera: the file's, or a view of the whole square from above one corner.
    pub camera: Camera,
    /// How the final image shows the camera's radiance.
    pub look: Look,
    /// Simulation time at which the water is frozen, seconds.
    pub time: f64,
    /// The square `[0, size]²` the water, the floor and the caustics map cover (1 without water).
    pub size: f64,
}

/// The scene's water, checked: the square `[0, size]²` of water whose rest level lies `depth` above
/// z = 0, its surface shaped by `source`.
#[derive(Clone, Debug)]
pub struct Water {
    /// What shapes the surface about its rest level.
    pub source: WaterSource,
    /// Side of the square, world units (the scene's [`Scene::size`]).
    pub size: f64,
    /// Height of the rest level above z = 0, world units: a flat pool's depth.
    pub depth: f64,
    /// The water's index of refraction, at least 1.
    pub ior: f64,
    /// Whether the surface tiles across the square's edges or clamps at them ([`Water::edge`]).
    pub wrap: bool,
    /// Beer-Lambert absorption `K` per RGB channel, per world unit of path (`exp(-K d)`).
    pub absorption: DVec3,
}

/// Where the water's heights, its displacements from the rest level, come from.
#[derive(Clone, Debug)]
pub enum WaterSource {
    /// Still water at the rest level (the file names no source).
    Flat,
    /// A sum of directional sine waves.
    Waves(Vec<Wave>),
    /// The procedural wave function of paper 2 (Sánchez-Crespo).
    Procedural(ProceduralParams),
    /// A Tessendorf FFT ocean, its spectrum drawn once.
    Ocean(Box<Ocean>),
    /// The ripple simulation's parameters; [`Water::surface_at`] runs it to the time asked.
    Ripple(RippleParams),
    /// A height field file's samples: displacements in world units, stretched over the square.
    HeightField(Grid),
}

impl Water {
    /// How the surface is read outside its square: [`Edge::Wrap`] if it tiles, else
    /// [`Edge::Clamp`].
    pub fn edge(&self) -> Edge {
        if self.wrap { Edge::Wrap } else { Edge::Clamp }
    }

    /// The surface at time `t` (seconds). The ripple simulation runs its initial drops, its settling
    /// steps and then `t` worth of further steps.
    pub fn surface_at(&self, t: f64) -> Result<Box<dyn Surface>> {
        Ok(match &self.source {
            WaterSource::Flat => Box::new(Flat),
            WaterSource::Waves(w) => Box::new(Waves::new(w, self.size, t)),
            WaterSource::Procedural(p) => Box::new(Procedural {
                params: p.clone(),
                t,
            }),
            WaterSource::Ocean(o) => Box::new(o.surface(t)),
            WaterSource::Ripple(p) => {
                let mut r = Ripples::new(p, self.size, self.edge())?;
                r.run_initial();
                let extra = (t / p.time_step).round().max(0.0) as u64;
                for _ in 0..extra {
                    r.step();
                }
                Box::new(r.surface())
            }
            WaterSource::HeightField(g) => Box::new(GridSurface {
                grid: g.clone(),
                size: self.size,
                edge: self.edge(),
            }),
        })
    }

    /// The water's rest level above z = 0.
    pub fn level(&self) -> f64 {
        self.depth
    }
}

// The ripple simulation of a scene's water: here, where the water is known, so that
// `crate::water::ripple` stays below the scene model.

impl ripple::Drop {
    /// The drop a click makes on `water` at `position`: a dent a sixteenth of the square across
    /// and curved enough to focus the light within a pool's depth, so a click shows bright rings
    /// at once.
    pub fn click(water: &Water, position: [f64; 2]) -> ripple::Drop {
        ripple::Drop {
            position,
            radius: water.size / 16.0,
            strength: -water.size / 60.0,
        }
    }
}

impl RippleParams {
    /// The simulation an interactive view runs on a scene's water: its own parameters if its water
    /// is a ripple simulation, else the defaults (made for a unit square) with the initial drops
    /// stretched to the scene's square. The wave speed stays the default's half a unit per second
    /// (real ripples of a few centimetres run at a few decimetres per second) so that a click's
    /// rings stay in view for seconds on a pool; it shrinks only on squares smaller than one unit,
    /// where the Courant condition needs it.
    pub fn for_water(water: &Water) -> Self {
        if let WaterSource::Ripple(p) = &water.source {
            return p.clone();
        }
        let s = water.size;
        let mut p = RippleParams {
            wave_speed: RippleParams::default().wave_speed * s.min(1.0),
            ..RippleParams::default()
        };
        for d in &mut p.drops {
            d.position = [d.position[0] * s, d.position[1] * s];
            d.radius *= s;
            d.strength *= s;
        }
        p
    }
}

/// The scene's light, checked: the sun, or a point light (a spot light with `cone`).
#[derive(Clone, Debug)]
pub struct Light {
    /// Unit direction of travel, z < 0 (the sun's; a spot light's axis; straight down for a bare
    /// point light).
    pub direction: DVec3,
    /// Linear-RGB colour, a factor on `intensity`.
    pub color: DVec3,
    /// The irradiance the sun puts on a surface facing it, or a point light on the floor straight
    /// below it, in the renderer's relative units.
    pub intensity: f64,
    /// A point light here instead of the sun (z > 0).
    pub position: Option<DVec3>,
    /// A spot light's half-angle around `direction`, radians (with `position` only).
    pub cone: Option<f64>,
}

impl Light {
    /// Whether this is the directional sun (no `position`), the light every technique but
    /// caustic-triangles needs.
    pub fn is_sun(&self) -> bool {
        self.position.is_none()
    }
}

/// The caustics map to compute: its size over the water's square, and the technique, by name, with
/// its parameter tables.
#[derive(Clone, Debug)]
pub struct CausticsSettings {
    /// Texels of the caustics map along x.
    pub width: u32,
    /// Texels of the caustics map along y.
    pub height: u32,
    /// The technique's registry name (`reference` unless the file names one).
    pub technique: String,
    /// The `[caustics]` table's other entries, the `[caustics.<technique>]` tables each
    /// technique reads its parameters from.
    pub params: toml::Table,
}

/// The scene's floor, checked: the plane z = 0 or a terrain, its albedo, walls and deck, and the
/// opaque objects that stand on it.
#[derive(Clone, Debug)]
pub struct Floor {
    /// Terrain heights above z = 0 on the scene square (clamped at its edges); `None` is the plane z = 0.
    pub terrain: Option<Grid>,
    /// The scene's diffuse objects as receivers of the light under the water ([`Solids::of`]):
    /// what the light meets besides the floor, and what shades the floor.
    pub solids: Option<Arc<Solids>>,
    /// Its albedo: a built-in pattern or an image over the square.
    pub albedo: Albedo,
    /// The pool's walls are receivers ([`FloorSpec::walls`]); see [`crate::walls`].
    pub walls: bool,
    /// What the deck around a pool is paved with.
    pub deck: Deck,
}

/// Opaque objects as receivers: each diffuse object's triangles and their tree, so the receivers'
/// height map ([`crate::receivers::ReceiverHeights`]) can take the first surface the light meets
/// whether it is the floor or an object (docs/receivers.md).
#[derive(Debug)]
pub struct Solids {
    meshes: Vec<(TriangleMesh, crate::mesh::MeshBvh)>,
}

impl Solids {
    /// The diffuse objects of `objects` (glass lets light through: it is no receiver), `None`
    /// where there are none.
    pub fn of(objects: &[Object]) -> Option<Arc<Solids>> {
        let meshes: Vec<_> = objects
            .iter()
            .filter(|o| matches!(o.material, Material::Diffuse { .. }))
            .map(|o| (o.mesh.clone(), o.mesh.bvh()))
            .collect();
        (!meshes.is_empty()).then(|| Arc::new(Solids { meshes }))
    }

    /// Opaque receivers from meshes in scene coordinates (an engine's own: a sea bed, rocks, a
    /// hull), `None` where there are none.
    pub fn of_meshes(meshes: Vec<TriangleMesh>) -> Option<Arc<Solids>> {
        let meshes: Vec<_> = meshes
            .into_iter()
            .filter(|m| !m.indices.is_empty())
            .map(|m| {
                let bvh = m.bvh();
                (m, bvh)
            })
            .collect();
        (!meshes.is_empty()).then(|| Arc::new(Solids { meshes }))
    }

    /// Axis-aligned bounds `(min, max)` of every object.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.meshes.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), (m, _)| {
                let (a, b) = m.bounds();
                (lo.min(a), hi.max(b))
            },
        )
    }

    /// The nearest hit of the ray `origin + t·dir`, `0 < t < t_max`, with any of the objects.
    pub fn intersect(&self, origin: DVec3, dir: DVec3, t_max: f64) -> Option<f64> {
        let meshes = self.meshes.iter().map(|(mesh, bvh)| (mesh, bvh));
        crate::mesh::nearest(meshes, origin, dir, t_max).map(|(_, t, _)| t)
    }
}

impl Floor {
    /// Whether anything under the water besides the plane `z = 0` receives the light: a terrain or
    /// opaque objects. Then the techniques meet the receivers' map ([`crate::receivers`]).
    pub fn has_receivers(&self) -> bool {
        self.terrain.is_some() || self.solids.is_some()
    }

    /// Height of the floor and its gradient at `p`.
    pub fn height_gradient(&self, p: DVec2, size: f64) -> (f64, DVec2) {
        match &self.terrain {
            Some(g) => g.sample(p, size, Edge::Clamp),
            None => (0.0, DVec2::ZERO),
        }
    }
}

/// The floor's albedo over the square `[0, size]²`: a built-in pattern, or an image stretched over
/// the square (repeating beyond it).
#[derive(Clone, Debug)]
pub enum Albedo {
    /// A built-in pattern.
    Pattern(FloorPattern),
    /// Linear RGB texels, row 0 at y = 0.
    Image {
        /// Texels along x.
        width: usize,
        /// Texels along y.
        height: usize,
        /// Row-major, `width × height` of them, row 0 at y = 0.
        texels: Vec<[f32; 3]>,
    },
}

/// The sand's grain and its darker and lighter patches: cell sizes (world units) of their value
/// noise and their amplitudes, as a share of the sand's colour.
const SAND_GRAIN: f64 = 0.05;
const SAND_GRAIN_AMPLITUDE: f64 = 0.08;
const SAND_PATCH: f64 = 0.5;
const SAND_PATCH_AMPLITUDE: f64 = 0.06;

/// `sin(x) / x`, the mean of a sinusoid over a box, as a share of its amplitude.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-6 { 1.0 } else { x.sin() / x }
}

/// The widest box, in cells, over which [`value_noise`] sums its lattice exactly; a wider one is
/// summed over this width and its spread scaled down to the wider box's.
const NOISE_EXACT_BOX: f64 = 2.0;

/// Below this half-width (in cells) a box is read as a point: the box mean differs from the point
/// value by O(a²), and the antiderivatives' difference would cancel in f32 on the GPU.
const NOISE_POINT: f64 = 1e-3;

/// Integral of the smoothstep hat `φ(t) = 1 − S(|t|)` (`S(t) = 3t² − 2t³`, the weight of a lattice
/// value at `t` cells from it) from −1 to `t`: `1/2 + sign(t) (u − u³ + u⁴/2)`, `u = min(|t|, 1)`.
fn hat_integral(t: f64) -> f64 {
    let u = t.abs().min(1.0);
    0.5 + t.signum() * (u - u * u * u + 0.5 * u * u * u * u)
}

/// Weights of the lattice values `i0 .. i0 + 4` in the mean of the smoothstep interpolation over
/// `[x − a, x + a]` (cells): each value's hat integrated over the box, over its width; the
/// hat's own values for a point. At most four values reach a box of `NOISE_EXACT_BOX` cells.
fn hat_box_weights(x: f64, a: f64) -> (i32, [f64; 4]) {
    let i0 = (x - a).floor() as i32;
    let mut w = [0.0; 4];
    for (k, w) in w.iter_mut().enumerate() {
        let t = x - f64::from(i0 + k as i32);
        *w = if a < NOISE_POINT {
            1.0 - smoothstep01(t.abs().min(1.0))
        } else {
            (hat_integral(t + a) - hat_integral(t - a)) / (2.0 * a)
        };
    }
    (i0, w)
}

fn smoothstep01(t: f64) -> f64 {
    t * t * (3.0 - 2.0 * t)
}

/// Value noise in [-1, 1): smoothstep-interpolated [`hash01`] values on a lattice of cells `cell`
/// wide (octave `seed` offsets the lattice's hash), box-filtered over the footprint's extent `w`
/// along each axis. The mean over the box is exact, the interpolation being a sum of lattice
/// values times separable hats (`hat_box_weights`), up to a box `NOISE_EXACT_BOX` cells wide;
/// a wider one takes that box's mean with its spread scaled as a box over `n` independent cells
/// scales it, `(1 + (w/cell)²)^(-1/4)` per axis against the exact box's, so the mean (0) is kept
/// and nothing jumps at the cap. GPU twin: `value_noise` in shading.wgsl.
fn value_noise(p: DVec2, cell: f64, seed: i32, w: DVec2) -> f64 {
    let q = p / cell;
    let r = w / cell;
    let exact = r.min(DVec2::splat(NOISE_EXACT_BOX));
    let (i0, wx) = hat_box_weights(q.x, 0.5 * exact.x);
    let (j0, wy) = hat_box_weights(q.y, 0.5 * exact.y);
    let j0 = j0.wrapping_add(seed);
    let mut n = 0.0;
    for (b, wy) in wy.iter().enumerate() {
        if *wy == 0.0 {
            continue;
        }
        let row: f64 = wx
            .iter()
            .enumerate()
            .filter(|(_, wx)| **wx != 0.0)
            .map(|(a, wx)| {
                wx * (2.0 * hash01(i0.wrapping_add(a as i32), j0.wrapping_add(b as i32)) - 1.0)
            })
            .sum();
        n += wy * row;
    }
    let fade = |r: f64| (1.0 + r * r).powf(-0.25);
    n * (fade(r.x) / fade(exact.x)) * (fade(r.y) / fade(exact.y))
}

impl Albedo {
    /// Linear-RGB albedo at floor point `p` of a square of side `size`.
    pub fn at(&self, p: DVec2, size: f64) -> DVec3 {
        self.filtered(p, size, DVec2::ZERO)
    }

    /// [`at`](Self::at), the pattern box-filtered over a footprint `extent` wide along x and y
    /// (world units; zero for a point): the tiles' grout lines through the integral of their
    /// pulse train (as the deck's joints), the sand's ripples through the sinc of a sinusoid's
    /// mean over the box, its grain and patches through their exact box mean (`value_noise`),
    /// so that far away each keeps its mean instead of aliasing. An image is read at its nearest
    /// texel. GPU twin: `floor_albedo` in shading.wgsl.
    pub fn filtered(&self, p: DVec2, size: f64, extent: DVec2) -> DVec3 {
        let u = p / size;
        let w = extent / size;
        match self {
            Albedo::Pattern(FloorPattern::Tiles) => {
                // 8 tiles across the square, 4 % grout lines.
                let t = u * 8.0;
                let (jx, jy) = (
                    joint_cover(t.x, w.x * 8.0, 0.04),
                    joint_cover(t.y, w.y * 8.0, 0.04),
                );
                let grout = 1.0 - (1.0 - jx) * (1.0 - jy);
                DVec3::new(0.62, 0.78, 0.82) * (1.0 - grout) + DVec3::new(0.18, 0.2, 0.22) * grout
            }
            Albedo::Pattern(FloorPattern::Sand) => {
                let ripple = (u.x * 157.0).sin()
                    * sinc(78.5 * w.x)
                    * (u.y * 113.0).sin()
                    * sinc(56.5 * w.y)
                    * 0.03;
                let grain = SAND_GRAIN_AMPLITUDE * value_noise(p, SAND_GRAIN, 0, extent)
                    + SAND_PATCH_AMPLITUDE * value_noise(p, SAND_PATCH, 7919, extent);
                DVec3::new(0.76, 0.68, 0.5) * (1.0 + grain) + DVec3::splat(ripple)
            }
            Albedo::Pattern(FloorPattern::Plain) => DVec3::splat(0.7),
            Albedo::Image {
                width,
                height,
                texels,
            } => {
                let j = ((u.x.rem_euclid(1.0)) * *width as f64) as usize;
                let i = ((u.y.rem_euclid(1.0)) * *height as f64) as usize;
                let t = texels[i.min(height - 1) * width + j.min(width - 1)];
                DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64)
            }
        }
    }
}

/// An object of the scene, checked and placed.
#[derive(Clone, Debug)]
pub struct Object {
    /// Its triangles in world coordinates (scaled, turned and moved into place).
    pub mesh: TriangleMesh,
    /// What its surface does to light.
    pub material: Material,
}

/// An object's material, checked.
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// A matte (Lambertian) surface.
    Diffuse {
        /// Its linear-RGB albedo.
        color: DVec3,
    },
    /// A clear dielectric that reflects and refracts by Fresnel's equations.
    Glass {
        /// Its index of refraction, at least 1.
        ior: f64,
        /// Linear-RGB factor on the light it refracts, at each crossing of its surface (white
        /// for clear glass).
        tint: DVec3,
    },
}

/// The final image's camera: a pinhole at `position` looking at `target`, z up.
#[derive(Clone, Debug)]
pub struct Camera {
    /// The eye, world coordinates.
    pub position: DVec3,
    /// The point at the image's centre, world coordinates.
    pub target: DVec3,
    /// Vertical field of view, degrees.
    pub fov_y: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
}

/// How the final image turns radiance into display values (`[camera]` `exposure`, `tone_map`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// Factor on radiance before the tone curve (positive; default 1).
    pub exposure: f64,
    /// The tone curve from exposed radiance to display values (default ACES).
    pub tone_map: crate::tone_map::ToneMap,
}

impl Default for Look {
    fn default() -> Self {
        Look {
            exposure: 1.0,
            tone_map: crate::tone_map::ToneMap::default(),
        }
    }
}

impl Camera {
    /// The primary ray through pixel centre `(x + 0.5, y + 0.5)`, y down the image.
    pub fn ray(&self, x: f64, y: f64) -> (DVec3, DVec3) {
        let forward = (self.target - self.position).normalize();
        let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
        let up = right.cross(forward);
        let half = (self.fov_y.to_radians() * 0.5).tan();
        let aspect = self.width as f64 / self.height as f64;
        let sx = (2.0 * (x + 0.5) / self.width as f64 - 1.0) * half * aspect;
        let sy = (1.0 - 2.0 * (y + 0.5) / self.height as f64) * half;
        (self.position, (forward + right * sx + up * sy).normalize())
    }
}

impl Scene {
    /// Take every object out of the scene, and with them the floor's receivers
    /// ([`Floor::solids`], which mirror the diffuse objects).
    pub fn clear_objects(&mut self) {
        self.objects.clear();
        self.floor.solids = None;
    }

    /// Read and check a scene file, its technique by `check_technique`; relative paths inside it
    /// are relative to the file. [`Scene::load`] passes the registry's check.
    pub fn load_with(path: &Path, check_technique: TechniqueCheck) -> Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let base = path.parent().unwrap_or(Path::new("."));
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        Scene::from_toml_with(&text, base, &name, check_technique).map_err(|e| match e {
            Error::SceneSyntax { message, .. } => Error::SceneSyntax {
                path: path.to_path_buf(),
                message,
            },
            other => other,
        })
    }

    /// A built-in scene by name, its technique checked by `check_technique`.
    /// [`Scene::builtin`] passes the registry's check.
    pub fn builtin_with(name: &str, check_technique: TechniqueCheck) -> Result<Scene> {
        let (_, text) = BUILTIN_SCENES
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| Error::UnknownScene(name.to_string()))?;
        Scene::from_toml_with(text, Path::new("."), name, check_technique)
    }

    /// A scene from a file's text, its technique checked by `check_technique`.
    /// [`Scene::from_toml`] passes the registry's check.
    pub fn from_toml_with(
        text: &str,
        base: &Path,
        name: &str,
        check_technique: TechniqueCheck,
    ) -> Result<Scene> {
        let file: SceneFile = toml::from_str(text).map_err(|e| Error::SceneSyntax {
            path: PathBuf::from(format!("<{name}>")),
            message: e.to_string(),
        })?;
        Scene::from_file_with(file, base, name, check_technique)
    }

    /// A scene from its file's schema, checked as a file is, its technique by `check_technique`;
    /// relative paths inside it are relative to `base`.
    pub fn from_file_with(
        file: SceneFile,
        base: &Path,
        name: &str,
        check_technique: TechniqueCheck,
    ) -> Result<Scene> {
        validate::validate(file, base, name, check_technique)
    }
}

#[cfg(test)]
mod deck_tests {
    use super::*;

    /// The coping runs all round the water with its dark joint at the edge; beyond it the pavers
    /// are a stone's albedo, each its own shade (the hash spreads them over ±15 %, not all alike),
    /// with darker joints between them.
    #[test]
    fn the_deck_is_coping_then_pavers() {
        let size = 4.0;
        for p in [[-0.1, 2.0], [4.15, 1.0], [2.0, -0.2], [3.0, 4.29]] {
            let a = Deck::Stone.albedo(DVec2::from(p), size, 0.0);
            assert_eq!(a, DVec3::new(0.78, 0.76, 0.71), "{p:?}");
            assert_eq!(Deck::Concrete.albedo(DVec2::from(p), size, 0.0), a);
        }
        assert_eq!(
            Deck::Stone.albedo(DVec2::new(-0.005, 2.0), size, 0.0),
            DVec3::new(0.30, 0.29, 0.27)
        );
        let mut shades = Vec::new();
        for row in 0..20 {
            for col in 0..20 {
                // The middle of paver (col, row) of the running bond, away from the pool.
                let y = (10.0 + row as f64 + 0.5) * PAVER;
                let x = (10.0 + col as f64 + 0.5 - 0.5 * (row % 2) as f64) * PAVER;
                let a = Deck::Stone.albedo(DVec2::new(x, y), size, 0.0);
                shades.push(a.x / 0.60);
            }
        }
        let (lo, hi) = shades
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &s| (l.min(s), h.max(s)));
        let mean = shades.iter().sum::<f64>() / shades.len() as f64;
        assert!(lo >= 0.85 && hi < 1.15 && hi - lo > 0.25, "{lo} {hi}");
        // A uniform hash: the mean shade of 400 pavers is the middle, 1.0 (measured 1.0008).
        assert!((mean - 1.0).abs() < 0.008, "{mean}");
        let joint = Deck::Stone.albedo(DVec2::new(12.0 * PAVER + 0.003, 12.3 * PAVER), size, 0.0);
        assert_eq!(joint, DVec3::new(0.32, 0.31, 0.29));
    }

    /// Filtered by a footprint, the joints keep their share of the deck: over a footprint of a
    /// whole paver (along one axis) a point sees the joint for `JOINT / PAVER` of it, and the
    /// average over many footprints matches the average of points.
    #[test]
    fn filtered_joints_keep_their_share() {
        let joint = JOINT / PAVER;
        for x in [0.1, 3.37, 10.9] {
            let c = joint_cover(x, 1.0, joint);
            assert!((c - joint).abs() < 1e-12, "{c}");
        }
        let (n, w) = (10_000, 0.37);
        let point: f64 = (0..n)
            .map(|k| joint_cover(k as f64 * 0.001_37, 0.0, joint))
            .sum::<f64>()
            / n as f64;
        let filtered: f64 = (0..n)
            .map(|k| joint_cover(k as f64 * 0.001_37, w, joint))
            .sum::<f64>()
            / n as f64;
        // Both sample the joints' share 1/60 = 0.016667 (measured 0.017100 and 0.016453).
        assert!((point - joint).abs() < 2e-3 && (filtered - joint).abs() < 2e-3);
        assert_eq!(joint_cover(5.0 + 0.5 * joint, 0.0, joint), 1.0);
        assert_eq!(joint_cover(5.5, 0.0, joint), 0.0);
    }

    #[test]
    fn the_noise_is_its_mean_over_the_box() {
        // Boxes up to NOISE_EXACT_BOX cells wide, straddling lattice lines, against a 200 x 200
        // midpoint rule over the point noise. Measured: at most 2.0e-6 apart (the rule's error).
        let cell = 0.05;
        let mut worst: f64 = 0.0;
        for (p, w) in [
            (DVec2::new(0.013, 0.071), DVec2::new(0.02, 0.07)),
            (DVec2::new(1.2345, -0.4321), DVec2::new(0.1, 0.1)),
            (DVec2::new(-0.3, 0.25), DVec2::new(0.001, 0.06)),
            (DVec2::new(3.0, 2.0), DVec2::new(0.099, 0.033)),
        ] {
            let n = 200;
            let mut sum = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let f = DVec2::new((j as f64 + 0.5) / n as f64, (i as f64 + 0.5) / n as f64);
                    sum += value_noise(p - 0.5 * w + f * w, cell, 7, DVec2::ZERO);
                }
            }
            let rule = sum / (n * n) as f64;
            worst = worst.max((value_noise(p, cell, 7, w) - rule).abs());
        }
        assert!(worst < 2e-5, "{worst}");
        // Just past NOISE_POINT the box mean is the point's value (O(a²) apart: measured
        // 5.6e-8), and a box beyond the exact width keeps fading without a step at the cap.
        let p = DVec2::new(0.4321, 0.1234);
        let at = |w: f64| value_noise(p, cell, 0, DVec2::splat(w));
        assert!((at(0.0) - at(2.2e-3 * cell)).abs() < 5.6e-7);
        let cap = cell * NOISE_EXACT_BOX;
        assert!((at(cap) - at(cap * (1.0 + 1e-9))).abs() < 1e-9);
        assert!(at(40.0 * cell).abs() < at(cap).abs());
    }

    /// The floor's patterns filtered over a footprint keep the mean of their points: averaged
    /// over the square, the tiles' and the sand's albedo come out the same filtered (footprints of
    /// 0.3 and 3 world units) as point-sampled, and a footprint far wider than the tiles' period
    /// or the sand's cells gives each pattern's mean everywhere.
    #[test]
    fn filtered_albedo_keeps_the_patterns_mean() {
        let size = 4.0;
        let n = 400;
        let mean = |a: &Albedo, w: f64| {
            let mut sum = DVec3::ZERO;
            for i in 0..n {
                for j in 0..n {
                    // An irrational step, so that the points do not lock onto the patterns.
                    let p = DVec2::new(j as f64 * 0.010_37, i as f64 * 0.010_13);
                    sum += a.filtered(p, size, DVec2::splat(w));
                }
            }
            sum / (n * n) as f64
        };
        let tiles = Albedo::Pattern(FloorPattern::Tiles);
        let sand = Albedo::Pattern(FloorPattern::Sand);
        // Measured, the largest channel apart at footprints 0.3 and 3: tiles 0.0050 and 0.0057
        // (the points' own sampling of the grout), sand 6.2e-5 and 0.0020.
        for (a, bound) in [(&tiles, 0.05), (&sand, 0.02)] {
            let point = mean(a, 0.0);
            for w in [0.3, 3.0] {
                let filtered = mean(a, w);
                let apart = (filtered - point).abs().max_element();
                assert!(apart < bound, "{a:?} {w}: {filtered} {point}");
            }
        }
        // The grout's share of the tiles is 1 - 0.96² = 7.84 %; the sand's grain and ripples
        // average to nothing.
        let g = 1.0 - 0.96f64 * 0.96;
        let tile_mean = DVec3::new(0.62, 0.78, 0.82) * (1.0 - g) + DVec3::new(0.18, 0.2, 0.22) * g;
        let wide = DVec2::splat(200.0);
        for p in [DVec2::new(0.3, 1.7), DVec2::new(2.9, 0.05)] {
            // Measured: tiles exact, sand 8.8e-5 (its noise fades as the square root).
            assert!(
                (tiles.filtered(p, size, wide) - tile_mean)
                    .abs()
                    .max_element()
                    < 1e-12
            );
            let s = sand.filtered(p, size, wide);
            assert!(
                (s - DVec3::new(0.76, 0.68, 0.5)).abs().max_element() < 8e-4,
                "{s}"
            );
        }
    }
}
