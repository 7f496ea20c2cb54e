//! The sky and the sun: their radiance, the ambient light, and their reflection in the water
//! (the footprint-filtered rough water and the sun's glint).

use glam::DVec3;

use super::Tracer;
use crate::optics::{fresnel_transmittance, reflect};
use crate::sky::{Sky, TURBIDITY};
use crate::water::Surface;
use crate::water::slopes::{Footprint, SlopeMoments, SlopePyramid, glint, visible_facets};

/// The ambient light of the final image for sunlight travelling along `sun`: the daylight sky's
/// irradiance on a horizontal surface, per unit of the sun's ([`Sky::horizontal_irradiance`]).
/// Both twins take it from here (the GPU's as a uniform).
pub fn sky_ambient(sun: DVec3) -> DVec3 {
    Sky::new(sun, TURBIDITY).horizontal_irradiance()
}

impl Tracer<'_> {
    pub(super) fn sun_radiance(&self) -> DVec3 {
        self.scene.light.color * self.scene.light.intensity
    }

    /// The sky's radiance along `d` with the sun's disk, in the image's unit: a surface of albedo
    /// `ρ` under irradiance `E` shows `ρ E` (the `1 / π` of a Lambertian reflector is left to the
    /// exposure), so a radiance `L` shows as `π L`.
    pub(super) fn sky(&self, d: DVec3) -> DVec3 {
        (self.sky.radiance(d) + DVec3::splat(self.sky.sun_disk(d)))
            * (std::f64::consts::PI * self.sun_radiance())
    }

    /// The sky alone, without the sun's disk: what rough water reflects besides the sun's glint.
    pub(super) fn sky_without_sun(&self, d: DVec3) -> DVec3 {
        self.sky.radiance(d) * (std::f64::consts::PI * self.sun_radiance())
    }

    /// The water's slope moments over the footprint of the ray along `d` meeting it at `p`: the
    /// cone of one sample from the eye, as wide as the distance from the camera (a bent path's
    /// own length would be a little longer) times the sample's angle.
    pub(super) fn water_slopes(
        &self,
        pyramid: &SlopePyramid,
        s: &dyn Surface,
        p: DVec3,
        d: DVec3,
    ) -> SlopeMoments {
        let distance = (p - self.scene.camera.position).length();
        let footprint = Footprint::of_ray(d, distance, self.spread);
        pyramid.filtered(s, p.truncate(), &footprint)
    }

    /// Water met at `p` along `d` shaded with the normals filtered by the sample's footprint
    /// ([`crate::water::slopes`]): the facets of the footprint the eye sees each reflect the sky
    /// by their Fresnel reflectance, the sun's reflection is the glint lobe of their roughness,
    /// and the rest of the light refracts along their mean normal by their mean transmittance
    /// ([`visible_facets`]). Returns the reflected light, the transmittance and the normal to
    /// refract at.
    pub(super) fn rough_water(
        &self,
        pyramid: &SlopePyramid,
        s: &dyn Surface,
        p: DVec3,
        d: DVec3,
        ior: f64,
    ) -> (DVec3, f64, DVec3) {
        let m = self.water_slopes(pyramid, s, p, d);
        let (facets, count) = visible_facets(d, &m);
        let mut reflected = self.glint(d, &m, ior);
        let (mut t_view, mut n) = (0.0, DVec3::ZERO);
        for &(facet, w) in &facets[..count] {
            let t = fresnel_transmittance(-d.dot(facet), 1.0, ior);
            reflected += self.sky_without_sun(reflect(d, facet)) * ((1.0 - t) * w);
            t_view += t * w;
            n += facet * w;
        }
        (reflected, t_view, n.normalize())
    }

    /// The sun's reflection off water of slope moments `m` toward the eye looking along `d`: the
    /// glint lobe of [`glint`] with the Fresnel reflectance of its mirroring facet, in the image's
    /// unit (`π L`, as [`sky`](Self::sky)).
    pub(super) fn glint(&self, d: DVec3, m: &SlopeMoments, ior: f64) -> DVec3 {
        let (g, h) = glint(-d, -self.sun, m, self.sun_variance);
        if g <= 0.0 {
            return DVec3::ZERO;
        }
        let f = 1.0 - fresnel_transmittance(-d.dot(h), 1.0, ior);
        self.sun_radiance() * (std::f64::consts::PI * f * g)
    }
}
