//! Water normals filtered by a pixel's footprint, as LEAN mapping does for bump maps
//! (M. Olano, D. Baker, "LEAN Mapping", I3D 2010, §3): the first and second moments of the slope,
//! `E[∇h]` and `E[∇h ∇hᵀ]`, average linearly, so a pyramid of their box averages gives, for any
//! footprint, the mean slope (the normal to shade with) and the slope covariance of the waves too
//! small to resolve (`E[∇h ∇hᵀ] − E[∇h] E[∇h]ᵀ`), which becomes the roughness of a Gaussian
//! distribution of facets. Far water then reflects a blurred sky and a sun glint spread over that
//! roughness instead of sparkling with whichever single wave a pixel's sample happens to meet.
//!
//! The glint is the sun's reflection off a Gaussian slope distribution as Cox and Munk model the
//! sea's glitter (C. Cox, W. Munk, "Measurement of the Roughness of the Sea Surface from
//! Photographs of the Sun's Glitter", JOSA 44, 1954): `L = E F p(∇h_f) / (4 cos θ_v cos⁴ β)`, with
//! `∇h_f` the slope of the facet that mirrors the sun to the eye, tilted by `β`, and Smith's
//! masking for Beckmann facets (B. Walter et al., "Microfacet Models for Refraction through Rough
//! Surfaces", EGSR 2007, eq. 27). The sun's own disk widens the distribution, so a perfectly flat
//! mirror still shows the sun as a small spot of the sun's whole reflected power.
//!
//! Off by default (`RenderOptions::filter_water`, `caustics render --filter-water`): against many
//! samples it does not yet beat the exact normals (docs/maintainers/look.md). Its GPU twin is
//! caustics-gpu's `final_image::slopes` and `final_image_rough_water.wgsl`'s `rough_water`.

use glam::{DVec2, DVec3};

use super::Surface;
use crate::grid::Edge;

/// Gradient samples along each side of a level-0 texel whose moments it holds.
const SUB: usize = 4;

/// Most taps along a stretched footprint's long axis; beyond it the taps read a coarser level.
pub const MAX_TAPS: usize = 16;

/// The first and second moments of the water's slope `∇h` over some area.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlopeMoments {
    /// `E[∇h] = (E[h_x], E[h_y])`: the mean slope, the normal to shade with.
    pub mean: DVec2,
    /// `E[h_x²]`.
    pub xx: f64,
    /// `E[h_y²]`.
    pub yy: f64,
    /// `E[h_x h_y]`.
    pub xy: f64,
}

impl SlopeMoments {
    /// One slope, no spread: the moments of a point.
    pub fn exact(g: DVec2) -> Self {
        SlopeMoments {
            mean: g,
            xx: g.x * g.x,
            yy: g.y * g.y,
            xy: g.x * g.y,
        }
    }

    fn to_array(self) -> [f64; 5] {
        [self.mean.x, self.mean.y, self.xx, self.yy, self.xy]
    }

    fn from_array(a: [f64; 5]) -> Self {
        SlopeMoments {
            mean: DVec2::new(a[0], a[1]),
            xx: a[2],
            yy: a[3],
            xy: a[4],
        }
    }

    /// `(1 − t) self + t other`: the moments of the mixture.
    pub fn lerp(self, other: Self, t: f64) -> Self {
        let (a, b) = (self.to_array(), other.to_array());
        Self::from_array(std::array::from_fn(|k| a[k] + (b[k] - a[k]) * t))
    }

    /// The slope covariance `(σ_xx, σ_yy, σ_xy)`, made positive semi-definite against rounding.
    pub fn covariance(&self) -> (f64, f64, f64) {
        let sxx = (self.xx - self.mean.x * self.mean.x).max(0.0);
        let syy = (self.yy - self.mean.y * self.mean.y).max(0.0);
        let limit = (sxx * syy).sqrt();
        let sxy = (self.xy - self.mean.x * self.mean.y).clamp(-limit, limit);
        (sxx, syy, sxy)
    }
}

/// The part of the water a view ray's sample stands for where it meets the surface: an ellipse
/// `width` across, `length` along the unit horizontal direction `along` (the ray's, stretched by
/// its grazing angle).
#[derive(Clone, Copy, Debug)]
pub struct Footprint {
    /// The ellipse's extent across the ray's horizontal direction, world units.
    pub width: f64,
    /// The ellipse's extent along `along`, world units (at least `width`).
    pub length: f64,
    /// Unit horizontal direction of the ray (+x for a vertical ray).
    pub along: DVec2,
}

impl Footprint {
    /// The footprint of a ray of unit direction `d` that has travelled `distance` from the eye,
    /// whose sample covers the angle `spread` (a pixel's angular size over the samples per side):
    /// the cone's width there, stretched along the ray by `1 / |d_z|` on the level surface.
    pub fn of_ray(d: DVec3, distance: f64, spread: f64) -> Self {
        let width = distance * spread;
        let horizontal = DVec2::new(d.x, d.y);
        let along = horizontal.try_normalize().unwrap_or(DVec2::X);
        Footprint {
            width,
            length: width / d.z.abs().max(1e-3),
            along,
        }
    }
}

/// The angle one of a camera's `n x n` samples per pixel covers: the pixel's vertical angular size
/// at the image's centre over `n` (`Camera::ray`'s lattice).
pub fn sample_spread(fov_y_degrees: f64, height: u32, n: u32) -> f64 {
    2.0 * (fov_y_degrees.to_radians() * 0.5).tan() / height as f64 / n.max(1) as f64
}

struct Level {
    cols: usize,
    rows: usize,
    texels: Vec<[f64; 5]>,
}

/// Box averages of the slope moments over the water's square: level 0 holds the moments of the
/// surface's exact slope over each texel of a `cols x rows` lattice (the water grid's), each level
/// above
/// averages 2 x 2 texels of the one below (fewer at an odd edge), up to one texel for the whole
/// square.
pub struct SlopePyramid {
    size: f64,
    edge: Edge,
    levels: Vec<Level>,
}

impl SlopePyramid {
    /// The pyramid of `surface`'s slopes over the square of side `size` (world units), level 0 on
    /// a `cols x rows` lattice (at least 1 x 1), read outside the square by `edge`.
    pub fn new(surface: &dyn Surface, cols: usize, rows: usize, size: f64, edge: Edge) -> Self {
        let (cols, rows) = (cols.max(1), rows.max(1));
        let (dx, dy) = (size / cols as f64, size / rows as f64);
        let mut texels = Vec::with_capacity(cols * rows);
        for i in 0..rows {
            for j in 0..cols {
                // The texel's own slopes: the moments of the interpolant's gradient averaged over
                // a 4 x 4 lattice inside it. The gradient at the texel's centre alone is the
                // central difference, which misses the slope of the shortest waves (none at all
                // at the grid's Nyquist wavelength) and so the roughness they make.
                let mut sum = [0.0; 5];
                for a in 0..SUB {
                    for b in 0..SUB {
                        let p = DVec2::new(
                            (j as f64 + (b as f64 + 0.5) / SUB as f64) * dx,
                            (i as f64 + (a as f64 + 0.5) / SUB as f64) * dy,
                        );
                        for (s, t) in sum
                            .iter_mut()
                            .zip(SlopeMoments::exact(surface.gradient(p)).to_array())
                        {
                            *s += t / (SUB * SUB) as f64;
                        }
                    }
                }
                texels.push(sum);
            }
        }
        let mut levels = vec![Level { cols, rows, texels }];
        while let Some(below) = levels.last().filter(|l| l.cols > 1 || l.rows > 1) {
            levels.push(below.halved());
        }
        SlopePyramid { size, edge, levels }
    }

    /// How many levels, level 0 included.
    pub fn levels(&self) -> usize {
        self.levels.len()
    }

    /// Level `k`'s columns, rows and texels (row by row, `E[h_x]`, `E[h_y]`, `E[h_x²]`, `E[h_y²]`,
    /// `E[h_x h_y]`): for tests of a GPU twin.
    pub fn level(&self, k: usize) -> (usize, usize, &[[f64; 5]]) {
        let l = &self.levels[k];
        (l.cols, l.rows, &l.texels)
    }

    /// Level 0's texel: the larger of its two sides.
    pub fn texel(&self) -> f64 {
        let l = &self.levels[0];
        self.size / l.cols.min(l.rows) as f64
    }

    /// Bilinear between the texel centres of level `k` at `p`, with the water's edge rule.
    fn bilinear(&self, k: usize, p: DVec2) -> SlopeMoments {
        let l = &self.levels[k];
        let u = p.x / (self.size / l.cols as f64) - 0.5;
        let v = p.y / (self.size / l.rows as f64) - 0.5;
        let (j0, i0) = (u.floor(), v.floor());
        let (fu, fv) = (u - j0, v - i0);
        let mut sum = [0.0; 5];
        for (di, wy) in [(0, 1.0 - fv), (1, fv)] {
            for (dj, wx) in [(0, 1.0 - fu), (1, fu)] {
                let t = l.fetch(i0 as i64 + di, j0 as i64 + dj, self.edge);
                for (s, t) in sum.iter_mut().zip(t) {
                    *s += wx * wy * t;
                }
            }
        }
        SlopeMoments::from_array(sum)
    }

    /// The moments at `p` over a square `2^lod` level-0 texels wide: the surface's exact slope
    /// (no spread) at `lod <= 0`, trilinear between levels above, the whole square's at the top.
    pub fn at_lod(&self, surface: &dyn Surface, p: DVec2, lod: f64) -> SlopeMoments {
        let exact = || SlopeMoments::exact(surface.gradient(p));
        if lod <= 0.0 {
            return exact();
        }
        let top = self.levels.len() - 1;
        if lod >= top as f64 {
            return self.bilinear(top, p);
        }
        let k = lod.floor() as usize;
        let below = if k == 0 { exact() } else { self.bilinear(k, p) };
        below.lerp(self.bilinear(k + 1, p), lod - k as f64)
    }

    /// The moments over `footprint` centred on `p`: up to [`MAX_TAPS`] taps along its long axis,
    /// each at the level whose texel matches the footprint's width (or the spacing of the taps,
    /// when the footprint is longer than that many widths). Where that is finer than the lattice
    /// the samples resolve the waves themselves: the exact slope at `p`, no spread.
    pub fn filtered(&self, surface: &dyn Surface, p: DVec2, footprint: &Footprint) -> SlopeMoments {
        let taps = (footprint.length / footprint.width.max(1e-12))
            .ceil()
            .clamp(1.0, MAX_TAPS as f64);
        let side = footprint.width.max(footprint.length / taps);
        let lod = (side / self.texel()).log2();
        if lod <= 0.0 {
            // The samples resolve the lattice: the exact slope where the ray meets the water.
            return SlopeMoments::exact(surface.gradient(p));
        }
        let n = taps as usize;
        let mut sum = [0.0; 5];
        for k in 0..n {
            let offset = ((k as f64 + 0.5) / taps - 0.5) * footprint.length;
            let m = self.at_lod(surface, p + footprint.along * offset, lod);
            for (s, t) in sum.iter_mut().zip(m.to_array()) {
                *s += t / taps;
            }
        }
        SlopeMoments::from_array(sum)
    }
}

impl Level {
    fn fetch(&self, i: i64, j: i64, edge: Edge) -> [f64; 5] {
        let (r, c) = (self.rows as i64, self.cols as i64);
        let (i, j) = match edge {
            Edge::Wrap => (i.rem_euclid(r), j.rem_euclid(c)),
            Edge::Clamp => (i.clamp(0, r - 1), j.clamp(0, c - 1)),
        };
        self.texels[(i * c + j) as usize]
    }

    fn halved(&self) -> Level {
        let (cols, rows) = (self.cols.div_ceil(2), self.rows.div_ceil(2));
        let mut texels = Vec::with_capacity(cols * rows);
        for i in 0..rows {
            for j in 0..cols {
                let mut sum = [0.0; 5];
                let mut n = 0.0;
                for ci in (2 * i)..(2 * i + 2).min(self.rows) {
                    for cj in (2 * j)..(2 * j + 2).min(self.cols) {
                        for (s, t) in sum.iter_mut().zip(self.texels[ci * self.cols + cj]) {
                            *s += t;
                        }
                        n += 1.0;
                    }
                }
                texels.push(sum.map(|s| s / n));
            }
        }
        Level { cols, rows, texels }
    }
}

/// Facets [`visible_facets`] spreads a footprint's slopes over.
pub const FACETS: usize = 6;
/// Gauss-Legendre nodes and weights on [-1, 1], 6 points.
const LEGENDRE: [(f64, f64); FACETS] = [
    (-0.932_469_514_203_152, 0.171_324_492_379_17),
    (-0.661_209_386_466_264, 0.360_761_573_048_139),
    (-0.238_619_186_083_197, 0.467_913_934_572_691),
    (0.238_619_186_083_197, 0.467_913_934_572_691),
    (0.661_209_386_466_264, 0.360_761_573_048_139),
    (0.932_469_514_203_152, 0.171_324_492_379_17),
];

/// The facets a view ray along `d` (going down) sees of water with slope moments `m`, weighted by
/// how much of each the eye sees: the slope distribution along the view's azimuth (across it, its
/// conditional mean) times each facet's area projected toward the eye, `(−d · n) / n_z =
/// |d_z| + |d_xy| ∂h/∂a` per unit of horizontal area, none for a facet turned away; this is the
/// distribution of visible normals of microfacet theory (E. Heitz, "Understanding the
/// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), 2014, §3). In the along
/// slope's standard units `u` the weight is `(u − u₀) φ(u)` above the slope `u₀` where facets turn
/// away, integrated by Gauss-Legendre over `[max(u₀, −4), max(u₀, 0) + 4]`. A grazing view sees
/// the faces of the waves turned toward it, which reflect less than the mean surface would at
/// that angle: the Fresnel reflectance averaged this way, not taken at the mean normal, is what a
/// fine lattice of samples converges to. With no spread along the view, the mean facet alone: the
/// first entry, the count 1.
pub fn visible_facets(d: DVec3, m: &SlopeMoments) -> ([(DVec3, f64); FACETS], usize) {
    let (sxx, syy, sxy) = m.covariance();
    let horizontal = DVec2::new(d.x, d.y);
    let run = horizontal.length();
    let a = horizontal.try_normalize().unwrap_or(DVec2::X);
    let along = DVec2::new(sxx * a.x + sxy * a.y, sxy * a.x + syy * a.y);
    let sigma = a.dot(along).max(0.0).sqrt();
    let mean = || {
        let mut f = [(DVec3::Z, 0.0); FACETS];
        f[0] = (crate::optics::height_field_normal(m.mean), 1.0);
        (f, 1)
    };
    if sigma <= 0.0 {
        return mean();
    }
    let u0 = if run > 0.0 {
        -(d.z.abs() + run * m.mean.dot(a)) / (run * sigma)
    } else {
        f64::NEG_INFINITY
    };
    let lo = u0.max(-4.0);
    let hi = lo.max(0.0) + 4.0;
    let step = along / sigma;
    let mut facets = [(DVec3::Z, 0.0); FACETS];
    let mut total = 0.0;
    for (f, &(x, w)) in facets.iter_mut().zip(&LEGENDRE) {
        let u = lo + (hi - lo) * 0.5 * (x + 1.0);
        let seen = w * (u - u0).max(0.0) * (-0.5 * u * u).exp();
        *f = (crate::optics::height_field_normal(m.mean + step * u), seen);
        total += seen;
    }
    if total <= 0.0 || !total.is_finite() {
        return mean();
    }
    (facets.map(|(n, w)| (n, w / total)), FACETS)
}

/// The slope variance the sun's disk adds to the facets that can mirror it: a facet tilt of `α / 2`
/// turns the reflection by the disk's radius `α`, and a uniform disk of radius `r` has a variance of
/// `r² / 4` along each axis.
pub fn sun_slope_variance(sun_radius: f64) -> f64 {
    sun_radius * sun_radius / 16.0
}

/// Smith's masking of Beckmann facets of slope variance `sigma2` along the view's azimuth, for a
/// view whose zenith cosine is `cos_theta` (Walter et al. 2007's rational fit of `Λ`).
fn smith_masking(cos_theta: f64, sigma2: f64) -> f64 {
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    if sin_theta <= 0.0 || sigma2 <= 0.0 {
        return 1.0;
    }
    let a = cos_theta / (sin_theta * (2.0 * sigma2).sqrt());
    if a >= 1.6 {
        return 1.0;
    }
    let lambda = (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
    1.0 / (1.0 + lambda)
}

/// The sun's glint off water of slope moments `m`, per unit of the sun's normal irradiance and
/// of the facet's Fresnel reflectance: the radiance toward the eye `to_eye` (unit, up) for sunlight
/// from `to_sun` (unit, up) is this times `E F`. `sun_variance` widens the slopes by the sun's disk
/// ([`sun_slope_variance`]). Also returns the half vector, whose Fresnel reflectance applies.
pub fn glint(to_eye: DVec3, to_sun: DVec3, m: &SlopeMoments, sun_variance: f64) -> (f64, DVec3) {
    let h = (to_eye + to_sun).normalize_or_zero();
    if to_eye.z <= 0.0 || h.z <= 0.0 {
        return (0.0, h);
    }
    let (sxx, syy, sxy) = m.covariance();
    let (sxx, syy) = (sxx + sun_variance, syy + sun_variance);
    let det = sxx * syy - sxy * sxy;
    let e = DVec2::new(-h.x / h.z, -h.y / h.z) - m.mean;
    let q = (syy * e.x * e.x - 2.0 * sxy * e.x * e.y + sxx * e.y * e.y) / det;
    let density = (-0.5 * q).exp() / (2.0 * std::f64::consts::PI * det.sqrt());
    let variance_along = |d: DVec3| {
        let a = DVec2::new(d.x, d.y).try_normalize().unwrap_or(DVec2::X);
        sxx * a.x * a.x + 2.0 * sxy * a.x * a.y + syy * a.y * a.y
    };
    let masking = smith_masking(to_eye.z, variance_along(to_eye))
        * smith_masking(to_sun.z, variance_along(to_sun));
    let cos2 = h.z * h.z;
    (density * masking / (4.0 * to_eye.z * cos2 * cos2), h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::water::Flat;
    use crate::water::waves::{Wave, Waves};

    fn sine(amplitude: f64, wavelength: f64, direction: [f64; 2]) -> Waves {
        Waves::new(
            &[Wave {
                amplitude,
                wavelength,
                direction,
                phase: 0.3,
                period: None,
            }],
            1.0,
            0.0,
        )
    }

    /// A sine of slope amplitude `a k` has slope variance `(a k)² / 2`: at the top of the pyramid
    /// all of it is roughness and the mean slope is the sine's mean, 0; the second moments are
    /// kept at every level (box averages of the level below).
    #[test]
    fn far_away_the_slope_becomes_roughness() {
        let (a, wavelength) = (0.01, 0.25);
        let s = sine(a, wavelength, [1.0, 0.0]);
        let p = SlopePyramid::new(&s, 64, 64, 1.0, Edge::Wrap);
        assert_eq!(p.levels(), 7);
        let k = 2.0 * std::f64::consts::PI / wavelength;
        let top = p.at_lod(&s, DVec2::new(0.3, 0.7), 10.0);
        let expected = 0.5 * (a * k) * (a * k);
        assert!(top.mean.length() < 1e-12, "{top:?}");
        // The lattice's samples of the sine average its square exactly (4 periods, 64 samples).
        assert!((top.xx - expected).abs() < 1e-9 * expected, "{top:?}");
        assert!(top.yy.abs() < 1e-12 && top.xy.abs() < 1e-12);
        let (sxx, _, _) = top.covariance();
        assert!((sxx - expected).abs() < 1e-9 * expected);
        // Every level holds the same total second moment over the square.
        for level in &p.levels {
            let mean: f64 =
                level.texels.iter().map(|t| t[2]).sum::<f64>() / level.texels.len() as f64;
            assert!((mean - expected).abs() < 1e-9 * expected, "{mean}");
        }
    }

    /// A filter that keeps the mean slope: over a footprint of a swell much longer than it, the
    /// filtered mean is the swell's slope there, and the short ripples on it become variance.
    #[test]
    fn the_filtered_mean_slope_is_the_resolved_waves() {
        let swell = Wave {
            amplitude: 0.02,
            wavelength: 2.0,
            direction: [1.0, 0.0],
            phase: 0.0,
            period: None,
        };
        let ripple = Wave {
            amplitude: 0.001,
            wavelength: 1.0 / 32.0,
            direction: [0.0, 1.0],
            phase: 0.0,
            period: None,
        };
        let both = Waves::new(&[swell.clone(), ripple], 2.0, 0.0);
        let only_swell = Waves::new(&[swell], 2.0, 0.0);
        let p = SlopePyramid::new(&both, 512, 512, 2.0, Edge::Wrap);
        let kr = 2.0 * std::f64::consts::PI * 32.0;
        for x in [0.1, 0.37, 0.8, 1.55] {
            let q = DVec2::new(x, 0.4);
            // A footprint of one ripple wavelength: 8 level-0 texels, lod 3.
            let f = Footprint {
                width: 1.0 / 32.0,
                length: 1.0 / 32.0,
                along: DVec2::X,
            };
            let m = p.filtered(&both, q, &f);
            let g = only_swell.gradient(q);
            // The level's box and the bilinear tent between its texels, each 1/32 wide, shrink the
            // swell's slope (amplitude 0.063) by about 0.12 %: measured up to 8.4e-5.
            assert!((m.mean - g).length() < 1.3e-4, "{m:?} {g}");
            let (_, syy, _) = m.covariance();
            let expected = 0.5 * (0.001 * kr) * (0.001 * kr);
            // A level-3 texel averages exactly one period of the ripple: measured 1.5e-15.
            assert!(
                (syy - expected).abs() < 1e-12 * expected,
                "{syy} {expected}"
            );
        }
    }

    #[test]
    fn flat_water_is_unchanged() {
        let p = SlopePyramid::new(&Flat, 32, 32, 4.0, Edge::Clamp);
        for lod in [-2.0, 0.5, 3.2, 9.0] {
            assert_eq!(
                p.at_lod(&Flat, DVec2::new(1.0, 2.0), lod),
                SlopeMoments::default()
            );
        }
        let up = DVec3::Z;
        let to_sun = DVec3::new(0.3, 0.1, 1.0).normalize();
        let to_eye = DVec3::new(-0.3, -0.1, 1.0).normalize();
        let (g, h) = glint(to_eye, to_sun, &SlopeMoments::default(), 1e-6);
        assert!((h - up).length() < 1e-12);
        // The mirror direction sees the peak of the sun's spot: 1 / (2π σ² 4 cos θ).
        let peak = 1.0 / (2.0 * std::f64::consts::PI * 1e-6 * 4.0 * to_eye.z);
        assert!((g - peak).abs() < 1e-9 * peak, "{g} {peak}");
    }

    /// Without spread every facet is the mean one: near water shades as it did unfiltered.
    /// With spread, a grazing view sees the faces turned toward it: the weighted mean facet leans
    /// toward the eye.
    #[test]
    fn grazing_views_see_the_faces_turned_toward_them() {
        let d = DVec3::new(1.0, 0.0, -0.05).normalize();
        let g = DVec2::new(0.02, -0.01);
        let (facets, count) = visible_facets(d, &SlopeMoments::exact(g));
        assert_eq!(count, 1);
        assert_eq!(facets[0], (crate::optics::height_field_normal(g), 1.0));
        let rough = SlopeMoments {
            mean: DVec2::ZERO,
            xx: 0.02,
            yy: 0.02,
            xy: 0.0,
        };
        let (facets, count) = visible_facets(d, &rough);
        assert_eq!(count, FACETS);
        let sum: f64 = facets.iter().map(|f| f.1).sum();
        assert!((sum - 1.0).abs() < 1e-12);
        let lean: DVec3 = facets.iter().map(|(n, w)| *n * *w).sum();
        // A facet faces the eye (travelling +x) when its normal has n_x < 0.
        assert!(lean.x < -0.05, "{lean}");
        // The side-to-side tilt stays the mean's.
        assert!(lean.y.abs() < 1e-12);
    }

    /// The glint conserves energy: over the hemisphere of views it returns the irradiance a mirror
    /// would, `E cos θ_sun` (with `F = 1`), for rough and smooth water alike, up to the light its
    /// masking takes at grazing views. Measured: within 4.1e-7 for slope variances up to 0.01.
    #[test]
    fn the_glint_reflects_what_a_mirror_does() {
        let to_sun = DVec3::new(0.5, 0.2, 0.8).normalize();
        for (sxx, syy, sxy) in [(1e-4, 1e-4, 0.0), (4e-3, 1e-3, 5e-4), (0.01, 0.01, 0.0)] {
            let m = SlopeMoments {
                mean: DVec2::ZERO,
                xx: sxx,
                yy: syy,
                xy: sxy,
            };
            // Midpoint rule over the view hemisphere in (cos θ, φ), refined near the mirror peak by
            // the fine grid it needs.
            let (nu, nphi) = (4000, 4000);
            let mut flux = 0.0;
            for a in 0..nu {
                let mu = (a as f64 + 0.5) / nu as f64;
                let sin = (1.0 - mu * mu).sqrt();
                for b in 0..nphi {
                    let phi = 2.0 * std::f64::consts::PI * (b as f64 + 0.5) / nphi as f64;
                    let v = DVec3::new(sin * phi.cos(), sin * phi.sin(), mu);
                    flux += glint(v, to_sun, &m, 0.0).0 * mu;
                }
            }
            flux *= 2.0 * std::f64::consts::PI / (nu * nphi) as f64;
            let rel = flux / to_sun.z - 1.0;
            assert!(
                rel.abs() < 4e-6,
                "{sxx} {syy} {sxy}: {flux} vs {}",
                to_sun.z
            );
        }
    }
}
