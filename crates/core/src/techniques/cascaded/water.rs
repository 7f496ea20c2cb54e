//! The water G-buffer pass (`water.wgsl`, per cascade).

use glam::DVec2;

use super::CascadedSetup;
use crate::grid::{Edge, Grid};
use crate::optics::height_field_normal;

/// Newton steps of the sun ray against the water surface.
pub const WATER_STEPS: u32 = 4;

/// Water G-buffer pass (§3.3 "water position" + "water normals", §3.3.1): texel `(i, j)` of cascade
/// `k` holds `[light-view depth, n.x, n.y, n.z]` of the water surface `z = level + h`, found by
/// [`WATER_STEPS`] Newton steps along the sun ray from the rest plane.
pub fn water_gbuffer(setup: &CascadedSetup, k: usize, water: &Grid) -> Vec<[f32; 4]> {
    let n = setup.res;
    let l = setup.light;
    let edge = if setup.wrap { Edge::Wrap } else { Edge::Clamp };
    let mut out = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let o = setup.ray_origin(k, i, j);
            let mut s = (setup.level - o.z) / l.z;
            let mut grad = DVec2::ZERO;
            for _ in 0..WATER_STEPS {
                let p = o + l * s;
                let (h, g) = water.sample(p.truncate(), setup.size, edge);
                grad = g;
                let f = p.z - setup.level - h;
                let df = l.z - g.dot(l.truncate());
                s -= f / df;
            }
            let nrm = height_field_normal(grad);
            out.push([s as f32, nrm.x as f32, nrm.y as f32, nrm.z as f32]);
        }
    }
    out
}
