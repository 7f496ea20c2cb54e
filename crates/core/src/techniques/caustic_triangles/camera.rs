//! The camera pass (paper 4, §4.3), CPU twin of `caustics-gpu`'s
//! `caustic_triangles::camera` (`caustic_triangles/camera.wgsl`): the technique's own final
//! image.
//!
//! Per pixel of the scene camera, the eye ray is traced against the floor plane `z = 0` and every
//! generator's layered distance map (the §3 search; the distance maps also hold the diffuse
//! occluders, so walls are found the same way).
//! - A **diffuse** point `y` (floor, wall) reflects `ρ (A + C E(y))`: `A` the ambient term, `C` the
//!   light's colour times intensity, `E` the light's irradiance in floor units (1 = the light on the
//!   floor straight below a point light, or anywhere under the sun):
//!   - a point light: the direct term `I cos / d²` (inside a spot's cone) where the light cube
//!     map's shadow distance in the direction of `y` is not nearer than `|y − light| / (1 + b)`,
//!     plus the caustic irradiance `Σ E` of that texel where its receiver distance
//!     `Σ E d / Σ E` is within the relative bias `b` of `|y − light|` (the distance test of §4.3:
//!     light that landed elsewhere in that direction, in front of or behind `y`, does not leak onto
//!     it);
//!   - the sun (its light cube map degenerates, see [`super::cube`]): `cos / |L_z|` where a shadow
//!     ray towards the sun meets no surface of any distance map, plus the floor map's caustic on the
//!     floor.
//! - A **glass** point (the generator) splits into the Fresnel-weighted reflection and refraction:
//!   the reflected ray, and the refracted ray traced through the glass in the generator's distance
//!   map (total internal reflections followed, at most `depth` events) and out, continue to the
//!   diffuse point they reach, which is shaded as above: the caustics are seen in the generator's
//!   reflections and refractions. These secondary rays look through other glass (one level of
//!   glass per path, a departure: the paper shades them the same way, with more bounces).
//! - Rays that meet nothing see a constant sky.
//!
//! Albedos are one colour for the floor and one for the occluders (the glass scenes' floor is
//! plain); the glass is clear (its tint is not applied). All in linear RGB; [`crate::render::to_rgb8`] tone maps.

use glam::DVec3;

use super::CausticTrianglesSetup;
use super::cube::{LightCube, sphere_span};
use super::distance_map::{Crossing, DistanceMap};
use super::scene::{FloorWindow, PointLight};
use crate::map::CausticsMap;
use crate::optics::{fresnel_transmittance, reflect, refract};
use crate::parallel::prelude::*;
use crate::scene::Camera;

/// The camera pass's shading constants.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraParams {
    /// Ambient irradiance, floor units.
    pub ambient: f64,
    /// Relative bias `b` of the shadow and caustic distance tests.
    pub bias: f64,
    /// Radiance of the rays that meet nothing, linear RGB.
    pub sky: DVec3,
    /// Diffuse albedo of the floor, linear RGB.
    pub floor_albedo: DVec3,
    /// Diffuse albedo of the occluders (walls), linear RGB.
    pub wall_albedo: DVec3,
    /// Light colour times intensity.
    pub light_color: DVec3,
}

impl Default for CameraParams {
    fn default() -> Self {
        CameraParams {
            ambient: 0.08,
            // The floor's distance from the light changes by ~tan θ · 2/C across a texel of a C²
            // face; 2 % covers θ up to ~75° at C = 512 and ~60° at C = 128.
            bias: 0.02,
            sky: DVec3::new(0.55, 0.65, 0.8),
            floor_albedo: DVec3::splat(0.7),
            wall_albedo: DVec3::new(0.75, 0.55, 0.45),
            light_color: DVec3::ONE,
        }
    }
}

/// Where the caustic irradiance and the shadows come from.
pub enum CameraLight<'a> {
    /// The sun (unit travel direction) and the floor map of its caustics.
    Sun {
        /// Unit direction the sunlight travels, `z < 0`.
        direction: DVec3,
        /// The floor map of the sun's caustics, floor units (its first channel is read).
        map: &'a CausticsMap,
        /// The floor square `map` covers and its resolution.
        floor: FloorWindow,
    },
    /// A point or spot light and its light cube map (caustics and shadow distances).
    Point {
        /// The light, its position and a spot's cone.
        light: PointLight,
        /// Its light cube map: the caustic's `(Σ E, Σ E d)` and the shadow distances per texel.
        cube: &'a LightCube,
    },
}

/// Everything the camera pass reads.
pub struct CameraInput<'a> {
    /// The scene camera whose pixels are traced.
    pub camera: &'a Camera,
    /// Every generator's setup and distance map: besides the floor, the surfaces an eye ray can
    /// meet (the maps hold the occluders too).
    pub generators: Vec<(&'a CausticTrianglesSetup, &'a DistanceMap)>,
    /// The light and where its caustics and shadows are read from.
    pub light: CameraLight<'a>,
    /// The shading constants.
    pub params: CameraParams,
}

#[derive(Clone, Copy, Debug)]
struct Hit {
    t: f64,
    normal: DVec3,
    glass: bool,
    floor: bool,
    generator: usize,
}

/// The offset of secondary rays off the surface they leave, world units.
pub const EPS: f64 = 1e-4;

impl CameraInput<'_> {
    /// Nearest of the floor plane and every distance map's surface (glass crossings per `mode`).
    fn nearest(&self, o: DVec3, d: DVec3, mode: Crossing) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        if d.z < 0.0 && o.z > 0.0 {
            best = Some(Hit {
                t: -o.z / d.z,
                normal: DVec3::Z,
                glass: false,
                floor: true,
                generator: 0,
            });
        }
        for (g, (s, dm)) in self.generators.iter().enumerate() {
            let limit = best.map_or(f64::INFINITY, |b| b.t);
            let Some((t0, t1)) = sphere_span(dm, o, d) else {
                continue;
            };
            if t0 >= limit {
                continue;
            }
            if let Some((t, surf)) = dm.trace(
                o + d * t0,
                d,
                0.0,
                t1.min(limit) - t0,
                mode,
                s.linear_steps,
                s.secant_iterations,
            ) && t0 + t < limit
            {
                best = Some(Hit {
                    t: t0 + t,
                    normal: surf.normal,
                    glass: surf.glass,
                    floor: false,
                    generator: g,
                });
            }
        }
        best
    }

    /// Whether any distance map has a surface along `o + t d`, `t > 0` (the sun's shadow ray).
    fn occluded(&self, o: DVec3, d: DVec3) -> bool {
        self.generators.iter().any(|(s, dm)| {
            sphere_span(dm, o, d).is_some_and(|(t0, t1)| {
                dm.trace(
                    o + d * t0,
                    d,
                    0.0,
                    t1 - t0,
                    Crossing::Entering,
                    s.linear_steps,
                    s.secant_iterations,
                )
                .is_some()
            })
        })
    }

    /// Irradiance (floor units) of the light at diffuse point `y` with unit normal `n`.
    pub fn irradiance(&self, y: DVec3, n: DVec3, floor: bool) -> f64 {
        let b = self.params.bias;
        match &self.light {
            CameraLight::Sun {
                direction,
                map,
                floor: window,
            } => {
                let mut e = 0.0;
                let cos = -n.dot(*direction);
                if cos > 0.0 && !self.occluded(y + n * EPS, -*direction) {
                    e += cos / -direction.z;
                }
                if floor {
                    let px = window.to_pixel(y.truncate());
                    let (j, i) = (px.x.floor(), px.y.floor());
                    if j >= 0.0 && i >= 0.0 && (j as usize) < map.width && (i as usize) < map.height
                    {
                        e += map.texels[i as usize * map.width + j as usize][0] as f64;
                    }
                }
                e
            }
            CameraLight::Point { light, cube } => {
                let v = y - light.position;
                let dist = v.length();
                let dir = v / dist;
                let k = cube.texel_of(dir);
                let mut e = 0.0;
                let cos = -n.dot(dir);
                if cos > 0.0 && light.lights(dir) && dist <= cube.shadow[k] as f64 * (1.0 + b) {
                    e += light.intensity() * cos / (dist * dist);
                }
                let [se, sed] = cube.caustic[k];
                if se > 0.0 {
                    let receiver = sed as f64 / se as f64;
                    if (dist - receiver).abs() <= b * receiver {
                        e += se as f64;
                    }
                }
                e
            }
        }
    }

    fn shade_diffuse(&self, o: DVec3, d: DVec3, h: &Hit) -> DVec3 {
        let y = o + d * h.t;
        let n = if h.normal.dot(d) > 0.0 {
            -h.normal
        } else {
            h.normal
        };
        let albedo = if h.floor {
            self.params.floor_albedo
        } else {
            self.params.wall_albedo
        };
        let e = self.irradiance(y, n, h.floor);
        albedo * (DVec3::splat(self.params.ambient) + self.params.light_color * e)
    }

    /// A secondary ray: the diffuse point it reaches (looking through glass), or the sky.
    fn secondary(&self, o: DVec3, d: DVec3) -> DVec3 {
        let o = o + d * EPS;
        match self.nearest(o, d, Crossing::DiffuseOnly) {
            Some(h) => self.shade_diffuse(o, d, &h),
            None => self.params.sky,
        }
    }

    /// Radiance along the eye ray `o + t d`.
    pub fn radiance(&self, o: DVec3, d: DVec3) -> DVec3 {
        let Some(h) = self.nearest(o, d, Crossing::Entering) else {
            return self.params.sky;
        };
        if !h.glass {
            return self.shade_diffuse(o, d, &h);
        }
        let (setup, dm) = self.generators[h.generator];
        let ior = setup.ior;
        let p = o + d * h.t;
        let n = h.normal;
        let cos_i = (-d.dot(n)).max(0.0);
        let reflected = self.secondary(p, reflect(d, n).normalize());
        let Some(t) = refract(d, n, 1.0 / ior) else {
            return reflected;
        };
        let t_in = fresnel_transmittance(cos_i, 1.0, ior);
        // Through the glass: leave it, or reflect totally inside, up to `depth` events.
        let (mut x, mut r) = (p, t.normalize());
        let eps = 1e-4 * dm.radius;
        for _ in 0..setup.depth {
            let Some((_, t1)) = sphere_span(dm, x, r) else {
                break;
            };
            let Some((dd, s)) = dm.trace(
                x,
                r,
                eps,
                t1,
                Crossing::Leaving,
                setup.linear_steps,
                setup.secant_iterations,
            ) else {
                break;
            };
            if !s.glass {
                break;
            }
            x += r * dd;
            let n_in = -s.normal;
            let cos = -r.dot(n_in);
            match refract(r, n_in, ior) {
                Some(out) => {
                    let t_out = fresnel_transmittance(cos, ior, 1.0);
                    let through = self.secondary(x, out.normalize());
                    return reflected * (1.0 - t_in) + through * (t_in * t_out);
                }
                None => r = reflect(r, n_in).normalize(),
            }
        }
        // Lost inside (depth, or a seam of the map): the reflection alone.
        reflected * (1.0 - t_in)
    }
}

/// The camera pass: linear RGB radiance per pixel, rows top to bottom.
pub fn camera_pass(input: &CameraInput) -> Vec<[f32; 3]> {
    let cam = input.camera;
    let (w, h) = (cam.width as usize, cam.height as usize);
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (o, d) = cam.ray((k % w) as f64, (k / w) as f64);
            let c = input.radiance(o, d);
            [c.x as f32, c.y as f32, c.z as f32]
        })
        .collect()
}

impl CameraParams {
    /// The scene's light colour and intensity, and its floor's albedo at the square's centre (the
    /// glass scenes' floor is plain).
    pub fn from_scene(scene: &crate::scene::Scene) -> Self {
        let centre = glam::DVec2::splat(0.5 * scene.size);
        CameraParams {
            floor_albedo: scene.floor.albedo.at(centre, scene.size),
            light_color: scene.light.color * scene.light.intensity,
            ..Default::default()
        }
    }
}

/// One generator of a scene, everything its passes need.
pub struct Generator {
    /// Its setup: photon image, light frame, search and reconstruction parameters.
    pub setup: CausticTrianglesSetup,
    /// Its layered distance map, around the glass object, holding the scene's occluders too.
    pub dm: DistanceMap,
}

/// Every glass object of `scene` as a generator (its distance map and setup).
pub fn generators(
    scene: &crate::scene::Scene,
    params: &super::CausticTrianglesParams,
) -> crate::Result<Vec<Generator>> {
    (0..super::glass_generators(scene)?)
        .map(|k| {
            let gs = super::GlassScene::from_scene(scene, k)?;
            let dm =
                DistanceMap::build(&gs, params.cube_resolution as usize, params.layers as usize);
            let setup = CausticTrianglesSetup::new(params, &gs)?;
            Ok(Generator { setup, dm })
        })
        .collect()
}

/// The whole technique on the CPU, ending in the camera pass: photon tracing, reconstruction into
/// the floor map (sun) or the light cube map and its shadow distances (point light), then the
/// image (linear RGB).
pub fn render_scene(
    scene: &crate::scene::Scene,
    params: &super::CausticTrianglesParams,
    camera_params: &CameraParams,
) -> crate::Result<Vec<[f32; 3]>> {
    let gens = generators(scene, params)?;
    let pairs: Vec<_> = gens.iter().map(|g| (&g.setup, &g.dm)).collect();
    let outputs: Vec<_> = pairs.iter().map(|(s, dm)| super::caustics(s, dm)).collect();
    let image = |light: CameraLight| {
        camera_pass(&CameraInput {
            camera: &scene.camera,
            generators: pairs.clone(),
            light,
            params: camera_params.clone(),
        })
    };
    Ok(match gens[0].setup.point {
        None => {
            let map = (outputs[1..].iter()).fold(outputs[0].map.clone(), |m, o| m.added(&o.map));
            image(CameraLight::Sun {
                direction: gens[0].setup.w,
                map: &map,
                floor: gens[0].setup.floor,
            })
        }
        Some(light) => {
            let mut cube = LightCube::new(params.light_cube as usize, light.position);
            for ((s, _), o) in pairs.iter().zip(&outputs) {
                super::cube::cube_triangles_pass(s, &o.photons, &o.irradiance, &mut cube);
            }
            super::cube::shadow_pass(&pairs, &mut cube);
            image(CameraLight::Point { light, cube: &cube })
        }
    })
}
