//! Pass 1 (Fig. 5): for each pixel, the `N` samples along x around its illumination centre, each
//! adding its share of the pixel and of the `M` pixels beside it along y to `M + 1` channels. GPU
//! twin: `pass1.wgsl`, a fragment shader into multiple render targets.

use super::prepass::{Tier, unpack_half_widths};
use super::{YukselSetup, box_share};

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
