//! The caustics techniques: the registry ([`REGISTRY`], one line per technique, each entry a
//! [`Descriptor`] beside its technique's code), the job every technique takes, and the CPU twin of
//! each (the oracle of its GPU implementation's tests and the fallback where no GPU adapter exists).
//!
//! The folder reads bottom-up: the job and what it makes ([`Job`], [`JobOutput`]) and the buffers'
//! kinds ([`buffers`]), then the description every technique is written against ([`describe`]),
//! then the techniques, then the registry that lists them with the reference
//! ([`registry`]). This file is the table of the folder; its re-exports keep the paths the front
//! ends use (`techniques::REGISTRY`, `techniques::find`, `techniques::Job`).

pub mod buffers;
pub mod cascaded;
pub mod caustic_triangles;
pub mod describe;
mod job;
pub mod procedural;
pub mod registry;
pub mod volumes;
pub mod yuksel;

pub use describe::{Descriptor, Input, check_inputs, floor_only_note};
pub use job::{Caustics, Job, JobOutput, SceneCaustics, heights_for, lattice_heights};
pub use registry::{ALIASES, REGISTRY, Spec, canonical, find, for_scene, names, reference};
