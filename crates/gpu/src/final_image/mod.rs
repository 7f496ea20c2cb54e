//! The final image on the GPU: the scene from its camera with the water, its Fresnel reflection of
//! the sky, the refracted floor lit through a caustics map, and the objects. It is the GPU twin of
//! the CPU renderer `caustics_core::render` (`crates/core/src/render.rs`, where the light transport
//! is written down) and gives the same image up to f32 rounding; `tests/render_gpu.rs` holds the
//! two together.
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | final image (compute, one invocation per pixel) | `shaders/final_image.wgsl` | `render::render` and `Tracer` |
//! | (shared) sky, floor albedo, tone map | `shaders/shading.wgsl` | `Tracer::sky`, `tone_map`, `Albedo::at` |
//! | (shared) mesh ray queries | `shaders/bvh.wgsl` | `MeshBvh::intersect` |
//!
//! How the inputs reach the shader, and where they differ from what the CPU reads:
//! - The water surface is sampled on a square grid ([`water_grid`]) and read back with the shared
//!   bicubic `grid_sample` of `water.wgsl`. A procedural surface is therefore the grid's
//!   interpolant here; render on the CPU with [`water_grid`]'s surface for an exact comparison.
//!   The grid is uploaded with a border ([`bordered_grid`]) so that a periodic surface is wrapped
//!   once per sample rather than per tap.
//! - The terrain is an `R32Float` texture through the same `grid_sample`, clamped; the caustics
//!   map an `Rgba32Float` texture filtered by hand like `CausticsMap::sample`, or in its place an
//!   eye-space image (`cascaded`) read like `EyeSpaceCaustics::sample`; an albedo image an
//!   `Rgba32Float` texture read at the nearest texel like `Albedo::at`.
//! - Each object's `MeshBvh` (the very tree the CPU traverses) is flattened into two storage
//!   buffers shared by all objects (bind group 1, `bvh.wgsl`).
//! - The image is written tone-mapped and sRGB-encoded into an `Rgba8Unorm` storage texture with
//!   the CPU's rounding, and read back as [`caustics_core::render::Image`].
//!
//! WGSL has no recursion: the CPU's recursive trace (water surface, glass reflection and
//! refraction) becomes a loop over a small stack of weighted rays, with the CPU's depth limit; the
//! header of `final_image.wgsl` explains why the sum is the same. The whole image is one dispatch,
//! which a desktop GPU finishes in milliseconds; a driver with a watchdog and a very large,
//! heavily supersampled image would want it split into bands.

mod upload;

pub use upload::{
    FinalImageUniform, GpuBvhNode, GpuBvhTriangle, GpuObject, Meshes, WATER_BORDER, albedo,
    bordered_grid, flags, meshes, slab_half_height, water_grid, water_grid_resolution,
};

use caustics_core::map::CausticsMap;
use caustics_core::render::{Caustics, Image, RenderOptions};
use caustics_core::scene::{Albedo, Scene};
use caustics_core::water::Surface;

use crate::shaders::{OPTICS, PassSource, WATER};
use crate::{GpuContext, GpuError, GpuTimer};

/// The sky, the floor's albedo and the tone curve, for any pass that shows the scene.
pub const SHADING: &str = include_str!("../shaders/shading.wgsl");
/// Ray queries against the objects' trees (bind group 1).
pub const BVH: &str = include_str!("../shaders/bvh.wgsl");

pub const FINAL_IMAGE: PassSource = PassSource {
    name: "final image",
    shared: &[OPTICS, WATER, SHADING, BVH],
    source: include_str!("../shaders/final_image.wgsl"),
};

/// Pixels per workgroup side (`@workgroup_size(8, 8)`).
const TILE: u32 = 8;

/// The final-image pipeline, built once per device.
pub struct FinalImage {
    pipeline: wgpu::ComputePipeline,
    scene_layout: wgpu::BindGroupLayout,
    mesh_layout: wgpu::BindGroupLayout,
    /// Bound in place of a height field, terrain, caustics map or albedo image the scene lacks.
    empty_r32: wgpu::Texture,
    empty_rgba32: wgpu::Texture,
}

fn texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        // Read with textureLoad only, so 32-bit float textures need not be filterable.
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

fn storage_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn float_texture(
    ctx: &GpuContext,
    what: &str,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
    texels: &[u8],
) -> Result<wgpu::Texture, GpuError> {
    ctx.check_texture_size(what, width, height)?;
    let size = wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    };
    let texel = format
        .block_copy_size(None)
        .expect("an uncompressed format");
    debug_assert_eq!(texels.len(), (width * height * texel) as usize);
    Ok(ctx.create_texture_with_data(
        &wgpu::TextureDescriptor {
            label: Some(what),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        texels,
    ))
}

/// An RGB image as `Rgba32Float` texels (alpha 1).
fn rgba32(texels: &[[f32; 3]]) -> Vec<[f32; 4]> {
    texels.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect()
}

fn storage_buffer<T: bytemuck::Pod + Default>(
    ctx: &GpuContext,
    what: &str,
    items: &[T],
) -> Result<wgpu::Buffer, GpuError> {
    // A storage binding may not be empty: one zeroed element stands for none.
    let fallback = [T::default()];
    let items = if items.is_empty() {
        &fallback[..]
    } else {
        items
    };
    let bytes: &[u8] = bytemuck::cast_slice(items);
    ctx.check_buffer_size(what, bytes.len() as u64)?;
    Ok(ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(what),
        contents: bytes,
        usage: wgpu::BufferUsages::STORAGE,
    }))
}

impl FinalImage {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let device = &ctx.device;
        let scene_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("final image scene"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(
                            std::mem::size_of::<FinalImageUniform>() as u64,
                        ),
                    },
                    count: None,
                },
                texture_entry(1),
                texture_entry(2),
                texture_entry(3),
                texture_entry(4),
                storage_entry(5),
                wgpu::BindGroupLayoutEntry {
                    binding: 6,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: wgpu::TextureFormat::Rgba8Unorm,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let mesh_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene meshes"),
            entries: &[storage_entry(0), storage_entry(1)],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("final image"),
            bind_group_layouts: &[Some(&scene_layout), Some(&mesh_layout)],
            immediate_size: 0,
        });
        let pipeline = ctx.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(FINAL_IMAGE.name),
            layout: Some(&layout),
            module: &FINAL_IMAGE.module(device),
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let empty_r32 = float_texture(
            ctx,
            "no height field",
            wgpu::TextureFormat::R32Float,
            1,
            1,
            bytemuck::bytes_of(&0f32),
        )?;
        let empty_rgba32 = float_texture(
            ctx,
            "no map",
            wgpu::TextureFormat::Rgba32Float,
            1,
            1,
            bytemuck::bytes_of(&[1f32; 4]),
        )?;
        ctx.check()?;
        Ok(FinalImage {
            pipeline,
            scene_layout,
            mesh_layout,
            empty_r32,
            empty_rgba32,
        })
    }

    /// Whether the adapter is a software one (lavapipe, WARP): the pass then runs on the same CPU
    /// cores as `caustics_core::render::render` and, measured on lavapipe, about twice as slowly,
    /// since the CPU renderer needs no texture fetches and no SIMD lanes wait on each other.
    pub fn software_adapter(ctx: &GpuContext) -> bool {
        ctx.info.device_type == wgpu::DeviceType::Cpu
    }

    /// Render `scene` from its camera: the GPU counterpart of `caustics_core::render::render`, with
    /// the same arguments (no progress: the image is one dispatch). `surface` is sampled on
    /// [`water_grid`]'s lattice; `caustics` is the floor's map (none: lit as if the water were
    /// flat). With a `timer`, the pass is timed as "final image" and the timestamps resolved; read
    /// them with [`GpuTimer::read`].
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        surface: Option<&dyn Surface>,
        caustics: Option<&CausticsMap>,
        options: &RenderOptions,
        timer: Option<&mut GpuTimer>,
    ) -> Result<Image, GpuError> {
        self.render_with(
            ctx,
            scene,
            surface,
            caustics.map(Caustics::Floor),
            options,
            timer,
        )
    }

    /// [`render`](Self::render) with the caustics from either source, the GPU counterpart of
    /// `caustics_core::render::render_with`: a floor map, or an eye-space image made for the
    /// scene's camera (`cascaded`), read at the pixel each floor point projects to.
    pub fn render_with(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        surface: Option<&dyn Surface>,
        caustics: Option<Caustics>,
        options: &RenderOptions,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<Image, GpuError> {
        let device = &ctx.device;
        let (width, height) = (scene.camera.width, scene.camera.height);
        ctx.check_texture_size("final image", width, height)?;

        let grid = surface.and_then(|s| water_grid(scene, s));
        let h_max = match (&grid, &scene.water) {
            (Some(g), Some(w)) => slab_half_height(g, w.size),
            _ => 0.0,
        };
        let meshes = meshes(scene);
        let params = upload::uniform(
            scene,
            grid.is_some(),
            h_max,
            caustics,
            options,
            meshes.objects.len() as u32,
        );

        let water_height = match &grid {
            Some(g) => {
                Some(ctx.upload_grid("water height field", &bordered_grid(&g.grid, g.edge))?)
            }
            None => None,
        };
        let terrain = match &scene.floor.terrain {
            Some(t) => Some(ctx.upload_grid("terrain height field", t)?),
            None => None,
        };
        let map = match caustics {
            Some(Caustics::Floor(m)) => Some(float_texture(
                ctx,
                "caustics map",
                wgpu::TextureFormat::Rgba32Float,
                m.width as u32,
                m.height as u32,
                bytemuck::cast_slice(&rgba32(&m.texels)),
            )?),
            Some(Caustics::EyeSpace(e)) => Some(float_texture(
                ctx,
                "eye-space caustics",
                wgpu::TextureFormat::Rgba32Float,
                e.width as u32,
                e.height as u32,
                bytemuck::cast_slice(&e.texels),
            )?),
            None => None,
        };
        let albedo_image = match &scene.floor.albedo {
            Albedo::Image {
                width,
                height,
                texels,
            } => Some(float_texture(
                ctx,
                "floor albedo image",
                wgpu::TextureFormat::Rgba32Float,
                *width as u32,
                *height as u32,
                bytemuck::cast_slice(&rgba32(texels)),
            )?),
            Albedo::Pattern(_) => None,
        };
        let objects = storage_buffer(ctx, "scene objects", &meshes.objects)?;
        let nodes = storage_buffer(ctx, "object BVH nodes", &meshes.nodes)?;
        let triangles = storage_buffer(ctx, "object BVH triangles", &meshes.triangles)?;
        let uniform = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("final image uniform"),
            contents: bytemuck::bytes_of(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let output = ctx.create_texture(&wgpu::TextureDescriptor {
            label: Some("final image"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });

        let view = |t: Option<&wgpu::Texture>, empty: &wgpu::Texture| {
            t.unwrap_or(empty).create_view(&Default::default())
        };
        let views = [
            view(water_height.as_ref(), &self.empty_r32),
            view(terrain.as_ref(), &self.empty_r32),
            view(map.as_ref(), &self.empty_rgba32),
            view(albedo_image.as_ref(), &self.empty_rgba32),
        ];
        let output_view = output.create_view(&Default::default());
        let scene_group = ctx.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("final image scene"),
            layout: &self.scene_layout,
            entries: &[
                entry(0, uniform.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(&views[0])),
                entry(2, wgpu::BindingResource::TextureView(&views[1])),
                entry(3, wgpu::BindingResource::TextureView(&views[2])),
                entry(4, wgpu::BindingResource::TextureView(&views[3])),
                entry(5, objects.as_entire_binding()),
                entry(6, wgpu::BindingResource::TextureView(&output_view)),
            ],
        });
        let mesh_group = ctx.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene meshes"),
            layout: &self.mesh_layout,
            entries: &[
                entry(0, nodes.as_entire_binding()),
                entry(1, triangles.as_entire_binding()),
            ],
        });

        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("final image"),
        });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("final image"),
                timestamp_writes: timer.as_mut().and_then(|t| t.compute_pass("final image")),
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &scene_group, &[]);
            pass.set_bind_group(1, &mesh_group, &[]);
            pass.dispatch_workgroups(width.div_ceil(TILE), height.div_ceil(TILE), 1);
        }
        if let Some(t) = &timer {
            t.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        let texels: Vec<[u8; 4]> = ctx.read_texture(&output)?;
        Ok(Image {
            width,
            height,
            rgb: texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}

fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}
