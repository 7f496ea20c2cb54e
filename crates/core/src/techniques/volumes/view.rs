//! The refracted view of §3.3 (Fig. 5): the camera above the water sees the objects through the
//! refracting surface. Each pixel's viewing ray meets the water, is refracted there, and is traced
//! against every object's reference planes and depth texture with the same acceptance test as §3.1;
//! the pixel takes the colour of the accepted texel of the object's final image (Eq. 4), or of the
//! floor where the ray reaches it first. GPU twin: `volumes/view.wgsl`.
//!
//! Beyond the paper (stated): the water's Fresnel reflectance mixes in a constant sky colour, the view
//! path is attenuated by `exp(−K d)`, and the floor is seen with one uniform albedo lit by its caustics
//! map (`albedo (E + Ia)`; flat-water light beyond the map's square), so the picture is whole; with
//! the pool's walls the rays that leave the square through a wall see it lit by its map
//! ([`view_pass`]).

use glam::{DVec2, DVec3};

use super::representation::covered;
use super::{ObjectMaps, VolumesSetup};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::optics::{fresnel_transmittance, height_field_normal, refract};
use crate::parallel::prelude::*;
use crate::scene::Camera;
use crate::walls::{Wall, WallMaps};

/// The sky the water reflects.
pub const SKY: [f64; 3] = [0.55, 0.7, 0.9];
/// Fixed-point steps from the rest plane to the waved surface along a viewing ray.
pub const SURFACE_STEPS: usize = 4;

/// The camera as the view pass reads it: pixel `(x, y)` (y down) looks along
/// `forward + right sx + up sy`, `sx = 2 (x + ½) / W − 1`, `sy = 1 − 2 (y + ½) / H`, with `right` and
/// `up` scaled by the field of view (as [`Camera::ray`]).
#[derive(Clone, Copy, Debug)]
pub struct ViewCamera {
    /// The eye, world frame.
    pub position: DVec3,
    /// Unit direction from the eye to the camera's target.
    pub forward: DVec3,
    /// Horizontal, to the right of `forward`, scaled to `tan(fov_y / 2)` times the aspect ratio:
    /// the offset to the image's right edge.
    pub right: DVec3,
    /// Perpendicular to `forward` and `right`, upwards, scaled to `tan(fov_y / 2)`: the offset to
    /// the image's top edge.
    pub up: DVec3,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
}

impl ViewCamera {
    /// The view pass's reading of the scene camera `c`.
    pub fn new(c: &Camera) -> Self {
        let forward = (c.target - c.position).normalize();
        let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
        let up = right.cross(forward);
        let half = (c.fov_y.to_radians() * 0.5).tan();
        let aspect = c.width as f64 / c.height as f64;
        ViewCamera {
            position: c.position,
            forward,
            right: right * half * aspect,
            up: up * half,
            width: c.width as usize,
            height: c.height as usize,
        }
    }

    /// Unit direction of the ray through the centre of pixel `(x, y)` (y down).
    pub fn dir(&self, x: usize, y: usize) -> DVec3 {
        let sx = 2.0 * (x as f64 + 0.5) / self.width as f64 - 1.0;
        let sy = 1.0 - 2.0 * (y as f64 + 0.5) / self.height as f64;
        (self.forward + self.right * sx + self.up * sy).normalize()
    }
}

/// What the refracted ray from `s` along `r` sees first: `(path, object, texel)` of the nearest
/// accepted plane point over all objects (planes taken in the order the ray meets them).
pub fn trace_objects(
    setup: &VolumesSetup,
    depths: &[&[[f32; 4]]],
    s: DVec3,
    r: DVec3,
) -> Option<(f64, usize, usize)> {
    let mut best: Option<(f64, usize, usize)> = None;
    for (k, o) in setup.objects.iter().enumerate() {
        let view = &o.view;
        let vr = view.v.dot(r);
        if vr <= 1e-6 {
            continue;
        }
        let half = 0.5 * o.spacing();
        let res = view.res;
        for p in 0..o.planes {
            let zk = o.plane_depth(p);
            let u = (view.lo.z + zk - view.v.dot(s)) / vr;
            if u < 0.0 || best.is_some_and(|b| b.0 <= u) {
                continue;
            }
            let px = view.to_pixel(view.to_frame(s + r * u));
            let (j, i) = (px.x.floor(), px.y.floor());
            if !(j >= 0.0 && i >= 0.0 && j < res as f64 && i < res as f64) {
                continue;
            }
            let texel = i as usize * res + j as usize;
            let t = &depths[k][texel];
            if covered(t) && (t[0] as f64 - zk).abs() <= half {
                best = Some((u, k, texel));
                // Later planes are further along the ray.
                break;
            }
        }
    }
    best
}

/// Where the viewing ray `o + t d` (going down) meets the waved surface, and the surface's
/// displacement gradient there.
pub fn surface_hit(
    setup: &VolumesSetup,
    heights: &Grid,
    wrap: bool,
    o: DVec3,
    d: DVec3,
) -> (DVec3, DVec2) {
    let edge = if wrap { Edge::Wrap } else { Edge::Clamp };
    let mut t = (setup.depth - o.z) / d.z;
    let mut hg = heights.sample((o + d * t).truncate(), setup.size, edge);
    for _ in 0..SURFACE_STEPS {
        t = (setup.depth + hg.0 - o.z) / d.z;
        hg = heights.sample((o + d * t).truncate(), setup.size, edge);
    }
    (o + d * t, hg.1)
}

/// The view pass: one RGB per camera pixel, row 0 at the top, seeing the pool's walls when `walls`
/// holds their maps: a refracted ray from the pool's surface that leaves the square through a
/// wall before it reaches the floor sees that wall, lit by its map's nearest texel (`albedo (E + Ia)`, the floor's albedo: the pool is
/// one material). The pool is sunk into a deck, as in the project's final image: a ray that meets
/// the deck's plane beyond the square, or the water's beyond it, sees the deck ([`deck`]).
#[allow(clippy::too_many_arguments)]
pub fn view_pass(
    setup: &VolumesSetup,
    camera: &ViewCamera,
    heights: &Grid,
    wrap: bool,
    objects: &[ObjectMaps],
    floor: &CausticsMap,
    walls: Option<&WallMaps>,
    floor_albedo: DVec3,
) -> Vec<[f32; 3]> {
    let depths: Vec<&[[f32; 4]]> = objects.iter().map(|o| o.depth.as_slice()).collect();
    let sky = DVec3::from(SKY);
    let flat = flat_floor_light(setup);
    let (w, h) = (camera.width, camera.height);
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let d = camera.dir(k % w, k / w);
            let o = camera.position;
            if d.z >= 0.0 || o.z <= setup.depth {
                return sky.as_vec3().to_array();
            }
            if walls.is_some()
                && let Some(c) = deck(setup, o + d * ((deck_height(setup) - o.z) / d.z).max(0.0))
            {
                return c.as_vec3().to_array();
            }
            let (s, grad) = surface_hit(setup, heights, wrap, o, d);
            if walls.is_some()
                && let Some(c) = deck(setup, s)
            {
                return c.as_vec3().to_array();
            }
            let n = height_field_normal(grad);
            let cos_i = -d.dot(n);
            let (Some(r), true) = (refract(d, n, setup.eta), cos_i > 0.0) else {
                return sky.as_vec3().to_array();
            };
            let tr = fresnel_transmittance(cos_i, 1.0, setup.ior);
            let t_floor = s.z / -r.z;
            let wall = walls.and_then(|maps| wall_hit(maps, setup.size, s, r));
            let t_end = wall.map_or(t_floor, |w| w.0.min(t_floor));
            let (path, under) = match trace_objects(setup, &depths, s, r) {
                Some((u, obj, texel)) if u < t_end => {
                    let c = objects[obj].image[texel];
                    (u, DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64))
                }
                _ if t_end < t_floor => {
                    let e = wall.expect("nearer than the floor").1;
                    (t_end, floor_albedo * (e + setup.params.ambient))
                }
                _ => {
                    let p = (s + r * t_floor).truncate();
                    let e = floor_texel(floor, p).unwrap_or(flat);
                    (t_floor, floor_albedo * (e + setup.params.ambient))
                }
            };
            let c = under * (-setup.absorption * path).exp() * tr + sky * (1.0 - tr);
            c.as_vec3().to_array()
        })
        .collect()
}

/// The deck's height: the final image's (`crates/core/src/render/shade.rs`, `shade_above`) less its
/// bound on the waves' height, which the view does not know.
pub fn deck_height(setup: &VolumesSetup) -> f64 {
    setup.depth + 0.1 * setup.size.min(1.0)
}

/// The deck around the pool at `p` when `p` lies beyond the pool's square (`None` over the pool):
/// the final image's grey checker of 1/3 m squares, in the sun's full light (relative to the
/// floor's under flat water: `1 / T(θ0)`, no water on the way) plus `Ia`.
pub fn deck(setup: &VolumesSetup, p: DVec3) -> Option<DVec3> {
    let inside = (0.0..=setup.size).contains(&p.x) && (0.0..=setup.size).contains(&p.y);
    if inside {
        return None;
    }
    let v = ((p.x * 3.0).floor() + (p.y * 3.0).floor()).rem_euclid(2.0);
    Some(DVec3::splat(0.32 + 0.04 * v) * (1.0 / setup.t_flat + setup.params.ambient))
}

/// Where the refracted ray `s + t r` from the surface inside the pool's square leaves it through a
/// wall: `t` and that wall's map's nearest texel there (the top row for a hit above the rest level,
/// near a crest); `None` from beyond the square or for a vertical ray.
pub fn wall_hit(walls: &WallMaps, size: f64, s: DVec3, r: DVec3) -> Option<(f64, DVec3)> {
    let inside = (0.0..=size).contains(&s.x) && (0.0..=size).contains(&s.y);
    if !inside {
        return None;
    }
    let (wall, t) = Wall::exit(s.truncate(), r.truncate(), size)?;
    let q = s + r * t;
    let m = walls.get(wall);
    let j = (wall.along(q) / m.length * m.cols as f64)
        .floor()
        .clamp(0.0, (m.cols - 1) as f64);
    let i = (q.z / m.height * m.rows as f64)
        .floor()
        .clamp(0.0, (m.rows - 1) as f64);
    let e = m.texels[i as usize * m.cols + j as usize];
    Some((t, DVec3::new(e[0] as f64, e[1] as f64, e[2] as f64)))
}

/// The floor map's nearest texel at `p`; `None` beyond the map's square, where the view pass uses
/// the light of flat water (as the project's final image does where a map has nothing): a periodic
/// map wrapped there would repeat the objects' shadows without the objects.
pub fn floor_texel(floor: &CausticsMap, p: DVec2) -> Option<DVec3> {
    let px = (p / floor.size * DVec2::new(floor.width as f64, floor.height as f64)).floor();
    if !(px.x >= 0.0 && px.y >= 0.0 && px.x < floor.width as f64 && px.y < floor.height as f64) {
        return None;
    }
    let t = floor.texels[px.y as usize * floor.width + px.x as usize];
    Some(DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64))
}

/// Relative irradiance on the floor under flat water: the absorption along the flat refracted sun.
pub fn flat_floor_light(setup: &VolumesSetup) -> DVec3 {
    (-setup.absorption * (setup.depth / -setup.t0.z)).exp()
}
