//! The eye-depth pass (`eye.wgsl`, once per frame).

use super::CascadedSetup;
use crate::grid::Grid;
use crate::optics::height_field_normal;

/// Eye-depth pass: per screen pixel `[view depth, floor area seen, floor z, N_z]` of the first
/// terrain hit of its ray, zeros where it sees no floor (`N_z > 0`, so `w == 0` marks "no floor").
///
/// The area is that of the floor at the pixel's own scale: `|(F_r − F_l) × (F_b − F_t)|` with
/// `F_l, F_r, F_t, F_b` the floor hits of the rays through the midpoints of the pixel's four edges,
/// and `N_z` that parallelogram's. The photons a pixel collects are all those landing inside its
/// cone, on the dunes' far faces as well as on the near faces the eye sees; at grazing views the
/// local normal of the face hit would give the area of that face alone, several times smaller than
/// the floor inside the cone, and the pixel would read up to 42 % too bright (measured on `shore`,
/// docs/cascaded.md). Where an edge ray misses the floor or meets it at less than half or more than
/// twice the centre's depth (a silhouette), the area falls back to the local face's:
/// `z_v² dsx dsy / (|r| |r̂·N|)` with `r` the pixel's ray (forward component 1) and `dsx dsy` the
/// pixel's size on the image plane at distance 1. Times `N_z` the area is horizontal, which the
/// footprint splat compares with a texel's.
pub fn eye_pass(setup: &CascadedSetup, terrain: Option<&Grid>) -> Vec<[f32; 4]> {
    let e = &setup.eye;
    let (w, h) = (e.width, e.height);
    let pixel = (2.0 * e.half * e.aspect / w as f64) * (2.0 * e.half / h as f64);
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let r = e.ray(x as f64 + 0.5, y as f64 + 0.5);
            let len = r.length();
            let d = r / len;
            let texel = match setup.terrain_hit(terrain, e.position, d) {
                Some(s) => {
                    let zv = s / len;
                    let f = e.position + r * zv;
                    let (x, y) = (x as f64, y as f64);
                    // With walls an edge ray must meet the centre's receiver (floor or the same
                    // wall): across a corner the parallelogram would span two planes.
                    let own = setup.walls.then(|| setup.receiver_normal(f));
                    let edge = |px: f64, py: f64| {
                        let r = e.ray(px, py);
                        let s = setup.terrain_hit(terrain, e.position, r.normalize())?;
                        let z = s / r.length();
                        let p = e.position + r * z;
                        let same = own.is_none_or(|n| setup.receiver_normal(p) == n);
                        (z > 0.5 * zv && z < 2.0 * zv && same).then_some(p)
                    };
                    let sides = [
                        edge(x, y + 0.5),
                        edge(x + 1.0, y + 0.5),
                        edge(x + 0.5, y),
                        edge(x + 0.5, y + 1.0),
                    ];
                    let (area, nz) = match sides {
                        [Some(l), Some(r), Some(t), Some(b)] => {
                            let c = (r - l).cross(b - t);
                            (c.length(), (c.z / c.length()).abs())
                        }
                        _ => {
                            let n = own.unwrap_or_else(|| {
                                height_field_normal(setup.terrain_height(terrain, f.truncate()).1)
                            });
                            let cos = d.dot(n).abs().max(1e-4);
                            (zv * zv * pixel / (len * cos), n.z)
                        }
                    };
                    // A wall's map is per area of the wall, not per horizontal area: its
                    // pixels take the area itself (N_z read as 1).
                    let nz = if own.is_some_and(|n| n.z == 0.0) {
                        1.0
                    } else {
                        nz
                    };
                    [zv as f32, area as f32, f.z as f32, nz.max(1e-6) as f32]
                }
                None => [0.0; 4],
            };
            out.push(texel);
        }
    }
    out
}
