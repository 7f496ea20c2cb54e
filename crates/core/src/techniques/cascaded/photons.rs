//! The photon pass (`photons.wgsl`, per cascade): each light texel's photon refracted, placed,
//! weighted and splatted into the cascade's screen-space caustic map, at a point or over its
//! footprint.

use glam::{DVec2, DVec3};

use super::{Brightness, CASCADES, CascadedSetup, Dispersion, FIXED_SCALE, Placement, Splat};
use crate::optics::{fresnel_transmittance, refract};

/// Sub-pixel steps of the footprint splat: a photon's position and its box's side are rounded to
/// 1/64 pixel and its shares computed in integers, so both twins give the same shares wherever f32
/// and f64 round the position to the same step.
pub const FOOTPRINT_SUBPIXELS: i64 = 64;
/// Largest side of a photon's footprint, pixels: its tent then spans 8 × 8 pixels (9 × 9 with the
/// straddle). Where a texel lights more floor than 4 × 4 pixels see, the tents no longer overlap
/// and the image shows the texels again.
pub const FOOTPRINT_MAX: f64 = 4.0;

/// One photon after refraction: where it lands, its incidence cosine and its path under water.
pub struct Photon {
    /// Where it lands, world coordinates: by the parameters' [`Placement`], or with the pool's walls
    /// the refracted ray's exact end on the floor or a wall.
    pub position: DVec3,
    /// Cosine of the sun's angle of incidence on the local water normal (for the Fresnel weight).
    pub cos_i: f64,
    /// Length of its refracted path from the water surface to `position`, world units (for the
    /// absorption).
    pub path: f64,
}

/// Refract the photon of a texel with IOR `ior` and place it (§3.4.1-3.4.2). `None` where the
/// terrain is above the water (dry land), the sun grazes the back of a wave, or on total internal
/// reflection.
pub fn place_photon(
    setup: &CascadedSetup,
    water: DVec3,
    normal: DVec3,
    terrain: DVec3,
    ior: f64,
) -> Option<Photon> {
    let l = setup.light;
    if terrain.z >= water.z {
        return None;
    }
    let cos_i = -l.dot(normal);
    if cos_i <= 0.0 {
        return None;
    }
    let t = refract(l, normal, 1.0 / ior)?;
    let position = if setup.walls && setup.terrain_range.is_none() {
        // Walls: the refracted ray's exact end on the floor or a wall (no water outside the pool).
        water + t * setup.box_hit(water, t)?
    } else {
        match setup.params.placement {
            Placement::Eq33 => water + t * ((terrain - water).dot(t) / t.length_squared()),
            Placement::Plane => water + t * ((water.z - terrain.z) / -t.z),
        }
    };
    Some(Photon {
        position,
        cos_i,
        path: (position - water).length(),
    })
}

/// The weight of a photon per channel, before the texel's flux (§3.4.3).
fn photon_weight(setup: &CascadedSetup, ph: &Photon, ior: f64, c: usize) -> f64 {
    let p = &setup.params;
    match p.brightness {
        Brightness::Ramps => {
            let d = setup.level - ph.position.z;
            let deep = ((p.max_depth - d) / p.max_depth).clamp(0.0, 1.0);
            let shallow = ((d - p.min_depth) / p.shallow_ramp).clamp(0.0, 1.0);
            p.c * deep * shallow
        }
        Brightness::Physical => {
            fresnel_transmittance(ph.cos_i, 1.0, ior) / setup.t_flat
                * (-setup.absorption[c] * ph.path).exp()
        }
    }
}

/// Screen-space caustic maps of all cascades: `CASCADES × height × width × 3` fixed-point sums.
pub fn screen_buffer_len(setup: &CascadedSetup) -> usize {
    CASCADES * setup.eye.width * setup.eye.height * 3
}

/// The sides `(x, y)`, in pixels, of the footprint of a photon of cascade `k` at world point `p`
/// that projects to `px`. Its area is the number of pixels its texel's floor covers,
/// `photon_flux(k) / (A N_z)` with `A N_z` the horizontal floor area of the pixel under `px`
/// (clamped to the screen) from the eye pass; its aspect is that of the screen-space bounding box of
/// the texel's floor parallelogram (edges `a = e_u du` and `b = (e_v − L e_v.z / L.z) dv`, both
/// horizontal, projected from `p`), since at grazing views a texel's floor is several times wider
/// than high on the screen. Each side is capped at [`FOOTPRINT_MAX`]; `(0, 0)` where that pixel sees
/// no floor (a point splat).
///
/// `photon_flux(k)` is the horizontal area of the texel's beam under flat water (a parallel beam
/// keeps its horizontal cross-section through a horizontal interface), so over flat water the boxes
/// of neighbouring photons tile the floor; a tilted floor changes both areas by the same `N_z`.
pub fn footprint_side(
    setup: &CascadedSetup,
    k: usize,
    eye: &[[f32; 4]],
    p: DVec3,
    px: DVec2,
) -> DVec2 {
    let (w, h) = (setup.eye.width as i64, setup.eye.height as i64);
    let x = (px.x.floor() as i64).clamp(0, w - 1) as usize;
    let y = (px.y.floor() as i64).clamp(0, h - 1) as usize;
    let e = eye[y * setup.eye.width + x];
    if e[3] == 0.0 {
        return DVec2::ZERO;
    }
    let pixels = setup.photon_flux(k) / (e[1] as f64 * e[3] as f64);
    let c = &setup.cascades[k];
    let a = setup.e_u * c.du;
    let b = (setup.e_v - setup.light * (setup.e_v.z / setup.light.z)) * c.dv;
    let (Some((pa, _)), Some((pb, _))) = (setup.eye.project(p + a), setup.eye.project(p + b))
    else {
        return DVec2::splat(pixels.sqrt().min(FOOTPRINT_MAX));
    };
    let (da, db) = (pa - px, pb - px);
    let aspect = ((da.x.abs() + db.x.abs()) / (da.y.abs() + db.y.abs()).max(1e-6)).clamp(1e-3, 1e3);
    DVec2::new((pixels * aspect).sqrt(), (pixels / aspect).sqrt()).min(DVec2::splat(FOOTPRINT_MAX))
}

/// Denominator of the tent's integer weights in [`splat_footprint`].
pub const TENT_WEIGHT: u32 = 4096;

/// `TENT_WEIGHT` times the integral of the unit-area tent of half-width `h` (sub-pixel steps) from
/// its left end to `t` steps from its centre, rounded down: 0 at `−h`, `TENT_WEIGHT` at `h`.
pub fn tent_cumulative(t: i64, h: i64) -> u32 {
    let den = 2 * h * h;
    let num = if t <= -h {
        0
    } else if t <= 0 {
        (t + h) * (t + h)
    } else if t < h {
        den - (h - t) * (h - t)
    } else {
        den
    };
    (TENT_WEIGHT as i64 * num / den) as u32
}

/// Add the fixed-point weights `q[c0..c1]` of a photon at pixel point `centre` over a separable
/// tent whose half-widths are `side` pixels, the footprint's sides from [`footprint_side`] (§3.4's
/// additive splat, with a footprint). A tent as wide as the photons' spacing sums to a constant
/// over a regular grid of photons (it is linear interpolation); a box of the spacing does so only
/// when the grid is aligned with the pixels, and leaves a moiré where the sun's texel grid is
/// rotated on the screen. The centre and half-widths are rounded to 1/[`FOOTPRINT_SUBPIXELS`]
/// pixel; each row's (and each pixel's) share of the tent is a difference of
/// [`tent_cumulative`]; the integer weight is split first over rows, then over each row's pixels,
/// as differences of `⌊q · cumulative share / TENT_WEIGHT⌋`, so the shares add up to `q` exactly and
/// both twins compute them in the same integers. Shares falling off the screen are dropped (as a
/// point splat drops a photon off the screen). `base` is the cascade's offset in `acc`.
#[allow(clippy::too_many_arguments)]
pub fn splat_footprint(
    width: usize,
    height: usize,
    base: usize,
    centre: DVec2,
    side: DVec2,
    q: [u32; 3],
    (c0, c1): (usize, usize),
    acc: &mut [u32],
) {
    let sub = FOOTPRINT_SUBPIXELS;
    let reach = FOOTPRINT_MAX + 1.0;
    if !(centre.x > -reach
        && centre.y > -reach
        && centre.x < width as f64 + reach
        && centre.y < height as f64 + reach)
    {
        return;
    }
    let steps =
        |side: f64| ((side * sub as f64).round() as i64).clamp(1, FOOTPRINT_MAX as i64 * sub);
    let (h_x, h_y) = (steps(side.x), steps(side.y));
    let c_x = (centre.x * sub as f64).floor() as i64;
    let c_y = (centre.y * sub as f64).floor() as i64;
    let d = TENT_WEIGHT as u64;
    let mut cum_y = 0u64;
    for j in (c_y - h_y).div_euclid(sub)..=(c_y + h_y - 1).div_euclid(sub) {
        let next_y = tent_cumulative(sub * (j + 1) - c_y, h_y) as u64;
        let row: [u64; 3] =
            std::array::from_fn(|c| q[c] as u64 * next_y / d - q[c] as u64 * cum_y / d);
        cum_y = next_y;
        if j < 0 || j >= height as i64 {
            continue;
        }
        let mut cum_x = 0u64;
        for i in (c_x - h_x).div_euclid(sub)..=(c_x + h_x - 1).div_euclid(sub) {
            let next_x = tent_cumulative(sub * (i + 1) - c_x, h_x) as u64;
            if i >= 0 && i < width as i64 {
                let at = base + (j as usize * width + i as usize) * 3;
                for c in c0..c1 {
                    let share = row[c] * next_x / d - row[c] * cum_x / d;
                    acc[at + c] = acc[at + c].wrapping_add(share as u32);
                }
            }
            cum_x = next_x;
        }
    }
}

/// Photon pass (§3.4) of cascade `k`: every texel's photon (or three under
/// [`Dispersion::Wavelength`]) is refracted, placed, weighted, projected into the eye and added in
/// fixed point to the pixel it falls in ([`Splat::Point`]) or over its footprint
/// ([`Splat::Footprint`], sized from the eye pass `eye`).
pub fn photons(
    setup: &CascadedSetup,
    k: usize,
    eye: &[[f32; 4]],
    gwater: &[[f32; 4]],
    gterrain: &[f32],
    acc: &mut [u32],
) {
    let n = setup.res;
    let l = setup.light;
    let (w, h) = (setup.eye.width, setup.eye.height);
    let base = k * w * h * 3;
    let mut splat = |ph: &Photon, c0: usize, c1: usize, ior: f64| {
        let Some((px, _)) = setup.eye.project(ph.position) else {
            return;
        };
        let q: [u32; 3] = std::array::from_fn(|c| {
            if (c0..c1).contains(&c) {
                (photon_weight(setup, ph, ior, c) * FIXED_SCALE + 0.5) as u32
            } else {
                0
            }
        });
        if setup.params.splat == Splat::Footprint {
            let side = footprint_side(setup, k, eye, ph.position, px);
            splat_footprint(w, h, base, px, side, q, (c0, c1), acc);
            return;
        }
        if px.x < 0.0 || px.y < 0.0 || px.x >= w as f64 || px.y >= h as f64 {
            return;
        }
        let at = base + ((px.y as usize) * w + px.x as usize) * 3;
        for c in c0..c1 {
            acc[at + c] = acc[at + c].wrapping_add(q[c]);
        }
    };
    for i in 0..n {
        for j in 0..n {
            let o = setup.ray_origin(k, i, j);
            let gw = gwater[i * n + j];
            let water = o + l * gw[0] as f64;
            let normal = DVec3::new(gw[1] as f64, gw[2] as f64, gw[3] as f64);
            let terrain = if setup.terrain_range.is_some() {
                o + l * gterrain[i * n + j] as f64
            } else {
                o + l * (-o.z / l.z)
            };
            if setup.params.dispersion == Dispersion::Wavelength {
                for c in 0..3 {
                    if let Some(ph) = place_photon(setup, water, normal, terrain, setup.ior[c]) {
                        splat(&ph, c, c + 1, setup.ior[c]);
                    }
                }
            } else if let Some(ph) = place_photon(setup, water, normal, terrain, setup.ior_mono) {
                splat(&ph, 0, 3, setup.ior_mono);
            }
        }
    }
}
