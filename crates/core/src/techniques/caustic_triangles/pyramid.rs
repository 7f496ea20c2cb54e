//! The merge pyramid of the hierarchical merging of small caustic triangles (§5, [`super::merge`]),
//! CPU twin of `caustic_triangles/pyramid.wgsl`.
//!
//! Layout: level `k` has `n_k = (P − 1) >> k` blocks per side, row major, at offset
//! `Σ_{j<k} n_j²`, one `[f32; 4]` each.

use super::CausticTrianglesSetup;
use super::irradiance::{quad_valid, tri_area};
use super::photon::pos;

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
