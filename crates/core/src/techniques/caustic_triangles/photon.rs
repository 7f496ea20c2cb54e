//! The photon tracing pass (§4.1), CPU twin of `caustic_triangles/photon.wgsl`: the photon hit
//! location image, and how its texels are read.

use glam::DVec2;

use super::{CausticTrianglesSetup, Crossing, DistanceMap};
use crate::optics::{fresnel_transmittance, reflect, refract};
use crate::parallel::prelude::*;

/// The marker of an invalid photon-image texel.
pub const INVALID: [f32; 4] = [0.0, 0.0, -1.0, 0.0];

/// Path signature of a photon that refracted `refractions` times and was totally internally
/// reflected `tir` times: `refractions + 64 tir`, exact in f32 (`depth` ≤ 32).
pub fn signature(refractions: u32, tir: u32) -> f32 {
    (refractions + 64 * tir) as f32
}

/// Photon tracing pass (§4.1) for texel `(i, j)`: `(x, y, Φ, σ)` of its floor hit ([`signature`]),
/// or [`INVALID`].
pub fn photon(setup: &CausticTrianglesSetup, dm: &DistanceMap, i: usize, j: usize) -> [f32; 4] {
    let Some((mut x, mut r, mut power)) = setup.photon_ray(dm, i, j) else {
        return INVALID;
    };
    let mut inside = false;
    let mut hit_glass = false;
    let mut d0 = 0.0;
    let (mut refractions, mut tir) = (0u32, 0u32);
    let eps = 1e-4 * dm.radius;
    for event in 0..=setup.depth {
        let d_floor = if r.z < 0.0 { -x.z / r.z } else { f64::INFINITY };
        // Where the ray leaves the sphere holding the map's surfaces.
        let oc = x - dm.centre;
        let b = oc.dot(r);
        let disc = b * b - (oc.length_squared() - dm.radius * dm.radius);
        let d_out = if disc > 0.0 { -b + disc.sqrt() } else { 0.0 };
        let d1 = d_out.min(d_floor);
        let crossing = if inside {
            Crossing::Leaving
        } else {
            Crossing::Entering
        };
        match dm.trace(
            x,
            r,
            d0,
            d1,
            crossing,
            setup.linear_steps,
            setup.secant_iterations,
        ) {
            None => {
                if !hit_glass || inside || !d_floor.is_finite() {
                    return INVALID;
                }
                let p = x + r * d_floor;
                return [
                    p.x as f32,
                    p.y as f32,
                    power as f32,
                    signature(refractions, tir),
                ];
            }
            Some((_, s)) if !s.glass => return INVALID,
            Some((d, s)) => {
                if event == setup.depth {
                    return INVALID;
                }
                hit_glass = true;
                x += r * d;
                let (n, n1, n2) = if inside {
                    (-s.normal, setup.ior, 1.0)
                } else {
                    (s.normal, 1.0, setup.ior)
                };
                let cos_i = -r.dot(n);
                match refract(r, n, n1 / n2) {
                    Some(t) => {
                        if setup.fresnel {
                            power *= fresnel_transmittance(cos_i, n1, n2);
                        }
                        r = t.normalize();
                        inside = !inside;
                        refractions += 1;
                    }
                    None => {
                        r = reflect(r, n).normalize();
                        tir += 1;
                    }
                }
                d0 = eps;
            }
        }
    }
    INVALID
}

/// The photon hit location image, row `i` (light-space `v`) major.
pub fn photon_pass(setup: &CausticTrianglesSetup, dm: &DistanceMap) -> Vec<[f32; 4]> {
    let p = setup.p;
    (0..p * p)
        .into_par_iter()
        .map(|k| photon(setup, dm, k / p, k % p))
        .collect()
}

pub(super) fn valid(t: &[f32; 4]) -> bool {
    t[2] >= 0.0
}

/// Whether photon `t` is valid and took the same path (signature) as the valid photon `me`.
pub fn same_path(me: &[f32; 4], t: &[f32; 4]) -> bool {
    valid(t) && t[3] == me[3]
}

pub(super) fn pos(t: &[f32; 4]) -> DVec2 {
    DVec2::new(t[0] as f64, t[1] as f64)
}

/// Total power of the valid photons, floor-area units.
pub fn photon_power(photons: &[[f32; 4]]) -> f64 {
    photons
        .iter()
        .filter(|t| valid(t))
        .map(|t| t[2] as f64)
        .sum()
}
