//! Pass 2 (Fig. 6): each pixel sums, over the `M + 1` rows around it, the channel that the row
//! wrote for it, then the absorption. GPU twin: `pass2.wgsl`, a fragment shader.

use crate::map::CausticsMap;

use super::YukselSetup;

/// Pass 2 (Fig. 6) for the map's rows `phase` modulo `2^level`: map pixel `(i, j)` sums channel `k`
/// of pass-1 row `i / 2^level + M − k`, then applies the absorption (the shift cancels: that row
/// holds the level's sample row `i / 2^level − (k − M/2 − shift.y)`).
pub fn pass2(setup: &YukselSetup, p1: &[f32], phase: usize, map: &mut CausticsMap) {
    let w = setup.width;
    let m = setup.region.m;
    let f = 1usize << setup.region.level;
    let ch = m + 1;
    let a = setup.attenuation;
    for i in (phase..setup.height).step_by(f) {
        for j in 0..w {
            let mut e = 0.0f32;
            for k in 0..ch {
                let r = i / f + m - k;
                e += p1[(r * w + j) * ch + k];
            }
            map.texels[i * w + j] = [e * a.x as f32, e * a.y as f32, e * a.z as f32];
        }
    }
}
