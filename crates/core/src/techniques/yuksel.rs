//! Technique `yuksel`: "Fast Real-time Caustics from Height Fields" (Yuksel & Keyser), the CPU twin
//! of `caustics-gpu`'s `yuksel` module, pass for pass.
//!
//! # The method (paper §3-4)
//! Caustics are gathered backwards, from each caustics-map pixel `P_G` on the floor `z = 0`: the light
//! reaching it comes through a rectangle `R` of the water around the *illumination centre*
//! `P_C = P_G + h L'` (Eq. 1), where `L'` is the flat-water refracted light direction scaled to climb
//! the rest depth `h`. `R` is sampled with one sample per map pixel; each sample's area is refracted
//! with the sample's own normal, constant over the area (§3), and lands as a pixel-sized square
//! whose overlap `α` with the pixel is its contribution (Eq. 4).
//!
//! - **Pre-pass** (§5, "an additional pass before the first pass"): the refracted ray of every sample
//!   and its intersection with the floor, computed once and stored as the offset `δ` of the hit from
//!   the sample's own pixel centre (in pixels) and the flux the sample carries.
//! - **Pass 1** (Fig. 5): for each pixel, the `N` samples along x around its illumination centre; each
//!   adds its overlap `ax · ay` with the pixel and with the `M` pixels beside it along y to `M + 1`
//!   channels, written through multiple render targets on the GPU.
//! - **Pass 2** (Fig. 6): each pixel sums, over the `M + 1` rows around it, the channel that the row
//!   wrote for it.
//!
//! The paper's Fig. 6 reads channel `k` at row offset `k − M/2` while Fig. 5 stores in channel `k`
//! the contribution to row offset `k − M/2`: the two pair up only if pass 2 reads row `−(k − M/2)`,
//! which is what both our passes do (row `i − d` holds, in the channel of offset `d`, what it gave
//! row `i`).
//!
//! # Beyond the paper (options)
//! - The flux of a sample is `E_h A (1 + L_xy · ∇h / |L_z|)`: the pixel area `A` as the sun sees the
//!   tilted water. The paper's "average refracted light intensity through A_i" is this; it makes the
//!   map conserve flux, so its mean over a periodic tile equals the reference's.
//! - `fresnel`: each sample carries `T(θi) / T(θ0)`, its Fresnel transmittance relative to flat water.
//! - `absorption`: `exp(−K d0)` per RGB channel with `d0 = h / |L'_z|`, the flat-water path length,
//!   applied in pass 2 (the per-sample path length differs from it by the wave height over the depth,
//!   and keeping one channel per offset keeps the paper's channel budget).
//! - Samples beyond the map are computed too (the pre-pass covers `N − 1` extra columns and `M` extra
//!   rows): with wrapped edges they are the periodic copies of the samples across the edge, so every
//!   pixel gathers its whole region and the map tiles; with clamped edges they see the clamped
//!   surface, as the reference does.
//!
//! # Where it departs from the reference
//! Light deflected further than the region `R` (`N/2` pixels along x, `M/2` along y) is lost; each
//! sample's flux lands as a box the size of a pixel (a box filter) instead of the true, stretched or
//! squeezed footprint; and the normal is constant over each sample, so focusing within a pixel is
//! invisible (the caustic is blurred to the pixel scale). The sample spacing is the map's pixel, so
//! the map's resolution sets how finely the water is sampled, independent of the height field's.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::optics::{fresnel_transmittance, height_field_normal, refract};

/// The largest channel count: 8 render targets of 4 channels.
pub const MAX_CHANNELS: u32 = 32;

/// The technique's parameters, `[caustics.yuksel]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct YukselParams {
    /// Samples along x per pixel (odd): the region `R` is `N` pixels wide.
    pub n: u32,
    /// Neighbouring pixels along y (even): `M + 1` channels, the region `R` is `M + 1` pixels tall.
    pub m: u32,
    pub fresnel: bool,
    pub absorption: bool,
}

impl Default for YukselParams {
    fn default() -> Self {
        YukselParams {
            n: 7,
            m: 6,
            fresnel: true,
            absorption: true,
        }
    }
}

impl YukselParams {
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        let p: YukselParams = match table.get("yuksel") {
            Some(v) => v
                .clone()
                .try_into()
                .map_err(|e| Error::field("caustics.yuksel", e.to_string()))?,
            None => YukselParams::default(),
        };
        p.validate()?;
        Ok(p)
    }

    pub fn validate(&self) -> Result<()> {
        if self.n == 0 || self.n.is_multiple_of(2) || self.n > 31 {
            return Err(Error::field(
                "caustics.yuksel.n",
                format!(
                    "must be odd, between 1 and 31 (samples centred on the illumination centre), got {}",
                    self.n
                ),
            ));
        }
        if !self.m.is_multiple_of(2) || self.m + 1 > MAX_CHANNELS {
            return Err(Error::field(
                "caustics.yuksel.m",
                format!(
                    "must be even and at most {} (M + 1 channels, at most {MAX_CHANNELS}), got {}",
                    MAX_CHANNELS - 2,
                    self.m
                ),
            ));
        }
        Ok(())
    }

    pub fn channels(&self) -> u32 {
        self.m + 1
    }
}

/// Everything the passes share, derived once from the scene (the GPU side uploads the same numbers
/// as its uniform block).
#[derive(Clone, Debug, PartialEq)]
pub struct YukselSetup {
    pub width: usize,
    pub height: usize,
    pub n: usize,
    pub m: usize,
    /// Map pixel size, world units.
    pub pixel: DVec2,
    /// `h L'` in world units: from a floor point to its illumination centre on the rest surface.
    pub centre_offset: DVec2,
    pub light: DVec3,
    pub eta: f64,
    pub ior: f64,
    pub depth: f64,
    pub size: f64,
    pub wrap: bool,
    /// `T(θ0)`, or 1 without the Fresnel option.
    pub t_flat: f64,
    pub fresnel: bool,
    /// Per-channel `exp(−K d0)` applied in pass 2.
    pub attenuation: DVec3,
}

impl YukselSetup {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        params: &YukselParams,
        width: usize,
        height: usize,
        size: f64,
        depth: f64,
        ior: f64,
        absorption: DVec3,
        wrap: bool,
        light: DVec3,
    ) -> Result<Self> {
        params.validate()?;
        let light = super::check_inputs(width, height, light)?;
        let eta = 1.0 / ior;
        let t0 = refract(light, DVec3::Z, eta).expect("air to water never reflects totally");
        let d0 = depth / -t0.z;
        Ok(YukselSetup {
            width,
            height,
            n: params.n as usize,
            m: params.m as usize,
            pixel: DVec2::new(size / width as f64, size / height as f64),
            // Up the refracted ray from the floor to the rest surface: P_C = P_G − T0 · h / T0_z.
            centre_offset: -t0.truncate() * (depth / -t0.z),
            light,
            eta,
            ior,
            depth,
            size,
            wrap,
            t_flat: if params.fresnel {
                fresnel_transmittance(-light.z, 1.0, ior)
            } else {
                1.0
            },
            fresnel: params.fresnel,
            attenuation: if params.absorption {
                (-absorption * d0).exp()
            } else {
                DVec3::ONE
            },
        })
    }

    /// Pre-pass texture size: samples for `N − 1` extra columns and `M` extra rows.
    pub fn prepass_size(&self) -> (usize, usize) {
        (self.width + self.n - 1, self.height + self.m)
    }

    /// Pass-1 texture size: every map column, `M` extra rows.
    pub fn pass1_size(&self) -> (usize, usize) {
        (self.width, self.height + self.m)
    }
}

/// Pre-pass: for the sample of pre-pass texel `(r, c)` (map pixel `(r − M/2, c − N/2)`), the hit
/// offset `δ` in pixels and the flux it carries relative to flat water: `[δx, δy, flux, 0]`.
pub fn prepass(setup: &YukselSetup, heights: &Grid) -> Vec<[f32; 4]> {
    let (pw, ph) = setup.prepass_size();
    let edge = if setup.wrap { Edge::Wrap } else { Edge::Clamp };
    let (nh, mh) = ((setup.n / 2) as f64, (setup.m / 2) as f64);
    let l = setup.light;
    let mut out = Vec::with_capacity(pw * ph);
    for r in 0..ph {
        for c in 0..pw {
            let pixel_centre = DVec2::new(c as f64 - nh + 0.5, r as f64 - mh + 0.5) * setup.pixel;
            let s = pixel_centre + setup.centre_offset;
            let (h, grad) = heights.sample(s, setup.size, edge);
            let normal = height_field_normal(grad);
            let cos_i = -l.dot(normal);
            let seen = 1.0 + l.truncate().dot(grad) / -l.z;
            let t = refract(l, normal, setup.eta);
            let texel = match t {
                Some(t) if cos_i > 0.0 && seen > 0.0 => {
                    let z = setup.depth + h;
                    let hit = s + t.truncate() * (z / -t.z);
                    let delta = (hit - pixel_centre) / setup.pixel;
                    let fresnel = if setup.fresnel {
                        fresnel_transmittance(cos_i, 1.0, setup.ior) / setup.t_flat
                    } else {
                        1.0
                    };
                    [delta.x as f32, delta.y as f32, (seen * fresnel) as f32, 0.0]
                }
                _ => [0.0, 0.0, 0.0, 0.0],
            };
            out.push(texel);
        }
    }
    out
}

/// Pass 1 (Fig. 5): pass-1 texel `(r, j)` holds, in channel `k`, what the `N` samples of sample row
/// `r − M/2` around column `j` give map pixel `(r − M/2 + k − M/2, j)`. Channels are contiguous per
/// texel: `M + 1` floats each.
pub fn pass1(setup: &YukselSetup, pre: &[[f32; 4]]) -> Vec<f32> {
    let (w, h1) = setup.pass1_size();
    let (pw, _) = setup.prepass_size();
    let ch = setup.m + 1;
    let (n, mh) = (setup.n, setup.m as i64 / 2);
    let nh = n as i64 / 2;
    let mut out = vec![0.0f32; w * h1 * ch];
    for r in 0..h1 {
        for j in 0..w {
            let texel = &mut out[(r * w + j) * ch..(r * w + j + 1) * ch];
            for s in 0..n {
                let p = pre[r * pw + j + s];
                let ax = (1.0 - (s as f32 - nh as f32 + p[0]).abs()).max(0.0);
                if ax == 0.0 {
                    continue;
                }
                for (k, t) in texel.iter_mut().enumerate() {
                    let d = k as i64 - mh;
                    let ay = (1.0 - (p[1] - d as f32).abs()).max(0.0);
                    *t += ax * ay * p[2];
                }
            }
        }
    }
    out
}

/// Pass 2 (Fig. 6): map pixel `(i, j)` sums channel `k` of pass-1 row `i + M − k`, then applies the
/// absorption.
pub fn pass2(setup: &YukselSetup, p1: &[f32]) -> CausticsMap {
    let (w, h) = (setup.width, setup.height);
    let ch = setup.m + 1;
    let (h1, m) = (h + setup.m, setup.m);
    let mut map = CausticsMap::new(w, h, setup.size);
    let a = setup.attenuation;
    for i in 0..h {
        for j in 0..w {
            let mut e = 0.0f32;
            for k in 0..ch {
                let r = i + m - k;
                debug_assert!(r < h1);
                e += p1[(r * w + j) * ch + k];
            }
            map.texels[i * w + j] = [e * a.x as f32, e * a.y as f32, e * a.z as f32];
        }
    }
    map
}

/// The whole technique on the CPU: the surface sampled as `heights` over the map's square.
pub fn caustics(setup: &YukselSetup, heights: &Grid) -> CausticsMap {
    let pre = prepass(setup, heights);
    let p1 = pass1(setup, &pre);
    pass2(setup, &p1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup(params: &YukselParams, res: usize, light: DVec3) -> YukselSetup {
        YukselSetup::new(params, res, res, 1.0, 0.4, 1.333, DVec3::ZERO, true, light).unwrap()
    }

    #[test]
    fn flat_water_gives_one() {
        let s = setup(&YukselParams::default(), 32, DVec3::new(0.3, 0.1, -1.0));
        let m = caustics(&s, &Grid::new(16, 16));
        for t in &m.texels {
            assert!((t[0] - 1.0).abs() < 1e-5, "{}", t[0]);
        }
    }

    #[test]
    fn periodic_flux_is_conserved_when_the_region_holds_the_deflection() {
        let n = 64;
        let g = Grid::from_fn(n, n, |i, j| {
            let x = (j as f64 + 0.5) / n as f64;
            let y = (i as f64 + 0.5) / n as f64;
            (0.002 * (std::f64::consts::TAU * (2.0 * x + y)).sin()) as f32
        });
        let params = YukselParams {
            fresnel: false,
            ..Default::default()
        };
        let s = setup(&params, 64, DVec3::new(0.2, 0.1, -1.0));
        let m = caustics(&s, &g);
        let mean = m.texels.iter().map(|t| t[0] as f64).sum::<f64>() / m.texels.len() as f64;
        assert!((mean - 1.0).abs() < 1e-4, "mean {mean}");
        let max = m.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
        assert!(max > 1.05, "waves focus: {max}");
    }

    #[test]
    fn bad_n_and_m_are_named() {
        let e = YukselParams {
            n: 0,
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("caustics.yuksel.n"), "{e}");
        let e = YukselParams {
            m: 40,
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("caustics.yuksel.m"), "{e}");
        let e = YukselParams {
            m: 3,
            ..Default::default()
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(e.contains("even"), "{e}");
    }
}
