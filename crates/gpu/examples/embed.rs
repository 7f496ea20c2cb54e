//! Caustics inside your own wgpu application. The application owns the device, the command
//! encoder, its water (here a compute shader of its own writing an `R32Float` height texture every
//! frame) and its render pass; any technique of the registry, named on the command line, reads that
//! texture and writes its caustics into a texture the application's pass samples. Nothing is read
//! back inside the loop: the example checks it with the GPU crate's traffic counters, then saves
//! the last frame once, as a picture.
//!
//! ```sh
//! cargo run --release -p caustics-gpu --example embed -- yuksel-targets out.png
//! cargo run --release -p caustics-gpu --example embed -- caustic-triangles:photon_image=256
//! ```

use caustics_core::scene::Scene;
use caustics_gpu::registry;
use caustics_gpu::{GpuContext, Output, WaterTextures};

/// The application's water: a few travelling sine waves, height in metres, written per texel.
const WATER: &str = r#"
struct Clock { time: f32, size: f32, _pad: vec2<f32> }
@group(0) @binding(0) var<uniform> clock: Clock;
@group(0) @binding(1) var heights: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(heights);
    if (id.x >= dims.x || id.y >= dims.y) { return; }
    let p = (vec2<f32>(id.xy) + 0.5) / vec2<f32>(dims) * clock.size;
    let tau = 6.2831853;
    // Wave numbers of whole periods over the square, so the surface tiles.
    // Wavelengths of 0.49 and 0.41 m on the 4 m pool, curved (A k² about 1 per metre) enough to
    // focus the sun a few metres down: soft, moving bands on a 1 m deep floor.
    let k1 = tau / clock.size * vec2<f32>(8.0, 2.0);
    let k2 = tau / clock.size * vec2<f32>(-4.0, 9.0);
    let h = 0.006 * sin(dot(k1, p) - 5.6 * clock.time)
          + 0.004 * sin(dot(k2, p) - 6.1 * clock.time + 1.0);
    textureStore(heights, vec2<i32>(id.xy), vec4<f32>(h, 0.0, 0.0, 0.0));
}
"#;

/// The application's own pass: the caustics texture drawn as a warm floor, full screen.
const SHOW: &str = r#"
@group(0) @binding(0) var caustics: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

fn shade(e: vec3<f32>) -> vec4<f32> {
    let lit = vec3<f32>(0.76, 0.66, 0.50) * e;
    return vec4<f32>(1.4 * lit / (1.0 + lit), 1.0);
}

fn texel(frag: vec4<f32>) -> vec4<f32> {
    let dims = vec2<f32>(textureDimensions(caustics));
    return textureLoad(caustics, vec2<i32>(frag.xy / 512.0 * dims), 0);
}

// A floor map: relative irradiance everywhere.
@fragment
fn fs_floor(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return shade(texel(frag).rgb);
}

// An eye-space image: alpha < 0 where the pixel sees no lit floor.
@fragment
fn fs_eye(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let e = texel(frag);
    return shade(select(vec3<f32>(0.2), e.rgb, e.a >= 0.0));
}
"#;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let spec = args.next().unwrap_or_else(|| "yuksel".to_string());
    let out = args.next();

    // 1. The application's device, made however it makes it; the GPU crate wraps it.
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("my engine"),
        required_features: adapter.features()
            & (wgpu::Features::FLOAT32_BLENDABLE | wgpu::Features::FLOAT32_FILTERABLE),
        required_limits: adapter.limits(),
        ..Default::default()
    }))?;
    let ctx = GpuContext::from_parts(instance, adapter, device, queue);
    let device = &ctx.device;

    // 2. The application's water texture and the pass that writes it.
    let n = 256;
    let heights = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("my water"),
        size: wgpu::Extent3d {
            width: n,
            height: n,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::R32Float,
        usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
        view_formats: &[],
    });
    let clock = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("my clock"),
        size: 16,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let water_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("my water"),
        source: wgpu::ShaderSource::Wgsl(WATER.into()),
    });
    let water_pass = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("my water"),
        layout: None,
        module: &water_module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let water_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("my water"),
        layout: &water_pass.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: clock.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(
                    &heights.create_view(&Default::default()),
                ),
            },
        ],
    });

    // 3. The scene the technique lights: the built-in pool's optics and sun, a 256² map.
    let mut scene = Scene::builtin("pool")?;
    scene.caustics.width = 256;
    scene.caustics.height = 256;
    let size = scene.water.as_ref().map_or(1.0, |w| w.size) as f32;

    // 4. The technique, by name: pipelines once, its frame configured on our water texture.
    let mut technique = registry::from_spec(&ctx, &spec)?;
    technique.configure(&ctx, &scene, &WaterTextures::of(&heights))?;
    let output = technique.output().expect("configured");
    let caustics = output.texture().clone();
    let fragment = match output {
        Output::Floor(_) => "fs_floor",
        Output::EyeSpace(_) => "fs_eye",
    };

    // 5. The application's pass that samples the caustics, into its own target.
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("my frame"),
        size: wgpu::Extent3d {
            width: 512,
            height: 512,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let target_view = target.create_view(&Default::default());
    let show_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("my floor"),
        source: wgpu::ShaderSource::Wgsl(SHOW.into()),
    });
    let show = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("my floor"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &show_module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &show_module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
        }),
        multiview_mask: None,
        cache: None,
    });
    let show_bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("my floor"),
        layout: &show.get_bind_group_layout(0),
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::TextureView(
                &caustics.create_view(&Default::default()),
            ),
        }],
    });

    // 6. The frame loop: our water, the technique, our pass, one encoder, one submission.
    let frames = 30;
    let mut steady = None;
    for frame in 0..frames {
        if frame == 2 {
            steady = Some(ctx.traffic());
        }
        let t = frame as f32 / 30.0;
        ctx.queue
            .write_buffer(&clock, 0, bytemuck::cast_slice(&[t, size, 0.0, 0.0]));
        // The sun swings slowly across the sky: a uniform write inside the technique.
        let a = 0.3 * t;
        scene.light.direction = glam::DVec3::new(0.3 * a.cos() as f64, 0.2, -1.0).normalize();
        technique.update(&ctx, &scene)?;
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&water_pass);
            pass.set_bind_group(0, &water_bind, &[]);
            pass.dispatch_workgroups(n.div_ceil(8), n.div_ceil(8), 1);
        }
        technique.encode(&mut encoder, None);
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("my floor"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations::default(),
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&show);
            pass.set_bind_group(0, &show_bind, &[]);
            pass.draw(0..3, 0..1);
        }
        ctx.queue.submit([encoder.finish()]);
    }
    ctx.wait()?;
    let d = ctx.traffic().since(&steady.expect("frames > 2"));
    println!(
        "{}: {} steady frames, the caustics crate created {} resources, uploaded {} bytes, read back {} times; {} kB of GPU memory",
        technique.name(),
        frames - 2,
        d.created(),
        d.uploaded_bytes,
        d.readbacks,
        technique.bytes() / 1024
    );
    if let Some(out) = out {
        // Once, after the loop: the application's frame as a picture.
        let texels: Vec<[u8; 4]> = ctx.read_texture(&target)?;
        let rgb: Vec<u8> = texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect();
        image::save_buffer(&out, &rgb, 512, 512, image::ExtendedColorType::Rgb8)?;
        println!("wrote {out}");
    }
    Ok(())
}
