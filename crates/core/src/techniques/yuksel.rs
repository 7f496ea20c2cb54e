//! Technique `yuksel`: "Fast Real-time Caustics from Height Fields" (Yuksel & Keyser), the CPU twin
//! of `caustics-gpu`'s `yuksel` module, pass for pass.
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
//!   lands in the map's own pixels ([`pass1`]): the light is kept, sample density lost; past that,
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
//!   all [`misfit`] (misplace their light, as a share of their width) by no more than `split`.
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

use crate::error::{Error, Result};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::optics::{fresnel_transmittance, height_field_normal, refract};

use super::buffers::{Buffer, BufferDesc, BufferInput, Index, Needs};
use super::describe::{
    Change, Descriptor, Kind, Param, ParamDefault as D, Receiver, serde_defaults,
};
use super::{Input, Job, Made};
use crate::plot::{Picture, flip_rows, heat, scalar_picture};

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
    flat_floor: Some("computes caustics on a flat floor (paper 1, §3)"),
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
    key: "preset",
    label: "region",
    kind: Kind::Choice(&["water", "paper"]),
    default: D::Text("water"),
    unit: "",
    doc: "water: N and M from the water's largest deflection; paper: the paper's N = 7, M = 6 (§6)",
    change: Change::Reconfigure,
    sweep: &["paper"],
};
const PASSES: Param = Param {
    key: "passes",
    label: "passes",
    kind: Kind::Choice(&["targets", "scatter"]),
    default: D::Auto("scatter, the paper's preset targets"),
    unit: "",
    doc: "targets: the paper's pre-pass texture, pass 1 into M+1 render-target channels and pass 2 (§4-5); scatter: each sample's light added into the map pixels its box covers, with integer atomics (ours: the same map, less time and memory)",
    change: Change::Reconfigure,
    sweep: &[],
};
const N: Param = Param {
    key: "n",
    label: "N",
    kind: Kind::Int {
        min: 1,
        max: MAX_N as i64,
        parity: Some(1),
        power_of_two: false,
    },
    default: D::Auto("from the preset"),
    unit: "pixels",
    doc: "samples along x per pixel (odd): region R is N pixels wide (§4)",
    change: Change::Reconfigure,
    sweep: &[],
};
const M: Param = Param {
    key: "m",
    label: "M",
    kind: Kind::Int {
        min: 0,
        max: MAX_M as i64,
        parity: Some(0),
        power_of_two: false,
    },
    default: D::Auto("from the preset"),
    unit: "pixels",
    doc: "neighbouring rows (even): M + 1 channels in pass 1 (§4)",
    change: Change::Reconfigure,
    sweep: &[],
};
const SUBSAMPLES: Param = Param {
    key: "subsamples",
    label: "samples per side",
    kind: Kind::int(1, MAX_SUBSAMPLES as i64),
    default: D::Auto("4, the paper's preset 1"),
    unit: "",
    doc: "samples per map pixel along each axis, each carrying 1/k² of its light (ours)",
    change: Change::Reconfigure,
    sweep: &["1", "2", "4"],
};
const SPLIT: Param = Param {
    key: "split",
    label: "split above",
    kind: Kind::float(0.0, 1.0),
    default: D::Float(DEFAULT_SPLIT),
    unit: "",
    doc: "each pixel lands as 1, 2 x 2, 4 x 4 ... up to k x k footprints, the first whose footprints misplace no more than this share of their width (or of a map pixel where narrower); 0: every pixel k x k (ours)",
    change: Change::Uniform,
    sweep: &["0", "0.3"],
};
const FOOTPRINT: Param = Param {
    key: "footprint",
    label: "footprints",
    kind: Kind::Bool,
    default: D::Auto("on, the paper's preset off"),
    unit: "",
    doc: "each sample's light lands on the box its patch of water maps to, not a pixel box (ours)",
    change: Change::Uniform,
    sweep: &[],
};
const FRESNEL: Param = Param {
    key: "fresnel",
    label: "Fresnel",
    kind: Kind::Bool,
    default: D::Bool(true),
    unit: "",
    doc: "each sample carries its Fresnel transmittance",
    change: Change::Uniform,
    sweep: &[],
};
const ABSORPTION: Param = Param {
    key: "absorption",
    label: "absorption",
    kind: Kind::Bool,
    default: D::Bool(true),
    unit: "",
    doc: "exp(-K d) along the flat-water path",
    change: Change::Uniform,
    sweep: &[],
};

/// The setup and the heights a job gives paper 1 (both twins): the flat floor it maps, the water's
/// own lattice where the water is a grid ([`super::lattice_heights`]).
pub fn job_setup(job: &Job, table: &toml::Table) -> Result<(YukselSetup, Grid)> {
    job.flat_floor(&DESCRIPTOR)?;
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
        )?;
        Ok((setup, super::lattice_heights(w, surface, width, height)))
    })
}

fn run_cpu(
    job: &Job,
    table: &toml::Table,
    _progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Made> {
    let (setup, heights) = job_setup(job, table)?;
    Ok(Made::floor(caustics(&setup, &heights), None))
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
/// The default samples per pixel along each axis (region from the water): 4 × 4 keeps every
/// `caustics compare` case within 5 % of the reference where 2 × 2 leaves the FFT ocean at 80°
/// over 8 % (docs/yuksel.md).
pub const DEFAULT_SUBSAMPLES: u32 = 4;
/// The default [`YukselParams::split`]: the largest misfit of a pixel's footprints before it is
/// sampled twice as finely along each axis. Measured over `caustics compare`'s 32 cases at 128²,
/// 256² and 512² (docs/yuksel.md, "Adaptive footprints"): the worst case 3.4, 2.4 and 3.1 % rel.
/// L1, where 0.2 reaches 4.0 % at 512² and 0 (every pixel 4 × 4) 3.2 % at 128², at 1.5 to 2 times
/// the cost.
pub const DEFAULT_SPLIT: f64 = 0.15;
/// The most samples per level pixel along each axis at a coarser level: there `k` grows with the
/// level (`k · 2^level`, up to this) so that the map's pixels keep `(8 / 2^level)²` samples at
/// least where a region forces a coarser level; GPU time grows with its square.
pub const MAX_LEVEL_SUBSAMPLES: u32 = 8;
/// The narrowest half-width of a footprint, in pixels: a sample whose light meets in a point
/// (a caustic's fold) still lands on a box of positive area, so its flux is counted once; and
/// the half-width stays a normal `f16` (the GPU packs the two half-widths into one channel).
const MIN_HALF_WIDTH: f32 = 1.0e-3;

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

/// How the GPU turns the samples into the map (the CPU twin computes the same shares either way).
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
    /// pixel where narrower; [`prepass`]). 0: every pixel's `k × k`. Default [`DEFAULT_SPLIT`].
    pub split: f64,
    pub fresnel: bool,
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

    pub fn from_table(table: &toml::Table) -> Result<Self> {
        let p: YukselParams = match table.get("yuksel") {
            Some(v) => v
                .clone()
                .try_into()
                .map_err(|e| Error::field("caustics.yuksel", e.to_string()))?,
            None => YukselParams::defaults(),
        };
        p.validate()?;
        Ok(p)
    }

    pub fn validate(&self) -> Result<()> {
        if let Some(n) = self.n
            && (n == 0 || n.is_multiple_of(2) || n > MAX_N)
        {
            return Err(Error::field(
                "caustics.yuksel.n",
                format!(
                    "must be odd, between 1 and {MAX_N} (samples centred on the illumination centre), got {n}"
                ),
            ));
        }
        if let Some(m) = self.m
            && (!m.is_multiple_of(2) || m > MAX_M)
        {
            return Err(Error::field(
                "caustics.yuksel.m",
                format!(
                    "must be even and at most {MAX_M} (M + 1 channels, at most {MAX_CHANNELS}), got {m}"
                ),
            ));
        }
        if !(0.0..=1.0).contains(&self.split) {
            return Err(Error::field(
                "caustics.yuksel.split",
                format!(
                    "must be between 0 and 1 (a share of a footprint's width; 0 splits every pixel), got {}",
                    self.split
                ),
            ));
        }
        if let Some(k) = self.subsamples
            && !(1..=MAX_SUBSAMPLES).contains(&k)
        {
            return Err(Error::field(
                "caustics.yuksel.subsamples",
                format!(
                    "must be between 1 and {MAX_SUBSAMPLES} (samples per pixel along each axis), got {k}"
                ),
            ));
        }
        Ok(())
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
    /// make the same map, the scatter (issue 28: 0.15 times the paper's memory, 0.6 to 0.9 times
    /// the render targets' time on lavapipe); the paper's preset keeps the paper's passes.
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
    pub n: usize,
    pub m: usize,
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

/// The range `[lo, hi]` (world units, per axis) of the offset `δ` of a sample's floor hit from
/// its pixel centre over `heights`: every texel's own deflection, refracted through the normal of
/// its central differences, `δ = (depth + h) T − depth T0` (`T` the refracted ray's sideways travel
/// per unit of descent, `T0` flat water's), widened by an eighth of the span each way for the
/// bicubic surface between texels (the margin caustic-triangles' copy band takes, there on the
/// slope). Texels the sun cannot light (facing away) carry no light and are left out.
pub fn region_bound(setup: &YukselSetup, heights: &Grid) -> (DVec2, DVec2) {
    let (cols, rows) = (heights.cols.max(1), heights.rows.max(1));
    let (dx, dy) = (setup.size / cols as f64, setup.size / rows as f64);
    let at = |i: usize, j: usize| heights.at(i, j) as f64;
    let l = setup.light;
    let t0 = refract(l, DVec3::Z, setup.eta).expect("air to water never reflects totally");
    let flat = t0.truncate() / -t0.z * setup.depth;
    let (mut lo, mut hi) = (flat, flat);
    for i in 0..heights.rows {
        for j in 0..heights.cols {
            let (jn, jp) = ((j + 1) % cols, (j + cols - 1) % cols);
            let (i_n, ip) = ((i + 1) % rows, (i + rows - 1) % rows);
            let grad = DVec2::new(
                (at(i, jn) - at(i, jp)) / (2.0 * dx),
                (at(i_n, j) - at(ip, j)) / (2.0 * dy),
            );
            let normal = height_field_normal(grad);
            if -l.dot(normal) <= 0.0 {
                continue;
            }
            if let Some(t) = refract(l, normal, setup.eta).filter(|t| t.z < 0.0) {
                let d = t.truncate() / -t.z * (setup.depth + at(i, j)).max(0.0);
                lo = lo.min(d);
                hi = hi.max(d);
            }
        }
    }
    let margin = (hi - lo) * 0.125;
    (lo - margin - flat, hi + margin - flat)
}

/// The smallest odd run of offsets that holds every sample landing on a pixel, along one axis:
/// a sample `o` pixels from the pixel whose hit is `δ` pixels from its own centre overlaps the
/// pixel iff `|o + δ| < 1`, so `o ∈ [−⌈δ_max⌉, −⌊δ_min⌋]`; padded by one to be odd, and at most
/// `limit` long (then centred on the same place: light is lost at both ends).
fn axis_region(lo: f64, hi: f64, limit: usize) -> (usize, i32, bool) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (limit, 0, true);
    }
    let first = -hi.ceil();
    let mut last = -lo.floor();
    if ((last - first) as i64) % 2 == 1 {
        last += 1.0;
    }
    let len = (last - first) as usize + 1;
    let centre = ((first + last) / 2.0) as i32;
    if len > limit {
        (limit, centre, true)
    } else {
        (len, centre, false)
    }
}

/// Everything the passes share, derived once from the scene (the GPU side uploads the same numbers
/// as its uniform block).
#[derive(Clone, Debug, PartialEq)]
pub struct YukselSetup {
    pub width: usize,
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
    pub light: DVec3,
    pub eta: f64,
    pub ior: f64,
    pub depth: f64,
    pub size: f64,
    pub wrap: bool,
    /// `T(θ0)`, or 1 without the Fresnel option.
    pub t_flat: f64,
    pub fresnel: bool,
    /// Per-channel `exp(−K d0)` applied in pass 2.
    pub attenuation: DVec3,
}

impl YukselSetup {
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
            t_flat: if params.fresnel {
                fresnel_transmittance(-light.z, 1.0, ior)
            } else {
                1.0
            },
            fresnel: params.fresnel,
            attenuation: if params.absorption {
                (-absorption * d0).exp()
            } else {
                DVec3::ONE
            },
        })
    }

    /// The region for `heights`: along each axis not fixed, the offsets that hold every
    /// deflection [`region_bound`] allows (GPU twin: `yuksel/region.wgsl`).
    pub fn region_for(&self, heights: &Grid) -> Region {
        let (lo, hi) = region_bound(self, heights);
        self.region_from_bound(lo, hi)
    }

    /// [`region_for`](Self::region_for) from the deflection range, world units.
    /// With both N and M from the water, the finest level (down to [`MAX_LEVEL`], while it
    /// divides the map's size) whose region holds the bound.
    pub fn region_from_bound(&self, lo: DVec2, hi: DVec2) -> Region {
        let auto = self.fixed.0.is_none() && self.fixed.1.is_none();
        let mut level = 0;
        loop {
            let pixel = self.pixel * (1u32 << level) as f64;
            let (l, h) = (lo / pixel, hi / pixel);
            let (n, sx, cx) = match self.fixed.0 {
                Some(n) => (n as usize, 0, false),
                None => axis_region(l.x, h.x, MAX_N as usize),
            };
            let (rows, sy, cy) = match self.fixed.1 {
                Some(m) => (m as usize + 1, 0, false),
                None => axis_region(l.y, h.y, MAX_M as usize + 1),
            };
            let region = Region {
                n,
                m: rows - 1,
                shift: [sx, sy],
                level,
                clamped: cx || cy,
            };
            let next = 2usize << level;
            if !region.clamped
                || !auto
                || level == MAX_LEVEL
                || !self.width.is_multiple_of(next)
                || !self.height.is_multiple_of(next)
            {
                return region;
            }
            level += 1;
        }
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

    /// Take the region for `heights` ([`region_for`](Self::region_for)); warns when the bound
    /// passes [`MAX_N`] or [`MAX_M`], since the light beyond is lost.
    pub fn fit_region(&mut self, heights: &Grid) {
        self.region = self.region_for(heights);
        if self.region.clamped {
            tracing::warn!(
                "yuksel: the water deflects light further than the largest gather region \
                 (N = {MAX_N}, M = {MAX_M}, at {} times the pixel of the {}x{} map): light \
                 beyond it is lost",
                1u32 << self.region.level,
                self.width,
                self.height
            );
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

/// The floor hit of the water at `s` (world units) and the flux its area carries relative to
/// flat water (the area as the sun sees the tilted water, times Fresnel): `None` where the sun
/// cannot light it. Mirrors `yuksel_hit` in `yuksel/sample.wgsl`.
fn hit(setup: &YukselSetup, heights: &Grid, s: DVec2) -> Option<(DVec2, f64)> {
    let edge = if setup.wrap { Edge::Wrap } else { Edge::Clamp };
    let l = setup.light;
    let (h, grad) = heights.sample(s, setup.size, edge);
    let normal = height_field_normal(grad);
    let cos_i = -l.dot(normal);
    let seen = 1.0 + l.truncate().dot(grad) / -l.z;
    let t = refract(l, normal, setup.eta).filter(|_| cos_i > 0.0 && seen > 0.0)?;
    let hit = s + t.truncate() * ((setup.depth + h) / -t.z);
    let fresnel = if setup.fresnel {
        fresnel_transmittance(cos_i, 1.0, setup.ior) / setup.t_flat
    } else {
        1.0
    };
    Some((hit, seen * fresnel))
}

/// `x` rounded to the nearest `f16` (ties to even), as its bits: the GPU packs a footprint's two
/// half-widths into one 32-bit channel with WGSL's `pack2x16float`. For the positive normal
/// values `footprint` makes.
fn f16_bits(x: f32) -> u32 {
    let b = x.to_bits();
    let r = b + 0xfff + ((b >> 13) & 1);
    let exponent = ((r >> 23) & 0xff) - 127 + 15;
    (exponent << 10) | ((r >> 13) & 0x3ff)
}

fn f16_value(h: u32) -> f32 {
    f32::from_bits(((((h >> 10) & 0x1f) + 127 - 15) << 23) | ((h & 0x3ff) << 13))
}

/// How many records a side a pixel's light takes in the pre-pass ([`prepass`]): `k`, the
/// default, or fewer where the pixel allows (with [`YukselSetup::split`]). Carried in the sign
/// bits of the packed half-widths, which are positive: none for `k`, x for 1, y for 2, both for 4
/// (below `k`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tier(u32);

impl Tier {
    /// The tier of `t` records a side out of `k`.
    pub fn of(t: usize, k: usize) -> Tier {
        Tier(match t {
            _ if t >= k => 0,
            1 => 0x8000,
            2 => 0x8000_0000,
            _ => 0x8000_8000,
        })
    }

    /// Records a side, out of `k`.
    pub fn side(packed: f32, k: usize) -> usize {
        match packed.to_bits() & 0x8000_8000 {
            0 => k,
            0x8000 => 1,
            0x8000_0000 => 2,
            _ => 4,
        }
    }
}

/// Two half-widths in one channel, as `bitcast<f32>(pack2x16float(half))` on the GPU, with the
/// record's [`Tier`] in their sign bits.
pub fn pack_half_widths(half: [f32; 2], tier: Tier) -> f32 {
    let [x, y] = half.map(|v| f16_bits(v.clamp(MIN_HALF_WIDTH, 6.0e4)));
    f32::from_bits(x | (y << 16) | tier.0)
}

/// The half-widths [`pack_half_widths`] packed.
pub fn unpack_half_widths(packed: f32) -> [f32; 2] {
    let b = packed.to_bits();
    [f16_value(b & 0x7fff), f16_value((b >> 16) & 0x7fff)]
}

/// The share of a box of centre `c` and half-width `h` (pixels) that lies in the pixel
/// `[−1/2, 1/2]`: summed over the pixels it covers, exactly 1, so no flux is lost or doubled.
/// With `h = 1/2` (the paper's pixel box) it is the overlap `1 − |c|` of two pixel squares.
pub fn box_share(c: f32, h: f32) -> f32 {
    ((c + h).min(0.5) - (c - h).max(-0.5)).max(0.0) / (2.0 * h)
}

/// Where the light of a patch of water lands (ours, beyond the paper): its *footprint*, the box
/// its patch (`area`, world units, around `s`) maps to on the floor, between the hits of the
/// patch's edge midpoints, taken along x for the width and along y for the height, min/max so that
/// a folded patch (rays crossing) stays positive, centred on the light's centroid; the flux its
/// centre's. Without footprints (the paper, §3), a box of the patch's own size around
/// its hit. `None` where the sun cannot light its centre.
struct Footprint {
    centre: DVec2,
    /// Half-widths, pixels.
    half: DVec2,
    flux: f64,
    /// How far the box misplaces the patch's light ([`misfit`]), as a share of its width.
    misfit: f64,
}

fn footprint(setup: &YukselSetup, heights: &Grid, s: DVec2, area: DVec2) -> Option<Footprint> {
    let (own, flux) = hit(setup, heights, s)?;
    if !setup.footprint {
        return Some(Footprint {
            centre: own,
            half: 0.5 * area / setup.pixel,
            flux,
            misfit: 0.0,
        });
    }
    // An edge the sun cannot light (or whose ray reflects) takes the patch's own hit and flux;
    // the box then cannot stand for the patch (below `k`, a finer tier takes it).
    let mut unlit = false;
    let mut edge = |d: DVec2| {
        hit(setup, heights, s + d).unwrap_or_else(|| {
            unlit = true;
            (own, flux)
        })
    };
    let [(xm, wxm), (xp, wxp), (ym, wym), (yp, wyp)] = [
        DVec2::new(-0.5 * area.x, 0.0),
        DVec2::new(0.5 * area.x, 0.0),
        DVec2::new(0.0, -0.5 * area.y),
        DVec2::new(0.0, 0.5 * area.y),
    ]
    .map(&mut edge);
    let (mid_x, mid_y) = ((xm + xp) * 0.5, (ym + yp) * 0.5);
    let half = DVec2::new((xp.x - xm.x).abs(), (yp.y - ym.y).abs()) * 0.5 / setup.pixel;
    Some(Footprint {
        // The light's centroid, for a map quadratic and a flux linear over the patch: the hit,
        // plus a third of each axis's edge midpoints' mean off it (the map bends: the mean of u²
        // over [−1/2, 1/2] is a third of its value at the ends), plus each axis's stretch times
        // its flux's change across the patch over 12 times the flux (the flux's slope weights
        // one side: the mean of u² is 1/12). Placing the box there keeps the light's first
        // moment, so a coarser footprint suffices (docs/yuksel.md, "Adaptive footprints").
        centre: own
            + ((mid_x - own) + (mid_y - own)) / 3.0
            + ((xp - xm) * (wxp - wxm) + (yp - ym) * (wyp - wym)) / (12.0 * flux),
        half,
        flux,
        misfit: if unlit {
            f64::INFINITY
        } else {
            misfit(setup, own, half, [xm, xp, ym, yp])
        },
    })
}

/// How far one box misplaces a patch's light, as a share of the box's width along each axis (or
/// of a map pixel where the box is narrower), the larger of the two: the patch's own hit off each
/// axis's edge midpoints' mean (the map bends within the patch, along it or sideways: its light
/// is denser on one side or curves) plus half the shear the box ignores (the x edges' hits apart
/// along y, the y edges' along x: the true footprint is a parallelogram). An affine map without
/// shear misplaces nothing. In pixels of the setup (a level's), where a map pixel is `2^−level`
/// of one. Mirrors `yuksel_footprint` in `yuksel/sample.wgsl`.
fn misfit(setup: &YukselSetup, hit: DVec2, half: DVec2, [xm, xp, ym, yp]: [DVec2; 4]) -> f64 {
    let (mid_x, mid_y) = ((xm + xp) * 0.5, (ym + yp) * 0.5);
    let bend = (hit - mid_x).abs() + (hit - mid_y).abs();
    let shear = DVec2::new((yp.x - ym.x).abs(), (xp.y - xm.y).abs()) * 0.5;
    let off = (bend + shear) / setup.pixel;
    let map_pixel = 1.0 / (1u32 << setup.region.level) as f64;
    (off.x / (2.0 * half.x).max(map_pixel)).max(off.y / (2.0 * half.y).max(map_pixel))
}

/// The `t × t` footprints of the pixel centred at `pixel_centre` (world units, before the
/// illumination centre's offset), row by row.
fn footprints(
    setup: &YukselSetup,
    heights: &Grid,
    pixel_centre: DVec2,
    t: usize,
) -> Vec<Option<Footprint>> {
    (0..t * t)
        .map(|q| {
            let within = (DVec2::new((q % t) as f64, (q / t) as f64) + 0.5) / t as f64 - 0.5;
            let s = pixel_centre + within * setup.pixel + setup.centre_offset;
            footprint(setup, heights, s, setup.pixel / t as f64)
        })
        .collect()
}

/// Pre-pass: where the light of each of a pixel's samples lands, relative to the pixel's centre:
/// `[centre x, centre y, half-widths packed, flux × its share]`. Pre-pass texels `(r·k + b,
/// c·k + a)`, `a, b < k`, belong to map pixel `(r − M/2 + shift.y, c − N/2 + shift.x)`.
/// Without [`YukselSetup::split`], they are its `k × k` samples, each 1/k of the pixel each way
/// carrying 1/k² of its flux. With it (ours), a pixel is sampled as coarsely as it allows: it lands
/// whole on one footprint, or as 2 × 2, 4 × 4 … up to `k × k`, the first whose footprints all
/// misfit by no more than `split` (flat water: one). Its `t × t` records fill texels `a, b < t`,
/// each carrying `1/t²`, tagged with `t` ([`pack_half_widths`]); the other texels of its block
/// are not read (the GPU leaves them as they were; here they repeat its records, tiled).
pub fn prepass(setup: &YukselSetup, heights: &Grid) -> Vec<[f32; 4]> {
    let (pw, ph) = setup.prepass_size();
    let k = setup.subsamples;
    let r0 = setup.region;
    let first = DVec2::new(
        r0.shift[0] as f64 - (r0.n / 2) as f64,
        r0.shift[1] as f64 - (r0.m / 2) as f64,
    );
    let mut out = vec![[0.0f32; 4]; pw * ph];
    for pr in 0..ph / k {
        for pc in 0..pw / k {
            let pixel_centre = (DVec2::new(pc as f64, pr as f64) + first + 0.5) * setup.pixel;
            let mut t = if setup.split.is_some() { 1 } else { k };
            let mut fs = footprints(setup, heights, pixel_centre, t);
            while let Some(limit) = setup.split
                && t < k
                && fs
                    .iter()
                    .any(|f| f.as_ref().is_none_or(|f| f.misfit > limit))
            {
                t = (2 * t).min(k);
                fs = footprints(setup, heights, pixel_centre, t);
            }
            let tier = Tier::of(t, k);
            let share = 1.0 / (t * t) as f64;
            for b in 0..k {
                for a in 0..k {
                    let f = &fs[(b % t) * t + a % t];
                    out[(pr * k + b) * pw + pc * k + a] = match f {
                        Some(f) => {
                            let d = (f.centre - pixel_centre) / setup.pixel;
                            let half = [f.half.x as f32, f.half.y as f32];
                            let packed = pack_half_widths(half, tier);
                            [d.x as f32, d.y as f32, packed, (f.flux * share) as f32]
                        }
                        None => [0.0, 0.0, pack_half_widths([0.5, 0.5], tier), 0.0],
                    };
                }
            }
        }
    }
    out
}

/// Pass 1 (Fig. 5) for the map's rows `phase` modulo `2^level`: pass-1 texel `(r, j)` (`j` a
/// column of the map, `r` a row of the level's map) holds, in channel `k`, the share of the light
/// of the samples (`k × k` each) of the level's sample row `R = r − M/2 + shift.y` at the level's
/// columns `j / 2^level + shift.x + [−N/2, N/2]` that falls in map pixel
/// `(2^level (R + k − M/2 − shift.y) + phase, j)`. At level 0 (one phase) these are the paper's
/// pass 1; at a coarser level the samples are the level's (the region's pixels are `2^level`
/// map pixels) and the light lands in the map's own pixels, so the level costs sample density,
/// not the map's detail. Channels are contiguous per texel: `M + 1` floats each.
pub fn pass1(setup: &YukselSetup, pre: &[[f32; 4]], phase: usize) -> Vec<f32> {
    let level = setup.region.level;
    let coarse = setup.at_level(level);
    let f = 1usize << level;
    let scale = f as f32;
    let centre = (scale - 1.0) * 0.5;
    // A level's pixel holds the light of `4^level` map pixels.
    let area = scale * scale;
    let (w, h1) = setup.pass1_size();
    let (pw, _) = coarse.prepass_size();
    let r0 = setup.region;
    let ch = r0.m + 1;
    let (n, sub) = (r0.n, coarse.subsamples);
    // Column offset of sample `s` from the pixel; row offset of channel `k`'s pixel from the row.
    let col0 = r0.shift[0] as f32 - (n / 2) as f32;
    let row0 = -((r0.m / 2) as f32) - r0.shift[1] as f32;
    let mut out = vec![0.0f32; w * h1 * ch];
    for r in 0..h1 {
        for j in 0..w {
            let (jc, qx) = (j / f, (j % f) as f32);
            let texel = &mut out[(r * w + j) * ch..(r * w + j + 1) * ch];
            let mut add = |p: [f32; 4], col: usize| {
                let [hx, hy] = unpack_half_widths(p[2]);
                // In map pixels from the map pixel's centre.
                let x = (col as f32 + col0 + p[0]) * scale + centre - qx;
                let ax = box_share(x, hx * scale);
                if ax == 0.0 {
                    return;
                }
                for (k, t) in texel.iter_mut().enumerate() {
                    let y = (p[1] - (k as f32 + row0)) * scale + centre - phase as f32;
                    let ay = box_share(y, hy * scale);
                    *t += ax * ay * p[3] * area;
                }
            };
            for col in 0..n {
                let first = (r * sub) * pw + (jc + col) * sub;
                let t = Tier::side(pre[first][2], sub);
                for b in 0..t {
                    for a in 0..t {
                        add(pre[first + b * pw + a], col);
                    }
                }
            }
        }
    }
    out
}

/// Pass 2 (Fig. 6) for the map's rows `phase` modulo `2^level`: map pixel `(i, j)` sums channel `k`
/// of pass-1 row `i / 2^level + M − k`, then applies the absorption (the shift cancels: that row
/// holds the level's sample row `i / 2^level − (k − M/2 − shift.y)`).
pub fn pass2(setup: &YukselSetup, p1: &[f32], phase: usize, map: &mut CausticsMap) {
    let w = setup.width;
    let m = setup.region.m;
    let f = 1usize << setup.region.level;
    let ch = m + 1;
    let a = setup.attenuation;
    for i in (phase..setup.height).step_by(f) {
        for j in 0..w {
            let mut e = 0.0f32;
            for k in 0..ch {
                let r = i / f + m - k;
                e += p1[(r * w + j) * ch + k];
            }
            map.texels[i * w + j] = [e * a.x as f32, e * a.y as f32, e * a.z as f32];
        }
    }
}

/// The whole technique on the CPU: the surface sampled as `heights` over the map's square, with
/// the region fitted to `heights` where N or M is not fixed.
pub fn caustics(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    let mut setup = setup.clone();
    setup.fit_region(heights);
    caustics_in_region(&setup, heights)
}

/// The passes in `setup`'s region as it stands: the pre-pass at its level, then pass 1 and pass 2
/// once per row phase (`2^level` of them) into the map's own pixels.
pub fn caustics_in_region(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    let pre = prepass(&setup.at_level(setup.region.level), heights);
    let mut map = CausticsMap::new(setup.width, setup.height, setup.size);
    for phase in 0..1usize << setup.region.level {
        let p1 = pass1(setup, &pre, phase);
        pass2(setup, &p1, phase, &mut map);
    }
    map
}

/// The pre-pass's and pass 1's textures, as the viewer shows them.
const BUFFERS: &[BufferDesc] = &[
    BufferDesc {
        key: "yuksel-offset",
        label: "yuksel pre-pass: hit offset",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "yuksel-flux",
        label: "yuksel pre-pass: flux",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "yuksel-channel",
        label: "yuksel pass 1: channel {k}",
        // M + 1 channels; with M chosen from the water, as many as it may choose (a channel past
        // the chosen M is drawn as the last).
        index: Some(Index {
            name: "channel",
            count: |own, _| {
                own.get("m")
                    .and_then(|v| v.as_integer())
                    .map_or(MAX_M, |m| m.max(0) as u32)
                    + 1
            },
        }),
        needs: Needs::Anything,
    },
];

/// The pre-pass (§4.1: each sample's hit offset and flux) and pass 1 (§4.2: channel `k` of the
/// `M + 1`, what each sample row gave the row `k - M/2` away), at the region's level.
fn draw_buffer(input: &BufferInput, buffer: Buffer) -> Result<Picture> {
    let (w, surface) = input.water()?;
    let n = input.map_size;
    let heights = super::heights_for(w, surface, n, n);
    let params = YukselParams::from_table(input.params)?;
    let mut setup = YukselSetup::new(
        &params,
        n,
        n,
        w.size,
        w.depth,
        w.ior,
        w.absorption,
        w.wrap,
        input.light,
    )?;
    setup.fit_region(&heights);
    // The samples are the region's level's (k × k per pixel of it).
    let coarse = setup.at_level(setup.region.level);
    let pre = prepass(&coarse, &heights);
    let (pw, ph) = coarse.prepass_size();
    match buffer.desc.key {
        "yuksel-offset" => {
            // δ in pixels: red for x, green for y, mid-grey at no offset, saturating at N/2.
            let reach = (setup.region.n / 2).max(1) as f32;
            let rgba = flip_rows(pw, ph, |t| {
                let p = pre[t];
                let c = |d: f32| ((0.5 + 0.5 * d / reach).clamp(0.0, 1.0) * 255.0) as u8;
                [c(p[0]), c(p[1]), 128, 255]
            });
            Ok(Picture {
                width: pw as u32,
                height: ph as u32,
                rgba,
                legend: format!("hit offset: red x, green y, grey 0, saturated at ±{reach} px"),
            })
        }
        "yuksel-flux" => {
            // Each of a pixel's k × k samples carries 1 / k² of its light: times k², 1 is what
            // flat water gives a whole pixel, whatever k.
            let g = Grid {
                cols: pw,
                rows: ph,
                // A pixel of `t × t` records: each carries 1/t² of its light.
                data: pre
                    .iter()
                    .map(|p| {
                        let t = Tier::side(p[2], coarse.subsamples) as f32;
                        p[3] * t * t
                    })
                    .collect(),
            };
            let (_, max) = g.min_max();
            let top = max.max(1.5);
            Ok(Picture {
                legend: format!(
                    "sample flux x t² (its t x t share of a pixel; 1: flat water): black 0, white {top:.2}"
                ),
                ..scalar_picture(&g, |v| heat(v / top))
            })
        }
        "yuksel-channel" => {
            let p1 = pass1(&setup, &pre, 0);
            let (w1, h1) = setup.pass1_size();
            let ch = setup.region.m + 1;
            let k = (buffer.index as usize).min(setup.region.m);
            let g = Grid {
                cols: w1,
                rows: h1,
                data: (0..w1 * h1).map(|t| p1[t * ch + k]).collect(),
            };
            let (_, max) = g.min_max();
            let top = max.max(1e-6);
            Ok(Picture {
                legend: format!(
                    "channel {k} of {ch} (row offset {}): black 0, white {top:.2}",
                    k as i64 - setup.region.m as i64 / 2 - setup.region.shift[1] as i64
                ),
                ..scalar_picture(&g, |v| heat(v / top))
            })
        }
        _ => super::buffers::no_buffers(input, buffer),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup(params: &YukselParams, res: usize, light: DVec3) -> YukselSetup {
        YukselSetup::new(params, res, res, 1.0, 0.4, 1.333, DVec3::ZERO, true, light).unwrap()
    }

    #[test]
    fn flat_water_gives_one() {
        let s = setup(&YukselParams::default(), 32, DVec3::new(0.3, 0.1, -1.0));
        let m = caustics(&s, &Grid::new(16, 16));
        let worst = m
            .texels
            .iter()
            .map(|t| (t[0] - 1.0).abs())
            .fold(0.0, f32::max);
        eprintln!("flat water: worst |E - 1| {worst:.2e}");
        // measured 0 (exact); the bound allows f32 rounding of the overlaps' sum
        for t in &m.texels {
            assert!((t[0] - 1.0).abs() < 1e-5, "{}", t[0]);
        }
    }

    /// The scatter by default, the paper's passes for its preset, either when named; the
    /// render-target entry pins them and refuses a scatter; the scatter's former name is `yuksel`.
    #[test]
    fn the_passes_follow_the_preset_unless_named() {
        use crate::techniques::Spec;
        let passes = |s: &str| {
            let spec: Spec = s.parse().unwrap();
            (
                spec.name(),
                YukselParams::from_table(&spec.params).unwrap().passes(),
            )
        };
        assert_eq!(passes("yuksel"), ("yuksel", Passes::Scatter));
        assert_eq!(passes("yuksel:preset=paper"), ("yuksel", Passes::Targets));
        assert_eq!(
            passes("yuksel:preset=paper,passes=scatter"),
            ("yuksel", Passes::Scatter)
        );
        assert_eq!(passes("yuksel:passes=targets"), ("yuksel", Passes::Targets));
        assert_eq!(
            passes("yuksel-targets"),
            ("yuksel-targets", Passes::Targets)
        );
        assert_eq!(passes("yuksel-gather"), ("yuksel", Passes::Scatter));
        let err = "yuksel-targets:passes=scatter".parse::<Spec>().unwrap_err();
        assert!(err.to_string().contains("passes"), "{err}");
        let err = "yuksel:passes=gather".parse::<Spec>().unwrap_err();
        assert!(err.to_string().contains("passes"), "{err}");
    }

    /// A scene whose technique's name pins `passes` and whose table says otherwise is refused,
    /// naming the key; the same table under the name that pins nothing, or agreeing with the
    /// pin, is read.
    #[test]
    fn a_scene_table_against_its_techniques_pin_is_refused() {
        let scene = |technique: &str, passes: &str| {
            crate::scene::Scene::from_toml(
                &format!(
                    "[water]\nsize = 4.0\ndepth = 1.0\n[light]\ndirection = [0.3, 0.2, -1.0]\n[caustics]\ntechnique = \"{technique}\"\n\
                     [caustics.yuksel]\npasses = \"{passes}\"\n"
                ),
                std::path::Path::new("."),
                "pinned",
            )
        };
        let Err(err) = scene("yuksel-targets", "scatter") else {
            panic!("yuksel-targets with passes scatter was accepted");
        };
        let text = err.to_string();
        assert!(
            text.contains("caustics.yuksel.passes") && text.contains("yuksel-targets"),
            "{text}"
        );
        for (technique, passes) in [
            ("yuksel-targets", "targets"),
            ("yuksel", "scatter"),
            ("yuksel", "targets"),
        ] {
            if let Err(e) = scene(technique, passes) {
                panic!("{technique} with passes {passes}: {e}");
            }
        }
    }

    /// Records a side of each pixel in `pre`, from its first record's tier.
    fn sides(s: &YukselSetup, pre: &[[f32; 4]]) -> Vec<usize> {
        let (pw, ph) = s.prepass_size();
        let k = s.subsamples;
        (0..ph / k)
            .flat_map(|r| (0..pw / k).map(move |c| (r, c)))
            .map(|(r, c)| Tier::side(pre[r * k * pw + c * k][2], k))
            .collect()
    }

    #[test]
    fn an_affine_map_misfits_nothing_and_a_bent_or_sheared_one_does() {
        let s = setup(&YukselParams::default(), 32, DVec3::NEG_Z);
        let p = s.pixel;
        let edges = |c: DVec2, dx: DVec2, dy: DVec2| [c - dx, c + dx, c - dy, c + dy];
        let c = DVec2::new(0.3, 0.2);
        let (dx, dy) = (DVec2::new(0.7 * p.x, 0.0), DVec2::new(0.0, 1.3 * p.y));
        let half = DVec2::new(0.7, 1.3);
        assert_eq!(misfit(&s, c, half, edges(c, dx, dy)), 0.0);
        // The hit a tenth of the box's width off both edge midpoints' means along x.
        let bent = c + DVec2::new(0.07 * p.x, 0.0);
        assert!((misfit(&s, bent, half, edges(c, dx, dy)) - 0.1).abs() < 1e-12);
        // The x edges' hits apart along y by a fifth of the box's height: half of it misplaced.
        let sheared = [
            c - dx - DVec2::new(0.0, 0.26 * p.y),
            c + dx + DVec2::new(0.0, 0.26 * p.y),
            c - dy,
            c + dy,
        ];
        assert!((misfit(&s, c, half, sheared) - 0.1).abs() < 1e-12);
        // Both x edges' hits off the hit along y: the footprint curves (a crescent).
        let curved = [
            c - dx + DVec2::new(0.0, 0.26 * p.y),
            c + dx + DVec2::new(0.0, 0.26 * p.y),
            c - dy,
            c + dy,
        ];
        assert!((misfit(&s, c, half, curved) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn a_records_tier_round_trips_through_its_sign_bits() {
        for k in [1, 2, 3, 4, 6, 8] {
            let mut t = 1;
            loop {
                let packed = pack_half_widths([0.3, 2.5], Tier::of(t, k));
                assert_eq!(Tier::side(packed, k), t, "t {t} of k {k}");
                assert_eq!(
                    unpack_half_widths(packed),
                    [0.3f32, 2.5].map(|v| f16_value(f16_bits(v)))
                );
                if t == k {
                    break;
                }
                t = (2 * t).min(k);
            }
        }
    }

    #[test]
    fn each_pixel_takes_the_footprints_its_water_needs() {
        let light = DVec3::new(0.3, 0.1, -1.0).normalize();
        let s = setup(&YukselParams::default(), 48, light);
        // Flat water: one footprint a pixel, and the map still flat water's.
        let flat = Grid::new(16, 16);
        assert!(sides(&s, &prepass(&s, &flat)).iter().all(|&t| t == 1));
        // Waves that focus the light: the pixels at their folds take 4 x 4, the rest fewer.
        let n = 48;
        let waves = Grid::from_fn(n, n, |i, j| {
            let (x, y) = ((j as f64 + 0.5) / n as f64, (i as f64 + 0.5) / n as f64);
            let tau = std::f64::consts::TAU;
            (0.02 * (tau * (3.0 * x + y)).sin() + 0.01 * (tau * (-2.0 * x + 5.0 * y)).sin()) as f32
        });
        let mut fitted = s.clone();
        fitted.fit_region(&waves);
        let tiers = sides(&fitted, &prepass(&fitted, &waves));
        let share =
            |t: usize| tiers.iter().filter(|&&v| v == t).count() as f64 / tiers.len() as f64;
        eprintln!(
            "pixels at 1, 2 x 2, 4 x 4: {:.3} {:.3} {:.3}",
            share(1),
            share(2),
            share(4)
        );
        assert!(share(1) > 0.1 && share(2) > 0.1 && share(4) > 0.1);
        let adaptive = caustics(&s, &waves);
        let every = caustics(
            &setup(
                &YukselParams {
                    split: 0.0,
                    ..Default::default()
                },
                48,
                light,
            ),
            &waves,
        );
        let mean = |m: &CausticsMap| {
            m.texels.iter().map(|t| t[0] as f64).sum::<f64>() / m.texels.len() as f64
        };
        let l1 = adaptive
            .texels
            .iter()
            .zip(&every.texels)
            .map(|(a, b)| (a[0] - b[0]).abs() as f64)
            .sum::<f64>()
            / every.texels.iter().map(|t| t[0] as f64).sum::<f64>();
        let max = every.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
        eprintln!(
            "adaptive vs every pixel 4 x 4: L1 {l1:.4}, means {} {}, max {max}",
            mean(&adaptive),
            mean(&every)
        );
        // The same light in all (periodic waves, a region that holds it; the mean is Fresnel's
        // below flat water's): measured means 0.998949 and 0.998963 (1.4e-5 apart), L1 between
        // the maps 0.0200 (pixels at 1, 2 x 2, 4 x 4: 0.198, 0.458, 0.344; max 21.3).
        assert!(max > 5.0, "the waves focus: {max}");
        assert!((mean(&adaptive) - mean(&every)).abs() < 1.4e-4);
        assert!(l1 < 0.05, "{l1}");
    }

    #[test]
    fn periodic_flux_is_conserved_when_the_region_holds_the_deflection() {
        let n = 64;
        let g = Grid::from_fn(n, n, |i, j| {
            let x = (j as f64 + 0.5) / n as f64;
            let y = (i as f64 + 0.5) / n as f64;
            (0.002 * (std::f64::consts::TAU * (2.0 * x + y)).sin()) as f32
        });
        let water = YukselParams {
            fresnel: false,
            ..Default::default()
        };
        let paper = YukselParams {
            fresnel: false,
            ..YukselParams::paper()
        };
        // measured mean − 1: −7.45e-9 (4 × 4 footprints, level 0), −1.12e-8 (at level 1, where
        // a level pixel's 8 × 8 samples spread over 2 × 2 map pixels), −8.38e-9 (the paper's); max
        // 1.044, 1.044, 1.081
        for (label, params, level) in [
            ("footprints", &water, 0),
            ("level 1", &water, 1),
            ("paper", &paper, 0),
        ] {
            let mut s = setup(params, 64, DVec3::new(0.2, 0.1, -1.0));
            s.region = Region {
                level,
                ..s.region_for(&g)
            };
            let m = caustics_in_region(&s, &g);
            let mean = m.texels.iter().map(|t| t[0] as f64).sum::<f64>() / m.texels.len() as f64;
            let max = m.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
            eprintln!(
                "periodic waves, {label}: mean - 1 = {:.2e}, max {max}",
                mean - 1.0
            );
            assert!((mean - 1.0).abs() < 8.9e-8, "{label}: mean {mean}");
            assert!(max > 1.03, "{label}: waves focus: {max}");
        }
    }

    #[test]
    fn bad_n_and_m_are_named() {
        let e = YukselParams {
            n: Some(0),
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("caustics.yuksel.n"), "{e}");
        let e = YukselParams {
            m: Some(40),
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("caustics.yuksel.m"), "{e}");
        let e = YukselParams {
            m: Some(3),
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("even"), "{e}");
    }

    #[test]
    fn the_region_follows_the_water_unless_fixed() {
        let light = DVec3::new(0.8, 0.6, -0.4).normalize();
        let s = setup(&YukselParams::default(), 64, light);
        // Flat water deflects nothing: each pixel gathers its own sample.
        let flat = s.region_for(&Grid::new(16, 16));
        assert_eq!(
            (flat.n, flat.m, flat.shift, flat.clamped),
            (1, 0, [0, 0], false)
        );
        let waves = Grid::from_fn(64, 64, |i, j| {
            let x = (j as f64 + 0.5) / 64.0;
            let y = (i as f64 + 0.5) / 64.0;
            (0.003 * (std::f64::consts::TAU * (2.0 * x + y)).sin()) as f32
        });
        let r = s.region_for(&waves);
        assert!(
            r.n > 1 && r.m > 0 && !r.n.is_multiple_of(2) && r.m.is_multiple_of(2),
            "{r:?}"
        );
        // Every hit lies within the region: no sample lands beyond its edge.
        let mut fitted = s.clone();
        fitted.fit_region(&waves);
        let pre = prepass(&fitted, &waves);
        // A box from `e0` to `e1` pixels off its pixel's centre reaches the pixels at offsets
        // `o` with `o + e0 < 1/2` and `o + e1 > −1/2`: all within the region.
        let inside = |e0: f32, e1: f32, half: usize, shift: i32| {
            let (lo, hi) = ((shift - half as i32) as f32, (shift + half as i32) as f32);
            (-0.5 - e1).floor() + 1.0 >= lo && (0.5 - e0).ceil() - 1.0 <= hi
        };
        for p in pre.iter().filter(|p| p[3] > 0.0) {
            let [hx, hy] = unpack_half_widths(p[2]);
            assert!(
                inside(p[0] - hx, p[0] + hx, r.n / 2, r.shift[0]),
                "{p:?} {r:?}"
            );
            assert!(
                inside(p[1] - hy, p[1] + hy, r.m / 2, r.shift[1]),
                "{p:?} {r:?}"
            );
        }
        // The paper's preset, and a given N, stay fixed.
        let paper = setup(&YukselParams::paper(), 64, light).region_for(&waves);
        assert_eq!((paper.n, paper.m, paper.shift), (7, 6, [0, 0]));
        let table: toml::Table = toml::from_str("[yuksel]\npreset = \"paper\"\nn = 9").unwrap();
        let p = YukselParams::from_table(&table).unwrap();
        assert_eq!(p.fixed(), (Some(9), Some(6)));
        let at_depth = |depth: f64| {
            YukselSetup::new(
                &YukselParams::default(),
                64,
                64,
                1.0,
                depth,
                1.333,
                DVec3::ZERO,
                true,
                light,
            )
            .unwrap()
            .region_for(&waves)
        };
        // Deeper: a coarser level holds it; far deeper: clamped at the coarsest.
        let r = at_depth(5.0);
        assert!(r.level > 0 && !r.clamped, "{r:?}");
        let r = at_depth(500.0);
        assert!(
            r.clamped && r.level == MAX_LEVEL && r.n == MAX_N as usize && r.m == MAX_M as usize,
            "{r:?}"
        );
    }
}
