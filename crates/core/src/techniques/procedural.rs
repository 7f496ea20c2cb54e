//! Technique `procedural`: "Inexpensive Underwater Caustics Using Cg" (Sánchez-Crespo Dalmau, 2003),
//! the CPU twin of `caustics-gpu`'s `procedural` module, pass for pass.
//!
//! # The method (paper, "Our Approach")
//! An aesthetics-driven simplification of backward ray tracing. From each ground point `P` one ray
//! goes straight up ("we project it vertically until we reach the wave point located right on top of
//! it") to the water surface `z = depth + h(P.xy)`. The normal there comes from the surface's exact
//! gradient (the paper's Cg version differentiates its wave function instead of taking finite
//! differences): [`height_field_normal`]. The ray is refracted from the water up into the air with
//! "Snell's law reversed" and the paper's IOR 1.33333: incident `(0, 0, 1)`, normal `−n` (facing the
//! ray), `η = n_water / n_air = ior`; total internal reflection gives no light. The refracted
//! direction `R` then looks up a *sun map*: "the closer to the vertical, the more light that comes
//! from that direction into the ocean".
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
//! # Where it departs from the reference
//! By design, everywhere: the caustic is not the focusing of flux but the brightness of the sky seen
//! straight up through the surface. Bright spots sit where the surface is nearly flat (its crests,
//! troughs and saddles) rather than where the waves focus the light a depth below; the map's mean is
//! not the incident flux; the pattern does not move with the depth (only the absorption does). It
//! is the look of caustics, at a per-point cost.

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::optics::{height_field_normal, refract};
use crate::water::Surface;
use crate::water::procedural::Procedural;

/// The paper's index of refraction of water.
pub const PAPER_IOR: f64 = 1.33333;
/// The sun disk's angular diameter, degrees (paper).
pub const SUN_DIAMETER_DEG: f64 = 0.53;
/// The halo's area over the sun disk's (paper: "about ten times larger").
pub const HALO_AREA: f64 = 10.0;
/// The light map spans this much more than the halo's radius, so its border texels are dark.
pub const LIGHT_MAP_MARGIN: f64 = 1.1;
pub const MAX_MESH_RESOLUTION: u32 = 2048;
pub const MAX_TARGET_RESOLUTION: u32 = 8192;
/// The sampler's anisotropy clamp, and the CPU twin's largest tap count.
pub const MAX_ANISOTROPY: u32 = 16;

use super::describe::{
    Change, Descriptor, Kind, Param, ParamDefault as D, Receiver, serde_defaults,
};
use super::{Input, Job, Made};

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
    flat_floor: Some("lights a flat floor at a constant depth (paper 2, \"Our Approach\")"),
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
    Change::Reconfigure,
);
const MESH_RESOLUTION: Param = Param::new(
    "mesh_resolution",
    "mesh",
    Kind::int(1, MAX_MESH_RESOLUTION as i64),
    D::Int(128),
    "quads per side",
    "the vertex variant's ground mesh",
    Change::Reconfigure,
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
    Change::Reconfigure,
);
const ANISOTROPY: Param = Param::new(
    "anisotropy",
    "anisotropy",
    Kind::int(1, MAX_ANISOTROPY as i64),
    D::Int(MAX_ANISOTROPY as i64),
    "",
    "the texture variant's sampler clamp (1: plain trilinear)",
    Change::Reconfigure,
);
const IOR: Param = Param::new(
    "ior",
    "IOR",
    Kind::float(1.0, 3.0),
    D::Float(PAPER_IOR),
    "",
    "index of refraction of the water (the paper's 1.33333, not the scene's)",
    Change::Uniform,
);
const FOLLOW_SUN: Param = Param::new(
    "follow_sun",
    "follow the sun",
    Kind::Bool,
    D::Bool(false),
    "",
    "the scene's sun instead of the paper's overhead one",
    Change::Uniform,
);
const ABSORPTION: Param = Param::new(
    "absorption",
    "absorption",
    Kind::Bool,
    D::Bool(true),
    "",
    "exp(-K d) along the gathering ray, with the scene's K",
    Change::Uniform,
);
const SUN_DIAMETER: Param = Param::new(
    "sun_diameter",
    "sun diameter",
    Kind::float(0.0, 30.0),
    D::Float(SUN_DIAMETER_DEG),
    "degrees",
    "the sun disk of the generated light map",
    Change::Reconfigure,
);
const HALO_AREA_PARAM: Param = Param::new(
    "halo_area",
    "halo area",
    Kind::float(1.0, 1000.0),
    D::Float(HALO_AREA),
    "",
    "the halo's area over the sun disk's",
    Change::Reconfigure,
);
const HALO_LEVEL: Param = Param::new(
    "halo_level",
    "halo level",
    Kind::float(0.0, 1.0),
    D::Float(0.5),
    "",
    "halo brightness at the sun disk's edge, relative to the disk",
    Change::Reconfigure,
);
const LIGHT_MAP_RESOLUTION: Param = Param::new(
    "light_map_resolution",
    "light map",
    Kind::int(2, 4096),
    D::Int(128),
    "texels per side",
    "the generated light map",
    Change::Reconfigure,
);
const LIGHT_MAP: Param = Param::new(
    "light_map",
    "light map file",
    Kind::Path,
    D::Auto("generated from the sun and halo"),
    "",
    "a PNG light map instead of the generated one",
    Change::Reconfigure,
);
const LIGHT_MAP_EXTENT: Param = Param::new(
    "light_map_extent",
    "light map extent",
    Kind::float(0.0, 80.0),
    D::Auto("1.1 x the halo radius"),
    "degrees",
    "half-angle the PNG light map spans from its centre to its edges",
    Change::Reconfigure,
);
const GROUND: Param = Param::new(
    "ground",
    "ground",
    Kind::float(0.0, 1.0),
    D::Float(0.5),
    "",
    "share of the floor's light the sun map does not modulate (Listing 2's additive blend)",
    Change::Uniform,
);

/// The setup and heights a job gives paper 2 (both twins).
pub fn job_setup(job: &Job, table: &toml::Table) -> Result<(ProceduralSetup, Grid)> {
    job.flat_floor(&DESCRIPTOR)?;
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
        )?;
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
) -> Result<Made> {
    let (setup, heights) = job_setup(job, table)?;
    Ok(Made::floor(
        caustics(&setup, &SurfaceInput::Grid(&heights)),
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
    pub const ALL: [Variant; 3] = [Variant::Vertex, Variant::Screen, Variant::Texture];

    pub fn name(self) -> &'static str {
        match self {
            Variant::Vertex => "vertex",
            Variant::Screen => "screen",
            Variant::Texture => "texture",
        }
    }

    pub fn parse(s: &str) -> Option<Variant> {
        Variant::ALL.into_iter().find(|v| v.name() == s)
    }
}

/// The technique's parameters, `[caustics.procedural]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProceduralCausticsParams {
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
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        let p: ProceduralCausticsParams = match table.get("procedural") {
            Some(v) => v
                .clone()
                .try_into()
                .map_err(|e| Error::field("caustics.procedural", e.to_string()))?,
            None => ProceduralCausticsParams::default(),
        };
        p.validate()?;
        Ok(p)
    }

    pub fn validate(&self) -> Result<()> {
        if !(0.0..=1.0).contains(&self.ground) {
            return Err(field(
                "ground",
                format!("must be between 0 and 1, got {}", self.ground),
            ));
        }
        if self.mesh_resolution == 0 || self.mesh_resolution > MAX_MESH_RESOLUTION {
            return Err(field(
                "mesh_resolution",
                format!(
                    "must be between 1 and {MAX_MESH_RESOLUTION} quads per side, got {}",
                    self.mesh_resolution
                ),
            ));
        }
        if !self.target_resolution.is_power_of_two()
            || self.target_resolution > MAX_TARGET_RESOLUTION
        {
            return Err(field(
                "target_resolution",
                format!(
                    "must be a power of two up to {MAX_TARGET_RESOLUTION} (each mip level halves it), got {}",
                    self.target_resolution
                ),
            ));
        }
        if !(1..=MAX_ANISOTROPY).contains(&self.anisotropy) {
            return Err(field(
                "anisotropy",
                format!(
                    "must be between 1 (trilinear) and {MAX_ANISOTROPY}, got {}",
                    self.anisotropy
                ),
            ));
        }
        if !(self.ior.is_finite() && self.ior > 1.0 && self.ior < 3.0) {
            return Err(field(
                "ior",
                format!("must be between 1 and 3, got {}", self.ior),
            ));
        }
        if !(self.sun_diameter.is_finite() && self.sun_diameter > 0.0 && self.sun_diameter < 30.0) {
            return Err(field(
                "sun_diameter",
                format!(
                    "must be between 0 and 30 degrees, got {}",
                    self.sun_diameter
                ),
            ));
        }
        if !(self.halo_area.is_finite() && self.halo_area >= 1.0 && self.halo_area <= 1000.0) {
            return Err(field(
                "halo_area",
                format!(
                    "must be between 1 (no halo) and 1000 times the sun disk's area, got {}",
                    self.halo_area
                ),
            ));
        }
        if !(self.halo_level.is_finite() && (0.0..=1.0).contains(&self.halo_level)) {
            return Err(field(
                "halo_level",
                format!("must be between 0 and 1, got {}", self.halo_level),
            ));
        }
        if !(2..=4096).contains(&self.light_map_resolution) {
            return Err(field(
                "light_map_resolution",
                format!(
                    "must be between 2 and 4096, got {}",
                    self.light_map_resolution
                ),
            ));
        }
        if let Some(e) = self.light_map_extent
            && !(e.is_finite() && e > 0.0 && e < 80.0)
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

/// The sun / light map over the tangent plane of the direction toward the sun: texel `(r, c)` is
/// centred at `uv = (−E + (c + ½) 2E / width, −E + (r + ½) 2E / height)`, read bilinearly, 0 beyond.
#[derive(Clone, Debug, PartialEq)]
pub struct LightMap {
    pub width: usize,
    pub height: usize,
    /// `E`: the map spans `uv ∈ [−E, E]²`, the tangent of the half-angle it covers.
    pub extent: f64,
    /// Row-major, row 0 at `v = −E`; normalised to 1 in the sun's direction.
    pub texels: Vec<f32>,
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl LightMap {
    /// The light map the parameters ask for: a PNG, or the paper's sun disk and halo.
    pub fn from_params(p: &ProceduralCausticsParams) -> Result<LightMap> {
        match &p.light_map {
            Some(path) => {
                let extent = match p.light_map_extent {
                    Some(deg) => deg.to_radians().tan(),
                    None => (LIGHT_MAP_MARGIN * p.sun_radii().1).tan(),
                };
                LightMap::load(path, extent)
            }
            None => Ok(LightMap::sun(p)),
        }
    }

    /// The brightness of the sky at angle `theta` (radians) from the sun: 1 in the disk, the halo's
    /// smooth fall from `halo_level` to 0 beyond it.
    pub fn profile(p: &ProceduralCausticsParams, theta: f64) -> f64 {
        let (r_s, r_h) = p.sun_radii();
        if theta <= r_s {
            1.0
        } else {
            p.halo_level * (1.0 - smoothstep(r_s, r_h, theta))
        }
    }

    /// The paper's sun: the disk and its halo, sampled at the texel centres.
    pub fn sun(p: &ProceduralCausticsParams) -> LightMap {
        let n = p.light_map_resolution as usize;
        let extent = (LIGHT_MAP_MARGIN * p.sun_radii().1).tan();
        let texel = 2.0 * extent / n as f64;
        let texels = (0..n * n)
            .map(|k| {
                let uv = DVec2::new(
                    -extent + ((k % n) as f64 + 0.5) * texel,
                    -extent + ((k / n) as f64 + 0.5) * texel,
                );
                LightMap::profile(p, uv.length().atan()) as f32
            })
            .collect();
        LightMap {
            width: n,
            height: n,
            extent,
            texels,
        }
        .normalised(Path::new("<generated sun>"))
        .expect("the generated sun is bright at its centre")
    }

    /// A greyscale reading of a PNG (any colour type; luma in [0, 1], no sRGB decoding: a light map
    /// is data), normalised to 1 at its centre.
    pub fn load(path: &Path, extent: f64) -> Result<LightMap> {
        let img = image::open(path).map_err(|e| Error::bad_file(path, e.to_string()))?;
        let luma = img.to_luma32f();
        let (width, height) = (luma.width() as usize, luma.height() as usize);
        if width < 2 || height < 2 {
            return Err(Error::bad_file(
                path,
                "a light map needs at least 2 x 2 texels",
            ));
        }
        LightMap {
            width,
            height,
            extent,
            texels: luma.into_raw(),
        }
        .normalised(path)
    }

    fn normalised(mut self, path: &Path) -> Result<LightMap> {
        let c = self.sample(DVec2::ZERO);
        if !(c > 0.0 && c.is_finite()) {
            return Err(Error::bad_file(
                path,
                format!(
                    "the light map is {c} at its centre, the sun's own direction: it must be bright there (the map is normalised to 1 at the centre)"
                ),
            ));
        }
        for t in &mut self.texels {
            *t = (*t as f64 / c) as f32;
        }
        Ok(self)
    }

    fn texel(&self, r: i64, c: i64) -> f64 {
        if r < 0 || c < 0 || r >= self.height as i64 || c >= self.width as i64 {
            0.0
        } else {
            self.texels[r as usize * self.width + c as usize] as f64
        }
    }

    /// Bilinear lookup at `uv`, 0 beyond the map (WGSL `light_lookup`).
    pub fn sample(&self, uv: DVec2) -> f64 {
        let t = (uv / self.extent * 0.5 + 0.5) * DVec2::new(self.width as f64, self.height as f64)
            - 0.5;
        let b = t.floor();
        let f = t - b;
        let (c, r) = (b.x as i64, b.y as i64);
        let top = self.texel(r, c) * (1.0 - f.x) + self.texel(r, c + 1) * f.x;
        let bottom = self.texel(r + 1, c) * (1.0 - f.x) + self.texel(r + 1, c + 1) * f.x;
        top * (1.0 - f.y) + bottom * f.y
    }
}

/// The water the technique reads.
#[derive(Clone, Copy)]
pub enum SurfaceInput<'a> {
    /// The paper's wave function, with its analytic gradient.
    Wave(&'a Procedural),
    /// A height grid over the scene square, through its bicubic interpolant (wrapped or clamped by
    /// the setup's `wrap`).
    Grid(&'a Grid),
}

impl SurfaceInput<'_> {
    /// Height and gradient at `p` (WGSL `water_at`).
    pub fn height_gradient(&self, p: DVec2, setup: &ProceduralSetup) -> (f64, DVec2) {
        match self {
            SurfaceInput::Wave(w) => w.height_gradient(p),
            SurfaceInput::Grid(g) => g.sample(
                p,
                setup.size,
                if setup.wrap { Edge::Wrap } else { Edge::Clamp },
            ),
        }
    }
}

/// Everything the passes share, derived once from the scene (the GPU side uploads the same numbers
/// as its uniform block).
#[derive(Clone, Debug)]
pub struct ProceduralSetup {
    pub variant: Variant,
    pub width: usize,
    pub height: usize,
    pub size: f64,
    pub depth: f64,
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
    pub light: LightMap,
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
        })
    }

    /// Mip levels of the texture variant's target, level 0 included.
    pub fn mip_levels(&self) -> usize {
        self.target.trailing_zeros() as usize + 1
    }
}

/// One gathering ray, for inspection and tests.
#[derive(Clone, Copy, Debug)]
pub struct Trace {
    /// Where the ray meets the rest level (the point whose height and normal are read).
    pub surface_point: DVec2,
    pub height: f64,
    pub normal: DVec3,
    /// The direction refracted into the air, `None` on total internal reflection.
    pub refracted: Option<DVec3>,
    /// Its light-map coordinates, `None` where it points away from the sun's hemisphere.
    pub uv: Option<DVec2>,
}

/// Follow the gathering ray from floor point `p` to the surface and out into the air.
pub fn trace(setup: &ProceduralSetup, water: &SurfaceInput, p: DVec2) -> Trace {
    let up = setup.up;
    // Line-plane intercept with the rest level (exact for the vertical ray).
    let s = p + up.truncate() * (setup.depth / up.z);
    let (h, grad) = water.height_gradient(s, setup);
    let normal = height_field_normal(grad);
    // Snell reversed: from the water (η = ior) up into the air, the normal facing the ray.
    let refracted = refract(up, -normal, setup.ior);
    let uv = refracted.and_then(|r| {
        let [e1, e2, sun] = setup.sun_frame;
        let z = r.dot(sun);
        (z > 0.0).then(|| DVec2::new(r.dot(e1), r.dot(e2)) / z)
    });
    Trace {
        surface_point: s,
        height: h,
        normal,
        refracted,
        uv,
    }
}

/// The caustic at floor point `p`, per RGB channel: the light map in the refracted direction times
/// the absorption along the way (WGSL `procedural_caustic`).
pub fn caustic_at(setup: &ProceduralSetup, water: &SurfaceInput, p: DVec2) -> [f32; 3] {
    let t = trace(setup, water, p);
    let e = t.uv.map_or(0.0, |uv| setup.light.sample(uv));
    let d = (setup.depth + t.height) / setup.up.z;
    let a = (-setup.absorption * d).exp() * (setup.ground + (1.0 - setup.ground) * e);
    [a.x as f32, a.y as f32, a.z as f32]
}

/// Per pixel: the caustic at the centre of every texel of a `width x height` lattice over the floor
/// square, row 0 at y = 0 (the screen pass at the map's size, the target pass at the target's).
pub fn per_pixel(
    setup: &ProceduralSetup,
    water: &SurfaceInput,
    width: usize,
    height: usize,
) -> Vec<[f32; 3]> {
    (0..height)
        .into_par_iter()
        .flat_map_iter(|i| {
            (0..width).map(move |j| {
                let p = DVec2::new(
                    (j as f64 + 0.5) / width as f64,
                    (i as f64 + 0.5) / height as f64,
                ) * setup.size;
                caustic_at(setup, water, p)
            })
        })
        .collect()
}

/// Vertex variant, the vertex shader's work: the caustic at every vertex `(k, l)` of the mesh, at
/// `(k, l) size / mesh`, row-major over `l` (`(mesh + 1)²` values).
pub fn vertex_values(setup: &ProceduralSetup, water: &SurfaceInput) -> Vec<[f32; 3]> {
    let n = setup.mesh;
    (0..=n)
        .into_par_iter()
        .flat_map_iter(|l| {
            (0..=n).map(move |k| {
                let p = DVec2::new(k as f64, l as f64) / n as f64 * setup.size;
                caustic_at(setup, water, p)
            })
        })
        .collect()
}

/// Vertex variant, the rasteriser's work: the mesh's values interpolated linearly over its
/// triangles at every map pixel centre. Quad `(k, l)` is split along its diagonal from vertex
/// `(k, l)` to `(k + 1, l + 1)`; on the diagonal both triangles agree.
pub fn rasterise(setup: &ProceduralSetup, values: &[[f32; 3]]) -> CausticsMap {
    let n = setup.mesh;
    let (w, h) = (setup.width, setup.height);
    let at = |k: usize, l: usize| values[l * (n + 1) + k];
    let texels = (0..h)
        .into_par_iter()
        .flat_map_iter(|i| {
            (0..w).map(move |j| {
                let g = DVec2::new(
                    (j as f64 + 0.5) / w as f64 * n as f64,
                    (i as f64 + 0.5) / h as f64 * n as f64,
                );
                let (k, l) = (
                    (g.x.floor() as usize).min(n - 1),
                    (g.y.floor() as usize).min(n - 1),
                );
                let (fx, fy) = (g.x - k as f64, g.y - l as f64);
                let (v00, v10, v01, v11) = (at(k, l), at(k + 1, l), at(k, l + 1), at(k + 1, l + 1));
                std::array::from_fn(|c| {
                    let (a, b, d, e) = (v00[c] as f64, v10[c] as f64, v01[c] as f64, v11[c] as f64);
                    let v = if fx >= fy {
                        a + fx * (b - a) + fy * (e - b)
                    } else {
                        a + fy * (d - a) + fx * (e - d)
                    };
                    v as f32
                })
            })
        })
        .collect();
    CausticsMap {
        width: w,
        height: h,
        size: setup.size,
        texels,
    }
}

/// Texture variant, the mip passes: level `k + 1` is the 2 x 2 box average of level `k`
/// (`(a + b + c + d) · ¼` in f32, in the order `downsample.wgsl` sums). Level 0 is `target²`.
pub fn mip_chain(level0: Vec<[f32; 3]>, target: usize) -> Vec<Vec<[f32; 3]>> {
    let map = crate::map::CausticsMap {
        width: target,
        height: target,
        size: 1.0,
        texels: level0,
    };
    map.pyramid().levels.into_iter().map(|l| l.texels).collect()
}

/// The sampler's level of detail and anisotropic taps for reading a `target²` texture into a
/// `width x height` map: `(λ, taps, major axis is x)`. The CPU twin's reading of Vulkan's rule for
/// an anisotropic sampler (the hardware's filter itself is implementation-defined): with `ρ_x`,
/// `ρ_y` the footprint of one map texel in target texels, `η = min(ρ_max / ρ_min, anisotropy)`,
/// `λ = log₂(ρ_max / η)` clamped to the chain, and `⌈η⌉` trilinear taps spread over the footprint's
/// major axis; a footprint smaller than a texel both ways is magnified: one bilinear tap of level 0.
pub fn sampling_footprint(setup: &ProceduralSetup) -> (f64, usize, bool) {
    let px = setup.target as f64 / setup.width as f64;
    let py = setup.target as f64 / setup.height as f64;
    let (major, minor) = (px.max(py), px.min(py));
    if major <= 1.0 {
        return (0.0, 1, px >= py);
    }
    let eta = (major / minor).min(setup.anisotropy as f64);
    let lambda = (major / eta)
        .log2()
        .clamp(0.0, (setup.mip_levels() - 1) as f64);
    (lambda, eta.ceil() as usize, px >= py)
}

fn bilinear(level: &[[f32; 3]], n: usize, uv: DVec2, wrap: bool) -> DVec3 {
    let t = uv * n as f64 - 0.5;
    let b = t.floor();
    let f = t - b;
    let fetch = |r: i64, c: i64| {
        let (r, c) = if wrap {
            (r.rem_euclid(n as i64), c.rem_euclid(n as i64))
        } else {
            (r.clamp(0, n as i64 - 1), c.clamp(0, n as i64 - 1))
        };
        let v = level[r as usize * n + c as usize];
        DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
    };
    let (c, r) = (b.x as i64, b.y as i64);
    let top = fetch(r, c).lerp(fetch(r, c + 1), f.x);
    let bottom = fetch(r + 1, c).lerp(fetch(r + 1, c + 1), f.x);
    top.lerp(bottom, f.y)
}

/// Trilinear lookup at `uv` (in [0, 1]² over the target) and level of detail `lambda`.
pub fn trilinear(
    levels: &[Vec<[f32; 3]>],
    target: usize,
    uv: DVec2,
    lambda: f64,
    wrap: bool,
) -> DVec3 {
    let l0 = lambda.floor() as usize;
    let f = lambda - l0 as f64;
    let a = bilinear(&levels[l0], target >> l0, uv, wrap);
    if f > 0.0 && l0 + 1 < levels.len() {
        a.lerp(bilinear(&levels[l0 + 1], target >> (l0 + 1), uv, wrap), f)
    } else {
        a
    }
}

/// Texture variant, the final pass: every map texel reads the mip chain at its centre with its
/// footprint (one map texel), trilinearly, with `taps` samples along the footprint's major axis.
pub fn resample(setup: &ProceduralSetup, levels: &[Vec<[f32; 3]>]) -> CausticsMap {
    let (w, h) = (setup.width, setup.height);
    let (lambda, taps, major_x) = sampling_footprint(setup);
    let axis = if major_x {
        DVec2::new(1.0 / w as f64, 0.0)
    } else {
        DVec2::new(0.0, 1.0 / h as f64)
    };
    let texels = (0..h)
        .into_par_iter()
        .flat_map_iter(|i| {
            (0..w).map(move |j| {
                let uv = DVec2::new((j as f64 + 0.5) / w as f64, (i as f64 + 0.5) / h as f64);
                let mut sum = DVec3::ZERO;
                for k in 0..taps {
                    let o = (k as f64 + 0.5) / taps as f64 - 0.5;
                    sum += trilinear(levels, setup.target, uv + axis * o, lambda, setup.wrap);
                }
                let v = sum / taps as f64;
                [v.x as f32, v.y as f32, v.z as f32]
            })
        })
        .collect();
    CausticsMap {
        width: w,
        height: h,
        size: setup.size,
        texels,
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
            let level0 = per_pixel(setup, water, setup.target, setup.target);
            resample(setup, &mip_chain(level0, setup.target))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::water::procedural::ProceduralParams;

    fn setup(params: &ProceduralCausticsParams, res: usize, light: DVec3) -> ProceduralSetup {
        ProceduralSetup::new(params, res, res, 1.0, 0.4, DVec3::ZERO, true, light).unwrap()
    }

    fn waves(n: usize) -> Grid {
        Grid::from_fn(n, n, |i, j| {
            let x = (j as f64 + 0.5) / n as f64;
            let y = (i as f64 + 0.5) / n as f64;
            let tau = std::f64::consts::TAU;
            (0.002 * (tau * (3.0 * x + y)).sin() + 0.001 * (tau * (-2.0 * x + 5.0 * y) + 1.0).sin())
                as f32
        })
    }

    /// The additive blend is affine in the bare sun-map lookup: `ground + (1 − ground) · bare`.
    #[test]
    fn the_caustic_is_added_over_the_lit_ground() {
        let g = waves(32);
        let bare = ProceduralCausticsParams {
            ground: 0.0,
            absorption: false,
            ..Default::default()
        };
        let blended = ProceduralCausticsParams {
            ground: 0.6,
            ..bare.clone()
        };
        let a = caustics(&setup(&bare, 24, DVec3::NEG_Z), &SurfaceInput::Grid(&g));
        let b = caustics(&setup(&blended, 24, DVec3::NEG_Z), &SurfaceInput::Grid(&g));
        for (x, y) in a.texels.iter().zip(&b.texels) {
            assert!(
                (0.6 + 0.4 * x[0] - y[0]).abs() < 1e-5,
                "{} vs {}",
                x[0],
                y[0]
            );
        }
        let e = ProceduralCausticsParams {
            ground: 1.5,
            ..Default::default()
        }
        .validate();
        assert!(
            e.unwrap_err()
                .to_string()
                .contains("caustics.procedural.ground")
        );
    }

    #[test]
    fn flat_water_gives_one_everywhere_in_every_variant() {
        let flat = Grid::new(16, 16);
        for variant in Variant::ALL {
            for follow_sun in [false, true] {
                let params = ProceduralCausticsParams {
                    variant,
                    follow_sun,
                    mesh_resolution: 10,
                    target_resolution: 64,
                    ..Default::default()
                };
                let s = ProceduralSetup::new(
                    &params,
                    40,
                    24,
                    2.0,
                    0.5,
                    DVec3::ZERO,
                    false,
                    DVec3::new(0.3, 0.1, -1.0),
                )
                .unwrap();
                let m = caustics(&s, &SurfaceInput::Grid(&flat));
                let worst = m
                    .texels
                    .iter()
                    .flatten()
                    .map(|c| (c - 1.0).abs())
                    .fold(0.0f32, f32::max);
                eprintln!("flat, {variant:?} {follow_sun}: worst |c - 1| {worst:.2e}");
                // measured 0 (every variant); the bound allows f32 rounding of a sum near 1
                assert!(worst < 1e-6, "{variant:?} {follow_sun}: {worst}");
            }
        }
    }

    #[test]
    fn the_light_map_is_the_papers_sun() {
        let p = ProceduralCausticsParams::default();
        let map = LightMap::sun(&p);
        assert_eq!(map.sample(DVec2::ZERO), 1.0);
        let (r_s, r_h) = p.sun_radii();
        assert!((r_s.to_degrees() - 0.265).abs() < 1e-12);
        // The halo covers ten times the disk's area.
        assert!((r_h * r_h / (r_s * r_s) - 10.0).abs() < 1e-9);
        // Inside the disk 1, at its edge the halo level, beyond the halo 0; smooth in between.
        let at = |theta: f64| map.sample(DVec2::new(theta.tan(), 0.0));
        assert!((at(0.9 * r_s) - 1.0).abs() < 1e-6);
        let mid = at(0.5 * (r_s + r_h));
        eprintln!("halo halfway: {mid}");
        assert!((mid - 0.25).abs() < 6e-4, "{mid}"); // measured 6.3e-5
        assert_eq!(at(1.05 * r_h), 0.0);
        assert_eq!(map.sample(DVec2::new(1.0, 1.0)), 0.0);
        let halo = |t: f64| LightMap::profile(&p, t);
        assert!(halo(1.5 * r_s) > halo(2.0 * r_s) && halo(2.0 * r_s) > halo(2.8 * r_s));
    }

    #[test]
    fn the_normal_is_the_papers_wave_gradient() {
        // The technique's normal is the analytic gradient of water/procedural.rs (itself tested
        // against finite differences there), and agrees with finite differences of the height.
        let wave = Procedural {
            params: ProceduralParams::default(),
            t: 0.7,
        };
        let s = setup(&ProceduralCausticsParams::default(), 8, DVec3::NEG_Z);
        for p in [
            DVec2::new(0.1, 0.2),
            DVec2::new(0.45, 0.8),
            DVec2::new(0.9, 0.33),
        ] {
            let t = trace(&s, &SurfaceInput::Wave(&wave), p);
            assert_eq!(t.surface_point, p, "the paper's ray is vertical");
            assert_eq!(t.normal, height_field_normal(wave.gradient(p)));
            let e = 1e-6;
            let fx = (wave.height(p + DVec2::X * e) - wave.height(p - DVec2::X * e)) / (2.0 * e);
            let fy = (wave.height(p + DVec2::Y * e) - wave.height(p - DVec2::Y * e)) / (2.0 * e);
            let n = height_field_normal(DVec2::new(fx, fy));
            eprintln!(
                "normal against differences: {:.2e}",
                (t.normal - n).length()
            );
            // measured at most 5.6e-10 (central differences with a step of 1e-6)
            assert!((t.normal - n).length() < 5e-9, "{} vs {n}", t.normal);
            assert_eq!(t.height, wave.height(p));
        }
    }

    #[test]
    fn snell_reversed_with_the_papers_ior() {
        // A surface rising along +x with slope tan α: its normal leans by α towards −x, so the
        // vertical ray meets it at α on the +x side, and leaves at asin(n sin α) from the normal on
        // that side: tilted from the vertical by asin(n sin α) − α towards +x.
        let alpha: f64 = 0.01;
        let g = Grid::from_fn(8, 8, |_, j| ((j as f64 + 0.5) / 8.0 * alpha.tan()) as f32);
        let s = ProceduralSetup::new(
            &ProceduralCausticsParams::default(),
            8,
            8,
            1.0,
            0.4,
            DVec3::ZERO,
            false,
            DVec3::NEG_Z,
        )
        .unwrap();
        let t = trace(&s, &SurfaceInput::Grid(&g), DVec2::new(0.5, 0.5));
        let r = t.refracted.unwrap();
        let out = ((PAPER_IOR * alpha.sin()).asin() - alpha).tan();
        assert!((r.x / r.z - out).abs() < 1e-8, "{} vs {out}", r.x / r.z);
        assert!((t.uv.unwrap().x - out).abs() < 1e-8 && t.uv.unwrap().y.abs() < 1e-12);
        // Steeper than the critical angle: total internal reflection, no light.
        let steep = Grid::from_fn(8, 8, |_, j| (j as f64 / 8.0 * 1.5) as f32);
        let t = trace(&s, &SurfaceInput::Grid(&steep), DVec2::new(0.5, 0.5));
        assert!(t.refracted.is_none());
        // Only the lit ground remains there (the paper's additive blend).
        let ground = ProceduralCausticsParams::default().ground as f32;
        assert_eq!(
            caustic_at(&s, &SurfaceInput::Grid(&steep), DVec2::new(0.5, 0.5)),
            [ground; 3]
        );
    }

    #[test]
    fn mirror_symmetric_water_gives_a_mirror_symmetric_map() {
        let n = 48;
        let base = waves(n);
        let mirrored = Grid::from_fn(n, n, |i, j| base.at(i, n - 1 - j));
        let (a_in, b_in) = (SurfaceInput::Grid(&base), SurfaceInput::Grid(&mirrored));
        for variant in Variant::ALL {
            let params = ProceduralCausticsParams {
                variant,
                mesh_resolution: 32,
                target_resolution: 128,
                ..Default::default()
            };
            let s =
                ProceduralSetup::new(&params, 64, 64, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z)
                    .unwrap();
            if variant == Variant::Vertex {
                // The mesh's diagonals do not mirror (its triangles differ), but its vertices do.
                let (a, b) = (vertex_values(&s, &a_in), vertex_values(&s, &b_in));
                let worst = (0..33 * 33)
                    .map(|k| (a[k][0] - b[(k / 33) * 33 + 32 - k % 33][0]).abs())
                    .fold(0.0f32, f32::max);
                eprintln!("{variant:?}: worst vertex asymmetry {worst:.2e}");
                // measured 0 (exact); the bound allows f32 rounding
                for l in 0..=32 {
                    for k in 0..=32 {
                        let (x, y) = (a[l * 33 + k][0], b[l * 33 + 32 - k][0]);
                        assert!((x - y).abs() < 1e-5, "vertex ({k}, {l}): {x} vs {y}");
                    }
                }
                continue;
            }
            let a = caustics(&s, &a_in);
            let b = caustics(&s, &b_in);
            let mut worst = 0.0f32;
            for i in 0..64 {
                for j in 0..64 {
                    let x = a.texels[i * 64 + j][0];
                    let y = b.texels[i * 64 + 63 - j][0];
                    worst = worst.max((x - y).abs());
                }
            }
            eprintln!("{variant:?}: worst texel asymmetry {worst:.2e}");
            // measured 1.19e-7 (texture: its mips sum in a fixed order), 0 (screen)
            assert!(worst < 1.2e-6, "{variant:?}: {worst}");
            // Between the spots only the ground's share of the light remains.
            let ground = s.ground as f32;
            let max = a.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
            let min = a.texels.iter().map(|t| t[0]).fold(1.0, f32::min);
            assert!(
                max > ground + 0.9 * (1.0 - ground) && min < ground + 0.1 * (1.0 - ground),
                "{variant:?}: a pattern, {min}..{max}"
            );
        }
    }

    #[test]
    fn follow_sun_turns_the_sun_map_to_the_scenes_sun() {
        let grid = waves(64);
        let water = SurfaceInput::Grid(&grid);
        let tilted = DVec3::new(0.4, -0.2, -1.0);
        let paper = ProceduralCausticsParams::default();
        let follow = ProceduralCausticsParams {
            follow_sun: true,
            ..Default::default()
        };
        // Overhead sun: the option changes nothing.
        let a = caustics(&setup(&paper, 48, DVec3::NEG_Z), &water);
        let b = caustics(&setup(&follow, 48, DVec3::NEG_Z), &water);
        assert_eq!(a, b);
        // Without the option the scene's sun is ignored (the paper's noon at the Equator).
        let c = caustics(&setup(&paper, 48, tilted), &water);
        assert_eq!(a, c);
        // With it, the frame's +z points at the sun, the gathering ray leans along −T0, and the
        // refracted direction of a flat patch is exactly the direction toward the sun.
        let s = setup(&follow, 48, tilted);
        assert!((s.sun_frame[2] - (-tilted.normalize())).length() < 1e-12);
        let flat = Grid::new(4, 4);
        let t = trace(&s, &SurfaceInput::Grid(&flat), DVec2::new(0.5, 0.5));
        assert!((t.refracted.unwrap() - s.sun_frame[2]).length() < 1e-12);
        assert!(t.uv.unwrap().length() < 1e-12);
        // The pattern moves with the sun: shifted by depth · tan θt along the light's direction, it
        // is close to the overhead map there (not identical: the oblique ray meets the surface at
        // another incidence), and far from the overhead map at the same point.
        let d = caustics(&s, &water);
        assert_ne!(a, d);
        let overhead = setup(&paper, 48, DVec3::NEG_Z);
        let shift = s.up.truncate() * (s.depth / s.up.z);
        assert!(shift.length() > 0.1, "{shift}");
        let (mut shifted, mut same_place) = (0.0f64, 0.0f64);
        for k in 0..400 {
            let p = DVec2::new(
                (k % 20) as f64 * 0.05 + 0.013,
                (k / 20) as f64 * 0.05 + 0.021,
            );
            let v = caustic_at(&s, &water, p)[0] as f64;
            shifted += (v - caustic_at(&overhead, &water, p + shift)[0] as f64).abs();
            same_place += (v - caustic_at(&overhead, &water, p)[0] as f64).abs();
        }
        assert!(
            shifted < 0.5 * same_place,
            "displaced: {shifted} against {same_place} in place"
        );
    }

    #[test]
    fn absorption_is_beer_lambert_along_the_vertical_path() {
        let flat = Grid::new(4, 4);
        let k = DVec3::new(0.5, 0.1, 0.05);
        let s = ProceduralSetup::new(
            &ProceduralCausticsParams::default(),
            8,
            8,
            1.0,
            0.6,
            k,
            true,
            DVec3::new(0.2, 0.0, -1.0),
        )
        .unwrap();
        let c = caustic_at(&s, &SurfaceInput::Grid(&flat), DVec2::new(0.3, 0.3));
        for q in 0..3 {
            let e = (c[q] as f64 - (-k[q] * 0.6).exp()).abs();
            eprintln!("Beer-Lambert channel {q}: {e:.2e}");
            assert!(e < 2e-7, "channel {q}: {e}"); // measured at most 1.98e-8 (f32)
        }
        let off = ProceduralSetup::new(
            &ProceduralCausticsParams {
                absorption: false,
                ..Default::default()
            },
            8,
            8,
            1.0,
            0.6,
            k,
            true,
            DVec3::NEG_Z,
        )
        .unwrap();
        assert_eq!(
            caustic_at(&off, &SurfaceInput::Grid(&flat), DVec2::new(0.3, 0.3)),
            [1.0; 3]
        );
    }

    #[test]
    fn vertex_interpolation_is_exact_at_vertices_and_linear_between() {
        // A map whose pixel centres fall on the mesh's vertices reproduces the vertex values; a
        // linear field is reproduced everywhere.
        let params = ProceduralCausticsParams {
            variant: Variant::Vertex,
            mesh_resolution: 4,
            ..Default::default()
        };
        let s = ProceduralSetup::new(&params, 16, 16, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z)
            .unwrap();
        let values: Vec<[f32; 3]> = (0..25)
            .map(|k| {
                let (x, y) = ((k % 5) as f32, (k / 5) as f32);
                [x + 2.0 * y, x, y]
            })
            .collect();
        let m = rasterise(&s, &values);
        for i in 0..16 {
            for j in 0..16 {
                let (x, y) = ((j as f32 + 0.5) / 4.0, (i as f32 + 0.5) / 4.0);
                let t = m.texels[i * 16 + j];
                // measured 0 (exact) in every texel; the bound allows f32 rounding of values to 12
                assert!((t[0] - (x + 2.0 * y)).abs() < 1e-5 && (t[1] - x).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn mips_average_and_resampling_reads_the_right_level() {
        let t = 16;
        let level0: Vec<[f32; 3]> = (0..t * t).map(|k| [(k % 7) as f32, 1.0, 0.0]).collect();
        let levels = mip_chain(level0.clone(), t);
        assert_eq!(levels.len(), 5);
        let mean0 = level0.iter().map(|v| v[0] as f64).sum::<f64>() / (t * t) as f64;
        let e = (levels[4][0][0] as f64 - mean0).abs();
        eprintln!("mip top against the mean: {e:.2e}");
        assert!(e < 1e-5, "{e}"); // measured 0 (exact); f32 rounding of a mean of 256 values to 6
        // A 4 x 4 map over a 16² target reads level 2 exactly at its texel centres.
        let params = ProceduralCausticsParams {
            variant: Variant::Texture,
            target_resolution: t as u32,
            ..Default::default()
        };
        let s =
            ProceduralSetup::new(&params, 4, 4, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z).unwrap();
        assert_eq!(sampling_footprint(&s), (2.0, 1, true));
        let m = resample(&s, &levels);
        for (a, b) in m.texels.iter().zip(&levels[2]) {
            // measured 0 (exact) in every texel
            assert!((a[0] - b[0]).abs() < 1e-6);
        }
        // A 2 x 8 map: a footprint of 8 x 2 texels, 4 anisotropic taps at level 1.
        let s =
            ProceduralSetup::new(&params, 2, 8, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z).unwrap();
        assert_eq!(sampling_footprint(&s), (1.0, 4, true));
        // Without anisotropy, the major axis alone sets the level: log2(8) = 3.
        let trilinear = ProceduralCausticsParams {
            anisotropy: 1,
            ..params.clone()
        };
        let s = ProceduralSetup::new(&trilinear, 2, 8, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z)
            .unwrap();
        assert_eq!(sampling_footprint(&s), (3.0, 1, true));
        // Magnified both ways: one bilinear tap of level 0.
        let s = ProceduralSetup::new(&params, 40, 20, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z)
            .unwrap();
        assert_eq!(sampling_footprint(&s), (0.0, 1, false));
    }

    #[test]
    fn bad_parameters_are_named() {
        for (p, name) in [
            (
                ProceduralCausticsParams {
                    target_resolution: 300,
                    ..Default::default()
                },
                "target_resolution",
            ),
            (
                ProceduralCausticsParams {
                    mesh_resolution: 0,
                    ..Default::default()
                },
                "mesh_resolution",
            ),
            (
                ProceduralCausticsParams {
                    ior: 0.9,
                    ..Default::default()
                },
                "ior",
            ),
            (
                ProceduralCausticsParams {
                    halo_area: 0.5,
                    ..Default::default()
                },
                "halo_area",
            ),
            (
                ProceduralCausticsParams {
                    anisotropy: 17,
                    ..Default::default()
                },
                "anisotropy",
            ),
        ] {
            let e = p.validate().unwrap_err().to_string();
            assert!(e.contains(&format!("caustics.procedural.{name}")), "{e}");
        }
        let mut t = toml::Table::new();
        t.insert(
            "procedural".into(),
            toml::Value::Table("variant = \"pixel\"".parse().unwrap()),
        );
        let e = ProceduralCausticsParams::from_table(&t)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("caustics.procedural") && e.contains("pixel"),
            "{e}"
        );
        let p = ProceduralCausticsParams {
            light_map: Some("/nonexistent/sun.png".into()),
            ..Default::default()
        };
        let e = LightMap::from_params(&p).unwrap_err().to_string();
        assert!(e.contains("sun.png"), "{e}");
    }

    #[test]
    fn a_png_light_map_is_normalised_at_its_centre() {
        let dir = std::env::temp_dir().join(format!("caustics-lightmap-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("sun.png");
        // A 9 x 9 picture, 200 at the centre texel, 100 in a ring, black elsewhere.
        let img = image::GrayImage::from_fn(9, 9, |x, y| {
            let r = ((x as i32 - 4).pow(2) + (y as i32 - 4).pow(2)) as f32;
            image::Luma([if r == 0.0 {
                200
            } else if r <= 2.0 {
                100
            } else {
                0
            }])
        });
        img.save(&path).unwrap();
        let p = ProceduralCausticsParams {
            light_map: Some(path.clone()),
            light_map_extent: Some(1.0),
            ..Default::default()
        };
        let m = LightMap::from_params(&p).unwrap();
        assert_eq!((m.width, m.height), (9, 9));
        assert!((m.extent - 1f64.to_radians().tan()).abs() < 1e-15);
        assert!((m.sample(DVec2::ZERO) - 1.0).abs() < 1e-6);
        assert!((m.texels[3 * 9 + 4] - 0.5).abs() < 1e-6);
        // Flat water under the overhead sun: 1.0 with this map too.
        let s = ProceduralSetup::new(&p, 4, 4, 1.0, 0.4, DVec3::ZERO, true, DVec3::NEG_Z).unwrap();
        let c = caustic_at(
            &s,
            &SurfaceInput::Grid(&Grid::new(4, 4)),
            DVec2::new(0.5, 0.5),
        );
        assert!((c[0] - 1.0).abs() < 1e-6);
        let black = dir.join("black.png");
        image::GrayImage::new(4, 4).save(&black).unwrap();
        let e = LightMap::load(&black, 0.01).unwrap_err().to_string();
        assert!(e.contains("black.png") && e.contains("centre"), "{e}");
    }
}
