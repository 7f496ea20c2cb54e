//! The view ray's search for the water surface and the floor: the slab the surface lies in, the
//! march through it to the first crossing, and where a ray meets the floor, terrain or pool walls.

use glam::{DVec2, DVec3};

use super::Tracer;
use crate::walls::Wall;
use crate::water::Surface;

/// Samples per side of the lattice [`slab_bounds`] searches.
pub const SLAB_LATTICE: usize = 128;

/// What the view rays' search for the water surface needs to know of it ([`slab_bounds`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Slab {
    /// Half the height of the slab the surface lies in, `|z − level| <= half_height`.
    pub half_height: f64,
    /// A bound on the surface's slope `|∇h|`, which limits how fast a ray's height above the
    /// surface can change (`first_crossing`).
    pub slope: f64,
}

/// The slab the water surface lies in and its steepest slope, which the view rays search: the
/// largest |h| and |∇h| on a [`SLAB_LATTICE`]² lattice of the square, each times 1.5 (room for
/// the interpolant between samples). The GPU's final image finds the same bounds on the GPU
/// (`final_image_slab.wgsl`).
pub fn slab_bounds(surface: &dyn Surface, size: f64) -> Slab {
    let n = SLAB_LATTICE;
    let (mut h, mut g): (f64, f64) = (0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            let p = DVec2::new(j as f64 + 0.5, i as f64 + 0.5) * (size / n as f64);
            let (height, gradient) = surface.height_gradient(p);
            h = h.max(height.abs());
            g = g.max(gradient.length());
        }
    }
    Slab {
        half_height: h * 1.5 + 1e-6,
        slope: g * 1.5 + 1e-6,
    }
}

impl Tracer<'_> {
    /// How a ray along `d` marches through the water's slab (`first_crossing`): its height
    /// above the surface changes by at most `|d_z| + slope · |d_xy|` per unit of distance.
    fn march(&self, d: DVec3) -> March {
        March {
            rate: d.z.abs() + self.slope_max * d.truncate().length(),
            min_step: self.min_step,
        }
    }

    /// The first crossing of the ray with `z = level + h(x, y)`.
    pub(super) fn hit_water(
        &self,
        s: &dyn Surface,
        o: DVec3,
        d: DVec3,
        level: f64,
    ) -> Option<(f64, DVec3)> {
        let top = level + self.h_max;
        let bottom = level - self.h_max;
        if o.z < bottom || d.z >= 0.0 {
            return None; // `trace` follows rays in the air, which meet the surface from above
        }
        let t0 = ((top - o.z) / d.z).max(0.0);
        let t1 = (bottom - o.z) / d.z;
        let f = |t: f64| {
            let p = o + d * t;
            p.z - level - s.height(p.truncate())
        };
        let t = first_crossing(f, t0, t1, self.march(d));
        Some((t, o + d * t))
    }

    /// The first crossing of a rising underwater ray with `z = level + h(x, y)` (the rest plane
    /// without a surface); `None` for a ray going down or level, or starting over the surface's
    /// slab, which cannot meet it from below.
    pub(super) fn hit_water_from_below(
        &self,
        o: DVec3,
        d: DVec3,
        level: f64,
    ) -> Option<(f64, DVec3)> {
        if d.z <= 0.0 {
            return None;
        }
        let Some(s) = self.surface else {
            let t = ((level - o.z) / d.z).max(0.0);
            return Some((t, o + d * t));
        };
        let (bottom, top) = (level - self.h_max, level + self.h_max);
        if o.z > top {
            return None;
        }
        let t0 = ((bottom - o.z) / d.z).max(0.0);
        let t1 = (top - o.z) / d.z;
        // Depth of the ray below the surface at distance t.
        let f = |t: f64| {
            let p = o + d * t;
            level + s.height(p.truncate()) - p.z
        };
        let t = first_crossing(f, t0, t1, self.march(d));
        Some((t, o + d * t))
    }

    /// Distance to and point on the floor or terrain along an underwater ray.
    pub(super) fn hit_floor(&self, o: DVec3, d: DVec3) -> (f64, DVec3) {
        if d.z >= 0.0 {
            return (f64::INFINITY, o);
        }
        match &self.scene.floor.terrain {
            None => {
                let t = -o.z / d.z;
                (t, o + d * t)
            }
            Some(_) => {
                let size = self.scene.size;
                let gap = |t: f64| {
                    let p = o + d * t;
                    p.z - self.scene.floor.height_gradient(p.truncate(), size).0
                };
                let t_end = -o.z / d.z;
                let step = t_end / FLOOR_STEPS as f64;
                let (mut a, mut ga) = (0.0, gap(0.0));
                if ga <= 0.0 {
                    return (0.0, o);
                }
                for k in 1..=FLOOR_STEPS {
                    let b = step * k as f64;
                    let gb = gap(b);
                    if gb <= 0.0 {
                        // Within a step the gap is nearly linear: regula falsi, as for the water.
                        let tol = ROOT_TOLERANCE * step;
                        let t = crate::receivers::regula_falsi(gap, (a, ga), (b, gb), tol, 30);
                        return (t, o + d * t);
                    }
                    (a, ga) = (b, gb);
                }
                (t_end, o + d * t_end)
            }
        }
    }
}

pub(super) fn inside(p: DVec2, size: f64) -> bool {
    p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size
}

/// A ray's march through the water's slab (`first_crossing`).
#[derive(Clone, Copy, Debug)]
struct March {
    /// A bound on how fast the ray's height above the surface changes per unit distance.
    rate: f64,
    /// The shortest step.
    min_step: f64,
}

/// Most steps of `first_crossing`'s march: no step is shorter than 1/`MARCH_STEPS` of the slab's
/// interval.
pub const MARCH_STEPS: usize = 512;

/// No step of `first_crossing`'s march is longer than 1/`EVEN_STEPS` of the slab's interval (or
/// its shortest step), so that a slope bound estimated too low (waves two
/// lattice spacings long, seen only at their crests and troughs) cannot send it across the slab in
/// one step.
pub const EVEN_STEPS: usize = 24;

/// The first `t` in `[t0, t1]` where `f` (a ray's height above the water surface, positive on the
/// side it starts) reaches 0. Each step is the height over its bound rate of change,
/// `f / march.rate`, which cannot pass a crossing (sphere tracing a height field of bounded
/// slope): a grazing ray meets the first crest that rises into it, not one it would have passed
/// through between evenly spaced steps (24 even steps over a far ray's slab are a metre apart on
/// the shore, where the waves are a few decimetres long: they see the far water through its
/// nearer crests). Steps are at least `march.min_step` and 1/[`MARCH_STEPS`] of the interval, and
/// at most 1/[`EVEN_STEPS`] of it or `min_step`, whichever is longer (a slab thinner than a few
/// shortest steps, as flat water's, is crossed in one: steps of 1/24 of its micrometres would not
/// move an f32 distance of metres on the GPU); then regula falsi in its Illinois form on the step
/// that crossed, or on what is left of the interval when the march ends without a crossing (the
/// slab's far side lies beyond the surface: only rounding, or the steps spent, leave it
/// uncrossed), to [`ROOT_TOLERANCE`] of the shortest step. Both crossings,
/// from above and from below, use it; the GPU twin is `crossing_after` in final_image_march.wgsl.
fn first_crossing(f: impl Fn(f64) -> f64, t0: f64, t1: f64, march: March) -> f64 {
    let shortest = march.min_step.max((t1 - t0) / MARCH_STEPS as f64);
    let longest = ((t1 - t0) / EVEN_STEPS as f64).max(march.min_step);
    let mut a = t0;
    let mut gap = f(a);
    if gap <= 0.0 {
        return t0;
    }
    // The slab's far side lies beyond the surface, so a crossing lies in [a, t1] even when the
    // march ends without one (rounding at the far side, or the steps spent): search the rest.
    let mut hi = None;
    // Each step is at least 1/MARCH_STEPS of the interval; two more for rounding, as the GPU's.
    for _ in 0..MARCH_STEPS + 2 {
        if a >= t1 {
            break;
        }
        let b = (a + (gap / march.rate).max(shortest).min(longest)).min(t1);
        let next = f(b);
        if next <= 0.0 {
            hi = Some((b, next));
            break;
        }
        a = b;
        gap = next;
    }
    let hi = match hi {
        Some(hi) => hi,
        None => match f(t1) {
            g if g > 0.0 => return t1,
            g => (t1, g),
        },
    };
    // Within a step the gap is nearly linear: a few chords reach its zero.
    let tol = ROOT_TOLERANCE * march.min_step;
    crate::receivers::regula_falsi(&f, (a, gap), hi, tol, 30)
}

/// The surface's crossing is found to this fraction of the march's shortest step.
pub const ROOT_TOLERANCE: f64 = 1e-4;

/// Even steps of an underwater ray's search for the terrain, from the water to the plane z = 0; the
/// step that crosses it is then narrowed by regula falsi to [`ROOT_TOLERANCE`] of a step.
pub const FLOOR_STEPS: u32 = 64;

/// Distance along the ray to the wall of the pool square it leaves through.
pub(super) fn wall_distance(o: DVec3, d: DVec3, size: f64) -> f64 {
    let exit = Wall::exit(o.truncate(), d.truncate(), size);
    exit.map_or(f64::INFINITY, |(_, t)| t).max(0.0)
}

/// The wall of the pool square nearest to `p` (the one a view ray leaving the square met).
pub(super) fn wall_at(p: DVec3, size: f64) -> Wall {
    let d = [p.x, size - p.x, p.y, size - p.y];
    let k = (1..4).fold(0, |k, i| if d[i] < d[k] { i } else { k });
    Wall::ALL[k]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ray grazing the water (1 in 100) meets the first crest that rises into it: the march's
    /// steps, the ray's height over the surface's bound on its rate of change, cannot pass a
    /// crossing. The ray dips 5 mm into a 1 m sine wave's crest 5 m along (a 10 cm chord) after
    /// clearing the crest before it by 5 mm; with a shortest step of 0.1 mm, only the slope
    /// bound keeps the steps short near the crest, and the crossing found is the fine scan's
    /// first root. Evenly spaced steps over the slab (24 steps 1.3 m apart here) go through that
    /// crest and two more, to meet the water at x = 8.07 m (measured).
    #[test]
    fn a_grazing_ray_meets_the_first_crest_it_dips_into() {
        use crate::water::waves::{Wave, Waves};
        let size = 32.0;
        let surface = Waves::new(
            &[Wave {
                amplitude: 0.1,
                wavelength: 1.0,
                direction: [1.0, 0.0],
                phase: 0.3,
                period: None,
            }],
            size,
            0.0,
        );
        let slab = slab_bounds(&surface, size);
        // The crest nearest x = 5 and the ray that dips 5 mm under it, descending 1 in 100.
        let crest = (0..100_000)
            .map(|k| 4.5 + k as f64 * 1e-5)
            .max_by(|a, b| {
                let h = |x: f64| surface.height(DVec2::new(x, 3.0));
                h(*a).total_cmp(&h(*b))
            })
            .unwrap();
        let d = DVec3::new(1.0, 0.0, -0.01).normalize();
        let z_crest = surface.height(DVec2::new(crest, 3.0)) - 0.005;
        let o = DVec3::new(0.0, 3.0, z_crest + 0.01 * crest);
        let gap = |t: f64| {
            let p = o + d * t;
            p.z - surface.height(p.truncate())
        };
        let t0 = (slab.half_height - o.z) / d.z;
        let t1 = (-slab.half_height - o.z) / d.z;
        let march = March {
            rate: d.z.abs() + slab.slope * d.truncate().length(),
            // Short, so that the slope bound has to keep the steps from passing the crest.
            min_step: 1e-4,
        };
        let found = first_crossing(gap, t0.max(0.0), t1, march);
        let steps = 4_000_000;
        let scan = (0..=steps)
            .map(|k| t0.max(0.0) + (t1 - t0.max(0.0)) * k as f64 / steps as f64)
            .find(|&t| gap(t) <= 0.0)
            .expect("the scan's crossing");
        let x = (o + d * found).x;
        eprintln!(
            "crossing at x = {x:.6} (crest {crest:.6}), t {found:.9} against the scan's {scan:.9}"
        );
        assert!(
            (x - crest).abs() < 0.05,
            "met at x = {x}, not the crest at {crest}"
        );
        // The scan's spacing is 7.6e-6 along the ray: the two agree within it.
        assert!((found - scan).abs() < 1e-5, "{found} against {scan}");
    }

    /// The march's two ends: a slab as thin as flat water's (2 µm here, with a 4 mm shortest
    /// step) is crossed in one step, so the whole search is the start, that step and one chord,
    /// which lands on a plane (3 heights); and a march that ends without a crossing, as rounding
    /// can leave the far side, returns that far side instead of a miss.
    #[test]
    fn the_march_crosses_a_thin_slab_in_one_step_and_never_misses() {
        let march = March {
            rate: 1.0,
            min_step: 0.004,
        };
        let calls = std::cell::Cell::new(0);
        let flat = |t: f64| {
            calls.set(calls.get() + 1);
            5.000_001 - t
        };
        let t = first_crossing(flat, 5.0, 5.000_002, march);
        assert!((t - 5.000_001).abs() < 1e-12, "{t}");
        assert_eq!(calls.get(), 3, "heights read crossing a thin slab");
        let t = first_crossing(|_| 1e-9, 2.0, 3.0, march);
        assert!((t - 3.0).abs() < 1e-8, "an uncrossed march ends at {t}");
    }
}
