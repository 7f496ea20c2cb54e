//! Technique `volumes` on the GPU: caustics on underwater objects from illumination volumes, colour
//! and depth textures and reference planes (paper 3). The method, its units and where it departs
//! from the reference are documented with its CPU twin, `caustics_core::techniques::volumes`, which
//! these passes mirror one for one:
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | depth texture / shadow map (compute, BVH rays) | `volumes/depth.wgsl` + `bvh.wgsl` | `representation::depth_pass` |
//! | water (compute) | `volumes/water.wgsl` | `illumination::water_pass` |
//! | illumination volumes × reference planes (raster, additive) | `volumes/slices.wgsl` | `illumination::slice_pass` |
//! | floor map (raster, additive) | `volumes/floor.wgsl` | `illumination::floor_pass` |
//! | over a terrain: each vertex's ray meets the receivers (compute) | `volumes/meet.wgsl` | `illumination::meet_pass` |
//! | over a terrain: the floor's light in the light's space (raster, additive), then the receivers' lookup | `volumes/floor_receivers.wgsl` | `illumination::received_floor_pass` |
//! | walls' maps, with walls (raster, additive, one layer per wall) | `volumes/walls.wgsl` | `illumination::wall_pass` |
//! | diffuse map and Eq. 4 (compute) | `volumes/shade.wgsl` | `representation::diffuse_map`, `illumination::shade_pass` |
//! | refracted view, §3.3 (compute) | `volumes/view.wgsl` | `view::view_pass` |
//!
//! The Rust beside them: `uniforms.rs` (the uniform blocks as the WGSL declares them), `frame.rs`
//! (a scene's resources and every pass's bind groups, [`VolumesFrame`]), `encode.rs` (the passes
//! recorded in the table's order), `readback.rs` (runs once and readbacks for tools and tests) and
//! `technique.rs` (the registry's entry); this file holds the passes and the pipelines.
//!
//! The slices are rasterised with additive blending, as the paper draws them: one triangle per
//! (reference plane, water triangle), pulled from the water buffer by the vertex shader, the depth
//! test of §3.1 in the fragment shader. The caustics maps are `Rgba32Float` where the adapter has
//! `FLOAT32_BLENDABLE`, otherwise `Rgba16Float` (blendable everywhere, about 3 significant digits).
//! The depth textures are cast as one BVH ray per texel (the same trees the CPU walks) rather than
//! rasterised: the same nearest surface at the same texel centres, and the CPU twin can follow it
//! exactly.

mod encode;
mod frame;
mod readback;
pub mod technique;
mod uniforms;

pub use frame::{VolumesFrame, WallsFrame};
pub use readback::GpuOutput;
pub use uniforms::{CameraUniform, PassUniform, ViewOptions, ViewUniform, VolumesUniform};

use crate::pass::{additive_pipeline, blendable_map_format, compute_pipeline};
use crate::shaders::passes;
use crate::{GpuContext, GpuError};

passes! {
    DEPTH = "volumes depth", "volumes/depth.wgsl";
    WATER_PASS = "volumes water", "volumes/water.wgsl";
    SLICES = "volumes slices", "volumes/slices.wgsl";
    FLOOR = "volumes floor", "volumes/floor.wgsl";
    MEET = "volumes meet", "volumes/meet.wgsl";
    FLOOR_RECEIVERS = "volumes floor over receivers", "volumes/floor_receivers.wgsl";
    WALLS = "volumes walls", "volumes/walls.wgsl";
    VIEW = "volumes view", "volumes/view.wgsl";
    SHADE = "volumes shade", "volumes/shade.wgsl";
}

/// The technique's pipelines, built once per device for one caustics-map format.
pub struct Volumes {
    depth: wgpu::ComputePipeline,
    water: wgpu::ComputePipeline,
    slices: wgpu::RenderPipeline,
    floor: wgpu::RenderPipeline,
    meet: wgpu::ComputePipeline,
    floor_receivers: wgpu::RenderPipeline,
    lookup: crate::receivers::ReceiverLookup,
    walls: wgpu::RenderPipeline,
    shade: wgpu::ComputePipeline,
    view: wgpu::ComputePipeline,
    /// `Rgba32Float` with `FLOAT32_BLENDABLE`, else `Rgba16Float`.
    pub map_format: wgpu::TextureFormat,
}

impl Volumes {
    /// Pipelines for the best caustics-map format this device blends.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Self::with_format(ctx, blendable_map_format(ctx))
    }

    /// Pipelines for a given caustics-map format (`Rgba32Float` needs `FLOAT32_BLENDABLE`).
    pub fn with_format(
        ctx: &GpuContext,
        map_format: wgpu::TextureFormat,
    ) -> Result<Self, GpuError> {
        let v = Volumes {
            depth: compute_pipeline(ctx, &DEPTH),
            water: compute_pipeline(ctx, &WATER_PASS),
            slices: additive_pipeline(ctx, &SLICES, map_format),
            floor: additive_pipeline(ctx, &FLOOR, map_format),
            meet: compute_pipeline(ctx, &MEET),
            floor_receivers: additive_pipeline(ctx, &FLOOR_RECEIVERS, map_format),
            lookup: crate::receivers::ReceiverLookup::new(ctx),
            walls: additive_pipeline(ctx, &WALLS, map_format),
            shade: compute_pipeline(ctx, &SHADE),
            view: compute_pipeline(ctx, &VIEW),
            map_format,
        };
        ctx.check()?;
        Ok(v)
    }
}
