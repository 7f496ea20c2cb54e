//! The vertex irradiance pass (§5), CPU twin of `caustic_triangles/irradiance.wgsl`: each photon's
//! `E = ΔΦ / ΔA` by the area rule ([`AreaRule`]).

use glam::DVec2;

use super::photon::{pos, same_path, valid};
use super::{AreaRule, CausticTrianglesSetup};

use crate::parallel::prelude::*;

pub(super) fn tri_area(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    0.5 * (b - a).perp_dot(c - a).abs()
}

/// Whether all four corners of quad `(qi, qj)` (corners `(qi..=qi+1, qj..=qj+1)`) are valid and
/// share one path signature.
pub(super) fn quad_valid(photons: &[[f32; 4]], p: usize, qi: i64, qj: i64) -> bool {
    if qi < 0 || qj < 0 || qi + 1 >= p as i64 || qj + 1 >= p as i64 {
        return false;
    }
    let (qi, qj) = (qi as usize, qj as usize);
    let first = photons[qi * p + qj];
    valid(&first)
        && [(0, 1), (1, 0), (1, 1)]
            .iter()
            .all(|&(a, b)| same_path(&first, &photons[(qi + a) * p + qj + b]))
}

/// Vertex irradiance of texel `(i, j)` (the §5 pass): `ΔΦ / ΔA`, or −1 where invalid.
pub fn vertex_irradiance(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    i: usize,
    j: usize,
) -> f32 {
    let p = setup.p;
    let me = photons[i * p + j];
    if !valid(&me) {
        return -1.0;
    }
    let at = |di: i64, dj: i64| -> Option<DVec2> {
        let (a, b) = (i as i64 + di, j as i64 + dj);
        if a < 0 || b < 0 || a >= p as i64 || b >= p as i64 {
            return None;
        }
        let t = photons[a as usize * p + b as usize];
        same_path(&me, &t).then(|| pos(&t))
    };
    let v = pos(&me);
    let (mut sum, mut count) = (0.0, 0u32);
    match setup.area_rule {
        AreaRule::Paper => {
            // Right, up, left, down: consecutive pairs span the four corner triangles.
            let ring = [at(0, 1), at(1, 0), at(0, -1), at(-1, 0)];
            for k in 0..4 {
                if let (Some(a), Some(b)) = (ring[k], ring[(k + 1) % 4]) {
                    sum += tri_area(v, a, b);
                    count += 1;
                }
            }
            if count == 0 {
                return -1.0;
            }
            let da = 2.0 * sum / count as f64;
            (me[2] as f64 / da.max(1e-30)) as f32
        }
        AreaRule::Hat => {
            // A periodic image's quads past an edge are those at the opposite edge (triangle
            // areas do not see the shift by `size`).
            let wrap = setup.water.filter(|w| w.periodic).map(|w| w.lattice as i64);
            // The quads around the vertex; in quad (qi, qj) the vertex is corner (ci, cj).
            for (ci, cj) in [(0i64, 0i64), (0, 1), (1, 0), (1, 1)] {
                let (mut qi, mut qj) = (i as i64 - ci, j as i64 - cj);
                if let Some(l) = wrap {
                    (qi, qj) = (qi.rem_euclid(l), qj.rem_euclid(l));
                }
                if !quad_valid(photons, p, qi, qj) {
                    continue;
                }
                let c = |a: i64, b: i64| pos(&photons[((qi + a) as usize) * p + (qj + b) as usize]);
                let (c00, c01, c10, c11) = (c(0, 0), c(0, 1), c(1, 0), c(1, 1));
                // Triangle 1: 00, 01, 11; triangle 2: 00, 11, 10.
                let in1 = (ci, cj) != (1, 0);
                let in2 = (ci, cj) != (0, 1);
                if in1 {
                    sum += tri_area(c00, c01, c11);
                    count += 1;
                }
                if in2 {
                    sum += tri_area(c00, c11, c10);
                    count += 1;
                }
            }
            if count == 0 {
                return -1.0;
            }
            let da = sum / 3.0;
            (me[2] as f64 * setup.lattice_share(i, j) / da.max(1e-30)) as f32
        }
    }
}

/// The vertex irradiance pass (§5): [`vertex_irradiance`] of every photon-image texel, row major.
pub fn irradiance_pass(setup: &CausticTrianglesSetup, photons: &[[f32; 4]]) -> Vec<f32> {
    let p = setup.p;
    (0..p * p)
        .into_par_iter()
        .map(|k| vertex_irradiance(setup, photons, k / p, k % p))
        .collect()
}
