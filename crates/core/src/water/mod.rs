//! Water surfaces. Every source gives, at a time `t`, a [`Surface`]: the displacement `h(x, y)` of the
//! water from its rest level and its exact gradient, so that refraction uses the true normal. Sources
//! that are periodic over the scene's square say so, and the reference and the techniques then wrap.
//!
//! - [`waves::Waves`]: a sum of directional sine waves with deep-water dispersion.
//! - [`procedural::Procedural`]: the 5-octave wave function of paper 2 with its analytic gradient.
//! - [`ocean::Ocean`]: a Tessendorf FFT ocean (Phillips spectrum), sampled on a grid.
//! - [`ripple::Ripples`]: the interactive discrete wave equation with damping and drops.
//! - a height field read from a file ([`crate::grid::Grid::load`]).

pub mod ocean;
pub mod procedural;
pub mod ripple;
pub mod slopes;
pub mod waves;

use glam::DVec2;

use crate::grid::{Edge, Grid};

/// A water surface frozen at one instant: the displacement from rest and its gradient at any point of
/// the plane. Points outside the scene square follow the surface's edge rule (periodic or clamped).
pub trait Surface: Send + Sync {
    /// The displacement from the rest level at horizontal point `p`, world units (positive up).
    fn height(&self, p: DVec2) -> f64;
    /// `(∂h/∂x, ∂h/∂y)` at `p`: the exact derivative of [`Surface::height`], dimensionless.
    fn gradient(&self, p: DVec2) -> DVec2;
    /// Both at once; override where they share work.
    fn height_gradient(&self, p: DVec2) -> (f64, DVec2) {
        (self.height(p), self.gradient(p))
    }
    /// The `(cols, rows)` of the sampled grid behind the surface, if it is one: the finest detail
    /// it holds, which the final image's filtered normals start from ([`slopes::SlopePyramid`]).
    fn lattice(&self) -> Option<(usize, usize)> {
        None
    }
}

/// The still surface.
pub struct Flat;

impl Surface for Flat {
    fn height(&self, _: DVec2) -> f64 {
        0.0
    }
    fn gradient(&self, _: DVec2) -> DVec2 {
        DVec2::ZERO
    }
}

/// A sampled height field over `[0, size]²` read through the bicubic interpolant of [`Grid::sample`].
pub struct GridSurface {
    /// The displacements from rest, world units, sample `(i, j)` at the map-texel centre.
    pub grid: Grid,
    /// Side of the square the grid covers, world units.
    pub size: f64,
    /// Periodic (the water wraps) or clamped outside the square.
    pub edge: Edge,
}

impl Surface for GridSurface {
    fn height(&self, p: DVec2) -> f64 {
        self.grid.height(p, self.size, self.edge)
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.grid.sample(p, self.size, self.edge).1
    }
    fn height_gradient(&self, p: DVec2) -> (f64, DVec2) {
        self.grid.sample(p, self.size, self.edge)
    }
    fn lattice(&self) -> Option<(usize, usize)> {
        Some((self.grid.cols, self.grid.rows))
    }
}

/// Sample any surface on the caustics-map lattice (`(j + 0.5) size / cols`, ...), e.g. to hand it to a
/// GPU technique as a texture.
pub fn sample_grid(surface: &dyn Surface, cols: usize, rows: usize, size: f64) -> Grid {
    Grid::from_fn(cols, rows, |i, j| {
        surface.height(DVec2::new(
            (j as f64 + 0.5) * size / cols as f64,
            (i as f64 + 0.5) * size / rows as f64,
        )) as f32
    })
}

#[cfg(test)]
pub(crate) mod test_support {
    use super::*;

    /// Central finite differences of the height against the surface's own gradient.
    pub fn assert_gradient_matches_finite_differences(s: &dyn Surface, points: &[DVec2], tol: f64) {
        let e = 1e-5;
        for &p in points {
            let g = s.gradient(p);
            let fx = (s.height(p + DVec2::X * e) - s.height(p - DVec2::X * e)) / (2.0 * e);
            let fy = (s.height(p + DVec2::Y * e) - s.height(p - DVec2::Y * e)) / (2.0 * e);
            let scale = 1.0 + g.length();
            assert!(
                (g.x - fx).abs() < tol * scale && (g.y - fy).abs() < tol * scale,
                "at {p}: analytic {g}, finite differences ({fx}, {fy})"
            );
        }
    }
}
