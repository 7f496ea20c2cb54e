//! Hierarchical merging of small caustic triangles (paper 4, §5, named there as future work: "it is
//! worth combining small triangles into a single triangle adding up their power", mipmap based),
//! CPU twin of `caustic_triangles/pyramid.wgsl` and `merge.wgsl`.
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
//!
//! Layout: level `k` has `n_k = (P − 1) >> k` blocks per side, row major, at offset
//! `Σ_{j<k} n_j²`, one `[f32; 4]` each.

use glam::DVec2;

use super::{CausticTrianglesSetup, pos, quad_valid, tri_area};

/// Blocks per side of each level `0..=levels` and the offset of each level.
pub fn layout(p: usize, levels: u32) -> (Vec<usize>, Vec<usize>) {
    let mut sides = Vec::new();
    let mut offsets = Vec::new();
    let mut off = 0;
    for k in 0..=levels {
        let n = (p.saturating_sub(1)) >> k;
        sides.push(n);
        offsets.push(off);
        off += n * n;
    }
    (sides, offsets)
}

/// Area of the quad of photons `(i, j)`, `(i, j + s)`, `(i + s, j + s)`, `(i + s, j)` as the two
/// drawn triangles.
fn quad_area(photons: &[[f32; 4]], p: usize, i: usize, j: usize, s: usize) -> f64 {
    let c = |a: usize, b: usize| pos(&photons[(i + a) * p + j + b]);
    let (c00, c01, c11, c10) = (c(0, 0), c(0, s), c(s, s), c(s, 0));
    tri_area(c00, c01, c11) + tri_area(c00, c11, c10)
}

/// The merge pyramid of a photon image and its vertex irradiances.
pub fn pyramid_pass(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    irradiance: &[f32],
) -> Vec<[f32; 4]> {
    let p = setup.p;
    let (sides, offsets) = layout(p, setup.merge_levels);
    let total = offsets.last().unwrap() + sides.last().unwrap().pow(2);
    let mut pyr = vec![[0.0f32; 4]; total];
    let small = setup.merge_texels * setup.floor.texel_area();
    for qi in 0..sides[0] {
        for qj in 0..sides[0] {
            if !quad_valid(photons, p, qi as i64, qj as i64) {
                continue;
            }
            let k = |a: usize, b: usize| (qi + a) * p + qj + b;
            let v = |k: usize| (pos(&photons[k]), irradiance[k] as f64);
            let (a, b, c, d) = (v(k(0, 0)), v(k(0, 1)), v(k(1, 1)), v(k(1, 0)));
            let (a1, a2) = (tri_area(a.0, b.0, c.0), tri_area(a.0, c.0, d.0));
            let phi = a1 * (a.1 + b.1 + c.1) / 3.0 + a2 * (a.1 + c.1 + d.1) / 3.0;
            pyr[qi * sides[0] + qj] = [phi as f32, (a1 + a2) as f32, 1.0, photons[k(0, 0)][3]];
        }
    }
    for lvl in 1..sides.len() {
        let (n, m) = (sides[lvl], sides[lvl - 1]);
        let s = 1usize << lvl;
        for a in 0..n {
            for b in 0..n {
                let child =
                    |da: usize, db: usize| pyr[offsets[lvl - 1] + (2 * a + da) * m + 2 * b + db];
                let kids = [child(0, 0), child(0, 1), child(1, 0), child(1, 1)];
                let phi: f64 = kids.iter().map(|c| c[0] as f64).sum();
                let uniform = kids.iter().all(|c| c[2] > 0.0 && c[3] == kids[0][3]);
                let area = quad_area(photons, p, a * s, b * s, s);
                let merged = uniform && area > 0.0 && area < small;
                pyr[offsets[lvl] + a * n + b] = [
                    phi as f32,
                    area as f32,
                    if merged { 1.0 } else { 0.0 },
                    kids[0][3],
                ];
            }
        }
    }
    pyr
}

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
