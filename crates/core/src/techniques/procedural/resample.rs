//! The resample pass (`resample.wgsl`): the map reads the texture variant's mip chain at its
//! pixels' centres, trilinearly with anisotropic taps ([`sampling_footprint`], Vulkan's LOD rule).

use glam::{DVec2, DVec3};

use super::ProceduralSetup;
use crate::map::CausticsMap;
use crate::parallel::prelude::*;

/// The sampler's level of detail and anisotropic taps for reading a `target²` texture into a
/// `width x height` map: `(λ, taps, major axis is x)`. The CPU twin's reading of Vulkan's rule for
/// an anisotropic sampler (the hardware's filter itself is implementation-defined): with `ρ_x`,
/// `ρ_y` the footprint of one map texel in target texels, `η = min(ρ_max / ρ_min, anisotropy)`,
/// `λ = log₂(ρ_max / η)` clamped to the chain, and `⌈η⌉` trilinear taps spread over the footprint's
/// major axis; a footprint smaller than a texel both ways is magnified: one bilinear tap of level 0.
pub fn sampling_footprint(setup: &ProceduralSetup) -> (f64, usize, bool) {
    let px = setup.target as f64 / setup.width as f64;
    let py = setup.target as f64 / setup.height as f64;
    let (major, minor) = (px.max(py), px.min(py));
    if major <= 1.0 {
        return (0.0, 1, px >= py);
    }
    let eta = (major / minor).min(setup.anisotropy as f64);
    let lambda = (major / eta)
        .log2()
        .clamp(0.0, (setup.mip_levels() - 1) as f64);
    (lambda, eta.ceil() as usize, px >= py)
}

fn bilinear(level: &[[f32; 3]], n: usize, uv: DVec2, wrap: bool) -> DVec3 {
    let t = uv * n as f64 - 0.5;
    let b = t.floor();
    let f = t - b;
    let fetch = |r: i64, c: i64| {
        let (r, c) = if wrap {
            (r.rem_euclid(n as i64), c.rem_euclid(n as i64))
        } else {
            (r.clamp(0, n as i64 - 1), c.clamp(0, n as i64 - 1))
        };
        let v = level[r as usize * n + c as usize];
        DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
    };
    let (c, r) = (b.x as i64, b.y as i64);
    let top = fetch(r, c).lerp(fetch(r, c + 1), f.x);
    let bottom = fetch(r + 1, c).lerp(fetch(r + 1, c + 1), f.x);
    top.lerp(bottom, f.y)
}

/// Trilinear lookup at `uv` (in [0, 1]² over the target) and level of detail `lambda`.
pub fn trilinear(
    levels: &[Vec<[f32; 3]>],
    target: usize,
    uv: DVec2,
    lambda: f64,
    wrap: bool,
) -> DVec3 {
    let l0 = lambda.floor() as usize;
    let f = lambda - l0 as f64;
    let a = bilinear(&levels[l0], target >> l0, uv, wrap);
    if f > 0.0 && l0 + 1 < levels.len() {
        a.lerp(bilinear(&levels[l0 + 1], target >> (l0 + 1), uv, wrap), f)
    } else {
        a
    }
}

/// Texture variant, the final pass: every map texel reads the mip chain at its centre with its
/// footprint (one map texel), trilinearly, with `taps` samples along the footprint's major axis.
pub fn resample(setup: &ProceduralSetup, levels: &[Vec<[f32; 3]>]) -> CausticsMap {
    let (w, h) = (setup.width, setup.height);
    let (lambda, taps, major_x) = sampling_footprint(setup);
    let axis = if major_x {
        DVec2::new(1.0 / w as f64, 0.0)
    } else {
        DVec2::new(0.0, 1.0 / h as f64)
    };
    let texels = (0..h)
        .into_par_iter()
        .flat_map_iter(|i| {
            (0..w).map(move |j| {
                let uv = DVec2::new((j as f64 + 0.5) / w as f64, (i as f64 + 0.5) / h as f64);
                let mut sum = DVec3::ZERO;
                for k in 0..taps {
                    let o = (k as f64 + 0.5) / taps as f64 - 0.5;
                    sum += trilinear(levels, setup.target, uv + axis * o, lambda, setup.wrap);
                }
                let v = sum / taps as f64;
                [v.x as f32, v.y as f32, v.z as f32]
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
