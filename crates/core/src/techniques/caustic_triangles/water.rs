//! The water surface as the caustic generator of technique `caustic-triangles`: the photon pass of a
//! height-field water surface under the sun, the CPU twin of
//! `caustic_triangles/water_photon.wgsl`. Everything after it (vertex irradiance, caustic
//! triangles, the splatting baseline, §5 merging) is the glass generator's code, told about the
//! water by [`WaterTransport`].
//!
//! # Water photon pass (§4.1 with the water surface as the generator)
//! The paper's photon image is the generator seen from the light. A height field is its own
//! parameterisation as the sun sees it (up to the shear along `L`), so the photon image is a lattice
//! over the water square: `(P + 1)²` photons at the corners `(jΔ, iΔ)`, `Δ = size / P`, so that the
//! `P²` photon-image quads tile the square exactly (and the tiles of a wrapping surface meet edge to
//! edge). Each photon is the surface point `(x, y, depth + h)` of the bicubic interpolant of the
//! height grid ([`Grid::sample`]; the GPU's `grid_sample`), the sun refracted there by exact Snell
//! through the true normal, and the floor `z = 0` met analytically; its texel is `(x, y, Φ, σ)` of
//! the floor hit as for glass, `σ = 1` (one refraction).
//!
//! Power in the technique's floor-area units, the normalisation of `crate::reference`:
//! `ΔΦ = Δ² (1 + L_xy · ∇h / |L_z|) · T(θi) / T(θ0)`, the cell's surface area projected along `L`
//! onto the horizontal (the sun's flux through it over the flux through the flat cell) times the
//! Fresnel transmittance relative to flat water. Flat water gives `ΔΦ = Δ²` per photon over a
//! regular grid of hits `Δ` apart: relative irradiance 1. A photon whose surface faces away from the
//! sun (`cos θi ≤ 0`, the projected area ≤ 0) is invalid (power `−1`), as the reference gives such
//! triangles nothing.
//!
//! # Absorption (Beer-Lambert)
//! The photon's power is one number; the water absorbs per channel along the refracted path. The
//! pass writes each photon's path length `d` (surface to floor) into a second buffer, and the
//! triangles pass interpolates `d` over each caustic triangle like the irradiance and multiplies by
//! `exp(−K d)` per channel ([`super::triangles_pass_with_paths`]). Glass generators keep `K = 0`.
//!
//! # Wrap
//! With `water.wrap` the refracted light that leaves the square re-enters it on the other side: every
//! triangle is drawn at nine offsets `(±size | 0, ±size | 0)` ([`CausticTrianglesSetup::copies`];
//! instanced draws on the GPU), and clipping keeps what falls in the square. Clamped water is drawn
//! once, from a lattice that reaches upwind of the square as far as the light that lands on it
//! comes from ([`clamped_lattice`]): the surface beyond the square, its heights clamped at the
//! edges, as the reference traces it.
//!
//! # Departures
//! - Power and path length are sampled at the lattice corners and interpolated; the reference
//!   integrates each fine triangle's projected area exactly. Both converge to the same map as `P`
//!   grows (docs/caustic-triangles.md measures how fast).

use std::sync::Arc;

use glam::{DVec2, DVec3};

use super::{
    CausticTrianglesParams, CausticTrianglesSetup, FloorWindow, INVALID, WaterTransport,
    irradiance_pass, light_frame, signature, triangles_pass_with_paths,
};
use crate::error::{Error, Result};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::optics::{air_transmittance, height_field_normal, refract};
use crate::parallel::prelude::*;
use crate::receivers::{
    LightSpace, ReceiverHeights, flat_refracted, light_space, received_with_light,
};
use crate::scene::{Floor, Scene, Water};
use crate::techniques::JobOutput;
use crate::walls::{Wall, WallMaps};

/// The water photon pass's inputs (the GPU uploads the same numbers, `WaterPhotonUniform`).
#[derive(Clone, Debug)]
pub struct WaterSetup {
    /// The reconstruction's setup: photon image side `P + 1`, the floor window the water square,
    /// `water` set.
    pub setup: CausticTrianglesSetup,
    /// Quads per side of the lattice, `P`.
    pub lattice: usize,
    /// Lattice spacing `Δ = size / P`.
    pub spacing: f64,
    /// Where photon `(0, 0)` lies on the surface: the square's corner, or upwind of it where the
    /// water does not tile ([`clamped_lattice`]).
    pub origin: DVec2,
    /// Unit direction the sunlight travels, `z < 0`.
    pub light: DVec3,
    /// Side of the water square `[0, size]²`, world units.
    pub size: f64,
    /// The water's rest level above the floor `z = 0`, world units: the surface is `z = depth + h`.
    pub depth: f64,
    /// The water's index of refraction.
    pub ior: f64,
    /// Whether each photon carries its Fresnel transmittance, relative to flat water's.
    pub fresnel: bool,
    /// `T(θ0)`, the Fresnel transmittance of flat water (1 without Fresnel).
    pub t_flat: f64,
    /// The surface tiles (`water.wrap`): its heights are sampled wrapped at the edges. Whether the
    /// light is carried across the edges as well is the transport's `wrap`, which walls turn off.
    pub surface_wrap: bool,
    /// The pool's walls receive light ([`WaterSetup::with_walls`]).
    pub walls: bool,
    /// What the photons meet instead of the plane `z = 0` ([`WaterSetup::with_receivers`]).
    pub receivers: Option<Arc<ReceiverHeights>>,
}

impl WaterSetup {
    /// A `P = params.photon_image` lattice over `water`'s square, lit by the sun travelling along
    /// `light`, into a `width x height` map of the square.
    pub fn new(
        params: &CausticTrianglesParams,
        water: &Water,
        light: DVec3,
        width: usize,
        height: usize,
    ) -> Result<Self> {
        params.validate()?;
        let light = crate::techniques::check_inputs(width, height, light)?;
        if !(water.size > 0.0 && water.size.is_finite() && water.depth.is_finite()) {
            return Err(Error::InvalidParameter(format!(
                "water size {} and depth {} must be finite, the size positive",
                water.size, water.depth
            )));
        }
        if !(water.ior >= 1.0 && water.ior.is_finite()) {
            return Err(Error::InvalidParameter(format!(
                "water ior must be at least 1, got {}",
                water.ior
            )));
        }
        let lattice = params.photon_image as usize;
        let spacing = water.size / lattice as f64;
        let (u, v, w) = light_frame(light);
        let setup = CausticTrianglesSetup {
            p: lattice + 1,
            u,
            v,
            w,
            rect_lo: DVec2::ZERO,
            cell: DVec2::splat(spacing),
            flux: spacing * spacing,
            ior: water.ior,
            depth: 1,
            fresnel: params.fresnel,
            linear_steps: params.linear_steps,
            secant_iterations: params.secant_iterations,
            area_rule: params.area_rule,
            splat_size: params.splat_size,
            merge_levels: params.merge_levels,
            merge_texels: params.merge_texels,
            floor: FloorWindow {
                origin: DVec2::ZERO,
                size: water.size,
                width,
                height,
            },
            point: None,
            light_cube: params.light_cube as usize,
            water: Some(WaterTransport {
                lattice,
                absorption: water.absorption,
                wrap: water.wrap,
                // Every quad until the heights are known ([`WaterSetup::fit_band`]).
                band: lattice,
                // A tiling surface's moved photons meet the floor plane moved alike.
                periodic: water.wrap,
            }),
        };
        let t_flat = air_transmittance(params.fresnel, -light.z, water.ior);
        let mut ws = WaterSetup {
            setup,
            lattice,
            spacing,
            origin: DVec2::ZERO,
            light,
            size: water.size,
            depth: water.depth,
            ior: water.ior,
            fresnel: params.fresnel,
            t_flat,
            surface_wrap: water.wrap,
            walls: false,
            receivers: None,
        };
        ws.fit_lattice();
        Ok(ws)
    }

    /// With `walls` the four walls of the square stop the light: nothing is carried
    /// across the edges any more (one copy of each triangle), the surface still tiles.
    pub fn with_walls(mut self, walls: bool) -> Self {
        self.walls = walls;
        if let Some(w) = self.setup.water.as_mut() {
            w.wrap = w.wrap && !walls;
        }
        self.fit_lattice();
        self
    }

    /// The lattice over the square, or over [`clamped_lattice`]'s domain where the water neither
    /// tiles nor stands between walls.
    fn fit_lattice(&mut self) {
        let quads = (self.size / self.spacing).round() as usize;
        let (lattice, origin) = if self.surface_wrap || self.walls {
            (quads, DVec2::ZERO)
        } else {
            let t0 = flat_refracted(self.light, self.ior);
            clamped_lattice(quads, self.size, self.depth, t0)
        };
        self.lattice = lattice;
        self.origin = origin;
        self.setup.p = lattice + 1;
        if let Some(w) = self.setup.water.as_mut() {
            w.lattice = lattice;
            w.band = lattice;
        }
    }

    /// The photons meet `receivers` (the floor's terrain as the light sees it) and their light is
    /// deposited in the light's space, then looked up by each floor texel ([`crate::receivers`]).
    /// Moved photons of a tiling surface no longer meet the receivers moved alike, so the photon
    /// image is not periodic.
    pub fn with_receivers(mut self, receivers: Arc<ReceiverHeights>) -> Self {
        self.receivers = Some(receivers);
        if let Some(w) = self.setup.water.as_mut() {
            w.periodic = false;
        }
        self
    }

    /// The photons meet `floor`'s terrain and objects where it has them ([`with_receivers`](Self::with_receivers)),
    /// through the receivers' map at the floor map's resolution, taken from `previous` where
    /// nothing it depends on changed.
    pub fn with_floor(self, floor: &Floor, previous: Option<&Arc<ReceiverHeights>>) -> Self {
        if !floor.has_receivers() {
            return self;
        }
        let t0 = flat_refracted(self.light, self.ior);
        let width = self.setup.floor.width;
        let (solids, size, depth) = (floor.solids.as_ref(), self.size, self.depth);
        let r = ReceiverHeights::reusing(previous, floor, solids, size, depth, t0, width);
        self.with_receivers(r)
    }

    /// The reconstruction's setup for receiver `wall` (`None`: the floor): a wall's map is the
    /// wall's `cols x rows` texels over `(along, z · size / depth)`, the wall stretched to the
    /// square's side so that the floor window's square texels cover it (the photons' power is
    /// stretched alike, [`receiver_photon`]).
    pub fn receiver_setup(&self, wall: Option<Wall>, maps: &WallMaps) -> CausticTrianglesSetup {
        let mut setup = self.setup.clone();
        if let Some(wall) = wall {
            let m = maps.get(wall);
            setup.floor = FloorWindow {
                origin: DVec2::ZERO,
                size: self.size,
                width: m.cols,
                height: m.rows,
            };
            // The moved photons meet a wall's plane at another height or not at all.
            if let Some(w) = setup.water.as_mut() {
                w.periodic = false;
            }
        }
        setup
    }

    /// Narrow the copies of tiling water to the quads whose light can cross an edge of the square
    /// under `heights` ([`copy_band`]); both twins call it before drawing.
    pub fn fit_band(&mut self, heights: &Grid) {
        let band = copy_band(self, heights);
        if let Some(w) = self.setup.water.as_mut() {
            w.band = band;
        }
    }

    /// Whether light is carried across the square's edges (tiling water without walls): every
    /// triangle is drawn at the nine offsets of [`CausticTrianglesSetup::copies`].
    pub fn wrap(&self) -> bool {
        self.setup.water.is_some_and(|w| w.wrap)
    }

    /// How the height grid is sampled past the square's edges: wrapped for a tiling surface, else
    /// clamped.
    pub fn edge(&self) -> Edge {
        if self.surface_wrap {
            Edge::Wrap
        } else {
            Edge::Clamp
        }
    }
}

/// The lattice of water that does not tile: quads per side and where photon `(0, 0)` lies.
///
/// The surface beyond the square sends light into it as well (its heights clamped at the square's
/// edges, as the reference traces it): the light that lands on the square left the surface about
/// `s = t₀_xy · depth / −t₀_z` upwind, at most that far over a floor at `z = 0` and less over
/// anything higher, so the lattice, at the square's own spacing, covers the square and the square
/// moved back by `s`, widened by a margin for the waves' deflection of the light from `t₀`
/// (`0.15 · depth`, about 8.5°, and two quads). It stays square, as the photon image is, and
/// keeps the square's lattice points.
pub fn clamped_lattice(quads: usize, size: f64, depth: f64, t0: DVec3) -> (usize, DVec2) {
    let spacing = size / quads as f64;
    let shift = t0.truncate() * (depth.max(0.0) / -t0.z);
    let margin = 0.15 * depth.max(0.0) + 2.0 * spacing;
    // On the square's own lattice points, extended: the square's photons are where they would be
    // without the extension.
    let lo = (((-shift).min(DVec2::ZERO) - DVec2::splat(margin)) / spacing).floor() * spacing;
    let hi = (DVec2::splat(size) - shift).max(DVec2::splat(size)) + DVec2::splat(margin);
    let extent = (hi - lo).max_element();
    ((extent / spacing).ceil() as usize, lo)
}

/// Photon `(i, j)` of the water photon pass: its texel `(x, y, Φ, σ)` (or [`INVALID`]) and its
/// refracted path length (0 where invalid).
pub fn photon(ws: &WaterSetup, heights: &Grid, i: usize, j: usize) -> ([f32; 4], f32) {
    receiver_photon(ws, heights, i, j, None)
}

/// The refracted sun at lattice corner `(i, j)`: the surface point, the unit refracted direction
/// and the photon's power; `None` where the surface faces away from the sun.
fn surface_ray(ws: &WaterSetup, heights: &Grid, i: usize, j: usize) -> Option<(DVec3, DVec3, f64)> {
    let l = ws.light;
    let p = ws.origin + DVec2::new(j as f64, i as f64) * ws.spacing;
    let (h, grad) = heights.sample(p, ws.size, ws.edge());
    let n = height_field_normal(grad);
    let cos_i = -l.dot(n);
    // The cell's area as the sun sees it, over the flat cell's.
    let seen = 1.0 + l.truncate().dot(grad) / -l.z;
    let t = refract(l, n, 1.0 / ws.ior).filter(|t| cos_i > 0.0 && seen > 0.0 && t.z < 0.0)?;
    let fresnel = air_transmittance(ws.fresnel, cos_i, ws.ior) / ws.t_flat;
    Some((p.extend(ws.depth + h), t, ws.setup.flux * seen * fresnel))
}

/// Photon `(i, j)` as receiver `wall` (`None`: the floor) sees it: the point where its ray meets
/// the receiver's plane, in the receiver's map coordinates (the floor: `(x, y)`; a wall: `(along,
/// z · size / depth)`, [`WaterSetup::receiver_setup`]), and the path length to it.
///
/// # Receivers: each plane gets the whole photon image
/// The ray of a photon ends on the first face of the box (floor or wall) it meets; for a ray from
/// inside a convex box that is the one face whose plane it meets within the face's rectangle. So
/// every receiver takes the photon image of the rays *extended to its plane* (behind the floor or
/// past a wall where they end elsewhere), builds its vertex irradiance and caustic triangles in
/// its own plane, and the clip to its map keeps exactly the part of each triangle whose light
/// ends there: a triangle straddling the floor-wall edge is split along that edge, its floor part
/// drawn on the floor and its wall part on the wall, each with the irradiance of its own plane.
/// The split line is where the extended triangles cross the edge on either side, the same rays
/// up to the linear interpolation of the hit positions.
///
/// A wall's photon is invalid where its ray runs parallel to or away from the wall, and where the
/// extended hit lies more than `size` below the floor (a near-vertical ray, whose extension would
/// put far vertices into the rasteriser; its triangles' share on the wall is a sliver at the
/// edge: the flux this loses is measured in the tests). A wall's power is multiplied by
/// `size / depth`, the stretch of its z axis, so that `ΔΦ / ΔA` stays the wall's irradiance in the
/// floor map's unit.
pub fn receiver_photon(
    ws: &WaterSetup,
    heights: &Grid,
    i: usize,
    j: usize,
    wall: Option<Wall>,
) -> ([f32; 4], f32) {
    let Some((start, t, power)) = surface_ray(ws, heights, i, j) else {
        return (INVALID, 0.0);
    };
    let sigma = signature(1, 0);
    let Some(wall) = wall else {
        let (q, d) = match &ws.receivers {
            Some(r) => match r.meet(start, t) {
                Some((hit, d)) => (light_space(hit, r.t0), d),
                None => return (INVALID, 0.0),
            },
            None => {
                let d = start.z / -t.z;
                ((start + t * d).truncate(), d)
            }
        };
        return ([q.x as f32, q.y as f32, power as f32, sigma], d as f32);
    };
    let toward = -t.dot(wall.normal());
    if toward <= 0.0 {
        return (INVALID, 0.0);
    }
    let gap = wall.point(0.0, 0.0, ws.size) - start;
    let d = -gap.dot(wall.normal()) / toward;
    let hit = start + t * d;
    if hit.z < -ws.size || !d.is_finite() {
        return (INVALID, 0.0);
    }
    let stretch = ws.size / ws.depth;
    (
        [
            wall.along(hit) as f32,
            (hit.z * stretch) as f32,
            (power * stretch) as f32,
            sigma,
        ],
        d as f32,
    )
}

/// The water photon image, row `i` major, and the path lengths.
pub fn photon_pass(ws: &WaterSetup, heights: &Grid) -> (Vec<[f32; 4]>, Vec<f32>) {
    receiver_photon_pass(ws, heights, None)
}

/// The photon image of receiver `wall` (`None`: the floor), [`receiver_photon`].
pub fn receiver_photon_pass(
    ws: &WaterSetup,
    heights: &Grid,
    wall: Option<Wall>,
) -> (Vec<[f32; 4]>, Vec<f32>) {
    let p = ws.setup.p;
    (0..p * p)
        .into_par_iter()
        .map(|k| receiver_photon(ws, heights, k / p, k % p, wall))
        .unzip()
}

/// The walls' maps of the water generator ([`WaterSetup::with_walls`]): each wall's photon image,
/// vertex irradiance and caustic triangles in its own plane ([`receiver_photon`]), in the
/// [`WallMaps`] of a `width x height` floor map.
pub fn wall_caustics(ws: &WaterSetup, heights: &Grid) -> Result<WallMaps> {
    check_heights(heights)?;
    let f = &ws.setup.floor;
    let mut maps = WallMaps::for_floor_map(f.width, f.height, ws.size, ws.depth);
    for wall in Wall::ALL {
        let setup = ws.receiver_setup(Some(wall), &maps);
        let (photons, paths) = receiver_photon_pass(ws, heights, Some(wall));
        let irradiance = irradiance_pass(&setup, &photons);
        let map = triangles_pass_with_paths(&setup, &photons, &irradiance, Some(&paths));
        maps.get_mut(wall).texels = map.texels;
    }
    Ok(maps)
}

/// Everything one run produces.
pub struct WaterOutput {
    /// The water photon image, `(P + 1)²` row major: `(x, y, Φ, σ)` of each photon's hit (light-space
    /// coordinates over a terrain's receivers), or [`INVALID`].
    pub photons: Vec<[f32; 4]>,
    /// Each photon's refracted path length from the surface to its hit, world units (0 where
    /// invalid).
    pub paths: Vec<f32>,
    /// Each photon's vertex irradiance `E = ΔΦ / ΔA`, −1 where invalid.
    pub irradiance: Vec<f32>,
    /// The floor map, relative irradiance per RGB channel after absorption.
    pub map: CausticsMap,
    /// The light-space deposit the floor map was looked up from, where objects are among the
    /// receivers.
    pub light: Option<LightSpace>,
}

fn check_heights(heights: &Grid) -> Result<()> {
    if heights.cols == 0 || heights.rows == 0 || heights.data.len() != heights.cols * heights.rows {
        return Err(Error::InvalidParameter(format!(
            "the water height grid is {} x {} with {} samples",
            heights.cols,
            heights.rows,
            heights.data.len()
        )));
    }
    heights.check_finite("the water height grid")
}

/// The bound the copy band is fitted from (the CPU twin of `band_bound.wgsl`): the grid's largest
/// forward finite-difference slope over a square of side `size`, wrapping at the edges, and its
/// lowest and highest heights.
pub fn band_bound(size: f64, heights: &Grid) -> (f64, f32, f32) {
    let (cols, rows) = (heights.cols.max(1), heights.rows.max(1));
    let (dx, dy) = (size / cols as f64, size / rows as f64);
    let at = |i: usize, j: usize| heights.at(i, j) as f64;
    let mut slope: f64 = 0.0;
    for i in 0..heights.rows {
        for j in 0..heights.cols {
            let (jn, i_n) = ((j + 1) % cols, (i + 1) % rows);
            slope = slope
                .max((at(i, jn) - at(i, j)).abs() / dx)
                .max((at(i_n, j) - at(i, j)).abs() / dy);
        }
    }
    let (lo, hi) = heights.min_max();
    (slope, lo, hi)
}

/// Quads from an edge of the lattice whose refracted light can reach past that edge: the farthest
/// the light travels sideways between the surface and the floor, `(depth + h_max) tan(θ_t + α)`,
/// in lattice cells, plus one. `α = atan s` is the steepest tilt of the surface's normal (`s` the
/// grid's largest finite-difference slope, times 1.25 · √2 for the bicubic interpolant's overshoot
/// and the diagonal), the incidence angle is at most the sun's zenith angle plus `α`, `θ_t` its
/// refraction, and the refracted ray leans from the vertical by at most `θ_t + α`. A bound, never
/// an estimate: light it leaves out would be lost. Every quad where the bound reaches 89°.
pub fn copy_band(ws: &WaterSetup, heights: &Grid) -> usize {
    let (slope, lo, hi) = band_bound(ws.size, heights);
    let h_max = hi as f64 + 0.25 * (hi - lo) as f64;
    let tilt = (slope * 1.25 * std::f64::consts::SQRT_2).atan();
    let zenith = (-ws.light.z).clamp(-1.0, 1.0).acos();
    let incidence = (zenith + tilt).min(std::f64::consts::FRAC_PI_2);
    let refracted = (incidence.sin() / ws.ior).asin();
    let lean = refracted + tilt;
    if !lean.is_finite() || lean >= 89f64.to_radians() || !h_max.is_finite() {
        return ws.lattice;
    }
    let reach = (ws.depth + h_max).max(0.0) * lean.tan();
    ((reach / ws.spacing).ceil() as usize + 1).min(ws.lattice)
}

/// The whole technique on the CPU with the water surface (its heights over the square) as the
/// generator: water photon pass, vertex irradiance, caustic triangles with absorption.
pub fn caustics(ws: &WaterSetup, heights: &Grid) -> Result<WaterOutput> {
    check_heights(heights)?;
    let mut ws = ws.clone();
    ws.fit_band(heights);
    let ws = &ws;
    let (photons, paths) = photon_pass(ws, heights);
    let irradiance = irradiance_pass(&ws.setup, &photons);
    let deposit = triangles_pass_with_paths(&ws.setup, &photons, &irradiance, Some(&paths));
    let (map, light) = received_with_light(deposit, ws.receivers.as_ref(), ws.wrap(), DVec3::ZERO);
    Ok(WaterOutput {
        photons,
        paths,
        irradiance,
        map,
        light,
    })
}

/// The floor's map and, with the scene's walls, the walls' maps ([`wall_caustics`]).
pub fn maps(ws: &WaterSetup, heights: &Grid) -> Result<JobOutput> {
    let walls = match ws.walls {
        true => Some(wall_caustics(ws, heights)?),
        false => None,
    };
    let out = caustics(ws, heights)?;
    Ok(JobOutput::received((out.map, out.light), walls))
}

/// The technique on a scene with water, the water as the generator, over the scene square at the
/// scene's caustics resolution; with the scene's walls, nothing carried across the edges (the
/// walls' own maps: [`render_with_walls`]).
pub fn render(scene: &Scene, params: &CausticTrianglesParams) -> Result<CausticsMap> {
    Ok(render_with_walls(scene, params)?.0)
}

/// [`render`] with the scene's walls (`floor.walls`): the floor map with nothing carried across
/// the edges, and the walls' maps ([`wall_caustics`]); `None` for the walls when the scene has
/// none. Over a terrain the photons meet it ([`WaterSetup::with_floor`]).
pub fn render_with_walls(
    scene: &Scene,
    params: &CausticTrianglesParams,
) -> Result<(CausticsMap, Option<WallMaps>)> {
    let (ws, heights) = super::water_setup(&crate::techniques::Job::new(scene, None, 1), params)?;
    let out = maps(&ws, &heights)?;
    let map = out.caustics.into_floor(super::DESCRIPTOR.name)?;
    Ok((map, out.walls))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{open_floor, slope, worst_off_the_attenuated_cosine};
    use crate::metrics::compare;
    use crate::reference::{ReferenceInput, ReferenceOptions, reference};
    use crate::scene::WaterSource;
    use crate::techniques::heights_for;
    use crate::water::Surface;

    fn params(p: u32) -> CausticTrianglesParams {
        CausticTrianglesParams {
            photon_image: p,
            ..Default::default()
        }
    }

    fn flat_water(wrap: bool, absorption: DVec3) -> Water {
        Water {
            source: WaterSource::Flat,
            size: 2.0,
            depth: 0.7,
            ior: 1.333,
            wrap,
            absorption,
        }
    }

    /// Under flat water every texel gets the unobstructed sun's relative irradiance, 1, attenuated
    /// by `exp(−K d0)` along the flat refracted path: the lattice shifted by the refraction wraps
    /// around exactly, so no light is lost at the edges and none is counted twice.
    #[test]
    fn flat_water_gives_relative_irradiance_one_everywhere() {
        let light = DVec3::new(0.3, 0.1, -1.0).normalize();
        let k = DVec3::new(0.45, 0.09, 0.05);
        let t0 = refract(light, DVec3::Z, 1.0 / 1.333).unwrap();
        let d0 = 0.7 / -t0.z;
        for (absorption, expect) in [(DVec3::ZERO, DVec3::ONE), (k, (-k * d0).exp())] {
            let water = flat_water(true, absorption);
            let ws = WaterSetup::new(&params(48), &water, light, 96, 96).unwrap();
            let out = caustics(&ws, &Grid::new(16, 16)).unwrap();
            let path = out
                .paths
                .iter()
                .map(|&d| (d as f64 - d0).abs())
                .fold(0.0, f64::max);
            eprintln!("flat water, K = {absorption}: worst path {path:.2e}");
            assert!(path < 1.8e-7, "path off by {path}"); // measured 1.83e-8

            let mut worst: f64 = 0.0;
            for t in &out.map.texels {
                for c in 0..3 {
                    worst = worst.max((t[c] as f64 / expect[c] - 1.0).abs());
                }
            }
            eprintln!("flat water, K = {absorption}: worst texel {worst:.2e}");
            // measured 3.39e-6 (K = 0.45, 0.09, 0.05), 3.34e-6 (clear)
            assert!(worst < 3.4e-5, "worst texel off by {worst}");
        }
    }

    /// Flat water over a sloping plane: each floor point `P` gets the sun's `n · (−t₀) / −t₀_z`
    /// on its tilted face, attenuated by `exp(−K d)` along its own refracted path `d = (depth −
    /// P_z) / −t₀_z`, as the reference gives it.
    #[test]
    fn flat_water_over_a_slope_gives_each_point_its_attenuated_cosine() {
        let light = DVec3::new(0.3, 0.1, -1.0).normalize();
        let k = DVec3::new(0.45, 0.09, 0.05);
        let water = flat_water(true, k);
        let (a, b) = (0.12, 0.1);
        let floor = open_floor(Some(slope(a, b, water.size, 64)));
        let t0 = crate::receivers::flat_refracted(light, water.ior);
        let r = ReceiverHeights::of_floor(
            &floor,
            floor.solids.as_ref(),
            water.size,
            water.depth,
            t0,
            96,
        );
        let ws = WaterSetup::new(&params(96), &water, light, 96, 96)
            .unwrap()
            .with_receivers(Arc::new(r));
        let out = caustics(&ws, &Grid::new(16, 16)).unwrap();
        let worst = worst_off_the_attenuated_cosine(&out.map, (a, b), water.depth, t0, k);
        eprintln!("flat water over a slope: worst texel {worst:.2e}");
        // measured 4.77e-6
        assert!(worst < 4.8e-5, "worst texel off by {worst}");
    }

    /// Without wrap the surface beyond the square (its heights clamped) still sends light into
    /// it: flat clamped water lights every texel with the flat water's 1, the upwind strip
    /// included, from one copy of each triangle.
    #[test]
    fn clamped_flat_water_lights_the_whole_square() {
        let light = DVec3::new(0.3, 0.1, -1.0).normalize();
        let water = flat_water(false, DVec3::ZERO);
        let ws = WaterSetup::new(&params(48), &water, light, 96, 96).unwrap();
        assert!(ws.lattice > 48 && !ws.wrap(), "lattice {}", ws.lattice);
        let out = caustics(&ws, &Grid::new(16, 16)).unwrap();
        let worst = out
            .map
            .texels
            .iter()
            .map(|t| (t[0] as f64 - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!("clamped flat water: worst texel off 1 by {worst:.2e}");
        // measured 1.5e-6
        assert!(worst < 1.5e-5, "worst texel off by {worst}");
        // With walls the square is closed: the lattice is the square's own.
        let walled = WaterSetup::new(&params(48), &water, light, 96, 96)
            .unwrap()
            .with_walls(true);
        assert_eq!((walled.lattice, walled.origin), (48, DVec2::ZERO));
    }

    /// A surface too steep for the sun (it faces away) gives invalid photons, as the reference
    /// gives its triangles nothing.
    #[test]
    fn surface_facing_away_from_the_sun_is_invalid() {
        let light = DVec3::new(0.8, 0.0, -0.6);
        let water = flat_water(false, DVec3::ZERO);
        let ws = WaterSetup::new(&params(8), &water, light, 16, 16).unwrap();
        // h = −2x: seen = 1 + 0.8 · (−2) / 0.6 < 0.
        let ramp = Grid::from_fn(16, 16, |_, j| (-2.0 * (j as f64 + 0.5) * 2.0 / 16.0) as f32);
        // The photon at (1, 1), inside the square.
        let k = ((DVec2::ONE - ws.origin) / ws.spacing).round();
        let (photon, d) = photon(&ws, &ramp, k.y as usize, k.x as usize);
        assert_eq!(photon[2], -1.0);
        assert_eq!(d, 0.0);
        let bad = Grid::from_fn(4, 4, |_, _| f32::NAN);
        assert!(caustics(&ws, &bad).is_err());
    }

    /// The reference's `res x res` floor map of `scene` with `surface`.
    fn reference_at(scene: &Scene, surface: &dyn Surface, res: usize) -> CausticsMap {
        let input = ReferenceInput::from_scene(scene, surface).unwrap();
        let options = ReferenceOptions::default();
        let (width, height) = (res, res);
        reference(
            &ReferenceInput {
                width,
                height,
                ..input
            },
            &options,
            &|_, _| {},
        )
        .unwrap()
    }

    /// The pool's ripples over a sand bar (a ridge across the pool, periodic like the light, its
    /// faces up to 31° steep, its crest 60 % of the way up): the photons meet the sand through the
    /// receivers' map and the floor map agrees with the reference, which marches the terrain
    /// itself, about as well as over the flat floor.
    #[test]
    fn a_sand_bar_agrees_with_the_reference() {
        let mut scene = crate::fixtures::gentle_pool();
        scene.floor.walls = false;
        let res = 256;
        let water = scene.water.clone().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let heights = heights_for(&water, surface.as_ref(), 512, 512);
        let bar = crate::fixtures::sand_bar(&water);
        let mut l1 = Vec::new();
        for terrain in [None, Some(bar)] {
            scene.floor.terrain = terrain;
            let truth = reference_at(&scene, surface.as_ref(), res);
            let t0 = crate::receivers::flat_refracted(scene.light.direction, water.ior);
            let receivers = ReceiverHeights::of_floor(
                &scene.floor,
                scene.floor.solids.as_ref(),
                water.size,
                water.depth,
                t0,
                res,
            );
            let ws = WaterSetup::new(&params(256), &water, scene.light.direction, res, res)
                .unwrap()
                .with_receivers(Arc::new(receivers));
            let m = compare(&caustics(&ws, &heights).unwrap().map, &truth);
            eprintln!("terrain {}: {m:?}", scene.floor.terrain.is_some());
            // measured +9.8e-4 (flat), +4.1e-4 (sand bar)
            assert!(m.flux_error.abs() < 0.0098, "flux {m:?}");
            l1.push(m.relative_l1);
        }
        // measured 2.15 % (flat), 1.84 % (sand bar); the receivers' target is 3 %
        assert!(l1[1] < 0.03, "sand bar {} against flat {}", l1[1], l1[0]);
    }

    /// The pool's waves against the reference (256² map, 4 cells per texel): relative L1, flux, and
    /// the reference's six brightest foci each within 3 texels (4.7 cm of the 4 m pool; measured
    /// at most 2.2) of one of ours.
    #[test]
    fn pool_waves_agree_with_the_reference() {
        let mut scene = crate::fixtures::gentle_pool();
        // The floor map alone, as this twin makes it (the pool's walls are off: nothing lost to
        // them, and the light wraps round as here).
        scene.floor.walls = false;
        let water = scene.water.as_ref().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let res = 256;
        let r = reference_at(&scene, surface.as_ref(), res);
        let heights = heights_for(water, surface.as_ref(), 512, 512);
        let mut l1 = Vec::new();
        for p in [128, 256] {
            let ws = WaterSetup::new(&params(p), water, scene.light.direction, res, res).unwrap();
            let out = caustics(&ws, &heights).unwrap();
            let m = compare(&out.map, &r);
            eprintln!("pool {res}², P = {p}: {m:?}");
            l1.push(m.relative_l1);
            // measured 2.37e-3 (P = 128), 9.8e-4 (P = 256)
            assert!(m.flux_error.abs() < 0.01, "flux {m:?}");
            if p == 256 {
                // The six brightest foci of the reference are among our brightest (peaks of
                // similar height swap ranks).
                let (ours, truth) = (foci(&out.map, 18), foci(&r, 6));
                eprintln!("foci: ours {ours:?}, reference {truth:?}");
                for f in &truth {
                    let near = ours
                        .iter()
                        .map(|o| torus_distance(*o, *f, res))
                        .fold(f64::MAX, f64::min);
                    eprintln!("reference focus {f:?}: nearest of ours {near:.2} texels");
                    // measured at most 2.24
                    assert!(
                        near <= 3.0,
                        "reference focus {f:?}: nearest of ours {near} texels away"
                    );
                }
            }
        }
        // measured 0.0700 and 0.0215
        assert!(l1[0] < 0.09, "P = 128: {}", l1[0]);
        assert!(l1[1] < 0.035, "P = 256: {}", l1[1]);
        assert!(l1[1] < l1[0], "converges: {l1:?}");
    }

    /// The band of quads the shifted copies are drawn for is a bound: the pool's waves with a low
    /// sun (the most sideways travel) and merged blocks give the same map as drawing every copy of
    /// every quad, and the band is much narrower than the lattice.
    #[test]
    fn copy_band_loses_no_light() {
        let mut scene = Scene::builtin("pool").unwrap();
        scene.light.direction = DVec3::new(0.8, 0.3, -0.5);
        let mut water = scene.water.clone().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let heights = heights_for(&water, surface.as_ref(), 256, 256);
        // Shallow enough that the sideways travel stays a fraction of the square.
        water.depth = 0.4;
        for merge_levels in [0, 2] {
            let p = CausticTrianglesParams {
                merge_levels,
                ..params(128)
            };
            let ws = WaterSetup::new(&p, &water, scene.light.direction, 128, 128).unwrap();
            let band = copy_band(&ws, &heights);
            eprintln!("band {band} of {} quads", ws.lattice);
            // measured 30 of 128 quads, both merge levels
            assert!(band < ws.lattice / 2, "band {band} of {}", ws.lattice);
            let (photons, paths) = photon_pass(&ws, &heights);
            let irradiance = irradiance_pass(&ws.setup, &photons);
            let draw = |band: usize| {
                let mut setup = ws.setup.clone();
                setup.water.as_mut().unwrap().band = band;
                triangles_pass_with_paths(&setup, &photons, &irradiance, Some(&paths))
            };
            let (narrow, all) = (draw(band), draw(ws.lattice));
            let worst = narrow
                .texels
                .iter()
                .zip(&all.texels)
                .map(|(a, b)| (a[1] - b[1]).abs())
                .fold(0.0f32, f32::max);
            assert!(
                worst == 0.0,
                "merge {merge_levels}: texels differ by {worst}"
            );
            // And the band is needed: a band of one quad loses the light that crosses the edges.
            let thin = draw(1);
            let lost = all
                .texels
                .iter()
                .zip(&thin.texels)
                .map(|(a, b)| a[1] - b[1])
                .sum::<f32>();
            eprintln!("merge {merge_levels}: a one-quad band loses {lost}");
            // measured 1454 (merge 0), 765 (merge 2)
            assert!(
                lost > 70.0,
                "merge {merge_levels}: a one-quad band lost only {lost}"
            );
        }
    }

    /// Flux of a floor map in the floor map's unit times area (channel mean).
    fn map_flux(m: &CausticsMap) -> f64 {
        let sum: f64 = m
            .texels
            .iter()
            .map(|t| (t[0] + t[1] + t[2]) as f64 / 3.0)
            .sum();
        sum * m.size * m.size / (m.width * m.height) as f64
    }

    /// Flat water under an oblique sun in a pool with walls: the refracted light travels
    /// `(a, b) = t_xy / |t_z|` sideways per unit of depth, so the floor gets 1 over the square less
    /// the strips `a D` and `b D` wide (the walls' shadows), the wall x = size gets `a` where light
    /// reaches it (above the line `y = b (D − z)`, the shadow of the wall y = 0), the wall y = size
    /// gets `b`, the others nothing, and floor plus walls hold all the light the surface lets
    /// through, `size²`. Tiling water too: walls stop what would wrap round.
    #[test]
    fn flat_water_lights_the_walls_it_faces() {
        let light = DVec3::new(0.3, 0.1, -1.0).normalize();
        let water = flat_water(true, DVec3::ZERO);
        let ws = WaterSetup::new(&params(48), &water, light, 96, 96)
            .unwrap()
            .with_walls(true);
        let heights = Grid::new(16, 16);
        let floor = caustics(&ws, &heights).unwrap().map;
        let walls = wall_caustics(&ws, &heights).unwrap();
        let t = refract(light, DVec3::Z, 1.0 / 1.333).unwrap();
        let (a, b) = (t.x / -t.z, t.y / -t.z);
        let (s, d) = (2.0, 0.7);
        let floor_flux = (s - a * d) * (s - b * d);
        let x1 = a * (s * d - b * d * d / 2.0);
        let y1 = b * (s * d - a * d * d / 2.0);
        let got = [
            map_flux(&floor),
            walls.get(Wall::X1).flux(),
            walls.get(Wall::Y1).flux(),
        ];
        eprintln!(
            "floor {:.5} / {floor_flux:.5}, x1 {:.5} / {x1:.5}, y1 {:.5} / {y1:.5}",
            got[0], got[1], got[2]
        );
        // Measured: floor +9.6e-3 (its lit region's upwind edges fall 0.37 texel before the
        // next texel centres: the rasteriser lights those texels whole), x1 +6e-4, y1 −1e-4.
        for (g, e, bound) in [
            (got[0], floor_flux, 0.02),
            (got[1], x1, 5e-3),
            (got[2], y1, 1e-3),
        ] {
            assert!((g / e - 1.0).abs() < bound, "{g} vs {e}");
        }
        assert_eq!(walls.get(Wall::X0).flux(), 0.0);
        assert_eq!(walls.get(Wall::Y0).flux(), 0.0);
        let total = got.iter().sum::<f64>();
        eprintln!("floor + walls {total:.6} of {}", s * s);
        // Measured: +8.6e-3, the floor's rasterised edges.
        assert!((total / (s * s) - 1.0).abs() < 0.02, "{total}");
        // Inside the lit regions the irradiance is the analytic one.
        let m = walls.get(Wall::X1);
        let (along, z) = m.texel_centre(m.rows / 2, m.cols * 3 / 4);
        let v = m.texels[m.texel(along, z).unwrap()][0] as f64;
        assert!((v / a - 1.0).abs() < 1e-4, "{v} vs {a}");
        let f = floor.texels[48 * 96 + 20][1] as f64;
        assert!((f - 1.0).abs() < 1e-4, "{f}");
    }

    /// The hat rule draws exactly the light the surface lets through: its edge photons carry only
    /// the half of their cell inside the square ([`CausticTrianglesSetup::lattice_share`]). Flat
    /// tiling water gives 1 on every texel and `size²` in all; with walls floor plus walls hold
    /// `size²`; smooth tiling waves give the surface's outgoing flux (each quad the mean of its
    /// corners' power). Without the share the edge vertices' `E` doubled: `+2/P` of flux.
    #[test]
    fn the_hat_rule_draws_the_surface_flux() {
        let light = DVec3::new(0.3, 0.1, -1.0).normalize();
        let p = CausticTrianglesParams {
            area_rule: super::super::AreaRule::Hat,
            ..params(48)
        };
        let water = flat_water(true, DVec3::ZERO);
        let flat = Grid::new(16, 16);
        let ws = WaterSetup::new(&p, &water, light, 96, 96).unwrap();
        let map = caustics(&ws, &flat).unwrap().map;
        let worst = map
            .texels
            .iter()
            .map(|t| (t[1] as f64 - 1.0).abs())
            .fold(0.0, f64::max);
        let flux = map_flux(&map) / 4.0 - 1.0;
        eprintln!("hat, flat, wrap: worst texel {worst:.2e}, flux {flux:+.2e}");
        // Measured: worst texel 2.9e-6, flux +6.2e-8 (every edge photon's whole power, the rings
        // cut at the edges: worst texel 3.1, flux +4.2e-2 = 49²/48² − 1).
        assert!(worst < 2.9e-5, "worst texel off by {worst}");
        assert!(flux.abs() < 6.2e-7, "flux {flux}");

        let ws = ws.with_walls(true);
        let floor = caustics(&ws, &flat).unwrap().map;
        let walls = wall_caustics(&ws, &flat).unwrap();
        let total = (map_flux(&floor) + walls.flux()) / 4.0 - 1.0;
        eprintln!("hat, flat, walls: floor + walls {total:+.2e}");
        // Measured: +8.6e-3, the floor's rasterised upwind edges (as for the paper rule in
        // `flat_water_lights_the_walls_it_faces`).
        assert!(total.abs() < 0.02, "floor + walls {total}");

        // Gentle tiling waves, one and two periods across the 2 m square.
        let waves = Grid::from_fn(64, 64, |i, j| {
            let (x, y) = ((j as f64 + 0.5) / 64.0, (i as f64 + 0.5) / 64.0);
            let tau = std::f64::consts::TAU;
            (0.01 * (tau * x).sin() + 0.006 * (tau * (2.0 * y + x) + 0.4).cos()) as f32
        });
        let ws = WaterSetup::new(&p, &water, light, 96, 96).unwrap();
        let out = caustics(&ws, &waves).unwrap();
        let n = ws.setup.p;
        let mut surface = 0.0;
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                let c = [(0, 0), (0, 1), (1, 0), (1, 1)]
                    .map(|(a, b)| out.photons[(i + a) * n + j + b][2] as f64);
                surface += c.iter().sum::<f64>() / 4.0;
            }
        }
        let flux = map_flux(&out.map) / surface - 1.0;
        eprintln!("hat, waves, wrap: flux {flux:+.2e} of the surface's {surface:.5}");
        // Measured: +8.1e-6.
        assert!(flux.abs() < 8.1e-5, "flux {flux}");
    }

    /// The pool's waves with walls and a low sun: light leaving the surface (every photon's power
    /// over its quads, the hat rule's exact flux) ends on the floor or a wall, the straddling
    /// triangles split between them.
    #[test]
    fn pool_light_ends_on_floor_and_walls() {
        let scene = Scene::builtin("pool").unwrap();
        let mut water = scene.water.clone().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let heights = heights_for(&water, surface.as_ref(), 128, 128);
        // Flux in one unit on both sides: no absorption along the paths.
        water.absorption = DVec3::ZERO;
        for zenith in [0.0f64, 30.0, 60.0] {
            let z = zenith.to_radians();
            let light = DVec3::new(z.sin() * 0.95, z.sin() * 0.31, -z.cos()).normalize();
            let p = CausticTrianglesParams {
                area_rule: super::super::AreaRule::Hat,
                ..params(128)
            };
            let ws = WaterSetup::new(&p, &water, light, 128, 128)
                .unwrap()
                .with_walls(true);
            let floor = caustics(&ws, &heights).unwrap().map;
            let walls = wall_caustics(&ws, &heights).unwrap();
            let (photons, _) = photon_pass(&ws, &heights);
            let n = ws.setup.p;
            // The surface's outgoing light: each quad carries the mean of its corners' power.
            let mut out = 0.0;
            for i in 0..n - 1 {
                for j in 0..n - 1 {
                    let c = [(0, 0), (0, 1), (1, 0), (1, 1)]
                        .map(|(a, b)| photons[(i + a) * n + j + b][2] as f64);
                    if c.iter().all(|&c| c >= 0.0) {
                        out += c.iter().sum::<f64>() / 4.0;
                    }
                }
            }
            // The same technique without walls, the light wrapping round onto the floor.
            let plain = WaterSetup::new(&p, &water, light, 128, 128).unwrap();
            let plain = map_flux(&caustics(&plain, &heights).unwrap().map);
            let lit: Vec<f64> = Wall::ALL.iter().map(|&w| walls.get(w).flux()).collect();
            let total = map_flux(&floor) + walls.flux();
            let (split, err) = (total / plain - 1.0, total / out - 1.0);
            eprintln!(
                "zenith {zenith}: out {out:.5}, floor {:.5}, walls {lit:.4?}, floor + walls \
                 {err:+.2e} of the outgoing light, {split:+.2e} of the map without walls",
                map_flux(&floor)
            );
            // Measured: +2.4e-4, −1.7e-3, −5.7e-3 (the built-in pool's wind ripples): what the
            // split along the floor-wall edges and the walls' cut-off photons move or lose.
            assert!(split.abs() < 1e-2, "zenith {zenith}: {split}");
            // Measured: +1.30e-2, −2.4e-3, −9.7e-3 (+2.84e-2, +1.44e-2, +6.3e-3 with every edge
            // photon's whole power, `lattice_share`): the texel-centre rasterisation of a 128²
            // lattice's thin bright triangles on a 128² map, and the walls' cut-off photons.
            assert!(err.abs() < 0.05, "zenith {zenith}: {err}");
            if zenith > 0.0 {
                // The sun shines towards +x, +y: the walls x = 0, y = 0 are in their own shadow.
                assert_eq!(lit[0] + lit[2], 0.0);
                assert!(lit[1] > lit[3] && lit[3] > 0.0, "{lit:?}");
            }
        }
    }

    fn torus_distance(a: (usize, usize), b: (usize, usize), n: usize) -> f64 {
        let d = |x: usize, y: usize| {
            let d = x.abs_diff(y);
            d.min(n - d) as f64
        };
        d(a.0, b.0).hypot(d(a.1, b.1))
    }

    /// The `count` brightest texels of the 3 x 3 box-filtered map that are the largest within 8
    /// texels (periodic), as (row, column).
    fn foci(map: &CausticsMap, count: usize) -> Vec<(usize, usize)> {
        let n = map.width;
        let at = |i: i64, j: i64| {
            let t =
                map.texels[(i.rem_euclid(n as i64) as usize) * n + j.rem_euclid(n as i64) as usize];
            (t[0] + t[1] + t[2]) as f64
        };
        let blur: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = ((k / n) as i64, (k % n) as i64);
                (-1..=1)
                    .flat_map(|a| (-1..=1).map(move |b| (a, b)))
                    .map(|(a, b)| at(i + a, j + b))
                    .sum()
            })
            .collect();
        let b = |i: i64, j: i64| {
            blur[(i.rem_euclid(n as i64) as usize) * n + j.rem_euclid(n as i64) as usize]
        };
        let mut peaks: Vec<(f64, (usize, usize))> = (0..n * n)
            .filter_map(|k| {
                let (i, j) = ((k / n) as i64, (k % n) as i64);
                let v = b(i, j);
                let max = (-8..=8)
                    .flat_map(|a| (-8..=8).map(move |c| (a, c)))
                    .all(|(a, c)| (a, c) == (0, 0) || b(i + a, j + c) < v);
                max.then_some((v, (k / n, k % n)))
            })
            .collect();
        peaks.sort_by(|x, y| y.0.total_cmp(&x.0));
        peaks.into_iter().take(count).map(|p| p.1).collect()
    }
}
