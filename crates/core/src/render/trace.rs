//! A view ray's path: through the air, refracted into the water, under it, and out through the
//! surface seen from below.

use glam::{DVec2, DVec3};

use super::Tracer;
use super::march::{inside, wall_at, wall_distance};
use super::shade::extent;
use super::spread::Spread;
use crate::optics::{fresnel_transmittance, height_field_normal, reflect, refract};
use crate::scene::Scene;
use crate::water::Surface;

/// Whether the scene's camera is under the water: inside the water's square and below the surface's
/// height there (the rest level without a surface). Its primary rays then start in the water.
pub fn camera_under_water(scene: &Scene, surface: Option<&dyn Surface>) -> bool {
    let Some(water) = &scene.water else {
        return false;
    };
    let p = scene.camera.position;
    let h = surface.map_or(0.0, |s| s.height(p.truncate()));
    inside(p.truncate(), water.size) && p.z < water.depth + h
}

/// A ray meeting the water surface from below, split by the Fresnel equations from the dense side.
#[derive(Clone, Copy, Debug)]
pub struct FromBelow {
    /// The mirrored ray, back into the water.
    pub reflected: DVec3,
    /// The ray refracted out into the air; `None` beyond Snell's window (total internal reflection).
    pub refracted: Option<DVec3>,
    /// The fraction of the flux that leaves the water (0 beyond the window); the reflected ray
    /// carries the rest, `1 - transmittance`.
    pub transmittance: f64,
}

/// Split the unit ray `d` meeting the surface of unit upward normal `n` from the water's side
/// (`d · n > 0`), the water of index `ior` under air. Snell's window is where `sin θ < 1 / ior`.
pub fn from_below(d: DVec3, n: DVec3, ior: f64) -> FromBelow {
    let refracted = refract(d, -n, ior);
    FromBelow {
        reflected: reflect(d, n),
        refracted,
        transmittance: if refracted.is_some() {
            fresnel_transmittance(d.dot(n), ior, 1.0)
        } else {
            0.0
        },
    }
}

impl Tracer<'_> {
    pub(super) fn trace(&self, o: DVec3, d: DVec3, depth: u32, spread: Spread) -> DVec3 {
        if depth > 6 {
            return DVec3::ZERO;
        }
        let scene = self.scene;
        let Some(water) = &scene.water else {
            return self.trace_air(o, d, depth, spread);
        };
        let size = water.size;
        let level = water.depth;
        // Water surface hit, searched in the slab |z - level| <= h_max.
        let water_hit = self.surface.and_then(|s| self.hit_water(s, o, d, level));
        let obj = self.nearest_object(o, d, water_hit.map_or(f64::INFINITY, |w| w.0));
        if let Some((t, n, k)) = obj {
            return self.shade_object(o + d * t, n, d, k, depth, false);
        }
        let Some((t, p)) = water_hit else {
            // A pool is sunk into a deck around it; beyond the terrain's square the world goes on.
            return self.shade_above(o, d);
        };
        if self.pool && !inside(p.truncate(), size) {
            return self.shade_above(o, d);
        }
        let s = self.surface.expect("a water hit implies a surface");
        let (reflected, t_view, n) = match &self.slopes {
            Some(pyramid) => self.rough_water(pyramid, s, p, d, water.ior),
            None => {
                let n = height_field_normal(s.gradient(p.truncate()));
                let t_view = fresnel_transmittance(-d.dot(n), 1.0, water.ior);
                (self.sky(reflect(d, n)) * (1.0 - t_view), t_view, n)
            }
        };
        let Some(r) = refract(d, n, 1.0 / water.ior) else {
            return reflected;
        };
        debug_assert!(t >= 0.0);
        let spread = spread.bent(
            |q| height_field_normal(s.gradient(q)),
            (p, d, t, n),
            |d, m| refract(d, m, 1.0 / water.ior),
        );
        reflected + self.trace_under(p, r, depth, spread) * t_view
    }

    /// Radiance arriving along `d` at point `o` under the water.
    pub(super) fn trace_under(&self, o: DVec3, d: DVec3, depth: u32, spread: Spread) -> DVec3 {
        // The same bound as `trace`: a ray reflected inside a glass object under water would
        // otherwise recurse until the stack overflows.
        if depth > 6 {
            return DVec3::ZERO;
        }
        let scene = self.scene;
        let water = scene.water.as_ref().expect("under water");
        let size = water.size;
        let (t_floor, floor_p) = self.hit_floor(o, d);
        // A ray going up ends at the surface seen from below instead; the branches below read
        // `t_floor` and `floor_p` as the ray's end, wherever it is.
        let ceiling = self.hit_water_from_below(o, d, water.depth);
        let (t_floor, floor_p) = ceiling.unwrap_or((t_floor, floor_p));
        let obj = self.nearest_object(o, d, t_floor);
        let (dist, colour) = if let Some((t, n, k)) = obj {
            (t, self.shade_object(o + d * t, n, d, k, depth, true))
        } else if self.pool && !inside(floor_p.truncate(), size) {
            // The ray meets a pool wall first: tiles lit by the ambient light, and by the sun
            // through the wall's map where the technique lit the walls.
            let t = wall_distance(o, d, size);
            let p = o + d * t;
            // The wall's tiles as the floor's, along the wall and up it, filtered over the
            // sample's footprint on the wall's plane.
            let [fa, fb] = spread.on_plane3(d, t, wall_at(p, size).normal());
            let extent = DVec2::new(
                (fa.x + fa.y).abs() + (fb.x + fb.y).abs(),
                fa.z.abs() + fb.z.abs(),
            );
            let a = scene
                .floor
                .albedo
                .filtered(DVec2::new(p.x + p.y, p.z), size, extent);
            (
                t,
                a * (self.ambient * self.scene.light.color + self.wall_light(p, size)),
            )
        } else if ceiling.is_some() {
            (
                t_floor,
                self.leave_water(floor_p, d, depth, t_floor, spread),
            )
        } else {
            let (_, g) = scene.floor.height_gradient(floor_p.truncate(), scene.size);
            let footprint = spread.on_plane(d, t_floor, height_field_normal(g));
            (t_floor, self.shade_floor(floor_p, footprint))
        };
        colour * (-water.absorption * dist).exp()
    }

    pub(super) fn trace_from(
        &self,
        o: DVec3,
        d: DVec3,
        depth: u32,
        under: bool,
        spread: Spread,
    ) -> DVec3 {
        if under {
            self.trace_under(o, d, depth, spread)
        } else {
            self.trace(o, d, depth, spread)
        }
    }

    /// No water in the scene: objects over the floor plane in open air.
    pub(super) fn trace_air(&self, o: DVec3, d: DVec3, depth: u32, spread: Spread) -> DVec3 {
        let t_floor = if d.z < 0.0 { -o.z / d.z } else { f64::INFINITY };
        if let Some((t, n, k)) = self.nearest_object(o, d, t_floor) {
            return self.shade_object(o + d * t, n, d, k, depth, false);
        }
        if t_floor.is_finite() {
            let p = o + d * t_floor;
            let footprint = spread.on_plane(d, t_floor, DVec3::Z);
            let albedo =
                self.scene
                    .floor
                    .albedo
                    .filtered(p.truncate(), self.scene.size, extent(footprint));
            let from = p + DVec3::Z * 1e-5;
            // With a caustics map of the light through the glass (relative to the unobstructed
            // sun), every object shadows the direct sun and the map brings back what the glass
            // transmitted; without one, glass lets the sun through unchanged.
            let (lit, caustic) = match &self.caustics {
                Some((_, pyramid)) => {
                    let c = pyramid.filtered(p.truncate(), footprint, false, None);
                    let blocked = self.occluded(from, -self.sun, f64::INFINITY, true);
                    (
                        if blocked { 0.0 } else { 1.0 },
                        DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64),
                    )
                }
                None => {
                    let blocked = self.occluded(from, -self.sun, f64::INFINITY, false);
                    (if blocked { 0.0 } else { 1.0 }, DVec3::ZERO)
                }
            };
            let e = (DVec3::splat(lit) + caustic) * (self.scene.light.intensity * -self.sun.z)
                + self.ambient;
            return albedo * e * self.scene.light.color;
        }
        self.sky(d)
    }

    /// Radiance arriving along `d` at point `p` of the surface, seen from below: the air's through
    /// Snell's window, weighted by the Fresnel transmittance from the dense side, plus the water's
    /// mirrored in the surface (all of it beyond the window).
    /// The ray met the surface at `p` after `t` along `d`; `spread` is its own, which the reflected
    /// ray carries on (the mirror image beyond Snell's window is filtered as a direct view is).
    pub(super) fn leave_water(
        &self,
        p: DVec3,
        d: DVec3,
        depth: u32,
        t: f64,
        spread: Spread,
    ) -> DVec3 {
        let water = self.scene.water.as_ref().expect("under water");
        let n = match self.surface {
            Some(s) => match &self.slopes {
                Some(pyramid) => height_field_normal(self.water_slopes(pyramid, s, p, d).mean),
                None => height_field_normal(s.gradient(p.truncate())),
            },
            None => DVec3::Z,
        };
        let split = from_below(d, n, water.ior);
        let mirrored = spread.bent(
            |q| {
                self.surface
                    .map_or(DVec3::Z, |s| height_field_normal(s.gradient(q)))
            },
            (p, d, t, n),
            |d, m| Some(reflect(d, m)),
        );
        let mut c = self.trace_under(p - n * 1e-5, split.reflected, depth + 1, mirrored)
            * (1.0 - split.transmittance);
        if let Some(r) = split.refracted {
            let none = Spread::default();
            c += self.trace(p + n * 1e-5, r, depth + 1, none) * split.transmittance;
        }
        c
    }
}
