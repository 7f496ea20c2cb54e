//! Technique `caustic-triangles` to the end: photon tracing, reconstruction (the light cube map of
//! a point light, or the floor map of the sun), and the camera pass (paper 4, §4.3), on the GPU; the
//! picture of a scene, and with `--bench` the wall-clock time of whole frames at the paper's sizes
//! (128 x 128 photon image, 6 x 512 x 512 light cube map) and larger.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p caustics-gpu --example caustic_triangles_camera --
//! docs/scenes/glass-lamp.toml docs/images/glass-lamp-caustic-triangles.png [--bench]`

use caustics_core::scene::Scene;
use caustics_core::techniques::caustic_triangles::CausticTrianglesParams;
use caustics_core::techniques::caustic_triangles::camera::{self, CameraParams};
use caustics_gpu::caustic_triangles::CausticTriangles;
use caustics_gpu::caustic_triangles::camera::CameraRenderer;
use caustics_gpu::{GpuContext, GpuOptions, GpuTimer};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene_arg = args.first().map_or("glass", |s| s.as_str());
    let out = args
        .get(1)
        .map_or("caustic-triangles-camera.png", |s| s.as_str());
    let bench = args.iter().any(|a| a == "--bench");
    let scene = Scene::load_or_builtin(scene_arg)?;
    let ctx = GpuContext::headless(&GpuOptions::default())?;
    let ct = CausticTriangles::new(&ctx)?;
    let renderer = CameraRenderer::new(&ctx)?;
    let cp = CameraParams::from_scene(&scene);
    println!("adapter: {}", ctx.describe());
    let params = CausticTrianglesParams::from_table(&scene.caustics.params)?;
    let gens = camera::generators(&scene, &params)?;
    let pairs: Vec<_> = gens.iter().map(|g| (&g.setup, &g.dm)).collect();
    let t0 = std::time::Instant::now();
    let image = renderer.render(&ctx, &ct, &pairs, &scene.camera, &cp, None)?;
    println!(
        "{} x {} in {:.2} s",
        image.width,
        image.height,
        t0.elapsed().as_secs_f64()
    );
    caustics_core::render::write_png(
        std::path::Path::new(out),
        image.width,
        image.height,
        &image.rgb,
        scene.look.exposure,
        scene.look.tone_map,
    )?;
    println!("wrote {out}");
    if !bench {
        return Ok(());
    }
    let light = if scene.light.is_sun() {
        "sun"
    } else {
        "point light"
    };
    println!(
        "\n| photon image | distance map | light cube | image | light | pass | GPU ms | frame wall ms |\n|---|---|---|---|---|---|---|---|"
    );
    for (p, light_cube, (w, h)) in [
        (128u32, 512u32, (640u32, 360u32)),
        (256, 512, (640, 360)),
        (256, 1024, (960, 540)),
    ] {
        let params = CausticTrianglesParams {
            photon_image: p,
            light_cube,
            ..params.clone()
        };
        let gens = camera::generators(&scene, &params)?;
        let pairs: Vec<_> = gens.iter().map(|g| (&g.setup, &g.dm)).collect();
        // The same frame with a 1 x 1 image is the technique without its camera pass: on a
        // software adapter the compute timestamps do not bracket the work, so the wall clocks of
        // the two give the camera pass's share.
        let mut medians = Vec::new();
        let mut passes: Vec<Vec<(String, f64)>> = Vec::new();
        for (cw, ch) in [(w, h), (1, 1)] {
            let mut cam = scene.camera.clone();
            cam.width = cw;
            cam.height = ch;
            let mut walls = Vec::new();
            for run in 0..4 {
                let mut timer = GpuTimer::new(&ctx, 64);
                let t0 = std::time::Instant::now();
                renderer.render(&ctx, &ct, &pairs, &cam, &cp, Some(&mut timer))?;
                let wall = t0.elapsed().as_secs_f64() * 1e3;
                let times = timer.read(&ctx)?;
                if run > 0 {
                    walls.push(wall);
                    if cw > 1 {
                        passes.push(times.into_iter().map(|t| (t.label, t.ms)).collect());
                    }
                }
            }
            walls.sort_by(f64::total_cmp);
            medians.push(walls[walls.len() / 2]);
        }
        let size = format!("{p}x{p}");
        let dm = format!("6x{}x{}", params.cube_resolution, params.cube_resolution);
        let lc = format!("6x{light_cube}x{light_cube}");
        let img = format!("{w}x{h}");
        // Per pass label: the median over runs of its summed time in a run (one per generator).
        let mut labels: Vec<String> = passes[0].iter().map(|(l, _)| l.clone()).collect();
        labels.sort();
        labels.dedup();
        for label in labels {
            let mut v: Vec<f64> = passes
                .iter()
                .map(|run| {
                    run.iter()
                        .filter(|(l, _)| *l == label)
                        .map(|(_, t)| t)
                        .sum()
                })
                .collect();
            v.sort_by(f64::total_cmp);
            println!(
                "| {size} | {dm} | {lc} | {img} | {light} | {label} | {:.2} | |",
                v[v.len() / 2]
            );
        }
        println!(
            "| {size} | {dm} | {lc} | {img} | {light} | whole frame ({} generators, median of 3) | | {:.0} |",
            pairs.len(),
            medians[0]
        );
        println!(
            "| {size} | {dm} | {lc} | {img} | {light} | without the camera pass (1 x 1 image) | | {:.0} |",
            medians[1]
        );
    }
    Ok(())
}
