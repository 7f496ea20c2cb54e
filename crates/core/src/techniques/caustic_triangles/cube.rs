//! The light cube map of a point light (paper 4, §4.2 and §4.3), CPU twin of
//! `caustics-gpu`'s `caustic_triangles` cube passes (`caustic_triangles/cube.wgsl`,
//! `shadow.wgsl`).
//!
//! The paper draws the caustic triangles "onto the light cube map faces": a cube map centred at
//! the light, one face per 90° frustum, so that the camera pass can find the caustic of a shaded
//! point from the direction it is seen in from the light, and the same cube map serves as the
//! shadow map. Per texel it holds
//! - `Σ E` and `Σ E d` of the caustic triangles covering the texel centre's direction: `E` the
//!   vertex irradiances of [`super::irradiance_pass`] (floor units, the receiver's irradiance),
//!   Gouraud shaded *on the receiver* (a cube face's perspective projection with perspective-correct
//!   interpolation is linear interpolation on the floor triangle), `d` the distance from the light
//!   to the receiver point. `Σ E d / Σ E` is the caustic's receiver distance, what the camera pass's
//!   distance test compares with (the caustic lights the point where the photons landed, not one in
//!   front of or behind it in the same direction: no light leak);
//! - the distance from the light to the first surface in the texel centre's direction (glass,
//!   diffuse occluder or floor): the shadow map of the direct light.
//!
//! Texel layout and face convention are the distance map's ([`super::distance_map`]): texel
//! `(face, row, col)` at index `(face C + row) C + col`, direction [`texel_dir`].
//!
//! The texel's solid angle, the distance and the cosine that turn power per cube-map area into the
//! receiver's irradiance cancel against the same factors in the triangle's projected area: we measure
//! `ΔA` on the receiver itself (the photon hits are floor points), so `E = ΔΦ / ΔA` is already the
//! receiver's irradiance and the cube map only has to carry it.
//!
//! For the sun, the light cube map of a light at infinity degenerates (every texel of a face sees
//! the same direction), so the technique keeps the floor map of [`super::triangles_pass`].

use glam::DVec3;

use super::CausticTrianglesSetup;
use super::distance_map::{Crossing, DistanceMap, face_st, texel_dir};

use crate::parallel::prelude::*;

/// Marks "no surface" in the shadow distances.
pub const FAR: f32 = f32::MAX;

/// The light cube map (see the module docs).
#[derive(Clone, Debug)]
pub struct LightCube {
    /// Texels per face side, `C` (the `light_cube` parameter).
    pub resolution: usize,
    /// The light, the cube map's centre.
    pub position: DVec3,
    /// `(Σ E, Σ E d)` per texel.
    pub caustic: Vec<[f32; 2]>,
    /// Distance to the first surface per texel, [`FAR`] where none.
    pub shadow: Vec<f32>,
}

/// `(S, T, W)` of `d` in face `face`'s frame: `S / W`, `T / W` are the face coordinates `(s, t)`
/// and `W > 0` in front of the face. The GPU's clip position is `(S, −T, W / 2, W)`.
pub fn face_local(face: usize, d: DVec3) -> DVec3 {
    let sign = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    match face / 2 {
        0 => DVec3::new(d.y, d.z, sign * d.x),
        1 => DVec3::new(d.z, d.x, sign * d.y),
        _ => DVec3::new(d.x, d.y, sign * d.z),
    }
}

impl LightCube {
    /// An empty light cube map centred at the light `position`: no caustic, every shadow distance
    /// [`FAR`].
    pub fn new(resolution: usize, position: DVec3) -> Self {
        let n = 6 * resolution * resolution;
        LightCube {
            resolution,
            position,
            caustic: vec![[0.0; 2]; n],
            shadow: vec![FAR; n],
        }
    }

    /// The texel whose centre is nearest to direction `d`.
    pub fn texel_of(&self, d: DVec3) -> usize {
        let c = self.resolution;
        let (face, s, t) = face_st(d);
        let col = (((s + 1.0) * 0.5 * c as f64).floor() as i64).clamp(0, c as i64 - 1) as usize;
        let row = (((t + 1.0) * 0.5 * c as f64).floor() as i64).clamp(0, c as i64 - 1) as usize;
        (face * c + row) * c + col
    }
}

/// Add one Gouraud-shaded floor triangle (vertices `x`, values `e`) into every face it covers,
/// as the rasteriser does with the face's perspective projection: a texel centre's direction `d`
/// is inside when `d = Σ αᵢ (xᵢ − light)` with every `αᵢ ≥ 0` (homogeneous rasterisation; no
/// clipping needed for vertices behind a face), and `αᵢ / Σ α` are its perspective-correct
/// barycentrics.
fn raster_cube_triangle(cube: &mut LightCube, x: [DVec3; 3], e: [f64; 3]) {
    let c = cube.resolution;
    let v = x.map(|p| p - cube.position);
    let det = v[0].dot(v[1].cross(v[2]));
    if det == 0.0 || !det.is_finite() {
        return;
    }
    let cr = [v[1].cross(v[2]), v[2].cross(v[0]), v[0].cross(v[1])];
    let dist = v.map(|p| p.length());
    for face in 0..6 {
        let l = v.map(|p| face_local(face, p));
        if l.iter().all(|p| p.z <= 0.0) {
            continue;
        }
        let (mut j0, mut j1, mut i0, mut i1) = (0i64, c as i64 - 1, 0i64, c as i64 - 1);
        if l.iter().all(|p| p.z > 0.0) {
            let px = l.map(|p| {
                (
                    (p.x / p.z + 1.0) * 0.5 * c as f64,
                    (p.y / p.z + 1.0) * 0.5 * c as f64,
                )
            });
            let lo_x = px.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
            let hi_x = px.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
            let lo_y = px.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
            let hi_y = px.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
            j0 = j0.max((lo_x - 0.5).ceil() as i64);
            j1 = j1.min((hi_x - 0.5).floor() as i64);
            i0 = i0.max((lo_y - 0.5).ceil() as i64);
            i1 = i1.min((hi_y - 0.5).floor() as i64);
        }
        for row in i0.max(0)..=i1 {
            for col in j0.max(0)..=j1 {
                let d = texel_dir(face, row as usize, col as usize, c);
                let a = cr.map(|n| d.dot(n) / det);
                if a.iter().any(|&a| a < 0.0) {
                    continue;
                }
                let sum = a[0] + a[1] + a[2];
                if sum <= 0.0 {
                    continue;
                }
                let b = a.map(|a| a / sum);
                let ev = b[0] * e[0] + b[1] * e[1] + b[2] * e[2];
                let dv = b[0] * dist[0] + b[1] * dist[1] + b[2] * dist[2];
                let t = &mut cube.caustic[(face * c + row as usize) * c + col as usize];
                t[0] += ev as f32;
                t[1] += (ev * dv) as f32;
            }
        }
    }
}

/// Caustic reconstruction into the light cube map (§4.2): the same two triangles per valid quad
/// as [`super::triangles_pass`], their floor-hit vertices projected from the light onto the cube
/// faces, added into `cube` (several generators add into one cube map).
pub fn cube_triangles_pass(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    irradiance: &[f32],
    cube: &mut LightCube,
) {
    for (x, e, _) in super::merge::drawn_quads(setup, photons, irradiance) {
        let [a, b, c, d] = x.map(|x| DVec3::new(x.x, x.y, 0.0));
        raster_cube_triangle(cube, [a, b, c], [e[0], e[1], e[2]]);
        raster_cube_triangle(cube, [a, c, d], [e[0], e[2], e[3]]);
    }
}

/// Where the ray `origin + t d` (unit `d`) is inside the distance map's sphere: `[t0, t1]`,
/// `t0 ≥ 0`, or `None`.
pub fn sphere_span(dm: &DistanceMap, origin: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let oc = origin - dm.centre;
    let b = oc.dot(d);
    let disc = b * b - (oc.length_squared() - dm.radius * dm.radius);
    if disc <= 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let t1 = -b + s;
    (t1 > 0.0).then_some(((-b - s).max(0.0), t1))
}

/// Distance from the light along `d` to the first surface: the floor, or any surface (glass or
/// diffuse) of this generator's distance map, whichever is nearer than `best`.
pub fn first_surface(
    setup: &CausticTrianglesSetup,
    dm: &DistanceMap,
    light: DVec3,
    d: DVec3,
    best: f64,
) -> f64 {
    let floor = if d.z < 0.0 {
        -light.z / d.z
    } else {
        f64::INFINITY
    };
    let mut best = best.min(floor);
    if let Some((t0, t1)) = sphere_span(dm, light, d)
        && t0 < best
        && let Some((t, _)) = dm.trace(
            light + d * t0,
            d,
            0.0,
            t1.min(best) - t0,
            Crossing::Entering,
            setup.linear_steps,
            setup.secant_iterations,
        )
    {
        best = best.min(t0 + t);
    }
    best
}

/// The shadow distances of `cube` (§4.3, "the light cube map as a shadow map"): per texel the
/// nearest surface of the floor and of every generator's distance map.
pub fn shadow_pass(generators: &[(&CausticTrianglesSetup, &DistanceMap)], cube: &mut LightCube) {
    let c = cube.resolution;
    let light = cube.position;
    cube.shadow = (0..6 * c * c)
        .into_par_iter()
        .map(|k| {
            let (face, row, col) = (k / (c * c), (k / c) % c, k % c);
            let d = texel_dir(face, row, col, c);
            let best = generators.iter().fold(f64::INFINITY, |b, (s, dm)| {
                first_surface(s, dm, light, d, b)
            });
            if best.is_finite() { best as f32 } else { FAR }
        })
        .collect();
}
