//! Technique `caustic-triangles`: "Caustic Triangles on the GPU" (Umenhoffer, Patow &
//! Szirmay-Kalos), the CPU twin of `caustics-gpu`'s `caustic_triangles` module, pass for pass.
//!
//! # The method
//! - **Layered distance map** (§3, [`distance_map`]): a cube map around the caustic generator with
//!   distance, normal and material per texel in several layers; rays are traced in it by a linear
//!   search then a secant search (`linear_steps`, `secant_iterations`).
//! - **Photon tracing pass** (§4.1, [`photon_pass`]): a `P x P` photon image over the generator's
//!   light-space bounding rectangle. The light ray of each texel is traced through the distance map,
//!   refracted at every glass surface it meets (weight `T`, the Fresnel transmittance, "the complement
//!   of the Fresnel factor if refraction happens"; total internal reflection reflects with weight 1)
//!   up to `depth` events, until it leaves the object, then to the floor. The texel stores the
//!   *photon hit location*, power and path signature, `(x, y, Φ, σ)` with
//!   `σ = refractions + 64 · total internal reflections` ([`signature`]); texels whose ray misses the generator, is
//!   stopped by a diffuse surface of the distance map (an occluder: the paper's distance test,
//!   which keeps light from leaking through walls), leaves upwards or runs out of depth hold power
//!   `−1`, the paper's "negative power" marker of invalid texels.
//! - **Caustic reconstruction** (§4.2 with the §5 optimisation): a separate pass at the photon
//!   image's resolution ([`irradiance_pass`]) computes each vertex's irradiance `E = ΔΦ / ΔA` once;
//!   the caustic triangles ([`triangles_pass`]) are two triangles per photon-image quad whose four
//!   corners are valid, Gouraud shaded between their vertices' `E` and added into the floor map.
//!
//! # Path signatures (a departure: the paper connects every valid quad)
//! Neighbouring photons that took different paths through the generator (one through a teapot's
//! spout, its neighbour past it; one refracted out, its neighbour totally internally reflected) land
//! on unrelated, often far apart, floor points: a triangle between them is no wavefront patch, and
//! Gouraud shading smeared a bright vertex's `E` over a long sliver (a streak across the map). So a
//! quad is drawn only when its four corners are valid *and* have the same signature `σ`, and the
//! area sums of a vertex use only neighbours of its own signature ([`same_path`]); a quad whose
//! corners disagree is treated like one with an invalid corner.
//!
//! # Power and area
//! A photon-image texel spans `a⊥ = Δu Δv` across the light, so the sun puts `a⊥ E⊥` through it;
//! relative to the unobstructed sun on the floor (`E⊥ |L_z|`) the photon carries
//! `ΔΦ = a⊥ / |L_z| · Π T` "floor-area units", and a floor area `A` that receives it uniformly has
//! relative irradiance `ΔΦ / A` (1 where the sun falls unobstructed).
//!
//! The paper's `ΔA` is "half of the total areas of triangles attached to this vertex" (its Fig. 5 is
//! lost). Read with the four triangles a vertex spans with consecutive pairs of its 4-neighbours
//! (right-up, up-left, left-down, down-right), their union is the diamond around the vertex, whose
//! half is exactly one photon cell when the hits form a regular grid: each vertex then owns the
//! area one photon covers, which is what `E = ΔΦ / ΔA` needs. Where some neighbours are invalid we
//! take twice the mean of the triangles present (the same value on a regular grid). This is
//! [`AreaRule::Paper`].
//!
//! It is not exactly flux conserving once the hits are distorted: Gouraud shading integrates to
//! `Σ_v E_v ∫ φ_v`, and the hat function `φ_v` of vertex `v` integrates to a third of the area of the
//! drawn triangles around it. [`AreaRule::Hat`] takes that, `ΔA = ⅓ Σ_{drawn t ∋ v} A_t`, so the
//! drawn triangles carry every photon's power exactly (up to rasterisation at texel centres). A
//! water generator's photons on the lattice's edges carry the share of their power that belongs
//! to the square ([`CausticTrianglesSetup::lattice_share`]), so the drawn flux is the surface's.
//!
//! # Departures from the paper
//! - The receiver of the caustics is the floor plane `z = 0`: the photon stores its floor position,
//!   and a photon whose ray meets a diffuse surface of the distance map (a wall) ends there and is
//!   invalid (the paper's distance test, moved into the tracing: no light leaks through walls). For
//!   the sun the triangles are drawn into the floor's caustics map (the light cube map of a light at
//!   infinity degenerates); for a point light they are drawn onto the faces of the light cube map
//!   as the paper does ([`cube`]), which the camera pass ([`camera`]) reads with its distance test
//!   and as its shadow map.
//! - The first hit is found by the same distance-map search as the others, from where the light
//!   ray enters the map's sphere, instead of by rasterising the generator from the light: one
//!   compute pass traces the whole path.
//! - The floor plane is intersected analytically (it is the receiver, not stored in the map).
//! - The maps hold the light transmitted through the generator (the caustic); the direct light
//!   and the shadows are the camera pass's, as in the paper.
//!
//! # Lights
//! The sun's photons start on a grid over the generator's light-space rectangle. A point light's
//! (a [`PointLight`], a spot with a cone) start at the light, one per texel of a grid over the
//! tangent plane at distance 1 of the cone of directions to the generator's bounding sphere; the
//! texel at `q` spans the solid angle `a / (1 + q²)^{3/2}` and carries `I` times it (texels outside
//! a spot's cone carry nothing). Everything after the photon pass is the same for both.
//!
//! # Splatting baseline
//! [`splat_pass`]: each valid photon adds its power as a square splat of fixed side `splat_size`
//! texels, `ΔΦ / (s² A_texel)` over the texel centres it covers: the method the paper argues
//! against (Fig. 1), for comparison.
//!
//! # Files
//! One per pass, named as its WGSL file in `caustics-gpu`'s `caustic_triangles/`:
//!
//! | file | pass | GPU twin |
//! |---|---|---|
//! | [`photon`](mod@photon) | photon tracing (§4.1) | `photon.wgsl` + `distance_map.wgsl` |
//! | [`irradiance`] | vertex irradiance (§5) | `irradiance.wgsl` |
//! | [`triangles`] | caustic triangles (§4.2) | `triangles.wgsl` |
//! | [`pyramid`] | merge pyramid (§5, with `merge_levels`) | `pyramid.wgsl` |
//! | [`merge`] | the drawn quads of merged blocks | `merge.wgsl` |
//! | [`splat`] | splatting baseline | `splat.wgsl` |
//! | [`cube`] | light cube map faces and shadow distances (§4.2-4.3, point light) | `cube.wgsl`, `shadow.wgsl` |
//! | [`camera`] | camera pass (§4.3) | `camera.wgsl` |
//! | [`water`] | the water surface as the generator: water photons, copy band | `water_setup.wgsl`, `water_photon.wgsl`, `band_bound.wgsl`, `band.wgsl` |
//! | [`distance_map`] | the layered distance map (§3), built on the CPU | `distance_map.wgsl` (its search) |
//!
//! Besides them: [`scene`] (the generator, occluders, lights, the floor window),
//! [`reference`](mod@reference) (the path-traced check), `buffers.rs` (the intermediate buffers as
//! pictures), and this file: the descriptor, the parameters, the setup every pass shares, and the
//! whole technique ([`caustics`], [`render`]).

mod buffers;
pub mod camera;
pub mod cube;
pub mod distance_map;
pub mod irradiance;
pub mod merge;
pub mod photon;
pub mod pyramid;
pub mod reference;
pub mod scene;
pub mod splat;
pub mod triangles;
pub mod water;

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::map::CausticsMap;
pub use distance_map::{Crossing, DistanceMap};
pub use irradiance::{irradiance_pass, vertex_irradiance};
pub use photon::{INVALID, photon, photon_pass, photon_power, same_path, signature};
pub use scene::{
    FloorWindow, GlassScene, Occluder, PointLight, Shape, bounding_sphere, light_frame,
};
pub use splat::{splat_pass, splat_pass_with_paths};
pub use triangles::{triangles_pass, triangles_pass_with_paths};

use super::describe::{
    Descriptor, Kind, Param, ParamDefault as D, Receiver, check_params, read_params, serde_defaults,
};
use super::{Input, Job, JobOutput};

/// Paper 4 as registered: the water surface as its generator where the scene has water, else
/// the scene's glass objects.
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "caustic-triangles",
    table: "caustic-triangles",
    paper: "4",
    summary: "layered distance maps, photon hit image, caustic triangles into a light cube map (Umenhoffer et al.)",
    docs: "docs/caustic-triangles.md",
    input: Input::GlassOrWater,
    receivers: &[Receiver::Floor, Receiver::Walls],
    params: &[
        Param {
            sweep: &["32", "64", "128", "256", "512"],
            ..Param::new(
                "photon_image",
                "photon image",
                Kind::int(2, 4096),
                D::Int(128),
                "texels per side",
                "the photon hit location image, P (§4.1; the paper: 128)",
            )
        },
        Param::new(
            "cube_resolution",
            "cube map",
            Kind::int(2, 2048),
            D::Int(256),
            "texels per face side",
            "the generator's layered distance map (§3; the paper: 512)",
        ),
        Param::new(
            "light_cube",
            "light cube",
            Kind::int(2, 4096),
            D::Int(512),
            "texels per face side",
            "the light cube map a point light's caustic triangles are drawn into (§4)",
        ),
        Param::new(
            "layers",
            "layers",
            Kind::int(1, MAX_LAYERS as i64),
            D::Int(4),
            "",
            "layers of the distance map (§3)",
        ),
        Param::new(
            "linear_steps",
            "linear steps",
            Kind::int(1, 4096),
            D::Int(64),
            "",
            "linear search steps per ray segment in the distance map (§3)",
        ),
        Param::new(
            "secant_iterations",
            "secant steps",
            Kind::int(0, 64),
            D::Int(8),
            "",
            "secant search iterations after the linear search (§3)",
        ),
        Param::new(
            "depth",
            "depth",
            Kind::int(1, 32),
            D::Int(6),
            "",
            "most refractions / reflections along a photon path (§4.1)",
        ),
        Param::on(
            "fresnel",
            "Fresnel",
            "each photon carries its Fresnel transmittance",
        ),
        Param::new(
            "area_rule",
            "area rule",
            Kind::Choice(&["paper", "hat"]),
            D::Text("paper"),
            "",
            "paper: half the 4-neighbour triangles (§4.2); hat: a third of the drawn triangles, flux-true",
        ),
        Param::new(
            "splat_size",
            "splat size",
            Kind::float(0.0, 64.0),
            D::Float(2.0),
            "texels",
            "side of the baseline's square splats",
        ),
        Param::new(
            "merge_levels",
            "merge levels",
            Kind::int(0, MAX_MERGE_LEVELS as i64),
            D::Int(0),
            "",
            "levels of the §5 hierarchical merging of small caustic triangles (0: off)",
        ),
        Param::new(
            "merge_texels",
            "merge below",
            Kind::float(0.0, 1.0e6),
            D::Float(2.0),
            "texels",
            "a block of quads is merged when its quad covers less than this (§5)",
        ),
    ],
    fixed: &[],
    point_light: true,
    buffers: buffers::BUFFERS,
    draw_buffer: buffers::draw_buffer,
    reference: false,
    validate: |t| CausticTrianglesParams::from_table(t).map(|_| ()),
    own_defaults: serde_defaults::<CausticTrianglesParams>,
    cpu: run_cpu,
};

/// The number of glass objects of a scene without water (its caustic generators), or an error
/// naming the scene where it has none.
pub fn glass_generators(scene: &crate::scene::Scene) -> Result<usize> {
    let n = scene
        .objects
        .iter()
        .filter(|o| matches!(o.material, crate::scene::Material::Glass { .. }))
        .count();
    if n == 0 {
        return Err(Error::InvalidParameter(format!(
            "scene `{}` has neither water nor a glass object: no caustics to compute",
            scene.name
        )));
    }
    Ok(n)
}

/// The water photon pass's setup and heights a job gives paper 4 with the water surface as its
/// generator (both twins).
pub fn water_job_setup(
    job: &Job,
    table: &toml::Table,
) -> Result<(water::WaterSetup, crate::grid::Grid)> {
    water_setup(job, &CausticTrianglesParams::from_table(table)?)
}

/// [`water_job_setup`] with its parameters read.
pub fn water_setup(
    job: &Job,
    params: &CausticTrianglesParams,
) -> Result<(water::WaterSetup, crate::grid::Grid)> {
    if !job.scene.light.is_sun() {
        return Err(Error::InvalidParameter(format!(
            "scene `{}`: caustic-triangles lights its water surface with the directional sun only (light.position is set)",
            job.scene.name
        )));
    }
    let (width, height) = job.size();
    job.with_surface(DESCRIPTOR.name, |w, surface| {
        let ws = water::WaterSetup::new(params, w, job.light(), width, height)?
            .with_walls(job.floor().walls)
            .with_floor(job.floor(), None);
        Ok((ws, super::heights_for(w, surface, width, height)))
    })
}

fn run_cpu(
    job: &Job,
    table: &toml::Table,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<JobOutput> {
    if job.scene.water.is_none() {
        glass_generators(job.scene)?;
        let params = CausticTrianglesParams::from_table(table)?;
        return Ok(JobOutput::floor(render(job.scene, &params)?, None));
    }
    let (ws, heights) = water_job_setup(job, table)?;
    let out = water::maps(&ws, &heights)?;
    progress(1, 1);
    Ok(out)
}

/// How a vertex's area `ΔA` is taken from the triangles around it (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AreaRule {
    /// Half the area of the triangles spanned with the 4-neighbours (the paper, §4.2). The
    /// default: as local as the hat rule is flux-true, and better in L1 on smooth water
    /// (docs/caustic-triangles.md, "The two area rules").
    #[default]
    Paper = 0,
    /// A third of the area of the drawn triangles around the vertex: the drawn flux is the
    /// photons' (a water lattice's edge photons: [`CausticTrianglesSetup::lattice_share`]).
    Hat = 1,
}

impl AreaRule {
    /// The rule's code in the GPU's uniform block (`area_rule`): 0 paper, 1 hat.
    pub fn code(self) -> u32 {
        self as u32
    }
}

/// The technique's parameters, `[caustics.caustic-triangles]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CausticTrianglesParams {
    /// Side of the photon hit location image, `P` (the paper: 128).
    pub photon_image: u32,
    /// Texels per face side of the generator's distance map.
    pub cube_resolution: u32,
    /// Texels per face side of the light cube map a point light's caustic triangles are drawn
    /// into (the paper: 512).
    pub light_cube: u32,
    /// Layers of the distance map.
    pub layers: u32,
    /// Linear search steps per ray segment.
    pub linear_steps: u32,
    /// Secant search iterations per hit.
    pub secant_iterations: u32,
    /// Most refractions / total internal reflections along a photon path.
    pub depth: u32,
    /// Whether each photon carries the Fresnel transmittance of every refraction (§4.1: "the
    /// complement of the Fresnel factor"); off, refractions pass all the power. Default on.
    pub fresnel: bool,
    /// How a vertex's area `ΔA` is taken (§4.2): the paper's (default) or the flux-true hat rule.
    pub area_rule: AreaRule,
    /// Side of the baseline's square splats, in map texels.
    pub splat_size: f64,
    /// Levels of the §5 hierarchical merging of small caustic triangles (0: off).
    pub merge_levels: u32,
    /// A block of quads is merged when its quad covers less than this many floor-map texels.
    pub merge_texels: f64,
}

impl Default for CausticTrianglesParams {
    fn default() -> Self {
        CausticTrianglesParams {
            photon_image: 128,
            cube_resolution: 256,
            light_cube: 512,
            layers: 4,
            linear_steps: 64,
            secant_iterations: 8,
            depth: 6,
            fresnel: true,
            area_rule: AreaRule::Paper,
            splat_size: 2.0,
            merge_levels: 0,
            merge_texels: 2.0,
        }
    }
}

/// Most layers of a distance map: the search keeps one bracket per layer in a fixed array (as
/// `distance_map.wgsl` does).
pub const MAX_LAYERS: u32 = 8;
/// Most levels of the §5 merge pyramid: merged blocks of up to 64 x 64 photon-image quads.
pub const MAX_MERGE_LEVELS: u32 = 6;

impl CausticTrianglesParams {
    /// The parameters from the `caustic-triangles` entry of a scene's `[caustics]` table, defaults
    /// for what it leaves out (all of them without the entry), validated.
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        read_params(table, &DESCRIPTOR, Self::validate)
    }

    /// Check every parameter against the range the descriptor gives it (a splat has a size); the
    /// error names the field.
    pub fn validate(&self) -> Result<()> {
        check_params(&DESCRIPTOR, self)?;
        if self.splat_size <= 0.0 {
            return Err(Error::field(
                "caustics.caustic-triangles.splat_size",
                format!("must be in (0, 64] texels, got {}", self.splat_size),
            ));
        }
        Ok(())
    }
}

/// Everything the passes share (the GPU side uploads the same numbers as its uniform block).
#[derive(Clone, Debug)]
pub struct CausticTrianglesSetup {
    /// Photon image side in texels, `P` (`P + 1` for a water lattice of `P` quads).
    pub p: usize,
    /// Light-space axis across the light (`w × y`, or x where the light travels along y).
    pub u: DVec3,
    /// Light-space axis across the light, `w × u`.
    pub v: DVec3,
    /// Unit direction the sunlight travels; for a point light, from the light to the generator's
    /// bounding-sphere centre (the photon image's axis).
    pub w: DVec3,
    /// Light-space rectangle of the photon image: its lower corner and the size of one texel.
    pub rect_lo: DVec2,
    /// Side of one photon-image texel along `u` and `v`: world units for the sun, tangents of the
    /// angle off `w` for a point light.
    pub cell: DVec2,
    /// Power of one photon before the Fresnel factors, floor-area units.
    pub flux: f64,
    /// The generator's index of refraction (glass, or the water's), in air.
    pub ior: f64,
    /// Most refractions / total internal reflections along a photon path (1 for water).
    pub depth: u32,
    /// Whether photons carry the Fresnel transmittance of each refraction.
    pub fresnel: bool,
    /// Linear search steps per ray segment in the distance map (§3).
    pub linear_steps: u32,
    /// Secant search iterations after the linear search (§3).
    pub secant_iterations: u32,
    /// How a vertex's area `ΔA` is taken (§4.2).
    pub area_rule: AreaRule,
    /// Side of the splatting baseline's square splats, floor-map texels.
    pub splat_size: f64,
    /// Levels of the §5 merge pyramid (0: no merging).
    pub merge_levels: u32,
    /// A block of quads is merged when its corner quad covers less than this many floor-map
    /// texels (§5).
    pub merge_texels: f64,
    /// The floor square the caustic triangles are drawn into and its resolution (for a water
    /// wall, the wall's map stretched over the square).
    pub floor: FloorWindow,
    /// A point light: the photon image spans the tangent plane of the directions from the light
    /// to the generator's bounding sphere (`rect_lo`, `cell` in units of `tan`), `flux` is the
    /// power through the texel straight along `w`.
    pub point: Option<PointLight>,
    /// Face side of the light cube map (point lights).
    pub light_cube: usize,
    /// A water surface as the generator ([`water`]): what the reconstruction passes add for it.
    /// `None` for glass.
    pub water: Option<WaterTransport>,
}

/// What the reconstruction passes do differently when the water surface is the generator
/// ([`water`]): Beer-Lambert absorption along each photon's refracted path, the copies of a tiling
/// surface, and which photons the splatting baseline splats.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaterTransport {
    /// Quads per side of the water lattice, `P`: the photon image is `(P + 1)²`, and its last row
    /// and column repeat the first ones' cells (the baseline splats photon `(i, j)` for cell
    /// `(i, j)`, `i, j < P`, only).
    pub lattice: usize,
    /// `K` per RGB channel: a point whose path length interpolates to `d` gets `exp(−K d)`.
    pub absorption: DVec3,
    /// A tiling surface: every primitive is drawn again shifted by `±size` in x and y.
    pub wrap: bool,
    /// Quads from an edge of the lattice whose light can cross that edge ([`water::copy_band`], a
    /// bound from the surface's steepest slope): a copy shifted by `±size` is drawn for those
    /// quads only ([`CausticTrianglesSetup::copy_rect`]), the others' copies would miss the square.
    pub band: usize,
    /// The photon image tiles in the receiver's plane: photon `(P, j)` is photon `(0, j)` moved
    /// by `size` in y, `(i, P)` is `(i, 0)` moved in x. A tiling surface seen on the floor (with or
    /// without walls); not a clamped surface, nor a wall's plane, which the moved photons meet
    /// elsewhere. The hat rule then takes an edge vertex's triangles across the edge too
    /// ([`CausticTrianglesSetup::lattice_share`]).
    pub periodic: bool,
}

impl CausticTrianglesSetup {
    /// Floor offsets every triangle (splat) is drawn at: nine copies around the square for tiling
    /// water, so light carried across an edge lands on the other side; one otherwise. Copy `k`
    /// is offset `((k mod 3) − 1, (k div 3) − 1) · size`, the GPU's instance `k`.
    pub fn copies(&self) -> Vec<DVec2> {
        match self.water {
            Some(w) if w.wrap => (0..9)
                .map(|k| DVec2::new((k % 3) as f64 - 1.0, (k / 3) as f64 - 1.0) * self.floor.size)
                .collect(),
            _ => vec![DVec2::ZERO],
        }
    }

    /// The quads copy `k` of [`copies`](Self::copies) is drawn for, `(i0, i1, j0, j1)` (rows
    /// `i0..i1`, columns `j0..j1`): every quad for the unshifted copy; for a copy shifted by `+size`
    /// in x (light that left through `x = 0`) the first [`WaterTransport::band`] columns, for `−size`
    /// the last ones, and the same in y. The band's ends fall on multiples of the largest merged
    /// block (§5), so a block is wholly in or out. The GPU's `copy_rect`.
    pub fn copy_rect(&self, k: usize) -> (usize, usize, usize, usize) {
        let quads = self.p.saturating_sub(1);
        let Some(w) = self.water.filter(|w| w.wrap) else {
            return (0, quads, 0, quads);
        };
        let block = 1usize << self.merge_levels;
        let band = w.band.div_ceil(block) * block;
        let range = |c: usize| match c {
            0 => (quads.saturating_sub(band) / block * block, quads),
            2 => (0, band.min(quads)),
            _ => (0, quads),
        };
        let (i0, i1) = range(k / 3);
        let (j0, j1) = range(k % 3);
        (i0, i1, j0, j1)
    }

    /// The share of photon `(i, j)`'s power the hat rule draws. A water photon sits on a lattice
    /// corner and carries a whole cell `Δ²` of light (what the paper rule, which extrapolates an
    /// edge vertex's `ΔA` to a whole cell, and the splats need); the `(P + 1)²` photons' power is
    /// `(P + 1)² / P²` of the square's, `+2/P` (+1.56 % at `P = 128`), which the hat rule, drawing
    /// every photon's power, drew. With a periodic photon image ([`WaterTransport::periodic`]) an
    /// edge vertex's `ΔA` is its whole ring, the triangles across the edge included, and it and its
    /// twin on the opposite edge each draw their side of the hat: together one photon, share 1.
    /// Otherwise (clamped water, a wall's plane) only the part of an edge vertex's cell inside the
    /// square is drawn: ½ per lattice edge it lies on (¼ at a corner), the trapezoid rule of the
    /// surface's outgoing flux over the square. Glass: 1.
    pub fn lattice_share(&self, i: usize, j: usize) -> f64 {
        match self.water {
            Some(w) if !w.periodic => {
                let edge = |k: usize| if k == 0 || k == w.lattice { 0.5 } else { 1.0 };
                edge(i) * edge(j)
            }
            _ => 1.0,
        }
    }

    /// Beer-Lambert absorption per channel (zero for glass).
    pub fn absorption(&self) -> DVec3 {
        self.water.map_or(DVec3::ZERO, |w| w.absorption)
    }
}

impl CausticTrianglesSetup {
    /// The setup of a glass generator: a `photon_image²` photon image over the generator's
    /// light-space rectangle (sun) or over the cone of directions to its bounding sphere (point
    /// light), and the power of one photon in floor-area units.
    pub fn new(params: &CausticTrianglesParams, scene: &GlassScene) -> Result<Self> {
        params.validate()?;
        let (u, v, w) = light_frame(scene.light);
        let p = params.photon_image as usize;
        let (lo, hi) = scene.light_rect(u, v);
        let cell = (hi - lo) / p as f64;
        // The sun puts `a⊥ / |L_z|` floor-area units through a texel of area `a⊥`; a point light
        // of intensity I puts `I dω` through a solid angle dω, and a tangent-plane cell of area a at
        // q subtends `a / (1 + q²)^{3/2}`.
        let flux = match scene.point {
            None => cell.x * cell.y / -scene.light.z,
            Some(pl) => pl.intensity() * cell.x * cell.y,
        };
        Ok(CausticTrianglesSetup {
            p,
            u,
            v,
            w,
            rect_lo: lo,
            cell,
            flux,
            ior: scene.ior,
            depth: params.depth,
            fresnel: params.fresnel,
            linear_steps: params.linear_steps,
            secant_iterations: params.secant_iterations,
            area_rule: params.area_rule,
            splat_size: params.splat_size,
            merge_levels: params.merge_levels,
            merge_texels: params.merge_texels,
            floor: scene.floor,
            point: scene.point,
            light_cube: params.light_cube as usize,
            water: None,
        })
    }

    /// The light ray of photon-image texel `(i, j)`: where it starts (outside the distance map's
    /// sphere, on the way in), its unit direction and its power; `None` where the texel carries no
    /// light into the map (outside a spot's cone, or missing the map's sphere).
    pub fn photon_ray(&self, dm: &DistanceMap, i: usize, j: usize) -> Option<(DVec3, DVec3, f64)> {
        let Some(pl) = self.point else {
            return Some((self.photon_origin(dm, i, j), self.w, self.flux));
        };
        let q = self.rect_lo + self.cell * DVec2::new(j as f64 + 0.5, i as f64 + 0.5);
        let len2 = 1.0 + q.length_squared();
        let d = (self.w + self.u * q.x + self.v * q.y) / len2.sqrt();
        if !pl.lights(d) {
            return None;
        }
        let oc = pl.position - dm.centre;
        let b = oc.dot(d);
        let disc = b * b - (oc.length_squared() - dm.radius * dm.radius);
        if disc <= 0.0 {
            return None;
        }
        let t = (-b - disc.sqrt()).max(0.0);
        Some((pl.position + d * t, d, self.flux / (len2 * len2.sqrt())))
    }

    /// Where the light ray of photon-image texel `(i, j)` starts: behind the distance map's sphere.
    pub fn photon_origin(&self, dm: &DistanceMap, i: usize, j: usize) -> DVec3 {
        let q = self.rect_lo + self.cell * DVec2::new(j as f64 + 0.5, i as f64 + 0.5);
        let c = dm.centre;
        c + self.u * (q.x - c.dot(self.u)) + self.v * (q.y - c.dot(self.v)) - self.w * dm.radius
    }
}

/// Everything one run produces.
pub struct Output {
    /// The photon hit location image, `P x P` row major: `(x, y, Φ, σ)` of each photon's floor
    /// hit, or [`INVALID`].
    pub photons: Vec<[f32; 4]>,
    /// Each photon's vertex irradiance `E = ΔΦ / ΔA`, floor units (1: the unobstructed sun, or a
    /// point light straight above), −1 where invalid.
    pub irradiance: Vec<f32>,
    /// The floor map of the caustic triangles (relative irradiance).
    pub map: CausticsMap,
}

/// The whole technique on the CPU for a built distance map.
pub fn caustics(setup: &CausticTrianglesSetup, dm: &DistanceMap) -> Output {
    let photons = photon_pass(setup, dm);
    let irradiance = irradiance_pass(setup, &photons);
    let map = triangles_pass(setup, &photons, &irradiance);
    Output {
        photons,
        irradiance,
        map,
    }
}

/// The technique for a whole scene, over the scene square at the scene's caustics resolution: a
/// scene with water has its water surface as the generator ([`water::render`]); otherwise every
/// glass object is one (a distance map each, as the paper does for generators far apart), their
/// caustic maps added.
pub fn render(scene: &crate::scene::Scene, params: &CausticTrianglesParams) -> Result<CausticsMap> {
    if scene.water.is_some() {
        return water::render(scene, params);
    }
    let generators = camera::generators(scene, params)?;
    let maps = generators.iter().map(|g| caustics(&g.setup, &g.dm).map);
    Ok(maps
        .reduce(|a, b| a.added(&b))
        .expect("at least one generator"))
}

#[cfg(test)]
mod tests;
