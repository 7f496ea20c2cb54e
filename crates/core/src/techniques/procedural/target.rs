//! The target pass (`target.wgsl`, paper: the second Cg method): the texture variant's caustic per
//! texel of its fixed-size `target²` render target over the floor square, mip level 0.

use super::ProceduralSetup;
use super::common::SurfaceInput;
use super::screen::per_pixel;

/// Texture variant, the target pass: [`per_pixel`] at the target's size, `target²` texels, row 0 at
/// y = 0.
pub fn target_pass(setup: &ProceduralSetup, water: &SurfaceInput) -> Vec<[f32; 3]> {
    per_pixel(setup, water, setup.target, setup.target)
}
