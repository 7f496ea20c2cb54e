use glam::{DVec2, DVec3};

use super::reference::{ReferenceOptions, reference};
use super::*;
use crate::metrics::compare;

/// A glass ball above the floor lit from an angle, the floor window around its caustic.
pub(crate) fn ball_scene(res: usize) -> GlassScene {
    ball_scene_in(res, 0.6)
}

pub(crate) fn ball_scene_in(res: usize, window: f64) -> GlassScene {
    let centre = DVec3::new(0.0, 0.0, 0.35);
    let light = DVec3::new(0.3, 0.2, -1.0).normalize();
    // The caustic lies around where the ray through the centre meets the floor.
    let foot = centre.truncate() + light.truncate() * (centre.z / -light.z);
    GlassScene::new(
        Shape::Sphere {
            centre,
            radius: 0.2,
        },
        1.5,
        light,
        FloorWindow {
            origin: foot - DVec2::splat(window / 2.0),
            size: window,
            width: res,
            height: res,
        },
        vec![],
    )
    .unwrap()
}

fn params(p: u32) -> CausticTrianglesParams {
    CausticTrianglesParams {
        photon_image: p,
        cube_resolution: 128,
        ..Default::default()
    }
}

#[test]
fn photon_power_matches_the_reference() {
    let s = ball_scene(64);
    let dm = DistanceMap::build(&s, 128, 2);
    let setup = CausticTrianglesSetup::new(&params(96), &s).unwrap();
    let photons = photon_pass(&setup, &dm);
    let ours = photon_power(&photons);
    let r = reference(
        &s,
        &ReferenceOptions {
            photons: 512,
            reflections: false,
            ..Default::default()
        },
    );
    let truth = r.budget.on_map + r.budget.off_map;
    assert!((ours / truth - 1.0).abs() < 0.02, "{ours} vs {truth}");
}

#[test]
fn triangles_beat_splats_against_the_reference() {
    let s = ball_scene(128);
    let dm = DistanceMap::build(&s, 128, 2);
    let r = reference(
        &s,
        &ReferenceOptions {
            photons: 1024,
            ..Default::default()
        },
    );
    let setup = CausticTrianglesSetup::new(&params(128), &s).unwrap();
    let out = caustics(&setup, &dm);
    let splats = splat_pass(&setup, &out.photons);
    let mt = compare(&out.map, &r.map);
    let ms = compare(&splats, &r.map);
    eprintln!("triangles {mt:?}\nsplats {ms:?}");
    assert!(mt.relative_l1 < 0.1, "{mt:?}");
    assert!(mt.relative_l1 < ms.relative_l1, "{mt:?} vs {ms:?}");
}

#[test]
fn the_hat_rule_conserves_the_photon_power() {
    let s = ball_scene_in(256, 2.4);
    let dm = DistanceMap::build(&s, 128, 2);
    let setup = CausticTrianglesSetup::new(
        &CausticTrianglesParams {
            area_rule: AreaRule::Hat,
            ..params(64)
        },
        &s,
    )
    .unwrap();
    let out = caustics(&setup, &dm);
    let drawn: f64 = out.map.texels.iter().map(|t| t[0] as f64).sum::<f64>() * s.floor.texel_area();
    // The power of the vertices of drawn triangles (the rim photons in no full quad are lost).
    let p = setup.p;
    let power: f64 = (0..p * p)
        .filter(|&k| out.irradiance[k] >= 0.0)
        .filter(|&k| {
            let (i, j) = ((k / p) as i64, (k % p) as i64);
            [(0, 0), (0, 1), (1, 0), (1, 1)]
                .iter()
                .any(|&(a, b)| quad_valid(&out.photons, p, i - a, j - b))
        })
        .map(|k| out.photons[k][2] as f64)
        .sum();
    let all = photon_power(&out.photons);
    let outside: f64 = out
        .photons
        .iter()
        .filter(|t| t[2] >= 0.0)
        .filter(|t| {
            let q = s.floor.to_pixel(DVec2::new(t[0] as f64, t[1] as f64));
            q.x < 2.0 || q.y < 2.0 || q.x > 254.0 || q.y > 254.0
        })
        .map(|t| t[2] as f64)
        .sum();
    eprintln!("drawn {drawn} in quads {power} all {all} near or beyond the edge {outside}");
    // What is left is rasterisation at texel centres (triangles smaller than a texel in the focus).
    assert!((drawn / power - 1.0).abs() < 0.02, "{drawn} vs {power}");
}

#[test]
fn a_wall_in_the_distance_map_stops_the_light() {
    let mut s = ball_scene(64);
    let c = DVec3::new(0.0, 0.0, 0.35);
    // A wall below the generator over the half x > centre + 0.05 (in the light's direction).
    s.occluders.push(Occluder::wall(
        DVec3::new(c.x + 0.05, -1.0, 0.06),
        DVec3::new(c.x + 1.0, 1.0, 0.1),
    ));
    let dm = DistanceMap::build(&s, 128, 4);
    assert!(
        dm.texels.iter().any(|t| t[3] < 0.0),
        "the wall is in the map"
    );
    let setup = CausticTrianglesSetup::new(&params(64), &s).unwrap();
    let out = caustics(&setup, &dm);
    // Everything right of the wall's edge, projected along the light to the floor, is dark.
    let l = s.light;
    let edge = c.x + 0.05 + l.x * (0.06 / -l.z);
    for (k, t) in out.map.texels.iter().enumerate() {
        let j = k % 64;
        let x = s.floor.origin.x + (j as f64 + 0.5) * s.floor.size / 64.0;
        if x > edge + 2.0 * s.floor.size / 64.0 {
            assert_eq!(t[0], 0.0, "texel {k} at x = {x} is lit behind the wall");
        }
    }
    let lit: f64 = out.map.texels.iter().map(|t| t[0] as f64).sum();
    assert!(lit > 0.0);
}

#[test]
fn bad_parameters_are_named() {
    let e = CausticTrianglesParams {
        layers: 0,
        ..Default::default()
    }
    .validate()
    .unwrap_err()
    .to_string();
    assert!(e.contains("caustic-triangles.layers"), "{e}");
    let t: toml::Table =
        toml::from_str("[caustic-triangles]\nphoton_image = 64\narea_rule = \"hat\"").unwrap();
    let p = CausticTrianglesParams::from_table(&t).unwrap();
    assert_eq!((p.photon_image, p.area_rule), (64, AreaRule::Hat));
}
