//! The geometry every pass repeats, `common.wgsl`'s: where a texel's sun ray starts
//! ([`CascadedSetup::ray_origin`]), the terrain hit of a ray ([`CascadedSetup::terrain_hit`],
//! [`terrain_march`]) and, with the pool's walls, the box of receivers
//! ([`CascadedSetup::box_hit`], [`CascadedSetup::receiver_normal`]).

use glam::{DVec2, DVec3};

use super::CascadedSetup;
use crate::grid::{Edge, Grid};
use crate::walls::Wall;

/// Even steps of the terrain march across the terrain's height range, before bisection.
pub const MARCH_STEPS: u32 = 64;
/// Bisection steps that refine the terrain hit the march brackets.
pub const BISECTION_STEPS: u32 = 20;

impl CascadedSetup {
    /// Where texel `(i, j)` of cascade `k`'s sun ray starts.
    pub fn ray_origin(&self, k: usize, i: usize, j: usize) -> DVec3 {
        let c = &self.cascades[k];
        let u = c.u0 + (j as f64 + 0.5) * c.du;
        let v = c.v0 + (i as f64 + 0.5) * c.dv;
        self.e_u * u + self.e_v * v + self.light * c.w0
    }

    /// Relative flux one photon of cascade `k` carries: `E⊥ du dv` with `E_h = 1`.
    pub fn photon_flux(&self, k: usize) -> f64 {
        self.cascades[k].du * self.cascades[k].dv / -self.light.z
    }

    pub(super) fn terrain_height(&self, terrain: Option<&Grid>, p: DVec2) -> (f64, DVec2) {
        match (terrain, self.terrain_range) {
            (Some(g), Some(_)) => g.sample(p, self.size, Edge::Clamp),
            _ => (0.0, DVec2::ZERO),
        }
    }

    /// The first terrain hit of the ray `o + s d` (`d` unit): a march of [`MARCH_STEPS`] even steps
    /// across the terrain's height range, then [`BISECTION_STEPS`] of bisection. The plane z = 0
    /// without terrain.
    pub fn terrain_hit(&self, terrain: Option<&Grid>, o: DVec3, d: DVec3) -> Option<f64> {
        if self.walls && self.terrain_range.is_none() {
            return self.box_hit(o, d);
        }
        terrain_march(o, d, self.terrain_range, MARCH_STEPS, |p| {
            self.terrain_height(terrain, p).0
        })
    }
}

impl CascadedSetup {
    /// With walls: where the ray `o + s d` (`d` pointing down) first meets a receiver, the floor or a
    /// wall's inside. A ray from above the rim enters through the pool's open top (the rest level)
    /// and must do so inside the square (else it meets the pool's surround: `None`); from inside the
    /// box it leaves through the floor where its floor point lies in the square, else through the
    /// wall [`Wall::exit`] names. Also the exact placement of a refracted photon
    /// ([`place_photon`](super::place_photon)).
    pub fn box_hit(&self, o: DVec3, d: DVec3) -> Option<f64> {
        if d.z >= 0.0 {
            return None;
        }
        let s0 = if o.z > self.level {
            (self.level - o.z) / d.z
        } else {
            0.0
        };
        let p = o + d * s0;
        let inside =
            |q: DVec3| (0.0..=self.size).contains(&q.x) && (0.0..=self.size).contains(&q.y);
        if !inside(p) {
            return None;
        }
        let s_floor = -p.z / d.z;
        if inside(p + d * s_floor) {
            return Some(s0 + s_floor);
        }
        let (_, s) = Wall::exit(p.truncate(), d.truncate(), self.size)?;
        Some(s0 + s)
    }

    /// The inward normal of the receiver a [`box_hit`](Self::box_hit) point lies on: the floor's
    /// below a millionth of the level, else the nearest wall's.
    pub fn receiver_normal(&self, p: DVec3) -> DVec3 {
        if p.z <= 1e-6 * self.level {
            return DVec3::Z;
        }
        let d = [p.x, self.size - p.x, p.y, self.size - p.y];
        let mut k = 0;
        for n in 1..4 {
            if d[n] < d[k] {
                k = n;
            }
        }
        Wall::ALL[k].normal()
    }
}

/// The march of [`CascadedSetup::terrain_hit`] with any step count (the tests use a fine one as the
/// exact hit).
pub fn terrain_march(
    o: DVec3,
    d: DVec3,
    range: Option<(f64, f64)>,
    steps: u32,
    height: impl Fn(DVec2) -> f64,
) -> Option<f64> {
    if d.z >= 0.0 {
        return None;
    }
    let Some((lo, hi)) = range else {
        let s = -o.z / d.z;
        return (s >= 0.0).then_some(s);
    };
    let s_a = ((hi - o.z) / d.z).max(0.0);
    let s_b = (lo - o.z) / d.z;
    if s_b < 0.0 {
        return None;
    }
    let gap = |s: f64| {
        let p = o + d * s;
        p.z - height(p.truncate())
    };
    if gap(s_a) <= 0.0 {
        return Some(s_a);
    }
    let step = (s_b - s_a) / steps as f64;
    let mut a = s_a;
    for n in 1..=steps {
        let b = s_a + step * n as f64;
        if gap(b) <= 0.0 {
            return Some(crate::receivers::bisect(gap, a, b, BISECTION_STEPS));
        }
        a = b;
    }
    Some(s_b)
}
