//! The caustics map: relative irradiance per RGB channel on the floor square, texel `(i, j)` centred
//! at `((j + 0.5) size / width, (i + 0.5) size / height)`, row 0 at y = 0. 1.0 is the irradiance that
//! the same sun gives through a flat, non-absorbing water surface onto a horizontal floor.

use std::path::Path;

use crate::error::Result;
use crate::grid::Grid;

/// Relative irradiance on the floor square `[0, size]²`, RGB per texel (see the module's doc).
#[derive(Clone, Debug, PartialEq)]
pub struct CausticsMap {
    /// Texels along x.
    pub width: usize,
    /// Texels along y.
    pub height: usize,
    /// Side of the floor square the map covers, world units.
    pub size: f64,
    /// `width · height` texels of `[r, g, b]` relative irradiance, row by row, row 0 at y = 0.
    pub texels: Vec<[f32; 3]>,
}

impl CausticsMap {
    /// A black map (no light anywhere) over the square of side `size`.
    pub fn new(width: usize, height: usize, size: f64) -> Self {
        CausticsMap {
            width,
            height,
            size,
            texels: vec![[0.0; 3]; width * height],
        }
    }

    /// A grey map over the square of side `size`: each grid sample in all three channels.
    pub fn from_grid(g: &Grid, size: f64) -> Self {
        CausticsMap {
            width: g.cols,
            height: g.rows,
            size,
            texels: g.data.iter().map(|&v| [v; 3]).collect(),
        }
    }

    /// The single-channel map the raw outputs hold: the mean of the channels, which is the relative
    /// irradiance itself when the water absorbs nothing.
    pub fn mean_channel(&self) -> Grid {
        Grid {
            cols: self.width,
            rows: self.height,
            data: self
                .texels
                .iter()
                .map(|t| (t[0] + t[1] + t[2]) / 3.0)
                .collect(),
        }
    }

    /// This map plus `other` texel by texel (the caustics of several generators, each traced on
    /// its own, on one floor).
    pub fn added(mut self, other: &CausticsMap) -> CausticsMap {
        for (a, b) in self.texels.iter_mut().zip(&other.texels) {
            for c in 0..3 {
                a[c] += b[c];
            }
        }
        self
    }

    /// Flux on the floor square (channel mean): relative irradiance times area, the unit of
    /// [`crate::walls::WallMap::flux`], so floor and walls add up.
    pub fn flux(&self) -> f64 {
        let sum: f64 = self
            .texels
            .iter()
            .map(|t| (t[0] + t[1] + t[2]) as f64 / 3.0)
            .sum();
        sum * self.size * self.size / (self.width * self.height) as f64
    }

    /// Bilinear lookup at floor point `(x, y)`, clamped at the edges (or wrapped).
    pub fn sample(&self, x: f64, y: f64, wrap: bool) -> [f32; 3] {
        let u = x / self.size * self.width as f64 - 0.5;
        let v = y / self.size * self.height as f64 - 0.5;
        let (j0, i0) = (u.floor(), v.floor());
        let (fu, fv) = ((u - j0) as f32, (v - i0) as f32);
        let fetch = |i: i64, j: i64| {
            let (i, j) = if wrap {
                (
                    i.rem_euclid(self.height as i64),
                    j.rem_euclid(self.width as i64),
                )
            } else {
                (
                    i.clamp(0, self.height as i64 - 1),
                    j.clamp(0, self.width as i64 - 1),
                )
            };
            self.texels[i as usize * self.width + j as usize]
        };
        let (i0, j0) = (i0 as i64, j0 as i64);
        let (a, b, c, d) = (
            fetch(i0, j0),
            fetch(i0, j0 + 1),
            fetch(i0 + 1, j0),
            fetch(i0 + 1, j0 + 1),
        );
        std::array::from_fn(|k| {
            (a[k] * (1.0 - fu) + b[k] * fu) * (1.0 - fv) + (c[k] * (1.0 - fu) + d[k] * fu) * fv
        })
    }

    /// Write the raw map: `.npy` (float32, shape (height, width)) or `.exr`, by extension.
    pub fn write_raw(&self, path: &Path) -> Result<()> {
        self.mean_channel().write_raw(path, "the raw caustics maps")
    }
}

/// Most taps a footprint-filtered lookup takes along its footprint's long axis (as a GPU's
/// anisotropic filtering does); longer footprints take coarser levels. `MAX_TAPS` in
/// final_image_inputs.wgsl.
pub const MAX_TAPS: usize = 8;

/// A caustics map and its box-filtered halvings: level `L` has `max(1, width >> L)` x
/// `max(1, height >> L)` texels over the same square, each the mean of the 2 x 2 texels of level
/// `L - 1` under it (an odd last row or column is dropped), down to one texel along the longer
/// side. The final image reads it over each sample's footprint on the floor, so that caustics
/// seen far away or through waves blend as the many rays of a pixel would instead of aliasing.
/// GPU twin: `caustics_mips.wgsl` builds the same levels, `sample_caustics_filtered` in
/// final_image_inputs.wgsl reads them.
#[derive(Clone, Debug)]
pub struct MapPyramid {
    /// Level 0 (the map itself) first, each next one half the size, down to one texel.
    pub levels: Vec<CausticsMap>,
}

/// Levels of the pyramid of a `width` x `height` map, level 0 included.
pub fn pyramid_levels(width: usize, height: usize) -> usize {
    width.max(height).max(1).ilog2() as usize + 1
}

impl CausticsMap {
    /// This map's [`MapPyramid`].
    pub fn pyramid(&self) -> MapPyramid {
        let mut levels = vec![self.clone()];
        for _ in 1..pyramid_levels(self.width, self.height) {
            let fine = levels.last().expect("level 0");
            let (w, h) = ((fine.width / 2).max(1), (fine.height / 2).max(1));
            let at = |i: usize, j: usize| {
                fine.texels[i.min(fine.height - 1) * fine.width + j.min(fine.width - 1)]
            };
            let mut coarse = CausticsMap::new(w, h, self.size);
            for i in 0..h {
                for j in 0..w {
                    let (a, b) = (at(2 * i, 2 * j), at(2 * i, 2 * j + 1));
                    let (c, d) = (at(2 * i + 1, 2 * j), at(2 * i + 1, 2 * j + 1));
                    coarse.texels[i * w + j] =
                        std::array::from_fn(|k| (a[k] + b[k] + c[k] + d[k]) * 0.25);
                }
            }
            levels.push(coarse);
        }
        MapPyramid { levels }
    }
}

impl MapPyramid {
    /// The map's mean over the footprint centred on floor point `p` and spanned by `axes` (world
    /// units: the parallelogram one sample covers on the floor), clamped or wrapped at the edges.
    ///
    /// As a GPU's anisotropic filtering: up to [`MAX_TAPS`] taps spread along the footprint's long
    /// axis, each trilinear at the level whose filter has the variance of a box as wide as the
    /// part of the footprint it stands for (a box of width `w` has variance `w²/12`; bilinear at
    /// level `L` of box-filtered texels `4^L/4`, so `2^L = w/√3`). A footprint within a texel reads
    /// level 0 bilinearly, as [`CausticsMap::sample`] does. A map that does not wrap reads
    /// `beyond` for the taps off its square where one is given (the light there is known
    /// otherwise), its clamped edges where not.
    pub fn filtered(
        &self,
        p: glam::DVec2,
        axes: [glam::DVec2; 2],
        wrap: bool,
        beyond: Option<[f32; 3]>,
    ) -> [f32; 3] {
        let base = &self.levels[0];
        let texels = glam::DVec2::new(base.width as f64, base.height as f64) / base.size;
        let (a, b) = (axes[0] * texels, axes[1] * texels);
        let (long, la) = if a.length() >= b.length() {
            (a, a.length())
        } else {
            (b, b.length())
        };
        // The parallelogram's width across its long side.
        let across = if la > 0.0 {
            a.perp_dot(b).abs() / la
        } else {
            0.0
        };
        let (la, across) = (la.max(1.0), across.max(1.0));
        let taps = ((la / across).ceil() as usize).clamp(1, MAX_TAPS);
        let width = (la / taps as f64).max(across);
        let level = (width / 3f64.sqrt()).log2().max(0.0);
        let step = long / texels;
        let mut sum = [0.0f32; 3];
        for t in 0..taps {
            let q = p + step * ((t as f64 + 0.5) / taps as f64 - 0.5);
            let off = !wrap
                && (q.cmplt(glam::DVec2::ZERO).any()
                    || q.cmpgt(glam::DVec2::splat(base.size)).any());
            let c = match beyond {
                Some(v) if off => v,
                _ => self.trilinear(q, level, wrap),
            };
            for k in 0..3 {
                sum[k] += c[k];
            }
        }
        sum.map(|s| s / taps as f32)
    }

    /// Bilinear at levels `floor(level)` and the next, blended by the fraction.
    fn trilinear(&self, p: glam::DVec2, level: f64, wrap: bool) -> [f32; 3] {
        let last = self.levels.len() - 1;
        let l0 = (level.floor() as usize).min(last);
        let f = if l0 == last {
            0.0
        } else {
            (level - l0 as f64) as f32
        };
        let a = self.levels[l0].sample(p.x, p.y, wrap);
        if f == 0.0 {
            return a;
        }
        let b = self.levels[l0 + 1].sample(p.x, p.y, wrap);
        std::array::from_fn(|k| a[k] * (1.0 - f) + b[k] * f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    fn checker(n: usize) -> CausticsMap {
        let mut m = CausticsMap::new(n, n, 2.0);
        for i in 0..n {
            for j in 0..n {
                let v = if (i + j) % 2 == 0 { 2.0 } else { 0.0 };
                m.texels[i * n + j] = [v, v * 0.5, 1.0];
            }
        }
        m
    }

    #[test]
    fn levels_halve_to_one_texel_and_keep_the_mean() {
        let mut m = CausticsMap::new(12, 5, 1.0);
        for (k, t) in m.texels.iter_mut().enumerate() {
            *t = [(k % 7) as f32, 1.0, (k % 3) as f32];
        }
        let p = m.pyramid();
        let dims: Vec<_> = p.levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(dims, [(12, 5), (6, 2), (3, 1), (1, 1)]);
        // A constant channel stays constant at every level.
        assert!(
            p.levels
                .iter()
                .all(|l| l.texels.iter().all(|t| t[1] == 1.0))
        );
        // Even sizes: every level's flux is the map's.
        let even = checker(16).pyramid();
        for l in &even.levels {
            assert!(
                (l.flux() - even.levels[0].flux()).abs() < 1e-9,
                "{}",
                l.flux()
            );
        }
    }

    #[test]
    fn a_point_footprint_reads_level_zero_and_a_wide_one_the_mean() {
        let m = checker(64);
        let p = m.pyramid();
        let q = DVec2::new(0.37, 1.21);
        let point = p.filtered(q, [DVec2::ZERO; 2], false, None);
        assert_eq!(point, m.sample(q.x, q.y, false));
        // A footprint of many texels each way averages the checker to its mean, 1.
        let wide = p.filtered(q, [DVec2::new(0.4, 0.0), DVec2::new(0.0, 0.4)], false, None);
        assert!(
            (wide[0] - 1.0).abs() < 1e-6 && (wide[1] - 0.5).abs() < 1e-6,
            "{wide:?}"
        );
        // So does a long, thin one: its taps along the long axis at a level as fine as its width.
        let thin = p.filtered(q, [DVec2::new(0.5, 0.5), DVec2::new(-0.1, 0.1)], true, None);
        assert!((thin[0] - 1.0).abs() < 1e-6, "{thin:?}");
    }

    #[test]
    fn the_filter_is_symmetric_in_its_axes_and_their_signs() {
        let mut m = CausticsMap::new(32, 32, 1.0);
        for (k, t) in m.texels.iter_mut().enumerate() {
            let v = ((k * 2_654_435_761) % 1000) as f32 / 1000.0;
            *t = [v, v, v];
        }
        let p = m.pyramid();
        let q = DVec2::new(0.41, 0.63);
        let (a, b) = (DVec2::new(0.11, 0.02), DVec2::new(-0.01, 0.04));
        let r = p.filtered(q, [a, b], false, None);
        for axes in [[b, a], [-a, b], [a, -b], [-b, -a]] {
            let s = p.filtered(q, axes, false, None);
            assert!((s[0] - r[0]).abs() < 1e-6, "{s:?} {r:?}");
        }
    }

    /// The filter is a box over the footprint: on stripes `cos(2π x / 16 texels)` along x, a
    /// footprint `L` texels long along x reads about the stripes' box mean over it, `sinc(π L /
    /// 16)` times the point value, and one as long along y (along the stripes) reads the point's.
    /// Averaged over the whole (wrapped) map, any footprint keeps the map's mean: the filter moves
    /// light about, it neither makes nor loses any.
    #[test]
    fn the_filter_is_a_box_that_keeps_the_mean() {
        let n = 128;
        let size = 1.0;
        let mut m = CausticsMap::new(n, n, size);
        for i in 0..n {
            for j in 0..n {
                let x = (j as f64 + 0.5) / 16.0;
                let v = 1.0 + 0.5 * (2.0 * std::f64::consts::PI * x).cos();
                m.texels[i * n + j] = [v as f32; 3];
            }
        }
        let p = m.pyramid();
        let texel = size / n as f64;
        let mut worst: f64 = 0.0;
        for l in [4.0, 8.0, 12.0] {
            let across = [DVec2::new(l * texel, 0.0), DVec2::new(0.0, 0.5 * texel)];
            let along = [DVec2::new(0.0, l * texel), DVec2::new(0.5 * texel, 0.0)];
            let arg = std::f64::consts::PI * l / 16.0;
            let gain = arg.sin() / arg;
            for k in 0..16 {
                let q = DVec2::new((k as f64 + 0.25) * 8.0 * texel, 0.5);
                let x = q.x / texel / 16.0;
                let point = 0.5 * (2.0 * std::f64::consts::PI * x).cos();
                let box_mean = 1.0 + gain * point;
                let got = p.filtered(q, across, true, None)[0] as f64;
                worst = worst.max((got - box_mean).abs());
                let still = p.filtered(q, along, true, None)[0] as f64;
                // Measured: equal (level 0, the taps along the stripes).
                assert!(
                    (still - m.sample(q.x, q.y, true)[0] as f64).abs() < 1e-6,
                    "{l} {k}"
                );
            }
        }
        // Measured: 0.0021 at most, against stripes of amplitude 0.5 whose box means over 4, 8
        // and 12 texels keep 0.90, 0.64 and 0.30 of it.
        assert!(worst < 0.02, "{worst}");
        for axes in [
            [
                DVec2::new(6.0 * texel, 2.0 * texel),
                DVec2::new(-texel, 3.0 * texel),
            ],
            [DVec2::new(40.0 * texel, 0.0), DVec2::new(0.0, 40.0 * texel)],
        ] {
            let mut sum = 0.0;
            let k = 97;
            for a in 0..k {
                for b in 0..k {
                    let q = DVec2::new((a as f64 + 0.5) / k as f64, (b as f64 + 0.5) / k as f64);
                    sum += p.filtered(q * size, axes, true, None)[0] as f64;
                }
            }
            let mean = sum / (k * k) as f64;
            // Measured: 1.000039 and 1.000000.
            assert!((mean - 1.0).abs() < 4e-4, "{mean}");
        }
    }

    /// A footprint across the edge of a map that does not wrap reads the light given for beyond
    /// it in its taps off the square, not the clamped edge: half off, half the way to it.
    #[test]
    fn taps_beyond_the_edge_read_the_light_beyond() {
        let mut m = CausticsMap::new(64, 64, 1.0);
        m.texels.iter_mut().for_each(|t| *t = [2.0; 3]);
        let p = m.pyramid();
        let axes = [DVec2::new(0.2, 0.0), DVec2::new(0.0, 0.02)];
        let q = DVec2::new(1.0, 0.5);
        let beyond = [0.5; 3];
        let half = p.filtered(q, axes, false, Some(beyond))[0];
        // 8 taps, 4 of them beyond x = 1: (4 x 2 + 4 x 0.5) / 8.
        assert_eq!(half, 1.25);
        assert_eq!(p.filtered(q, axes, false, None)[0], 2.0);
        assert_eq!(p.filtered(q, axes, true, Some(beyond))[0], 2.0);
    }
}
