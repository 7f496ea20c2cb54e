//! The caustic triangles pass (§4.2), CPU twin of `caustic_triangles/triangles.wgsl`: two
//! Gouraud-shaded triangles per drawn quad ([`merge::drawn_quads`]), rasterised at texel centres.

use glam::{DVec2, DVec3};

use super::{CausticTrianglesSetup, FloorWindow, merge};
use crate::map::CausticsMap;

/// Edge `a → b`'s function at `c` (twice the signed area of `a, b, c`), the same number with the
/// sign flipped for `b → a`: evaluated from the edge's lower endpoint either way, so two triangles
/// sharing the edge agree on which side of it a texel centre lies, to the bit.
fn edge_function(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    if (a.x, a.y) <= (b.x, b.y) {
        (b - a).perp_dot(c - a)
    } else {
        -(a - b).perp_dot(c - b)
    }
}

/// Whether a texel centre exactly on edge `a → b` belongs to the triangle on the edge's positive
/// side (`inside` > 0 where that is its interior): one of the two triangles that share an edge
/// takes it, as a GPU's fill rule does, so a texel is never drawn twice nor missed.
fn owns_ties(a: DVec2, b: DVec2, inside: f64) -> bool {
    let d = (b - a) * inside.signum();
    d.y < 0.0 || (d.y == 0.0 && d.x > 0.0)
}

/// Every texel centre inside triangle `v` (map pixel coordinates): its index and barycentric
/// coordinates, what the rasteriser interpolates with.
pub(super) fn raster_barycentric(
    width: usize,
    height: usize,
    v: [DVec2; 3],
    mut texel: impl FnMut(usize, [f64; 3]),
) {
    let area2 = (v[1] - v[0]).perp_dot(v[2] - v[0]);
    if area2 == 0.0 || !area2.is_finite() {
        return;
    }
    let lo = v[0].min(v[1]).min(v[2]);
    let hi = v[0].max(v[1]).max(v[2]);
    let j0 = ((lo.x - 0.5).ceil().max(0.0)) as i64;
    let j1 = ((hi.x - 0.5).floor()).min(width as f64 - 1.0) as i64;
    let i0 = ((lo.y - 0.5).ceil().max(0.0)) as i64;
    let i1 = ((hi.y - 0.5).floor()).min(height as f64 - 1.0) as i64;
    for i in i0..=i1 {
        for j in j0..=j1 {
            let c = DVec2::new(j as f64 + 0.5, i as f64 + 0.5);
            let e = [
                edge_function(v[1], v[2], c),
                edge_function(v[2], v[0], c),
                edge_function(v[0], v[1], c),
            ];
            let inside = (0..3).all(|k| {
                let side = e[k] * area2;
                side > 0.0 || (side == 0.0 && owns_ties(v[(k + 1) % 3], v[(k + 2) % 3], area2))
            });
            if inside {
                let (b0, b1) = (e[0] / area2, e[1] / area2);
                texel(i as usize * width + j as usize, [b0, b1, 1.0 - b0 - b1]);
            }
        }
    }
}

pub(super) fn to_map(floor: &FloorWindow, acc: Vec<[f32; 3]>) -> CausticsMap {
    let mut map = floor.empty_map();
    map.texels = acc;
    map
}

/// One value per RGB channel: `e exp(−K d)` (the fragment shader's colour).
pub(super) fn attenuated(e: f64, d: f64, k: DVec3) -> [f32; 3] {
    let a = (-k * d).exp() * e;
    [a.x as f32, a.y as f32, a.z as f32]
}

/// Caustic triangles (§4.2): two per quad of four valid photon-image texels of one path signature,
/// `(i, j) (i, j+1) (i+1, j+1)` and `(i, j) (i+1, j+1) (i+1, j)`, Gouraud shaded, added; with
/// `merge_levels`, merged blocks of small quads instead ([`merge`]).
pub fn triangles_pass(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    irradiance: &[f32],
) -> CausticsMap {
    triangles_pass_with_paths(setup, photons, irradiance, None)
}

/// [`triangles_pass`] with each photon's refracted path length (a water generator, [`water`](super::water)):
/// each vertex carries its irradiance attenuated along its own path, `E exp(−K d)` per channel,
/// and that is what the triangle interpolates (Gouraud shading of the absorbed light: across a
/// triangle the path changes by millimetres, and the vertex shader does the exponentials the
/// fragments would otherwise repeat); the triangles are drawn at every offset of
/// [`CausticTrianglesSetup::copies`].
pub fn triangles_pass_with_paths(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    irradiance: &[f32],
    paths: Option<&[f32]>,
) -> CausticsMap {
    let f = &setup.floor;
    let k = setup.absorption();
    let copies = setup.copies();
    let rects: Vec<_> = (0..copies.len()).map(|k| setup.copy_rect(k)).collect();
    let mut acc = vec![[0.0f32; 3]; f.width * f.height];
    for (x, e, idx) in merge::drawn_quads(setup, photons, irradiance) {
        let d = paths.map_or([0.0; 4], |p| idx.map(|i| p[i] as f64));
        let light: [[f32; 3]; 4] = std::array::from_fn(|v| attenuated(e[v], d[v], k));
        let (qi, qj) = (idx[0] / setup.p, idx[0] % setup.p);
        for (&off, &(i0, i1, j0, j1)) in copies.iter().zip(&rects) {
            if !((i0..i1).contains(&qi) && (j0..j1).contains(&qj)) {
                continue;
            }
            let [a, b, c, q] = x.map(|x| f.to_pixel(x + off));
            for (v, t) in [([a, b, c], [0, 1, 2]), ([a, c, q], [0, 2, 3])] {
                raster_barycentric(f.width, f.height, v, |texel, w| {
                    let [l0, l1, l2] = t.map(|v| light[v]);
                    for (c, a) in acc[texel].iter_mut().enumerate() {
                        *a += (w[0] * l0[c] as f64 + w[1] * l1[c] as f64 + w[2] * l2[c] as f64)
                            as f32;
                    }
                });
            }
        }
    }
    to_map(f, acc)
}
