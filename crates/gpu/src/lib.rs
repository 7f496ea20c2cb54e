//! `caustics-gpu`: the GPU side of caustics on wgpu + WGSL. Device plumbing ([`GpuContext`]),
//! readback, per-pass timestamps, the shared WGSL math ([`shaders`]), and the GPU water simulations.
//! Each technique lives in its own module with one WGSL file per pass; its CPU twin lives in
//! `caustics-core`.

pub mod adapter;
pub mod bake;
pub mod bvh;
pub mod cascaded;
pub mod caustic_triangles;
pub mod context;
pub mod final_image;
pub mod map_mips;
pub mod pass;
pub mod probe;
pub mod procedural;
pub mod receivers;
pub mod registry;
pub mod renderer;
pub mod shaders;
pub mod technique;
pub mod timing;
mod transfer;
pub use transfer::{Readback, f16_to_f32};
/// The Vulkan validation layer: native only (a browser's WebGPU validates on its own).
#[cfg(not(target_arch = "wasm32"))]
pub mod validation;
pub mod volumes;
pub mod water;
pub mod yuksel;

pub use context::traffic::{self, TrafficCounts};
pub use context::{GpuContext, GpuOptions};
pub use technique::{Output, Technique, WallsOutput, WaterTextures};
pub use timing::{GpuTimer, PassTime};

/// The versions this crate's API speaks: an application names `caustics_gpu::wgpu` and
/// `caustics_gpu::glam` (and the core crate's types) without matching them by hand.
pub use caustics_core::{self as core, glam, toml};
pub use wgpu;

/// Everything that can go wrong on the GPU side, each naming the problem.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error("no GPU adapter found: wanted {wanted}; adapters present: {}", if seen.is_empty() { "none".to_string() } else { seen.join(", ") })]
    NoAdapter { wanted: String, seen: Vec<String> },
    #[error("the GPU adapter refused to create a device: {0}")]
    RequestDevice(String),
    #[error("{what} of {size} is beyond what this GPU allows ({limit})")]
    TooLarge {
        what: String,
        size: String,
        limit: String,
    },
    #[error("the GPU device was lost: {0}")]
    DeviceLost(String),
    #[error("GPU validation error: {0}")]
    Validation(String),
    #[error("reading GPU results back failed: {0}")]
    Readback(String),
    #[error("{0}")]
    BadOption(String),
    #[error(transparent)]
    Core(#[from] caustics_core::Error),
}
