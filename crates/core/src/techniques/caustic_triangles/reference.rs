//! The ground truth for technique `caustic-triangles`: a photon tracer with exact geometry (the
//! analytic sphere, or the mesh's BVH), exact Snell refraction and exact Fresnel weights.
//!
//! # Method
//! Photons start on a jittered `N x N` grid over the generator's light-space rectangle (the same
//! rectangle the technique's photon image covers), one per cell at a random point of it, travelling
//! along the sun direction `L`. A cell of perpendicular area `a⊥` carries the flux the sun puts
//! through it, `a⊥ E⊥`; expressed relative to the unobstructed sun on the floor (`E⊥ |L_z|`) that is
//! `a⊥ / |L_z|` "floor-area units", so a photon landing in a texel of area `A` adds
//! `a⊥ / (|L_z| A)` times its weight to the relative irradiance there: 1 is the unobstructed sun.
//!
//! At each glass interface the photon splits into the refracted part (weight `T`, the exact Fresnel
//! transmittance for unpolarised light) and the reflected part (`1 − T`); under total internal
//! reflection all of it is reflected. With `reflections` both branches are followed (up to `depth`
//! interface events in all, reflected light that leaves the glass reaches the floor too); without,
//! only the refracted branch is (and total internal reflection, which has no other), and the dropped
//! reflected power is booked in [`PowerBudget`]. Light that leaves the glass travels to the floor
//! unless an occluder (wall) stops it.
//!
//! Only light that has entered the generator's rectangle and struck the generator is traced: the
//! map is the caustic (transmitted) light, not the direct sun around the shadow.
//!
//! # Convergence
//! The grid is stratified: each texel receives `(N a_texel / a_rect)` photons at roughly constant
//! spacing, so the error away from the caustic's singular curves falls faster than `1/√photons`.
//! The tests and `docs/caustic-triangles.md` state the photon count and the difference between
//! `N` and `2N` runs.

use crate::random::hash01;
use glam::{DVec2, DVec3};

use super::scene::{GlassScene, light_frame};
use crate::map::CausticsMap;
use crate::optics::{fresnel_transmittance, reflect, refract};
use crate::parallel::prelude::*;

/// How the reference photon tracer runs.
#[derive(Clone, Debug)]
pub struct ReferenceOptions {
    /// Photons per side of the light-space rectangle: `N²` photons.
    pub photons: u32,
    /// Most interface events (refractions and reflections) along one path.
    pub depth: u32,
    /// Follow the reflected branches as well as the refracted ones.
    pub reflections: bool,
    /// Seed of the photons' jitter within their grid cells: the same seed gives the same map.
    pub seed: u64,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            photons: 2048,
            depth: 8,
            reflections: true,
            seed: 1,
        }
    }
}

/// Where the power of the photons that struck the generator went, in floor-area units (relative
/// irradiance times area). `incident` equals the sum of all the others.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PowerBudget {
    /// Struck the generator above the floor with no occluder in the way.
    pub incident: f64,
    /// Reached the floor inside the map window.
    pub on_map: f64,
    /// Reached the floor outside the window.
    pub off_map: f64,
    /// Left going up (never reaches the floor).
    pub escaped: f64,
    /// Stopped by an occluder.
    pub occluded: f64,
    /// Reflected at the outer surface and not followed (without `reflections`).
    pub reflected_away: f64,
    /// Partially reflected inside and not followed (without `reflections`).
    pub internal_dropped: f64,
    /// Still inside (or still bouncing) after `depth` events.
    pub depth_cut: f64,
}

impl PowerBudget {
    fn add(&mut self, o: &PowerBudget) {
        self.incident += o.incident;
        self.on_map += o.on_map;
        self.off_map += o.off_map;
        self.escaped += o.escaped;
        self.occluded += o.occluded;
        self.reflected_away += o.reflected_away;
        self.internal_dropped += o.internal_dropped;
        self.depth_cut += o.depth_cut;
    }

    /// `incident` minus everything booked: zero up to rounding.
    pub fn unaccounted(&self) -> f64 {
        self.incident
            - (self.on_map
                + self.off_map
                + self.escaped
                + self.occluded
                + self.reflected_away
                + self.internal_dropped
                + self.depth_cut)
    }
}

/// What [`reference()`] gives.
pub struct ReferenceResult {
    /// Relative irradiance on the floor of the light that went through the generator (1: the
    /// unobstructed sun), the same in all three channels.
    pub map: CausticsMap,
    /// Where the power of the photons that struck the generator went.
    pub budget: PowerBudget,
    /// Photons on the grid, `N²`, those that missed the generator included.
    pub photons: u64,
}

struct Tracer<'a> {
    scene: &'a GlassScene,
    opts: &'a ReferenceOptions,
}

impl Tracer<'_> {
    /// Follow light of `weight` from `x` along `dir`, `inside` the glass or not, with `events`
    /// interface events used; deposit what reaches the floor.
    #[allow(clippy::too_many_arguments)]
    fn trace(
        &self,
        x: DVec3,
        dir: DVec3,
        inside: bool,
        weight: f64,
        events: u32,
        map: &mut [f64],
        b: &mut PowerBudget,
    ) {
        let s = self.scene;
        let t_floor = if dir.z < 0.0 {
            -x.z / dir.z
        } else {
            f64::INFINITY
        };
        let glass = s.generator.intersect(x, dir, t_floor);
        let t_glass = glass.map_or(f64::INFINITY, |g| g.0);
        let t_occ = if inside {
            None
        } else {
            s.occluder_hit(x, dir, t_glass.min(t_floor))
        };
        if t_occ.is_some() {
            b.occluded += weight;
            return;
        }
        match glass {
            None if inside => {
                // Numerically lost inside (a ray grazing a mesh seam): count it as cut.
                b.depth_cut += weight;
            }
            None => {
                if !t_floor.is_finite() {
                    b.escaped += weight;
                    return;
                }
                let p = x + dir * t_floor;
                let px = s.floor.to_pixel(p.truncate());
                let (j, i) = (px.x.floor(), px.y.floor());
                if j >= 0.0
                    && i >= 0.0
                    && (j as usize) < s.floor.width
                    && (i as usize) < s.floor.height
                {
                    map[i as usize * s.floor.width + j as usize] += weight;
                    b.on_map += weight;
                } else {
                    b.off_map += weight;
                }
            }
            Some((t, normal)) => {
                if events >= self.opts.depth {
                    b.depth_cut += weight;
                    return;
                }
                let p = x + dir * t;
                let (n, n1, n2) = if inside {
                    (-normal, s.ior, 1.0)
                } else {
                    (normal, 1.0, s.ior)
                };
                let cos_i = -dir.dot(n);
                match refract(dir, n, n1 / n2) {
                    Some(tdir) => {
                        let tr = fresnel_transmittance(cos_i, n1, n2);
                        self.trace(
                            p,
                            tdir.normalize(),
                            !inside,
                            weight * tr,
                            events + 1,
                            map,
                            b,
                        );
                        let r = weight * (1.0 - tr);
                        if self.opts.reflections {
                            self.trace(p, reflect(dir, n), inside, r, events + 1, map, b);
                        } else if inside {
                            b.internal_dropped += r;
                        } else {
                            b.reflected_away += r;
                        }
                    }
                    None => self.trace(p, reflect(dir, n), inside, weight, events + 1, map, b),
                }
            }
        }
    }
}

/// The reference floor map (relative irradiance of the light that went through the generator) and
/// where the power went.
pub fn reference(scene: &GlassScene, opts: &ReferenceOptions) -> ReferenceResult {
    let (u, v, w) = light_frame(scene.light);
    // A point light: a jittered grid over the tangent plane (at distance 1 along `w`) of the cone
    // of directions from the light to the generator's bounding sphere, a photon at q carrying
    // `I a / (1 + q²)^{3/2}` (the solid angle of its cell); directions outside a spot's cone
    // carry nothing.
    let (lo, hi) = scene.light_rect(u, v);
    let n = opts.photons.max(1) as usize;
    let cell = (hi - lo) / n as f64;
    // Start every photon outside everything: behind the farthest point of the scene along L.
    let (bmin, bmax) = scene.generator.bounds();
    let mut reach = bmin.length().max(bmax.length()) + (bmax - bmin).length();
    for o in &scene.occluders {
        let (a, c) = o.mesh.bounds();
        reach = reach.max(a.length()).max(c.length());
    }
    let start = -2.0 * reach;
    let flux = match scene.point {
        None => cell.x * cell.y / -scene.light.z,
        Some(pl) => pl.intensity() * cell.x * cell.y,
    } / scene.floor.texel_area();
    let texels = scene.floor.width * scene.floor.height;
    let tracer = Tracer { scene, opts };
    let (acc, budget) = (0..n)
        .into_par_iter()
        .fold(
            || (vec![0.0f64; texels], PowerBudget::default()),
            |(mut map, mut b), i| {
                for j in 0..n {
                    let k = (i * n + j) as u64 ^ opts.seed.wrapping_mul(0x2545_F491_4F6C_DD1D);
                    let q = lo
                        + cell * DVec2::new(j as f64 + hash01(2 * k), i as f64 + hash01(2 * k + 1));
                    let (origin, dir, power) = match scene.point {
                        None => (u * q.x + v * q.y + w * start, w, flux),
                        Some(pl) => {
                            let len2 = 1.0 + q.length_squared();
                            let d = (w + u * q.x + v * q.y) / len2.sqrt();
                            if !pl.lights(d) {
                                continue;
                            }
                            (pl.position, d, flux / (len2 * len2.sqrt()))
                        }
                    };
                    let first = scene.generator.intersect(origin, dir, f64::INFINITY);
                    let Some((t, _)) = first else { continue };
                    if scene.occluder_hit(origin, dir, t).is_some() {
                        continue;
                    }
                    if origin.z + dir.z * t < 0.0 {
                        continue; // the part of the generator under the floor
                    }
                    let mut pb = PowerBudget {
                        incident: power,
                        ..Default::default()
                    };
                    tracer.trace(origin, dir, false, power, 0, &mut map, &mut pb);
                    b.add(&pb);
                }
                (map, b)
            },
        )
        .reduce(
            || (vec![0.0f64; texels], PowerBudget::default()),
            |(mut a, mut ba), (c, bc)| {
                a.iter_mut().zip(&c).for_each(|(x, y)| *x += y);
                ba.add(&bc);
                (a, ba)
            },
        );
    let mut map = scene.floor.empty_map();
    for (t, e) in map.texels.iter_mut().zip(&acc) {
        *t = [*e as f32; 3];
    }
    // The budget in floor-area units (relative irradiance x area).
    let a = scene.floor.texel_area();
    let scale = |x: f64| x * a;
    let budget = PowerBudget {
        incident: scale(budget.incident),
        on_map: scale(budget.on_map),
        off_map: scale(budget.off_map),
        escaped: scale(budget.escaped),
        occluded: scale(budget.occluded),
        reflected_away: scale(budget.reflected_away),
        internal_dropped: scale(budget.internal_dropped),
        depth_cut: scale(budget.depth_cut),
    };
    ReferenceResult {
        map,
        budget,
        photons: (n * n) as u64,
    }
}

#[cfg(test)]
mod tests {
    use super::super::scene::{FloorWindow, Occluder, Shape};
    use super::*;

    /// Where a single ray leaves the generator along the refracted-only path (total internal
    /// reflection followed): the exit point and direction, or `None` if it misses or stays inside for
    /// `depth` events. Paraxial checks use it.
    fn exit_ray(
        scene: &GlassScene,
        origin: DVec3,
        dir: DVec3,
        depth: u32,
    ) -> Option<(DVec3, DVec3)> {
        let (mut x, mut d, mut inside) = (origin, dir.normalize(), false);
        for _ in 0..depth {
            let Some((t, normal)) = scene.generator.intersect(x, d, f64::INFINITY) else {
                return (!inside).then_some((x, d));
            };
            x += d * t;
            let (n, eta) = if inside {
                (-normal, scene.ior)
            } else {
                (normal, 1.0 / scene.ior)
            };
            match refract(d, n, eta) {
                Some(t) => {
                    d = t.normalize();
                    inside = !inside;
                    if !inside {
                        return Some((x, d));
                    }
                }
                None => d = reflect(d, n),
            }
        }
        None
    }

    fn ball(centre: DVec3, r: f64, n: f64, light: DVec3, window: f64, res: usize) -> GlassScene {
        GlassScene::new(
            Shape::Sphere { centre, radius: r },
            n,
            light,
            FloorWindow {
                origin: centre.truncate() - DVec2::splat(window / 2.0),
                size: window,
                width: res,
                height: res,
            },
            vec![],
        )
        .unwrap()
    }

    /// Paraxial ball lens: back focal distance `f = n r / (2 (n − 1))` from the centre.
    #[test]
    fn paraxial_focus_is_the_ball_lens_focus() {
        for (r, n) in [(0.1, 1.5), (0.25, 1.33), (1.0, 1.8)] {
            let c = DVec3::new(0.3, -0.2, 2.0);
            let s = ball(c, r, n, DVec3::NEG_Z, 1.0, 8);
            let rho = 1e-4 * r;
            let (p, d) = exit_ray(&s, c + DVec3::new(rho, 0.0, 10.0), DVec3::NEG_Z, 8).unwrap();
            // Where the exit ray crosses the axis x = c.x.
            let t = (c.x - p.x) / d.x;
            let focus = c.z - (p.z + t * d.z);
            let f = n * r / (2.0 * (n - 1.0));
            assert!((focus - f).abs() < 1e-6 * f, "r {r} n {n}: {focus} vs {f}");
        }
    }

    /// Energy: with refraction only, the floor receives `∫ T(θ)² dA` over the disc (the exit angle
    /// of a sphere equals the entry refraction angle, so both interfaces transmit `T(θ)`), and the
    /// outer surface reflects `∫ (1 − T) dA`.
    #[test]
    fn sphere_power_is_conserved() {
        let (r, n) = (0.2, 1.5);
        let c = DVec3::new(0.0, 0.0, 1.0);
        let s = ball(c, r, n, DVec3::NEG_Z, 4.0, 64);
        let res = reference(
            &s,
            &ReferenceOptions {
                photons: 1024,
                reflections: false,
                depth: 8,
                seed: 3,
            },
        );
        let b = res.budget;
        // Quadrature over ρ ∈ [0, r] (midpoint, fine).
        let (mut floor, mut refl, m) = (0.0, 0.0, 200_000);
        for k in 0..m {
            let rho = (k as f64 + 0.5) / m as f64 * r;
            let cos = (1.0 - (rho / r).powi(2)).sqrt();
            let t = fresnel_transmittance(cos, 1.0, n);
            let da = std::f64::consts::TAU * rho * r / m as f64;
            floor += t * t * da;
            refl += (1.0 - t) * da;
        }
        let disc = std::f64::consts::PI * r * r;
        assert!((b.incident - disc).abs() < 2e-3 * disc, "{b:?} vs {disc}");
        assert!(b.unaccounted().abs() < 1e-9 * disc, "{b:?}");
        let got = b.on_map + b.off_map;
        assert!((got - floor).abs() < 2e-3 * disc, "floor {got} vs {floor}");
        assert!(
            (b.reflected_away - refl).abs() < 2e-3 * disc,
            "{} vs {refl}",
            b.reflected_away
        );
        assert!(b.internal_dropped > 0.0 && b.depth_cut == 0.0, "{b:?}");
    }

    #[test]
    fn following_reflections_accounts_for_everything() {
        let s = ball(
            DVec3::new(0.0, 0.0, 0.3),
            0.2,
            1.5,
            DVec3::new(0.4, 0.1, -1.0),
            2.0,
            32,
        );
        let res = reference(
            &s,
            &ReferenceOptions {
                photons: 256,
                ..Default::default()
            },
        );
        let b = res.budget;
        assert!(b.unaccounted().abs() < 1e-9, "{b:?}");
        assert_eq!(b.reflected_away + b.internal_dropped, 0.0);
        assert!(b.escaped > 0.0 && b.on_map > 0.8 * b.incident, "{b:?}");
    }

    #[test]
    fn a_wall_leaves_the_floor_behind_it_dark() {
        let c = DVec3::new(0.0, 0.0, 0.5);
        let mut s = ball(c, 0.2, 1.5, DVec3::NEG_Z, 1.0, 64);
        // A wall under the sphere's +x half, between it and the floor.
        s.occluders.push(Occluder::wall(
            DVec3::new(0.0, -1.0, 0.05),
            DVec3::new(1.0, 1.0, 0.1),
        ));
        let res = reference(
            &s,
            &ReferenceOptions {
                photons: 256,
                ..Default::default()
            },
        );
        let m = &res.map;
        for i in 0..64 {
            for j in 40..64 {
                assert_eq!(m.texels[i * 64 + j][0], 0.0, "({i}, {j})");
            }
        }
        assert!(res.budget.occluded > 0.3 * res.budget.incident);
    }
}
