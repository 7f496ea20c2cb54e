//! The shortest way in: caustics from your own height texture on your own floor. Your device, your
//! water (an `R32Float` texture of heights in metres), your render pass; the caustics crate adds one
//! technique, named by its spec string, between them.
//!
//! ```sh
//! cargo run --release -p caustics-gpu --example minimal -- yuksel:n=15 floor.png
//! ```

use caustics_gpu::core::scene::WaterOnly;
use caustics_gpu::wgpu::{self, util::DeviceExt};
use caustics_gpu::{GpuContext, WaterTextures, registry};

/// Your floor: sand lit by the caustics map (relative irradiance, 1 under flat water).
const FLOOR: &str = r#"
@group(0) @binding(0) var caustics: texture_2d<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u)) * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(0.4 * vec3<f32>(0.9, 0.8, 0.6) * textureLoad(caustics, vec2<i32>(p.xy), 0).rgb, 1.0);
}"#;

/// The floor, `n` x `n` pixels of `Rgba8Unorm`, lit by technique `spec` under two sine waves.
pub fn floor(spec: &str, n: u32) -> Result<Vec<[u8; 4]>, Box<dyn std::error::Error>> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        required_limits: adapter.limits(),
        ..Default::default()
    }))?;
    // Your water: heights in metres, here two sine waves over the 4 m square, written once.
    let k = std::f32::consts::TAU / n as f32;
    let heights: Vec<f32> = (0..n * n)
        .map(|i| ((i % n) as f32, (i / n) as f32))
        .map(|(x, y)| 0.006 * (8.0 * k * x).sin() + 0.004 * (k * (-4.0 * x + 9.0 * y)).sin())
        .collect();
    let texture = |label, format, usage| wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: n,
            height: n,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    };
    let water = device.create_texture_with_data(
        &queue,
        &texture(
            "my water",
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::TEXTURE_BINDING,
        ),
        Default::default(),
        bytemuck::cast_slice(&heights),
    );
    let target = device.create_texture(&texture(
        "my floor",
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    ));
    // The caustics: the scene is the water alone (4 m square, 1 m deep), the technique a spec.
    let ctx = GpuContext::shared(instance, adapter, device, queue);
    let scene = WaterOnly::new(4.0, 1.0).map(n).scene()?;
    let mut technique = registry::from_spec(&ctx, spec)?;
    technique.configure(&ctx, &scene, &WaterTextures::of(&water))?;
    let map = technique
        .output()
        .ok_or("configured")?
        .texture()
        .create_view(&Default::default());
    // Your pass reads the map as any texture.
    let module = ctx
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("my floor"),
            source: wgpu::ShaderSource::Wgsl(FLOOR.into()),
        });
    let pipeline = ctx
        .device
        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("my floor"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: None,
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: None,
                compilation_options: Default::default(),
                targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
    let bind = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("my floor"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::TextureView(&map),
        }],
    });
    // One frame: the technique's uniforms (sun, camera) brought up to date, its passes, then
    // yours, in your encoder.
    technique.update(&ctx, &scene)?;
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    technique.encode(&mut encoder, None);
    let view = target.create_view(&Default::default());
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: &view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations::default(),
        })],
        ..Default::default()
    });
    pass.set_pipeline(&pipeline);
    pass.set_bind_group(0, &bind, &[]);
    pass.draw(0..3, 0..1);
    drop(pass);
    ctx.queue.submit([encoder.finish()]);
    Ok(ctx.read_texture(&target)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let spec = args.next().unwrap_or_else(|| "yuksel".into());
    let pixels = floor(&spec, 256)?;
    let red = pixels.iter().map(|p| p[0] as f64).collect::<Vec<_>>();
    let mean = red.iter().sum::<f64>() / red.len() as f64;
    let brightest = red.iter().cloned().fold(0.0, f64::max);
    println!("{spec}: the floor's red channel averages {mean:.1}, its brightest pixel {brightest}");
    if let Some(out) = args.next() {
        let rgb: Vec<u8> = pixels.iter().flat_map(|p| [p[0], p[1], p[2]]).collect();
        image::save_buffer(&out, &rgb, 256, 256, image::ExtendedColorType::Rgb8)?;
        println!("wrote {out}");
    }
    Ok(())
}
