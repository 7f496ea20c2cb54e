//! Technique `caustic-triangles` against its reference photon tracer: focus position and total
//! power, the error of caustic triangles (both area rules) and of the splatting baseline at several
//! photon-image sizes, under the sun and under the `glass-lamp` scene's point light, and pictures
//! (technique | reference | difference).
//!
//! `cargo run --release -p caustics-core --example caustic_triangles_compare -- [out_dir]`

use std::path::Path;
use std::time::Instant;

use caustics_core::map::CausticsMap;
use caustics_core::metrics::{Metrics, compare};
use caustics_core::techniques::caustic_triangles::reference::{ReferenceOptions, reference};
use caustics_core::techniques::caustic_triangles::{
    self as ct, AreaRule, CausticTrianglesParams, CausticTrianglesSetup, DistanceMap, FloorWindow,
    GlassScene, Shape,
};
use glam::{DVec2, DVec3};
use image::{Rgb, RgbImage};

/// The `glass` scene's sphere (radius 0.12, ior 1.5, its sun), optionally raised by `lift`, the
/// floor window of side `window` centred where the ray through the centre meets the floor.
fn glass_sphere(lift: f64, light: DVec3, window: f64, res: usize) -> GlassScene {
    glass_sphere_lit(lift, light, None, window, res)
}

/// The same sphere lit by the point light at `lamp` instead of the sun when given.
fn glass_sphere_lit(
    lift: f64,
    light: DVec3,
    lamp: Option<DVec3>,
    window: f64,
    res: usize,
) -> GlassScene {
    let centre = DVec3::new(0.35, 0.5, 0.12 + lift);
    let light = lamp.map_or(light, |l| centre - l).normalize();
    let foot = centre.truncate() + light.truncate() * (centre.z / -light.z);
    let s = GlassScene::new(
        Shape::Sphere {
            centre,
            radius: 0.12,
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
    .unwrap();
    match lamp {
        None => s,
        Some(position) => s
            .with_point_light(ct::PointLight {
                position,
                axis: light,
                cone: None,
            })
            .unwrap(),
    }
}

fn total(m: &CausticsMap, floor: &FloorWindow) -> f64 {
    m.texels.iter().map(|t| t[0] as f64).sum::<f64>() * floor.texel_area()
}

fn peak(m: &CausticsMap, floor: &FloorWindow) -> (DVec2, f32) {
    let (k, v) =
        m.texels.iter().enumerate().fold(
            (0, 0.0f32),
            |b, (k, t)| if t[0] > b.1 { (k, t[0]) } else { b },
        );
    let px = DVec2::new((k % m.width) as f64 + 0.5, (k / m.width) as f64 + 0.5);
    (floor.origin + px / m.width as f64 * floor.size, v)
}

fn write_triptych(path: &Path, a: &CausticsMap, r: &CausticsMap) -> f32 {
    let (w, h) = (a.width as u32, a.height as u32);
    let gap = 4;
    let mut img = RgbImage::from_pixel(3 * w + 2 * gap, h, Rgb([255, 255, 255]));
    let mut diffs: Vec<f32> = a
        .texels
        .iter()
        .zip(&r.texels)
        .map(|(x, y)| (x[0] - y[0]).abs())
        .collect();
    diffs.sort_by(f32::total_cmp);
    let range = diffs[((diffs.len() - 1) as f32 * 0.99) as usize].max(1e-6);
    // Tone map so that 1 (the unobstructed sun) is mid-grey; bright foci compress.
    let grey = |e: f32| {
        let v = (e.max(0.0) / (1.0 + e.max(0.0)) * 255.0) as u8;
        Rgb([v, v, v])
    };
    for i in 0..h {
        for j in 0..w {
            let y = h - 1 - i; // row 0 is the lowest y: draw it at the bottom, as seen from above
            let k = (i * w + j) as usize;
            img.put_pixel(j, y, grey(a.texels[k][0]));
            img.put_pixel(w + gap + j, y, grey(r.texels[k][0]));
            let d = ((a.texels[k][0] - r.texels[k][0]) / range).clamp(-1.0, 1.0);
            let c = if d >= 0.0 {
                Rgb([255, (255.0 * (1.0 - d)) as u8, (255.0 * (1.0 - d)) as u8])
            } else {
                Rgb([(255.0 * (1.0 + d)) as u8, (255.0 * (1.0 + d)) as u8, 255])
            };
            img.put_pixel(2 * (w + gap) + j, y, c);
        }
    }
    img.save(path).expect("write png");
    range
}

fn row(name: &str, p: u32, m: &Metrics, ms: f64) {
    println!(
        "| {name} | {p}x{p} | {:.4} | {:.4} | {:+.4} | {:.3} | {ms:.0} |",
        m.relative_l1, m.relative_rmse, m.flux_error, m.ssim
    );
}

fn main() {
    let out = std::env::args().nth(1).unwrap_or_else(|| "docs/img".into());
    std::fs::create_dir_all(&out).unwrap();
    let sun = DVec3::new(0.45, 0.3, -0.8);

    // 1. Focus: overhead light, the sphere raised so that the paraxial focus lies on the floor.
    let (r, n) = (0.12, 1.5);
    let f = n * r / (2.0 * (n - 1.0));
    let s = glass_sphere(f - r, DVec3::NEG_Z, 0.24, 256);
    let t = Instant::now();
    let refr = reference(
        &s,
        &ReferenceOptions {
            photons: 4096,
            ..Default::default()
        },
    );
    println!(
        "focus scene: sphere r {r}, n {n}, centre {:?}, paraxial back focal distance {f:.4} (focus on the floor at the centre's x, y)",
        DVec3::new(0.35, 0.5, f)
    );
    println!(
        "reference: {} photons, {:.1} s, budget {:?}",
        refr.photons,
        t.elapsed().as_secs_f64(),
        refr.budget
    );
    let (pr, vr) = peak(&refr.map, &s.floor);
    println!("reference peak at {pr:.4} value {vr:.1}");
    for p in [64, 128, 256] {
        let params = CausticTrianglesParams {
            photon_image: p,
            cube_resolution: 256,
            ..Default::default()
        };
        let dm = DistanceMap::build(&s, 256, 2);
        let setup = CausticTrianglesSetup::new(&params, &s).unwrap();
        let o = ct::caustics(&setup, &dm);
        let (pt, vt) = peak(&o.map, &s.floor);
        println!(
            "triangles P={p}: peak at {pt:.4} value {vt:.1}, photon power {:.5}, drawn {:.5}, reference on map {:.5}",
            ct::photon_power(&o.photons),
            total(&o.map, &s.floor),
            refr.budget.on_map
        );
    }

    // 2. The glass scene's sphere with its sun (resting on the floor: a concentrated spot), and the
    // same sphere raised by 0.25 (past the focus: a spread caustic), 256 x 256 over a 0.6 window.
    // 3. The same under the `glass-lamp` scene's light as a bare point light.
    let lamp = DVec3::new(0.15, 0.25, 0.75);
    for (label, lift, point) in [
        ("resting", 0.0, None),
        ("raised", 0.25, None),
        ("lamp-resting", 0.0, Some(lamp)),
        ("lamp-raised", 0.25, Some(lamp)),
    ] {
        let s = glass_sphere_lit(lift, sun, point, 0.6, 256);
        println!("\n## {label} sphere (lift {lift}, point light {point:?})");
        let t = Instant::now();
        let r1 = reference(
            &s,
            &ReferenceOptions {
                photons: 4096,
                ..Default::default()
            },
        );
        let r_time = t.elapsed().as_secs_f64();
        let r2 = reference(
            &s,
            &ReferenceOptions {
                photons: 2048,
                seed: 7,
                ..Default::default()
            },
        );
        let conv = compare(&r2.map, &r1.map);
        println!(
            "\nglass sphere: reference {} photons in {r_time:.1} s; 2048^2 vs 4096^2: rel L1 {:.4}, rel RMSE {:.4}",
            r1.photons, conv.relative_l1, conv.relative_rmse
        );
        println!(
            "budget {:?}, unaccounted {:.2e}",
            r1.budget,
            r1.budget.unaccounted()
        );
        println!(
            "\n| method | photon image | rel. L1 | rel. RMSE | flux error | SSIM | CPU ms |\n|---|---|---|---|---|---|---|"
        );
        let dm = DistanceMap::build(&s, 256, 2);
        for p in [64u32, 128, 256] {
            for (name, rule, merge_levels) in [
                ("triangles (paper ΔA)", AreaRule::Paper, 0),
                ("triangles (hat ΔA)", AreaRule::Hat, 0),
                (
                    "triangles (paper ΔA), §5 merging 4 levels",
                    AreaRule::Paper,
                    4,
                ),
            ] {
                let params = CausticTrianglesParams {
                    photon_image: p,
                    cube_resolution: 256,
                    area_rule: rule,
                    merge_levels,
                    ..Default::default()
                };
                let setup = CausticTrianglesSetup::new(&params, &s).unwrap();
                let t = Instant::now();
                let o = ct::caustics(&setup, &dm);
                let ms = t.elapsed().as_secs_f64() * 1e3;
                row(name, p, &compare(&o.map, &r1.map), ms);
                if p == 128 && rule == AreaRule::Paper && merge_levels == 0 {
                    let range = write_triptych(
                        &Path::new(&out).join(format!("caustic-triangles-128-{label}.png")),
                        &o.map,
                        &r1.map,
                    );
                    eprintln!("triangles 128 difference range ±{range}");
                    for splat in [1.0, 2.0, 4.0] {
                        let setup = CausticTrianglesSetup::new(
                            &CausticTrianglesParams {
                                splat_size: splat,
                                ..params.clone()
                            },
                            &s,
                        )
                        .unwrap();
                        let m = ct::splat_pass(&setup, &o.photons);
                        let range = write_triptych(
                            &Path::new(&out)
                                .join(format!("caustic-splats-128-s{splat}-{label}.png")),
                            &m,
                            &r1.map,
                        );
                        eprintln!("splats {splat} difference range ±{range}");
                    }
                }
            }
            for splat in [1.0, 2.0, 4.0] {
                let params = CausticTrianglesParams {
                    photon_image: p,
                    cube_resolution: 256,
                    splat_size: splat,
                    ..Default::default()
                };
                let setup = CausticTrianglesSetup::new(&params, &s).unwrap();
                let t = Instant::now();
                let photons = ct::photon_pass(&setup, &dm);
                let m = ct::splat_pass(&setup, &photons);
                let ms = t.elapsed().as_secs_f64() * 1e3;
                row(
                    &format!("splats ({splat} texels)"),
                    p,
                    &compare(&m, &r1.map),
                    ms,
                );
            }
        }
    }
}
