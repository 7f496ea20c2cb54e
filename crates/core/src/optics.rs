//! Geometric optics shared by the reference and every CPU technique: Snell refraction and the Fresnel
//! transmittance of unpolarised light. The WGSL twin is `crates/gpu/src/shaders/optics.wgsl`; the two
//! are tested against each other.

use glam::DVec3;

/// Refract the unit direction `incident` at a surface with unit normal `normal` (pointing against
/// `incident`, i.e. `incident · normal < 0`), going from index `n1` into index `n2`.
///
/// Snell's law in vector form, `t = η i + (η cos θi − cos θt) n` with `η = n1 / n2`,
/// `cos θi = −i·n`, `cos θt = sqrt(1 − η² (1 − cos² θi))`. Returns `None` on total internal reflection.
pub fn refract(incident: DVec3, normal: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -incident.dot(normal);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(eta * incident + (eta * cos_i - cos_t) * normal)
}

/// Fresnel transmittance of unpolarised light crossing an interface from `n1` to `n2` at incidence
/// cosine `cos_i`: `T = 1 − (Rs + Rp) / 2` with the exact Fresnel amplitudes
/// `rs = (n1 cos θi − n2 cos θt) / (n1 cos θi + n2 cos θt)`, `rp = (n2 cos θi − n1 cos θt) / (n2 cos θi + n1 cos θt)`.
/// Energy, not radiance: the transmitted flux fraction. Zero under total internal reflection.
pub fn fresnel_transmittance(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let cos_i = cos_i.abs().min(1.0);
    let sin_t = n1 / n2 * (1.0 - cos_i * cos_i).max(0.0).sqrt();
    if sin_t >= 1.0 {
        return 0.0;
    }
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    1.0 - 0.5 * (rs * rs + rp * rp)
}

/// The Fresnel transmittance from air into a medium of index `ior`, or 1 where a technique leaves
/// Fresnel out (`on` false): the weight of a sample's light.
pub fn air_transmittance(on: bool, cos_i: f64, ior: f64) -> f64 {
    if on {
        fresnel_transmittance(cos_i, 1.0, ior)
    } else {
        1.0
    }
}

/// Reflect `incident` about `normal`.
pub fn reflect(incident: DVec3, normal: DVec3) -> DVec3 {
    incident - 2.0 * incident.dot(normal) * normal
}

/// Upward unit normal of the height field `z = h(x, y)` with gradient `(∂h/∂x, ∂h/∂y)`.
pub fn height_field_normal(gradient: glam::DVec2) -> DVec3 {
    DVec3::new(-gradient.x, -gradient.y, 1.0).normalize()
}

/// Unit direction towards the sun under flat water, from `to_sun` (unit, towards the sun in air,
/// z > 0) and the water's index of refraction: Snell's law at a horizontal surface, the air's
/// horizontal part over `ior` and z = cos θt. The twin of `sun_under_water` in the shading rule's
/// WGSL module (`crates/gpu/src/shaders/caustics_light.wgsl`).
pub fn sun_under_water(to_sun: DVec3, ior: f64) -> DVec3 {
    let cos_i = to_sun.z.max(0.0);
    let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (ior * ior)).max(0.0).sqrt();
    DVec3::new(to_sun.x / ior, to_sun.y / ior, cos_t)
}

/// Flat water's light on a surface of unit normal `n` at `depth` below the surface, relative to a
/// horizontal surface just under clear water: Beer-Lambert extinction `absorption` (per metre)
/// along the refracted path `depth / cos θt`, times the beam's cosine on the surface over its
/// cosine on the horizontal (across itself the refracted beam is `1 / cos θt` times denser than
/// over the horizontal). `toward_sun` is [`sun_under_water`]'s direction. What a technique's map
/// reads where the water is flat, and what a surface no map holds receives; the twin of
/// `flat_water_light` in `crates/gpu/src/shaders/caustics_light.wgsl`.
pub fn flat_water_light(absorption: DVec3, depth: f64, toward_sun: DVec3, n: DVec3) -> DVec3 {
    let cos_t = toward_sun.z.max(1e-3);
    (-absorption * (depth / cos_t)).exp() * (n.dot(toward_sun).max(0.0) / cos_t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sun_under_water_is_the_refracted_beam_and_flat_water_conserves_its_flux() {
        for deg in [0.0f64, 20.0, 45.0, 70.0, 85.0] {
            let th = deg.to_radians();
            let to_sun = DVec3::new(th.sin() * 0.6, th.sin() * 0.8, th.cos());
            let under = sun_under_water(to_sun, 1.333);
            let refracted = refract(-to_sun, DVec3::Z, 1.0 / 1.333).unwrap();
            assert!(
                (under + refracted).length() < 1e-12,
                "{deg}°: {under} vs {refracted}"
            );
            // Clear water: a horizontal receiver gets exactly flat water's light, and a surface
            // facing the beam gets 1 / cos θt of it (the same flux over a narrower section).
            let clear = DVec3::ZERO;
            assert!((flat_water_light(clear, 2.0, under, DVec3::Z) - DVec3::ONE).length() < 1e-12);
            let facing = flat_water_light(clear, 2.0, under, under);
            assert!((facing.x * under.z - 1.0).abs() < 1e-12, "{deg}°: {facing}");
            // Turned away from the sun: none; absorption along depth / cos θt.
            assert_eq!(flat_water_light(clear, 1.0, under, -under), DVec3::ZERO);
            let k = DVec3::new(0.45, 0.09, 0.05);
            let absorbed = flat_water_light(k, 1.5, under, DVec3::Z);
            assert!((absorbed - (-k * 1.5 / under.z).exp()).length() < 1e-12);
        }
    }

    #[test]
    fn snell_law_holds() {
        let n = DVec3::Z;
        for deg in [0.0f64, 10.0, 30.0, 60.0, 85.0] {
            let th = deg.to_radians();
            let i = DVec3::new(th.sin(), 0.0, -th.cos());
            let t = refract(i, n, 1.0 / 1.333).unwrap();
            assert!((t.length() - 1.0).abs() < 1e-12);
            let sin_t = (t.x * t.x + t.y * t.y).sqrt();
            assert!((th.sin() - 1.333 * sin_t).abs() < 1e-12, "{deg}");
            assert!(t.z < 0.0);
        }
    }

    #[test]
    fn total_internal_reflection_from_below() {
        let th = 60f64.to_radians(); // beyond the critical angle asin(1/1.333) = 48.6°
        let i = DVec3::new(th.sin(), 0.0, th.cos());
        assert!(refract(i, -DVec3::Z, 1.333).is_none());
        assert_eq!(fresnel_transmittance(th.cos(), 1.333, 1.0), 0.0);
    }

    #[test]
    fn fresnel_normal_incidence_and_reciprocity() {
        let r0 = ((1.333f64 - 1.0) / (1.333 + 1.0)).powi(2);
        assert!((fresnel_transmittance(1.0, 1.0, 1.333) - (1.0 - r0)).abs() < 1e-12);
        // Stokes reciprocity: T(air → water at θi) = T(water → air at θt).
        let th = 50f64.to_radians();
        let sin_t = th.sin() / 1.333;
        let cos_t = (1.0 - sin_t * sin_t).sqrt();
        let a = fresnel_transmittance(th.cos(), 1.0, 1.333);
        let b = fresnel_transmittance(cos_t, 1.333, 1.0);
        assert!((a - b).abs() < 1e-12);
        assert!(fresnel_transmittance(1e-9, 1.0, 1.333) < 1e-6);
    }
}
