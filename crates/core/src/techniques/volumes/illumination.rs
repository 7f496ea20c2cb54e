//! The illumination volumes of §3.2: the refracted light at the water lattice's vertices, the slices
//! of each triangle's volume by the reference planes drawn into an object's caustics map, the floor
//! map, the walls' maps, and Eq. 4. GPU twins: `volumes/{water,slices,floor,walls,shade}.wgsl`.

use glam::{DVec2, DVec3};

use super::representation::{OrthoView, covered};
use super::{CellRect, ObjectView, VolumesSetup};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::optics::{air_transmittance, height_field_normal, refract};
use crate::parallel::{par_sum, prelude::*};
use crate::receivers::{ReceiverHeights, light_space};
use crate::walls::{Wall, WallMaps};

/// One lattice vertex after refraction: `[x, y, z, weight, tx, ty, tz, 0]`: the point on the surface,
/// the Fresnel weight `T(θi) / T(θ0)` (0 where no light enters: the surface faces away from the sun)
/// and the unit refracted direction.
pub type WaterVertex = [f32; 8];

/// Refraction at lattice vertex `(i, j)`; the surface is the bicubic interpolant of `heights`.
pub fn water_vertex(
    setup: &VolumesSetup,
    heights: &Grid,
    wrap: bool,
    i: usize,
    j: usize,
) -> WaterVertex {
    let p = setup.lattice.position(i, j);
    let edge = if wrap { Edge::Wrap } else { Edge::Clamp };
    let (h, grad) = heights.sample(p, setup.size, edge);
    let n = height_field_normal(grad);
    let l = setup.light;
    let cos_i = -l.dot(n);
    let z = setup.depth + h;
    match refract(l, n, setup.eta) {
        Some(t) if cos_i > 0.0 => {
            let w = air_transmittance(setup.params.fresnel, cos_i, setup.ior) / setup.t_flat;
            [
                p.x as f32, p.y as f32, z as f32, w as f32, t.x as f32, t.y as f32, t.z as f32, 0.0,
            ]
        }
        _ => [p.x as f32, p.y as f32, z as f32, 0.0, 0.0, 0.0, -1.0, 0.0],
    }
}

/// The water pass: every lattice vertex, row-major.
pub fn water_pass(setup: &VolumesSetup, heights: &Grid, wrap: bool) -> Vec<WaterVertex> {
    let lat = &setup.lattice;
    (0..lat.vertex_count())
        .into_par_iter()
        .map(|k| water_vertex(setup, heights, wrap, k / (lat.nx + 1), k % (lat.nx + 1)))
        .collect()
}

/// A triangle of an illumination volume cut by a plane: its vertices, their intensities `Ic` (Eq. 3,
/// per channel) and their refracted directions.
#[derive(Clone, Copy, Debug)]
pub struct Slice {
    /// Where each vertex's refracted ray meets the plane, world frame.
    pub points: [DVec3; 3],
    /// `Ic` at each vertex, RGB relative irradiance across the rays (before the receiver's
    /// cosine).
    pub intensity: [DVec3; 3],
    /// Each vertex's unit refracted direction `t`, as the water pass gave it.
    pub dirs: [DVec3; 3],
}

fn v3(a: &[f32], k: usize) -> DVec3 {
    DVec3::new(a[k] as f64, a[k + 1] as f64, a[k + 2] as f64)
}

/// The illumination volume of the water triangle `tri` cut by the plane `{x : n · x = c}`, `n` the
/// side the light travels to. `None` where no light leaves the triangle, where the sun sees its back,
/// where a ray runs parallel to the plane or meets it above the water, or where the slice is flat.
///
/// Eq. 3 per vertex: `Ic = Φ w exp(−K d) / (Ad (n · t))`, with `Φ` the triangle's area projected along
/// the sun onto the horizontal (`Ii Aw cos θi` relative to the sun on a horizontal surface), `w` the
/// Fresnel weight, `d` the vertex's path to the plane, `Ad` the slice's area and `n · t = cos θt`.
pub fn slice(setup: &VolumesSetup, tri: [&WaterVertex; 3], n: DVec3, c: f64) -> Option<Slice> {
    if tri.iter().any(|v| v[3] <= 0.0) {
        return None;
    }
    let s = tri.map(|v| v3(v, 0));
    let t = tri.map(|v| v3(v, 4));
    let l = setup.light;
    let flux = -l.dot((s[1] - s[0]).cross(s[2] - s[0])) / (2.0 * -l.z);
    if flux <= 0.0 {
        return None;
    }
    let mut points = [DVec3::ZERO; 3];
    let mut path = [0.0; 3];
    let mut cos_t = [0.0; 3];
    for k in 0..3 {
        cos_t[k] = n.dot(t[k]);
        if cos_t[k] <= 1e-6 {
            return None;
        }
        path[k] = (c - n.dot(s[k])) / cos_t[k];
        if path[k] < 0.0 {
            return None;
        }
        points[k] = s[k] + t[k] * path[k];
    }
    let area = 0.5
        * (points[1] - points[0])
            .cross(points[2] - points[0])
            .length();
    if !(area > 0.0 && area.is_finite()) {
        return None;
    }
    let intensity = std::array::from_fn(|k| {
        (-setup.absorption * path[k]).exp() * (flux * tri[k][3] as f64 / (area * cos_t[k]))
    });
    Some(Slice {
        points,
        intensity,
        dirs: t,
    })
}

/// Call `f(i, j, barycentrics)` for every texel centre inside the triangle `v` (pixel coordinates,
/// y down as in the framebuffer), with the rasteriser's top-left rule for centres exactly on an edge:
/// such a centre belongs to the triangle only if the edge is a left edge (the interior on its right,
/// outward normal towards −x) or a top edge (horizontal, interior below it). Triangles that share an
/// edge then draw each centre on it once, as the GPU does (flat water lines texel centres up on the
/// lattice's diagonals).
pub fn raster(
    width: usize,
    height: usize,
    v: [DVec2; 3],
    mut f: impl FnMut(usize, usize, [f64; 3]),
) {
    let area2 = (v[1] - v[0]).perp_dot(v[2] - v[0]);
    if area2 == 0.0 || !area2.is_finite() {
        return;
    }
    // Edge k is opposite vertex k; it owns the centres on it if it is top-left.
    let owns = |k: usize| {
        let (a, b, c) = (v[(k + 1) % 3], v[(k + 2) % 3], v[k]);
        let e = b - a;
        let mut n = DVec2::new(e.y, -e.x);
        if n.dot(c - a) > 0.0 {
            n = -n;
        }
        n.x < 0.0 || (n.x == 0.0 && n.y < 0.0)
    };
    let top_left = [owns(0), owns(1), owns(2)];
    let lo = v[0].min(v[1]).min(v[2]);
    let hi = v[0].max(v[1]).max(v[2]);
    let j0 = (lo.x - 0.5).ceil().max(0.0);
    let j1 = (hi.x - 0.5).floor().min(width as f64 - 1.0);
    let i0 = (lo.y - 0.5).ceil().max(0.0);
    let i1 = (hi.y - 0.5).floor().min(height as f64 - 1.0);
    if j1 < j0 || i1 < i0 {
        return;
    }
    for i in i0 as usize..=i1 as usize {
        for j in j0 as usize..=j1 as usize {
            let c = DVec2::new(j as f64 + 0.5, i as f64 + 0.5);
            let e = [
                (v[2] - v[1]).perp_dot(c - v[1]),
                (v[0] - v[2]).perp_dot(c - v[2]),
                (v[1] - v[0]).perp_dot(c - v[0]),
            ];
            let inside = (0..3).all(|k| {
                let s = e[k] * area2.signum();
                s > 0.0 || (s == 0.0 && top_left[k])
            });
            if inside {
                let b0 = e[0] / area2;
                let b1 = e[1] / area2;
                f(i, j, [b0, b1, 1.0 - b0 - b1]);
            }
        }
    }
}

/// The shadow test's bias for floor points: nothing lies below the floor, so any surface in the
/// shadow map's column over a floor point occludes it (even an object's base resting on the floor at
/// the point's own depth).
pub const FLOOR_BIAS: f64 = -1e30;

/// Whether world point `p` sees the refracted sun past the objects in the shadow map (always without
/// one): no stored surface lies more than `bias` in front of it. On an object's surface the bias
/// absorbs the map's texel quantisation on the surfaces it was rendered from ([`FLOOR_BIAS`] on the
/// floor).
pub fn lit(view: Option<&OrthoView>, map: &[[f32; 4]], p: DVec3, bias: f64) -> bool {
    let Some(view) = view else { return true };
    let q = view.to_frame(p);
    match view.lookup(map, q) {
        Some(t) => t[0] as f64 >= q.z - bias,
        None => true,
    }
}

fn interpolate(values: &[DVec3; 3], b: [f64; 3]) -> DVec3 {
    values[0] * b[0] + values[1] * b[1] + values[2] * b[2]
}

/// The slice pass (§3.2, Fig. 4a): every illumination volume of the object's cells cut by each of its
/// reference planes, drawn additively into its caustics map; a fragment is kept where the depth test
/// accepts it (the stored depth within `Δ/2` of the plane's) and the shadow map lets the sun through,
/// and carries `Ic · max(0, −t · n)`.
pub fn slice_pass(
    setup: &VolumesSetup,
    object: &ObjectView,
    depth: &[[f32; 4]],
    water: &[WaterVertex],
    shadow: &[[f32; 4]],
) -> Vec<[f32; 3]> {
    let view = &object.view;
    let res = view.res;
    let half = 0.5 * object.spacing();
    let cells = object.cells;
    let shadow_view = setup.shadow.as_ref();
    par_sum(0..object.planes, res * res, |acc, k| {
        let zk = object.plane_depth(k);
        let c = view.lo.z + zk;
        for m in 0..cells.triangles() {
            let idx = cells.triangle(&setup.lattice, m);
            let tri = idx.map(|i| &water[i]);
            let Some(s) = slice(setup, tri, view.v, c) else {
                continue;
            };
            let px = s.points.map(|p| view.to_pixel(view.to_frame(p)));
            raster(res, res, px, |i, j, b| {
                let t = &depth[i * res + j];
                if !covered(t) || (t[0] as f64 - zk).abs() > half {
                    return;
                }
                let normal = DVec3::new(t[1] as f64, t[2] as f64, t[3] as f64);
                let dir = interpolate(&s.dirs, b).normalize();
                let cos = -dir.dot(normal);
                if cos <= 0.0 {
                    return;
                }
                let p = view.texel_point(i, j, t[0] as f64);
                if !lit(shadow_view, shadow, p, setup.shadow_bias) {
                    return;
                }
                acc[i * res + j] += interpolate(&s.intensity, b) * cos;
            });
        }
    })
    .into_iter()
    .map(|e| e.as_vec3().to_array())
    .collect()
}

/// The floor pass: every illumination volume of the water cut by the floor `z = 0` and drawn into the
/// floor map, fragments kept where the shadow map lets the sun through. `Ic · cos θt` on the floor is
/// `Φ w exp(−K d) / Ad`: the flux over the area it lands on.
pub fn floor_pass(setup: &VolumesSetup, water: &[WaterVertex], shadow: &[[f32; 4]]) -> CausticsMap {
    let shadow_view = setup.shadow.as_ref();
    draw_floor(setup, |idx, scale, acc| {
        let tri = idx.map(|i| &water[i]);
        let Some(s) = slice(setup, tri, DVec3::NEG_Z, 0.0) else {
            return;
        };
        let px = s.points.map(|p| p.truncate() * scale);
        raster(setup.width, setup.height, px, |i, j, b| {
            let dir = interpolate(&s.dirs, b).normalize();
            let p = DVec3::new((j as f64 + 0.5) / scale.x, (i as f64 + 0.5) / scale.y, 0.0);
            if lit(shadow_view, shadow, p, FLOOR_BIAS) {
                acc[i * setup.width + j] += interpolate(&s.intensity, b) * -dir.z;
            }
        });
    })
}

/// Where each lattice vertex's refracted ray first meets the receivers (GPU twin `meet.wgsl`):
/// `[q_x, q_y, d, 1]` with `q` the hit's light-space point and `d` the path in the water, `[0, 0,
/// 0, 0]` where no light leaves the vertex or its ray never comes down onto them.
pub fn meet_pass(water: &[WaterVertex], receivers: &ReceiverHeights) -> Vec<[f32; 4]> {
    water
        .par_iter()
        .map(|v| {
            if v[3] <= 0.0 {
                return [0.0; 4];
            }
            match receivers.meet(v3(v, 0), v3(v, 4)) {
                Some((hit, d)) => {
                    let q = light_space(hit, receivers.t0);
                    [q.x as f32, q.y as f32, d as f32, 1.0]
                }
                None => [0.0; 4],
            }
        })
        .collect()
}

/// The floor pass over receivers (GPU twin `floor_receivers.wgsl`): each illumination volume ends
/// where its vertices' rays meet the receivers ([`meet_pass`]) and is drawn in the light's space
/// at their light-space points, each vertex carrying `Φ w exp(−K d) / A_q` with `A_q` the drawn
/// triangle's area: flux per unit area of `z = 0` along the light, the deposit the receivers'
/// lookup reads ([`crate::receivers::lookup`], no absorption: each vertex carries its own path's).
/// Fragments are kept where the shadow map lets the sun reach the receiver point under them.
pub fn received_floor_pass(
    setup: &VolumesSetup,
    receivers: &ReceiverHeights,
    water: &[WaterVertex],
    hits: &[[f32; 4]],
    shadow: &[[f32; 4]],
) -> CausticsMap {
    let shadow_view = setup.shadow.as_ref();
    let t0 = receivers.t0;
    draw_floor(setup, |idx, scale, acc| {
        let h = idx.map(|i| hits[i]);
        if h.iter().any(|h| h[3] == 0.0) {
            return;
        }
        let s = idx.map(|i| v3(&water[i], 0));
        let l = setup.light;
        let flux = -l.dot((s[1] - s[0]).cross(s[2] - s[0])) / (2.0 * -l.z);
        let q = h.map(|h| DVec2::new(h[0] as f64, h[1] as f64));
        let area = 0.5 * (q[1] - q[0]).perp_dot(q[2] - q[0]).abs();
        if flux <= 0.0 || !(area > 0.0 && area.is_finite()) {
            return;
        }
        let intensity: [DVec3; 3] = std::array::from_fn(|k| {
            (-setup.absorption * h[k][2] as f64).exp() * (flux * water[idx[k]][3] as f64 / area)
        });
        raster(
            setup.width,
            setup.height,
            q.map(|q| q * scale),
            |i, j, b| {
                let c = DVec2::new((j as f64 + 0.5) / scale.x, (i as f64 + 0.5) / scale.y);
                let z = receivers.height(c);
                let p = (c - t0.truncate() * (z / -t0.z)).extend(z);
                if lit(shadow_view, shadow, p, FLOOR_BIAS) {
                    acc[i * setup.width + j] += interpolate(&intensity, b);
                }
            },
        );
    })
}

/// The floor map's texels summed over every triangle of the lattice: `draw` adds one triangle's
/// fragments (its water vertices' indices, the map's texels per unit length).
fn draw_floor(
    setup: &VolumesSetup,
    draw: impl Fn([usize; 3], DVec2, &mut [DVec3]) + Sync,
) -> CausticsMap {
    let (w, h) = (setup.width, setup.height);
    let scale = DVec2::new(w as f64 / setup.size, h as f64 / setup.size);
    let cells: CellRect = setup.all_cells();
    let acc = par_sum(cells.i0..cells.i1, w * h, |acc, ci| {
        for cj in cells.j0..cells.j1 {
            for which in 0..2 {
                draw(setup.lattice.triangle(ci, cj, which), scale, acc);
            }
        }
    });
    let mut map = CausticsMap::new(w, h, setup.size);
    for (t, e) in map.texels.iter_mut().zip(acc) {
        *t = e.as_vec3().to_array();
    }
    map
}

/// The wall pass: every illumination volume of the water cut by each wall's plane
/// `{x : n · x = c}` (`n = −wall.normal()`, the side the light travels to) and drawn into that
/// wall's map in its texel space `(along, z)`, fragments kept where the shadow map lets the sun
/// through; a fragment carries `Ic · (t · n)`, the irradiance on the wall (as `Ic · cos θt` on the
/// floor: the flux over the area it lands on).
///
/// # Every receiver gets the whole volume, the clip keeps the light that ends there
/// The water is the pool's square (the lattice with walls), so a ray leaves the surface inside the
/// box of floor and walls and ends on the first of its faces it meets; from inside a convex box
/// that is the one face whose plane it meets within the face's rectangle. Each wall's plane
/// therefore takes every volume extended to it (past the floor, or beyond another wall, where the
/// rays end elsewhere), and clipping the slice to the wall's rectangle (`along` in `[0, size]`,
/// `z` in `[0, depth]`) keeps exactly the part whose light ends on that wall; the floor pass,
/// clipped to `[0, size]²`, keeps exactly the part that ends on the floor, since a ray meeting the
/// floor plane outside the square has crossed a wall on the way. A volume straddling the
/// floor-wall edge is split along it, each part drawn with its own plane's Eq. 3 intensities.
///
/// A slice is dropped where a vertex's ray runs parallel to or away from the wall (no point on the
/// plane: [`slice()`]), and where a vertex meets the wall plane more than `size` below the floor (a
/// near-vertical ray whose extension would put a far vertex into the rasteriser), as
/// caustic-triangles drops such photons: the slice's share on the wall is then a sliver at its
/// edge, and the flux lost is measured in the tests. Light meeting a wall above the rest water
/// level (near a crest at the wall) is outside the map and lost as well. The shadow test uses the
/// objects' depth tolerance (`shadow_bias`), not [`FLOOR_BIAS`]: along `t₀` an object may lie
/// beyond a wall point (the wall the sun faces), and must not shadow it.
pub fn wall_pass(setup: &VolumesSetup, water: &[WaterVertex], shadow: &[[f32; 4]]) -> WallMaps {
    let mut maps = WallMaps::for_floor_map(setup.width, setup.height, setup.size, setup.depth);
    let cells: CellRect = setup.all_cells();
    let shadow_view = setup.shadow.as_ref();
    for wall in Wall::ALL {
        let map = maps.get_mut(wall);
        let (cols, height) = (map.cols, map.rows);
        let scale = DVec2::new(cols as f64 / setup.size, height as f64 / setup.depth);
        let n = -wall.normal();
        let c = n.dot(wall.point(0.0, 0.0, setup.size));
        let acc = par_sum(cells.i0..cells.i1, cols * height, |acc, ci| {
            for cj in cells.j0..cells.j1 {
                for which in 0..2 {
                    let idx = setup.lattice.triangle(ci, cj, which);
                    let tri = idx.map(|i| &water[i]);
                    let Some(s) = slice(setup, tri, n, c) else {
                        continue;
                    };
                    if s.points.iter().any(|p| p.z < -setup.size) {
                        continue;
                    }
                    let px = s.points.map(|p| DVec2::new(wall.along(p), p.z) * scale);
                    raster(cols, height, px, |i, j, b| {
                        let dir = interpolate(&s.dirs, b).normalize();
                        let p = wall.point(
                            (j as f64 + 0.5) / scale.x,
                            (i as f64 + 0.5) / scale.y,
                            setup.size,
                        );
                        if !lit(shadow_view, shadow, p, setup.shadow_bias) {
                            return;
                        }
                        acc[i * cols + j] += interpolate(&s.intensity, b) * dir.dot(n);
                    });
                }
            }
        });
        for (t, e) in map.texels.iter_mut().zip(acc) {
            *t = e.as_vec3().to_array();
        }
    }
    maps
}

/// Eq. 4 over the diffuse map: `Io = Id (Ic + Ia)` where the object covers the texel.
pub fn shade_pass(diffuse: &[[f32; 4]], caustics: &[[f32; 3]], ambient: f64) -> Vec<[f32; 3]> {
    let a = ambient as f32;
    diffuse
        .iter()
        .zip(caustics)
        .map(|(d, e)| {
            if d[3] > 0.0 {
                [d[0] * (e[0] + a), d[1] * (e[1] + a), d[2] * (e[2] + a)]
            } else {
                [0.0; 3]
            }
        })
        .collect()
}
