//! Technique `caustic-triangles` with the water surface as the generator, on the `pool` scene
//! (512 x 512 map, its waves, sun and absorption): relative L1 against the reference (4 cells per
//! texel) of the caustic triangles and of the splatting baseline at photon images 64 to 512, and the
//! GPU time per pass (median of 7 frames after a warm-up) with the wall clock of the submission.
//! The tables of docs/caustic-triangles.md ("The water surface as the generator").
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p caustics-gpu --example caustic_triangles_water`

use caustics_core::metrics::compare;
use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::scene::Scene;
use caustics_core::techniques::caustic_triangles::CausticTrianglesParams;
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_gpu::caustic_triangles::{CausticTriangles, Reconstruction};
use caustics_gpu::timing::median_runs;
use caustics_gpu::{GpuContext, GpuOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ctx = GpuContext::headless(&GpuOptions::default())?;
    let ct = CausticTriangles::new(&ctx)?;
    println!("adapter: {}; floor map {:?}", ctx.describe(), ct.map_format);
    let scene = Scene::builtin("pool")?;
    let w = scene.water.as_ref().expect("the pool has water");
    let surface = w.surface_at(scene.time)?;
    let (res, light) = (512usize, scene.light.direction);
    let t0 = std::time::Instant::now();
    let r = reference(
        &ReferenceInput::from_scene(&scene, surface.as_ref())?,
        &ReferenceOptions::default(),
        &|_, _| {},
    )?;
    println!(
        "reference {res}² in {:.2} s (CPU)",
        t0.elapsed().as_secs_f64()
    );
    let heights = caustics_core::techniques::heights_for(w, surface.as_ref(), res, res);
    let sizes = [64u32, 128, 256, 512];
    println!("\n| photon image | triangles L1 | triangles flux | splats L1 | splats flux |");
    println!("|---|---|---|---|---|");
    for p in sizes {
        let params = CausticTrianglesParams {
            photon_image: p,
            ..Default::default()
        };
        let ws = WaterSetup::new(&params, w, light, res, res)?;
        let tri = ct.run_water(&ctx, &ws, &heights, Reconstruction::Triangles)?;
        let spl = ct.run_water(&ctx, &ws, &heights, Reconstruction::Splats)?;
        let (a, b) = (compare(&tri.map, &r), compare(&spl.map, &r));
        println!(
            "| {p}² (+1) | {:.3} | {:+.2} % | {:.3} | {:+.2} % |",
            a.relative_l1,
            100.0 * a.flux_error,
            b.relative_l1,
            100.0 * b.flux_error
        );
    }
    println!("\n| photon image | pass | GPU ms (median of 7) |\n|---|---|---|");
    for p in sizes {
        let params = CausticTrianglesParams {
            photon_image: p,
            ..Default::default()
        };
        let ws = WaterSetup::new(&params, w, light, res, res)?;
        let wf = ct.water_frame(&ctx, &ws, &heights)?;
        for rec in [Reconstruction::Triangles, Reconstruction::Splats] {
            let m = median_runs(&ctx, 4, 7, |encoder, timer| {
                ct.encode_water(&wf, encoder, Some(timer), rec)
            })?;
            for (label, ms) in &m.passes {
                println!("| {p}² | {label} | {ms:.2} |");
            }
            println!(
                "| {p}² | whole submission {rec:?} (wall clock) | {:.2} |",
                m.wall_ms
            );
        }
    }
    Ok(())
}
