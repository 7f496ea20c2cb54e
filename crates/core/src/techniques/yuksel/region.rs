//! The gather region (ours, beyond the paper's fixed N = 7, M = 6 of §6): N, M, their shift along
//! the refracted sun and the level, chosen from a bound on the water's largest deflection. GPU
//! twin: `region_bound.wgsl` (the bound over every texel) and `region.wgsl` (one thread).

use glam::{DVec2, DVec3};

use crate::grid::Grid;
use crate::optics::{height_field_normal, refract};

use super::{MAX_LEVEL, MAX_M, MAX_N, Region, YukselSetup};

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

impl YukselSetup {
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
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::techniques::yuksel::tests::setup;
    use crate::techniques::yuksel::{YukselParams, prepass, unpack_half_widths};

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
