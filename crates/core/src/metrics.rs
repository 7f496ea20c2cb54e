//! How far a caustics map is from the reference: the numbers `caustics compare` reports.
//!
//! All act on the mean of the RGB channels (the raw map).
//! - relative L1: `Σ|a − r| / Σ|r|`, the share of the reference's light that is misplaced or missing;
//! - relative RMSE: `sqrt(mean((a − r)²)) / mean(r)`;
//! - flux error: `Σa / Σr − 1`, light gained (+) or lost (−) over the whole map;
//! - SSIM (Wang et al. 2004) of the tone-mapped maps (`tone_map`), 8 x 8 windows, `C1 = (0.01)²`,
//!   `C2 = (0.03)²` for values in [0, 1]: structure, as an eye compares two caustic patterns.

use crate::grid::Grid;
use crate::map::CausticsMap;

/// A map's distances from the reference, as defined in the module's doc.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metrics {
    /// `Σ|a − r| / Σ|r|`: the share of the reference's light misplaced or missing (0 is exact).
    pub relative_l1: f64,
    /// `sqrt(mean((a − r)²)) / mean(r)` (0 is exact).
    pub relative_rmse: f64,
    /// `Σa / Σr − 1`: light gained (+) or lost (−) over the whole map.
    pub flux_error: f64,
    /// Mean SSIM of the tone-mapped maps, up to 1 for identical ones.
    pub ssim: f64,
}

/// The metrics of a technique's map against the reference's, on their channel means; the maps
/// must have the same size (panics otherwise).
pub fn compare(technique: &CausticsMap, reference: &CausticsMap) -> Metrics {
    compare_grids(&technique.mean_channel(), &reference.mean_channel())
}

/// The metrics of single-channel map `a` against the reference `r`, of the same size (panics
/// otherwise).
pub fn compare_grids(a: &Grid, r: &Grid) -> Metrics {
    assert_eq!(
        (a.cols, a.rows),
        (r.cols, r.rows),
        "maps of different sizes"
    );
    let n = a.data.len() as f64;
    let (mut l1, mut l1_ref, mut sq, mut sum_a, mut sum_r) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (&x, &y) in a.data.iter().zip(&r.data) {
        let (x, y) = (x as f64, y as f64);
        l1 += (x - y).abs();
        l1_ref += y.abs();
        sq += (x - y) * (x - y);
        sum_a += x;
        sum_r += y;
    }
    Metrics {
        relative_l1: l1 / l1_ref,
        relative_rmse: (sq / n).sqrt() / (sum_r / n),
        flux_error: sum_a / sum_r - 1.0,
        ssim: ssim(&tone_map(a), &tone_map(r)),
    }
}

/// Relative irradiance to [0, 1] as a display would show it: `E / (1 + E)` scaled so flat water
/// (1.0) sits at mid-grey. Bright foci compress instead of clipping.
pub fn tone_map(g: &Grid) -> Grid {
    Grid {
        cols: g.cols,
        rows: g.rows,
        data: g
            .data
            .iter()
            .map(|&e| e.max(0.0) / (1.0 + e.max(0.0)))
            .collect(),
    }
}

/// Mean SSIM over non-overlapping 8 x 8 windows (the whole map when smaller).
pub fn ssim(a: &Grid, b: &Grid) -> f64 {
    const C1: f64 = 0.01 * 0.01;
    const C2: f64 = 0.03 * 0.03;
    let win = 8.min(a.cols).min(a.rows);
    let (mut total, mut count) = (0.0, 0);
    for i0 in (0..=a.rows - win).step_by(win) {
        for j0 in (0..=a.cols - win).step_by(win) {
            let (mut ma, mut mb) = (0.0, 0.0);
            let n = (win * win) as f64;
            for i in i0..i0 + win {
                for j in j0..j0 + win {
                    ma += a.at(i, j) as f64;
                    mb += b.at(i, j) as f64;
                }
            }
            ma /= n;
            mb /= n;
            let (mut va, mut vb, mut cov) = (0.0, 0.0, 0.0);
            for i in i0..i0 + win {
                for j in j0..j0 + win {
                    let (x, y) = (a.at(i, j) as f64 - ma, b.at(i, j) as f64 - mb);
                    va += x * x;
                    vb += y * y;
                    cov += x * y;
                }
            }
            va /= n - 1.0;
            vb /= n - 1.0;
            cov /= n - 1.0;
            total += ((2.0 * ma * mb + C1) * (2.0 * cov + C2))
                / ((ma * ma + mb * mb + C1) * (va + vb + C2));
            count += 1;
        }
    }
    total / count as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(v: &[f32], cols: usize) -> Grid {
        Grid {
            cols,
            rows: v.len() / cols,
            data: v.to_vec(),
        }
    }

    #[test]
    fn known_differences_give_known_numbers() {
        let r = grid(&[1.0, 1.0, 2.0, 0.0], 2);
        let a = grid(&[1.5, 1.0, 1.0, 0.0], 2);
        let m = compare_grids(&a, &r);
        // |0.5| + |−1| over Σ|r| = 4.
        assert!((m.relative_l1 - 1.5 / 4.0).abs() < 1e-12);
        // sqrt((0.25 + 1) / 4) / mean(r) = 1.
        assert!((m.relative_rmse - (1.25f64 / 4.0).sqrt()).abs() < 1e-12);
        // Σa = 3.5 against 4.
        assert!((m.flux_error - (3.5 / 4.0 - 1.0)).abs() < 1e-12);
    }

    #[test]
    fn ssim_is_one_for_equal_maps_and_falls_with_noise() {
        let g = Grid::from_fn(32, 32, |i, j| ((i * 3 + j * 5) % 7) as f32 * 0.3);
        assert!((ssim(&tone_map(&g), &tone_map(&g)) - 1.0).abs() < 1e-12);
        let noisy = Grid::from_fn(32, 32, |i, j| {
            g.at(i, j) + if (i + j) % 2 == 0 { 0.4 } else { -0.4 }
        });
        let s = ssim(&tone_map(&noisy), &tone_map(&g));
        assert!(s < 0.9 && s > 0.0, "{s}");
        // A constant offset of the means alone: SSIM's luminance term, (2 μa μb + C1) / (μa² + μb² + C1).
        let a = Grid::from_fn(8, 8, |_, _| 0.5);
        let b = Grid::from_fn(8, 8, |_, _| 0.25);
        let expected = (2.0 * 0.5 * 0.25 + 1e-4) / (0.25 + 0.0625 + 1e-4);
        assert!((ssim(&a, &b) - expected).abs() < 1e-9);
    }
}
