//! The composition pass (`compose.wgsl`, once per frame): each pixel reads the cascade its eye
//! depth falls in.

use glam::DVec3;

use super::{CASCADES, CascadedFrame, CascadedSetup, FIXED_SCALE};

/// Which cascades a pixel at view depth `z` reads and with what weights (§3.5.1 + our blend band):
/// `(k, weight of k, weight of k + 1)`; `None` beyond the last cascade or where no floor is seen.
pub fn cascade_weights(setup: &CascadedSetup, z: f64) -> Option<(usize, f64, f64)> {
    if z <= 0.0 {
        return None;
    }
    let k = setup.cascades.iter().position(|c| z <= c.far)?;
    let far = setup.cascades[k].far;
    let prev = if k == 0 {
        setup.params.near
    } else {
        setup.cascades[k - 1].far
    };
    let band = setup.params.blend * (far - prev);
    if k + 1 < CASCADES && band > 0.0 && z > far - band {
        let t = (z - (far - band)) / band;
        Some((k, 1.0 - t, t))
    } else {
        Some((k, 1.0, 0.0))
    }
}

/// One cascade's irradiance at pixel `(x, y)` per channel.
fn cascade_value(setup: &CascadedSetup, acc: &[u32], k: usize, pixel: usize, area: f64) -> DVec3 {
    let at = (k * setup.eye.width * setup.eye.height + pixel) * 3;
    let s = setup.photon_flux(k) / (FIXED_SCALE * area);
    DVec3::new(acc[at] as f64, acc[at + 1] as f64, acc[at + 2] as f64) * s
}

/// Composition pass (§3.5): per pixel `[r, g, b, cascade]` of relative irradiance (1 under flat,
/// clear water on a horizontal floor), `cascade` the index read (plus the blend fraction).
pub fn compose(setup: &CascadedSetup, eye: &[[f32; 4]], acc: &[u32]) -> Vec<[f32; 4]> {
    eye.iter()
        .enumerate()
        .map(|(pixel, e)| {
            let Some((k, a, b)) = cascade_weights(setup, e[0] as f64) else {
                return [0.0, 0.0, 0.0, -1.0];
            };
            let area = e[1] as f64;
            let mut v = cascade_value(setup, acc, k, pixel, area) * a;
            if b > 0.0 {
                v += cascade_value(setup, acc, k + 1, pixel, area) * b;
            }
            [v.x as f32, v.y as f32, v.z as f32, (k as f64 + b) as f32]
        })
        .collect()
}

impl CascadedFrame {
    /// Cascade `k`'s own caustic map in relative irradiance (before composition).
    pub fn cascade_map(&self, setup: &CascadedSetup, k: usize) -> Vec<[f32; 3]> {
        self.eye
            .iter()
            .enumerate()
            .map(|(pixel, e)| {
                if e[3] == 0.0 {
                    return [0.0; 3];
                }
                let v = cascade_value(setup, &self.acc, k, pixel, e[1] as f64);
                [v.x as f32, v.y as f32, v.z as f32]
            })
            .collect()
    }
}
