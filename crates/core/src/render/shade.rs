//! Shading where a view ray ends: the floor and its caustics, the pool's walls, the objects, and
//! the deck above the water.

use glam::{DVec2, DVec3};

use super::Tracer;
use super::march::wall_at;
use super::spread::Spread;
use crate::optics::{flat_water_light, fresnel_transmittance, reflect, refract};
use crate::scene::Material;

impl Tracer<'_> {
    pub(super) fn nearest_object(
        &self,
        o: DVec3,
        d: DVec3,
        t_max: f64,
    ) -> Option<(f64, DVec3, usize)> {
        let meshes = self.scene.objects.iter().map(|o| &o.mesh).zip(&self.bvhs);
        crate::mesh::nearest(meshes, o, d, t_max).map(|(k, t, n)| (t, n, k))
    }

    /// Whether an object lies between `o` and `o + t_max d`: a diffuse one, or any (glass included)
    /// `with_glass`.
    pub(super) fn occluded(&self, o: DVec3, d: DVec3, t_max: f64, with_glass: bool) -> bool {
        self.scene.objects.iter().zip(&self.bvhs).any(|(obj, bvh)| {
            (with_glass || matches!(obj.material, Material::Diffuse { .. }))
                && bvh.intersect(&obj.mesh, o, d, t_max).is_some()
        })
    }

    /// The floor at `p`, its caustics and albedo filtered over the sample's `footprint` there.
    pub(super) fn shade_floor(&self, p: DVec3, footprint: [DVec2; 2]) -> DVec3 {
        let scene = self.scene;
        let water = scene.water.as_ref().expect("under water");
        let size = water.size;
        let albedo = scene
            .floor
            .albedo
            .filtered(p.truncate(), size, extent(footprint));
        let e_h = scene.light.intensity * -self.sun.z;
        let flat = || {
            flat_water_light(
                water.absorption,
                water.depth - p.z,
                -self.sun_water,
                DVec3::Z,
            )
        };
        let wrap = water.wrap && scene.floor.terrain.is_none();
        let relative = match (&self.caustics, &self.eye_space) {
            // Beyond a map that does not tile (a terrain's, clamped at its edges) nothing says
            // where the light focuses: the floor there gets the flat water's light, the mean of
            // any pattern (stretching the map's edge texels to the horizon drew streaks); a
            // footprint across the map's edge reads the flat light for its taps beyond it.
            (Some((_, pyramid)), _) => {
                let f = flat().as_vec3().to_array();
                let c = pyramid.filtered(p.truncate(), footprint, wrap, Some(f));
                DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)
            }
            (None, Some((image, eye))) => image.sample(eye, p).unwrap_or_else(flat),
            (None, None) => flat(),
        };
        let shadow = if self.occluded(p + DVec3::Z * 1e-4, -self.sun_water, f64::INFINITY, false) {
            0.0
        } else {
            1.0
        };
        let direct = relative * (e_h * self.t_flat * shadow);
        let ambient = self.ambient * (-water.absorption * water.depth).exp();
        albedo * (direct + ambient) * scene.light.color
    }

    /// The sun's light on wall point `p` through its wall's map, or an eye-space technique's
    /// image where the wall point projects (cascaded lights the walls it sees); none without
    /// either; shadowed by the objects as the floor is.
    pub(super) fn wall_light(&self, p: DVec3, size: f64) -> DVec3 {
        let wall = wall_at(p, size);
        let c = match (self.walls, &self.eye_space) {
            (Some(maps), _) => maps.get(wall).sample(wall.along(p), p.z),
            (None, Some((image, eye))) => match image.sample(eye, p) {
                Some(v) => [v.x as f32, v.y as f32, v.z as f32],
                None => return DVec3::ZERO,
            },
            (None, None) => return DVec3::ZERO,
        };
        if self.occluded(
            p + wall.normal() * 1e-4,
            -self.sun_water,
            f64::INFINITY,
            false,
        ) {
            return DVec3::ZERO;
        }
        let e_h = self.scene.light.intensity * -self.sun.z;
        DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)
            * (e_h * self.t_flat)
            * self.scene.light.color
    }

    pub(super) fn shade_object(
        &self,
        p: DVec3,
        n: DVec3,
        d: DVec3,
        k: usize,
        depth: u32,
        under: bool,
    ) -> DVec3 {
        let obj = &self.scene.objects[k];
        // Closed meshes with outward normals: the ray enters where it meets the outside.
        let entering = n.dot(d) < 0.0;
        let n = if entering { n } else { -n };
        match &obj.material {
            Material::Diffuse { color } => {
                let sun_dir = if under { self.sun_water } else { self.sun };
                let lambert = n.dot(-sun_dir).max(0.0);
                let lit = || {
                    if lambert > 0.0 && !self.occluded(p + n * 1e-4, -sun_dir, f64::INFINITY, false)
                    {
                        1.0
                    } else {
                        0.0
                    }
                };
                // Under the water, the shading rule's light relative to flat, clear water, times
                // what flat water passes onto the horizontal (E cos θi T): the technique's
                // light-space deposit where the object is among its receivers (shaded by them,
                // as a shadow map shades), else flat water's refracted beam, absorbed along its
                // path, on the surface's cosine over the horizontal's.
                let e_h = self.scene.light.intensity * -self.sun.z * self.t_flat;
                let direct = match (&self.scene.water, under, self.light) {
                    (Some(_), true, Some(light)) => {
                        let [r, g, b] = light.light_at(p, n);
                        DVec3::new(r as f64, g as f64, b as f64) * e_h
                    }
                    (Some(w), true, None) => {
                        let depth = (w.depth - p.z).max(0.0);
                        flat_water_light(w.absorption, depth, -self.sun_water, n) * (e_h * lit())
                    }
                    _ => DVec3::splat(self.scene.light.intensity * lambert * lit()),
                };
                *color * (direct + self.ambient) * self.scene.light.color
            }
            Material::Glass { ior, tint } => {
                let outside_ior = if under {
                    self.scene.water.as_ref().map_or(1.0, |w| w.ior)
                } else {
                    1.0
                };
                let (n1, n2) = if entering {
                    (outside_ior, *ior)
                } else {
                    (*ior, outside_ior)
                };
                let cos_i = -d.dot(n);
                let t = fresnel_transmittance(cos_i, n1, n2);
                let none = Spread::default();
                let refl = self.trace_from(p + n * 1e-5, reflect(d, n), depth + 1, under, none);
                let refr = match refract(d, n, n1 / n2) {
                    Some(r) => self.trace_from(p - n * 1e-5, r, depth + 1, under, none) * *tint,
                    None => DVec3::ZERO,
                };
                refl * (1.0 - t) + refr * t
            }
        }
    }

    /// Above the water, outside the pool: the deck, or the sky.
    pub(super) fn shade_above(&self, o: DVec3, d: DVec3) -> DVec3 {
        let water = self.scene.water.as_ref().expect("water");
        if self.pool && d.z < 0.0 {
            let deck = water.depth + 0.1 * water.size.min(1.0) + self.h_max;
            let t = (deck - o.z) / d.z;
            if t > 0.0 {
                let p = o + d * t;
                // A sample's footprint on the deck, stretched by the grazing angle.
                let footprint = (p - o).length() * self.spread / d.z.abs().max(0.05);
                let albedo = self
                    .scene
                    .floor
                    .deck
                    .albedo(p.truncate(), water.size, footprint);
                return albedo
                    * (DVec3::splat(self.scene.light.intensity * -self.sun.z) + self.ambient)
                    * self.scene.light.color;
            }
        }
        if !self.pool && d.z < 0.0 {
            // Beyond the surface's slab the open sea: the flat-water Fresnel reflection of the sky.
            let r = fresnel_transmittance(-d.z, 1.0, water.ior);
            return self.sky(reflect(d, DVec3::Z)) * (1.0 - r);
        }
        self.sky(d)
    }
}

/// The widths along x and y of the box around a footprint spanned by `axes`.
pub(super) fn extent(axes: [DVec2; 2]) -> DVec2 {
    axes[0].abs() + axes[1].abs()
}
