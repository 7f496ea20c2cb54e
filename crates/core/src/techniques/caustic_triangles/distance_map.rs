//! Layered distance maps (paper §3; Umenhoffer, Patow & Szirmay-Kalos, GPU Gems 3 ch. 17): a cube
//! map around the caustic generator whose texels hold, per layer, the distance from the cube's
//! centre (the *reference point*) to a surface in the texel's direction, the surface normal, and its
//! material. Rays are traced against it by a linear search for a change of sign of
//! `|l| − |l'|` (undershooting to overshooting or back) followed by a secant search.
//!
//! # Layout (shared with `caustic_triangles/distance_map.wgsl`)
//! One `[f32; 4]` per texel, `(n.x, n.y, n.z, s)`, index `((layer · 6 + face) · C + row) · C + col`.
//! The material is the sign of `s`: `s > 0` the generator's glass at distance `s` (its index of
//! refraction is the generator's, in the uniform block: one generator per map), `s < 0` a diffuse
//! occluder at distance `−s`, `s = 0` no surface in this layer.
//!
//! Faces: 0 `+x`, 1 `−x`, 2 `+y`, 3 `−y`, 4 `+z`, 5 `−z`; on the faces of axis `a` the texel
//! coordinates run along the two other axes in the order (y, z), (z, x), (x, y):
//! `s = d[u] / |d[a]|`, `t = d[v] / |d[a]|`, column `(s + 1) C / 2 − ½`, row `(t + 1) C / 2 − ½`.
//!
//! # Building it (departure)
//! The paper renders the layers by rasterisation (depth peeling). Here each texel's ray from the
//! reference point is cast through the exact geometry (analytic sphere or mesh BVH, and the
//! occluders' BVHs) and its first `layers` hits, in order of distance, fill layers 0, 1, …: the
//! depth-peeling order the paper names for the general case. It is built once on the CPU for a
//! rigid generator and uploaded.

use glam::DVec3;

use super::scene::GlassScene;

use crate::parallel::prelude::*;

/// A generator's layered distance map (see the module docs): per cube-map texel and layer, the
/// distance, normal and material of a surface around the reference point.
#[derive(Clone, Debug)]
pub struct DistanceMap {
    /// Texels per cube-face side, `C`.
    pub resolution: usize,
    /// Layers: a texel's ray keeps its first `layers` surfaces, nearest in layer 0 (at most
    /// [`MAX_LAYERS`](super::MAX_LAYERS) are searched).
    pub layers: usize,
    /// The reference point.
    pub centre: DVec3,
    /// Radius of the sphere around the reference point holding every stored surface (the search
    /// range of a ray).
    pub radius: f64,
    /// `(n.x, n.y, n.z, s)` per texel, indexed `((layer · 6 + face) · C + row) · C + col`: `s > 0`
    /// glass at distance `s` from the reference point, `s < 0` an occluder at `−s`, 0 no surface.
    pub texels: Vec<[f32; 4]>,
}

/// Which glass crossings a traced ray stops at (diffuse surfaces always stop it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// Entering the glass (a ray outside it).
    Entering,
    /// Leaving the glass (a ray inside it).
    Leaving,
    /// None: the glass is looked through (the camera pass's secondary rays).
    DiffuseOnly,
}

/// A surface found in the map.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Distance from the reference point to the surface, world units (not the ray parameter).
    pub distance: f64,
    /// Unit surface normal, bilinear between texels like the distance (outward on the glass).
    pub normal: DVec3,
    /// The generator's glass; `false` for a diffuse occluder.
    pub glass: bool,
}

/// The face and `(s, t) ∈ [−1, 1]²` of a direction.
pub fn face_st(d: DVec3) -> (usize, f64, f64) {
    let a = d.abs();
    let (face, m, s, t) = if a.x >= a.y && a.x >= a.z {
        (if d.x >= 0.0 { 0 } else { 1 }, a.x, d.y, d.z)
    } else if a.y >= a.z {
        (if d.y >= 0.0 { 2 } else { 3 }, a.y, d.z, d.x)
    } else {
        (if d.z >= 0.0 { 4 } else { 5 }, a.z, d.x, d.y)
    };
    (face, s / m, t / m)
}

/// Unit direction through the centre of texel `(row, col)` of `face`.
pub fn texel_dir(face: usize, row: usize, col: usize, c: usize) -> DVec3 {
    let s = (col as f64 + 0.5) / c as f64 * 2.0 - 1.0;
    let t = (row as f64 + 0.5) / c as f64 * 2.0 - 1.0;
    let sign = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    let d = match face / 2 {
        0 => DVec3::new(sign, s, t),
        1 => DVec3::new(t, sign, s),
        _ => DVec3::new(s, t, sign),
    };
    d.normalize()
}

impl DistanceMap {
    /// Cast the ray of every texel from the generator's bounding-box centre through the generator and
    /// the occluders and keep its first `layers` hits.
    pub fn build(scene: &GlassScene, resolution: usize, layers: usize) -> DistanceMap {
        let c = resolution.max(2);
        let layers = layers.max(1);
        let (lo, hi) = scene.generator.bounds();
        let centre = 0.5 * (lo + hi);
        let eps = 1e-7 * (hi - lo).length().max(1e-9);
        // Per (face, row): the texels of that row, every layer.
        let rows: Vec<Vec<[f32; 4]>> = (0..6 * c)
            .into_par_iter()
            .map(|fr| {
                let (face, row) = (fr / c, fr % c);
                let mut out = vec![[0.0f32; 4]; c * layers];
                for col in 0..c {
                    let d = texel_dir(face, row, col, c);
                    let mut t = 0.0;
                    for layer in 0..layers {
                        let o = centre + d * (t + eps);
                        let g = scene.generator.intersect(o, d, f64::INFINITY);
                        let occ = scene
                            .occluders
                            .iter()
                            .filter_map(|oc| oc.bvh.intersect(&oc.mesh, o, d, f64::INFINITY));
                        let mut best: Option<(f64, DVec3, bool)> = g.map(|(s, n)| (s, n, true));
                        for (s, n) in occ {
                            if best.is_none_or(|b| s < b.0) {
                                best = Some((s, n, false));
                            }
                        }
                        let Some((s, n, glass)) = best else { break };
                        t += eps + s;
                        let sd = if glass { t } else { -t };
                        out[layer * c + col] = [n.x as f32, n.y as f32, n.z as f32, sd as f32];
                    }
                }
                out
            })
            .collect();
        let mut texels = vec![[0.0f32; 4]; 6 * c * c * layers];
        let mut radius = 0.0f64;
        for (fr, row) in rows.iter().enumerate() {
            let (face, r) = (fr / c, fr % c);
            for layer in 0..layers {
                for col in 0..c {
                    let v = row[layer * c + col];
                    radius = radius.max(v[3].abs() as f64);
                    texels[((layer * 6 + face) * c + r) * c + col] = v;
                }
            }
        }
        DistanceMap {
            resolution: c,
            layers,
            centre,
            // A texel's worth of margin: a ray must start outside every surface.
            radius: radius * (1.0 + 4.0 / c as f64),
            texels,
        }
    }

    fn texel(&self, layer: usize, face: usize, row: usize, col: usize) -> [f32; 4] {
        let c = self.resolution;
        self.texels[((layer * 6 + face) * c + row) * c + col]
    }

    /// The surface of `layer` in direction `d` (from the reference point): bilinear within the
    /// face where the four texels around `d` hold the same material, the nearest texel otherwise
    /// (silhouettes, material boundaries, the face's outer half texel).
    pub fn sample(&self, layer: usize, d: DVec3) -> Option<Surface> {
        let c = self.resolution;
        let (face, s, t) = face_st(d);
        let x = (s + 1.0) * 0.5 * c as f64 - 0.5;
        let y = (t + 1.0) * 0.5 * c as f64 - 0.5;
        let x0 = (x.floor() as i64).clamp(0, c as i64 - 2) as usize;
        let y0 = (y.floor() as i64).clamp(0, c as i64 - 2) as usize;
        let fx = (x - x0 as f64).clamp(0.0, 1.0);
        let fy = (y - y0 as f64).clamp(0.0, 1.0);
        let q = [
            self.texel(layer, face, y0, x0),
            self.texel(layer, face, y0, x0 + 1),
            self.texel(layer, face, y0 + 1, x0),
            self.texel(layer, face, y0 + 1, x0 + 1),
        ];
        let same = q.iter().all(|v| v[3] > 0.0) || q.iter().all(|v| v[3] < 0.0);
        let v = if same {
            let wts = [
                (1.0 - fx) * (1.0 - fy),
                fx * (1.0 - fy),
                (1.0 - fx) * fy,
                fx * fy,
            ];
            let mut acc = [0.0f64; 4];
            for (v, w) in q.iter().zip(wts) {
                for k in 0..4 {
                    acc[k] += v[k] as f64 * w;
                }
            }
            acc
        } else {
            let k = (if fy >= 0.5 { 2 } else { 0 }) + (if fx >= 0.5 { 1 } else { 0 });
            q[k].map(|x| x as f64)
        };
        if v[3] == 0.0 {
            return None;
        }
        Some(Surface {
            distance: v[3].abs(),
            normal: DVec3::new(v[0], v[1], v[2]).normalize_or_zero(),
            glass: v[3] > 0.0,
        })
    }

    /// `|l| − |l'|` of `layer` at the point `p`: negative in front of the stored surface
    /// (undershooting), positive behind it (overshooting); `None` where the layer is empty.
    fn offset(&self, layer: usize, p: DVec3) -> Option<(f64, Surface)> {
        let l = p - self.centre;
        let len = l.length();
        self.sample(layer, l / len.max(1e-30))
            .map(|s| (len - s.distance, s))
    }

    /// Trace `x + R d`, `d ∈ [d0, d1]` (unit `R`) against every layer: a linear search of
    /// `linear_steps` steps for the first step where `|l| − |l'|` changes sign in some layer, then
    /// `secant_iterations` secant steps in that bracket. A glass hit counts only if the ray crosses
    /// it the way `mode` says; the search then goes on. Returns the ray parameter and the surface
    /// there.
    #[allow(clippy::too_many_arguments)]
    pub fn trace(
        &self,
        x: DVec3,
        r: DVec3,
        d0: f64,
        d1: f64,
        mode: Crossing,
        linear_steps: u32,
        secant_iterations: u32,
    ) -> Option<(f64, Surface)> {
        if d1 <= d0 {
            return None;
        }
        let steps = linear_steps.max(1);
        let dd = (d1 - d0) / steps as f64;
        let tol = 8.0 / self.resolution as f64;
        let mut prev: [Option<f64>; 8] = [None; 8];
        let layers = self.layers.min(8);
        for (k, p) in prev.iter_mut().enumerate().take(layers) {
            *p = self.offset(k, x + r * d0).map(|o| o.0);
        }
        for step in 1..=steps {
            let d_hi = d0 + dd * step as f64;
            let d_lo = d_hi - dd;
            let mut best: Option<(f64, Surface)> = None;
            for (k, pk) in prev.iter_mut().enumerate().take(layers) {
                let cur = self.offset(k, x + r * d_hi).map(|o| o.0);
                if let (Some(f_lo), Some(f_hi)) = (*pk, cur)
                    && ((f_lo < 0.0) != (f_hi < 0.0))
                    && let Some(hit) =
                        self.secant(k, x, r, (d_lo, f_lo), (d_hi, f_hi), secant_iterations, tol)
                {
                    let crossing_ok = !hit.1.glass
                        || match mode {
                            Crossing::Entering => r.dot(hit.1.normal) < 0.0,
                            Crossing::Leaving => r.dot(hit.1.normal) >= 0.0,
                            Crossing::DiffuseOnly => false,
                        };
                    if crossing_ok && best.is_none_or(|b| hit.0 < b.0) {
                        best = Some(hit);
                    }
                }
                *pk = cur;
            }
            if best.is_some() {
                return best;
            }
        }
        None
    }

    #[allow(clippy::too_many_arguments)]
    fn secant(
        &self,
        layer: usize,
        x: DVec3,
        r: DVec3,
        (mut d_lo, mut f_lo): (f64, f64),
        (mut d_hi, mut f_hi): (f64, f64),
        iterations: u32,
        tol: f64,
    ) -> Option<(f64, Surface)> {
        let mut d = d_lo + (d_hi - d_lo) * f_lo / (f_lo - f_hi);
        for _ in 0..iterations {
            let (f, _) = self.offset(layer, x + r * d)?;
            if (f < 0.0) == (f_lo < 0.0) {
                d_lo = d;
                f_lo = f;
            } else {
                d_hi = d;
                f_hi = f;
            }
            if f_lo == f_hi {
                break;
            }
            d = d_lo + (d_hi - d_lo) * f_lo / (f_lo - f_hi);
        }
        let (f, s) = self.offset(layer, x + r * d)?;
        // A sign change across a jump of the layer (its surface changes) is no hit.
        (f.abs() <= tol * s.distance.max(1e-12)).then_some((d, s))
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;

    use super::super::scene::{FloorWindow, Shape};
    use super::*;

    fn sphere_scene() -> GlassScene {
        GlassScene::new(
            Shape::Sphere {
                centre: DVec3::new(0.1, 0.2, 0.5),
                radius: 0.3,
            },
            1.5,
            DVec3::NEG_Z,
            FloorWindow {
                origin: DVec2::ZERO,
                size: 1.0,
                width: 4,
                height: 4,
            },
            vec![],
        )
        .unwrap()
    }

    #[test]
    fn faces_round_trip() {
        for face in 0..6 {
            for (row, col) in [(0, 0), (3, 7), (15, 15)] {
                let d = texel_dir(face, row, col, 16);
                let (f, s, t) = face_st(d);
                assert_eq!(f, face);
                let x = (s + 1.0) * 8.0 - 0.5;
                let y = (t + 1.0) * 8.0 - 0.5;
                assert!((x - col as f64).abs() < 1e-9 && (y - row as f64).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn a_sphere_is_one_layer_at_its_radius_and_rays_find_it() {
        let s = sphere_scene();
        let dm = DistanceMap::build(&s, 32, 2);
        for t in &dm.texels[..6 * 32 * 32] {
            assert!((t[3] - 0.3).abs() < 1e-6, "{t:?}");
        }
        assert!(dm.texels[6 * 32 * 32..].iter().all(|t| t[3] == 0.0));
        // A ray from outside, off-centre, and back out from inside.
        let x = DVec3::new(0.2, 0.25, 1.5);
        let (d, surf) = dm
            .trace(x, DVec3::NEG_Z, 0.0, 2.0, Crossing::Entering, 64, 8)
            .unwrap();
        let exact = Shape::Sphere {
            centre: dm.centre,
            radius: 0.3,
        }
        .intersect(x, DVec3::NEG_Z, 9.0)
        .unwrap();
        assert!((d - exact.0).abs() < 1e-4, "{d} vs {}", exact.0);
        assert!(surf.glass && (surf.normal - exact.1).length() < 1e-2);
        let p = x + DVec3::NEG_Z * d;
        let (d2, s2) = dm
            .trace(p, DVec3::NEG_Z, 1e-4, 1.0, Crossing::Leaving, 64, 8)
            .unwrap();
        assert!(
            s2.normal.z < 0.0
                && (d2 - 2.0 * (0.3f64.powi(2) - 0.1f64.powi(2) - 0.05f64.powi(2)).sqrt()).abs()
                    < 1e-3,
            "{d2}"
        );
        // Entering is ignored from inside: no hit going up from the bottom.
        assert!(
            dm.trace(p, DVec3::Z, 1e-3, 0.01, Crossing::Leaving, 8, 8)
                .is_none()
        );
    }
}
