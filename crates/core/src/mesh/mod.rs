//! Triangle meshes for the objects under and above the water: built-in shapes (a sphere, a box and
//! the Utah teapot), meshes read from OBJ files, and the ray queries the CPU reference needs.
//!
//! Everything is `f64` and z is up, like the rest of the crate. A mesh carries one smooth normal per
//! vertex because refraction through a glass object is only as good as its normals: the facets of a
//! tessellation show up in the caustics long before they show up in a shaded image. Triangles are
//! counter-clockwise seen from outside, so the winding and the normals agree on which side is out,
//! and closed meshes have a positive [`TriangleMesh::volume`].
//!
//! - [`sphere`], [`cuboid`], [`teapot`]: shapes in their own units, placed with
//!   [`TriangleMesh::transformed`].
//! - [`load_obj`]: any OBJ file; missing normals are computed with [`smooth_normals`].
//! - A ray tracer builds a [`MeshBvh`] once per mesh and asks it for each ray's nearest hit (its
//!   tests hold it to every triangle tried in turn).

mod bvh;
mod obj;
mod primitives;
mod teapot;

use std::collections::HashMap;

use glam::{DAffine3, DMat3, DVec3};

use crate::error::{Error, Result};

pub use bvh::MeshBvh;
pub use obj::load_obj;
pub use primitives::{cuboid, sphere};
pub use teapot::teapot;

/// Indexed triangles: a smooth surface shares each vertex among the triangles around it, so it has
/// one normal per point and [`TriangleMesh::is_closed`] can pair up edges; flat faces and creases
/// repeat their vertices instead, one copy per normal.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions, in the shape's own units or world units once placed, z up.
    pub positions: Vec<DVec3>,
    /// Unit, outward, one per position.
    pub normals: Vec<DVec3>,
    /// Counter-clockwise seen from outside.
    pub indices: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// Axis-aligned bounds `(min, max)` of the vertices. An empty mesh gives the inverted box
    /// `(+∞, −∞)`, which is the identity of a union of boxes.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        bounds_of(&self.positions)
    }

    /// The mesh under an affine map. Normals go through the inverse transpose, which keeps them
    /// perpendicular to the surface under non-uniform scaling; a mirroring map (negative
    /// determinant) also reverses the winding so that triangles stay counter-clockwise seen from
    /// outside. `m` should be invertible: a singular map flattens the mesh and its normals.
    pub fn transformed(&self, m: DAffine3) -> TriangleMesh {
        let [c0, c1, c2] = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis];
        // The cofactor matrix is det · M⁻ᵀ; it stays finite when M is singular, and scaling it by
        // the sign of det gives M⁻ᵀ up to a positive factor, which the normalisation removes.
        let cofactor = DMat3::from_cols(c1.cross(c2), c2.cross(c0), c0.cross(c1));
        let det = m.matrix3.determinant();
        let sign = if det < 0.0 { -1.0 } else { 1.0 };
        TriangleMesh {
            positions: self
                .positions
                .iter()
                .map(|&p| m.transform_point3(p))
                .collect(),
            normals: self
                .normals
                .iter()
                .map(|&n| (sign * (cofactor * n)).normalize_or_zero())
                .collect(),
            indices: if det < 0.0 {
                self.indices.iter().map(|&[a, b, c]| [a, c, b]).collect()
            } else {
                self.indices.clone()
            },
        }
    }

    /// Total surface area of the triangles, in the square of the positions' unit.
    pub fn area(&self) -> f64 {
        self.triangles()
            .map(|[a, b, c]| 0.5 * (b - a).cross(c - a).length())
            .sum()
    }

    /// Signed volume by the divergence theorem: the sum over triangles of the tetrahedra they span
    /// with the origin. Exact for a closed mesh (positive when wound counter-clockwise from
    /// outside) and independent of where the origin is; for an open mesh it depends on the origin
    /// and is only an estimate.
    pub fn volume(&self) -> f64 {
        self.triangles()
            .map(|[a, b, c]| a.dot(b.cross(c)))
            .sum::<f64>()
            / 6.0
    }

    /// Whether the mesh bounds a solid: every undirected edge is shared by exactly two triangles.
    /// Vertices closer than 1e-9 of the bounding-box diagonal count as one first, so that meshes with
    /// split vertices (flat-shaded faces, UV seams) are judged by their shape, and triangles that
    /// collapse under that welding are ignored. A mesh without triangles is not closed.
    pub fn is_closed(&self) -> bool {
        if self.indices.is_empty() {
            return false;
        }
        let (weld_id, _) = weld(&self.positions);
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for tri in &self.indices {
            let [a, b, c] = tri.map(|i| weld_id[i as usize]);
            if a == b || b == c || c == a {
                continue;
            }
            for (p, q) in [(a, b), (b, c), (c, a)] {
                *edges.entry((p.min(q), p.max(q))).or_default() += 1;
            }
        }
        !edges.is_empty() && edges.values().all(|&n| n == 2)
    }

    /// Checks what the ray queries and the renderers rely on, naming `what` (the scene field or
    /// object the mesh came from) in the error.
    pub fn validate(&self, what: &str) -> Result<()> {
        self.check().map_err(|problem| Error::field(what, problem))
    }

    /// The problem with the mesh, if any, worded to follow the name of its source.
    fn check(&self) -> std::result::Result<(), String> {
        if self.positions.is_empty() || self.indices.is_empty() {
            return Err(format!(
                "is an empty mesh ({} vertices, {} triangles)",
                self.positions.len(),
                self.indices.len()
            ));
        }
        if self.normals.len() != self.positions.len() {
            return Err(format!(
                "has {} normals for {} vertices",
                self.normals.len(),
                self.positions.len()
            ));
        }
        if let Some((i, p)) = self
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite())
        {
            return Err(format!("has a non-finite vertex {i}: {p}"));
        }
        if let Some((i, n)) = self
            .normals
            .iter()
            .enumerate()
            .find(|(_, n)| !n.is_finite())
        {
            return Err(format!("has a non-finite normal at vertex {i}: {n}"));
        }
        let count = self.positions.len();
        for (t, tri) in self.indices.iter().enumerate() {
            if let Some(&i) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(format!(
                    "has triangle {t} referring to vertex {i}, but there are only {count} vertices"
                ));
            }
        }
        Ok(())
    }

    /// Nearest hit of the ray `origin + t·dir` with `0 < t < t_max`: `t` (a distance when `dir` is a
    /// unit vector) and the interpolated normal, which stays outward whichever side is hit. This
    /// tests every triangle; for many rays build [`TriangleMesh::bvh`] once and use
    /// [`MeshBvh::intersect`], which returns the same hits.
    #[cfg(test)]
    pub fn ray_intersect(&self, origin: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, DVec3)> {
        let mut best: Option<(f64, usize, f64, f64)> = None;
        let mut t_best = t_max;
        for (i, &[a, b, c]) in self.indices.iter().enumerate() {
            let p0 = self.positions[a as usize];
            let (e1, e2) = (
                self.positions[b as usize] - p0,
                self.positions[c as usize] - p0,
            );
            if let Some((t, u, v)) = bvh::intersect_triangle(origin, dir, p0, e1, e2, t_best) {
                t_best = t;
                best = Some((t, i, u, v));
            }
        }
        best.map(|(t, i, u, v)| (t, self.interpolated_normal(i, u, v)))
    }

    /// Builds the acceleration structure for [`MeshBvh::intersect`] with this mesh.
    pub fn bvh(&self) -> MeshBvh {
        MeshBvh::build(self)
    }

    /// The vertex normals of triangle `i` blended at barycentric `(u, v)`; where they cancel (a
    /// triangle across a crease whose vertex normals oppose) the face normal stands in.
    fn interpolated_normal(&self, i: usize, u: f64, v: f64) -> DVec3 {
        let [a, b, c] = self.indices[i].map(|k| k as usize);
        let n = (1.0 - u - v) * self.normals[a] + u * self.normals[b] + v * self.normals[c];
        n.try_normalize().unwrap_or_else(|| {
            let [pa, pb, pc] = [self.positions[a], self.positions[b], self.positions[c]];
            (pb - pa).cross(pc - pa).normalize_or_zero()
        })
    }

    fn triangles(&self) -> impl Iterator<Item = [DVec3; 3]> + '_ {
        self.indices
            .iter()
            .map(|tri| tri.map(|i| self.positions[i as usize]))
    }
}

/// Per-vertex normals as the area-weighted mean of the normals of the triangles around each vertex:
/// large triangles dominate, so a sliver at a seam cannot tilt the shading. A vertex that touches no
/// triangle of non-zero area gets +z, so that every normal is a unit vector.
pub fn smooth_normals(positions: &[DVec3], indices: &[[u32; 3]]) -> Vec<DVec3> {
    let mut sums = vec![DVec3::ZERO; positions.len()];
    for tri in indices {
        let [a, b, c] = tri.map(|i| positions[i as usize]);
        // The cross product's length is twice the area, which is the weight we want.
        let n = (b - a).cross(c - a);
        for &i in tri {
            sums[i as usize] += n;
        }
    }
    sums.into_iter()
        .map(|n| n.try_normalize().unwrap_or(DVec3::Z))
        .collect()
}

/// Smooth normals across split vertices: positions that [`weld`] joins share one normal, so a mesh
/// whose vertices were duplicated for texture seams still shades smoothly across them.
fn smooth_normals_welded(positions: &[DVec3], indices: &[[u32; 3]]) -> Vec<DVec3> {
    let (weld_id, representatives) = weld(positions);
    let welded_positions: Vec<DVec3> = representatives
        .iter()
        .map(|&i| positions[i as usize])
        .collect();
    let welded_indices: Vec<[u32; 3]> = indices
        .iter()
        .map(|tri| tri.map(|i| weld_id[i as usize]))
        .collect();
    let normals = smooth_normals(&welded_positions, &welded_indices);
    weld_id.iter().map(|&w| normals[w as usize]).collect()
}

/// The nearest hit before `t_max` of the ray `o + t d` with any of `meshes`: the mesh's index,
/// `t` and the interpolated outward normal.
pub fn nearest<'a>(
    meshes: impl IntoIterator<Item = (&'a TriangleMesh, &'a MeshBvh)>,
    o: DVec3,
    d: DVec3,
    t_max: f64,
) -> Option<(usize, f64, DVec3)> {
    let mut best: Option<(usize, f64, DVec3)> = None;
    for (k, (mesh, bvh)) in meshes.into_iter().enumerate() {
        if let Some((t, n)) = bvh.intersect(mesh, o, d, best.map_or(t_max, |b| b.1)) {
            best = Some((k, t, n));
        }
    }
    best
}

/// Axis-aligned bounds `(min, max)` of `points`; `(+∞, −∞)`, the identity of a union of boxes,
/// for none.
pub(crate) fn bounds_of<'a>(points: impl IntoIterator<Item = &'a DVec3>) -> (DVec3, DVec3) {
    let empty = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    (points.into_iter()).fold(empty, |(lo, hi), &p| (lo.min(p), hi.max(p)))
}

/// The zero normals of `normals` (where a file or a patch gave none) from the faces around the
/// vertex ([`smooth_normals_welded`]).
pub(crate) fn fill_zero_normals(normals: &mut [DVec3], positions: &[DVec3], indices: &[[u32; 3]]) {
    if normals.contains(&DVec3::ZERO) {
        let computed = smooth_normals_welded(positions, indices);
        for (n, c) in normals.iter_mut().zip(computed) {
            if *n == DVec3::ZERO {
                *n = c;
            }
        }
    }
}

/// Joins vertices within 1e-9 of the bounding-box diagonal of each other. Returns, for every vertex,
/// the id of its group, and for every group the vertex that represents it. Points are hashed into
/// cells of the tolerance's size and compared with the representatives of the 27 cells around
/// them, so the cost is linear in the number of vertices.
fn weld(positions: &[DVec3]) -> (Vec<u32>, Vec<u32>) {
    let (lo, hi) = bounds_of(positions);
    let tolerance = 1e-9 * (hi - lo).length();
    // A zero tolerance (a single point, or no points) still needs a finite cell size.
    let cell_size = if tolerance > 0.0 && tolerance.is_finite() {
        tolerance
    } else {
        1.0
    };
    let cell = |p: DVec3| ((p - lo) / cell_size).floor().as_i64vec3();
    let mut grid: HashMap<glam::I64Vec3, Vec<u32>> = HashMap::new();
    let mut weld_id = Vec::with_capacity(positions.len());
    let mut representatives: Vec<u32> = Vec::new();
    for (i, &p) in positions.iter().enumerate() {
        let c = cell(p);
        let mut found = None;
        'search: for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let Some(group) = grid.get(&(c + glam::I64Vec3::new(dx, dy, dz))) else {
                        continue;
                    };
                    for &g in group {
                        let q = positions[representatives[g as usize] as usize];
                        if p.distance(q) <= tolerance {
                            found = Some(g);
                            break 'search;
                        }
                    }
                }
            }
        }
        let id = found.unwrap_or_else(|| {
            let g = representatives.len() as u32;
            representatives.push(i as u32);
            grid.entry(c).or_default().push(g);
            g
        });
        weld_id.push(id);
    }
    (weld_id, representatives)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit right-angled tetrahedron, counter-clockwise from outside.
    pub(super) fn tetrahedron() -> TriangleMesh {
        let positions = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        let indices = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let normals = smooth_normals(&positions, &indices);
        TriangleMesh {
            positions,
            normals,
            indices,
        }
    }

    #[test]
    fn tetrahedron_measures() {
        let t = tetrahedron();
        assert!((t.volume() - 1.0 / 6.0).abs() < 1e-15);
        assert!((t.area() - (1.5 + 3f64.sqrt() / 2.0)).abs() < 1e-14);
        assert!(t.is_closed());
        assert_eq!(t.bounds(), (DVec3::ZERO, DVec3::ONE));
        // The normal at the right-angle corner points away from the solid, into the negative octant.
        assert!(t.normals[0].dot(DVec3::ONE) < 0.0);
    }

    #[test]
    fn open_mesh_is_not_closed() {
        let mut t = tetrahedron();
        t.indices.pop();
        assert!(!t.is_closed());
        assert!(!TriangleMesh::default().is_closed());
    }

    #[test]
    fn split_vertices_are_welded_for_closedness() {
        // Every triangle gets its own copies of its corners, off by far less than the tolerance.
        let t = tetrahedron();
        let mut split = TriangleMesh::default();
        for (k, tri) in t.indices.iter().enumerate() {
            let base = split.positions.len() as u32;
            for &i in tri {
                split
                    .positions
                    .push(t.positions[i as usize] + DVec3::splat(1e-13 * k as f64));
                split.normals.push(t.normals[i as usize]);
            }
            split.indices.push([base, base + 1, base + 2]);
        }
        assert!(split.is_closed());
        assert!((split.volume() - 1.0 / 6.0).abs() < 1e-12);
    }

    #[test]
    fn transform_scales_volume_and_keeps_normals_outward() {
        let s = sphere(1.0, 32, 16);
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::new(2.0, 0.5, 1.0),
            glam::DQuat::from_rotation_z(0.3),
            DVec3::new(1.0, -2.0, 3.0),
        );
        let e = s.transformed(m);
        assert!((e.volume() - s.volume()).abs() < 1e-12, "det is 1");
        let centre = DVec3::new(1.0, -2.0, 3.0);
        for (p, n) in e.positions.iter().zip(&e.normals) {
            assert!((n.length() - 1.0).abs() < 1e-12);
            assert!(n.dot(*p - centre) > 0.0);
        }
        // The normal of an ellipsoid x²/a² + ... at p is the gradient (x/a², ...), exactly what the
        // inverse transpose gives for the vertices of a sphere.
        let plain =
            sphere(1.0, 32, 16).transformed(DAffine3::from_scale(DVec3::new(2.0, 0.5, 1.0)));
        for (p, n) in plain.positions.iter().zip(&plain.normals) {
            let g = (*p / DVec3::new(4.0, 0.25, 1.0)).normalize();
            assert!(n.distance(g) < 1e-12);
        }
    }

    #[test]
    fn mirror_keeps_winding_outward() {
        let c = cuboid(DVec3::new(1.0, 2.0, 3.0));
        let m = c.transformed(DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0)));
        assert!((m.volume() - 48.0).abs() < 1e-12);
        for tri in &m.indices {
            let [a, b, cc] = tri.map(|i| m.positions[i as usize]);
            let face = (b - a).cross(cc - a).normalize();
            assert!(face.dot(m.normals[tri[0] as usize]) > 0.999);
        }
    }

    #[test]
    fn validate_names_the_mesh_and_the_problem() {
        let ok = tetrahedron();
        ok.validate("objects[0]").unwrap();

        let message = |m: &TriangleMesh| m.validate("objects[2].mesh").unwrap_err().to_string();

        let e = message(&TriangleMesh::default());
        assert!(e.contains("objects[2].mesh") && e.contains("empty"), "{e}");

        let mut nan = tetrahedron();
        nan.positions[3].y = f64::NAN;
        let e = message(&nan);
        assert!(
            e.contains("objects[2].mesh") && e.contains("non-finite vertex 3"),
            "{e}"
        );

        let mut inf = tetrahedron();
        inf.normals[1].x = f64::INFINITY;
        assert!(message(&inf).contains("non-finite normal"));

        let mut out = tetrahedron();
        out.indices[2][1] = 9;
        let e = message(&out);
        assert!(e.contains("triangle 2") && e.contains("vertex 9"), "{e}");

        let mut short = tetrahedron();
        short.normals.pop();
        assert!(message(&short).contains("3 normals for 4 vertices"));
    }

    #[test]
    fn smooth_normals_are_area_weighted() {
        // Two triangles at a right angle sharing the edge along x; the larger one (4× the area)
        // pulls the shared vertices' normal towards its own.
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(0.0, 0.0, -0.5),
        ];
        let indices = vec![[0, 1, 2], [0, 3, 1]];
        let n = smooth_normals(&positions, &indices);
        let expected = (DVec3::Z * 2.0 + DVec3::NEG_Y * 0.5).normalize();
        assert!(n[0].distance(expected) < 1e-15);
        assert!(n[2].distance(DVec3::Z) < 1e-15);
        assert!(n[3].distance(DVec3::NEG_Y) < 1e-15);
        // An isolated vertex still gets a unit normal.
        let n = smooth_normals(&[DVec3::ZERO; 4], &[[0, 1, 2]]);
        assert!(n.iter().all(|n| (n.length() - 1.0).abs() < 1e-15));
    }

    #[test]
    fn brute_force_ray_hits_the_tetrahedron() {
        let t = tetrahedron();
        let (d, n) = t
            .ray_intersect(DVec3::new(0.2, 0.2, 5.0), DVec3::NEG_Z, f64::INFINITY)
            .unwrap();
        assert!((d - 4.4).abs() < 1e-12);
        assert!(n.z > 0.0);
        assert!(
            t.ray_intersect(DVec3::new(0.2, 0.2, 5.0), DVec3::NEG_Z, 4.0)
                .is_none()
        );
        assert!(
            t.ray_intersect(DVec3::new(2.0, 2.0, 5.0), DVec3::NEG_Z, 10.0)
                .is_none()
        );
    }
}
