//! The vertex pass (`vertex.wgsl`, paper: "Implementation Using OpenGL"): the caustic at every
//! vertex of a fine ground mesh ([`vertex_values`], the vertex shader's work), interpolated linearly
//! over its triangles into the map ([`rasterise`], the rasteriser's).

use glam::DVec2;

use super::ProceduralSetup;
use super::common::{SurfaceInput, caustic_at};
use crate::map::CausticsMap;
use crate::parallel::prelude::*;

/// Vertex variant, the vertex shader's work: the caustic at every vertex `(k, l)` of the mesh, at
/// `(k, l) size / mesh`, row-major over `l` (`(mesh + 1)²` values).
pub fn vertex_values(setup: &ProceduralSetup, water: &SurfaceInput) -> Vec<[f32; 3]> {
    let n = setup.mesh;
    (0..=n)
        .into_par_iter()
        .flat_map_iter(|l| {
            (0..=n).map(move |k| {
                let p = DVec2::new(k as f64, l as f64) / n as f64 * setup.size;
                caustic_at(setup, water, p)
            })
        })
        .collect()
}

/// Vertex variant, the rasteriser's work: the mesh's values interpolated linearly over its
/// triangles at every map pixel centre. Quad `(k, l)` is split along its diagonal from vertex
/// `(k, l)` to `(k + 1, l + 1)`; on the diagonal both triangles agree.
pub fn rasterise(setup: &ProceduralSetup, values: &[[f32; 3]]) -> CausticsMap {
    let n = setup.mesh;
    let (w, h) = (setup.width, setup.height);
    let at = |k: usize, l: usize| values[l * (n + 1) + k];
    let texels = (0..h)
        .into_par_iter()
        .flat_map_iter(|i| {
            (0..w).map(move |j| {
                let g = DVec2::new(
                    (j as f64 + 0.5) / w as f64 * n as f64,
                    (i as f64 + 0.5) / h as f64 * n as f64,
                );
                let (k, l) = (
                    (g.x.floor() as usize).min(n - 1),
                    (g.y.floor() as usize).min(n - 1),
                );
                let (fx, fy) = (g.x - k as f64, g.y - l as f64);
                let (v00, v10, v01, v11) = (at(k, l), at(k + 1, l), at(k, l + 1), at(k + 1, l + 1));
                std::array::from_fn(|c| {
                    let (a, b, d, e) = (v00[c] as f64, v10[c] as f64, v01[c] as f64, v11[c] as f64);
                    let v = if fx >= fy {
                        a + fx * (b - a) + fy * (e - b)
                    } else {
                        a + fy * (d - a) + fx * (e - d)
                    };
                    v as f32
                })
            })
        })
        .collect();
    CausticsMap {
        width: w,
        height: h,
        size: setup.size,
        texels,
    }
}
