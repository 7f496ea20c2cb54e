//! `caustics-core`: everything about water caustics that needs no GPU. The scene model, the water
//! surfaces, the optics shared by all techniques, the physically based reference that judges them,
//! the CPU twins of the GPU techniques, and a CPU renderer of the final image.
//!
//! The reference on the built-in pool, the truth every technique is measured against (a caustics
//! map holds relative irradiance: 1 where flat, clear water would put the sun's light):
//!
//! ```
//! use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
//! use caustics_core::scene::Scene;
//!
//! let scene = Scene::builtin("pool")?;
//! let water = scene.water.as_ref().expect("the pool has water");
//! let surface = water.surface_at(0.0)?;
//! let input = ReferenceInput {
//!     width: 64,
//!     height: 64,
//!     ..ReferenceInput::from_scene(&scene, surface.as_ref())?
//! };
//! let map = reference(&input, &ReferenceOptions::default(), &|_done, _total| {})?;
//! let brightest = map.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
//! assert!(brightest > 1.0, "the ripples focus the sun");
//! # Ok::<(), caustics_core::Error>(())
//! ```
//!
//! # Features
//!
//! None is on by default, so an application that hands the GPU its own heights builds only what
//! it uses; the `caustics` tool turns on all three.
//!
//! - `formats`: height fields from `.npy`, `.exr` and 16-bit PNG files, maps written as `.npy`,
//!   `.exr` and PNG, albedo and light-map images, OBJ meshes. Without it, a scene that names such
//!   a file is refused with an error that names the feature.
//! - `fft`: the FFT ocean's CPU surface through rustfft. Without it the same sums are taken
//!   directly, `O(n³)` for an `n²` ocean (half a second at 512²).
//! - `parallel`: the reference, the CPU twins and the CPU renderer on every core (rayon). Without
//!   it they run on the calling thread, with the same results.

#![warn(missing_docs)]

pub mod bake;
pub mod cases;
pub mod error;
pub mod eye;
#[cfg(test)]
mod fixtures;
pub mod grid;
pub mod map;
pub mod mesh;
pub mod metrics;
pub mod optics;
pub mod orbit;
mod parallel;
pub mod plot;
mod random;
pub mod receivers;
pub mod reference;
pub mod render;
pub mod scene;
pub mod sky;
pub mod techniques;
pub mod tone_map;
pub mod walls;
pub mod water;

pub use error::{Error, Result};
/// The version of the vector types this crate's API takes.
pub use glam;
/// The version of the table type this crate's API takes (technique parameters).
pub use toml;
