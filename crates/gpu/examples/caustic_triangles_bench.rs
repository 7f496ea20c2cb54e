//! GPU timestamps per pass of technique `caustic-triangles` (median of 7 frames after a warm-up) at
//! the paper's sizes (128 x 128 photon image, 6 x 512 x 512 cube map) and larger, on the `glass`
//! scene's sphere with its sun, into a 512 x 512 floor map.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p caustics-gpu --example caustic_triangles_bench`

use caustics_core::techniques::caustic_triangles::{
    CausticTrianglesParams, CausticTrianglesSetup, DistanceMap, FloorWindow, GlassScene, Shape,
};
use caustics_gpu::caustic_triangles::{CausticTriangles, Reconstruction};
use caustics_gpu::timing::median_runs;
use caustics_gpu::{GpuContext, GpuOptions};
use glam::{DVec2, DVec3};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ctx = GpuContext::headless(&GpuOptions::default())?;
    let ct = CausticTriangles::new(&ctx)?;
    println!("adapter: {}; floor map {:?}", ctx.describe(), ct.map_format);
    let centre = DVec3::new(0.35, 0.5, 0.12);
    let light = DVec3::new(0.45, 0.3, -0.8).normalize();
    let foot = centre.truncate() + light.truncate() * (centre.z / -light.z);
    let scene = GlassScene::new(
        Shape::Sphere {
            centre,
            radius: 0.12,
        },
        1.5,
        light,
        FloorWindow {
            origin: foot - DVec2::splat(0.3),
            size: 0.6,
            width: 512,
            height: 512,
        },
        vec![],
    )?;
    println!("| photon image | cube map | pass | GPU ms (median of 7) |\n|---|---|---|---|");
    for (p, cube) in [(128u32, 512u32), (256, 512), (512, 512)] {
        let dm = DistanceMap::build(&scene, cube as usize, 2);
        let params = CausticTrianglesParams {
            photon_image: p,
            cube_resolution: cube,
            layers: 2,
            ..Default::default()
        };
        let setup = CausticTrianglesSetup::new(&params, &scene)?;
        let frame = ct.frame(&ctx, &setup, &dm)?;
        for rec in [Reconstruction::Triangles, Reconstruction::Splats] {
            let m = median_runs(&ctx, 4, 7, |encoder, timer| {
                ct.encode(&frame, encoder, Some(timer), rec)
            })?;
            for (label, ms) in &m.passes {
                println!("| {p}x{p} | 6x{cube}x{cube} | {label} | {ms:.2} |");
            }
            println!(
                "| {p}x{p} | 6x{cube}x{cube} | whole submission {rec:?} (wall clock) | {:.2} |",
                m.wall_ms
            );
        }
    }
    Ok(())
}
