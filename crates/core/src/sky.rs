//! The daylight sky of the final image: Preetham, Shirley and Smits 1999, "A Practical Analytic
//! Model for Daylight" (SIGGRAPH 99), the clear sky's luminance and chromaticity from the sun's
//! height and the air's turbidity, with the sun's disk at its true size. Its GPU twin is `perez_sky`
//! and `xyy_to_rgb` in caustics-gpu's `shaders/shading.wgsl`, called by `sky_radiance` in
//! `final_image/final_image_inputs.wgsl`, which evaluate the same Perez functions from the coefficients
//! [`Sky::coefficients`] hands them.
//!
//! The model (§ 3 and appendix A.2 of the paper): each of the luminance `Y` and the chromaticities
//! `x`, `y` follows Perez et al.'s all-weather function of the view's zenith angle `θ` and its angle
//! to the sun `γ`,
//!
//! `F(θ, γ) = (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ)`,
//!
//! scaled to the zenith's value: `Y(θ, γ) = Y_z F(θ, γ) / F(0, θ_s)`. The coefficients `A..E` are
//! linear in the turbidity `T`, the zenith's luminance and chromaticities polynomials in `T` and the
//! sun's zenith angle `θ_s` (the paper's appendix, reproduced below). `Yxy` becomes CIE XYZ and then
//! linear sRGB (Rec. 709 primaries, D65).
//!
//! Units: the model's `Y_z` is in kcd/m². The scene's sun is an irradiance (`light.intensity` times
//! `light.color` on a surface facing it), so the sky's radiance is given per unit of it: divided by
//! [`SUN_ILLUMINANCE`], a clear day's direct normal illuminance, 100 klx. A horizontal floor under
//! the sun at 45° then gets 0.26 of the sun's normal irradiance from the sky
//! ([`Sky::horizontal_irradiance`]; 26 klx against the sun's 71 klx on it; Preetham's model is
//! known to run bright towards the horizon, measured clear days give 10-20 klx).

use std::f64::consts::{FRAC_PI_2, PI};

use glam::DVec3;

/// The air's turbidity of the sky: 2 is very clear, 3 a clear summer day, 6 hazy (Preetham's
/// Figure 4). A clear day, which is when water shows caustics.
pub const TURBIDITY: f64 = 2.5;

/// The direct sun's normal illuminance the sky's luminance is measured against, klx (a clear day's,
/// sea level, the sun high).
pub const SUN_ILLUMINANCE: f64 = 100.0;

/// The sun's angular radius, radians (0.2666°, the mean apparent radius).
pub const SUN_RADIUS: f64 = 0.004_653;

/// Rows of the CIE XYZ to linear sRGB matrix (D65).
const XYZ_TO_RGB: [[f64; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// The clear sky for one sun.
#[derive(Clone, Debug)]
pub struct Sky {
    /// Unit direction towards the sun.
    to_sun: DVec3,
    /// `A..E` of the Perez function for `Y`, `x` and `y`.
    perez: [[f64; 5]; 3],
    /// `Y_z / F(0, θ_s)` (already per unit of the sun's irradiance), `x_z / F(0, θ_s)`,
    /// `y_z / F(0, θ_s)`: the factor each channel's `F(θ, γ)` is multiplied by.
    scale: [f64; 3],
}

fn perez(c: &[f64; 5], cos_theta: f64, gamma: f64) -> f64 {
    let [a, b, c, d, e] = *c;
    let cos_gamma = gamma.cos();
    (1.0 + a * (b / cos_theta).exp()) * (1.0 + c * (d * gamma).exp() + e * cos_gamma * cos_gamma)
}

/// The view's zenith cosine the Perez function is evaluated at: the horizon's for directions below
/// it (their gradation term is the horizon's; the angle to the sun stays the direction's own), and
/// never 0, where `e^(B / cos θ)` is undefined.
fn zenith_cos(d: DVec3) -> f64 {
    d.z.max(1e-3)
}

impl Sky {
    /// The sky for sunlight travelling along `sun` (unit, pointing down) with turbidity `t`.
    pub fn new(sun: DVec3, t: f64) -> Sky {
        let to_sun = -sun.normalize();
        // The sun's zenith angle; a sun at or below the horizon is taken at the horizon.
        let theta_s = to_sun.z.clamp(0.0, 1.0).acos().min(FRAC_PI_2 - 1e-3);
        // Appendix A.2: the distribution coefficients.
        let coefficients = [
            [
                0.1787 * t - 1.4630,
                -0.3554 * t + 0.4275,
                -0.0227 * t + 5.3251,
                0.1206 * t - 2.5771,
                -0.0670 * t + 0.3703,
            ],
            [
                -0.0193 * t - 0.2592,
                -0.0665 * t + 0.0008,
                -0.0004 * t + 0.2125,
                -0.0641 * t - 0.8989,
                -0.0033 * t + 0.0452,
            ],
            [
                -0.0167 * t - 0.2608,
                -0.0950 * t + 0.0092,
                -0.0079 * t + 0.2102,
                -0.0441 * t - 1.6537,
                -0.0109 * t + 0.0529,
            ],
        ];
        // The zenith's luminance (kcd/m²) and chromaticities.
        let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * theta_s);
        let y_z = (4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192;
        let (s1, s2, s3) = (theta_s, theta_s * theta_s, theta_s * theta_s * theta_s);
        let x_z = t * t * (0.00166 * s3 - 0.00375 * s2 + 0.00209 * s1)
            + t * (-0.02903 * s3 + 0.06377 * s2 - 0.03202 * s1 + 0.00394)
            + (0.11693 * s3 - 0.21196 * s2 + 0.06052 * s1 + 0.25886);
        let yc_z = t * t * (0.00275 * s3 - 0.00610 * s2 + 0.00317 * s1)
            + t * (-0.04214 * s3 + 0.08970 * s2 - 0.04153 * s1 + 0.00516)
            + (0.15346 * s3 - 0.26756 * s2 + 0.06670 * s1 + 0.26688);
        let zenith = [y_z / SUN_ILLUMINANCE, x_z, yc_z];
        let mut scale = [0.0; 3];
        for k in 0..3 {
            scale[k] = zenith[k] / perez(&coefficients[k], 1.0, theta_s);
        }
        Sky {
            to_sun,
            perez: coefficients,
            scale,
        }
    }

    /// What the GPU twin evaluates: per row, `A, B, C, D, E` and the channel's scale, for `Y`, `x`
    /// and `y`.
    pub fn coefficients(&self) -> [[f64; 6]; 3] {
        std::array::from_fn(|k| {
            let [a, b, c, d, e] = self.perez[k];
            [a, b, c, d, e, self.scale[k]]
        })
    }

    /// The sky's radiance along unit `d`, linear sRGB, per unit of the sun's irradiance (1/sr),
    /// without the sun's disk.
    pub fn radiance(&self, d: DVec3) -> DVec3 {
        let cos_theta = zenith_cos(d);
        let gamma = d.dot(self.to_sun).clamp(-1.0, 1.0).acos();
        let [lum, x, y] =
            std::array::from_fn(|k| self.scale[k] * perez(&self.perez[k], cos_theta, gamma));
        xyy_to_rgb(lum, x, y)
    }

    /// The sun's disk along unit `d`: the sun's whole irradiance spread over its solid angle inside
    /// the disk, nothing outside (1/sr, as [`radiance`](Self::radiance)).
    pub fn sun_disk(&self, d: DVec3) -> f64 {
        let cos_radius = SUN_RADIUS.cos();
        if d.dot(self.to_sun) >= cos_radius {
            1.0 / (2.0 * PI * (1.0 - cos_radius))
        } else {
            0.0
        }
    }

    /// The irradiance the sky alone gives a horizontal surface facing up, `∫ L(ω) cos θ dω` over
    /// the upper hemisphere, per unit of the sun's irradiance: the ambient light of the floor, the
    /// walls and the objects (midpoint rule in `cos θ` and azimuth, 64 x 128 directions: within
    /// 0.1 % of 4x as many, `the_ambient_light_is_the_skys_irradiance`).
    pub fn horizontal_irradiance(&self) -> DVec3 {
        self.irradiance_midpoint(64, 128)
    }

    /// `∫ L cos θ dω` by the midpoint rule over `n_mu` steps of `cos θ` and `n_phi` of azimuth.
    fn irradiance_midpoint(&self, n_mu: usize, n_phi: usize) -> DVec3 {
        let mut sum = DVec3::ZERO;
        for i in 0..n_mu {
            let mu = (i as f64 + 0.5) / n_mu as f64;
            let s = (1.0 - mu * mu).sqrt();
            for j in 0..n_phi {
                let phi = 2.0 * PI * (j as f64 + 0.5) / n_phi as f64;
                sum += self.radiance(DVec3::new(s * phi.cos(), s * phi.sin(), mu)) * mu;
            }
        }
        // dω = dμ dφ.
        sum * (2.0 * PI / (n_mu * n_phi) as f64)
    }
}

/// Luminance and chromaticity to linear sRGB, negative components clipped.
fn xyy_to_rgb(lum: f64, x: f64, y: f64) -> DVec3 {
    if y <= 0.0 || lum <= 0.0 {
        return DVec3::ZERO;
    }
    let xyz = DVec3::new(x / y * lum, lum, (1.0 - x - y) / y * lum);
    DVec3::new(
        DVec3::from(XYZ_TO_RGB[0]).dot(xyz),
        DVec3::from(XYZ_TO_RGB[1]).dot(xyz),
        DVec3::from(XYZ_TO_RGB[2]).dot(xyz),
    )
    .max(DVec3::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn luminance(c: DVec3) -> f64 {
        0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
    }

    fn sun_at(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
        let (se, ce) = elevation_deg.to_radians().sin_cos();
        let (sa, ca) = azimuth_deg.to_radians().sin_cos();
        -DVec3::new(ce * ca, ce * sa, se)
    }

    fn dir(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
        -sun_at(elevation_deg, azimuth_deg)
    }

    #[test]
    fn the_zenith_matches_the_papers_model() {
        // Appendix A.2 by hand for T = 2.5 and the sun at 45°: χ = (4/9 - 2.5/120)(π/2) = 0.66541,
        // Y_z = (4.0453·2.5 - 4.9710) tan χ - 0.2155·2.5 + 2.4192 = 5.91611 kcd/m².
        let sky = Sky::new(sun_at(45.0, 0.0), 2.5);
        let zenith = sky.scale[0] * perez(&sky.perez[0], 1.0, FRAC_PI_2 / 2.0);
        assert!(
            (zenith * SUN_ILLUMINANCE - 5.91611).abs() < 1e-4,
            "{zenith}"
        );
        // Its colour is the clear sky's blue.
        let c = sky.radiance(DVec3::Z);
        assert!(c.z > c.y && c.y > c.x, "{c}");
    }

    #[test]
    fn the_sky_is_brightest_towards_the_sun() {
        for elevation in [15.0, 35.0, 60.0] {
            let sky = Sky::new(sun_at(elevation, 30.0), TURBIDITY);
            let towards = luminance(sky.radiance(dir(elevation, 30.0)));
            // Every other direction of a coarse sphere is darker.
            for e in (2..90).step_by(8) {
                for a in (0..360).step_by(15) {
                    let d = dir(e as f64, a as f64);
                    if d.dot(dir(elevation, 30.0)) < 0.99 {
                        let l = luminance(sky.radiance(d));
                        assert!(
                            l < towards,
                            "sun at {elevation}°: {l} at ({e}°, {a}°) >= {towards}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_sky_is_symmetric_about_the_suns_vertical_plane() {
        let sky = Sky::new(sun_at(40.0, 30.0), TURBIDITY);
        for e in [5.0, 20.0, 45.0, 80.0] {
            for offset in [10.0, 45.0, 90.0, 170.0] {
                let a = sky.radiance(dir(e, 30.0 + offset));
                let b = sky.radiance(dir(e, 30.0 - offset));
                assert!(
                    (a - b).length() <= 1e-12 * a.length().max(1.0),
                    "{a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn the_sky_follows_the_sun() {
        // A low sun gives a dimmer zenith and a brighter horizon around it than a high sun.
        let high = Sky::new(sun_at(70.0, 0.0), TURBIDITY);
        let low = Sky::new(sun_at(10.0, 0.0), TURBIDITY);
        assert!(luminance(low.radiance(DVec3::Z)) < luminance(high.radiance(DVec3::Z)));
        assert!(low.horizontal_irradiance().y < high.horizontal_irradiance().y);
    }

    #[test]
    fn the_ambient_light_is_the_skys_irradiance() {
        let sky = Sky::new(sun_at(45.0, 0.0), TURBIDITY);
        let e = sky.horizontal_irradiance();
        // Against a 4x finer midpoint grid along each axis.
        let fine = sky.irradiance_midpoint(256, 512);
        assert!(
            ((e - fine) / fine).abs().max_element() < 1e-3,
            "{e} vs {fine}"
        );
        // A clear sky lights a horizontal surface less than the sun does there (sin 45° of its
        // normal irradiance) and more than a twentieth of it. The model gives 0.260 / 0.707 = 0.367.
        let ratio = luminance(e) / (45f64.to_radians().sin());
        assert!((0.05..1.0).contains(&ratio), "{ratio}");
    }

    #[test]
    fn the_sun_disk_carries_the_suns_irradiance() {
        let sky = Sky::new(sun_at(50.0, 10.0), TURBIDITY);
        let to_sun = dir(50.0, 10.0);
        // ∫ over the disk of the disk's radiance dω = 1.
        let solid = 2.0 * PI * (1.0 - SUN_RADIUS.cos());
        assert!((sky.sun_disk(to_sun) * solid - 1.0).abs() < 1e-12);
        let beside = (to_sun + DVec3::new(0.0, 0.0, 2.0 * SUN_RADIUS)).normalize();
        assert_eq!(sky.sun_disk(beside), 0.0);
    }
}
