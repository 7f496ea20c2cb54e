//! The reference's physical properties. Run with `--release`: the
//! triangulations are fine.

use caustics_core::grid::{Edge, Grid};
use caustics_core::map::CausticsMap;
use caustics_core::optics::{fresnel_transmittance, height_field_normal, refract};
use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::scene::{Albedo, Floor, FloorPattern, Water, WaterSource};
use caustics_core::water::waves::{Wave, Waves};
use caustics_core::water::{Flat, GridSurface, Surface};
use glam::{DVec2, DVec3};

fn water(size: f64, depth: f64, wrap: bool) -> Water {
    Water {
        source: WaterSource::Flat,
        size,
        depth,
        ior: 1.333,
        wrap,
        absorption: DVec3::ZERO,
    }
}

fn plane() -> Floor {
    Floor {
        terrain: None,
        solids: None,
        albedo: Albedo::Pattern(FloorPattern::Plain),
        walls: false,
        deck: Default::default(),
    }
}

fn run(
    surface: &dyn Surface,
    water: &Water,
    floor: &Floor,
    light: DVec3,
    res: usize,
    cells_per_texel: u32,
) -> CausticsMap {
    let input = ReferenceInput {
        surface,
        water,
        floor,
        light: light.normalize(),
        width: res,
        height: res,
    };
    let options = ReferenceOptions {
        cells_per_texel,
        ..Default::default()
    };
    reference(&input, &options, &|_, _| {}).expect("reference runs")
}

fn ripples(size: f64) -> Waves {
    let w = |a, l, d: [f64; 2], phase| Wave {
        amplitude: a,
        wavelength: l,
        direction: d,
        phase,
        period: None,
    };
    Waves::new(
        &[
            w(0.006, 0.5, [1.0, 0.3], 0.0),
            w(0.004, 0.33, [-0.4, 1.0], 1.0),
            w(0.003, 0.25, [0.7, -0.7], 2.0),
        ],
        size,
        0.0,
    )
}

fn mean(m: &CausticsMap) -> f64 {
    m.texels.iter().map(|t| t[0] as f64).sum::<f64>() / m.texels.len() as f64
}

#[test]
fn flat_water_gives_one_everywhere() {
    for light in [
        DVec3::new(0.0, 0.0, -1.0),
        DVec3::new(0.3, 0.1, -1.0),
        DVec3::new(-0.8, 0.5, -0.4),
    ] {
        let m = run(&Flat, &water(1.0, 0.4, true), &plane(), light, 64, 2);
        let worst = m
            .texels
            .iter()
            .map(|t| (t[0] - 1.0).abs())
            .fold(0.0, f32::max);
        eprintln!("flat, light {light}: worst |E - 1| {worst:.2e}");
        // measured 0 (exact) at every sun; the bound allows f32 rounding
        for t in &m.texels {
            assert!((t[0] - 1.0).abs() < 1e-6, "light {light}: texel {}", t[0]);
        }
    }
    // Clamped edges: the traced domain must still cover the whole square.
    let m = run(
        &Flat,
        &water(1.0, 0.4, false),
        &plane(),
        DVec3::new(0.5, -0.2, -1.0),
        48,
        2,
    );
    let worst = m
        .texels
        .iter()
        .map(|t| (t[0] - 1.0).abs())
        .fold(0.0, f32::max);
    eprintln!("flat, clamped: worst |E - 1| {worst:.2e}");
    for t in &m.texels {
        assert!((t[0] - 1.0).abs() < 1e-6, "clamped: texel {}", t[0]); // measured 0
    }
}

#[test]
fn periodic_mean_is_the_mean_fresnel_ratio() {
    let size = 1.0;
    let s = ripples(size);
    let light = DVec3::new(0.4, 0.2, -1.0).normalize();
    let w = water(size, 0.5, true);
    let m = run(&s, &w, &plane(), light, 128, 4);
    // Independent quadrature of the same flux: the area the sun sees, (1 + L_xy · ∇h / |L_z|) dx dy,
    // times T(θi) / T(θ0).
    let t0 = fresnel_transmittance(-light.z, 1.0, w.ior);
    let n = 1024;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let p = DVec2::new(j as f64 + 0.5, i as f64 + 0.5) * (size / n as f64);
            let g = s.gradient(p);
            let nrm = height_field_normal(g);
            let seen = 1.0 + light.truncate().dot(g) / -light.z;
            sum += fresnel_transmittance(-light.dot(nrm), 1.0, w.ior) / t0 * seen;
        }
    }
    let expected = sum / (n * n) as f64;
    let got = mean(&m);
    eprintln!(
        "periodic mean {got} against the quadrature's {expected}: {:.2e}",
        got - expected
    );
    assert!(
        (got - expected).abs() < 1.6e-8, // measured -1.60e-9
        "mean {got}, expected {expected}"
    );
    // And the waves make real caustics: not a flat map.
    let max = m.texels.iter().map(|t| t[0]).fold(0.0f32, f32::max);
    assert!(max > 1.5, "max {max}");
}

#[test]
fn refining_the_triangulation_converges() {
    let s = ripples(1.0);
    let w = water(1.0, 0.3, true);
    let light = DVec3::new(0.2, 0.1, -1.0);
    let fine = run(&s, &w, &plane(), light, 64, 32);
    let l1 = |m: &CausticsMap| {
        m.texels
            .iter()
            .zip(&fine.texels)
            .map(|(a, b)| (a[0] - b[0]).abs() as f64)
            .sum::<f64>()
            / m.texels.len() as f64
    };
    let errors: Vec<f64> = [1, 2, 4, 8]
        .iter()
        .map(|&c| l1(&run(&s, &w, &plane(), light, 64, c)))
        .collect();
    eprintln!("L1 against 32 cells per texel: {errors:?}");
    for k in 1..errors.len() {
        assert!(
            errors[k] < errors[k - 1],
            "errors {errors:?} must shrink as triangles halve"
        );
    }
    // measured 3.1e-3, 4.7e-4, 1.3e-4, 3.0e-5: errors[3] / errors[0] = 0.0097
    assert!(errors[3] < 0.097 * errors[0], "errors {errors:?}");
}

#[test]
fn mirror_symmetric_input_gives_mirror_symmetric_output() {
    // A surface symmetric under x -> size - x, light in the yz-plane: the map must be symmetric too.
    let n = 64;
    let size = 1.0;
    let g = Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64 - 0.5;
        let y = (i as f64 + 0.5) / n as f64;
        (0.01 * (x * 14.0).cos() * (y * std::f64::consts::TAU * 3.0).sin()
            + 0.006 * (x * x * 60.0).cos()) as f32
    });
    // Enforce exact mirror symmetry of the samples.
    let g = Grid::from_fn(n, n, |i, j| 0.5 * (g.at(i, j) + g.at(i, n - 1 - j)));
    let s = GridSurface {
        grid: g,
        size,
        edge: Edge::Wrap,
    };
    let m = run(
        &s,
        &water(size, 0.35, true),
        &plane(),
        DVec3::new(0.0, 0.3, -1.0),
        64,
        4,
    );
    let mut worst: f64 = 0.0;
    for i in 0..64 {
        for j in 0..64 {
            let a = m.texels[i * 64 + j][0] as f64;
            let b = m.texels[i * 64 + 63 - j][0] as f64;
            worst = worst.max((a - b).abs() / (1.0 + a.abs()));
        }
    }
    eprintln!("mirror asymmetry {worst:.2e}");
    assert!(worst < 1e-6, "asymmetry {worst}"); // measured 0 (exact); f32 rounding allowed
}

/// A Gaussian bump `a exp(−r² / 2σ²)` is a converging lens of paraxial focal length
/// `f = n / ((n − 1) κ)` below its apex, with curvature `κ = a / σ²` (refraction at one spherical
/// surface from air into water). The floor's brightest point lies on the ray through the apex, and
/// before the focus the irradiance under the apex grows as paraxial optics says.
#[test]
fn a_lens_bump_focuses_where_geometric_optics_says() {
    struct Bump {
        a: f64,
        sigma: f64,
        c: DVec2,
    }
    impl Surface for Bump {
        fn height(&self, p: DVec2) -> f64 {
            let r2 = (p - self.c).length_squared();
            self.a * (-r2 / (2.0 * self.sigma * self.sigma)).exp()
        }
        fn gradient(&self, p: DVec2) -> DVec2 {
            -(p - self.c) / (self.sigma * self.sigma) * self.height(p)
        }
    }
    let n = 1.333;
    let bump = Bump {
        a: 0.01,
        sigma: 0.08,
        c: DVec2::new(0.5, 0.5),
    };
    let kappa = bump.a / (bump.sigma * bump.sigma);
    let f = n / ((n - 1.0) * kappa);
    let res = 96;
    let peak_at = |depth: f64, light: DVec3| {
        let m = run(&bump, &water(1.0, depth, true), &plane(), light, res, 4);
        let (k, v) = m
            .texels
            .iter()
            .enumerate()
            .max_by(|a, b| a.1[0].total_cmp(&b.1[0]))
            .unwrap();
        let p = DVec2::new((k % res) as f64 + 0.5, (k / res) as f64 + 0.5) / res as f64;
        (p, v[0] as f64)
    };
    // Overhead: the focus lies under the apex.
    let (p, v) = peak_at(f, DVec3::new(0.0, 0.0, -1.0));
    assert!((p - bump.c).length() < 1.5 / res as f64, "peak at {p}");
    assert!(v > 5.0, "a focus, not a ripple: {v}");
    // Oblique: the focus follows the ray refracted at the apex (where the normal is vertical).
    let light = DVec3::new(0.35, 0.0, -1.0).normalize();
    let t = refract(light, DVec3::Z, 1.0 / n).unwrap();
    let depth = f * 0.8;
    let apex_ray = bump.c + t.truncate() * ((depth + bump.a) / -t.z);
    let (p, _) = peak_at(depth, light);
    // The surface tiles, so positions compare modulo the square.
    let apart = (p - apex_ray + DVec2::splat(0.5)).rem_euclid(DVec2::ONE) - DVec2::splat(0.5);
    assert!(
        apart.length() < 0.03,
        "peak at {p}, apex ray lands at {apex_ray}"
    );
    // Before the focus, paraxial optics maps the apex's neighbourhood onto the floor scaled by
    // (1 − z / f), z the distance from the apex down to the floor, so the irradiance under the apex
    // is 1 / (1 − z / f)² (Fresnel at the apex equals flat water's under overhead light).
    // Fine texels, so that the averaged patch is small against σ (the bump's curvature falls off
    // as r²/σ², the lens's spherical aberration).
    let res = 384;
    for frac in [0.25, 0.5, 0.65] {
        let depth = f * frac;
        let m = run(
            &bump,
            &water(1.0, depth, true),
            &plane(),
            DVec3::NEG_Z,
            res,
            2,
        );
        let c = res / 2;
        // The apex sits on the corner of four texels: average them.
        let v = (m.texels[c * res + c][0]
            + m.texels[(c - 1) * res + c][0]
            + m.texels[c * res + c - 1][0]
            + m.texels[(c - 1) * res + c - 1][0]) as f64
            / 4.0;
        let z = depth + bump.a;
        let expected = 1.0 / (1.0 - z / f).powi(2);
        assert!(
            (v / expected - 1.0).abs() < 0.03,
            "depth {depth}: apex irradiance {v}, paraxial {expected}"
        );
    }
}

#[test]
fn absorption_follows_beer_lambert_along_the_refracted_path() {
    let mut w = water(1.0, 0.5, true);
    w.absorption = DVec3::new(0.9, 0.2, 0.05);
    let light = DVec3::new(0.3, 0.0, -1.0).normalize();
    let m = run(&Flat, &w, &plane(), light, 16, 1);
    let t = refract(light, DVec3::Z, 1.0 / w.ior).unwrap();
    let d = w.depth / -t.z;
    for c in 0..3 {
        let expected = (-w.absorption[c] * d).exp();
        for texel in &m.texels {
            assert!(
                (texel[c] as f64 - expected).abs() < 1e-5,
                "channel {c}: {} vs {expected}",
                texel[c]
            );
        }
    }
}

/// Flat water over a planar slope: the irradiance is the beam's, `E⊥ |T · m|`, so relative to a
/// horizontal floor `|T · m| / |T_z|` with `m` the slope's unit normal.
#[test]
fn terrain_receives_the_cosine_of_its_slope() {
    let n = 64;
    let size = 1.0;
    let slope = 0.3;
    let terrain = Grid::from_fn(n, n, |_, j| {
        (0.05 + slope * (j as f64 + 0.5) / n as f64 * size) as f32
    });
    let floor = Floor {
        terrain: Some(terrain),
        solids: None,
        albedo: Albedo::Pattern(FloorPattern::Sand),
        walls: false,
        deck: Default::default(),
    };
    let w = water(size, 0.6, true);
    let light = DVec3::new(0.25, 0.1, -1.0).normalize();
    let m = run(&Flat, &w, &floor, light, 32, 2);
    let t = refract(light, DVec3::Z, 1.0 / w.ior).unwrap();
    let normal = DVec3::new(-slope, 0.0, 1.0).normalize();
    let expected = t.dot(normal).abs() / t.z.abs();
    // Away from the ramp's ends, where the clamped terrain bends and wrapped light arrives.
    for i in 4..28 {
        for j in 8..24 {
            let v = m.texels[i * 32 + j][0] as f64;
            assert!(
                (v - expected).abs() < 2e-3,
                "texel ({i}, {j}) = {v}, expected {expected}"
            );
        }
    }
}

#[test]
fn bad_parameters_are_errors() {
    let w = water(1.0, 0.4, true);
    let floor = plane();
    let input = ReferenceInput {
        surface: &Flat,
        water: &w,
        floor: &floor,
        light: DVec3::new(0.0, 0.0, 1.0),
        width: 8,
        height: 8,
    };
    assert!(
        reference(&input, &ReferenceOptions::default(), &|_, _| {})
            .unwrap_err()
            .to_string()
            .contains("point down")
    );
    let input = ReferenceInput {
        light: DVec3::NEG_Z,
        width: 0,
        ..input
    };
    assert!(reference(&input, &ReferenceOptions::default(), &|_, _| {}).is_err());
    // A map whose accumulators would not fit is refused before anything is allocated.
    let input = ReferenceInput {
        width: 16384,
        height: 16384,
        ..input
    };
    let e = reference(&input, &ReferenceOptions::default(), &|_, _| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("16384 x 16384") && e.contains("GiB"), "{e}");
}
