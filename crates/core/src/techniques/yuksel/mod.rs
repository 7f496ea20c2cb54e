//! Technique `yuksel`: "Fast Real-time Caustics from Height Fields" (Yuksel & Keyser), the CPU twin
//! of `caustics-gpu`'s `yuksel` module, pass for pass: one file here per pass there, named as its
//! WGSL file, so that a pass and its twin are read side by side.
//!
//! | pass | WGSL (crates/gpu/src/yuksel/) | CPU twin (this folder) |
//! |---|---|---|
//! | what every pass shares: the uniform block, the region, a box's share of a pixel | `common.wgsl` | this file: [`YukselSetup`], [`Region`], [`box_share`] |
//! | region bound (every texel's deflection) and region (N, M, shift, level; ours) | `region_bound.wgsl`, `region.wgsl` | `region.rs`: [`region_bound`], [`YukselSetup::region_for`] |
//! | pre-pass (§5): each pixel's tier and its records, the pixels at k filled sharing their edges' rays, the spans | `prepass.wgsl`, `prepass_fill.wgsl`, `prepass_span.wgsl` + `sample.wgsl`, `fill.wgsl` | `prepass.rs`: [`prepass()`], with `hit`, `footprint`, `misfit` and the records' packing ([`Tier`], [`pack_half_widths`]) |
//! | pass 1 (Fig. 5): N samples along x into M + 1 channels | `pass1.wgsl` | `pass1.rs`: [`pass1()`] |
//! | pass 2 (Fig. 6): the channels summed along y, the absorption | `pass2.wgsl` | `pass2.rs`: [`pass2()`]; the two passes over every row phase: [`caustics`] |
//! | the scatter (ours, the default `passes`): each record added into the map where it is made, in fixed point, then resolved | `scatter_tier.wgsl`, `scatter_fill.wgsl`, `scatter_resolve.wgsl` + `scatter.wgsl` | `scatter.rs`: [`scatter()`] |
//! | the viewer's pictures of the pre-pass and pass 1 | | `buffers.rs` |
//!
//! # The method (paper §3-4)
//! Caustics are gathered backwards, from each caustics-map pixel `P_G` on the floor `z = 0`: the light
//! reaching it comes through a rectangle `R` of the water around the *illumination centre*
//! `P_C = P_G + h L'` (Eq. 1), where `L'` is the flat-water refracted light direction scaled to climb
//! the rest depth `h`. `R` is sampled with one sample per map pixel; each sample's area is refracted
//! with the sample's own normal, constant over the area (§3), and lands as a pixel-sized square
//! whose overlap `α` with the pixel is its contribution (Eq. 4). (Our default samples more
//! finely and lands each sample on its footprint: below.)
//!
//! - **Pre-pass** (§5, "an additional pass before the first pass"): the refracted ray of every sample
//!   and its intersection with the floor, computed once and stored as the offset of where its
//!   light lands from the sample's own pixel centre (in pixels) and the flux the sample carries.
//! - **Pass 1** (Fig. 5): for each pixel, the `N` samples along x around its illumination centre; each
//!   adds its overlap `ax · ay` with the pixel and with the `M` pixels beside it along y to `M + 1`
//!   channels, written through multiple render targets on the GPU.
//! - **Pass 2** (Fig. 6): each pixel sums, over the `M + 1` rows around it, the channel that the row
//!   wrote for it.
//! - **The scatter** (ours, the GPU's default `passes`): each record of the pre-pass added where it
//!   is made into the map pixels its box covers, clipped to the region as pass 1 gathers it, in
//!   fixed point: the same shares as pass 1 and pass 2 without the pre-pass texture or the render
//!   targets ([`scatter()`]).
//!
//! The paper's Fig. 6 reads channel `k` at row offset `k − M/2` while Fig. 5 stores in channel `k`
//! the contribution to row offset `k − M/2`: the two pair up only if pass 2 reads row `−(k − M/2)`,
//! which is what both our passes do (row `i − d` holds, in the channel of offset `d`, what it gave
//! row `i`).
//!
//! # Beyond the paper (options)
//! - The flux of a sample is `E_h A (1 + L_xy · ∇h / |L_z|)`: the pixel area `A` as the sun sees the
//!   tilted water. The paper's "average refracted light intensity through A_i" is this; it makes the
//!   map conserve flux, so its mean over a periodic tile equals the reference's.
//! - `fresnel`: each sample carries `T(θi) / T(θ0)`, its Fresnel transmittance relative to flat water.
//! - `absorption`: `exp(−K d0)` per RGB channel with `d0 = h / |L'_z|`, the flat-water path length,
//!   applied in pass 2 (the per-sample path length differs from it by the wave height over the depth,
//!   and keeping one channel per offset keeps the paper's channel budget).
//! - Samples beyond the map are computed too (the pre-pass covers `N − 1` extra columns and `M` extra
//!   rows): with wrapped edges they are the periodic copies of the samples across the edge, so every
//!   pixel gathers its whole region and the map tiles; with clamped edges they see the clamped
//!   surface, as the reference does.
//!
//! - **The region from the water** (default, `preset = "water"`): the paper fixes `N`, `M` in map
//!   pixels (7 and 6, §6), so light the waves throw further, or a finer map, loses light. Unless `n`
//!   or `m` is given, the region is chosen each frame from a bound on the largest deflection
//!   ([`region_bound`]: every texel's deflection from its slope, height, the depth and the sun,
//!   with a margin), and shifted along the refracted sun (`shift`) where the deflections lean one
//!   way. Its cost: GPU time grows with `N × (M + 1) × k²`. Past [`MAX_N`] or [`MAX_M`] the
//!   samples are taken on a map 2, 4 or 8 times coarser ([`Region::level`]) while the light still
//!   lands in the map's own pixels ([`pass1()`]): the light is kept, sample density lost; past that,
//!   the region is clamped with a warning. The GPU
//!   computes the same region in a one-workgroup pass (`region.wgsl`), so no frame reads heights
//!   back. `preset = "paper"` keeps the paper's 7 and 6.
//!
//! - **Samples and footprints** (default, `preset = "water"`; the paper's preset keeps one
//!   sample per pixel and pixel boxes): each pixel of the water is sampled `k × k` times
//!   ([`DEFAULT_SUBSAMPLES`]), each sample carrying `1/k²` of the pixel's flux, and each sample's
//!   light lands on its *footprint*, the box its patch of water maps to on the floor (between
//!   the hits of the patch's edge midpoints, `footprint`), shared among the pixels it overlaps
//!   in proportion ([`box_share`]): flux is conserved exactly, and light focused narrower than a
//!   pixel stays in one pixel instead of being spread over two as a pixel box spreads it. The box
//!   sits on the light's centroid (for a map that bends quadratically and a flux that varies
//!   linearly over the patch).
//! - **Adaptive footprints** (default, [`YukselParams::split`]): a pixel takes only as many
//!   footprints as its water needs, 1, 2 × 2, 4 × 4 … up to `k × k`: the first whose footprints
//!   all misfit (`misfit`: misplace their light, as a share of their width) by no more than `split`.
//!   Flat or gently curved water takes one, a caustic's fold the finest; the pre-pass refracts
//!   and pass 1 gathers that many.
//!
//! # Where it departs from the reference
//! Light deflected further than the region `R` (`N/2` pixels along x, `M/2` along y) is lost
//! (with the paper's fixed region). The footprint is an axis-aligned box from the ray map's
//! stretch along x and along y, not the true quadrilateral, so light sheared across the axes is
//! placed within the box only; and the normal is constant over each sample, so focusing within
//! a sample's patch is invisible. With the paper's settings each sample is a pixel-sized box (a
//! box filter), which blurs caustics sharper than a pixel. The sample spacing is the map's
//! pixel over `k` (times `2^level` where the region needs a coarser level), independent of the
//! height field's.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::grid::Grid;
use crate::map::CausticsMap;
use crate::optics::{air_transmittance, refract};
use crate::receivers::Shared;
use crate::receivers::{LightSpace, received_with_light};

use super::describe::{
    Descriptor, Kind, Param, ParamDefault as D, Receiver, check_params, read_params, serde_defaults,
};
use super::{Input, Job, JobOutput};

mod buffers;
pub mod pass1;
pub mod pass2;
pub mod prepass;
pub mod region;
pub mod scatter;
#[cfg(test)]
mod tests;

use buffers::{BUFFERS, draw_buffer};
pub use pass1::pass1;
pub use pass2::pass2;
pub use prepass::{Tier, pack_half_widths, prepass, unpack_half_widths};
pub use region::region_bound;
pub use scatter::{FIXED, scatter, scatter_deposit, scatter_in_region};

/// Paper 1 as registered: the passes its `passes` names (the scatter by default, the paper's
/// render-target passes, §4, with its preset).
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "yuksel",
    table: "yuksel",
    paper: "1",
    summary: "fast backward caustics from height fields: pre-pass, N samples along x into M+1 channels, sum along y (Yuksel & Keyser); by default its samples added into the map where they are made",
    docs: "docs/yuksel.md",
    input: Input::Water,
    receivers: &[Receiver::Floor],
    params: PARAMS,
    fixed: &[],
    point_light: false,
    buffers: BUFFERS,
    draw_buffer,
    reference: false,
    validate: |t| YukselParams::from_table(t).map(|_| ()),
    own_defaults: serde_defaults::<YukselParams>,
    cpu: run_cpu,
};

/// Paper 1's own passes (§4-5) whatever the preset: the pre-pass texture, pass 1 into multiple
/// render targets, pass 2; the same maps as [`DESCRIPTOR`]'s scatter, side by side with it.
pub const TARGETS: Descriptor = Descriptor {
    name: "yuksel-targets",
    summary: "paper 1's render-target passes (pre-pass texture, pass 1 into M+1 channels, pass 2) whatever the preset: the same maps as `yuksel`'s scatter",
    params: TARGET_PARAMS,
    fixed: &[("passes", "targets")],
    ..DESCRIPTOR
};

const PARAMS: &[Param] = &[
    PRESET, PASSES, N, M, SUBSAMPLES, SPLIT, FOOTPRINT, FRESNEL, ABSORPTION,
];
/// `yuksel-targets`'s: its name pins `passes`.
const TARGET_PARAMS: &[Param] = &[
    PRESET, N, M, SUBSAMPLES, SPLIT, FOOTPRINT, FRESNEL, ABSORPTION,
];

const PRESET: Param = Param {
    sweep: &["paper"],
    ..Param::new(
        "preset",
        "region",
        Kind::Choice(&["water", "paper"]),
        D::Text("water"),
        "",
        "water: N and M from the water's largest deflection; paper: the paper's N = 7, M = 6 (§6)",
    )
};
const PASSES: Param = Param::new(
    "passes",
    "passes",
    Kind::Choice(&["targets", "scatter"]),
    D::Auto("scatter, the paper's preset targets"),
    "",
    "targets: the paper's pre-pass texture, pass 1 into M+1 render-target channels and pass 2 (§4-5); scatter: each sample's light added into the map pixels its box covers, with integer atomics (ours: the same map, less time and memory)",
);
const N: Param = Param::new(
    "n",
    "N",
    Kind::Int {
        min: 1,
        max: MAX_N as i64,
        parity: Some(1),
        power_of_two: false,
    },
    D::Auto("from the preset"),
    "pixels",
    "samples along x per pixel (odd): region R is N pixels wide (§4)",
);
const M: Param = Param::new(
    "m",
    "M",
    Kind::Int {
        min: 0,
        max: MAX_M as i64,
        parity: Some(0),
        power_of_two: false,
    },
    D::Auto("from the preset"),
    "pixels",
    "neighbouring rows (even): M + 1 channels in pass 1 (§4)",
);
const SUBSAMPLES: Param = Param {
    sweep: &["1", "2", "4"],
    ..Param::new(
        "subsamples",
        "samples per side",
        Kind::int(1, MAX_SUBSAMPLES as i64),
        D::Auto("4, the paper's preset 1"),
        "",
        "samples per map pixel along each axis, each carrying 1/k² of its light (ours)",
    )
};
const SPLIT: Param = Param {
    sweep: &["0", "0.3"],
    ..Param::new(
        "split",
        "split above",
        Kind::float(0.0, 1.0),
        D::Float(DEFAULT_SPLIT),
        "",
        "each pixel lands as 1, 2 x 2, 4 x 4 ... up to k x k footprints, the first whose footprints misplace no more than this share of their width (or of a map pixel where narrower); 0: every pixel k x k (ours)",
    )
};
const FOOTPRINT: Param = Param::new(
    "footprint",
    "footprints",
    Kind::Bool,
    D::Auto("on, the paper's preset off"),
    "",
    "each sample's light lands on the box its patch of water maps to, not a pixel box (ours)",
);
const FRESNEL: Param = Param::on(
    "fresnel",
    "Fresnel",
    "each sample carries its Fresnel transmittance",
);
const ABSORPTION: Param = Param::on(
    "absorption",
    "absorption",
    "exp(-K d) along the flat-water path",
);

/// The setup and the heights a job gives paper 1 (both twins): the flat floor it maps, the water's
/// own lattice where the water is a grid ([`super::lattice_heights`]).
pub fn job_setup(job: &Job, table: &toml::Table) -> Result<(YukselSetup, Grid)> {
    job.note_floor_only(&DESCRIPTOR);
    let params = YukselParams::from_table(table)?;
    let (width, height) = job.size();
    job.with_surface(DESCRIPTOR.name, |w, surface| {
        let setup = YukselSetup::new(
            &params,
            width,
            height,
            w.size,
            w.depth,
            w.ior,
            w.absorption,
            w.wrap,
            job.light(),
        )?
        .with_floor(job.floor(), None);
        Ok((setup, super::lattice_heights(w, surface, width, height)))
    })
}

/// The CPU twin of the passes the GPU runs for `table` (`passes`): the scatter's, or the
/// paper's pass 1 and pass 2; the same map either way, to the scatter's fixed point.
fn run_cpu(
    job: &Job,
    table: &toml::Table,
    _progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<JobOutput> {
    let (setup, heights) = job_setup(job, table)?;
    let deposit = match YukselParams::from_table(table)?.passes() {
        Passes::Scatter => scatter_deposit(&setup, &heights),
        Passes::Targets => caustics_deposit(&setup, &heights),
    };
    Ok(JobOutput::received(
        setup.received_with_light(deposit),
        None,
    ))
}

/// The largest channel count: 8 render targets of 4 channels.
pub const MAX_CHANNELS: u32 = 32;
/// The widest region a pixel gathers along x: pass 1's time grows with `N × (M + 1)`, and the
/// coarser levels take over where a region would be wider.
pub const MAX_N: u32 = 31;
/// The tallest region: `M + 1 ≤` [`MAX_CHANNELS`] channels in pass 1's render targets.
pub const MAX_M: u32 = MAX_CHANNELS - 2;
/// The coarsest level the region may be sampled at: pixels `2^level` times the map's.
pub const MAX_LEVEL: u32 = 3;
/// The most samples per pixel along each axis: GPU time grows with their square.
pub const MAX_SUBSAMPLES: u32 = 4;
/// The default samples per pixel along each axis (region from the water): the fewest that keep
/// every `caustics compare` case within 5 % of the reference (rel. L1), a grazing sun over the
/// FFT ocean the hardest (docs/yuksel.md for the measurements).
pub const DEFAULT_SUBSAMPLES: u32 = 4;
/// The default [`YukselParams::split`]: the largest misfit of a pixel's footprints before it is
/// sampled twice as finely along each axis. The rule: the largest split (the cheapest: fewer
/// pixels take the finer tiers) that keeps every `caustics compare` case, at every map size
/// measured, within 5 % of the reference (rel. L1) with a margin (docs/yuksel.md, "Adaptive
/// footprints", for the measurements).
pub const DEFAULT_SPLIT: f64 = 0.15;
/// The most samples per level pixel along each axis at a coarser level: there `k` grows with the
/// level (`k · 2^level`, up to this) so that the map's pixels keep `(8 / 2^level)²` samples at
/// least where a region forces a coarser level; GPU time grows with its square.
pub const MAX_LEVEL_SUBSAMPLES: u32 = 8;

/// How the region is chosen where `n` or `m` is not given.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// From a bound on the water's largest deflection on the floor ([`region_bound`]), every
    /// frame, and placed along the refracted sun where the deflections lean.
    #[default]
    Water,
    /// The paper's N = 7, M = 6 (§6), centred on the illumination centre, for comparison.
    Paper,
}

/// How the GPU turns the samples into the map; the CPU run takes the same passes' twin (the same
/// shares either way, summed in another order).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Passes {
    /// The paper's (§4-5): the pre-pass texture, pass 1 gathering `N × (M + 1)` samples into
    /// render-target channels, pass 2 summing them.
    Targets,
    /// Ours: each sample's light added into the map's pixels its box covers where it is made, in
    /// fixed point with integer atomics: no pre-pass texture or render targets, so a fraction of
    /// the memory, and no gather over the region, so less time (docs/yuksel.md).
    Scatter,
}

/// The technique's parameters, `[caustics.yuksel]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct YukselParams {
    /// `"water"` (default) or `"paper"`: where `n` or `m` is not given.
    pub preset: Preset,
    /// Samples along x per pixel (odd): the region `R` is `N` pixels wide. Given, it is fixed
    /// and centred on the illumination centre.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub n: Option<u32>,
    /// Neighbouring pixels along y (even): `M + 1` channels, the region `R` is `M + 1` pixels
    /// tall. Given, it is fixed and centred.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub m: Option<u32>,
    /// Samples per map pixel along each axis (1 to [`MAX_SUBSAMPLES`]), each carrying `1/k²`
    /// of the pixel's light. Default: [`DEFAULT_SUBSAMPLES`] with the region from the water,
    /// the paper's 1 with `preset = "paper"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub subsamples: Option<u32>,
    /// Whether each sample's light lands on its footprint (the box its patch of water really
    /// maps to) rather than the paper's box of the sample's size. Default: true with the region
    /// from the water, false with `preset = "paper"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub footprint: Option<bool>,
    /// With footprints, each pixel lands as 1, 2 × 2, 4 × 4 … up to `k × k` footprints: the
    /// first whose footprints all misplace no more than this share of their width (or of a map
    /// pixel where narrower; [`prepass()`]). 0: every pixel's `k × k`. Default [`DEFAULT_SPLIT`].
    pub split: f64,
    /// Each sample carries `T(θi) / T(θ0)`, its Fresnel transmittance relative to flat water
    /// (beyond the paper).
    pub fresnel: bool,
    /// `exp(−K d0)` per RGB channel in pass 2, `d0` the flat-water path from the surface to the
    /// floor, with the scene's `K` (beyond the paper).
    pub absorption: bool,
    /// How the GPU makes the map. Default: the scatter with the region from the water, the
    /// paper's render targets with `preset = "paper"` ([`passes`](Self::passes)).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub passes: Option<Passes>,
}

impl Default for YukselParams {
    fn default() -> Self {
        Self::defaults()
    }
}

impl YukselParams {
    /// The paper's fixed region, N = 7, M = 6.
    pub fn paper() -> Self {
        YukselParams {
            preset: Preset::Paper,
            ..Self::defaults()
        }
    }

    /// The defaults: the region from the water, Fresnel and absorption on.
    pub fn defaults() -> Self {
        YukselParams {
            preset: Preset::Water,
            n: None,
            m: None,
            subsamples: None,
            footprint: None,
            split: DEFAULT_SPLIT,
            fresnel: true,
            absorption: true,
            passes: None,
        }
    }

    /// The `yuksel` table of `table` (a scene's `[caustics]`), defaults where it is absent,
    /// checked as [`validate`](Self::validate) does.
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        read_params(table, &DESCRIPTOR, Self::validate)
    }

    /// Check every value's range (`n` odd, `m` even, within their limits); the error names the
    /// field out of it.
    pub fn validate(&self) -> Result<()> {
        check_params(&DESCRIPTOR, self)
    }

    /// Samples per pixel along each axis and whether they land on their footprints: given, or
    /// the preset's (the paper's: 1, pixel boxes).
    pub fn sampling(&self) -> (u32, bool) {
        let (k, footprint) = match self.preset {
            Preset::Paper => (1, false),
            Preset::Water => (DEFAULT_SUBSAMPLES, true),
        };
        (
            self.subsamples.unwrap_or(k),
            self.footprint.unwrap_or(footprint),
        )
    }

    /// The GPU's passes: given, or the preset's. The default is the cheaper of the two that
    /// make the same map, the scatter (less memory and less time: docs/yuksel.md, "The
    /// scatter"); the paper's preset keeps the paper's passes (§4-5).
    pub fn passes(&self) -> Passes {
        self.passes.unwrap_or(match self.preset {
            Preset::Water => Passes::Scatter,
            Preset::Paper => Passes::Targets,
        })
    }

    /// The fixed N and M: given, or the paper's; `None` where the water chooses.
    pub fn fixed(&self) -> (Option<u32>, Option<u32>) {
        match self.preset {
            Preset::Paper => (Some(self.n.unwrap_or(7)), Some(self.m.unwrap_or(6))),
            Preset::Water => (self.n, self.m),
        }
    }
}

/// The gather region of every pixel: samples at column offsets `shift.x + [−N/2, N/2]` and row
/// offsets `shift.y + [−M/2, M/2]` from the pixel's own sample (the one at its illumination
/// centre). Mirrors `YukselRegion` in `yuksel/common.wgsl`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// `N`: samples gathered along x (odd), in the level's pixels (§4).
    pub n: usize,
    /// `M`: rows beside the pixel along y (even), `M + 1` channels, in the level's pixels (§4).
    pub m: usize,
    /// `[x, y]`: the region's centre offset from the pixel's own sample, in the level's pixels,
    /// where the deflections lean one way (ours; `[0, 0]` for the paper's fixed region).
    pub shift: [i32; 2],
    /// The samples are those of a map `2^level` times coarser (N, M and the shift in its pixels),
    /// their light landing in the map's own pixels: where the deflection passes the largest
    /// region at the map's own pixels, a coarser level keeps the light at the cost of sample
    /// density (`(k / 2^level)²` per map pixel).
    pub level: u32,
    /// Whether the bound asked for more than [`MAX_N`] or [`MAX_M`] even at [`MAX_LEVEL`]:
    /// light is lost.
    pub clamped: bool,
}

/// Everything the passes share, derived once from the scene (the GPU side uploads the same numbers
/// as its uniform block).
#[derive(Clone, Debug, PartialEq)]
pub struct YukselSetup {
    /// Map pixels along x.
    pub width: usize,
    /// Map pixels along y.
    pub height: usize,
    /// The region the CPU passes gather: fixed, or the largest until [`fit_region`](Self::fit_region).
    pub region: Region,
    /// N and M given (or the paper's); `None` where the water chooses.
    pub fixed: (Option<u32>, Option<u32>),
    /// Samples per pixel along each axis ([`YukselParams::sampling`]).
    pub subsamples: usize,
    /// Each sample's light on its footprint (true) or on a box of the sample's size (the paper).
    pub footprint: bool,
    /// The misfit above which a pixel is sampled more finely ([`YukselParams::split`]); `None`
    /// where every pixel takes its `k × k` (no footprints, or `split = 0`).
    pub split: Option<f64>,
    /// Map pixel size, world units.
    pub pixel: DVec2,
    /// `h L'` in world units: from a floor point to its illumination centre on the rest surface.
    pub centre_offset: DVec2,
    /// Unit direction the sunlight travels, z < 0.
    pub light: DVec3,
    /// Air to water, `η = 1 / ior`: the ratio Snell's law takes for the sunlight entering.
    pub eta: f64,
    /// Index of refraction of the water.
    pub ior: f64,
    /// The water's rest level above the floor plane z = 0 (the paper's `h`), world units.
    pub depth: f64,
    /// Side of the square `[0, size]²` the water and the map cover, world units.
    pub size: f64,
    /// The water's heights repeat across the square's edges (else they are clamped there).
    pub wrap: bool,
    /// `T(θ0)`, or 1 without the Fresnel option.
    pub t_flat: f64,
    /// Each sample carries its Fresnel transmittance relative to flat water
    /// ([`YukselParams::fresnel`]).
    pub fresnel: bool,
    /// `K` per channel, zero without the absorption option.
    pub absorption: DVec3,
    /// Per-channel `exp(−K d0)` applied in pass 2 (1 over receivers: the lookup attenuates).
    pub attenuation: DVec3,
    /// What the samples' light meets instead of the plane `z = 0` ([`YukselSetup::with_floor`]).
    pub receivers: Option<Shared>,
    /// The pool's walls close the square ([`YukselSetup::with_floor`]): the surface beyond them
    /// sends no light, and light that leaves the square meets a wall, not the floor across it.
    pub walls: bool,
}

impl YukselSetup {
    /// The setup for a `width` x `height` map of the square of side `size`, water `depth` deep
    /// with index `ior`, absorption `K` per channel, `wrap`ped or clamped edges, sunlight
    /// travelling along `light` (z < 0); the region is fixed or the largest until
    /// [`fit_region`](Self::fit_region).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        params: &YukselParams,
        width: usize,
        height: usize,
        size: f64,
        depth: f64,
        ior: f64,
        absorption: DVec3,
        wrap: bool,
        light: DVec3,
    ) -> Result<Self> {
        params.validate()?;
        let light = super::check_inputs(width, height, light)?;
        let eta = 1.0 / ior;
        let t0 = refract(light, DVec3::Z, eta).expect("air to water never reflects totally");
        let d0 = depth / -t0.z;
        let fixed = params.fixed();
        let (subsamples, footprint) = params.sampling();
        Ok(YukselSetup {
            subsamples: subsamples as usize,
            footprint,
            split: (footprint && params.split > 0.0).then_some(params.split),
            width,
            height,
            region: Region {
                n: fixed.0.unwrap_or(MAX_N) as usize,
                m: fixed.1.unwrap_or(MAX_M) as usize,
                shift: [0, 0],
                level: 0,
                clamped: false,
            },
            fixed,
            pixel: DVec2::new(size / width as f64, size / height as f64),
            // Up the refracted ray from the floor to the rest surface: P_C = P_G − T0 · h / T0_z.
            centre_offset: -t0.truncate() * (depth / -t0.z),
            light,
            eta,
            ior,
            depth,
            size,
            wrap,
            t_flat: air_transmittance(params.fresnel, -light.z, ior),
            fresnel: params.fresnel,
            absorption: if params.absorption {
                absorption
            } else {
                DVec3::ZERO
            },
            attenuation: if params.absorption {
                (-absorption * d0).exp()
            } else {
                DVec3::ONE
            },
            receivers: None,
            walls: false,
        })
    }

    /// The samples' light meets `floor`'s terrain where it has one: the receivers' map at the
    /// map's resolution (from `previous` where nothing it depends on changed), the light deposited
    /// in the light's space and looked up per floor pixel ([`crate::receivers`]). The
    /// absorption moves into the lookup, along the flat-water path to each receiver point, as the
    /// paper takes the flat floor's. A pool's walls ([`crate::scene::Floor::walls`]) close the
    /// square: a sample on the surface beyond them carries no light ([`Self::walls`]).
    pub fn with_floor(mut self, floor: &crate::scene::Floor, previous: Option<&Shared>) -> Self {
        self.walls = floor.walls && floor.terrain.is_none();
        let t0 = crate::receivers::flat_refracted(self.light, self.ior);
        self.receivers =
            Shared::of_floor(previous, floor, true, self.size, self.depth, t0, self.width);
        if self.receivers.is_some() {
            self.attenuation = DVec3::ONE;
        }
        self
    }

    /// `map` (the light's deposit) as the floor receives it: itself on the plane `z = 0`, else
    /// looked up per floor pixel through the receivers.
    pub fn received(&self, map: CausticsMap) -> CausticsMap {
        crate::receivers::received(map, self.receivers.as_ref(), self.wrap, self.absorption)
    }

    /// [`received`](Self::received), with the deposit where objects are among the receivers.
    pub fn received_with_light(&self, map: CausticsMap) -> (CausticsMap, Option<LightSpace>) {
        let receivers = self.receivers.as_ref().map(|r| &r.0);
        received_with_light(map, receivers, self.wrap, self.absorption)
    }

    /// Samples per pixel along each axis at `level`: `k · 2^level`, at most
    /// [`MAX_LEVEL_SUBSAMPLES`] (or `k` where it is larger).
    pub fn subsamples_at(&self, level: u32) -> usize {
        (self.subsamples << level).min(self.subsamples.max(MAX_LEVEL_SUBSAMPLES as usize))
    }

    /// This setup's passes at `level`: a map `2^level` times coarser over the same square, sampled
    /// [`subsamples_at`](Self::subsamples_at) times along each axis per pixel.
    pub fn at_level(&self, level: u32) -> YukselSetup {
        YukselSetup {
            width: self.width >> level,
            height: self.height >> level,
            subsamples: self.subsamples_at(level),
            pixel: self.pixel * (1u32 << level) as f64,
            ..self.clone()
        }
    }

    /// The row phases the GPU records: `2^level` of the largest level this setup may choose
    /// (pass 1 and pass 2 of a phase past the frame's level draw nothing).
    pub fn phases(&self) -> u32 {
        if self.fixed.0.is_none() && self.fixed.1.is_none() {
            1 << MAX_LEVEL
        } else {
            1
        }
    }

    /// The largest region the GPU may choose: its textures are allocated for it.
    pub fn capacity(&self) -> (usize, usize) {
        (
            self.fixed.0.unwrap_or(MAX_N) as usize,
            self.fixed.1.unwrap_or(MAX_M) as usize,
        )
    }

    /// Pre-pass texture size: `k × k` samples for each pixel of the map, `N − 1` extra columns
    /// and `M` extra rows.
    pub fn prepass_size(&self) -> (usize, usize) {
        let k = self.subsamples;
        (
            (self.width + self.region.n - 1) * k,
            (self.height + self.region.m) * k,
        )
    }

    /// Pass-1 texture size: every map column, the level's rows and `M` extra.
    pub fn pass1_size(&self) -> (usize, usize) {
        (
            self.width,
            (self.height >> self.region.level) + self.region.m,
        )
    }
}

/// The share of a box of centre `c` and half-width `h` (pixels) that lies in the pixel
/// `[−1/2, 1/2]`: summed over the pixels it covers, exactly 1, so no flux is lost or doubled.
/// With `h = 1/2` (the paper's pixel box) it is the overlap `1 − |c|` of two pixel squares.
pub fn box_share(c: f32, h: f32) -> f32 {
    ((c + h).min(0.5) - (c - h).max(-0.5)).max(0.0) / (2.0 * h)
}

/// The whole technique on the CPU through the paper's passes (§4-5: the pre-pass, pass 1, pass 2;
/// the twin of the render targets, [`scatter()`] the scatter's): the surface sampled as `heights`
/// over the map's square, with the region fitted to `heights` where N or M is not fixed.
pub fn caustics(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    setup.received(caustics_deposit(setup, heights))
}

/// [`caustics`]'s light before the receivers' lookup: its light-space deposit.
pub fn caustics_deposit(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    let mut setup = setup.clone();
    setup.fit_region(heights);
    targets_in_region(&setup, heights)
}

/// The passes in `setup`'s region as it stands: the pre-pass at its level, then pass 1 and pass 2
/// once per row phase (`2^level` of them) into the map's own pixels.
pub fn caustics_in_region(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    setup.received(targets_in_region(setup, heights))
}

fn targets_in_region(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    let pre = prepass(&setup.at_level(setup.region.level), heights);
    let mut map = CausticsMap::new(setup.width, setup.height, setup.size);
    for phase in 0..1usize << setup.region.level {
        let p1 = pass1(setup, &pre, phase);
        pass2(setup, &p1, phase, &mut map);
    }
    map
}
