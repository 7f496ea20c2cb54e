//! Technique `cascaded`: the GPU passes against their CPU twin (G-buffers of every cascade and the
//! final screen-space caustics), the uniform block against its WGSL twin, and (ignored by default) the
//! per-pass timings of docs/benchmarks.md.

#[macro_use]
mod common;
mod wgsl;

use caustics_core::scene::Scene;
use caustics_core::techniques::cascaded::{
    self, CASCADES, CascadedParams, CascadedSetup, Dispersion, Placement, Splat,
};
use caustics_gpu::GpuTimer;
use caustics_gpu::cascaded::{Cascaded, CascadedUniform};
use caustics_gpu::context::test_gpu;

fn shore(width: u32, height: u32) -> Scene {
    let mut s = Scene::builtin("shore").unwrap();
    s.camera.width = width;
    s.camera.height = height;
    s
}

fn uniform_matches_its_wgsl_size() {
    assert_eq!(
        wgsl::wgsl_struct_size(&caustics_gpu::cascaded::PHOTONS, "Cascaded"),
        std::mem::size_of::<CascadedUniform>()
    );
}

fn gbuffers_match_the_cpu_twin() {
    let ctx = test_gpu();
    let cascaded = Cascaded::new(&ctx).unwrap();
    let scene = shore(96, 54);
    let params = CascadedParams {
        resolution: 96,
        ..Default::default()
    };
    let setup = CascadedSetup::from_scene(&scene, &params).unwrap();
    let water = cascaded::water_grid(&scene, 128).unwrap();
    let terrain = scene.floor.terrain.as_ref();
    let tex = ctx.upload_grid("water", &water).unwrap();
    let frame = cascaded
        .frame(&ctx, &setup, &tex.create_view(&Default::default()), terrain)
        .unwrap();
    for k in 0..CASCADES {
        let (gw, gt) = cascaded.gbuffers(&ctx, &frame, k).unwrap();
        let cw = cascaded::water_gbuffer(&setup, k, &water);
        let ct = cascaded::terrain_gbuffer(&setup, k, terrain);
        let (mut depth, mut normal, mut ground) = (0f32, 0f32, 0f32);
        for t in 0..cw.len() {
            depth = depth.max((gw[t][0] - cw[t][0]).abs());
            normal = normal.max(
                (1..4)
                    .map(|c| (gw[t][c] - cw[t][c]).abs())
                    .fold(0.0, f32::max),
            );
            ground = ground.max((gt[t] - ct[t]).abs());
        }
        eprintln!(
            "cascade {k}: max |Δ| water depth {depth:.2e}, normal {normal:.2e}, terrain depth {ground:.2e}"
        );
        // Depths in world units on a 32 m scene (measured: below 6.7e-6 on lavapipe 25.0.7); the normal's components
        // (measured: up to 5.6e-5, f32 rounding of the steep wavelets' finite differences; lavapipe 25.0.7).
        assert!(depth < 5e-5, "cascade {k}: water depth {depth}");
        assert!(normal < 2e-4, "cascade {k}: normal {normal}");
        assert!(ground < 5e-5, "cascade {k}: terrain depth {ground}");
    }
}

/// Agreement of two screen images over the pixels the CPU lights: the difference of the totals, and
/// the mean absolute per-pixel difference, both relative to the CPU's mean.
fn agreement(cpu: &[[f32; 4]], gpu: &[[f32; 4]]) -> (f64, f64, usize) {
    let (mut sc, mut sg, mut diff, mut n, mut moved) = (0.0, 0.0, 0.0, 0usize, 0usize);
    for (a, b) in cpu.iter().zip(gpu) {
        if a[3] < 0.0 {
            continue;
        }
        for c in 0..3 {
            sc += a[c] as f64;
            sg += b[c] as f64;
            let d = (a[c] - b[c]).abs() as f64;
            diff += d;
            if d > 1e-3 * (a[c].abs() as f64).max(1e-3) {
                moved += 1;
            }
        }
        n += 3;
    }
    let mean = sc / n as f64;
    (((sg - sc) / sc).abs(), diff / n as f64 / mean, moved)
}

fn screen_caustics_match_the_cpu_twin() {
    let ctx = test_gpu();
    let cascaded = Cascaded::new(&ctx).unwrap();
    let scene = shore(240, 135);
    let water = cascaded::water_grid(&scene, 128).unwrap();
    let terrain = scene.floor.terrain.as_ref();
    for (placement, dispersion, terrain_pass, splat) in [
        (Placement::Eq33, Dispersion::None, true, Splat::Footprint),
        (
            Placement::Plane,
            Dispersion::Wavelength,
            true,
            Splat::Footprint,
        ),
        (Placement::Eq33, Dispersion::Post, false, Splat::Footprint),
        (Placement::Eq33, Dispersion::None, true, Splat::Point),
    ] {
        let params = CascadedParams {
            resolution: 192,
            placement,
            dispersion,
            dispersion_scale: 20.0,
            terrain_pass,
            splat,
            ..Default::default()
        };
        let setup = CascadedSetup::from_scene(&scene, &params).unwrap();
        let cpu = cascaded::caustics(&setup, &water, terrain);
        let gpu = cascaded
            .caustics(&ctx, &setup, &water, terrain, None)
            .unwrap();
        let eye = cpu
            .eye
            .iter()
            .zip(&gpu.eye)
            .map(|(a, b)| ((a[0] - b[0]).abs() / a[0].max(1.0)) as f64)
            .fold(0.0, f64::max);
        let same = cpu.acc.iter().zip(&gpu.acc).filter(|(a, b)| a == b).count();
        let (total, mean_abs, moved) = agreement(&cpu.image, &gpu.image);
        eprintln!(
            "{placement:?} {dispersion:?} terrain pass {terrain_pass} {splat:?} splat: eye depth max rel {eye:.1e}; \
             fixed-point sums identical {:.3} %; image total {total:.2e}, mean |Δ| / mean {mean_abs:.2e}, \
             channels differing > 0.1 %: {moved}",
            100.0 * same as f64 / cpu.acc.len() as f64,
        );
        // measured on lavapipe 25.0.7 (Mesa), the largest over the four cases: eye 2.3e-5, total 4.51e-6,
        // mean |Δ| / mean 7.49e-5; 10x.
        assert!(eye < 2.3e-4, "eye depth {eye}");
        // A photon that f32 and f64 put on different sides of a pixel edge (or of a footprint's
        // 1/64-pixel step) moves its weight to the neighbour: totals agree closely, single pixels
        // differ by whole photons (point splat) or by a few units of a share (footprint).
        assert!(total < 4.5e-5, "total {total}");
        assert!(mean_abs < 7.5e-4, "mean |Δ| {mean_abs}");
    }
}

/// `cargo test --release -p caustics-gpu --test cascaded_gpu -- --ignored --nocapture timings`:
/// per-pass GPU time (`GpuTimer`) and wall time (each pass submitted alone and waited for) and
/// memory, for docs/benchmarks.md. Medians over `frames` frames after one warm-up frame.
fn timings() {
    use caustics_gpu::cascaded::Pass;
    use std::collections::BTreeMap;
    let ctx = test_gpu();
    let cascaded = Cascaded::new(&ctx).unwrap();
    let scene = Scene::builtin("shore").unwrap();
    let water = cascaded::water_grid(&scene, 128).unwrap();
    let terrain = scene.floor.terrain.as_ref();
    let tex = ctx.upload_grid("water", &water).unwrap();
    let view = tex.create_view(&Default::default());
    println!("adapter: {}", ctx.describe());
    println!("screen {} x {}", scene.camera.width, scene.camera.height);
    // `CASCADED_RESOLUTIONS=512,1024` and `CASCADED_FRAMES=n` choose a subset (a 2048² frame with
    // the terrain pass takes about a minute on lavapipe).
    let list: Vec<u32> = std::env::var("CASCADED_RESOLUTIONS")
        .map(|v| v.split(',').filter_map(|r| r.trim().parse().ok()).collect())
        .unwrap_or_else(|_| vec![512, 1024, 2048]);
    let frames_wanted: Option<usize> = std::env::var("CASCADED_FRAMES")
        .ok()
        .and_then(|v| v.parse().ok());
    for (res, terrain_pass) in list.iter().flat_map(|&r| [(r, true), (r, false)]) {
        let frames = frames_wanted.unwrap_or(if res == 2048 { 1 } else { 5 });
        let params = CascadedParams {
            resolution: res,
            terrain_pass,
            ..Default::default()
        };
        println!("resolution {res}², terrain pass {terrain_pass}, {frames} frame(s)");
        let setup = CascadedSetup::from_scene(&scene, &params).unwrap();
        let frame = cascaded.frame(&ctx, &setup, &view, terrain).unwrap();
        let passes = Cascaded::passes(&setup);
        let mut timer = GpuTimer::new(&ctx, passes.len() as u32);
        let mut stamp: BTreeMap<String, Vec<f64>> = Default::default();
        let mut wall: BTreeMap<String, Vec<f64>> = Default::default();
        let mut whole = Vec::new();
        for f in 0..frames + 1 {
            for &pass in &passes {
                let t0 = std::time::Instant::now();
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                cascaded.encode_pass(&frame, &mut encoder, pass, &mut Some(&mut timer));
                ctx.queue.submit([encoder.finish()]);
                ctx.wait().unwrap();
                if f > 0 {
                    wall.entry(pass.label())
                        .or_default()
                        .push(t0.elapsed().as_secs_f64() * 1e3);
                }
            }
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            timer.resolve(&mut encoder);
            ctx.queue.submit([encoder.finish()]);
            for t in timer.read(&ctx).unwrap() {
                if f > 0 {
                    stamp.entry(t.label).or_default().push(t.ms);
                }
            }
            // The whole frame in one submission.
            let t0 = std::time::Instant::now();
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            cascaded.encode(&frame, &mut encoder, None);
            ctx.queue.submit([encoder.finish()]);
            ctx.wait().unwrap();
            if f > 0 {
                whole.push(t0.elapsed().as_secs_f64() * 1e3);
            }
        }
        let median = |v: &[f64]| {
            let mut v = v.to_vec();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let get = |m: &BTreeMap<String, Vec<f64>>, p: Pass| {
            m.get(&p.label()).map_or(f64::NAN, |v| median(v))
        };
        println!("| res | pass | GpuTimer ms | wall ms |");
        let (mut st, mut wt, mut st_t, mut wt_t) = (0.0, 0.0, 0.0, 0.0);
        for &pass in &passes {
            let (a, b) = (get(&stamp, pass), get(&wall, pass));
            st += a;
            wt += b;
            if matches!(pass, Pass::Terrain(_)) {
                st_t += a;
                wt_t += b;
            }
            println!("| {res} | {} | {a:.2} | {b:.1} |", pass.label());
        }
        for k in 0..CASCADES {
            let sum = |m: &BTreeMap<String, Vec<f64>>| {
                [Pass::Water(k), Pass::Terrain(k), Pass::Photons(k)]
                    .iter()
                    .map(|&p| get(m, p))
                    .filter(|t| t.is_finite())
                    .sum::<f64>()
            };
            println!(
                "| {res} | cascade {k} total | {:.2} | {:.1} | without terrain: {:.1} ms wall |",
                sum(&stamp),
                sum(&wall),
                sum(&wall) - get(&wall, Pass::Terrain(k)).max(0.0)
            );
        }
        println!(
            "| {res} | frame | {st:.2} (without terrain {:.2}) | {wt:.1} (without terrain {:.1}); one submission {:.1} | G-buffers {:.1} MiB (shared), per-cascade screen map {:.1} MiB, total {:.1} MiB |",
            st - st_t,
            wt - wt_t,
            median(&whole),
            frame.gbuffer_bytes as f64 / 1048576.0,
            frame.cascade_map_bytes as f64 / 1048576.0,
            frame.bytes() as f64 / 1048576.0
        );
    }
}

/// Through the `Technique` trait: the registry's `cascaded` on the pool at a small camera, the
/// heights the test's own (sampled at `water_resolution()`, uploaded by the test).
mod through_the_trait {
    use super::*;
    use caustics_core::grid::Grid;
    use caustics_core::water::sample_grid;
    use caustics_gpu::{GpuContext, Output, Technique, WaterTextures};

    const PARAMS: &str = "[cascaded]\nresolution = 64\n";
    /// 10x the agreement measured through the trait on the pool (see the tests).
    const TOTAL: f64 = 5.1e-5;
    const MEAN_ABS: f64 = 4.5e-4;

    fn pool() -> Scene {
        let mut s = Scene::builtin("pool").unwrap();
        s.camera.width = 64;
        s.camera.height = 36;
        s
    }

    fn params() -> toml::Table {
        toml::from_str(PARAMS).unwrap()
    }

    fn heights(t: &dyn Technique, scene: &Scene) -> Grid {
        let w = scene.water.as_ref().unwrap();
        let (cols, rows) = t.water_resolution(scene);
        let surface = w.surface_at(scene.time).unwrap();
        sample_grid(surface.as_ref(), cols as usize, rows as usize, w.size)
    }

    fn frame(ctx: &GpuContext, t: &dyn Technique) {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        t.encode(&mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
    }

    fn read_image(ctx: &GpuContext, t: &dyn Technique) -> Vec<[f32; 4]> {
        let Some(Output::EyeSpace(tex)) = t.output() else {
            panic!("cascaded makes an eye-space image");
        };
        ctx.read_texture(tex).unwrap()
    }

    fn cpu(scene: &Scene, water: &Grid) -> Vec<[f32; 4]> {
        let p = CascadedParams::from_table(&params()).unwrap();
        let setup = CascadedSetup::from_scene(scene, &p).unwrap();
        cascaded::caustics(&setup, water, scene.floor.terrain.as_ref()).image
    }

    pub fn cascaded_through_the_trait_matches_the_cpu_twin() {
        let ctx = test_gpu();
        let scene = pool();
        let mut t = caustics_gpu::registry::create(&ctx, "cascaded", &params()).unwrap();
        assert_eq!(t.water_resolution(&scene), (256, 256));
        let h = heights(t.as_ref(), &scene);
        let tex = ctx.upload_grid("test heights", &h).unwrap();
        t.configure(&ctx, &scene, &WaterTextures::of(&tex)).unwrap();
        t.update(&ctx, &scene).unwrap();
        frame(&ctx, t.as_ref());
        let gpu = read_image(&ctx, t.as_ref());
        assert_eq!(gpu.len(), 64 * 36, "the camera's size");
        let cpu = cpu(&scene, &h);
        let (total, mean_abs, moved) = agreement(&cpu, &gpu);
        let valued = gpu.iter().filter(|p| p[3] >= 0.0).count();
        eprintln!(
            "trait, pool: image total {total:.2e}, mean |Δ| / mean {mean_abs:.2e}, {moved} channels > 0.1 %, {valued} pixels with a value"
        );
        // No value is alpha -1 on both twins, the same pixels; no NaN.
        assert!(gpu.iter().all(|p| p.iter().all(|c| c.is_finite())));
        assert!(
            cpu.iter()
                .zip(&gpu)
                .all(|(a, b)| (a[3] < 0.0) == (b[3] < 0.0))
        );
        assert!(valued > 0);
        // The pool's walls are receivers: the camera sees the walls x = 4 and y = 4,
        // whose pixels both twins light alike.
        let p = CascadedParams::from_table(&params()).unwrap();
        let setup = CascadedSetup::from_scene(&scene, &p).unwrap();
        assert!(setup.walls);
        let eye = cascaded::eye_pass(&setup, None);
        let on_walls: Vec<usize> = (0..eye.len())
            .filter(|&k| {
                let (x, y) = ((k % 64) as f64 + 0.5, (k / 64) as f64 + 0.5);
                let q = setup.eye.position + setup.eye.ray(x, y) * eye[k][0] as f64;
                eye[k][3] != 0.0 && setup.receiver_normal(q).z == 0.0
            })
            .collect();
        let lit = on_walls.iter().filter(|&&k| gpu[k][1] > 0.0).count();
        eprintln!("{} wall pixels, {lit} lit on the GPU", on_walls.len());
        assert!(on_walls.len() > 100 && lit > 50, "{} {lit}", on_walls.len());
        // measured total 5.13e-6, mean |Δ| / mean 4.49e-5 on lavapipe 25.0.7 (Mesa); 10x.
        assert!(total < TOTAL && mean_abs < MEAN_ABS, "{total} {mean_abs}");
    }

    /// Ten frames of moving water, camera and sun after the first: uniform writes only, and the
    /// last frame's image is the CPU twin's for the last camera, sun and heights.
    pub fn cascaded_frames_create_and_read_nothing() {
        let ctx = test_gpu();
        let mut scene = pool();
        let mut t = caustics_gpu::registry::create(&ctx, "cascaded", &params()).unwrap();
        let h = heights(t.as_ref(), &scene);
        let tex = ctx.upload_grid("test heights", &h).unwrap();
        t.configure(&ctx, &scene, &WaterTextures::of(&tex)).unwrap();
        t.update(&ctx, &scene).unwrap();
        frame(&ctx, t.as_ref());
        ctx.wait().unwrap();
        let before = ctx.traffic();
        let mut h = h;
        let start = scene.camera.position;
        for f in 1..=10 {
            let f = f as f64;
            scene.time = 0.1 * f;
            scene.camera.position = start + glam::DVec3::new(0.03 * f, -0.02 * f, 0.01 * f);
            scene.light.direction = glam::DVec3::new(0.3 + 0.01 * f, 0.1, -1.0).normalize();
            h = heights(t.as_ref(), &scene);
            common::write_heights(&ctx, &tex, &h);
            t.update(&ctx, &scene).unwrap();
            frame(&ctx, t.as_ref());
        }
        ctx.wait().unwrap();
        let d = ctx.traffic().since(&before);
        eprintln!("ten cascaded frames: {d:?}");
        assert_eq!(d.created(), 0, "{d:?}");
        assert_eq!(d.readbacks, 0, "{d:?}");
        assert!(
            d.uploaded_bytes > 0 && d.uploaded_bytes <= 10 * 4096,
            "{d:?}"
        );
        let gpu = read_image(&ctx, t.as_ref());
        let (total, mean_abs, _) = agreement(&cpu(&scene, &h), &gpu);
        eprintln!("after ten frames: image total {total:.2e}, mean |Δ| / mean {mean_abs:.2e}");
        // measured total 1.72e-7, mean |Δ| / mean 4.44e-6 on lavapipe 25.0.7 (Mesa)
        assert!(total < 1.7e-6 && mean_abs < 4.4e-5, "{total} {mean_abs}");
    }
}

test_main! {
    cpu uniform_matches_its_wgsl_size,
    gpu gbuffers_match_the_cpu_twin,
    gpu screen_caustics_match_the_cpu_twin,
    gpu_ignored timings,
    gpu through_the_trait::cascaded_through_the_trait_matches_the_cpu_twin,
    gpu through_the_trait::cascaded_frames_create_and_read_nothing,
}
