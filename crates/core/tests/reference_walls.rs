//! The reference with the pool's walls as receivers: conservation of the light that
//! leaves the water surface, the far wall lit and the near floor in shadow under a low sun, and the
//! cosine law on a wall under flat water. Run with `--release`.

use caustics_core::map::CausticsMap;
use caustics_core::optics::{fresnel_transmittance, height_field_normal, refract};
use caustics_core::reference::{
    ReferenceInput, ReferenceOptions, ReferenceOutput, reference_with_walls,
};
use caustics_core::scene::{Albedo, Floor, FloorPattern, Water, WaterSource};
use caustics_core::walls::Wall;
use caustics_core::water::waves::{Wave, Waves};
use caustics_core::water::{Flat, Surface};
use glam::{DVec2, DVec3};

fn water(size: f64, depth: f64, absorption: DVec3) -> Water {
    Water {
        source: WaterSource::Flat,
        size,
        depth,
        ior: 1.333,
        wrap: true,
        absorption,
    }
}

fn pool() -> Floor {
    Floor {
        terrain: None,
        solids: None,
        albedo: Albedo::Pattern(FloorPattern::Plain),
        walls: true,
        deck: Default::default(),
    }
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

/// A sun `zenith` degrees from the zenith, travelling along `heading` in the horizontal.
fn sun(zenith: f64, heading: DVec2) -> DVec3 {
    let (s, c) = zenith.to_radians().sin_cos();
    (heading.normalize() * s).extend(-c)
}

fn run(
    surface: &dyn Surface,
    water: &Water,
    light: DVec3,
    res: usize,
    options: &ReferenceOptions,
) -> ReferenceOutput {
    let floor = pool();
    let input = ReferenceInput {
        surface,
        water,
        floor: &floor,
        light,
        width: res,
        height: res,
    };
    reference_with_walls(&input, options, &|_, _| {}).expect("reference runs")
}

/// Flux on the floor per channel, in the map's unit times area.
fn floor_flux(m: &CausticsMap) -> DVec3 {
    let area = (m.size / m.width as f64) * (m.size / m.height as f64);
    m.texels
        .iter()
        .map(|t| DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64))
        .sum::<DVec3>()
        * area
}

/// The light that leaves the surface, found by an independent quadrature (the area the sun sees,
/// `(1 + L_xy · ∇h / |L_z|) dx dy`, times `T(θi) / T(θ0)`), equals what floor and walls receive;
/// and with absorption each channel's deposit equals the reference's own transmitted flux.
#[test]
fn floor_and_walls_hold_the_light_that_leaves_the_surface() {
    let size = 1.0;
    let s = ripples(size);
    let light = sun(70.0, DVec2::new(1.0, 0.3));
    let w = water(size, 0.5, DVec3::ZERO);
    let options = ReferenceOptions {
        cells_per_texel: 4,
        absorption: false,
        ..Default::default()
    };
    let out = run(&s, &w, light, 64, &options);
    let walls = out.walls.as_ref().expect("walls on");
    let received = floor_flux(&out.floor).x + walls.flux();
    let t0 = fresnel_transmittance(-light.z, 1.0, w.ior);
    let n = 1024;
    let mut leaving = 0.0;
    for i in 0..n {
        for j in 0..n {
            let p = DVec2::new(j as f64 + 0.5, i as f64 + 0.5) * (size / n as f64);
            let g = s.gradient(p);
            let seen = 1.0 + light.truncate().dot(g) / -light.z;
            let cos_i = -light.dot(height_field_normal(g));
            leaving += seen * fresnel_transmittance(cos_i, 1.0, w.ior) / t0;
        }
    }
    leaving *= (size / n as f64).powi(2);
    let wall_share = walls.flux() / received;
    let err = (received - leaving).abs() / leaving;
    eprintln!(
        "leaving {leaving:.9}, floor + walls {received:.9} (walls {:.1} %): relative {err:.2e}",
        wall_share * 100.0
    );
    // Measured 7.0e-6 (the triangulation's flux against the quadrature).
    assert!(err < 5e-5, "{err}");
    assert!(
        wall_share > 0.2,
        "a low sun sends much of the light to the walls"
    );

    // With absorption: per channel, the deposit is exactly what the surface let through.
    let w = water(size, 0.5, DVec3::new(0.4, 0.1, 0.05));
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let out = run(&s, &w, light, 64, &options);
    let walls = out.walls.as_ref().expect("walls on");
    let wall_flux = walls
        .maps
        .iter()
        .map(|m| {
            m.texels
                .iter()
                .map(|t| DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64))
                .sum::<DVec3>()
                * m.texel_area()
        })
        .sum::<DVec3>();
    let received = floor_flux(&out.floor) + wall_flux;
    let err = ((received - out.transmitted) / out.transmitted)
        .abs()
        .max_element();
    eprintln!("absorbing water: deposit vs transmitted, relative {err:.2e} (worst channel)");
    // Measured 9.8e-10 (f32 texels summed back).
    assert!(err < 1e-8, "{err}");
}

/// A low sun travelling along +x: the far wall (x = size) is lit, the wall it comes from is dark,
/// and the floor by that wall lies in its shadow, `depth · tan θt` wide, θt the refracted angle.
#[test]
fn a_low_sun_lights_the_far_wall_and_shadows_the_near_floor() {
    let size = 1.0;
    let depth = 0.4;
    let res = 128;
    let s = ripples(size);
    let light = sun(75.0, DVec2::X);
    let w = water(size, depth, DVec3::ZERO);
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let out = run(&s, &w, light, res, &options);
    let walls = out.walls.as_ref().expect("walls on");
    let t = refract(light, DVec3::Z, 1.0 / w.ior).unwrap();
    let tan_t = t.x / -t.z;
    let texel = size / res as f64;
    // Per row of texels: the shadow's edge is the nearest floor point that the rays through the
    // surface by the wall x = 0 reach in that row (refracted by the waves' own normals, which
    // also deflect them along y and can fold the ray map: a minimum over the surface's first
    // centimetres, not the ray at x = 0 alone); the first texel holding any light must be the
    // one that edge falls in.
    let mut edges = vec![f64::INFINITY; res];
    for a in 0..8 * res {
        for k in 0..=80 {
            let p = DVec2::new(k as f64 * 1e-3, (a as f64 + 0.5) * texel / 8.0);
            let (h, g) = s.height_gradient(p);
            let r = refract(light, height_field_normal(g), 1.0 / w.ior).unwrap();
            let land = p + r.truncate() * ((depth + h) / -r.z);
            let i = (land.y / texel).floor();
            if (0.0..res as f64).contains(&i) {
                edges[i as usize] = edges[i as usize].min(land.x);
            }
        }
    }
    // Rows by the y-walls are left out: the waves deflect some light sideways onto those walls.
    let rows = 8..res - 8;
    let (mut worst, mut sum) = (0.0f64, 0.0);
    for i in rows.clone() {
        let edge = edges[i];
        let row = &out.floor.texels[i * res..(i + 1) * res];
        let first = row.iter().position(|t| t[0] > 0.0).expect("a lit floor") as f64;
        let off = first - (edge / texel).floor();
        worst = worst.max(off.abs());
        sum += off;
        for (j, t) in row.iter().enumerate().take(first as usize) {
            assert_eq!(t[0], 0.0, "({i}, {j}) in the shadow");
        }
        let lit = &row[(edge / texel) as usize + 3];
        assert!(lit[0] > 0.1, "row {i} beyond the shadow: {}", lit[0]);
    }
    eprintln!(
        "shadow edge per row: first lit texel vs the edge ray's texel, worst {worst} texels, mean \
         {:.2}; flat water's edge depth · tan θt = {:.4} m",
        sum / rows.len() as f64,
        depth * tan_t
    );
    // Measured: worst 2 texels, mean -0.06 (the edges sampled 8 times per texel along y).
    assert!(worst <= 2.0, "{worst}");
    let mean = |w: Wall| {
        let m = walls.get(w);
        m.mean_channel().data.iter().map(|&v| v as f64).sum::<f64>() / m.texels.len() as f64
    };
    eprintln!(
        "walls' mean: x0 {:.4}, x1 {:.4}, y0 {:.4}, y1 {:.4}; flat water gives x1 tan θt = {tan_t:.4}",
        mean(Wall::X0),
        mean(Wall::X1),
        mean(Wall::Y0),
        mean(Wall::Y1)
    );
    assert_eq!(mean(Wall::X0), 0.0);
    assert!((mean(Wall::X1) / tan_t - 1.0).abs() < 0.1);
    // The ripples deflect a little light sideways onto the y-walls, far less than onto x1.
    assert!(mean(Wall::Y0) + mean(Wall::Y1) < 0.1 * mean(Wall::X1));
}

/// Flat water and a sun along +x: only x1 is lit, uniformly, at the cosine law's irradiance
/// relative to the floor's, `cos(angle to the wall's normal) / cos θt = sin θt / cos θt`, and the
/// floor is 1 beyond the shadow and 0 in it.
#[test]
fn flat_water_lights_the_far_wall_by_the_cosine_law() {
    let size = 2.0;
    let depth = 0.5;
    let res = 64;
    for zenith in [40.0, 75.0] {
        let light = sun(zenith, DVec2::X);
        let w = water(size, depth, DVec3::ZERO);
        let options = ReferenceOptions {
            cells_per_texel: 2,
            ..Default::default()
        };
        let out = run(&Flat, &w, light, res, &options);
        let walls = out.walls.as_ref().expect("walls on");
        let t = refract(light, DVec3::Z, 1.0 / w.ior).unwrap();
        let tan_t = t.x / -t.z;
        let x1 = walls.get(Wall::X1);
        let worst = x1
            .texels
            .iter()
            .map(|t| (t[0] as f64 / tan_t - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "sun {zenith}°: x1 / tan θt - 1 at worst {worst:.2e} over {} texels",
            x1.texels.len()
        );
        // Measured 1.6e-8 (f32).
        assert!(worst < 1.5e-7, "{worst}");
        for w in [Wall::X0, Wall::Y0, Wall::Y1] {
            assert!(walls.get(w).texels.iter().all(|t| t[0] == 0.0), "{w:?} lit");
        }
        let shadow = depth * tan_t;
        let texel = size / res as f64;
        let mut floor_worst = 0.0f64;
        for i in 0..res {
            for j in 0..res {
                let v = out.floor.texels[i * res + j][0] as f64;
                let (x0, x1) = (j as f64 * texel, (j + 1) as f64 * texel);
                let lit = ((x1 - shadow.max(x0)) / texel).clamp(0.0, 1.0);
                floor_worst = floor_worst.max((v - lit).abs());
            }
        }
        eprintln!("floor against its lit fraction: worst {floor_worst:.2e}");
        // Measured 6.9e-9 at worst.
        assert!(floor_worst < 6e-8, "{floor_worst}");
    }
}
