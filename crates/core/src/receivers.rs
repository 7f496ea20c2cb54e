//! What lies under the water as the sun sees it through flat water, and how a technique's light
//! meets it: the receivers' height map in the light's space.
//!
//! This is caustics mapping's receiver model (Shah, Konttinen & Pattanaik, "Caustics Mapping: An
//! Image-Space Technique for Real-Time Caustics", TVCG 13(2), 2007, §3: the receivers' positions
//! rendered from the light, the refracted rays met against them in the light's image) and paper 5's
//! light-view terrain depth, written for one sun under one water surface.
//!
//! # The light's space
//! Orthographic along `t₀`, the sun refracted by flat water: every ray a technique follows leaves
//! the surface near `t₀`. A point `P`'s light-space coordinate is where the line through it along
//! `t₀` meets the floor plane, `q(P) = P_xy + P_z · t₀_xy / −t₀_z` (an oblique projection: on the
//! plane `z = 0` a point is its own light-space point, so on a flat floor the light's texels are
//! the floor's); its depth is its height `P_z`. [`ReceiverHeights`] holds, per light-space texel,
//! the height of the first receiver that line meets coming down from the water: the one nearest
//! the light.
//!
//! # Meeting a ray
//! A ray `s + d t` leaving the surface meets the receivers where `g(d) = P_z(d) − H(q(P(d)))`
//! changes sign (`H` the map, bilinear). Along `t₀` itself `q` does not move and one step of
//! `g / −t_z` lands on the receiver; a ray tilted from `t₀` moves `q` by `t_xy − t_z t₀_xy / t₀_z`
//! per unit `d`, so steps bounded by `g` over the largest rate (`−t_z` plus that drift times the
//! map's steepest slope) never step over a receiver, and bisection finishes the sign change.
//!
//! # Looking the light up
//! A technique that meets the receivers this way deposits its light in light space: flux per unit
//! area of the plane `z = 0` along the light, which is the relative irradiance of a flat floor. A
//! receiver point `P` with normal `n` then takes [`lookup`]: the deposit at `q(P)` times
//! `n · (−t₀) / −t₀_z` (its area as the light sees it over its horizontal area under a flat floor's
//! light), and nothing where it lies below the map's height at `q(P)` (something nearer the light
//! covers it), as a shadow map's depth test.

use std::sync::Arc;

use glam::{DVec2, DVec3};

use crate::map::CausticsMap;
use crate::optics::refract;
use crate::parallel::prelude::*;
use crate::scene::{Floor, Solids};

/// Light-space coordinate of `p`: where the line through it along `t0` meets the plane `z = 0`.
pub fn light_space(p: DVec3, t0: DVec3) -> DVec2 {
    p.truncate() + t0.truncate() * (p.z / -t0.z)
}

/// The direction the sun (`light`, travelling, `z < 0`) takes under flat water of `ior`.
pub fn flat_refracted(light: DVec3, ior: f64) -> DVec3 {
    refract(light, DVec3::Z, 1.0 / ior).unwrap_or(DVec3::NEG_Z)
}

/// The receivers' heights in the light's space: per texel of a square light-space window, the
/// height of the first receiver met coming down along `t0` from the water.
#[derive(Clone, Debug)]
pub struct ReceiverHeights {
    /// The flat-water refracted sun, unit, `z < 0`.
    pub t0: DVec3,
    /// Light-space corner of texel (0, 0).
    pub origin: DVec2,
    /// Side of a texel.
    pub texel: f64,
    /// Texels along light-space x: the square's `resolution` plus a margin each side.
    pub cols: usize,
    /// Texels along light-space y (as many as `cols`: the window is square).
    pub rows: usize,
    /// Row-major heights.
    pub heights: Vec<f32>,
    /// The largest change of the bilinear map's height per unit light-space distance over the
    /// floor (the objects left out): the bound [`Self::meet`] steps by, and the depth test's
    /// tolerance. An object's sides rise sheer from the floor; a step ends short of them or inside
    /// them, where the sign change finds them, so a ray misses at most a corner narrower than its
    /// sideways drift over one step (a few centimetres under waves).
    pub max_slope: f64,
    /// The floor's terrain over the `size` square (`None`: the plane `z = 0`), for the receivers'
    /// points and normals in [`lookup`].
    pub terrain: Option<crate::grid::Grid>,
    /// The opaque objects in the map: the first surface a line meets may be one of them, and the
    /// floor under them is covered.
    pub solids: Option<Arc<Solids>>,
    /// Side of the floor square, world units.
    pub size: f64,
    /// The water's depth it was made for: the rest level the lines along `t0` start from, and the
    /// height a texel holds where its line meets no receiver.
    pub depth: f64,
    /// Texels across the floor square (the window's texels less the margins).
    pub resolution: usize,
}

impl ReceiverHeights {
    /// The floor's receivers (its terrain and `solids`, the objects) seen along `t0` from water
    /// `depth` deep over the `size` square, at `resolution` texels across the square. The window
    /// is the square widened by how far along `t0` the highest receiver point moves in light
    /// space, so every receiver point over the square has its texel; lookups beyond it take the
    /// nearest edge texel.
    pub fn of_floor(
        floor: &Floor,
        solids: Option<&Arc<Solids>>,
        size: f64,
        depth: f64,
        t0: DVec3,
        resolution: usize,
    ) -> Self {
        let resolution = resolution.max(1);
        let texel = size / resolution as f64;
        let terrain_top = floor.terrain.as_ref().map_or(0.0, |g| g.min_max().1 as f64);
        let solids_top = solids.map_or(0.0, |s| s.bounds().1.z);
        let top = terrain_top.max(solids_top).clamp(0.0, depth);
        let shift = t0.truncate().abs() * (top / -t0.z);
        let margin = ((shift.max_element() / texel).ceil() as usize) + 2;
        let n = resolution + 2 * margin;
        let origin = DVec2::splat(-(margin as f64) * texel);
        let march = floor.terrain.as_ref().map(|g| HeightMarch::new(g, size));
        let lines: Vec<(f32, f32)> = (0..n * n)
            .into_par_iter()
            .map(|k| {
                let q = origin + (DVec2::new((k % n) as f64, (k / n) as f64) + 0.5) * texel;
                // The line through q along t0, from the water's rest level down.
                let s = q.extend(0.0) + t0 * (depth / t0.z);
                let height = |p: DVec2| floor.height_gradient(p, size).0;
                // The floor plane z = 0 lies `depth / −t0_z` along the line.
                let ground = match &march {
                    None => Some(depth / -t0.z),
                    Some(m) => m.intersect(s, t0, &height),
                };
                let first = match solids {
                    None => ground,
                    Some(solids) => {
                        let limit = ground.unwrap_or(f64::INFINITY);
                        solids.intersect(s, t0, limit).or(ground)
                    }
                };
                let at = |d: Option<f64>| d.map_or(depth, |d| (s + t0 * d).z.min(depth)) as f32;
                (at(ground), at(first))
            })
            .collect();
        let (ground, heights): (Vec<f32>, Vec<f32>) = lines.into_iter().unzip();
        let mut map = ReceiverHeights {
            t0,
            origin,
            texel,
            cols: n,
            rows: n,
            heights,
            max_slope: 0.0,
            terrain: floor.terrain.clone(),
            solids: solids.cloned(),
            size,
            depth,
            resolution,
        };
        // The floor's slope: the heights without the objects.
        let heights = std::mem::replace(&mut map.heights, ground);
        map.max_slope = map.steepest();
        map.heights = heights;
        map
    }

    /// [`of_floor`](Self::of_floor), or `previous` where it was made
    /// from the same floor, objects, water and sun (a frame that refits every frame builds the map
    /// once).
    pub fn reusing(
        previous: Option<&Arc<ReceiverHeights>>,
        floor: &Floor,
        solids: Option<&Arc<Solids>>,
        size: f64,
        depth: f64,
        t0: DVec3,
        resolution: usize,
    ) -> Arc<ReceiverHeights> {
        match previous {
            Some(p)
                if p.t0 == t0
                    && p.size == size
                    && p.depth == depth
                    && p.resolution == resolution
                    && p.terrain == floor.terrain
                    && same_solids(p.solids.as_ref(), solids) =>
            {
                p.clone()
            }
            _ => Arc::new(Self::of_floor(floor, solids, size, depth, t0, resolution)),
        }
    }

    fn steepest(&self) -> f64 {
        let mut slope: f32 = 0.0;
        for i in 0..self.rows {
            for j in 0..self.cols {
                let h = self.at(i, j);
                if j + 1 < self.cols {
                    slope = slope.max((self.at(i, j + 1) - h).abs());
                }
                if i + 1 < self.rows {
                    slope = slope.max((self.at(i + 1, j) - h).abs());
                }
            }
        }
        // Bilinear: the gradient's two components each bounded by the steepest edge.
        slope as f64 * std::f64::consts::SQRT_2 / self.texel
    }

    fn at(&self, i: usize, j: usize) -> f32 {
        self.heights[i * self.cols + j]
    }

    /// The map's height at light-space point `q`, bilinear between texel centres, clamped at the
    /// window's edges.
    pub fn height(&self, q: DVec2) -> f64 {
        let u = (q - self.origin) / self.texel - 0.5;
        let (j0, i0) = (u.x.floor(), u.y.floor());
        let (fu, fv) = (u.x - j0, u.y - i0);
        let fetch = |i: f64, j: f64| {
            let i = (i as i64).clamp(0, self.rows as i64 - 1) as usize;
            let j = (j as i64).clamp(0, self.cols as i64 - 1) as usize;
            self.at(i, j) as f64
        };
        let (a, b) = (fetch(i0, j0), fetch(i0, j0 + 1.0));
        let (c, d) = (fetch(i0 + 1.0, j0), fetch(i0 + 1.0, j0 + 1.0));
        (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv
    }

    /// Where the ray `s + d t` (`t` unit, going down) first meets the receivers, and its length
    /// `d`; `None` where it starts below them (dry land above the water) or never comes down.
    pub fn meet(&self, s: DVec3, t: DVec3) -> Option<(DVec3, f64)> {
        if t.z >= 0.0 {
            return None;
        }
        let drift = (t.truncate() - self.t0.truncate() * (t.z / self.t0.z)).length();
        let rate = -t.z + self.max_slope * drift;
        let gap = |d: f64| {
            let p = s + t * d;
            p.z - self.height(light_space(p, self.t0))
        };
        let d = march(gap, rate, self.texel)?;
        Some((s + t * d, d))
    }

    /// Whether receiver point `p` is the first the light meets along `t0` (within `bias`), not
    /// covered by another receiver nearer the light.
    pub fn lit(&self, p: DVec3, bias: f64) -> bool {
        p.z >= self.height(light_space(p, self.t0)) - bias
    }
}

/// One receivers' map shared between a technique's setups, equal only to itself: a setup compared
/// every frame compares the map's identity, not its texels ([`ReceiverHeights::reusing`]
/// hands back the same map while nothing it depends on changed).
#[derive(Clone, Debug)]
pub struct Shared(pub Arc<ReceiverHeights>);

impl PartialEq for Shared {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl Shared {
    /// The receivers of `floor` seen along `t0` at `resolution` texels a side: its terrain, and
    /// its objects unless `objects` is false (for a technique that lights and shades them by its
    /// own means: paper 3's depth textures); `previous` where nothing it depends on changed
    /// ([`ReceiverHeights::reusing`]); `None` on the plane `z = 0`, which every technique lights
    /// directly.
    pub fn of_floor(
        previous: Option<&Shared>,
        floor: &Floor,
        objects: bool,
        size: f64,
        depth: f64,
        t0: DVec3,
        resolution: usize,
    ) -> Option<Shared> {
        let solids = floor.solids.as_ref().filter(|_| objects);
        if floor.terrain.is_none() && solids.is_none() {
            return None;
        }
        let previous = previous.map(|p| &p.0);
        let r = ReceiverHeights::reusing(previous, floor, solids, size, depth, t0, resolution);
        Some(Shared(r))
    }

    /// Whether `receivers` were made from `floor`'s terrain and objects (both absent on the bare
    /// plane `z = 0`): a frame whose sun, water and map are unchanged keeps them without building
    /// a setup.
    pub fn fits(receivers: Option<&Shared>, floor: &Floor) -> bool {
        match receivers {
            None => !floor.has_receivers(),
            Some(r) => {
                floor.has_receivers()
                    && r.terrain == floor.terrain
                    && same_solids(r.solids.as_ref(), floor.solids.as_ref())
            }
        }
    }
}

impl Shared {
    /// [`Shared::fits`] for receivers made without the objects.
    pub fn fits_terrain(receivers: Option<&Shared>, floor: &Floor) -> bool {
        match receivers {
            None => floor.terrain.is_none(),
            Some(r) => r.solids.is_none() && r.terrain.is_some() && r.terrain == floor.terrain,
        }
    }
}

fn same_solids(a: Option<&Arc<Solids>>, b: Option<&Arc<Solids>>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        (a, b) => a.is_none() && b.is_none(),
    }
}

/// A technique's light as it left it in the light's space, for the receivers its floor map does
/// not hold (the objects among them) to look up as a shadow map is read ([`light_at`]).
#[derive(Clone, Debug)]
pub struct LightSpace {
    /// The deposit, on the floor map's window.
    pub deposit: CausticsMap,
    /// The receivers its light met, objects included.
    pub receivers: Arc<ReceiverHeights>,
    /// Whether the deposit tiles (as the floor map does).
    pub wrap: bool,
    /// `K` per channel along a receiver's flat-water path; zero where the deposit carries its
    /// own paths' absorption.
    pub absorption: DVec3,
}

impl LightSpace {
    /// The light at receiver point `p` with unit normal `n` ([`light_at`]).
    pub fn light_at(&self, p: DVec3, n: DVec3) -> [f32; 3] {
        light_at(
            &self.deposit,
            &self.receivers,
            p,
            n,
            self.wrap,
            self.absorption,
        )
    }
}

/// [`received`], and the deposit itself where objects are among the receivers (the light they
/// take: [`LightSpace`]).
pub fn received_with_light(
    map: CausticsMap,
    receivers: Option<&Arc<ReceiverHeights>>,
    wrap: bool,
    absorption: DVec3,
) -> (CausticsMap, Option<LightSpace>) {
    let Some(r) = receivers else {
        return (map, None);
    };
    let floor = lookup(&map, r, wrap, absorption);
    let light = r.solids.is_some().then(|| LightSpace {
        deposit: map,
        receivers: r.clone(),
        wrap,
        absorption,
    });
    (floor, light)
}

/// `map` (a technique's deposit) as the floor receives it: itself on the plane `z = 0`, else
/// looked up per floor texel through `receivers` ([`lookup`]).
pub fn received(
    map: CausticsMap,
    receivers: Option<&Shared>,
    wrap: bool,
    absorption: DVec3,
) -> CausticsMap {
    match receivers {
        None => map,
        Some(r) => lookup(&map, r, wrap, absorption),
    }
}

impl std::ops::Deref for Shared {
    type Target = ReceiverHeights;
    fn deref(&self) -> &ReceiverHeights {
        &self.0
    }
}

/// The first zero of `gap` from `d = 0` (positive there), when `gap` changes at most `rate` per
/// unit `d`: conservative steps, then [`regula_falsi`] on the sign change. `None` where
/// `gap(0) ≤ 0`. Steps no shorter than `1e-7 · scale`.
pub fn march(gap: impl Fn(f64) -> f64, rate: f64, scale: f64) -> Option<f64> {
    let mut g = gap(0.0);
    if g <= 0.0 {
        return None;
    }
    let tol = 1e-7 * scale;
    let mut d = 0.0;
    for _ in 0..256 {
        let step = (g / rate).max(tol);
        let g_next = gap(d + step);
        if g_next <= 0.0 {
            return Some(regula_falsi(&gap, (d, g), (d + step, g_next), tol, 48));
        }
        d += step;
        g = g_next;
        if g < tol {
            return Some(d);
        }
    }
    Some(d)
}

/// The sign change of `gap` between `a` (positive) and `b` (not), halved `iterations` times: the
/// middle of the last bracket.
pub fn bisect(gap: impl Fn(f64) -> f64, mut a: f64, mut b: f64, iterations: u32) -> f64 {
    for _ in 0..iterations {
        let m = 0.5 * (a + b);
        if gap(m) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// The sign change of `gap` between `a` (where it is `ga > 0`) and `b` (`gb ≤ 0`) by the Illinois
/// form of regula falsi: each guess is where the chord between the bracket's ends crosses zero,
/// and an end kept twice running has its value halved so the bracket closes from both sides. A
/// ray's gap to a bilinear map is quadratic within a texel, so a few guesses reach what
/// bisection needs twenty for; and where the conservative step already landed on the receiver
/// (a ray along `t0`), the first guess is it. Stops once a guess is within `tol` of zero or the
/// bracket narrower than `tol`, or after `iterations`.
pub fn regula_falsi(
    gap: impl Fn(f64) -> f64,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    tol: f64,
    iterations: u32,
) -> f64 {
    let mut m = b;
    let mut side = 0;
    for _ in 0..iterations {
        m = (a * gb - b * ga) / (gb - ga);
        let gm = gap(m);
        if gm > 0.0 {
            (a, ga) = (m, gm);
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            (b, gb) = (m, gm);
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
        if gm.abs() < tol || b - a < tol {
            break;
        }
    }
    m
}

/// A ray against a bicubic height field: the bound [`march`] steps by.
pub struct HeightMarch {
    max_slope: f64,
    size: f64,
}

impl HeightMarch {
    /// For the bicubic interpolant of `g` over the `size` square.
    pub fn new(g: &crate::grid::Grid, size: f64) -> Self {
        let (dx, dy) = (size / g.cols as f64, size / g.rows as f64);
        let mut max_slope: f64 = 0.0;
        for i in 0..g.rows {
            for j in 0..g.cols {
                let v = g.at(i, j) as f64;
                if j + 1 < g.cols {
                    max_slope = max_slope.max((g.at(i, j + 1) as f64 - v).abs() / dx);
                }
                if i + 1 < g.rows {
                    max_slope = max_slope.max((g.at(i + 1, j) as f64 - v).abs() / dy);
                }
            }
        }
        // The bicubic interpolant overshoots the samples' slopes by at most 25 % (Catmull-Rom).
        HeightMarch {
            max_slope: max_slope * 1.25 * std::f64::consts::SQRT_2,
            size,
        }
    }

    /// The length `d` along `s + d t` to where the ray first meets the surface `height`.
    pub fn intersect(&self, s: DVec3, t: DVec3, height: &dyn Fn(DVec2) -> f64) -> Option<f64> {
        let rate = -t.z + self.max_slope * t.truncate().length();
        march(
            |d| {
                let p = s + t * d;
                p.z - height(p.truncate())
            },
            rate,
            self.size,
        )
    }
}

/// Where each texel of a `width x height` floor map looks the light up, made once per terrain
/// and sun: [`ReceiverHeights::point`] at its centre on the floor. The GPU uploads the same
/// numbers.
pub fn floor_texels(receivers: &ReceiverHeights, width: usize, height: usize) -> Vec<[f32; 4]> {
    let size = receivers.size;
    let texel = DVec2::new(size / width as f64, size / height as f64);
    (0..width * height)
        .map(|k| {
            let c = (DVec2::new((k % width) as f64, (k / width) as f64) + 0.5) * texel;
            let (z, grad) = receivers.terrain.as_ref().map_or((0.0, DVec2::ZERO), |g| {
                g.sample(c, size, crate::grid::Edge::Clamp)
            });
            receivers.point(c.extend(z), crate::optics::height_field_normal(grad))
        })
        .collect()
}

impl ReceiverHeights {
    /// How far below the map's height a receiver point may lie and still be lit: half a texel's
    /// rise at the map's steepest slope (at least 45°), what bilinear reading loses.
    pub fn bias(&self) -> f64 {
        0.5 * self.texel * self.max_slope.max(1.0)
    }

    /// The share of the light deposited at its light-space point that receiver point `p` with
    /// unit normal `n` takes: `n · (−t₀) / −t₀_z`, its area as the light sees it over its
    /// horizontal area; 0 where another receiver nearer the light covers it (a shadow map's
    /// depth test, [`lit`](Self::lit)). `shaders/receivers.wgsl`'s `receiver_share` is its twin.
    pub fn share(&self, p: DVec3, n: DVec3) -> f64 {
        match self.lit(p, self.bias()) {
            true => (n.dot(-self.t0) / -self.t0.z).max(0.0),
            false => 0.0,
        }
    }

    /// Where receiver point `p` with unit normal `n` looks the light up, as `[q_x, q_y, share,
    /// d]`: `q` its light-space point, its [`share`](Self::share), and `d = (depth − P_z) / −t₀_z`
    /// its flat-water path.
    pub fn point(&self, p: DVec3, n: DVec3) -> [f32; 4] {
        let q = light_space(p, self.t0);
        let path = (self.depth - p.z) / -self.t0.z;
        [q.x as f32, q.y as f32, self.share(p, n) as f32, path as f32]
    }
}

/// The light receiver point `p` with unit normal `n` takes from a technique's light-space
/// deposit `light` (on the floor map's window), relative to what flat, clear water gives a
/// horizontal surface: the deposit at its light-space point times its share, attenuated by
/// `absorption` along its flat-water path ([`ReceiverHeights::point`]). Any receiver, on the
/// floor or not (an object, an engine's own mesh), looks its light up this way; [`lookup`] is it
/// at every floor texel.
pub fn light_at(
    light: &CausticsMap,
    receivers: &ReceiverHeights,
    p: DVec3,
    n: DVec3,
    wrap: bool,
    absorption: DVec3,
) -> [f32; 3] {
    deposited(light, receivers.point(p, n), wrap, absorption)
}

fn deposited(light: &CausticsMap, point: [f32; 4], wrap: bool, absorption: DVec3) -> [f32; 3] {
    let [qx, qy, share, path] = point;
    let a = (-absorption * path as f64).exp().as_vec3();
    let e = light.sample(qx as f64, qy as f64, wrap);
    std::array::from_fn(|c| e[c] * share * a[c])
}

/// A floor map (the floor's `(x, y)` texels) from a light-space deposit `light` (flux per unit
/// area of `z = 0` along the light, on the same window as the floor map): each texel takes the
/// deposit at its light-space point times its share ([`floor_texels`]). `absorption` (`K` per
/// channel; zero where the deposit carries its own paths' absorption) attenuates by `exp(−K d)`
/// along the flat-water path. On a flat floor without absorption this is `light` itself.
pub fn lookup(
    light: &CausticsMap,
    receivers: &ReceiverHeights,
    wrap: bool,
    absorption: DVec3,
) -> CausticsMap {
    let mut out = CausticsMap::new(light.width, light.height, light.size);
    let texels = floor_texels(receivers, light.width, light.height);
    for (t, &point) in out.texels.iter_mut().zip(&texels) {
        *t = deposited(light, point, wrap, absorption);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grid::Grid;
    use crate::scene::Solids;

    use crate::fixtures::open_floor as floor;

    fn slope(n: usize, size: f64, rise: f64) -> Grid {
        Grid::from_fn(n, n, |_, j| {
            (rise * (j as f64 + 0.5) / n as f64 * size) as f32
        })
    }

    #[test]
    fn a_flat_floor_is_its_own_light_space() {
        let t0 = flat_refracted(DVec3::new(-0.35, 0.2, -1.0).normalize(), 1.333);
        let r = ReceiverHeights::of_floor(&floor(None), None, 4.0, 1.0, t0, 16);
        assert!(r.heights.iter().all(|&h| h == 0.0));
        let s = DVec3::new(1.3, 2.1, 1.02);
        let t = DVec3::new(0.1, -0.05, -1.0).normalize();
        let (hit, d) = r.meet(s, t).unwrap();
        assert!(hit.z.abs() < 1e-9, "{hit}");
        assert!((d - s.z / -t.z).abs() < 1e-9);
        assert!(light_space(hit, t0).distance(hit.truncate()) < 1e-12);
    }

    #[test]
    fn rays_meet_a_plane_slope_where_the_plane_is() {
        // z = 0.2 x over a 4 m square: the bilinear light-space map of a plane is the plane.
        let (size, depth) = (4.0, 1.5);
        let f = floor(Some(slope(64, size, 0.2)));
        let t0 = flat_refracted(DVec3::new(0.4, -0.3, -1.0).normalize(), 1.333);
        let r = ReceiverHeights::of_floor(&f, f.solids.as_ref(), size, depth, t0, 64);
        for (x, y, tx) in [(1.0, 1.0, 0.0), (2.5, 3.0, 0.15), (0.5, 2.0, -0.2)] {
            let s = DVec3::new(x, y, depth + 0.03);
            let t = (t0 + DVec3::new(tx, 0.05, 0.0)).normalize();
            let (hit, _) = r.meet(s, t).unwrap();
            assert!((hit.z - 0.2 * hit.x).abs() < 1e-6, "{hit}");
        }
    }

    /// Any receiver point looks its light up as a shadow map is read (the light a mesh of an
    /// engine's takes): a slab held over a flat floor under a uniform deposit gives its top the
    /// deposit, a face tilted toward the refracted sun its cosine over the horizontal's, the
    /// floor in its shade nothing and the floor beyond it the deposit attenuated along its
    /// flat-water path; at a floor texel's centre it is the floor map's texel.
    #[test]
    fn any_receiver_point_looks_its_light_up_as_a_shadow_map() {
        let (size, depth) = (4.0, 2.0);
        let t0 = flat_refracted(DVec3::new(-0.3, 0.25, -1.0).normalize(), 1.333);
        let slab = crate::mesh::cuboid(DVec3::new(0.5, 0.5, 0.05))
            .transformed(glam::DAffine3::from_translation(DVec3::new(2.0, 2.0, 1.0)));
        let solids = Solids::of_meshes(vec![slab]);
        let r = ReceiverHeights::of_floor(&floor(None), solids.as_ref(), size, depth, t0, 64);
        let mut deposit = CausticsMap::new(64, 64, size);
        deposit.texels.iter_mut().for_each(|t| *t = [1.0; 3]);
        let k = DVec3::new(0.3, 0.05, 0.0);
        let light = |p: DVec3, n: DVec3| light_at(&deposit, &r, p, n, false, k);
        let path = |z: f64| (-k * (depth - z) / -t0.z).exp();
        let top = light(DVec3::new(2.0, 2.0, 1.05), DVec3::Z);
        let expect = path(1.05);
        for c in 0..3 {
            assert!((top[c] as f64 - expect[c]).abs() < 1e-6, "{top:?} {expect}");
        }
        // The floor in the slab's shade: where the light through its middle would land.
        let under = light_space(DVec3::new(2.0, 2.0, 1.0), t0).extend(0.0);
        assert_eq!(light(under, DVec3::Z), [0.0; 3]);
        // A face turned 30° toward the sun beyond the slab's shade.
        let toward = (-t0.truncate()).normalize().extend(0.0);
        let n =
            (DVec3::Z * 30f64.to_radians().cos() + toward * 30f64.to_radians().sin()).normalize();
        let p = DVec3::new(0.5, 0.5, 0.3);
        let tilted = light(p, n)[0] as f64;
        let cosine = n.dot(-t0) / -t0.z;
        assert!(
            (tilted - cosine * path(0.3).x).abs() < 1e-6,
            "{tilted} {cosine}"
        );
        assert!(cosine > 1.0, "{cosine}");
        // At a floor texel's centre, the lookup's texel.
        let map = lookup(&deposit, &r, false, k);
        let c = DVec3::new((10.0 + 0.5) * size / 64.0, (20.0 + 0.5) * size / 64.0, 0.0);
        assert_eq!(light(c, DVec3::Z), map.texels[20 * 64 + 10]);
    }
}
