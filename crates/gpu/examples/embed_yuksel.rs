//! Using a technique inside your own wgpu application: your instance, adapter, device and queue,
//! your command encoder; the technique records its passes into it and leaves the caustics map in a
//! texture your shaders sample (`Rgba32Float`, relative irradiance, 1 = flat water).
//!
//! `cargo run --release -p caustics-gpu --example embed_yuksel`

use caustics_core::techniques::yuksel::{YukselParams, YukselSetup};
use caustics_core::water::sample_grid;
use caustics_core::water::waves::{Wave, Waves};
use caustics_gpu::yuksel::{Variant, Yuksel};
use caustics_gpu::{GpuContext, GpuTimer};
use glam::DVec3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // 1. The application's own device, made however the application makes it.
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("my engine"),
        required_features: adapter.features() & wgpu::Features::TIMESTAMP_QUERY,
        required_limits: adapter.limits(),
        ..Default::default()
    }))?;
    let ctx = GpuContext::from_parts(instance, adapter, device, queue);

    // 2. The technique's pipelines, once; a frame's textures and bind groups, once per size.
    let yuksel = Yuksel::new(&ctx)?;
    let (size, depth) = (4.0, 1.0);
    let setup = YukselSetup::new(
        &YukselParams {
            n: 21,
            m: 20,
            ..Default::default()
        },
        512,
        512,
        size,
        depth,
        1.333,
        DVec3::new(0.45, 0.09, 0.05),
        true,
        DVec3::new(0.3, 0.1, -1.0).normalize(),
    )?;
    let wave = |a, l, d: [f64; 2]| Wave {
        amplitude: a,
        wavelength: l,
        direction: d,
        phase: 0.0,
    };
    let mut frame: Option<caustics_gpu::yuksel::Frame> = None;
    let mut timer = GpuTimer::new(&ctx, 8);
    for step in 0..4 {
        // 3. Every frame: new heights (here sampled on the CPU; `Frame::update_heights`), then the
        //    passes recorded into the application's encoder, before its own passes that sample
        //    `frame.map`.
        let t = step as f64 / 30.0;
        let waves = Waves::new(
            &[
                wave(0.004, 0.5, [1.0, 0.25]),
                wave(0.003, 0.36, [-0.4, 1.0]),
            ],
            size,
            t,
        );
        let heights = sample_grid(&waves, 256, 256, size);
        let f = match &frame {
            Some(f) => {
                f.update_heights(&ctx, &heights);
                f
            }
            None => frame.insert(yuksel.frame(&ctx, &setup, &heights, Variant::RenderTargets)?),
        };
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let map: &wgpu::Texture = yuksel.encode(f, &mut encoder, Some(&mut timer));
        // ... the application's own passes that bind `map` go here ...
        timer.resolve(&mut encoder);
        ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        let passes = timer.read(&ctx)?;
        let texels: Vec<[f32; 4]> = ctx.read_texture(map)?;
        let mean = texels.iter().map(|t| t[1] as f64).sum::<f64>() / texels.len() as f64;
        let max = texels.iter().map(|t| t[1]).fold(0.0f32, f32::max);
        println!(
            "t = {t:.3} s: map mean {mean:.3}, max {max:.2}; GPU {}",
            passes
                .iter()
                .map(|p| format!("{} {:.3} ms", p.label, p.ms))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    Ok(())
}
