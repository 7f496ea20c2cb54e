//! Technique `caustic-triangles` on the GPU: "Caustic Triangles on the GPU" (Umenhoffer, Patow &
//! Szirmay-Kalos). The method, the area rules and where it departs from the paper are documented
//! with its CPU twin, `caustics_core::techniques::caustic_triangles`, which these passes mirror one
//! for one:
//!
//! | pass | WGSL | recorded in | CPU twin |
//! |---|---|---|---|
//! | photon tracing (compute, §4.1) | `caustic_triangles/photon.wgsl` + `distance_map.wgsl` | `generator.rs` | `photon::photon_pass` |
//! | vertex irradiance (compute, §5) | `caustic_triangles/irradiance.wgsl` | `generator.rs` | `irradiance::irradiance_pass` |
//! | caustic triangles (render, §4.2) | `caustic_triangles/triangles.wgsl` + `merge.wgsl` | `generator.rs` | `triangles::triangles_pass` (`merge::drawn_quads`) |
//! | merge pyramid (compute, §5, with `merge_levels`) | `caustic_triangles/pyramid.wgsl` | `generator.rs` | `pyramid::pyramid_pass` |
//! | splatting baseline (render) | `caustic_triangles/splat.wgsl` | `generator.rs` | `splat::splat_pass` |
//! | caustic triangles on the light cube map faces (render, §4.2, point light) | `caustic_triangles/cube.wgsl` | `cube.rs` | `cube::cube_triangles_pass` |
//! | light cube shadow distances (compute, §4.3) | `caustic_triangles/shadow.wgsl` | `cube.rs` | `cube::shadow_pass` |
//! | camera pass (compute, §4.3), [`camera`] | `caustic_triangles/camera.wgsl` | `camera.rs` | `camera::camera_pass` |
//! | water photon pass (compute, the water surface as the generator) | `caustic_triangles/water_photon.wgsl` | `water.rs` | `water::photon_pass` |
//! | copy band (compute, tiling water: a bound over every texel, then one thread) | `caustic_triangles/band_bound.wgsl`, `band.wgsl` | `water.rs` | `water::copy_band` |
//!
//! The CPU twins are files of `caustics_core::techniques::caustic_triangles` of the same names
//! (`photon.rs` for `photon.wgsl`, ...). Beside the passes: `uniforms.rs` (the uniform blocks as
//! the WGSL declares them), `generator.rs` (one generator's frame, [`GeneratorFrame`]), `cube.rs`
//! (the light cube map, [`LightCubeTarget`]), `water.rs` (the water generator's frame and the
//! walls, [`WaterFrame`]), `readback.rs` (runs once and readbacks for tools and tests),
//! `technique.rs` (the registry's entry); this file holds the passes and the pipelines.
//!
//! With the water surface as the generator ([`WaterFrame`], `caustics_core::techniques::
//! caustic_triangles::water`) the water photon pass replaces the photon tracing pass and also
//! writes each photon's refracted path length; the triangles and splats read it for Beer-Lambert
//! absorption and draw nine instances (offsets of `±size`) of each primitive for tiling water. The
//! eight shifted copies are drawn only over the band of quads whose light can cross an edge; the
//! copy band pass fits that band on the GPU from the heights it reads and writes the indirect draw
//! of the shifted copies, so a frame never reads the heights on the CPU (the CPU twin fits the same
//! bound in f64, `WaterSetup::fit_band`; any band at least the light's reach draws the same map).
//!
//! With the pool's walls (`WaterSetup::with_walls`) nothing wraps; each wall is a
//! receiver of its own ([`WallFrames`]): the water photon pass again with the uniform's `receiver`
//! (the rays extended to the wall's plane, `water::receiver_photon`), vertex irradiance and
//! triangles into its layer of a 4-layer wall-map texture (`water::wall_caustics`).
//!
//! The layered distance map is built on the CPU ([`DistanceMap::build`]) and uploaded as a storage
//! buffer; the photon hit location image and the vertex irradiances are storage buffers that the
//! vertex shaders read (no vertex buffers: 6 vertices per photon-image quad, 6 per splat). The floor
//! map is drawn with additive blending into `Rgba32Float` where the adapter has
//! `FLOAT32_BLENDABLE`, otherwise into `Rgba16Float` (blendable everywhere; about 3 significant
//! digits, ~0.2 % of the total lost to rounding in accumulation).
//!
//! [`DistanceMap::build`]: caustics_core::techniques::caustic_triangles::DistanceMap::build

pub mod camera;
mod cube;
mod generator;
mod readback;
pub mod technique;
mod uniforms;
mod water;

pub use cube::{CubeBinds, LightCubeTarget};
pub use generator::GeneratorFrame;
pub use readback::{GpuOutput, WaterGpuOutput};
pub use uniforms::{CausticTrianglesUniform, CopyBandBuffer, WaterPhotonUniform};
pub use water::{WallFrame, WallFrames, WaterFrame};

use crate::pass::{additive_pipeline, blendable_map_format, compute_pipeline};
use crate::shaders::passes;
use crate::{GpuContext, GpuError};

passes! {
    PHOTON = "caustic-triangles photon tracing", "caustic_triangles/photon.wgsl";
    IRRADIANCE = "caustic-triangles vertex irradiance", "caustic_triangles/irradiance.wgsl";
    TRIANGLES = "caustic-triangles triangles", "caustic_triangles/triangles.wgsl";
    PYRAMID = "caustic-triangles merge pyramid", "caustic_triangles/pyramid.wgsl";
    CUBE = "caustic-triangles light cube map", "caustic_triangles/cube.wgsl";
    SHADOW = "caustic-triangles light cube shadow distances", "caustic_triangles/shadow.wgsl";
    WATER_PHOTON = "caustic-triangles water photons", "caustic_triangles/water_photon.wgsl";
    COPY_BAND = "caustic-triangles copy band", "caustic_triangles/band.wgsl";
    BAND_BOUND = "caustic-triangles band bound", "caustic_triangles/band_bound.wgsl";
    SPLAT = "caustic-triangles splats", "caustic_triangles/splat.wgsl";
    CAMERA = "caustic-triangles camera pass", "caustic_triangles/camera.wgsl";
}

/// How the photon hits become the floor map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reconstruction {
    /// The paper's caustic triangles.
    Triangles,
    /// The fixed-size splatting baseline.
    Splats,
}

/// The technique's pipelines, built once per device for one floor-map format.
pub struct CausticTriangles {
    pub(crate) photon: wgpu::ComputePipeline,
    pub(crate) irradiance: wgpu::ComputePipeline,
    pyramid: wgpu::ComputePipeline,
    triangles: wgpu::RenderPipeline,
    splat: wgpu::RenderPipeline,
    cube: wgpu::RenderPipeline,
    shadow: wgpu::ComputePipeline,
    water_photon: wgpu::ComputePipeline,
    copy_band: wgpu::ComputePipeline,
    band_bound: wgpu::ComputePipeline,
    /// The receivers' lookup of a water frame over a terrain.
    lookup: crate::receivers::ReceiverLookup,
    /// `Rgba32Float` with `FLOAT32_BLENDABLE`, else `Rgba16Float` (floor and light cube maps).
    pub map_format: wgpu::TextureFormat,
}

impl CausticTriangles {
    /// Pipelines for the best floor-map format this device blends.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Self::with_format(ctx, blendable_map_format(ctx))
    }

    /// Pipelines for a given floor-map format (`Rgba32Float` needs `FLOAT32_BLENDABLE`).
    pub fn with_format(
        ctx: &GpuContext,
        map_format: wgpu::TextureFormat,
    ) -> Result<Self, GpuError> {
        let t = CausticTriangles {
            photon: compute_pipeline(ctx, &PHOTON),
            irradiance: compute_pipeline(ctx, &IRRADIANCE),
            pyramid: compute_pipeline(ctx, &PYRAMID),
            triangles: additive_pipeline(ctx, &TRIANGLES, map_format),
            splat: additive_pipeline(ctx, &SPLAT, map_format),
            cube: additive_pipeline(ctx, &CUBE, map_format),
            shadow: compute_pipeline(ctx, &SHADOW),
            water_photon: compute_pipeline(ctx, &WATER_PHOTON),
            copy_band: compute_pipeline(ctx, &COPY_BAND),
            band_bound: compute_pipeline(ctx, &BAND_BOUND),
            lookup: crate::receivers::ReceiverLookup::new(ctx),
            map_format,
        };
        ctx.check()?;
        Ok(t)
    }
}
