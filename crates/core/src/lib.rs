//! `caustics-core`: everything about water caustics that needs no GPU. The scene model, the water
//! surfaces, the optics shared by all techniques, the physically based reference that judges them,
//! the CPU twins of the GPU techniques, and a CPU renderer of the final image.

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
pub mod plot;
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
