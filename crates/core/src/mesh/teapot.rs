//! The Utah teapot: Martin Newell's 1975 model of a Melitta teapot as 32 bicubic Bézier patches,
//! in the classic 306-point table (Crow, "The origins of the teapot", IEEE CG&A 7(1), 1987). Its
//! proportions are the ones everyone uses, squatter by a factor of 1.3 than Newell's real teapot
//! (Blinn's correction for non-square pixels, kept ever since).
//!
//! In its own units the teapot stands on z = 0 with the lid's knob at z = 3.15; the body, nearly a
//! surface of revolution, is 2 in radius at its widest, the handle reaches x = −3 and the spout's
//! lip x ≈ 3.434, and it is symmetric in y. It is not a closed solid: the spout is open, the lid
//! does not meet the rim, and the handle and spout pass through the body. The last four patches,
//! the bottom, are a later addition; Newell's teapot had none.
//!
//! Normals come from the patches' derivatives rather than from the triangles, so that refraction
//! through a glass teapot sees the smooth surface however coarse the tessellation.

use glam::DVec3;

use super::TriangleMesh;

/// The teapot with every patch cut into `subdivisions` × `subdivisions` quads (at least 1), two
/// triangles each, less those that collapse at the poles of the lid and the bottom:
/// `64 s² − 8 s` triangles, 9120 for `s = 12`. Vertices along the seams between patches are
/// repeated but bit-identical, so the triangles meet without cracks.
pub fn teapot(subdivisions: u32) -> TriangleMesh {
    let (indices, points) = data();
    let patches: Vec<Patch> = indices.iter().map(|i| control_points(i, &points)).collect();
    tessellate(&patches, subdivisions.max(1) as usize)
}

/// Control points `P[i][j]`; the surface is `Σᵢⱼ Bᵢ(u) Bⱼ(v) P[i][j]` with the cubic Bernstein
/// polynomials `B`. For every teapot patch `∂v × ∂u` points outward.
type Patch = [[DVec3; 4]; 4];

fn control_points(indices: &[u16; 16], points: &[[f64; 3]]) -> Patch {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| DVec3::from_array(points[usize::from(indices[4 * i + j]) - 1]))
    })
}

fn tessellate(patches: &[Patch], n: usize) -> TriangleMesh {
    let mut positions = Vec::with_capacity(patches.len() * (n + 1) * (n + 1));
    let mut normals = Vec::with_capacity(positions.capacity());
    let mut indices = Vec::with_capacity(patches.len() * 2 * n * n);
    for patch in patches {
        let base = positions.len() as u32;
        // A cross product of derivatives this small relative to the patch's size is rounding noise.
        let (lo, hi) = super::bounds_of(patch.iter().flatten());
        let negligible = 1e-12 * (hi - lo).length_squared();
        for i in 0..=n {
            for j in 0..=n {
                let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                positions.push(evaluate(patch, u, v).0);
                normals.push(normal(patch, u, v, negligible));
            }
        }
        let at = |i: usize, j: usize| base + (i * (n + 1) + j) as u32;
        for i in 0..n {
            for j in 0..n {
                let [a, b, c, d] = [at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)];
                // Counter-clockwise around ∂v × ∂u, the outward normal.
                for tri in [[a, b, c], [b, d, c]] {
                    let [pa, pb, pc] = tri.map(|k| positions[k as usize]);
                    // Poles are evaluated exactly (see `evaluate`), so a collapsed triangle has
                    // two equal corners.
                    if pa != pb && pb != pc && pc != pa {
                        indices.push(tri);
                    }
                }
            }
        }
    }
    // Where even the nudged derivatives fail, the faces around the vertex decide.
    super::fill_zero_normals(&mut normals, &positions, &indices);
    without_unused_vertices(TriangleMesh {
        positions,
        normals,
        indices,
    })
}

/// The point and the two partial derivatives `(S, ∂S/∂u, ∂S/∂v)` at `(u, v)`. A row of equal
/// control points (a pole) evaluates to exactly that point rather than to the point times a sum of
/// Bernstein weights that rounds to one only approximately, so that the vertices at a pole coincide
/// exactly, and its `v` derivative is exactly zero.
fn evaluate(p: &Patch, u: f64, v: f64) -> (DVec3, DVec3, DVec3) {
    let (bu, dbu) = bernstein(u);
    let (bv, dbv) = bernstein(v);
    let mut rows = [DVec3::ZERO; 4];
    let mut rows_dv = [DVec3::ZERO; 4];
    for (i, row) in p.iter().enumerate() {
        if row.iter().all(|&q| q == row[0]) {
            rows[i] = row[0];
        } else {
            rows[i] = blend(bv, *row);
            rows_dv[i] = blend(dbv, *row);
        }
    }
    (blend(bu, rows), blend(dbu, rows), blend(bu, rows_dv))
}

/// `Σ wₖ qₖ`, always in the same order, so that the two patches on either side of a seam compute
/// bit-identical points from the control points they share.
fn blend(w: [f64; 4], q: [DVec3; 4]) -> DVec3 {
    w[0] * q[0] + w[1] * q[1] + w[2] * q[2] + w[3] * q[3]
}

/// The cubic Bernstein polynomials at `t` and their derivatives. At `t = 0` and `t = 1` the values
/// are exactly one and zeros.
fn bernstein(t: f64) -> ([f64; 4], [f64; 4]) {
    let s = 1.0 - t;
    (
        [s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t],
        [
            -3.0 * s * s,
            3.0 * s * s - 6.0 * t * s,
            6.0 * t * s - 3.0 * t * t,
            3.0 * t * t,
        ],
    )
}

/// The unit outward normal `∂v × ∂u` at `(u, v)`, or zero where the cross product is below
/// `negligible`. At a pole one derivative vanishes; the surface still has a tangent plane there,
/// and its normal is the limit of the normals around it, so the derivatives are taken again a
/// hundred-millionth of the way towards the patch's centre. That puts the normal at the top of the
/// lid within 1e-8 of +z, where the normal of any one triangle of the fan around it is tilted by
/// the fan's slope. The short step costs no precision: the pole's row adds exactly nothing to
/// `∂v` (see [`evaluate`]), so the small derivative comes without cancellation.
fn normal(p: &Patch, u: f64, v: f64, negligible: f64) -> DVec3 {
    let inward = |t: f64| t + (0.5 - t) * 1e-8;
    for (u, v) in [(u, v), (inward(u), inward(v))] {
        let (_, du, dv) = evaluate(p, u, v);
        let n = dv.cross(du);
        if n.length() > negligible {
            return n.normalize();
        }
    }
    DVec3::ZERO
}

/// Drops the vertices that only collapsed triangles used (one per pole and patch), renumbering the
/// rest in order of first use.
fn without_unused_vertices(mesh: TriangleMesh) -> TriangleMesh {
    let mut new_index = vec![u32::MAX; mesh.positions.len()];
    let mut out = TriangleMesh {
        indices: mesh.indices,
        ..TriangleMesh::default()
    };
    for k in out.indices.iter_mut().flatten() {
        let old = *k as usize;
        if new_index[old] == u32::MAX {
            new_index[old] = out.positions.len() as u32;
            out.positions.push(mesh.positions[old]);
            out.normals.push(mesh.normals[old]);
        }
        *k = new_index[old];
    }
    out
}

/// Newell's data in its classic text form: the patch count, then per patch 16 one-based indices
/// into the points (row `i` of a patch is `P[i][0..4]`, the control points for `u = i/3` along its
/// `v` direction); the point count, then one `x,y,z` per point. The patches are the rim (1-4), the
/// body, upper then lower (5-12), the handle (13-16), the spout (17-20), the lid's knob and the lid
/// (21-28) and the bottom (29-32). Points 205, 206, 216 and 223 are unused and 271 repeats 93, as
/// in every copy of the data.
const DATA: &str = include_str!("teapot.txt");

/// [`DATA`]'s patches and points.
fn data() -> (Vec<[u16; 16]>, Vec<[f64; 3]>) {
    let mut lines = DATA.lines();
    let mut table = || {
        let n: usize = lines.next().and_then(|l| l.parse().ok()).expect("a count");
        (&mut lines)
            .take(n)
            .map(|l| l.split(',').map(|x| x.parse().expect("a number")).collect())
            .collect::<Vec<Vec<f64>>>()
    };
    let patches = table()
        .iter()
        .map(|p| std::array::from_fn(|k| p[k] as u16))
        .collect();
    let points = table().iter().map(|p| [p[0], p[1], p[2]]).collect();
    (patches, points)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Patch `k`'s control points, as the table gives them.
    fn patch(k: usize) -> Patch {
        let (indices, points) = data();
        control_points(&indices[k], &points)
    }

    #[test]
    fn table_has_the_known_symmetries() {
        // The rim, the body, the lid and the bottom are surfaces of revolution made of quarters: each
        // patch is the previous one turned by 90° about z (clockwise seen from above, except the
        // bottom, which runs the other way). A mistyped coordinate breaks one of these.
        let clockwise = |q: DVec3| DVec3::new(q.y, -q.x, q.z);
        let anticlockwise = |q: DVec3| DVec3::new(-q.y, q.x, q.z);
        for (first, turn) in [
            (0, clockwise as fn(DVec3) -> DVec3),
            (4, clockwise),
            (8, clockwise),
            (20, clockwise),
            (24, clockwise),
            (28, anticlockwise),
        ] {
            for k in first..first + 3 {
                let (a, b) = (patch(k), patch(k + 1));
                for (i, j) in (0..4).flat_map(|i| (0..4).map(move |j| (i, j))) {
                    assert_eq!(turn(a[i][j]), b[i][j], "patch {} point {i},{j}", k + 2);
                }
            }
        }
        // The handle and the spout are two halves mirrored in y, with v reversed.
        for k in [12, 14, 16, 18] {
            let (a, b) = (patch(k), patch(k + 1));
            for (i, j) in (0..4).flat_map(|i| (0..4).map(move |j| (i, j))) {
                let mirrored = a[i][3 - j] * DVec3::new(1.0, -1.0, 1.0);
                assert_eq!(mirrored, b[i][j], "patch {} point {i},{j}", k + 2);
            }
        }
    }

    #[test]
    fn table_uses_every_point_but_four() {
        let (indices, points) = data();
        assert_eq!((indices.len(), points.len()), (32, 306));
        let mut used = [false; 306];
        for &i in indices.iter().flatten() {
            used[usize::from(i) - 1] = true;
        }
        let unused: Vec<usize> = (1..=306).filter(|&i| !used[i - 1]).collect();
        assert_eq!(unused, [205, 206, 216, 223]);
        assert_eq!(points[93 - 1], points[271 - 1]);
    }

    #[test]
    fn extents_counts_and_normals() {
        for s in [1, 4, 16] {
            let t = teapot(s);
            t.validate("teapot").unwrap();
            let s = s as usize;
            assert_eq!(t.indices.len(), 64 * s * s - 8 * s);
            assert!(t.area() > 0.0);
            for n in &t.normals {
                assert!((n.length() - 1.0).abs() < 1e-12, "{n}");
            }
            // Every vertex is used.
            let mut used = vec![false; t.positions.len()];
            t.indices
                .iter()
                .flatten()
                .for_each(|&i| used[i as usize] = true);
            assert!(used.iter().all(|&u| u));
        }
        assert_eq!(teapot(0).indices.len(), 56);

        let t = teapot(16);
        let (lo, hi) = t.bounds();
        assert_eq!((lo.z, hi.z), (0.0, 3.15));
        assert_eq!((lo.y, hi.y), (-2.0, 2.0));
        assert_eq!(lo.x, -3.0);
        // The spout's lip peaks at x = 3.4341 between samples; 16 per patch reach 3.4335.
        assert!((hi.x - 3.434).abs() < 1e-3, "{}", hi.x);
        // Roughly the volume of the body, a solid of revolution of radius up to 2 and height 2.4.
        let v = t.volume();
        assert!((20.0..30.0).contains(&v), "{v}");
    }

    #[test]
    fn normals_point_outward_and_agree_with_the_winding() {
        // The tightest curl, the spout's lip, turns the normal by up to 45° across one triangle at
        // this resolution.
        let t = teapot(16);
        for tri in &t.indices {
            let [a, b, c] = tri.map(|i| t.positions[i as usize]);
            let face = (b - a).cross(c - a).normalize();
            for &i in tri {
                let n = t.normals[i as usize];
                assert!(
                    face.dot(n) > 0.5,
                    "triangle {tri:?}: face {face}, vertex normal {n}"
                );
            }
        }
        let normal_at = |p: DVec3| {
            let i = t
                .positions
                .iter()
                .position(|&q| q.distance(p) < 1e-12)
                .unwrap();
            t.normals[i]
        };
        // The poles, where the derivatives vanish.
        assert!(normal_at(DVec3::new(0.0, 0.0, 3.15)).distance(DVec3::Z) < 1e-7);
        assert!(normal_at(DVec3::ZERO).distance(DVec3::NEG_Z) < 1e-7);
        // The widest point of the body, and the outside of the handle.
        assert!(normal_at(DVec3::new(2.0, 0.0, 0.9)).distance(DVec3::X) < 1e-9);
        assert!(normal_at(DVec3::new(-3.0, 0.0, 1.8)).distance(DVec3::NEG_X) < 1e-9);
    }

    #[test]
    fn seen_from_outside_the_surface_faces_the_viewer() {
        // Rays from all around mostly hit front faces; they see back faces only through the spout's
        // opening and the gap between the lid and the rim.
        let t = teapot(8);
        let bvh = t.bvh();
        let (mut front, mut back) = (0, 0);
        for k in 0..2000 {
            // A Fibonacci sphere of viewpoints, each aimed at a point on the teapot's axis.
            let z = 1.0 - 2.0 * (k as f64 + 0.5) / 2000.0;
            let phi = k as f64 * 2.399_963_229_728_653;
            let r = (1.0 - z * z).sqrt();
            let origin = 10.0 * DVec3::new(r * phi.cos(), r * phi.sin(), z);
            let target = DVec3::new(0.0, 0.0, 0.3 + 2.5 * (k % 7) as f64 / 6.0);
            let dir = (target - origin).normalize();
            if let Some((_, n)) = bvh.intersect(&t, origin, dir, f64::INFINITY) {
                if n.dot(dir) < 0.0 {
                    front += 1
                } else {
                    back += 1
                }
            }
        }
        assert!(
            front > 1500 && back * 100 < front,
            "{front} front, {back} back"
        );
    }

    #[test]
    fn degenerate_normals_fall_back_to_the_faces() {
        // The knob with its first two rows made to coincide: at the top both derivatives vanish,
        // and just inside the normal is still too small to trust.
        let knob: Vec<Patch> = (20..24)
            .map(|k| {
                let mut p = patch(k);
                p[1] = p[0];
                p
            })
            .collect();
        let mesh = tessellate(&knob, 6);
        mesh.validate("knob").unwrap();
        for n in &mesh.normals {
            assert!((n.length() - 1.0).abs() < 1e-12);
        }
        // The faces around the top, all four patches of them, average to +z.
        let top = DVec3::new(0.0, 0.0, 3.15);
        for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
            if *p == top {
                assert!(n.distance(DVec3::Z) < 1e-9, "{n}");
            }
        }
    }
}
