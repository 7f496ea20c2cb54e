//! What every evaluating pass shares, `common.wgsl`'s math: the water read at a point
//! ([`SurfaceInput`], WGSL `water_at`), the light map ([`LightMap`], WGSL `light_lookup`), and the
//! caustic at one floor point ([`trace`], [`caustic_at`], WGSL `procedural_caustic`).

use std::path::Path;

use glam::{DVec2, DVec3};

use super::{LIGHT_MAP_MARGIN, ProceduralCausticsParams, ProceduralSetup};
use crate::error::{Error, Result};
use crate::grid::{Edge, Grid};
use crate::optics::{height_field_normal, refract};
use crate::water::Surface;
use crate::water::procedural::Procedural;

/// The sun / light map over the tangent plane of the direction toward the sun: texel `(r, c)` is
/// centred at `uv = (−E + (c + ½) 2E / width, −E + (r + ½) 2E / height)`, read bilinearly, 0 beyond.
#[derive(Clone, Debug, PartialEq)]
pub struct LightMap {
    /// Texels along `u` (columns).
    pub width: usize,
    /// Texels along `v` (rows).
    pub height: usize,
    /// `E`: the map spans `uv ∈ [−E, E]²`, the tangent of the half-angle it covers.
    pub extent: f64,
    /// Row-major, row 0 at `v = −E`; normalised to 1 in the sun's direction.
    pub texels: Vec<f32>,
}

fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

impl LightMap {
    /// The light map the parameters ask for: a PNG, or the paper's sun disk and halo.
    pub fn from_params(p: &ProceduralCausticsParams) -> Result<LightMap> {
        match &p.light_map {
            Some(path) => {
                let extent = match p.light_map_extent {
                    Some(deg) => deg.to_radians().tan(),
                    None => (LIGHT_MAP_MARGIN * p.sun_radii().1).tan(),
                };
                LightMap::load(path, extent)
            }
            None => Ok(LightMap::sun(p)),
        }
    }

    /// The brightness of the sky at angle `theta` (radians) from the sun: 1 in the disk, the halo's
    /// smooth fall from `halo_level` to 0 beyond it.
    pub fn profile(p: &ProceduralCausticsParams, theta: f64) -> f64 {
        let (r_s, r_h) = p.sun_radii();
        if theta <= r_s {
            1.0
        } else {
            p.halo_level * (1.0 - smoothstep(r_s, r_h, theta))
        }
    }

    /// The paper's sun: the disk and its halo, sampled at the texel centres.
    pub fn sun(p: &ProceduralCausticsParams) -> LightMap {
        let n = p.light_map_resolution as usize;
        let extent = (LIGHT_MAP_MARGIN * p.sun_radii().1).tan();
        let texel = 2.0 * extent / n as f64;
        let texels = (0..n * n)
            .map(|k| {
                let uv = DVec2::new(
                    -extent + ((k % n) as f64 + 0.5) * texel,
                    -extent + ((k / n) as f64 + 0.5) * texel,
                );
                LightMap::profile(p, uv.length().atan()) as f32
            })
            .collect();
        LightMap {
            width: n,
            height: n,
            extent,
            texels,
        }
        .normalised(Path::new("<generated sun>"))
        .expect("the generated sun is bright at its centre")
    }

    /// A greyscale reading of a PNG (any colour type; luma in [0, 1], no sRGB decoding: a light map
    /// is data), normalised to 1 at its centre.
    #[cfg_attr(not(feature = "formats"), allow(unused_variables))]
    pub fn load(path: &Path, extent: f64) -> Result<LightMap> {
        #[cfg(not(feature = "formats"))]
        return Err(Error::feature_off(path, "a light map", "formats"));
        #[cfg(feature = "formats")]
        {
            let img = image::open(path).map_err(|e| Error::bad_file(path, e.to_string()))?;
            let luma = img.to_luma32f();
            let (width, height) = (luma.width() as usize, luma.height() as usize);
            if width < 2 || height < 2 {
                return Err(Error::bad_file(
                    path,
                    "a light map needs at least 2 x 2 texels",
                ));
            }
            LightMap {
                width,
                height,
                extent,
                texels: luma.into_raw(),
            }
            .normalised(path)
        }
    }

    fn normalised(mut self, path: &Path) -> Result<LightMap> {
        let c = self.sample(DVec2::ZERO);
        if !(c > 0.0 && c.is_finite()) {
            return Err(Error::bad_file(
                path,
                format!(
                    "the light map is {c} at its centre, the sun's own direction: it must be bright there (the map is normalised to 1 at the centre)"
                ),
            ));
        }
        for t in &mut self.texels {
            *t = (*t as f64 / c) as f32;
        }
        Ok(self)
    }

    fn texel(&self, r: i64, c: i64) -> f64 {
        if r < 0 || c < 0 || r >= self.height as i64 || c >= self.width as i64 {
            0.0
        } else {
            self.texels[r as usize * self.width + c as usize] as f64
        }
    }

    /// Bilinear lookup at `uv`, 0 beyond the map (WGSL `light_lookup`).
    pub fn sample(&self, uv: DVec2) -> f64 {
        let t = (uv / self.extent * 0.5 + 0.5) * DVec2::new(self.width as f64, self.height as f64)
            - 0.5;
        let b = t.floor();
        let f = t - b;
        let (c, r) = (b.x as i64, b.y as i64);
        let top = self.texel(r, c) * (1.0 - f.x) + self.texel(r, c + 1) * f.x;
        let bottom = self.texel(r + 1, c) * (1.0 - f.x) + self.texel(r + 1, c + 1) * f.x;
        top * (1.0 - f.y) + bottom * f.y
    }
}

/// The water the technique reads.
#[derive(Clone, Copy)]
pub enum SurfaceInput<'a> {
    /// The paper's wave function, with its analytic gradient.
    Wave(&'a Procedural),
    /// A height grid over the scene square, through its bicubic interpolant (wrapped or clamped by
    /// the setup's `wrap`).
    Grid(&'a Grid),
}

impl SurfaceInput<'_> {
    /// Height and gradient at `p` (WGSL `water_at`).
    pub fn height_gradient(&self, p: DVec2, setup: &ProceduralSetup) -> (f64, DVec2) {
        match self {
            SurfaceInput::Wave(w) => w.height_gradient(p),
            SurfaceInput::Grid(g) => g.sample(
                p,
                setup.size,
                if setup.wrap { Edge::Wrap } else { Edge::Clamp },
            ),
        }
    }
}

/// One gathering ray, for inspection and tests.
#[derive(Clone, Copy, Debug)]
pub struct Trace {
    /// Where the ray meets the rest level (the point whose height and normal are read).
    pub surface_point: DVec2,
    /// The water's height above its rest level there, world units.
    pub height: f64,
    /// The water's upward unit normal there, from the height's gradient.
    pub normal: DVec3,
    /// The direction refracted into the air, `None` on total internal reflection.
    pub refracted: Option<DVec3>,
    /// Its light-map coordinates, `None` where it points away from the sun's hemisphere.
    pub uv: Option<DVec2>,
}

/// Follow the gathering ray from floor point `p` to the surface and out into the air.
pub fn trace(setup: &ProceduralSetup, water: &SurfaceInput, p: DVec2) -> Trace {
    let up = setup.up;
    // Line-plane intercept with the rest level (exact for the vertical ray).
    let s = p + up.truncate() * (setup.depth / up.z);
    let (h, grad) = water.height_gradient(s, setup);
    let normal = height_field_normal(grad);
    // Snell reversed: from the water (η = ior) up into the air, the normal facing the ray.
    let refracted = refract(up, -normal, setup.ior);
    let uv = refracted.and_then(|r| {
        let [e1, e2, sun] = setup.sun_frame;
        let z = r.dot(sun);
        (z > 0.0).then(|| DVec2::new(r.dot(e1), r.dot(e2)) / z)
    });
    Trace {
        surface_point: s,
        height: h,
        normal,
        refracted,
        uv,
    }
}

/// The caustic at floor point `p`, per RGB channel: the light map in the refracted direction times
/// the absorption along the way (WGSL `procedural_caustic`).
pub fn caustic_at(setup: &ProceduralSetup, water: &SurfaceInput, p: DVec2) -> [f32; 3] {
    let t = trace(setup, water, p);
    let e = t.uv.map_or(0.0, |uv| setup.light.sample(uv));
    let d = (setup.depth + t.height) / setup.up.z;
    let a = (-setup.gathered_absorption() * d).exp() * (setup.ground + (1.0 - setup.ground) * e);
    [a.x as f32, a.y as f32, a.z as f32]
}
