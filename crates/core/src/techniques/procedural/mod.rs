//! Technique `procedural`: "Inexpensive Underwater Caustics Using Cg" (Sánchez-Crespo Dalmau, 2003),
//! the CPU twin of `caustics-gpu`'s `procedural` module, pass for pass.
//!
//! # Files: one per GPU pass
//! | pass | WGSL (crates/gpu/src/procedural/) | CPU twin (this folder) |
//! |---|---|---|
//! | vertex: caustic per mesh vertex, linear over the triangles | `vertex.wgsl` | `vertex.rs`: [`vertex_values`] + [`rasterise`] |
//! | screen: caustic per map pixel, no filtering | `screen.wgsl` | `screen.rs`: [`per_pixel`] at the map's size |
//! | texture: caustic per texel of the target, mip level 0 | `target.wgsl` | `target.rs`: [`target_pass`] ([`per_pixel`] at the target's size) |
//! | texture: one 2 x 2 box downsample per mip level | `downsample.wgsl` | `downsample.rs`: [`mip_chain`] |
//! | texture: the map reads the chain, trilinear + anisotropic | `resample.wgsl` | `resample.rs`: [`resample`], [`sampling_footprint`], [`trilinear`] |
//! | what the evaluating passes share: the water, the light map, the per-point caustic | `common.wgsl` | `common.rs`: [`SurfaceInput`], [`LightMap`], [`trace`], [`caustic_at`] |
//!
//! This file holds the descriptor, the parameters, the setup every pass shares and [`caustics`],
//! the passes in the setup's variant; `tests.rs` the tests.
//!
//! # The method (paper, "Our Approach")
//! An aesthetics-driven simplification of backward ray tracing. From each ground point `P` one ray
//! goes straight up ("we project it vertically until we reach the wave point located right on top
//! of it") to the water surface `z = depth + h(P.xy)`. The normal there comes from the surface's
//! exact gradient (the paper's Cg version differentiates its wave function instead of taking finite
//! differences): [`height_field_normal`](crate::optics::height_field_normal). The ray is refracted
//! from the water up into the air with "Snell's law reversed" and the paper's IOR 1.33333: incident
//! `(0, 0, 1)`, normal `−n` (facing the ray), `η = n_water / n_air = ior`; total internal
//! reflection gives no light. The refracted direction `R` then looks up a *sun map*: "the closer to
//! the vertical, the more light that comes from that direction into the ocean".
//!
//! # The light map (paper: the sun disk and its halo)
//! The paper's numbers: the sun disk subtends 0.53°, and its halo "covers about ten times" the disk's
//! area, so the halo's outer radius is `√10 × 0.265° ≈ 0.84°`. The map is parameterised over the
//! tangent plane of the direction toward the sun: with `R'` the refracted direction in a frame whose
//! `+z` points at the sun, `uv = R'.xy / R'.z` (the gnomonic projection, `|uv| = tan θ` with `θ` the
//! angle from the sun). Its texels hold `1` inside the disk and `halo_level · (1 − smoothstep(r_s,
//! r_h, θ))` in the halo (a smooth fall to 0 at the halo's edge), and span `uv ∈ [−E, E]²` with
//! `E = tan(1.1 r_h)`; they are read bilinearly at texel centres, 0 beyond the map (the same code on
//! the GPU, with `textureLoad`, so no float filtering is needed). A PNG can replace it
//! (`light_map = "sun.png"`, grey levels taken linearly, row 0 of the file at `v = −E`, and
//! `light_map_extent` the half-angle in degrees the picture spans).
//!
//! **Scale.** The map is normalised so that its value in the sun's own direction is exactly 1: flat
//! water under the default (overhead) sun then gives exactly 1.0 everywhere, the caustics map's
//! "flat water" level. This is the technique's *relative irradiance scale*, an aesthetic one, not a
//! physical one: the procedural map neither conserves flux nor knows the Fresnel transmittance; the
//! paper only asks that "zero means no lighting, one means a beam of very focused light".
//!
//! # Beyond the paper (options)
//! - `follow_sun = true`: the paper assumes "noon in the Equator", the sun overhead, which is the
//!   default whatever the scene's sun. With this option the scene's sun is used. The ground sees the
//!   sun *through* the surface, so the comparison is made in air: `R` is compared with `−L`, the
//!   direction toward the sun in air (the sun's angular size is an angle in air), and the gathering
//!   ray leaves the floor along `−T₀`, where `T₀ = refract(L)` is the direction flat water bends the
//!   sunlight into. Flat water then refracts the ray out exactly along `−L`, so flat water still
//!   gives 1.0 under any sun; for an overhead sun `−T₀ = (0, 0, 1)`: the paper's vertical ray, and the
//!   same map as without the option. The tilted ray meets the surface where it crosses the rest
//!   level (the paper's line-plane intercept, listing 1): the wave height moves that point by
//!   `h tan θ_t`, negligible against the wave lengths. (Keeping the vertical ray and only turning the
//!   sun map would leave flat water dark under any sun more than ~1° from the zenith.)
//! - `absorption = true` (default): `exp(−K d)` per RGB channel, `K` the scene's, `d` the path in
//!   water from the floor to the surface along the gathering ray, `(depth + h) / up_z` (the vertical
//!   path by default).
//! - Water input: the paper's wave function is evaluated analytically ([`SurfaceInput::Wave`], its
//!   exact gradient from `water/procedural.rs`); every other source is read, as `yuksel` does, as a
//!   height grid through the bicubic interpolant of [`Grid::sample`], whose gradient is the exact
//!   derivative of the interpolated height ([`SurfaceInput::Grid`]).
//!
//! # The three variants (paper: "Implementation Using OpenGL" and "Using Cg")
//! - [`Variant::Vertex`]: the caustic is computed per vertex of a fine ground mesh of
//!   `mesh_resolution²` quads over the floor square, each split along its `(0,0)–(1,1)` diagonal, and
//!   interpolated linearly over the triangles (GPU: a vertex shader computes it, the rasteriser
//!   interpolates it into the map; CPU: [`rasterise`], the same interpolation at the pixel centres).
//! - [`Variant::Screen`]: per pixel, at full resolution, no filtering: each map texel evaluates the
//!   caustic at its centre ([`per_pixel`]).
//! - [`Variant::Texture`]: per pixel into a fixed `target_resolution²` texture-space render target
//!   over the floor square ([`per_pixel`] at that size), a full mip chain by 2 × 2 box filtering on the
//!   GPU ([`mip_chain`], one pass per level), then read into the map at the map's resolution by
//!   trilinear + anisotropic sampling ([`resample`]; the GPU uses a sampler with
//!   `anisotropy_clamp = anisotropy`, 16 by default; the CPU twin Vulkan's LOD rule
//!   `λ = log₂(ρ_max / η)`, `η = min(ρ_max / ρ_min, anisotropy)`, and `⌈η⌉` trilinear taps along
//!   the footprint's major axis: [`sampling_footprint`]). How a GPU spreads its anisotropic taps is
//!   its own: Mesa's lavapipe, for one, filters with an elliptical Gaussian (EWA) wider than the
//!   footprint even where the footprint is square, where hardware reduces to trilinear;
//!   `anisotropy = 1` gives plain trilinear filtering everywhere.
//!
//! # Over a terrain
//! The paper's floor is flat; its rule carries to any floor because the gathering ray is a line
//! along the technique's light (`up`): every point on that line reaches the surface at the same
//! place, so the caustic of a floor point is the flat floor's at the point's light-space position
//! ([`crate::receivers`], with `t₀ = −up`). The passes evaluate the map on the plane `z = 0` as
//! they do for a flat floor and the receivers' lookup reads it per floor texel, with the face's
//! cosine against the light, the depth test, and `exp(−K d)` along the point's own path to the
//! rest level ([`ProceduralSetup::with_floor`]). Under the paper's overhead sun the light space is
//! the floor's own texels and the cosine is the normal's `z`.
//!
//! # Where it departs from the reference
//! By design, everywhere: the caustic is not the focusing of flux but the brightness of the sky seen
//! straight up through the surface. Bright spots sit where the surface is nearly flat (its crests,
//! troughs and saddles) rather than where the waves focus the light a depth below; the map's mean is
//! not the incident flux; the pattern does not move with the depth (only the absorption does). It
//! is the look of caustics, at a per-point cost.

mod common;
mod downsample;
mod resample;
mod screen;
mod target;
#[cfg(test)]
mod tests;
mod vertex;

pub use common::{LightMap, SurfaceInput, Trace, caustic_at, trace};
pub use downsample::mip_chain;
pub use resample::{resample, sampling_footprint, trilinear};
pub use screen::per_pixel;
pub use target::target_pass;
pub use vertex::{rasterise, vertex_values};

use std::path::PathBuf;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::map::CausticsMap;
use crate::optics::refract;
use crate::receivers::Shared;
use crate::receivers::{LightSpace, received_with_light};
use crate::water::Surface;

/// The paper's index of refraction of water.
pub const PAPER_IOR: f64 = 1.33333;
/// The sun disk's angular diameter, degrees (paper).
pub const SUN_DIAMETER_DEG: f64 = 0.53;
/// The halo's area over the sun disk's (paper: "about ten times larger").
pub const HALO_AREA: f64 = 10.0;
/// The light map spans this much more than the halo's radius, so its border texels are dark.
pub const LIGHT_MAP_MARGIN: f64 = 1.1;
/// The most quads per side of the vertex variant's ground mesh (`mesh_resolution`).
pub const MAX_MESH_RESOLUTION: u32 = 2048;
/// The largest side of the texture variant's render target, texels (`target_resolution`).
pub const MAX_TARGET_RESOLUTION: u32 = 8192;
/// The sampler's anisotropy clamp, and the CPU twin's largest tap count.
pub const MAX_ANISOTROPY: u32 = 16;

use super::describe::{
    Descriptor, Kind, Param, ParamDefault as D, Receiver, check_params, read_params, serde_defaults,
};
use super::{Input, Job, JobOutput};

/// A variant's parameter list: its own sampling parameters, then those every variant reads (the
/// lists differ only in the first).
macro_rules! with_shared_params {
    ($($own:expr),* $(,)?) => {
        &[
            $($own,)*
            IOR,
            FOLLOW_SUN,
            ABSORPTION,
            SUN_DIAMETER,
            HALO_AREA_PARAM,
            HALO_LEVEL,
            LIGHT_MAP_RESOLUTION,
            LIGHT_MAP,
            LIGHT_MAP_EXTENT,
            GROUND,
        ]
    };
}

/// Paper 2 as registered: its variant from the table (the screen variant by default).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "procedural",
    table: "procedural",
    paper: "2",
    summary: "aesthetic procedural caustics: vertical ray to the waves, refract, look up a sun map (Sanchez-Crespo); its variant from `variant`",
    docs: "docs/procedural.md",
    input: Input::Water,
    receivers: &[Receiver::Floor],
    params: with_shared_params![VARIANT, MESH_RESOLUTION, TARGET_RESOLUTION, ANISOTROPY,],
    fixed: &[],
    point_light: false,
    buffers: &[],
    draw_buffer: crate::techniques::buffers::no_buffers,
    reference: false,
    validate: |t| ProceduralCausticsParams::from_table(t).map(|_| ()),
    own_defaults: serde_defaults::<ProceduralCausticsParams>,
    cpu: run_cpu,
};

/// Paper 2 per vertex of a fine ground mesh.
pub const VERTEX: Descriptor = Descriptor {
    name: "procedural-vertex",
    summary: "paper 2 per vertex of a fine ground mesh, interpolated over its triangles",
    params: with_shared_params![Param {
        sweep: &["32", "64", "128", "256"],
        ..MESH_RESOLUTION
    },],
    fixed: &[("variant", "vertex")],
    ..DESCRIPTOR
};

/// Paper 2 per pixel of the map.
pub const SCREEN: Descriptor = Descriptor {
    name: "procedural-screen",
    summary: "paper 2 per pixel at the map's resolution, no filtering",
    params: with_shared_params![],
    fixed: &[("variant", "screen")],
    ..DESCRIPTOR
};

/// Paper 2 into a texture-space target, mipmapped.
pub const TEXTURE: Descriptor = Descriptor {
    name: "procedural-texture",
    summary: "paper 2 per pixel into a fixed texture-space target, mipmapped, resampled into the map",
    params: with_shared_params![
        Param {
            sweep: &["64", "128", "256", "512"],
            ..TARGET_RESOLUTION
        },
        ANISOTROPY,
    ],
    fixed: &[("variant", "texture")],
    ..DESCRIPTOR
};

const VARIANT: Param = Param::new(
    "variant",
    "variant",
    Kind::Choice(&["vertex", "screen", "texture"]),
    D::Text("screen"),
    "",
    "vertex: a fine ground mesh; screen: per map pixel; texture: a mipmapped target",
);
const MESH_RESOLUTION: Param = Param::new(
    "mesh_resolution",
    "mesh",
    Kind::int(1, MAX_MESH_RESOLUTION as i64),
    D::Int(128),
    "quads per side",
    "the vertex variant's ground mesh",
);
const TARGET_RESOLUTION: Param = Param::new(
    "target_resolution",
    "target",
    Kind::Int {
        min: 1,
        max: MAX_TARGET_RESOLUTION as i64,
        parity: None,
        power_of_two: true,
    },
    D::Int(256),
    "texels per side",
    "the texture variant's square render target (each mip level halves it)",
);
const ANISOTROPY: Param = Param::new(
    "anisotropy",
    "anisotropy",
    Kind::int(1, MAX_ANISOTROPY as i64),
    D::Int(MAX_ANISOTROPY as i64),
    "",
    "the texture variant's sampler clamp (1: plain trilinear)",
);
const IOR: Param = Param::new(
    "ior",
    "IOR",
    Kind::float(1.0, 3.0),
    D::Float(PAPER_IOR),
    "",
    "index of refraction of the water (the paper's 1.33333, not the scene's)",
);
const FOLLOW_SUN: Param = Param::new(
    "follow_sun",
    "follow the sun",
    Kind::Bool,
    D::Bool(false),
    "",
    "the scene's sun instead of the paper's overhead one",
);
const ABSORPTION: Param = Param::on(
    "absorption",
    "absorption",
    "exp(-K d) along the gathering ray, with the scene's K",
);
const SUN_DIAMETER: Param = Param::new(
    "sun_diameter",
    "sun diameter",
    Kind::float(0.0, 30.0),
    D::Float(SUN_DIAMETER_DEG),
    "degrees",
    "the sun disk of the generated light map",
);
const HALO_AREA_PARAM: Param = Param::new(
    "halo_area",
    "halo area",
    Kind::float(1.0, 1000.0),
    D::Float(HALO_AREA),
    "",
    "the halo's area over the sun disk's",
);
const HALO_LEVEL: Param = Param::new(
    "halo_level",
    "halo level",
    Kind::float(0.0, 1.0),
    D::Float(0.5),
    "",
    "halo brightness at the sun disk's edge, relative to the disk",
);
const LIGHT_MAP_RESOLUTION: Param = Param::new(
    "light_map_resolution",
    "light map",
    Kind::int(2, 4096),
    D::Int(128),
    "texels per side",
    "the generated light map",
);
const LIGHT_MAP: Param = Param::new(
    "light_map",
    "light map file",
    Kind::Path,
    D::Auto("generated from the sun and halo"),
    "",
    "a PNG light map instead of the generated one",
);
const LIGHT_MAP_EXTENT: Param = Param::new(
    "light_map_extent",
    "light map extent",
    Kind::float(0.0, 80.0),
    D::Auto("1.1 x the halo radius"),
    "degrees",
    "half-angle the PNG light map spans from its centre to its edges",
);
const GROUND: Param = Param::new(
    "ground",
    "ground",
    Kind::float(0.0, 1.0),
    D::Float(0.5),
    "",
    "share of the floor's light the sun map does not modulate (Listing 2's additive blend)",
);

/// The setup and heights a job gives paper 2 (both twins).
pub fn job_setup(job: &Job, table: &toml::Table) -> Result<(ProceduralSetup, Grid)> {
    job.note_floor_only(&DESCRIPTOR);
    let params = ProceduralCausticsParams::from_table(table)?;
    let (width, height) = job.size();
    job.with_surface(DESCRIPTOR.name, |w, surface| {
        let setup = ProceduralSetup::new(
            &params,
            width,
            height,
            w.size,
            w.depth,
            w.absorption,
            w.wrap,
            job.light(),
        )?
        .with_floor(job.floor(), None);
        let heights = job_heights(w, surface, &setup);
        Ok((setup, heights))
    })
}

/// The height grid paper 2 reads (the job carries the frozen surface, not its time, so the
/// paper's wave function too is read through a grid): a file's own samples, or the surface sampled
/// at least as finely as the lattice the variant evaluates on (the map, the mesh's vertices, or the
/// texture-space target).
pub fn job_heights(
    water: &crate::scene::Water,
    surface: &dyn Surface,
    setup: &ProceduralSetup,
) -> Grid {
    let n = match setup.variant {
        Variant::Vertex => setup.mesh + 1,
        Variant::Screen => 0,
        Variant::Texture => setup.target,
    };
    match &water.source {
        crate::scene::WaterSource::HeightField(g) => g.clone(),
        _ => {
            crate::water::sample_grid(surface, setup.width.max(n), setup.height.max(n), water.size)
        }
    }
}

fn run_cpu(
    job: &Job,
    table: &toml::Table,
    _progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<JobOutput> {
    let (setup, heights) = job_setup(job, table)?;
    let deposit = caustics(&setup, &SurfaceInput::Grid(&heights));
    Ok(JobOutput::received(
        setup.received_with_light(deposit),
        None,
    ))
}

/// Which of the paper's three implementations runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Variant {
    /// Per vertex of a fine ground mesh, interpolated over its triangles.
    Vertex,
    /// Per pixel at the map's resolution, no filtering.
    #[default]
    Screen,
    /// Per pixel into a fixed texture-space target, mipmapped, resampled into the map.
    Texture,
}

impl Variant {
    /// Every variant, in the order of the `variant` parameter's choices.
    pub const ALL: [Variant; 3] = [Variant::Vertex, Variant::Screen, Variant::Texture];

    /// Its word in the table (`variant = "vertex"`) and in its entry's name
    /// (`procedural-vertex`).
    pub fn name(self) -> &'static str {
        ["vertex", "screen", "texture"][self as usize]
    }
}

/// The technique's parameters, `[caustics.procedural]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProceduralCausticsParams {
    /// Which of the paper's three implementations runs (default: per pixel of the map).
    pub variant: Variant,
    /// Quads per side of the ground mesh of the vertex variant.
    pub mesh_resolution: u32,
    /// Side of the texture variant's square render target (a power of two).
    pub target_resolution: u32,
    /// The texture variant's sampler: its anisotropy clamp (1: plain trilinear).
    pub anisotropy: u32,
    /// Index of refraction of the water (the paper's 1.33333, not the scene's).
    pub ior: f64,
    /// Use the scene's sun instead of the paper's overhead one.
    pub follow_sun: bool,
    /// `exp(−K d)` along the gathering ray, with the scene's `K`.
    pub absorption: bool,
    /// Sun disk diameter, degrees.
    pub sun_diameter: f64,
    /// Halo area over the sun disk's area.
    pub halo_area: f64,
    /// Halo brightness at the sun disk's edge, relative to the disk.
    pub halo_level: f64,
    /// Texels per side of the generated light map.
    pub light_map_resolution: u32,
    /// A PNG light map instead of the generated one (relative to the working directory).
    pub light_map: Option<PathBuf>,
    /// Half-angle, degrees, that the PNG light map spans from its centre to its edges (default: the
    /// generated map's, 1.1 × the halo radius).
    pub light_map_extent: Option<f64>,
    /// The paper blends its caustic *additively* over the ground as already lit ("color.rgb +=
    /// tex2D(GroundMap)", Listing 2). In relative irradiance: `ground + (1 − ground) · caustic`, so
    /// flat water still gives 1 and `ground` is the share of the floor's light that the sun map does
    /// not modulate. 0 is the bare sun-map lookup.
    pub ground: f64,
}

impl Default for ProceduralCausticsParams {
    fn default() -> Self {
        ProceduralCausticsParams {
            variant: Variant::Screen,
            mesh_resolution: 128,
            target_resolution: 256,
            anisotropy: MAX_ANISOTROPY,
            ior: PAPER_IOR,
            follow_sun: false,
            absorption: true,
            sun_diameter: SUN_DIAMETER_DEG,
            halo_area: HALO_AREA,
            halo_level: 0.5,
            light_map_resolution: 128,
            light_map: None,
            light_map_extent: None,
            ground: 0.5,
        }
    }
}

fn field(name: &str, problem: String) -> Error {
    Error::field(format!("caustics.procedural.{name}"), problem)
}

impl ProceduralCausticsParams {
    /// The `procedural` table of `table` (a scene's `[caustics]`), defaults where it is absent,
    /// checked as [`validate`](Self::validate) does.
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        read_params(table, &DESCRIPTOR, Self::validate)
    }

    /// Check every value against its parameter's range; the error names the first field out of
    /// it. The refractive index and the sun's and the light map's angles exclude their bounds.
    pub fn validate(&self) -> Result<()> {
        check_params(&DESCRIPTOR, self)?;
        if !(self.ior > 1.0 && self.ior < 3.0) {
            return Err(field(
                "ior",
                format!("must be between 1 and 3, got {}", self.ior),
            ));
        }
        if !(self.sun_diameter > 0.0 && self.sun_diameter < 30.0) {
            return Err(field(
                "sun_diameter",
                format!(
                    "must be between 0 and 30 degrees, got {}",
                    self.sun_diameter
                ),
            ));
        }
        if let Some(e) = self.light_map_extent
            && !(e > 0.0 && e < 80.0)
        {
            return Err(field(
                "light_map_extent",
                format!("must be between 0 and 80 degrees, got {e}"),
            ));
        }
        Ok(())
    }

    /// Radii of the sun disk and of the halo, radians.
    pub fn sun_radii(&self) -> (f64, f64) {
        let r_s = (0.5 * self.sun_diameter).to_radians();
        (r_s, r_s * self.halo_area.sqrt())
    }
}

/// Everything the passes share, derived once from the scene (the GPU side uploads the same numbers
/// as its uniform block).
#[derive(Clone, Debug)]
pub struct ProceduralSetup {
    /// Which of the paper's three implementations runs.
    pub variant: Variant,
    /// Texels of the caustics map along x.
    pub width: usize,
    /// Texels of the caustics map along y.
    pub height: usize,
    /// Side of the square `[0, size]²` the water and the map cover, world units.
    pub size: f64,
    /// The water's rest level above the floor plane z = 0, world units.
    pub depth: f64,
    /// The water's heights repeat across the square's edges (else they are clamped there).
    pub wrap: bool,
    /// Quads per side of the vertex variant's mesh.
    pub mesh: usize,
    /// Side of the texture variant's target.
    pub target: usize,
    /// The texture variant's sampler's anisotropy clamp.
    pub anisotropy: u32,
    /// Water to air, `η = n_water / n_air`.
    pub ior: f64,
    /// The sun frame: `[e1, e2, s]`, `s` the unit direction toward the sun, `e1`, `e2` its tangent
    /// plane (`X`, `Y` for the overhead sun).
    pub sun_frame: [DVec3; 3],
    /// Unit direction of the gathering ray from the floor up to the surface.
    pub up: DVec3,
    /// `K` per channel, zero without the absorption option.
    pub absorption: DVec3,
    /// [`ProceduralCausticsParams::ground`].
    pub ground: f64,
    /// The sun / light map the refracted gathering rays look up.
    pub light: LightMap,
    /// The terrain the gathering rays start from ([`ProceduralSetup::with_floor`]).
    pub receivers: Option<Shared>,
}

impl ProceduralSetup {
    /// `light` is the direction the sunlight travels (used with `follow_sun`).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        params: &ProceduralCausticsParams,
        width: usize,
        height: usize,
        size: f64,
        depth: f64,
        absorption: DVec3,
        wrap: bool,
        light: DVec3,
    ) -> Result<Self> {
        params.validate()?;
        let light = super::check_inputs(width, height, light)?;
        let (sun, up) = if params.follow_sun {
            let t0 = refract(light, DVec3::Z, 1.0 / params.ior)
                .expect("air to water never reflects totally");
            (-light, -t0)
        } else {
            (DVec3::Z, DVec3::Z)
        };
        let e1 = DVec3::Y.cross(sun).normalize();
        let e2 = sun.cross(e1);
        Ok(ProceduralSetup {
            variant: params.variant,
            width,
            height,
            size,
            depth,
            wrap,
            mesh: params.mesh_resolution as usize,
            target: params.target_resolution as usize,
            anisotropy: params.anisotropy,
            ior: params.ior,
            sun_frame: [e1, e2, sun],
            up,
            absorption: if params.absorption {
                absorption
            } else {
                DVec3::ZERO
            },
            ground: params.ground,
            light: LightMap::from_params(params)?,
            receivers: None,
        })
    }

    /// The gathering rays start from `floor`'s terrain where it has one. Every point on a line
    /// along the technique's light (`−up`) gathers through the same surface point, so the
    /// caustic is the flat floor's at the point's light-space position: the passes evaluate the
    /// light-space map as on the plane `z = 0`, and the receivers' lookup gives each floor texel
    /// its value, its face's cosine against the light, the depth test, and the absorption along
    /// its own path (`(depth − z) / up_z`, the rest level's: the paper's `h` is left out there).
    /// The receivers' map is `previous` where nothing it depends on changed.
    pub fn with_floor(mut self, floor: &crate::scene::Floor, previous: Option<&Shared>) -> Self {
        self.receivers = Shared::of_floor(
            previous, floor, true, self.size, self.depth, -self.up, self.width,
        );
        self
    }

    /// `K` per channel along each gathering ray: zero over receivers, whose lookup attenuates.
    pub fn gathered_absorption(&self) -> DVec3 {
        match self.receivers {
            Some(_) => DVec3::ZERO,
            None => self.absorption,
        }
    }

    /// The passes' map as the floor receives it: itself on the plane `z = 0`, else looked up per
    /// floor texel through the receivers.
    pub fn received(&self, map: CausticsMap) -> CausticsMap {
        crate::receivers::received(map, self.receivers.as_ref(), self.wrap, self.absorption)
    }

    /// [`received`](Self::received), with the deposit where objects are among the receivers.
    pub fn received_with_light(&self, map: CausticsMap) -> (CausticsMap, Option<LightSpace>) {
        let receivers = self.receivers.as_ref().map(|r| &r.0);
        received_with_light(map, receivers, self.wrap, self.absorption)
    }

    /// Mip levels of the texture variant's target, level 0 included.
    pub fn mip_levels(&self) -> usize {
        self.target.trailing_zeros() as usize + 1
    }
}

/// The whole technique on the CPU, in the setup's variant.
pub fn caustics(setup: &ProceduralSetup, water: &SurfaceInput) -> CausticsMap {
    match setup.variant {
        Variant::Screen => CausticsMap {
            width: setup.width,
            height: setup.height,
            size: setup.size,
            texels: per_pixel(setup, water, setup.width, setup.height),
        },
        Variant::Vertex => rasterise(setup, &vertex_values(setup, water)),
        Variant::Texture => {
            let level0 = target_pass(setup, water);
            resample(setup, &mip_chain(level0, setup.target))
        }
    }
}
