//! `caustics-web`: the built-in water scenes with every GPU technique, in a browser on WebGPU.
//!
//! The page is the viewer's GPU-resident frame with a canvas for a window: the same registry
//! ([`caustics_gpu::technique`]), the same [`Renderer`](caustics_gpu::renderer::Renderer) (water
//! source, up to two techniques, their final images, in one submission), the same orbit camera and
//! sun ([`caustics_core::orbit`]). Nothing is read back; a second submission's pass stretches each
//! side's image over its half of the canvas. `www/` holds the page and its script, which build
//! the technique menu from [`Page::techniques`] (the descriptors) and drive [`Page::frame`] from
//! `requestAnimationFrame`. `scripts/build-web` builds the site.
//!
//! Everything here is for `wasm32`; on other targets the crate is empty.
#![cfg(target_arch = "wasm32")]

mod blit;
mod page;
mod water;

pub use page::Page;
