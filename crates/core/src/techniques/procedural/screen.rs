//! The screen pass (`screen.wgsl`, paper: the first Cg method): the caustic at the centre of every
//! map pixel, at full resolution, no filtering. The texture variant's target pass evaluates the same
//! lattice at the target's size ([`super::target_pass`]).

use glam::DVec2;

use super::ProceduralSetup;
use super::common::{SurfaceInput, caustic_at};

use crate::parallel::prelude::*;

/// Per pixel: the caustic at the centre of every texel of a `width x height` lattice over the floor
/// square, row 0 at y = 0 (the screen pass at the map's size, the target pass at the target's).
pub fn per_pixel(
    setup: &ProceduralSetup,
    water: &SurfaceInput,
    width: usize,
    height: usize,
) -> Vec<[f32; 3]> {
    (0..height)
        .into_par_iter()
        .flat_map_iter(|i| {
            (0..width).map(move |j| {
                let p = DVec2::new(
                    (j as f64 + 0.5) / width as f64,
                    (i as f64 + 0.5) / height as f64,
                ) * setup.size;
                caustic_at(setup, water, p)
            })
        })
        .collect()
}
