//! Frame time of technique `volumes` on the built-in scene `objects` at the paper's 512 x 512 (floor
//! map and every object's textures 512 x 512, a 512 x 512 water lattice over the pool, and the
//! refracted view of §3.3 at 512 x 512) for 5, 10 and 50 reference planes: GPU timestamps per pass and the wall clock of the whole submission, median
//! of 5 frames after a warm-up; and the memory the representation takes against a volumetric texture
//! of the same resolution (the paper's claim, §4).
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p caustics-gpu --example volumes_bench`

use caustics_core::scene::Scene;
use caustics_core::techniques::volumes::view::ViewCamera;
use caustics_core::techniques::volumes::{VolumesInput, VolumesParams, VolumesSetup};
use caustics_gpu::timing::median_runs;
use caustics_gpu::volumes::{ViewOptions, Volumes};
use caustics_gpu::{GpuContext, GpuOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ctx = GpuContext::headless(&GpuOptions::default())?;
    let volumes = Volumes::new(&ctx)?;
    println!(
        "adapter: {}; caustics maps {:?}",
        ctx.describe(),
        volumes.map_format
    );
    let mut scene = Scene::builtin("objects")?;
    scene.caustics.width = 512;
    scene.caustics.height = 512;
    let input = VolumesInput::from_scene(&scene)?;
    let water = scene.water.as_ref().expect("the objects scene has water");
    let surface = water.surface_at(scene.time)?;
    let heights = caustics_core::water::sample_grid(surface.as_ref(), 512, 512, water.size);
    scene.camera.width = 512;
    scene.camera.height = 512;
    let view = ViewOptions {
        camera: ViewCamera::new(&scene.camera),
        floor_albedo: glam::DVec3::new(0.62, 0.78, 0.82),
    };
    println!("\n| planes | pass | GPU ms (median of 5) |\n|---|---|---|");
    let mut summary = Vec::new();
    for planes in [5u32, 10, 50] {
        let params = VolumesParams {
            planes,
            texture: 512,
            water_cells: 512,
            shadow: 512,
            ..Default::default()
        };
        let setup = VolumesSetup::new(&params, &input)?;
        let frame = volumes.frame(&ctx, &setup, &input, &heights, water.wrap, Some(&view))?;
        let m = median_runs(&ctx, 9, 5, |encoder, timer| {
            volumes.encode(&frame, encoder, Some(timer))
        })?;
        for (label, ms) in &m.passes {
            println!("| {planes} | {label} | {ms:.1} |");
        }
        let wall = m.wall_ms;
        println!("| {planes} | whole frame (wall clock) | {wall:.1} |");
        summary.push((planes, wall, frame.slice_triangles(), frame.bytes()));
    }
    println!(
        "\n| planes | slice triangles | frame ms | fps | GPU memory of the frame |\n|---|---|---|---|---|"
    );
    for (planes, wall, tris, bytes) in &summary {
        println!(
            "| {planes} | {tris} | {wall:.0} | {:.2} | {:.1} MiB |",
            1e3 / wall,
            *bytes as f64 / (1 << 20) as f64
        );
    }
    // The paper's comparison: per object one colour texture (RGBA8) and one depth texture (32 bits)
    // against a volumetric texture of one RGBA8 slice image per sampling plane (Iwasaki et al.).
    let texels = 512u64 * 512;
    let objects = input.objects.len() as u64;
    println!(
        "\n| planes | colour + depth textures (paper 3) | volumetric texture (slices) |\n|---|---|---|"
    );
    for planes in [5u64, 10, 50] {
        println!(
            "| {planes} | {:.1} MiB | {:.1} MiB |",
            (objects * texels * 8) as f64 / (1 << 20) as f64,
            (objects * texels * 4 * planes) as f64 / (1 << 20) as f64
        );
    }
    Ok(())
}
