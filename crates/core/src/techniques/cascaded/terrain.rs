//! The terrain G-buffer pass (`terrain.wgsl`, per cascade, with a terrain only).

use super::CascadedSetup;
use crate::grid::Grid;

/// Terrain G-buffer pass (§3.3 "terrain position", §3.3.1): the light-view depth of the terrain
/// under each texel's (unrefracted) sun ray.
pub fn terrain_gbuffer(setup: &CascadedSetup, k: usize, terrain: Option<&Grid>) -> Vec<f32> {
    let n = setup.res;
    let mut out = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let o = setup.ray_origin(k, i, j);
            let s = setup.terrain_hit(terrain, o, setup.light).unwrap_or(-1.0);
            out.push(s as f32);
        }
    }
    out
}
