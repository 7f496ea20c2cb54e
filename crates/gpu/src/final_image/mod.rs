//! The final image on the GPU: the scene from its camera with the water, its Fresnel reflection of
//! the sky, the refracted floor lit through a caustics map, and the objects. It is the GPU twin of
//! the CPU renderer `caustics_core::render` (`crates/core/src/render/`, where the light transport
//! is written down) and gives the same image up to f32 rounding; `tests/render_gpu.rs` holds the
//! two together.
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | the water's heights in Hermite form (compute, one invocation per texel) | `water/water_patches.wgsl` ([`crate::water::patches`]) | (the grid's bicubic sample) |
//! | water slab bounds (compute, 128² samples) | `final_image/final_image_slab.wgsl` | [`slab_bounds`]: the slab's half height and the slope bound of the march |
//! | the water's surface from the camera (render, a grid of up to 128² cells through the heights, raised by the slope bound times a cell's diagonal so that it lies above the surface) | `final_image/final_image_surface.wgsl` | (none: where a primary ray's march may start without passing a crossing, so the crossing found is the march's) |
//! | the floor map's pyramid (compute, one dispatch a level, in the image's pass) | `map_mips.wgsl` | `CausticsMap::pyramid` |
//! | the water's slope moments' pyramid (compute, one dispatch a level, in the image's pass, when the normals are filtered) | `final_image/water_slopes_base.wgsl`, `final_image/water_slopes_halve.wgsl` ([`slopes`]) | `SlopePyramid::new` |
//! | final image (compute, one invocation per pixel) | `final_image/final_image.wgsl`, after its parts `final_image_inputs.wgsl` (the uniform, bindings and inputs' reads), `final_image_spread.wgsl`, `final_image_receivers.wgsl`, `final_image_march.wgsl`, `final_image_shade.wgsl`, `final_image_rough_water.wgsl` | `render::render` and `Tracer` (`render/mod.rs`, `spread.rs`, `shade.rs`, `march.rs`, `sky.rs`, `trace.rs`) |
//! | (shared) sky, floor albedo, tone map | `shaders/shading.wgsl` | `Tracer::sky`, `tone_map`, `Albedo::filtered` |
//! | (shared) mesh ray queries | `shaders/bvh.wgsl` | `MeshBvh::intersect` |
//!
//! The image is a [`FinalImageFrame`]: built once per scene and image size (the objects' trees, the
//! terrain and albedo textures, the output texture, the bind groups), then per frame one uniform
//! write ([`FinalImageFrame::update`]) and four passes recorded into the caller's encoder
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
//!   [`FinalImage::render`] uploads) for an exact comparison. The slab the surface lies
//!   in is found from that texture on the GPU each frame, as the CPU finds it from its surface.
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
//!   the CPU's rounding; [`FinalImage::render`] reads it back as
//!   [`caustics_core::render::Image`].
//!
//! WGSL has no recursion: the CPU's recursive trace (water surface, glass reflection and
//! refraction) becomes a loop over a small stack of weighted rays, with the CPU's depth limit; the
//! header of `final_image_inputs.wgsl` explains why the sum is the same. The whole image is one
//! dispatch, which a desktop GPU finishes in milliseconds; a driver with a watchdog and a very
//! large, heavily supersampled image would want it split into bands.

mod encode;
mod frame;
pub use frame::ImageInputs;
mod readback;
mod resources;
pub mod slopes;
mod upload;

pub use resources::{upload_map, upload_walls, write_map};
pub use upload::{
    FinalImageUniform, GpuObject, Meshes, SLAB_LATTICE, Slab, SlabUniform, albedo, flags, meshes,
    slab_bounds, water_grid, water_grid_resolution,
};

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use crate::map_mips::{MapMips, mips_pipeline};
use crate::pass::compute_pipeline;
use crate::pass::float_texture;
use crate::shaders::passes;
use crate::water::patches::{Patches, WaterPatches};
use crate::{GpuContext, GpuError};
use resources::{storage_entry, texture_entry};
use slopes::{SlopePipelines, SlopePyramid};
use upload::Lighting;

// The final image pass is `final_image.wgsl` and the modules it imports, each the twin of a file of
// `caustics_core::render`: `final_image_inputs` (the uniform, bindings and input reads),
// `final_image_spread` (ray differentials, `render/spread.rs`), `final_image_receivers` (eye-space
// caustics, objects, the pool's walls), `final_image_march` (`render/march.rs`),
// `final_image_shade` (`render/shade.rs`) and `final_image_rough_water` (`render/sky.rs`).
passes! {
    FINAL_IMAGE = "final image", "final_image/final_image.wgsl";
    FINAL_IMAGE_SLAB = "final image slab", "final_image/final_image_slab.wgsl";
    FINAL_IMAGE_SURFACE = "final image surface", "final_image/final_image_surface.wgsl";
}

/// The most cells along a side of the grid the water's surface is rasterised as
/// (`final_image_surface.wgsl`'s `MAX_CELLS`).
const SURFACE_CELLS: u32 = 128;

/// The format of the rasterised surface's distances, read by the image pass.
const SURFACE_HITS: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
const SURFACE_DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Pixels per workgroup side (`@workgroup_size(8, 8)`, both passes).
const TILE: u32 = 8;

/// The `@id` of the image pass's `FLAGS` override: its name is the module's, mangled by the WESL
/// linker.
const FLAGS_ID: &str = "0";

/// The flags a pipeline is specialised by (`FLAGS` in `final_image_inputs.wgsl`); the others are
/// read from the uniform (its `SET_AT_RUN_TIME`).
const SPECIALISED: u32 = !(flags::WRAP_SURFACE | flags::WRAP_CAUSTICS);

/// The image pass's pipelines, one per set of flags a frame has used: the shader's `FLAGS`
/// override, so that each scene's pipeline holds only the code it runs.
struct ImagePipelines {
    layout: wgpu::PipelineLayout,
    module: wgpu::ShaderModule,
    by_flags: Mutex<HashMap<u32, wgpu::ComputePipeline>>,
}

impl ImagePipelines {
    /// The pipeline for `flags`, built the first time a frame asks for its specialised ones.
    fn get(&self, ctx: &GpuContext, flags: u32) -> wgpu::ComputePipeline {
        let flags = flags & SPECIALISED;
        let mut built = self.by_flags.lock().unwrap_or_else(|e| e.into_inner());
        let pipeline = built.entry(flags).or_insert_with(|| {
            ctx.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(FINAL_IMAGE.name),
                layout: Some(&self.layout),
                module: &self.module,
                entry_point: Some("main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &[(FLAGS_ID, flags as f64)],
                    ..Default::default()
                },
                cache: None,
            })
        });
        pipeline.clone()
    }
}

/// The final-image pipelines, built once per device (the image pass's once per set of flags).
pub struct FinalImage {
    pipelines: Arc<ImagePipelines>,
    slab_pipeline: wgpu::ComputePipeline,
    /// The water's surface rasterised from the camera: where the search for it along a primary
    /// ray starts.
    surface_pipeline: wgpu::RenderPipeline,
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
    pipelines: Arc<ImagePipelines>,
    /// The image pass's pipeline for the flags of the uniform last written, and those flags.
    pipeline: Option<(u32, wgpu::ComputePipeline)>,
    slab_pipeline: wgpu::ComputePipeline,
    surface_pipeline: wgpu::RenderPipeline,
    /// The rasterised surface's bind group, distances and depth (none without a surface).
    surface: Option<SurfaceRaster>,
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

/// The water's surface rasterised for one frame's camera: what `final_image_surface.wgsl` reads
/// (the image's uniform, the heights in Hermite form and the slab's bounds) and writes.
struct SurfaceRaster {
    group: wgpu::BindGroup,
    hits: wgpu::TextureView,
    depth: wgpu::TextureView,
    /// The grid's cells along each side.
    cells: (u32, u32),
}

/// The surface's render pipeline: the grid's triangles, none culled (a crest's far side is seen
/// from behind where the next is low), the nearest kept by a reversed depth.
fn surface_pipeline(ctx: &GpuContext) -> wgpu::RenderPipeline {
    let module = FINAL_IMAGE_SURFACE.module(&ctx.device);
    ctx.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(FINAL_IMAGE_SURFACE.name),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: SURFACE_DEPTH,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(SURFACE_HITS.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

impl FinalImage {
    /// Build the pipelines and bind group layouts of the slab, the patches, the map's and slopes'
    /// pyramids and the image, and the placeholder textures bound for what a scene lacks.
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
                wgpu::BindGroupLayoutEntry {
                    binding: 11,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<
                            crate::receivers::LightSpaceUniform,
                        >() as u64),
                    },
                    count: None,
                },
                texture_entry(12),
                texture_entry(13),
                texture_entry(14),
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
        let pipelines = Arc::new(ImagePipelines {
            layout,
            module: FINAL_IMAGE.module(device),
            by_flags: Mutex::new(HashMap::new()),
        });
        let slab_pipeline = compute_pipeline(ctx, &FINAL_IMAGE_SLAB);
        let surface_pipeline = surface_pipeline(ctx);
        let mips_pipeline = mips_pipeline(ctx);
        let empty_r32 = float_texture(
            ctx,
            "no height field",
            wgpu::TextureFormat::R32Float,
            (1, 1, 1),
            bytemuck::bytes_of(&0f32),
        )?;
        let empty_rgba32 = float_texture(
            ctx,
            "no map",
            wgpu::TextureFormat::Rgba32Float,
            (1, 1, 1),
            bytemuck::bytes_of(&[1f32; 4]),
        )?;
        let empty_walls = float_texture(
            ctx,
            "no walls' maps",
            wgpu::TextureFormat::Rgba32Float,
            (1, 1, 1),
            bytemuck::bytes_of(&[0f32; 4]),
        )?;
        ctx.check()?;
        Ok(FinalImage {
            pipelines,
            slab_pipeline,
            surface_pipeline,
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
}
