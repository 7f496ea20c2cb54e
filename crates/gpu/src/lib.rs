//! `caustics-gpu`: the GPU side of caustics on wgpu + WGSL. Device plumbing ([`GpuContext`]),
//! readback, per-pass timestamps, the shared WGSL math ([`shaders`]), and the GPU water simulations.
//! Each technique lives in its own module with one WGSL file per pass; its CPU twin lives in
//! `caustics-core`.
//!
//! In your own wgpu code: your device, your water (an `R32Float` texture of heights in metres),
//! one technique named by its spec string; the map it writes is a texture your passes read
//! (relative irradiance, 1 under flat water). `examples/minimal.rs` draws a floor with it.
//!
//! ```no_run
//! use caustics_gpu::core::scene::WaterOnly;
//! use caustics_gpu::{GpuContext, WaterTextures, registry, wgpu};
//!
//! # fn frame(
//! #     instance: wgpu::Instance,
//! #     adapter: wgpu::Adapter,
//! #     device: wgpu::Device,
//! #     queue: wgpu::Queue,
//! #     heights: &wgpu::Texture,
//! # ) -> Result<(), Box<dyn std::error::Error>> {
//! let ctx = GpuContext::shared(instance, adapter, device, queue);
//! // A 4 m square of water 1 m deep over a flat floor, its caustics map 256² texels.
//! let scene = WaterOnly::new(4.0, 1.0).map(256).scene()?;
//! let mut technique = registry::from_spec(&ctx, "yuksel:n=15")?;
//! technique.configure(&ctx, &scene, &WaterTextures::of(heights))?;
//! // Bind this view in your pass.
//! let map = technique.output().expect("configured").texture().create_view(&Default::default());
//! // Each frame: the technique's passes, in your encoder, before your own.
//! technique.update(&ctx, &scene)?;
//! let mut encoder = ctx.device.create_command_encoder(&Default::default());
//! technique.encode(&mut encoder, None);
//! ctx.queue.submit([encoder.finish()]);
//! # let _ = map;
//! # Ok(())
//! # }
//! ```
//!
//! # Features
//!
//! - `vulkan`, `metal`, `dx12` (default) and `gles`: wgpu's back ends. An application that
//!   chooses them in its own `wgpu` dependency (Bevy does) turns default features off.
//! - `validation`: the Khronos validation layer under `CAUSTICS_VALIDATION=1` (through `ash`);
//!   without it that variable is refused by name.

#![warn(missing_docs)]

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
/// The Vulkan validation layer: native only (a browser's WebGPU validates on its own), with the
/// `validation` feature.
#[cfg(all(feature = "validation", not(target_arch = "wasm32")))]
pub mod validation;
#[cfg(all(not(feature = "validation"), not(target_arch = "wasm32")))]
#[path = "validation_off.rs"]
mod validation;
pub mod volumes;
pub mod water;
pub mod yuksel;

pub use context::traffic::{self, TrafficCounts};
pub use context::{GpuContext, GpuOptions, parse_backends};
pub use technique::{Output, Technique, WallsOutput, WaterTextures};
pub use timing::{GpuTimer, PassTime};

/// The versions this crate's API speaks: an application names `caustics_gpu::wgpu` and
/// `caustics_gpu::glam` (and the core crate's types) without matching them by hand.
pub use caustics_core::{self as core, glam, toml};
pub use wgpu;

/// Everything that can go wrong on the GPU side, each naming the problem.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter matched: none at all, none of the asked-for name, or none that can present to
    /// the window's surface.
    #[error("no GPU adapter found: wanted {wanted}; adapters present: {}", if seen.is_empty() { "none".to_string() } else { seen.join(", ") })]
    NoAdapter {
        /// What was asked for: an adapter whose name contains a given text, or any adapter (with
        /// wgpu's reason for finding none).
        wanted: String,
        /// Every adapter the instance enumerated, as "name (backend)".
        seen: Vec<String>,
    },
    /// The adapter was found but refused the device (or the validation layer could not be set up);
    /// holds the reason.
    #[error("the GPU adapter refused to create a device: {0}")]
    RequestDevice(String),
    /// A texture or buffer larger than the device's limits, refused before wgpu sees it.
    #[error("{what} of {size} is beyond what this GPU allows ({limit})")]
    TooLarge {
        /// What the resource was for, e.g. "caustic-triangles floor map".
        what: String,
        /// The size asked for, as text ("W x H" in texels, or "N bytes").
        size: String,
        /// The device's limit, as text in the same unit.
        limit: String,
    },
    /// The device was lost (a driver reset, a removed GPU, a crash, `destroy()`); holds the reason
    /// in words. No later frame on that device can recover.
    #[error("the GPU device was lost: {0}")]
    DeviceLost(String),
    /// An error wgpu or the validation layer reported since the last [`GpuContext::check`], or
    /// inputs that do not fit the frame they are given to; holds the messages.
    #[error("GPU validation error: {0}")]
    Validation(String),
    /// Mapping a buffer back to the CPU failed, or the data read back is not the size expected.
    #[error("reading GPU results back failed: {0}")]
    Readback(String),
    /// A parameter, option or environment variable the caller chose is not valid, or a call came in
    /// the wrong order; the message names it.
    #[error("{0}")]
    BadOption(String),
    /// An error of the core crate (scene, parameters, water), passed through.
    #[error(transparent)]
    Core(#[from] caustics_core::Error),
}
