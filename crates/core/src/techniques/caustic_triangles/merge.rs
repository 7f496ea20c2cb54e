//! Hierarchical merging of small caustic triangles (paper 4, §5, named there as future work: "it is
//! worth combining small triangles into a single triangle adding up their power", mipmap based),
//! CPU twin of `caustic_triangles/merge.wgsl` (the pyramid it reads: [`pyramid`](super::pyramid),
//! `pyramid.wgsl`).
//!
//! In a focus the caustic triangles shrink below a texel: rasterised at texel centres most cover
//! none and their power is lost (−4 to −11 % on the resting sphere). The pyramid merges them:
//! - level 0 holds per photon-image quad `(Φ, A, valid, σ)`: the power its two Gouraud triangles
//!   carry, `Φ = Σ_t A_t (E_a + E_b + E_c) / 3`, their floor area, whether it is drawn, its path;
//! - a level-`k` block is the `2^k x 2^k` quads from `(a 2^k, b 2^k)`; it is *merged* when its four
//!   level-`k−1` children are valid (level 1) or merged (above) with one signature and the quad of
//!   its corner photons covers less than `merge_texels` floor-map texels (and more than nothing);
//!   its `Φ` is the sum of its children's.
//!
//! Merging is hereditary (a merged block's sub-blocks are merged), so every quad finds the same
//! highest merged block above it; that block's corner quad draws it, as two flat-shaded triangles
//! of irradiance `Φ / A` over its corner photons, and the other quads inside draw nothing. The power
//! of the merged quads is kept exactly; what a merged quad smaller than a texel still misses at
//! texel centres is the residual loss.

use glam::DVec2;

use super::CausticTrianglesSetup;
use super::irradiance::quad_valid;
use super::photon::pos;
pub use super::pyramid::{layout, pyramid_pass};

/// What quad `(qi, qj)` draws: `None`, or the level of the block whose corner it is (0: itself,
/// Gouraud) with the flat irradiance of a merged block.
pub fn quad_draw(
    setup: &CausticTrianglesSetup,
    pyr: &[[f32; 4]],
    qi: usize,
    qj: usize,
) -> Option<(usize, f64)> {
    let (sides, offsets) = layout(setup.p, setup.merge_levels);
    if pyr[qi * sides[0] + qj][2] <= 0.0 {
        return None;
    }
    let mut level = 0;
    for k in 1..sides.len() {
        let (a, b) = (qi >> k, qj >> k);
        if a >= sides[k] || b >= sides[k] || pyr[offsets[k] + a * sides[k] + b][2] <= 0.0 {
            break;
        }
        level = k;
    }
    if level == 0 {
        return Some((0, 0.0));
    }
    let s = 1usize << level;
    if !qi.is_multiple_of(s) || !qj.is_multiple_of(s) {
        return None;
    }
    let t = pyr[offsets[level] + (qi >> level) * sides[level] + (qj >> level)];
    Some((level, t[0] as f64 / t[1] as f64))
}

/// Every drawn quad: its corner photons' floor hits (00, 01, 11, 10), their values, and their
/// indices in the photon image (what a water generator's path lengths are read by).
pub fn drawn_quads(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    irradiance: &[f32],
) -> Vec<([DVec2; 4], [f64; 4], [usize; 4])> {
    let p = setup.p;
    let pyr = (setup.merge_levels > 0).then(|| pyramid_pass(setup, photons, irradiance));
    let mut out = Vec::new();
    for qi in 0..p.saturating_sub(1) {
        for qj in 0..p - 1 {
            let (s, flat) = match &pyr {
                None if quad_valid(photons, p, qi as i64, qj as i64) => (1, None),
                None => continue,
                Some(pyr) => match quad_draw(setup, pyr, qi, qj) {
                    None => continue,
                    Some((0, _)) => (1, None),
                    Some((l, e)) => (1usize << l, Some(e)),
                },
            };
            let k = [(0, 0), (0, s), (s, s), (s, 0)].map(|(a, b)| (qi + a) * p + qj + b);
            let x = k.map(|k| pos(&photons[k]));
            let e = match flat {
                Some(e) => [e; 4],
                None => k.map(|k| irradiance[k] as f64),
            };
            out.push((x, e, k));
        }
    }
    out
}
