//! Technique `cascaded`: "Cascaded caustic maps" for large oceans (Bäcklund, paper 5), the CPU twin
//! of `caustics-gpu`'s `cascaded` module, pass for pass.
//!
//! # Files: one per GPU pass
//! | pass | WGSL (crates/gpu/src/cascaded/) | CPU twin (this folder) |
//! |---|---|---|
//! | eye depth (compute, once) | `eye.wgsl` | `eye.rs`: [`eye_pass`] |
//! | water G-buffer (compute, per cascade) | `water.wgsl` | `water.rs`: [`water_gbuffer`] |
//! | terrain G-buffer (compute, per cascade, optional) | `terrain.wgsl` | `terrain.rs`: [`terrain_gbuffer`] |
//! | photons + splat (compute, per cascade) | `photons.wgsl` | `photons.rs`: [`photons`], [`place_photon`], [`footprint_side`], [`splat_footprint`] |
//! | composition (compute, once) | `compose.wgsl` | `compose.rs`: [`compose`], [`cascade_weights`] |
//! | post-process dispersion (compute, once, optional) | `disperse.wgsl` | `disperse.rs`: [`disperse`] |
//! | the geometry every pass repeats | `common.wgsl` | `common.rs`: [`CascadedSetup::ray_origin`], [`CascadedSetup::terrain_hit`], [`terrain_march`], [`CascadedSetup::box_hit`], [`CascadedSetup::receiver_normal`] |
//!
//! This file holds the descriptor, the parameters, the setup every pass shares ([`CascadedSetup`],
//! whose fields the GPU uploads as its uniform block) and [`caustics`], the passes in order;
//! `tests.rs` the tests.
//!
//! # The method (paper §3)
//! - **Cascades** (§3.2.2, "fit to scene"): the eye frustum is cut into [`CASCADES`] sub-frusta that
//!   share the near plane and whose far planes grow linearly. Each gets an orthographic sun view
//!   (§3.2.1) whose rectangle bounds where the sub-frustum's underwater part takes its light from
//!   on the water plane (see [`CascadedSetup::from_scene`]); the rectangle's sides change in steps and its
//!   origin snaps to whole texels, so the photons do not shimmer as the camera moves.
//! - **Light-view G-buffers** (§3.3, §3.3.1), per cascade on a `resolution²` grid: the water's
//!   light-view depth (the position is rebuilt from it, §3.3.1) and normal, written by one pass
//!   ([`water_gbuffer`]), and the terrain's light-view depth ([`terrain_gbuffer`]). Where the paper
//!   rasterises meshes, we intersect each texel's sun ray with the height fields.
//! - **Photons** (§3.4): each texel is one photon, refracted (IOR 1.333, §3.4.1; total internal
//!   reflection ends it), placed on the terrain by Eq. 3.3 (§3.4.2, derivation at [`Placement`]),
//!   weighted ([`Brightness`], §3.4.3), projected into the eye's screen space and splatted
//!   additively into the cascade's screen-space caustic map ([`photons`]).
//! - **Composition** (§3.5): each pixel takes the cascade its eye depth falls in ([`compose`]).
//!
//! # Designed here (the paper's copy stops at §3.5.1)
//! - The blend band between cascades (§3.5 beyond 3.5.1): over the last `blend` fraction of a
//!   cascade's depth interval the pixel fades linearly into the next cascade, which also covers it
//!   (every sub-frustum starts at the shared near plane).
//! - The eye-depth pass that the composition samples (§3.5.1 samples the eye's depth buffer): the
//!   eye ray against the terrain, ignoring the view's refraction at the water, as the paper's
//!   screen-space overlay does. It also gives the floor area each pixel sees, which turns the splatted
//!   flux into irradiance.
//! - Photon units: every photon carries the sun's flux through its texel, `E⊥ du dv`, so the
//!   cascades agree in brightness at their seams. In the paper's ramp mode this is multiplied by
//!   `C · deep · shallow`; with a constant per photon, as the paper writes it, a cascade with 4x the
//!   texel area would be 4x darker. The physically based mode multiplies it by the Fresnel
//!   transmittance relative to flat water and by Beer-Lambert absorption per RGB along the photon's
//!   path; dividing by the pixel's floor area then gives the same relative irradiance as the
//!   reference (1 under flat, clear water on a horizontal floor).
//! - Dispersion (§3.6, both variants): see [`Dispersion`].
//!
//! # Splatting
//! Photons are summed as unsigned fixed point (`round(w · 2^14)`), per cascade, pixel and channel:
//! on the GPU with `atomicAdd` into a storage buffer, here with plain adds. Integer sums do not depend
//! on the order the photons arrive in, so the two twins differ only where f32 and f64 place a photon
//! in different pixels (or footprint steps). By default each photon is spread over its footprint,
//! the screen-space box of the floor its light texel lights ([`Splat::Footprint`], ours: the paper
//! splats points, which near the eye, where a pixel sees less floor than a texel lights, leaves a
//! dotted moiré); the integer shares add up to the photon's weight exactly.

mod common;
mod compose;
mod disperse;
mod eye;
mod photons;
mod terrain;
#[cfg(test)]
mod tests;
mod water;

pub use common::{BISECTION_STEPS, MARCH_STEPS, terrain_march};
pub use compose::{cascade_weights, compose};
pub use disperse::disperse;
pub use eye::eye_pass;
pub use photons::{
    FOOTPRINT_MAX, FOOTPRINT_SUBPIXELS, Photon, TENT_WEIGHT, footprint_side, photons, place_photon,
    screen_buffer_len, splat_footprint, tent_cumulative,
};
pub use terrain::terrain_gbuffer;
pub use water::{WATER_STEPS, water_gbuffer};

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::optics::{fresnel_transmittance, refract};
use crate::scene::{Scene, WaterSource};

// The eye camera's projection, which this technique's passes follow and the final image reads the
// technique's image through: it lives below both, in `crate::eye`.
pub use crate::eye::EyeCamera;

/// The fixed number of cascades (§3.2.2: "a fixed number of cascades" avoids shimmering).
pub const CASCADES: usize = 4;
/// Fixed-point scale of the splatted photon weights.
pub const FIXED_SCALE: f64 = 16384.0;
/// Water's refractive index at 20 °C for the red, green and blue channels: the C (656.3 nm),
/// D (589.3 nm) and F (486.1 nm) lines, 1.3311, 1.3330, 1.3371 (CRC Handbook of Chemistry and
/// Physics, "Index of refraction of water"; Daimon & Masumura, Appl. Opt. 46 (2007) agree to 1e-4).
pub const WATER_IOR_RGB: [f64; 3] = [1.3311, 1.3330, 1.3371];

/// Where a photon lands (§3.4.2).
///
/// **Eq. 3.3, derived.** A texel's sun ray meets the water at `P_w` and, had the water not been
/// there, the terrain at `P_t` (both rebuilt from the G-buffers' light-view depths). After refraction
/// the photon travels along `T` from `P_w`. The paper places it where `P_t` projects orthogonally onto
/// that ray: `P = P_w + ((P_t − P_w) · T / |T|²) T`. It is the point of the refracted ray closest to
/// the straight ray's terrain hit, so it stays within `|P_t − P_w| sin ∠(L, T)` of `P_t`; it is not on
/// the terrain, and it is not the true hit even over a flat floor (the true hit lies a distance
/// `(P_w.z − P_t.z) / (−T_z)` along `T`, Eq. 3.3 goes `|P_t − P_w| cos ∠(L, T)`; the two agree only to
/// first order in the angle). The error grows with the refraction angle, the terrain's slope and the
/// water column; the tests measure it against exact marching of the terrain.
///
/// **Plane** (ours, same cost): intersect the refracted ray with the horizontal plane through `P_t`,
/// `P = P_w + T (P_w.z − P_t.z) / (−T_z)`: exact over a flat floor, first-order in the slope over the
/// distance between `P_t` and the true hit on a sloping one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Placement {
    /// Eq. 3.3 (the paper's): the point of the refracted ray closest to the straight ray's terrain
    /// hit `P_t`.
    Eq33,
    /// The refracted ray's hit on the horizontal plane through `P_t` (ours).
    Plane,
}

use super::buffers::{Buffer, BufferDesc, BufferInput, Index, Needs, check_index};
use super::describe::{
    Descriptor, Kind, Param, ParamDefault as D, Receiver, check_params, read_params, serde_defaults,
};
use super::{Input, Job, JobOutput, SceneCaustics};
use crate::plot::{Picture, rgb_picture};

/// Paper 5 as registered: an image in the eye camera's screen space, not a floor map.
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "cascaded",
    table: "cascaded",
    paper: "5",
    summary: "cascaded caustic maps for oceans: four light-view cascades, photons splatted in eye space, dispersion (Backlund)",
    docs: "docs/cascaded.md",
    input: Input::EyeSpace,
    receivers: &[Receiver::EyeSpace],
    params: &[
        Param {
            sweep: &["64", "128", "256", "512", "1024"],
            ..Param::new(
                "resolution",
                "cascade resolution",
                Kind::int(16, 8192),
                D::Int(512),
                "texels per side",
                "caustic-map texels per side of each of the four cascades (§3.3)",
            )
        },
        Param::new(
            "placement",
            "cascade placement",
            Kind::Choice(&["eq33", "plane"]),
            D::Text("eq33"),
            "",
            "eq33: the photon placed by Eq. 3.3; plane: on the horizontal plane through the terrain hit (ours)",
        ),
        Param::new(
            "dispersion",
            "dispersion",
            Kind::Choice(&["none", "wavelength", "post"]),
            D::Text("none"),
            "",
            "none; wavelength: one IOR per channel (§3.6); post: a screen-space shift (ours)",
        ),
        Param::new(
            "dispersion_scale",
            "dispersion scale",
            Kind::float(0.0, 1.0e3),
            D::Float(1.0),
            "",
            "exaggeration of the dispersion (1: water's measured dispersion)",
        ),
        Param::new(
            "splat",
            "splat",
            Kind::Choice(&["footprint", "point"]),
            D::Text("footprint"),
            "",
            "footprint: a tent the size of the photon's floor area (ours); point: one pixel (§3.4)",
        ),
        Param::new(
            "brightness",
            "brightness",
            Kind::Choice(&["physical", "ramps"]),
            D::Text("physical"),
            "",
            "physical: relative irradiance; ramps: the paper's depth ramps (§3.4.3)",
        ),
        Param::new(
            "near",
            "near",
            Kind::float(0.0, 1.0e6),
            D::Float(0.1),
            "world units",
            "the eye's near plane (view depth)",
        ),
        Param::new(
            "far",
            "far",
            Kind::float(0.0, 1.0e6),
            D::Float(48.0),
            "world units",
            "the far plane of the last cascade (view depth)",
        ),
        Param::new(
            "blend",
            "blend",
            Kind::float(0.0, 1.0),
            D::Float(0.1),
            "",
            "fraction of each cascade's depth interval over which it blends into the next",
        ),
        Param::new(
            "c",
            "C",
            Kind::float(-1.0e6, 1.0e6),
            D::Float(1.0),
            "",
            "C of §3.4.3 (ramps)",
        ),
        Param::new(
            "min_depth",
            "min depth",
            Kind::float(-1.0e6, 1.0e6),
            D::Float(0.0),
            "world units",
            "MIN_DEPTH of §3.4.3 (ramps)",
        ),
        Param::new(
            "max_depth",
            "max depth",
            Kind::float(0.0, 1.0e6),
            D::Float(10.0),
            "world units",
            "MAX_DEPTH of §3.4.3 (ramps)",
        ),
        Param::new(
            "shallow_ramp",
            "shallow ramp",
            Kind::float(0.0, 1.0e6),
            D::Float(1.0),
            "world units",
            "width of the shallow ramp of §3.4.3 (the paper: 1)",
        ),
        Param::on(
            "terrain_pass",
            "terrain pass",
            "the terrain's light-view depth pass; off, the floor is the plane z = 0 (Fig. 4.3)",
        ),
    ],
    fixed: &[],
    point_light: false,
    buffers: &[BufferDesc {
        key: "cascade",
        label: "cascade {k}: caustic map",
        index: Some(Index {
            name: "cascade",
            count: |_, _| CASCADES as u32,
        }),
        needs: Needs::Anything,
    }],
    draw_buffer,
    reference: false,
    validate: |t| CascadedParams::from_table(t).map(|_| ()),
    own_defaults: serde_defaults::<CascadedParams>,
    cpu: run_cpu,
};

/// Side of the height grid the technique reads a water surface through when the water gives
/// neither an ocean's nor a file's own grid (the shore's ocean is 128²).
pub const WATER_GRID: usize = 256;

/// The setup and the water grid a job gives paper 5 (both twins): a file's own grid, an ocean
/// read at its own lattice (its own grid, [`super::lattice_heights`]), any other surface sampled
/// [`WATER_GRID`]² over the square.
pub fn job_setup(job: &Job, table: &toml::Table) -> Result<(CascadedSetup, Grid)> {
    let params = CascadedParams::from_table(table)?;
    let setup = CascadedSetup::from_scene(job.scene, &params)?;
    let grid = job.with_surface(DESCRIPTOR.name, |water, surface| {
        Ok(match &water.source {
            WaterSource::HeightField(g) => g.clone(),
            WaterSource::Ocean(_) => super::lattice_heights(water, surface, 0, 0),
            _ => crate::water::sample_grid(surface, WATER_GRID, WATER_GRID, water.size),
        })
    })?;
    Ok((setup, grid))
}

fn run_cpu(
    job: &Job,
    table: &toml::Table,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<JobOutput> {
    let (setup, water) = job_setup(job, table)?;
    let image = caustics(&setup, &water, job.scene.floor.terrain.as_ref()).image;
    progress(1, 1);
    Ok(JobOutput {
        caustics: SceneCaustics::EyeSpace(crate::eye::EyeSpaceCaustics {
            width: setup.eye.width,
            height: setup.eye.height,
            texels: image,
        }),
        light: None,
        walls: None,
    })
}

/// Photon brightness (§3.4.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Brightness {
    /// The paper's: `C · deep · shallow`, `deep = clamp((MAX_DEPTH − d) / MAX_DEPTH)`,
    /// `shallow = clamp((d − MIN_DEPTH) / shallow_ramp)` with `d` the water column over the photon
    /// (the paper's ramp is 1 unit wide: `shallow_ramp = 1`).
    Ramps,
    /// Fresnel transmittance (relative to flat water) times Beer-Lambert `exp(−K s)` per RGB over the
    /// photon's path `s` under water.
    Physical,
}

/// How a photon is splatted into the eye's screen space (§3.4, "splat additively"; the footprint is
/// ours).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Splat {
    /// Over its footprint: a tent in screen space as wide as the photons' spacing there, the
    /// footprint of its light texel on the floor ([`footprint_side`]: `photon_flux / (pixel floor
    /// area)` pixels, both horizontal areas, the pixel's from the eye pass), capped at
    /// [`FOOTPRINT_MAX`] pixels a side. Where a pixel sees
    /// less floor than a texel lights, a point splat leaves most pixels with 0 or 1 photons (a dotted
    /// moiré); the footprint spreads each photon's flux over the floor its texel actually lights,
    /// conserving it exactly ([`splat_footprint`]).
    Footprint,
    /// Into the one pixel the photon projects into (the paper's points).
    Point,
}

/// Light dispersion (§3.6; the copy stops before it, both variants are designed here).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dispersion {
    /// No dispersion: one photon per texel, refracted with the scene's IOR, into all three channels.
    None,
    /// Ray-based: each texel sends one photon per RGB channel, refracted with that channel's IOR
    /// ([`WATER_IOR_RGB`], offsets from green added to the scene's IOR and scaled by
    /// `dispersion_scale`), each splatted into its own channel.
    Wavelength,
    /// Post-process (ours): the photons are refracted once (the scene's IOR); afterwards each pixel's
    /// red and blue are read from where flat water would have sent green, i.e. channel `c` at floor
    /// point `F` is the composed channel `c` at `F − δ_c`, `δ_c = d (tan θ_c − tan θ_G) L̂_xy` with `d`
    /// the water column over `F` and `θ_c` the flat-water refraction angle for channel `c`. It shifts
    /// the colours by the mean lateral dispersion but cannot spread them by the waves' tilt.
    Post,
}

/// The technique's parameters, `[caustics.cascaded]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CascadedParams {
    /// Caustic-map (light-view G-buffer) resolution per cascade, texels per side.
    pub resolution: u32,
    /// Eye near plane, world units of view depth, shared by every cascade's sub-frustum; default 0.1.
    pub near: f64,
    /// Far plane of the last cascade, world units of view depth; the cascades' far planes split
    /// `[near, far]` evenly (§3.2.2). Default 48.
    pub far: f64,
    /// Fraction of each cascade's depth interval over which it blends into the next (0: hard seams).
    pub blend: f64,
    /// Where a photon lands (§3.4.2): by Eq. 3.3 (default) or on the plane through the terrain hit.
    pub placement: Placement,
    /// How a photon is weighted (§3.4.3): relative irradiance (default) or the paper's depth ramps.
    pub brightness: Brightness,
    /// `C` of §3.4.3 (ramp mode).
    pub c: f64,
    /// `MIN_DEPTH` of §3.4.3 (ramp mode), world units of water column over the photon: the shallow
    /// ramp starts here, photons in shallower water are dark (near the shore). Default 0.
    pub min_depth: f64,
    /// `MAX_DEPTH` of §3.4.3 (ramp mode), world units of water column: the brightness falls
    /// linearly from full at the surface to 0 at this depth. Positive; default 10.
    pub max_depth: f64,
    /// Width of the shallow ramp of §3.4.3 (ramp mode), world units of water column: the brightness
    /// rises from 0 at `min_depth` to full at `min_depth + shallow_ramp`. Positive; the paper's is 1.
    pub shallow_ramp: f64,
    /// Whether the terrain light-view depth pass runs; without it the floor is taken as the plane
    /// z = 0 (the paper's Fig. 4.3 times the technique without this pass).
    pub terrain_pass: bool,
    /// Light dispersion (§3.6): none (default), one refraction per wavelength, or the post-process.
    pub dispersion: Dispersion,
    /// Exaggeration of the dispersion (1: water's measured dispersion).
    pub dispersion_scale: f64,
    /// How photons are splatted into the eye's image: over their footprint (default, ours) or as
    /// points (§3.4).
    pub splat: Splat,
}

impl Default for CascadedParams {
    fn default() -> Self {
        CascadedParams {
            resolution: 512,
            near: 0.1,
            far: 48.0,
            blend: 0.1,
            placement: Placement::Eq33,
            brightness: Brightness::Physical,
            c: 1.0,
            min_depth: 0.0,
            max_depth: 10.0,
            shallow_ramp: 1.0,
            terrain_pass: true,
            dispersion: Dispersion::None,
            dispersion_scale: 1.0,
            splat: Splat::Footprint,
        }
    }
}

impl CascadedParams {
    /// The parameters from the `cascaded` entry of a scene's `[caustics]` table, defaults for what it
    /// leaves out (all of them without the entry), validated.
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        read_params(table, &DESCRIPTOR, Self::validate)
    }

    /// Check the ranges the passes rely on: the descriptor's, `0 < near < far`, positive
    /// `max_depth` and `shallow_ramp`.
    pub fn validate(&self) -> Result<()> {
        check_params(&DESCRIPTOR, self)?;
        let bad = |f: &str, m: String| Err(Error::field(format!("caustics.cascaded.{f}"), m));
        if !(self.near > 0.0 && self.far > self.near) {
            return bad(
                "far",
                format!(
                    "need 0 < near < far, got near {} far {}",
                    self.near, self.far
                ),
            );
        }
        if !(self.max_depth > 0.0 && self.shallow_ramp > 0.0) {
            return bad(
                "max_depth",
                "max_depth and shallow_ramp must be positive".into(),
            );
        }
        Ok(())
    }
}

/// One cascade's sun view: texel `(i, j)` is the sun ray through light-view point
/// `(u0 + (j + ½) du, v0 + (i + ½) dv)`, starting on the near plane `w = w0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CascadeView {
    /// Light-view `u` (along [`CascadedSetup::e_u`]) of the rectangle's lower edge, world units, a
    /// multiple of `du` (snapped to whole texels so the photons do not shimmer).
    pub u0: f64,
    /// Light-view `v` (along [`CascadedSetup::e_v`]) of the rectangle's lower edge, world units, a
    /// multiple of `dv`.
    pub v0: f64,
    /// Texel side along `e_u`, world units.
    pub du: f64,
    /// Texel side along `e_v`, world units.
    pub dv: f64,
    /// Light-view depth (along the sunlight) of the plane the texels' rays start on, world units:
    /// every ray starts at least 1 above the water's rest level and the terrain's top.
    pub w0: f64,
    /// Eye view depth of the sub-frustum's far plane.
    pub far: f64,
}

/// Everything the passes share (the GPU uploads the same numbers as its uniform block).
#[derive(Clone, Debug)]
pub struct CascadedSetup {
    /// The parameters the setup was built from.
    pub params: CascadedParams,
    /// Texels per side of every cascade's light-view grid (`params.resolution`).
    pub res: usize,
    /// Unit direction of the sunlight and the light-view axes: `(e_u, e_v, light)` orthonormal.
    pub light: DVec3,
    /// Light-view `u` axis: horizontal, across the sun's horizontal direction (x when the sun is
    /// straight overhead).
    pub e_u: DVec3,
    /// Light-view `v` axis: `light × e_u`.
    pub e_v: DVec3,
    /// The cascades' sun views, nearest sub-frustum first.
    pub cascades: [CascadeView; CASCADES],
    /// The eye camera whose screen space the photons are splatted into and composed in.
    pub eye: EyeCamera,
    /// The water's rest level (z of the still surface), world units.
    pub level: f64,
    /// Side of the scene square `[0, size]²` the water and terrain height fields cover, world units.
    pub size: f64,
    /// Whether the water height field repeats beyond the square (else it is clamped at its edges).
    pub wrap: bool,
    /// Refractive index per channel (all equal unless [`Dispersion::Wavelength`]).
    pub ior: [f64; 3],
    /// The scene's IOR (green under dispersion).
    pub ior_mono: f64,
    /// Beer-Lambert absorption `K` per RGB channel, per world unit of path under water (physical
    /// brightness).
    pub absorption: DVec3,
    /// `T(θ0)` of flat water.
    pub t_flat: f64,
    /// Bounds of the terrain's interpolant (padded), `None` for the plane z = 0.
    pub terrain_range: Option<(f64, f64)>,
    /// Post-process dispersion: the floor shift per unit of water column for each channel.
    pub post_shift: [DVec2; 3],
    /// The pool's walls receive light (`floor.walls`, a flat floor only): the receivers
    /// are the inside of the box `[0, size]² x [0, level]`, floor and walls
    /// ([`CascadedSetup::box_hit`]).
    pub walls: bool,
}

fn bad(m: String) -> Error {
    Error::InvalidParameter(m)
}

impl CascadedSetup {
    /// The setup for a scene's water, floor (its terrain clamped at the square's edges, or the
    /// plane z = 0), sun and camera: the cascades fitted to the scene.
    ///
    /// Fit to scene: the sub-frustum `[near, far_k]` is clipped to the slab between the lowest floor
    /// and the water level (its 8 corners and 12 edges against the slab's two planes), every vertex of
    /// that polytope is carried back up the flat-water refracted ray to the water plane (where the
    /// photon that lands there entered), and the cascade's rectangle bounds those points in light-view
    /// coordinates, widened by a margin of a fifth of the water column for the waves' deflection. The
    /// rectangle's sides are then rounded up to a multiple of 1/8 of the next power of two (so they
    /// change in steps, not every frame) and its origin snapped to whole texels.
    pub fn from_scene(scene: &Scene, params: &CascadedParams) -> Result<Self> {
        let water = scene.water.as_ref().ok_or_else(|| {
            bad(format!(
                "scene `{}` has no water: cascaded caustics need one",
                scene.name
            ))
        })?;
        let (light, level, ior) = (scene.light.direction, water.level(), water.ior);
        let terrain = scene.floor.terrain.as_ref();
        params.validate()?;
        if light.z >= 0.0 || !light.is_finite() {
            return Err(bad(format!("the light direction {light} must point down")));
        }
        let light = light.normalize();
        let eta = 1.0 / ior;
        let t0 = refract(light, DVec3::Z, eta).expect("air to water never reflects totally");
        let lxy = DVec3::new(-light.y, light.x, 0.0);
        let e_u = if lxy.length() < 1e-9 {
            DVec3::X
        } else {
            lxy.normalize()
        };
        let e_v = light.cross(e_u);
        let eye = EyeCamera::new(&scene.camera);
        let terrain_range = match (terrain, params.terrain_pass) {
            (Some(g), true) => {
                let (lo, hi) = g.min_max();
                let pad = 0.05 * (hi - lo) as f64 + 1e-3;
                Some((lo as f64 - pad, hi as f64 + pad))
            }
            _ => None,
        };
        let (z_lo, _) = terrain_range.unwrap_or((0.0, 0.0));
        let z_lo = z_lo.min(level - 1e-3);
        let z_top = level.max(terrain_range.map_or(0.0, |r| r.1)) + 1.0;
        let res = params.resolution as usize;
        let cascades = std::array::from_fn(|k| {
            let far = params.near + (params.far - params.near) * (k + 1) as f64 / CASCADES as f64;
            let corner = |z: f64, c: usize| {
                let x = if c & 1 == 0 { 0.0 } else { eye.width as f64 };
                let y = if c & 2 == 0 { 0.0 } else { eye.height as f64 };
                eye.position + eye.ray(x, y) * z
            };
            let corners: Vec<DVec3> = [params.near, far]
                .iter()
                .flat_map(|&z| (0..4).map(move |c| (z, c)))
                .map(|(z, c)| corner(z, c))
                .collect();
            // The frustum's edges: near to far, then round the near and the far rectangles.
            let ring = [0, 1, 3, 2];
            let around = (0..8).map(|k| (k / 4 * 4 + ring[k % 4], k / 4 * 4 + ring[(k + 1) % 4]));
            let edges = (0..4).map(|c| (c, c + 4)).chain(around);
            let mut points = Vec::new();
            for p in &corners {
                if p.z >= z_lo && p.z <= level {
                    points.push(*p);
                }
            }
            for (a, b) in edges {
                let (a, b) = (corners[a], corners[b]);
                for plane in [z_lo, level] {
                    let t = (plane - a.z) / (b.z - a.z);
                    if (0.0..=1.0).contains(&t) {
                        points.push(a + (b - a) * t);
                    }
                }
            }
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for p in &points {
                let w = *p - t0 * ((level - p.z) / -t0.z);
                let uv = DVec2::new(w.dot(e_u), w.dot(e_v));
                lo = lo.min(uv);
                hi = hi.max(uv);
            }
            if points.is_empty() {
                // The sub-frustum sees no water: a tiny rectangle in front of the eye.
                let p = eye.position + eye.forward * far;
                lo = DVec2::new(p.dot(e_u), p.dot(e_v));
                hi = lo + DVec2::ONE;
            }
            let margin = 0.2 * (level - z_lo);
            lo -= DVec2::splat(margin);
            hi += DVec2::splat(margin);
            let step = |extent: f64| {
                let padded = extent * res as f64 / (res as f64 - 1.0);
                let q = 2f64.powf(padded.log2().ceil()) / 8.0;
                (padded / q).ceil() * q / res as f64
            };
            let (du, dv) = (step(hi.x - lo.x), step(hi.y - lo.y));
            let (u0, v0) = ((lo.x / du).floor() * du, (lo.y / dv).floor() * dv);
            // The near plane: every texel's ray starts at or above z_top.
            let mut w0 = f64::INFINITY;
            for (u, v) in [
                (u0, v0),
                (u0 + res as f64 * du, v0),
                (u0, v0 + res as f64 * dv),
                (u0 + res as f64 * du, v0 + res as f64 * dv),
            ] {
                let a = u * e_u.z + v * e_v.z;
                w0 = w0.min((z_top - a) / light.z);
            }
            CascadeView {
                u0,
                v0,
                du,
                dv,
                w0,
                far,
            }
        });
        let scale = params.dispersion_scale;
        let ior_rgb = match params.dispersion {
            Dispersion::Wavelength => WATER_IOR_RGB.map(|n| ior + scale * (n - WATER_IOR_RGB[1])),
            _ => [ior; 3],
        };
        let post_shift = match params.dispersion {
            Dispersion::Post => {
                let sin_i = light.truncate().length();
                let dir = light.truncate().normalize_or_zero();
                let tan_t = |n: f64| {
                    let s = sin_i / n;
                    s / (1.0 - s * s).sqrt()
                };
                WATER_IOR_RGB.map(|n| {
                    let n = ior + scale * (n - WATER_IOR_RGB[1]);
                    dir * (tan_t(n) - tan_t(ior))
                })
            }
            _ => [DVec2::ZERO; 3],
        };
        Ok(CascadedSetup {
            params: params.clone(),
            res,
            light,
            e_u,
            e_v,
            cascades,
            eye,
            level,
            size: water.size,
            wrap: water.wrap,
            ior: ior_rgb,
            ior_mono: ior,
            absorption: water.absorption,
            t_flat: fresnel_transmittance(-light.z, 1.0, ior),
            terrain_range,
            post_shift,
            walls: scene.floor.walls,
        })
    }
}

/// Everything one frame computes, kept for pictures and tests.
pub struct CascadedFrame {
    /// The eye-depth pass per pixel, row by row: `[view depth, floor area seen, floor z, N_z]`
    /// ([`eye_pass`]).
    pub eye: Vec<[f32; 4]>,
    /// The fixed-point screen-space caustic map of every cascade.
    pub acc: Vec<u32>,
    /// The composed (and, under [`Dispersion::Post`], dispersed) screen-space caustics.
    pub image: Vec<[f32; 4]>,
}

/// The whole technique on the CPU: the water as a height field over the scene square (wrapped or
/// clamped as the scene says), the terrain clamped, `None` for the plane z = 0.
pub fn caustics(setup: &CascadedSetup, water: &Grid, terrain: Option<&Grid>) -> CascadedFrame {
    let terrain = if setup.terrain_range.is_some() {
        terrain
    } else {
        None
    };
    let eye = eye_pass(setup, terrain);
    let mut acc = vec![0u32; screen_buffer_len(setup)];
    for k in 0..CASCADES {
        let gw = water_gbuffer(setup, k, water);
        let gt = if setup.terrain_range.is_some() {
            terrain_gbuffer(setup, k, terrain)
        } else {
            Vec::new()
        };
        photons(setup, k, &eye, &gw, &gt, &mut acc);
    }
    let mut image = compose(setup, &eye, &acc);
    if setup.params.dispersion == Dispersion::Post {
        image = disperse(setup, &eye, &image);
    }
    CascadedFrame { eye, acc, image }
}

/// The water of a scene as the height field the technique samples: the ocean's own grid, a file's
/// grid, or any other surface sampled `n × n` over the square.
pub fn water_grid(scene: &Scene, n: usize) -> Result<Grid> {
    let water = scene
        .water
        .as_ref()
        .ok_or_else(|| bad(format!("scene `{}` has no water", scene.name)))?;
    Ok(match &water.source {
        WaterSource::Ocean(o) => o.height_grid(scene.time),
        WaterSource::HeightField(g) => g.clone(),
        _ => crate::water::sample_grid(&*water.surface_at(scene.time)?, n, n, water.size),
    })
}

/// Cascade `k`'s own screen-space caustic map (§3.3), before the blend between cascades: where
/// each cascade's photons land in the eye's image.
fn draw_buffer(input: &BufferInput, buffer: Buffer) -> Result<Picture> {
    let (scene, surface) = input.scene_with_water()?;
    let k = check_index(buffer.index, CASCADES, "cascades")?;
    let job = Job::new(&scene, Some(surface), 1);
    let (setup, grid) = job_setup(&job, input.params)?;
    let frame = caustics(&setup, &grid, scene.floor.terrain.as_ref());
    let map = frame.cascade_map(&setup, k);
    Ok(rgb_picture(
        setup.eye.width,
        setup.eye.height,
        |t| (frame.eye[t][3] != 0.0).then(|| map[t]),
        &format!("cascade {k} of {CASCADES}, relative irradiance"),
    ))
}
