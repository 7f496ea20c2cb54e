//! The final image on the GPU: the scene from its camera with the water, its Fresnel reflection of
//! the sky, the refracted floor lit through a caustics map, and the objects. It is the GPU twin of
//! the CPU renderer `caustics_core::render` (`crates/core/src/render.rs`, where the light transport
//! is written down) and gives the same image up to f32 rounding; `tests/render_gpu.rs` holds the
//! two together.
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | the water's heights in Hermite form (compute, one invocation per texel) | `water/water_patches.wgsl` ([`crate::water::patches`]) | (the grid's bicubic sample) |
//! | water slab bounds (compute, 128² samples) | `final_image/final_image_slab.wgsl` | [`slab_bounds`]: the slab's half height and the slope bound of the march |
//! | the floor map's pyramid (compute, one dispatch a level, in the image's pass) | `map_mips.wgsl` | `CausticsMap::pyramid` |
//! | the water's slope moments' pyramid (compute, one dispatch a level, in the image's pass, when the normals are filtered) | `final_image/water_slopes_base.wgsl`, `final_image/water_slopes_halve.wgsl` ([`slopes`]) | `SlopePyramid::new` |
//! | final image (compute, one invocation per pixel) | `final_image/final_image.wgsl` | `render::render` and `Tracer` |
//! | (shared) sky, floor albedo, tone map | `shaders/shading.wgsl` | `Tracer::sky`, `tone_map`, `Albedo::filtered` |
//! | (shared) mesh ray queries | `shaders/bvh.wgsl` | `MeshBvh::intersect` |
//!
//! The image is a [`FinalImageFrame`]: built once per scene and image size (the objects' trees, the
//! terrain and albedo textures, the output texture, the bind groups), then per frame one uniform
//! write ([`FinalImageFrame::update`]) and three passes recorded into the caller's encoder
//! ([`FinalImageFrame::encode`]). Nothing is created or read back per frame; the one exception is
//! the first update whose options filter the water's normals, which makes their pyramid, once.
//!
//! How the inputs reach the shader, and where they differ from what the CPU reads:
//! - The water is the heights texture the techniques read ([`crate::WaterTextures`]), through the
//!   bicubic of `water.wgsl` with the water's edge rule per tap, as the CPU's `Grid::sample`: in
//!   Hermite form (`grid_sample_hermite`, from the texels' central differences written once a
//!   frame), which reads 4 texels where `grid_sample` reads 16 for the same surface (the time it
//!   saves: docs/benchmarks.md). A procedural surface is therefore the grid's interpolant here;
//!   render on the CPU with the grid's surface ([`water_grid`] is the one
//!   [`FinalImage::render_with`] uploads) for an exact comparison. The slab the surface lies in is
//!   found from that texture on the GPU each frame, as the CPU finds it from its surface.
//! - The terrain is an `R32Float` texture through the same `grid_sample`, clamped; the caustics
//!   are the technique's output texture, bound as it is: a floor map read by hand over each
//!   sample's footprint through its pyramid like `MapPyramid::filtered` (the pyramid's levels below
//!   the map in one more texture, made again each frame from the map), or an eye-space image
//!   (`cascaded`) read like
//!   `EyeSpaceCaustics::sample`; an albedo image an `Rgba32Float` texture read at the nearest texel
//!   like `Albedo::at`.
//! - The walls' maps (a technique that lights the pool's walls) are one `Rgba32Float` 2D array
//!   texture of four layers with each layer's column count in a small storage buffer
//!   ([`crate::technique::WallsOutput`]), read like `WallMap::sample`; without maps the count is 0
//!   and the walls get the ambient light alone.
//! - Each object's `MeshBvh` (the very tree the CPU traverses) is flattened into two storage
//!   buffers shared by all objects (bind group 1, `bvh.wgsl`).
//! - The image is written tone-mapped and sRGB-encoded into an `Rgba8Unorm` storage texture with
//!   the CPU's rounding; [`FinalImage::render_with`] reads it back as
//!   [`caustics_core::render::Image`].
//!
//! WGSL has no recursion: the CPU's recursive trace (water surface, glass reflection and
//! refraction) becomes a loop over a small stack of weighted rays, with the CPU's depth limit; the
//! header of `final_image.wgsl` explains why the sum is the same. The whole image is one dispatch,
//! which a desktop GPU finishes in milliseconds; a driver with a watchdog and a very large,
//! heavily supersampled image would want it split into bands.

pub mod slopes;
mod upload;

pub use upload::{
    FinalImageUniform, GpuObject, Meshes, SLAB_LATTICE, Slab, SlabUniform, albedo, flags, meshes,
    slab_bounds, water_grid, water_grid_resolution,
};

use caustics_core::map::{CausticsMap, pyramid_levels};
use caustics_core::render::{Caustics, Image, RenderOptions};
use caustics_core::scene::{Albedo, Scene};
use caustics_core::walls::WallMaps;
use caustics_core::water::Surface;

use crate::map_mips::{MapMips, mip_chain, mips_pipeline};
use crate::pass::{begin_compute, bind_group, compute_pipeline};
use crate::shaders::{BVH, OPTICS, SHADING, WATER, passes};
use crate::technique::{Output, WallsOutput, WaterTextures};
use crate::water::patches::{Patches, WaterPatches};
use crate::{GpuContext, GpuError, GpuTimer};
use slopes::{SlopePipelines, SlopePyramid};
use upload::Lighting;

passes! {
    FINAL_IMAGE = "final image", [OPTICS, WATER, SHADING, BVH], "final_image/final_image.wgsl";
    FINAL_IMAGE_SLAB = "final image slab", [WATER], "final_image/final_image_slab.wgsl";
}

/// Pixels per workgroup side (`@workgroup_size(8, 8)`, both passes).
const TILE: u32 = 8;

/// The final-image pipelines, built once per device.
pub struct FinalImage {
    pipeline: wgpu::ComputePipeline,
    slab_pipeline: wgpu::ComputePipeline,
    /// The water's heights in Hermite form, which the search for the surface reads.
    patches: WaterPatches,
    mips_pipeline: wgpu::ComputePipeline,
    slopes: SlopePipelines,
    scene_layout: wgpu::BindGroupLayout,
    /// Bind group 2: the water's slope moments.
    slopes_layout: wgpu::BindGroupLayout,
    mesh_layout: wgpu::BindGroupLayout,
    /// Bound in place of a height field, terrain, caustics map or albedo image the scene lacks.
    empty_r32: wgpu::Texture,
    empty_rgba32: wgpu::Texture,
    /// Bound in place of the walls' maps (one zero layer).
    empty_walls: wgpu::Texture,
}

/// A level of the floor map's pyramid read back: its width and its texels, row by row.
pub type PyramidLevel = (u32, Vec<[f32; 4]>);

/// The final image of one scene at one image size, everything it reads and writes living across
/// frames: built by [`FinalImage::frame`], updated per frame by one uniform write when the camera,
/// sun or options moved (and, the first time the options filter the water, the pyramid of its
/// slope moments made).
pub struct FinalImageFrame {
    pipeline: wgpu::ComputePipeline,
    slab_pipeline: wgpu::ComputePipeline,
    patches_pipeline: WaterPatches,
    /// The water's heights in Hermite form, filled each frame (none without water).
    patches: Option<Patches>,
    /// The dispatches of the floor map's pyramid below level 0; none for other lighting.
    mips_groups: Option<MapMips>,
    /// The levels `mips_groups` write, below level 0.
    pyramid: Option<wgpu::Texture>,
    /// The water's slope moments, built in the image's pass when the options filter the normals:
    /// made with the frame when its first options filter them, else by the first
    /// [`update`](FinalImageFrame::update) that does (none without a surface).
    slopes: Option<SlopePyramid>,
    slope_pipelines: SlopePipelines,
    slopes_layout: wgpu::BindGroupLayout,
    /// Bind group 2: the pyramid's buffer, or a zero placeholder until there is one.
    slopes_group: wgpu::BindGroup,
    /// A pyramid the options asked for could not be made: not tried again.
    slopes_failed: bool,
    scene_group: wgpu::BindGroup,
    mesh_group: wgpu::BindGroup,
    /// The slab pass's bind group, with a heights texture bound (none: no surface, `h_max` = 0).
    slab_group: Option<wgpu::BindGroup>,
    uniform: wgpu::Buffer,
    /// The bits of the largest |h| and |∇h| on the slab lattice (`final_image_slab.wgsl`).
    slab_max: wgpu::Buffer,
    output: wgpu::Texture,
    lighting: Lighting,
    /// A floor map's square given by the caller (a CPU map's own), in place of the scene's.
    map_size: Option<f64>,
    object_count: u32,
    size: (u32, u32),
    /// What the uniform holds, so that a frame whose camera, sun and options stand still uploads
    /// nothing.
    written: Option<FinalImageUniform>,
    /// Kept alive with the bind groups that read them.
    _resources: Vec<wgpu::Buffer>,
    _textures: Vec<wgpu::Texture>,
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

/// The final image's view of a walls texture: all its layers.
fn walls_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

/// Upload CPU-made walls' maps (the reference's) as the final image reads them: an `Rgba32Float`
/// 2D array texture of four layers, as wide as the widest wall ([`WallsOutput`]'s layout), and
/// each layer's column count. Once per set of maps, not per frame.
pub fn upload_walls(
    ctx: &GpuContext,
    maps: &WallMaps,
) -> Result<(wgpu::Texture, [u32; 4]), GpuError> {
    let cols = maps.maps.each_ref().map(|m| m.cols as u32);
    let width = cols.iter().copied().max().unwrap_or(1).max(1);
    let rows = maps.maps[0].rows as u32;
    ctx.check_texture_size("walls' maps", width, rows)?;
    let mut texels = vec![[0f32; 4]; (width * rows) as usize * 4];
    for (k, m) in maps.maps.iter().enumerate() {
        for i in 0..m.rows {
            for j in 0..m.cols {
                let t = m.texels[i * m.cols + j];
                texels[(k * rows as usize + i) * width as usize + j] = [t[0], t[1], t[2], 1.0];
            }
        }
    }
    let texture = ctx.create_texture_with_data(
        &wgpu::TextureDescriptor {
            label: Some("walls' maps"),
            size: wgpu::Extent3d {
                width,
                height: rows,
                depth_or_array_layers: 4,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&texels),
    );
    Ok((texture, cols))
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

/// A CPU caustics map as the `Rgba32Float` texture a technique's floor output is
/// ([`Output::Floor`]), for [`FinalImage::frame`] or [`FinalImage::render_with`].
pub fn upload_map(ctx: &GpuContext, map: &CausticsMap) -> Result<wgpu::Texture, GpuError> {
    float_texture(
        ctx,
        "caustics map",
        wgpu::TextureFormat::Rgba32Float,
        map.width as u32,
        map.height as u32,
        bytemuck::cast_slice(&rgba32(&map.texels)),
    )
}

/// `map`'s texels into mip 0 of `texture` (`Rgba32Float`, `COPY_DST`, at least the map's size):
/// a floor map the CPU made, for a texture that lives across frames.
pub fn write_map(ctx: &GpuContext, texture: &wgpu::Texture, map: &CausticsMap) {
    ctx.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&rgba32(&map.texels)),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(16 * map.width as u32),
            rows_per_image: Some(map.height as u32),
        },
        wgpu::Extent3d {
            width: map.width as u32,
            height: map.height as u32,
            depth_or_array_layers: 1,
        },
    );
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
                storage_entry(7),
                wgpu::BindGroupLayoutEntry {
                    binding: 8,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2Array,
                        multisampled: false,
                    },
                    count: None,
                },
                storage_entry(9),
                texture_entry(10),
            ],
        });
        let mesh_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("scene meshes"),
            entries: &[storage_entry(0), storage_entry(1)],
        });
        let slopes_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("water slope moments"),
            entries: &[storage_entry(0)],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("final image"),
            bind_group_layouts: &[
                Some(&scene_layout),
                Some(&mesh_layout),
                Some(&slopes_layout),
            ],
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
        let slab_pipeline = compute_pipeline(ctx, &FINAL_IMAGE_SLAB);
        let mips_pipeline = mips_pipeline(ctx);
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
        let empty_walls = float_texture(
            ctx,
            "no walls' maps",
            wgpu::TextureFormat::Rgba32Float,
            1,
            1,
            bytemuck::bytes_of(&[0f32; 4]),
        )?;
        ctx.check()?;
        Ok(FinalImage {
            pipeline,
            slab_pipeline,
            patches: WaterPatches::new(ctx),
            mips_pipeline,
            slopes: SlopePipelines::new(ctx),
            scene_layout,
            slopes_layout,
            mesh_layout,
            empty_r32,
            empty_rgba32,
            empty_walls,
        })
    }

    /// Whether the adapter is a software one (lavapipe, WARP): the pass then runs on the same CPU
    /// cores as `caustics_core::render::render` and, measured on lavapipe, about twice as slowly,
    /// since the CPU renderer needs no texture fetches and no SIMD lanes wait on each other.
    pub fn software_adapter(ctx: &GpuContext) -> bool {
        ctx.info.device_type == wgpu::DeviceType::Cpu
    }

    /// The final image of `scene` at its camera's size, every resource built here once: the
    /// objects' trees (a scene whose objects change needs a new frame), the terrain and albedo
    /// textures, the `Rgba8Unorm` output, the uniform and the bind groups.
    ///
    /// `water`: the heights as the techniques read them, bound as they are (the caller may rewrite
    /// the texture every frame); `None` without water. `caustics`: the technique's output texture,
    /// bound as it is: a floor map over the water square (over the scene square without water), or
    /// an eye-space image of the scene's camera; `None` lights the floor as under flat water.
    /// [`update`](FinalImageFrame::update) takes the first frame's camera and sun before
    /// [`encode`](FinalImageFrame::encode).
    pub fn frame(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        water: Option<&WaterTextures>,
        caustics: Option<Output>,
        options: &RenderOptions,
    ) -> Result<FinalImageFrame, GpuError> {
        self.build(ctx, scene, water, caustics, None, None, options)
    }

    /// [`frame`](Self::frame) with the walls' maps of a technique that lit the pool's walls (bound
    /// as they are; ignored when the scene's walls are off).
    pub fn frame_with_walls(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        water: Option<&WaterTextures>,
        caustics: Option<Output>,
        walls: Option<WallsOutput>,
        options: &RenderOptions,
    ) -> Result<FinalImageFrame, GpuError> {
        self.build(ctx, scene, water, caustics, walls, None, options)
    }

    /// [`frame_with_walls`](Self::frame_with_walls), a floor map's square given (`map_size`) or
    /// the scene's.
    #[allow(clippy::too_many_arguments)]
    fn build(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        water: Option<&WaterTextures>,
        caustics: Option<Output>,
        walls: Option<WallsOutput>,
        map_size: Option<f64>,
        options: &RenderOptions,
    ) -> Result<FinalImageFrame, GpuError> {
        let (width, height) = (scene.camera.width, scene.camera.height);
        ctx.check_texture_size("final image", width, height)?;
        // Heights without water in the scene have no square to cover: the frame has no surface.
        let water = water.filter(|_| scene.water.is_some());
        let lighting = match caustics {
            Some(Output::Floor(_)) => Lighting::Floor {
                size: map_size.unwrap_or(scene.water.as_ref().map_or(scene.size, |w| w.size)),
            },
            Some(Output::EyeSpace(_)) => Lighting::EyeSpace,
            None => Lighting::Flat,
        };

        let meshes = meshes(scene);
        let terrain = match &scene.floor.terrain {
            Some(t) => Some(ctx.upload_grid("terrain height field", t)?),
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
        let walls = walls.filter(|_| scene.floor.walls && scene.water.is_some());
        let wall_cols =
            storage_buffer(ctx, "walls' columns", &walls.map_or([0u32; 4], |w| w.cols))?;
        let objects = storage_buffer(ctx, "scene objects", &meshes.objects)?;
        let nodes = storage_buffer(ctx, "object BVH nodes", &meshes.trees.nodes)?;
        let triangles = storage_buffer(ctx, "object BVH triangles", &meshes.trees.triangles)?;
        let uniform = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("final image uniform"),
            size: std::mem::size_of::<FinalImageUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let slab_max = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("final image slab bounds"),
            size: 8,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let output = ctx.texture_2d(
            "final image",
            (width, height, 1),
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
        );

        let (mips, mips_groups) = match caustics {
            Some(Output::Floor(map)) => self.pyramid(ctx, map).unzip(),
            _ => (None, None),
        };
        let view = |t: Option<&wgpu::Texture>, empty: &wgpu::Texture| {
            t.unwrap_or(empty).create_view(&Default::default())
        };
        let patches = water.map(|w| {
            let wrap = scene.water.as_ref().is_some_and(|sw| sw.wrap);
            self.patches.frame(ctx, &w.heights, wrap)
        });
        let water_view = match &patches {
            Some(p) => p.view.clone(),
            None => view(None, &self.empty_rgba32),
        };
        let no_slopes = storage_buffer(ctx, "no water slope moments", &[0f32; 5])?;
        // The slope moments' pyramid is made by `update` (the first below, when the options filter
        // the water), which leaves the water unfiltered where it cannot be made.
        let slopes_group = bind_group(
            ctx,
            "water slope moments",
            &self.slopes_layout,
            &[no_slopes.as_entire_binding()],
        );
        let views = [
            view(terrain.as_ref(), &self.empty_r32),
            view(caustics.map(|c| c.texture()), &self.empty_rgba32),
            view(albedo_image.as_ref(), &self.empty_rgba32),
            output.create_view(&Default::default()),
            walls_view(walls.map_or(&self.empty_walls, |w| w.texture)),
            view(mips.as_ref(), &self.empty_rgba32),
        ];
        let scene_group = bind_group(
            ctx,
            "final image scene",
            &self.scene_layout,
            &[
                uniform.as_entire_binding(),
                wgpu::BindingResource::TextureView(&water_view),
                wgpu::BindingResource::TextureView(&views[0]),
                wgpu::BindingResource::TextureView(&views[1]),
                wgpu::BindingResource::TextureView(&views[2]),
                objects.as_entire_binding(),
                wgpu::BindingResource::TextureView(&views[3]),
                slab_max.as_entire_binding(),
                wgpu::BindingResource::TextureView(&views[4]),
                wall_cols.as_entire_binding(),
                wgpu::BindingResource::TextureView(&views[5]),
            ],
        );
        let mesh_group = bind_group(
            ctx,
            "scene meshes",
            &self.mesh_layout,
            &[nodes.as_entire_binding(), triangles.as_entire_binding()],
        );
        let mut resources = vec![objects, nodes, triangles, wall_cols, no_slopes];
        let slab_group = match (water, &scene.water) {
            (Some(w), Some(sw)) => {
                // The water's square and edge rule are the scene's: a new frame when they change.
                let slab = SlabUniform {
                    size: sw.size as f32,
                    wrap: sw.wrap as u32,
                    lattice: SLAB_LATTICE,
                    _pad: 0,
                };
                let slab_uniform = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("final image slab uniform"),
                    contents: bytemuck::bytes_of(&slab),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let group = bind_group(
                    ctx,
                    "final image slab",
                    &self.slab_pipeline.get_bind_group_layout(0),
                    &[
                        slab_uniform.as_entire_binding(),
                        wgpu::BindingResource::TextureView(&w.heights),
                        slab_max.as_entire_binding(),
                    ],
                );
                resources.push(slab_uniform);
                Some(group)
            }
            _ => None,
        };

        let mut frame = FinalImageFrame {
            pipeline: self.pipeline.clone(),
            slab_pipeline: self.slab_pipeline.clone(),
            patches_pipeline: self.patches.clone(),
            patches,
            mips_groups,
            scene_group,
            mesh_group,
            slab_group,
            uniform,
            slab_max,
            output,
            lighting,
            map_size,
            object_count: meshes.objects.len() as u32,
            size: (width, height),
            written: None,
            _resources: resources,
            pyramid: mips,
            slopes: None,
            slope_pipelines: self.slopes.clone(),
            slopes_layout: self.slopes_layout.clone(),
            slopes_group,
            slopes_failed: false,
            _textures: terrain.into_iter().chain(albedo_image).collect(),
        };
        frame.update(ctx, scene, options);
        ctx.check()?;
        Ok(frame)
    }

    /// The levels of `map`'s pyramid below level 0 (`CausticsMap::pyramid`: level `L` is
    /// `max(1, size >> L)`), as the mips of one `Rgba32Float` texture whose level `L - 1` is the
    /// pyramid's level `L`, and the dispatches that fill it; none for a map of one texel.
    fn pyramid(&self, ctx: &GpuContext, map: &wgpu::Texture) -> Option<(wgpu::Texture, MapMips)> {
        let levels = pyramid_levels(map.width() as usize, map.height() as usize) as u32 - 1;
        if levels == 0 {
            return None;
        }
        let mips = mip_chain(
            ctx,
            "caustics map pyramid",
            ((map.width() / 2).max(1), (map.height() / 2).max(1)),
            levels,
            wgpu::TextureUsages::COPY_SRC,
        );
        let groups = MapMips::beside(ctx, &self.mips_pipeline, map, &mips);
        Some((mips, groups))
    }

    /// Render `scene` from its camera: the GPU counterpart of `caustics_core::render::render`, with
    /// the same arguments (no progress: the image is one dispatch). `surface` is sampled on
    /// [`water_grid`]'s lattice; `caustics` is the floor's map (none: lit as if the water were
    /// flat). With a `timer`, the passes are timed as [`encode`](FinalImageFrame::encode) says and
    /// the timestamps resolved; read them with [`GpuTimer::read`].
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
    /// scene's camera (`cascaded`), read at the pixel each floor point projects to. A one-off
    /// image from CPU inputs: the water grid and the map are uploaded into textures, a
    /// [`FinalImageFrame`] is built on them, and the image is read back.
    pub fn render_with(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        surface: Option<&dyn Surface>,
        caustics: Option<Caustics>,
        options: &RenderOptions,
        timer: Option<&mut GpuTimer>,
    ) -> Result<Image, GpuError> {
        self.render_with_walls(ctx, scene, surface, caustics, None, options, timer)
    }

    /// [`render_with`](Self::render_with), the pool's walls lit through CPU-made walls' maps (the
    /// reference's), the GPU counterpart of `caustics_core::render::render_with_walls`.
    #[allow(clippy::too_many_arguments)]
    pub fn render_with_walls(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        surface: Option<&dyn Surface>,
        caustics: Option<Caustics>,
        walls: Option<&WallMaps>,
        options: &RenderOptions,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<Image, GpuError> {
        let grid = surface.and_then(|s| water_grid(scene, s));
        let heights = match &grid {
            Some(g) => Some(ctx.upload_grid("water height field", &g.grid)?),
            None => None,
        };
        let water = heights.as_ref().map(WaterTextures::of);
        let map = match caustics {
            Some(Caustics::Floor(m)) => Some(upload_map(ctx, m)?),
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
        let (output, map_size) = match (caustics, &map) {
            (Some(Caustics::Floor(m)), Some(t)) => (Some(Output::Floor(t)), Some(m.size)),
            (Some(Caustics::EyeSpace(_)), Some(t)) => (Some(Output::EyeSpace(t)), None),
            _ => (None, None),
        };
        let walls = match walls {
            Some(w) => Some(upload_walls(ctx, w)?),
            None => None,
        };
        let walls_output = walls.as_ref().map(|(texture, cols)| WallsOutput {
            texture,
            cols: *cols,
        });
        let frame = self.build(
            ctx,
            scene,
            water.as_ref(),
            output,
            walls_output,
            map_size,
            options,
        )?;

        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("final image"),
            });
        frame.encode(&mut encoder, timer.as_deref_mut());
        if let Some(t) = &timer {
            t.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        let texels: Vec<[u8; 4]> = ctx.read_texture(frame.output())?;
        Ok(Image {
            width: frame.size.0,
            height: frame.size.1,
            rgb: texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}

impl FinalImageFrame {
    /// Take this frame's camera, sun, exposure and supersampling from `scene` and `options`: one
    /// uniform write (and the slope moments' pyramid made, the first time the options filter the
    /// water). What the frame was built with stays: the image size (the aspect ratio is the
    /// frame's), the textures, the objects; a change to those needs a new frame.
    pub fn update(&mut self, ctx: &GpuContext, scene: &Scene, options: &RenderOptions) {
        let wrap = scene.water.as_ref().is_some_and(|w| w.wrap);
        if let Some(patches) = &mut self.patches {
            patches.set_wrap(ctx, wrap);
        }
        if options.filter_water && self.slopes.is_none() && !self.slopes_failed {
            self.make_slopes(ctx, scene);
        }
        if let Some(slopes) = &mut self.slopes {
            slopes.set_wrap(ctx, wrap);
        }
        let lighting = match self.lighting {
            // A floor map covers the water square (the scene's without water), as the techniques
            // lay their maps out, unless the caller said otherwise.
            Lighting::Floor { .. } => Lighting::Floor {
                size: self
                    .map_size
                    .unwrap_or(scene.water.as_ref().map_or(scene.size, |w| w.size)),
            },
            other => other,
        };
        let params = upload::uniform(
            scene,
            self.slab_group.is_some(),
            self.slopes.as_ref().map(|s| s.lattice()),
            lighting,
            options,
            self.object_count,
            self.size,
        );
        if self
            .written
            .is_some_and(|w| bytemuck::bytes_of(&w) == bytemuck::bytes_of(&params))
        {
            return;
        }
        ctx.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&params));
        self.written = Some(params);
    }

    /// Record the water's patches and slab bound (when there is water) and the image into
    /// `encoder`. With a `timer`, every pass is timed: the patches as "water patches", the slab
    /// pass (128² bicubic samples) as "final image slab", the image as "final image"; a timer
    /// needs room for three passes per image.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, mut timer: Option<&mut GpuTimer>) {
        if let Some(patches) = &self.patches {
            self.patches_pipeline.encode(patches, encoder, &mut timer);
        }
        if let Some(group) = &self.slab_group {
            encoder.clear_buffer(&self.slab_max, 0, None);
            let mut pass = begin_compute(encoder, &mut timer, FINAL_IMAGE_SLAB.name);
            pass.set_pipeline(&self.slab_pipeline);
            pass.set_bind_group(0, group, &[]);
            let groups = SLAB_LATTICE.div_ceil(TILE);
            pass.dispatch_workgroups(groups, groups, 1);
        }
        let mut pass = begin_compute(encoder, &mut timer, FINAL_IMAGE.name);
        // The floor map's pyramid, finest level first; the image's dispatch reads it all.
        if let Some(mips) = &self.mips_groups {
            mips.encode(&mut pass);
        }
        if let Some(slopes) = self.slopes.as_ref().filter(|_| self.filters_water()) {
            slopes.encode(&mut pass);
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.scene_group, &[]);
        pass.set_bind_group(1, &self.mesh_group, &[]);
        pass.set_bind_group(2, &self.slopes_group, &[]);
        let (width, height) = self.size;
        pass.dispatch_workgroups(width.div_ceil(TILE), height.div_ceil(TILE), 1);
    }

    /// The slope moments' pyramid, for options that filter the water's normals in a frame built
    /// without them: made once, on the frame's heights. Where it cannot be made (a lattice whose
    /// pyramid exceeds the adapter's buffers), the water stays unfiltered, said in the log.
    fn make_slopes(&mut self, ctx: &GpuContext, scene: &Scene) {
        let (Some(patches), Some(water)) = (&self.patches, &scene.water) else {
            return;
        };
        match self.slope_pipelines.pyramid(
            ctx,
            &patches.view,
            patches.size(),
            water.size,
            water.wrap,
        ) {
            Ok(pyramid) => {
                self.slopes_group = bind_group(
                    ctx,
                    "water slope moments",
                    &self.slopes_layout,
                    &[pyramid.moments.as_entire_binding()],
                );
                self.slopes = Some(pyramid);
            }
            Err(e) => {
                tracing::warn!("the water's normals stay unfiltered: {e}");
                self.slopes_failed = true;
            }
        }
    }

    /// Whether the uniform last written filters the waves' normals by the samples' footprints.
    fn filters_water(&self) -> bool {
        self.written
            .is_some_and(|w| w.flags & flags::FILTER_WATER != 0)
    }

    /// The levels of the water's slope moments the last submitted frame built, finest first (none
    /// without a surface; stale when the options do not filter the normals): for tests against
    /// `caustics_core::water::slopes::SlopePyramid`. A readback; not for the frame.
    pub fn read_slopes(
        &self,
        ctx: &GpuContext,
    ) -> Result<Vec<Vec<[f32; slopes::MOMENTS]>>, GpuError> {
        match &self.slopes {
            Some(s) => s.read(ctx),
            None => Ok(Vec::new()),
        }
    }

    /// The image: `Rgba8Unorm`, tone-mapped and sRGB-encoded (the 8-bit codes of
    /// `caustics_core::render`'s image), usable as a storage, sampled or copied texture.
    pub fn output(&self) -> &wgpu::Texture {
        &self.output
    }

    /// The levels below level 0 of the floor map's pyramid the last submitted frame built (none
    /// without a floor map), finest first, each with its width: for tests against
    /// `CausticsMap::pyramid`. Readbacks; not for the frame.
    pub fn read_pyramid(&self, ctx: &GpuContext) -> Result<Vec<PyramidLevel>, GpuError> {
        let Some(mips) = &self.pyramid else {
            return Ok(Vec::new());
        };
        (0..mips.mip_level_count())
            .map(|k| {
                let w = mips
                    .size()
                    .mip_level_size(k, wgpu::TextureDimension::D2)
                    .width;
                Ok((w, ctx.read_texture_mip(mips, 0, k)?))
            })
            .collect()
    }

    /// The slab the last submitted frame searched for the water surface in and the slope bound
    /// of its march (zeros without a surface): for tests against [`slab_bounds`]. A readback;
    /// not for the frame.
    pub fn read_slab(&self, ctx: &GpuContext) -> Result<Slab, GpuError> {
        if self.slab_group.is_none() {
            return Ok(Slab::default());
        }
        let bits: Vec<u32> = ctx.read_buffer(&self.slab_max)?;
        let scaled = |b: u32| f32::from_bits(b) as f64 * 1.5 + 1e-6;
        Ok(Slab {
            half_height: scaled(bits[0]),
            slope: scaled(bits[1]),
        })
    }
}
