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

use super::{TriangleMesh, smooth_normals_welded};

/// The teapot with every patch cut into `subdivisions` × `subdivisions` quads (at least 1), two
/// triangles each, less those that collapse at the poles of the lid and the bottom:
/// `64 s² − 8 s` triangles, 9120 for `s = 12`. Vertices along the seams between patches are
/// repeated but bit-identical, so the triangles meet without cracks.
pub fn teapot(subdivisions: u32) -> TriangleMesh {
    let patches: Vec<Patch> = PATCHES.iter().map(control_points).collect();
    tessellate(&patches, subdivisions.max(1) as usize)
}

/// Control points `P[i][j]`; the surface is `Σᵢⱼ Bᵢ(u) Bⱼ(v) P[i][j]` with the cubic Bernstein
/// polynomials `B`. For every teapot patch `∂v × ∂u` points outward.
type Patch = [[DVec3; 4]; 4];

fn control_points(indices: &[u16; 16]) -> Patch {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| DVec3::from_array(VERTICES[usize::from(indices[4 * i + j]) - 1]))
    })
}

fn tessellate(patches: &[Patch], n: usize) -> TriangleMesh {
    let mut positions = Vec::with_capacity(patches.len() * (n + 1) * (n + 1));
    let mut normals = Vec::with_capacity(positions.capacity());
    let mut indices = Vec::with_capacity(patches.len() * 2 * n * n);
    for patch in patches {
        let base = positions.len() as u32;
        // A cross product of derivatives this small relative to the patch's size is rounding noise.
        let (lo, hi) = patch
            .iter()
            .flatten()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &q| {
                (lo.min(q), hi.max(q))
            });
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
    if normals.contains(&DVec3::ZERO) {
        let fallback = smooth_normals_welded(&positions, &indices);
        for (n, f) in normals.iter_mut().zip(fallback) {
            if *n == DVec3::ZERO {
                *n = f;
            }
        }
    }
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

/// Newell's 32 patches as 16 one-based indices into [`VERTICES`] each, so the table reads as it is
/// published: row `i` of a patch is `P[i][0..4]`, the control points for `u = i/3` along its
/// `v` direction.
const PATCHES: [[u16; 16]; 32] = [
    // Rim.
    [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16],
    [4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28],
    [
        19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40,
    ],
    [31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13],
    // Body, upper then lower.
    [
        13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60,
    ],
    [
        16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69,
    ],
    [
        28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78,
    ],
    [
        40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57,
    ],
    [
        57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96,
    ],
    [
        60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105,
    ],
    [
        69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114,
    ],
    [
        78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93,
    ],
    // Handle.
    [
        121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136,
    ],
    [
        124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133,
    ],
    [
        133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155,
    ],
    [
        136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69,
    ],
    // Spout.
    [
        162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177,
    ],
    [
        165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174,
    ],
    [
        174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197,
    ],
    [
        177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194,
    ],
    // Lid: knob, then the lid itself.
    [
        204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215,
    ],
    [
        204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222,
    ],
    [
        204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229,
    ],
    [
        204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212,
    ],
    [
        212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245,
    ],
    [
        215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254,
    ],
    [
        222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263,
    ],
    [
        229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242,
    ],
    // Bottom.
    [
        270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274,
    ],
    [
        270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285,
    ],
    [
        270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294,
    ],
    [
        270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271,
    ],
];

/// The 306 control points, one-based in [`PATCHES`]; 205, 206, 216 and 223 are unused and 271 repeats
/// 93, as in every copy of the data.
const VERTICES: [[f64; 3]; 306] = [
    // Rim.
    [1.4, 0.0, 2.4],
    [1.4, -0.784, 2.4],
    [0.784, -1.4, 2.4],
    [0.0, -1.4, 2.4],
    [1.3375, 0.0, 2.53125],
    [1.3375, -0.749, 2.53125],
    [0.749, -1.3375, 2.53125],
    [0.0, -1.3375, 2.53125],
    [1.4375, 0.0, 2.53125],
    [1.4375, -0.805, 2.53125],
    [0.805, -1.4375, 2.53125],
    [0.0, -1.4375, 2.53125],
    [1.5, 0.0, 2.4],
    [1.5, -0.84, 2.4],
    [0.84, -1.5, 2.4],
    [0.0, -1.5, 2.4],
    [-0.784, -1.4, 2.4],
    [-1.4, -0.784, 2.4],
    [-1.4, 0.0, 2.4],
    [-0.749, -1.3375, 2.53125],
    [-1.3375, -0.749, 2.53125],
    [-1.3375, 0.0, 2.53125],
    [-0.805, -1.4375, 2.53125],
    [-1.4375, -0.805, 2.53125],
    [-1.4375, 0.0, 2.53125],
    [-0.84, -1.5, 2.4],
    [-1.5, -0.84, 2.4],
    [-1.5, 0.0, 2.4],
    [-1.4, 0.784, 2.4],
    [-0.784, 1.4, 2.4],
    [0.0, 1.4, 2.4],
    [-1.3375, 0.749, 2.53125],
    [-0.749, 1.3375, 2.53125],
    [0.0, 1.3375, 2.53125],
    [-1.4375, 0.805, 2.53125],
    [-0.805, 1.4375, 2.53125],
    [0.0, 1.4375, 2.53125],
    [-1.5, 0.84, 2.4],
    [-0.84, 1.5, 2.4],
    [0.0, 1.5, 2.4],
    [0.784, 1.4, 2.4],
    [1.4, 0.784, 2.4],
    [0.749, 1.3375, 2.53125],
    [1.3375, 0.749, 2.53125],
    [0.805, 1.4375, 2.53125],
    [1.4375, 0.805, 2.53125],
    [0.84, 1.5, 2.4],
    [1.5, 0.84, 2.4],
    // Body.
    [1.75, 0.0, 1.875],
    [1.75, -0.98, 1.875],
    [0.98, -1.75, 1.875],
    [0.0, -1.75, 1.875],
    [2.0, 0.0, 1.35],
    [2.0, -1.12, 1.35],
    [1.12, -2.0, 1.35],
    [0.0, -2.0, 1.35],
    [2.0, 0.0, 0.9],
    [2.0, -1.12, 0.9],
    [1.12, -2.0, 0.9],
    [0.0, -2.0, 0.9],
    [-0.98, -1.75, 1.875],
    [-1.75, -0.98, 1.875],
    [-1.75, 0.0, 1.875],
    [-1.12, -2.0, 1.35],
    [-2.0, -1.12, 1.35],
    [-2.0, 0.0, 1.35],
    [-1.12, -2.0, 0.9],
    [-2.0, -1.12, 0.9],
    [-2.0, 0.0, 0.9],
    [-1.75, 0.98, 1.875],
    [-0.98, 1.75, 1.875],
    [0.0, 1.75, 1.875],
    [-2.0, 1.12, 1.35],
    [-1.12, 2.0, 1.35],
    [0.0, 2.0, 1.35],
    [-2.0, 1.12, 0.9],
    [-1.12, 2.0, 0.9],
    [0.0, 2.0, 0.9],
    [0.98, 1.75, 1.875],
    [1.75, 0.98, 1.875],
    [1.12, 2.0, 1.35],
    [2.0, 1.12, 1.35],
    [1.12, 2.0, 0.9],
    [2.0, 1.12, 0.9],
    [2.0, 0.0, 0.45],
    [2.0, -1.12, 0.45],
    [1.12, -2.0, 0.45],
    [0.0, -2.0, 0.45],
    [1.5, 0.0, 0.225],
    [1.5, -0.84, 0.225],
    [0.84, -1.5, 0.225],
    [0.0, -1.5, 0.225],
    [1.5, 0.0, 0.15],
    [1.5, -0.84, 0.15],
    [0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15],
    [-1.12, -2.0, 0.45],
    [-2.0, -1.12, 0.45],
    [-2.0, 0.0, 0.45],
    [-0.84, -1.5, 0.225],
    [-1.5, -0.84, 0.225],
    [-1.5, 0.0, 0.225],
    [-0.84, -1.5, 0.15],
    [-1.5, -0.84, 0.15],
    [-1.5, 0.0, 0.15],
    [-2.0, 1.12, 0.45],
    [-1.12, 2.0, 0.45],
    [0.0, 2.0, 0.45],
    [-1.5, 0.84, 0.225],
    [-0.84, 1.5, 0.225],
    [0.0, 1.5, 0.225],
    [-1.5, 0.84, 0.15],
    [-0.84, 1.5, 0.15],
    [0.0, 1.5, 0.15],
    [1.12, 2.0, 0.45],
    [2.0, 1.12, 0.45],
    [0.84, 1.5, 0.225],
    [1.5, 0.84, 0.225],
    [0.84, 1.5, 0.15],
    [1.5, 0.84, 0.15],
    // Handle.
    [-1.6, 0.0, 2.025],
    [-1.6, -0.3, 2.025],
    [-1.5, -0.3, 2.25],
    [-1.5, 0.0, 2.25],
    [-2.3, 0.0, 2.025],
    [-2.3, -0.3, 2.025],
    [-2.5, -0.3, 2.25],
    [-2.5, 0.0, 2.25],
    [-2.7, 0.0, 2.025],
    [-2.7, -0.3, 2.025],
    [-3.0, -0.3, 2.25],
    [-3.0, 0.0, 2.25],
    [-2.7, 0.0, 1.8],
    [-2.7, -0.3, 1.8],
    [-3.0, -0.3, 1.8],
    [-3.0, 0.0, 1.8],
    [-1.5, 0.3, 2.25],
    [-1.6, 0.3, 2.025],
    [-2.5, 0.3, 2.25],
    [-2.3, 0.3, 2.025],
    [-3.0, 0.3, 2.25],
    [-2.7, 0.3, 2.025],
    [-3.0, 0.3, 1.8],
    [-2.7, 0.3, 1.8],
    [-2.7, 0.0, 1.575],
    [-2.7, -0.3, 1.575],
    [-3.0, -0.3, 1.35],
    [-3.0, 0.0, 1.35],
    [-2.5, 0.0, 1.125],
    [-2.5, -0.3, 1.125],
    [-2.65, -0.3, 0.9375],
    [-2.65, 0.0, 0.9375],
    [-2.0, -0.3, 0.9],
    [-1.9, -0.3, 0.6],
    [-1.9, 0.0, 0.6],
    [-3.0, 0.3, 1.35],
    [-2.7, 0.3, 1.575],
    [-2.65, 0.3, 0.9375],
    [-2.5, 0.3, 1.125],
    [-1.9, 0.3, 0.6],
    [-2.0, 0.3, 0.9],
    // Spout.
    [1.7, 0.0, 1.425],
    [1.7, -0.66, 1.425],
    [1.7, -0.66, 0.6],
    [1.7, 0.0, 0.6],
    [2.6, 0.0, 1.425],
    [2.6, -0.66, 1.425],
    [3.1, -0.66, 0.825],
    [3.1, 0.0, 0.825],
    [2.3, 0.0, 2.1],
    [2.3, -0.25, 2.1],
    [2.4, -0.25, 2.025],
    [2.4, 0.0, 2.025],
    [2.7, 0.0, 2.4],
    [2.7, -0.25, 2.4],
    [3.3, -0.25, 2.4],
    [3.3, 0.0, 2.4],
    [1.7, 0.66, 0.6],
    [1.7, 0.66, 1.425],
    [3.1, 0.66, 0.825],
    [2.6, 0.66, 1.425],
    [2.4, 0.25, 2.025],
    [2.3, 0.25, 2.1],
    [3.3, 0.25, 2.4],
    [2.7, 0.25, 2.4],
    [2.8, 0.0, 2.475],
    [2.8, -0.25, 2.475],
    [3.525, -0.25, 2.49375],
    [3.525, 0.0, 2.49375],
    [2.9, 0.0, 2.475],
    [2.9, -0.15, 2.475],
    [3.45, -0.15, 2.5125],
    [3.45, 0.0, 2.5125],
    [2.8, 0.0, 2.4],
    [2.8, -0.15, 2.4],
    [3.2, -0.15, 2.4],
    [3.2, 0.0, 2.4],
    [3.525, 0.25, 2.49375],
    [2.8, 0.25, 2.475],
    [3.45, 0.15, 2.5125],
    [2.9, 0.15, 2.475],
    [3.2, 0.15, 2.4],
    [2.8, 0.15, 2.4],
    // Lid.
    [0.0, 0.0, 3.15],
    [0.0, -0.002, 3.15],
    [0.002, 0.0, 3.15],
    [0.8, 0.0, 3.15],
    [0.8, -0.45, 3.15],
    [0.45, -0.8, 3.15],
    [0.0, -0.8, 3.15],
    [0.0, 0.0, 2.85],
    [0.2, 0.0, 2.7],
    [0.2, -0.112, 2.7],
    [0.112, -0.2, 2.7],
    [0.0, -0.2, 2.7],
    [-0.002, 0.0, 3.15],
    [-0.45, -0.8, 3.15],
    [-0.8, -0.45, 3.15],
    [-0.8, 0.0, 3.15],
    [-0.112, -0.2, 2.7],
    [-0.2, -0.112, 2.7],
    [-0.2, 0.0, 2.7],
    [0.0, 0.002, 3.15],
    [-0.8, 0.45, 3.15],
    [-0.45, 0.8, 3.15],
    [0.0, 0.8, 3.15],
    [-0.2, 0.112, 2.7],
    [-0.112, 0.2, 2.7],
    [0.0, 0.2, 2.7],
    [0.45, 0.8, 3.15],
    [0.8, 0.45, 3.15],
    [0.112, 0.2, 2.7],
    [0.2, 0.112, 2.7],
    [0.4, 0.0, 2.55],
    [0.4, -0.224, 2.55],
    [0.224, -0.4, 2.55],
    [0.0, -0.4, 2.55],
    [1.3, 0.0, 2.55],
    [1.3, -0.728, 2.55],
    [0.728, -1.3, 2.55],
    [0.0, -1.3, 2.55],
    [1.3, 0.0, 2.4],
    [1.3, -0.728, 2.4],
    [0.728, -1.3, 2.4],
    [0.0, -1.3, 2.4],
    [-0.224, -0.4, 2.55],
    [-0.4, -0.224, 2.55],
    [-0.4, 0.0, 2.55],
    [-0.728, -1.3, 2.55],
    [-1.3, -0.728, 2.55],
    [-1.3, 0.0, 2.55],
    [-0.728, -1.3, 2.4],
    [-1.3, -0.728, 2.4],
    [-1.3, 0.0, 2.4],
    [-0.4, 0.224, 2.55],
    [-0.224, 0.4, 2.55],
    [0.0, 0.4, 2.55],
    [-1.3, 0.728, 2.55],
    [-0.728, 1.3, 2.55],
    [0.0, 1.3, 2.55],
    [-1.3, 0.728, 2.4],
    [-0.728, 1.3, 2.4],
    [0.0, 1.3, 2.4],
    [0.224, 0.4, 2.55],
    [0.4, 0.224, 2.55],
    [0.728, 1.3, 2.55],
    [1.3, 0.728, 2.55],
    [0.728, 1.3, 2.4],
    [1.3, 0.728, 2.4],
    // Bottom.
    [0.0, 0.0, 0.0],
    [1.5, 0.0, 0.15],
    [1.5, 0.84, 0.15],
    [0.84, 1.5, 0.15],
    [0.0, 1.5, 0.15],
    [1.5, 0.0, 0.075],
    [1.5, 0.84, 0.075],
    [0.84, 1.5, 0.075],
    [0.0, 1.5, 0.075],
    [1.425, 0.0, 0.0],
    [1.425, 0.798, 0.0],
    [0.798, 1.425, 0.0],
    [0.0, 1.425, 0.0],
    [-0.84, 1.5, 0.15],
    [-1.5, 0.84, 0.15],
    [-1.5, 0.0, 0.15],
    [-0.84, 1.5, 0.075],
    [-1.5, 0.84, 0.075],
    [-1.5, 0.0, 0.075],
    [-0.798, 1.425, 0.0],
    [-1.425, 0.798, 0.0],
    [-1.425, 0.0, 0.0],
    [-1.5, -0.84, 0.15],
    [-0.84, -1.5, 0.15],
    [0.0, -1.5, 0.15],
    [-1.5, -0.84, 0.075],
    [-0.84, -1.5, 0.075],
    [0.0, -1.5, 0.075],
    [-1.425, -0.798, 0.0],
    [-0.798, -1.425, 0.0],
    [0.0, -1.425, 0.0],
    [0.84, -1.5, 0.15],
    [1.5, -0.84, 0.15],
    [0.84, -1.5, 0.075],
    [1.5, -0.84, 0.075],
    [0.798, -1.425, 0.0],
    [1.425, -0.798, 0.0],
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Patch `k`'s control points, as the table gives them.
    fn patch(k: usize) -> Patch {
        control_points(&PATCHES[k])
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
        let mut used = [false; 306];
        for &i in PATCHES.iter().flatten() {
            used[usize::from(i) - 1] = true;
        }
        let unused: Vec<usize> = (1..=306).filter(|&i| !used[i - 1]).collect();
        assert_eq!(unused, [205, 206, 216, 223]);
        assert_eq!(VERTICES[93 - 1], VERTICES[271 - 1]);
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
