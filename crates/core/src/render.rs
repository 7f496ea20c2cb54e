//! The final image on the CPU: the scene seen from its camera, the floor or terrain lit by the sun
//! through a caustics map, the water surface with the Fresnel reflection of a sky and the refraction
//! of what is under it, and the objects. This is the no-GPU fallback and the picture of the README.
//!
//! Light transport (radiometric, linear RGB, before tone mapping):
//! - The sun gives the horizontal irradiance `E_h = I |L_z|` above the water.
//! - Under water, the floor receives `E_h T(θ₀) M(x, y)`, where `M` is the caustics map (relative
//!   irradiance: Fresnel, focusing, absorption and terrain slope are already in it), plus an
//!   ambient term, the daylight sky's irradiance on a horizontal surface ([`sky_ambient`]), absorbed
//!   over the water's depth. A Lambertian floor reflects `ρ / π` of it.
//! - On the way back to the eye, the view ray is attenuated by `exp(−K d)` in the water and
//!   transmitted with `1 − R`, where `R` is the Fresnel reflectance of the surface for the view ray;
//!   `R` weights the reflected sky: Preetham's daylight model for this sun with the sun's disk at
//!   its true size ([`crate::sky`]).
//! - The caustics come from a map of the floor square ([`Caustics::Floor`]), or, for a technique
//!   that computes them in the eye camera's screen space (`cascaded`, paper 5), from an image made
//!   for this camera ([`Caustics::EyeSpace`]): a floor point `F` reached by a view ray (refracted at
//!   the water) reads that image where `F` projects through the camera, which is the pixel whose
//!   straight ray the technique's eye pass followed to `F`. Where the image has nothing there (off
//!   the image, no floor seen, beyond the last cascade), `F` is lit as under flat water.
//! - A camera under the surface (inside the water's square, below the water's height there) starts
//!   its rays in the water ([`camera_under_water`]). A ray meeting the surface from below splits by
//!   the Fresnel equations from the dense side ([`from_below`]): inside Snell's window (the cone of
//!   half-angle asin(1/n) about the surface normal) part of it refracts out to the sky, the rest
//!   reflects back down; beyond the window it is totally reflected, so the surface mirrors the pool.
//! - With the pool's walls as receivers and a technique that lit them, a wall point gets
//!   `E_h T(θ₀) W(along, z)` from the sun, `W` its wall's map in the same relative unit as `M`
//!   (absorption along the light's path already in it), besides the ambient term it gets anyway.
//! - Objects under water are lit by the flat-water refracted sun with their own shadow test; they
//!   do not receive caustics from the reference (which knows only the floor) until a technique that
//!   handles mesh receivers provides them.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::eye::EyeCamera;
use crate::map::{CausticsMap, MapPyramid};
use crate::mesh::MeshBvh;
use crate::optics::{fresnel_transmittance, height_field_normal, reflect, refract};
use crate::scene::{Camera, Material, Scene};
use crate::sky::{SUN_RADIUS, Sky, TURBIDITY};
use crate::walls::{Wall, WallMaps};
use crate::water::Surface;
use crate::water::slopes::{
    Footprint, SlopeMoments, SlopePyramid, glint, sample_spread, sun_slope_variance, visible_facets,
};

// What the techniques hand the final image, and the tone curve, defined below the techniques and
// the scene model, under the names the front ends know them by.
pub use crate::eye::{EYE_SPACE_MIN_WEIGHT, EyeSpaceCaustics};
pub use crate::techniques::Caustics;
pub use crate::tone_map::{ToneMap, tone_curve, tone_map};

/// Where each pixel of an image made for `scene`'s camera sees the floor: its straight ray's
/// first hit on the floor or its terrain, `None` where it meets neither. These are the points an
/// [`EyeSpaceCaustics`]'s texels describe, so that a front end can compare one with a floor map.
pub fn eye_floor_points(scene: &Scene) -> crate::Result<Vec<Option<glam::DVec3>>> {
    use crate::techniques::cascaded::{CascadedSetup, eye_pass};
    let setup = CascadedSetup::from_scene(scene, &Default::default())?;
    let e = &setup.eye;
    Ok(eye_pass(&setup, scene.floor.terrain.as_ref())
        .iter()
        .enumerate()
        .map(|(p, g)| {
            (g[3] != 0.0).then(|| {
                let (x, y) = ((p % e.width) as f64 + 0.5, (p / e.width) as f64 + 0.5);
                e.position + e.ray(x, y) * g[0] as f64
            })
        })
        .collect())
}

pub struct RenderOptions {
    /// Samples per pixel along each axis (n² rays per pixel).
    pub supersampling: u32,
    /// Radiance is multiplied by this before the tone curve.
    pub exposure: f64,
    pub tone_map: ToneMap,
    /// Filter the water's normals by each sample's footprint ([`crate::water::slopes`]): far
    /// water shades with the mean slope and the roughness of the waves it cannot resolve. Off
    /// (the default), every sample shades with the exact normal where it meets the surface.
    /// Both final images (caustics-gpu's `final_image` is its twin); not the default, since many
    /// samples' FLIP prefers the exact normals: docs/look.md has the measurements.
    pub filter_water: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            supersampling: 2,
            exposure: 1.0,
            tone_map: ToneMap::default(),
            filter_water: false,
        }
    }
}

impl RenderOptions {
    /// The scene's own exposure and tone curve (its `[camera]` keys), with `supersampling`.
    pub fn for_scene(scene: &Scene, supersampling: u32) -> Self {
        RenderOptions {
            supersampling,
            exposure: scene.look.exposure,
            tone_map: scene.look.tone_map,
            ..Default::default()
        }
    }
}

/// An 8-bit sRGB image, rows top to bottom.
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

/// Samples per side of the lattice [`slab_bounds`] searches.
pub const SLAB_LATTICE: usize = 128;

/// What the view rays' search for the water surface needs to know of it ([`slab_bounds`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Slab {
    /// Half the height of the slab the surface lies in, `|z − level| <= half_height`.
    pub half_height: f64,
    /// A bound on the surface's slope `|∇h|`, which limits how fast a ray's height above the
    /// surface can change ([`first_crossing`]).
    pub slope: f64,
}

/// The slab the water surface lies in and its steepest slope, which the view rays search: the
/// largest |h| and |∇h| on a [`SLAB_LATTICE`]² lattice of the square, each times 1.5 (room for
/// the interpolant between samples). The GPU's final image finds the same bounds on the GPU
/// (`final_image_slab.wgsl`).
pub fn slab_bounds(surface: &dyn Surface, size: f64) -> Slab {
    let n = SLAB_LATTICE;
    let (mut h, mut g): (f64, f64) = (0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            let p = DVec2::new(j as f64 + 0.5, i as f64 + 0.5) * (size / n as f64);
            let (height, gradient) = surface.height_gradient(p);
            h = h.max(height.abs());
            g = g.max(gradient.length());
        }
    }
    Slab {
        half_height: h * 1.5 + 1e-6,
        slope: g * 1.5 + 1e-6,
    }
}

/// Side of the square grid a GPU front end samples an analytic surface on for the final image
/// (`FinalImage::render_with` in caustics-gpu), and the lattice the CPU's filtered water normals
/// start from for a surface that is not a grid: the caustics map's resolution (the detail the
/// scene asks the caustics to resolve), at least 256 so that small maps still give the view rays a
/// smooth surface, and at most 4096 (a 64 MiB texture, within every adapter's limits).
pub fn water_grid_resolution(scene: &Scene) -> usize {
    scene
        .caustics
        .width
        .max(scene.caustics.height)
        .clamp(256, 4096) as usize
}

/// The ambient light of the final image for sunlight travelling along `sun`: the daylight sky's
/// irradiance on a horizontal surface, per unit of the sun's ([`Sky::horizontal_irradiance`]).
/// Both twins take it from here (the GPU's as a uniform).
pub fn sky_ambient(sun: DVec3) -> DVec3 {
    Sky::new(sun, TURBIDITY).horizontal_irradiance()
}

/// How the rays of a sample's neighbours, one sample spacing away along each image axis, differ
/// from its own: in origin and in direction (ray differentials, H. Igehy, "Tracing Ray
/// Differentials", SIGGRAPH 99), taken as secants across the sample rather than derivatives, so
/// that at the water they see how much the waves turn the refracted rays over the sample's
/// footprint, however curved the surface is within it. Carried along a sample's first path (its
/// primary ray, that ray's refraction, and the surface's mirror image of either seen from below;
/// glass, the air through Snell's window and the rays they spawn have none), they give the
/// footprint on the floor and the walls that the caustics and albedo are filtered over: the spread
/// of points that many rays of the sample would reach.
#[derive(Clone, Copy, Debug, Default)]
struct Spread {
    o: [DVec3; 2],
    d: [DVec3; 2],
}

impl Spread {
    /// The camera's: rays through image points half a sample spacing `h` (pixels) either side of
    /// `(x, y)` along each axis. GPU twin: `camera_spread` in final_image.wgsl.
    fn of_camera(cam: &Camera, x: f64, y: f64, h: f64) -> Spread {
        let dir = |dx: f64, dy: f64| cam.ray(x + dx, y + dy).1;
        Spread {
            o: [DVec3::ZERO; 2],
            d: [
                dir(0.5 * h, 0.0) - dir(-0.5 * h, 0.0),
                dir(0.0, 0.5 * h) - dir(0.0, -0.5 * h),
            ],
        }
    }

    /// The footprint's axes where the ray `o + t d` meets the plane through its end with normal
    /// `m` (Igehy's transfer: the neighbours' points on that plane, less the ray's own).
    fn on_plane(&self, d: DVec3, t: f64, m: DVec3) -> [DVec2; 2] {
        self.on_plane3(d, t, m).map(DVec3::truncate)
    }

    /// [`on_plane`](Self::on_plane) in three dimensions (a wall's plane).
    fn on_plane3(&self, d: DVec3, t: f64, m: DVec3) -> [DVec3; 2] {
        let cos = m.dot(d);
        std::array::from_fn(|k| {
            let v = self.o[k] + self.d[k] * t;
            if cos.abs() > 1e-9 {
                v - d * (m.dot(v) / cos)
            } else {
                v
            }
        })
    }

    /// Through the water surface met at `p` along `d` after `t`, its normal there `n`: each axis's
    /// neighbours meet the surface half a footprint either side of `p` (on the facet's plane, as
    /// Igehy's transfer has it), where the surface's own normals (`normal_at`) `bend` them: refract
    /// from above, reflect from below (the secant of the bent direction across the footprint).
    /// GPU twin: `bent_axis` in final_image.wgsl.
    fn bent(
        &self,
        normal_at: impl Fn(DVec2) -> DVec3,
        (p, d, t, n): (DVec3, DVec3, f64, DVec3),
        bend: impl Fn(DVec3, DVec3) -> Option<DVec3>,
    ) -> Spread {
        let mut out = Spread::default();
        let cos = n.dot(d);
        for k in 0..2 {
            let v = self.o[k] + self.d[k] * t;
            // A ray along the facet's plane: its neighbours' points off the ray, unprojected.
            let dp = if cos.abs() > 1e-9 {
                v - d * (n.dot(v) / cos)
            } else {
                v
            };
            let side = |sign: f64| {
                let m = normal_at((p + dp * (0.5 * sign)).truncate());
                bend((d + self.d[k] * (0.5 * sign)).normalize(), m)
            };
            out.o[k] = dp;
            if let (Some(a), Some(b)) = (side(-1.0), side(1.0)) {
                out.d[k] = b - a;
            }
        }
        out
    }
}

struct Tracer<'a> {
    scene: &'a Scene,
    surface: Option<&'a dyn Surface>,
    /// The floor's map and its pyramid, read over each sample's footprint on the floor.
    caustics: Option<(&'a CausticsMap, MapPyramid)>,
    eye_space: Option<(&'a EyeSpaceCaustics, EyeCamera)>,
    /// The walls' maps, when the technique lit the pool's walls.
    walls: Option<&'a WallMaps>,
    bvhs: Vec<MeshBvh>,
    /// Bound on |h| of the water, for the slab the surface lies in.
    h_max: f64,
    /// Bound on the water's slope |∇h|, for the march through that slab ([`first_crossing`]).
    slope_max: f64,
    /// The shortest step of that march: a quarter of the slab lattice's spacing.
    min_step: f64,
    sun: DVec3,
    /// Refracted sun direction under flat water and its transmittance.
    sun_water: DVec3,
    t_flat: f64,
    pool: bool,
    /// The daylight sky for this sun ([`crate::sky`]) and the irradiance it gives a horizontal
    /// surface, times the sun's intensity (as the sun's direct light is), before the light's
    /// colour: the ambient light of everything the sun does not reach directly.
    sky: Sky,
    ambient: DVec3,
    /// The water's slope moments for footprint-filtered normals ([`crate::water::slopes`]).
    slopes: Option<SlopePyramid>,
    /// The angle one sample of a pixel covers, for the footprint of a ray on the water.
    spread: f64,
    /// The slope variance the sun's disk adds to the glint.
    sun_variance: f64,
}

/// Render the scene from its camera. `caustics` is the map of the floor (none: the floor is lit as if
/// the water were flat). `progress(rows_done, rows)` reports as rows finish.
pub fn render(
    scene: &Scene,
    surface: Option<&dyn Surface>,
    caustics: Option<&CausticsMap>,
    options: &RenderOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Image {
    render_with(
        scene,
        surface,
        caustics.map(Caustics::Floor),
        options,
        progress,
    )
}

/// [`render`] with the caustics from either source: a floor map or an eye-space image.
pub fn render_with(
    scene: &Scene,
    surface: Option<&dyn Surface>,
    caustics: Option<Caustics>,
    options: &RenderOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Image {
    render_with_walls(scene, surface, caustics, None, options, progress)
}

/// [`render_with`], the pool's walls lit by the sun through their maps (`walls`, from a technique
/// that lights them: the reference) as well as by the ambient light; `None` leaves the walls to
/// the ambient light alone.
pub fn render_with_walls(
    scene: &Scene,
    surface: Option<&dyn Surface>,
    caustics: Option<Caustics>,
    walls: Option<&WallMaps>,
    options: &RenderOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Image {
    let cam = &scene.camera;
    let slab = match (surface, &scene.water) {
        (Some(s), Some(w)) => slab_bounds(s, w.size),
        _ => Slab::default(),
    };
    let ior = scene.water.as_ref().map_or(1.0, |w| w.ior);
    let sun = scene.light.direction;
    let tracer = Tracer {
        scene,
        surface,
        caustics: match caustics {
            Some(Caustics::Floor(m)) => Some((m, m.pyramid())),
            _ => None,
        },
        eye_space: match caustics {
            Some(Caustics::EyeSpace(e)) => Some((e, e.eye(cam))),
            _ => None,
        },
        walls: walls.filter(|_| scene.floor.walls),
        bvhs: scene.objects.iter().map(|o| o.mesh.bvh()).collect(),
        h_max: slab.half_height,
        slope_max: slab.slope,
        min_step: scene.water.as_ref().map_or(0.0, |w| w.size) / (4 * SLAB_LATTICE) as f64,
        sun,
        sun_water: refract(sun, DVec3::Z, 1.0 / ior).unwrap_or(sun),
        t_flat: fresnel_transmittance(-sun.z, 1.0, ior),
        pool: scene.floor.terrain.is_none(),
        sky: Sky::new(sun, TURBIDITY),
        ambient: sky_ambient(sun) * scene.light.intensity,
        slopes: match (surface, &scene.water) {
            (Some(s), Some(w)) if options.filter_water => {
                let (cols, rows) = s.lattice().unwrap_or_else(|| {
                    let n = water_grid_resolution(scene);
                    (n, n)
                });
                Some(SlopePyramid::new(s, cols, rows, w.size, w.edge()))
            }
            _ => None,
        },
        spread: sample_spread(cam.fov_y, cam.height, options.supersampling),
        sun_variance: sun_slope_variance(SUN_RADIUS),
    };
    let under = camera_under_water(scene, surface);
    let n = options.supersampling.max(1) as usize;
    let (w, h) = (cam.width as usize, cam.height as usize);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Vec<u8>> = (0..h)
        .into_par_iter()
        .map(|y| {
            let mut row = Vec::with_capacity(w * 3);
            for x in 0..w {
                let mut c = DVec3::ZERO;
                for sy in 0..n {
                    for sx in 0..n {
                        let (ox, oy) = sample_offset(sx, sy, n);
                        let (sx, sy) = (x as f64 + ox - 0.5, y as f64 + oy - 0.5);
                        let (o, d) = cam.ray(sx, sy);
                        let spread = Spread::of_camera(cam, sx, sy, 1.0 / n as f64);
                        c += tracer.trace_from(o, d, 0, under, spread);
                    }
                }
                let c = c / (n * n) as f64 * options.exposure;
                row.extend(tone_map(c, options.tone_map));
            }
            let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(d, h);
            row
        })
        .collect();
    Image {
        width: cam.width,
        height: cam.height,
        rgb: rows.concat(),
    }
}

/// Where sample `(sx, sy)` of a pixel's `n` x `n` lies in it, from its corner (`[0, 1)²`): on a
/// rotated grid, no two samples in one row or one column of the pixel's `n²` x `n²` sub-grid
/// (n-rooks; for 2 x 2 the rotated-grid pattern of RGSS), so that an edge or a caustic's line
/// near the image's axes is resolved in `n²` steps instead of `n`, for the same rays: measured on
/// the shore at 960 x 540 against 8 x 8 samples, mean FLIP 0.0108 against 0.0125 on the square
/// grid (docs/look.md). For odd `n` one sample sits at the pixel's centre (for `n = 1` the only
/// one). GPU twin: `sample_offset` in final_image.wgsl.
pub fn sample_offset(sx: usize, sy: usize, n: usize) -> (f64, f64) {
    let n = n as f64;
    let (sx, sy) = (sx as f64, sy as f64);
    (
        (sx + (sy + 0.5) / n) / n,
        (sy + (n - 1.0 - sx + 0.5) / n) / n,
    )
}

/// Whether the scene's camera is under the water: inside the water's square and below the surface's
/// height there (the rest level without a surface). Its primary rays then start in the water.
pub fn camera_under_water(scene: &Scene, surface: Option<&dyn Surface>) -> bool {
    let Some(water) = &scene.water else {
        return false;
    };
    let p = scene.camera.position;
    let h = surface.map_or(0.0, |s| s.height(p.truncate()));
    inside(p.truncate(), water.size) && p.z < water.depth + h
}

/// A ray meeting the water surface from below, split by the Fresnel equations from the dense side.
#[derive(Clone, Copy, Debug)]
pub struct FromBelow {
    /// The mirrored ray, back into the water.
    pub reflected: DVec3,
    /// The ray refracted out into the air; `None` beyond Snell's window (total internal reflection).
    pub refracted: Option<DVec3>,
    /// The fraction of the flux that leaves the water (0 beyond the window); the reflected ray
    /// carries the rest, `1 - transmittance`.
    pub transmittance: f64,
}

/// Split the unit ray `d` meeting the surface of unit upward normal `n` from the water's side
/// (`d · n > 0`), the water of index `ior` under air. Snell's window is where `sin θ < 1 / ior`.
pub fn from_below(d: DVec3, n: DVec3, ior: f64) -> FromBelow {
    let refracted = refract(d, -n, ior);
    FromBelow {
        reflected: reflect(d, n),
        refracted,
        transmittance: if refracted.is_some() {
            fresnel_transmittance(d.dot(n), ior, 1.0)
        } else {
            0.0
        },
    }
}

impl Tracer<'_> {
    fn sun_radiance(&self) -> DVec3 {
        self.scene.light.color * self.scene.light.intensity
    }

    /// The sky's radiance along `d` with the sun's disk, in the image's unit: a surface of albedo
    /// `ρ` under irradiance `E` shows `ρ E` (the `1 / π` of a Lambertian reflector is left to the
    /// exposure), so a radiance `L` shows as `π L`.
    fn sky(&self, d: DVec3) -> DVec3 {
        (self.sky.radiance(d) + DVec3::splat(self.sky.sun_disk(d)))
            * (std::f64::consts::PI * self.sun_radiance())
    }

    /// The sky alone, without the sun's disk: what rough water reflects besides the sun's glint.
    fn sky_without_sun(&self, d: DVec3) -> DVec3 {
        self.sky.radiance(d) * (std::f64::consts::PI * self.sun_radiance())
    }

    /// The water's slope moments over the footprint of the ray along `d` meeting it at `p`: the
    /// cone of one sample from the eye, as wide as the distance from the camera (a bent path's
    /// own length would be a little longer) times the sample's angle.
    fn water_slopes(
        &self,
        pyramid: &SlopePyramid,
        s: &dyn Surface,
        p: DVec3,
        d: DVec3,
    ) -> SlopeMoments {
        let distance = (p - self.scene.camera.position).length();
        let footprint = Footprint::of_ray(d, distance, self.spread);
        pyramid.filtered(s, p.truncate(), &footprint)
    }

    /// Water met at `p` along `d` shaded with the normals filtered by the sample's footprint
    /// ([`crate::water::slopes`]): the facets of the footprint the eye sees each reflect the sky
    /// by their Fresnel reflectance, the sun's reflection is the glint lobe of their roughness,
    /// and the rest of the light refracts along their mean normal by their mean transmittance
    /// ([`visible_facets`]). Returns the reflected light, the transmittance and the normal to
    /// refract at.
    fn rough_water(
        &self,
        pyramid: &SlopePyramid,
        s: &dyn Surface,
        p: DVec3,
        d: DVec3,
        ior: f64,
    ) -> (DVec3, f64, DVec3) {
        let m = self.water_slopes(pyramid, s, p, d);
        let (facets, count) = visible_facets(d, &m);
        let mut reflected = self.glint(d, &m, ior);
        let (mut t_view, mut n) = (0.0, DVec3::ZERO);
        for &(facet, w) in &facets[..count] {
            let t = fresnel_transmittance(-d.dot(facet), 1.0, ior);
            reflected += self.sky_without_sun(reflect(d, facet)) * ((1.0 - t) * w);
            t_view += t * w;
            n += facet * w;
        }
        (reflected, t_view, n.normalize())
    }

    /// The sun's reflection off water of slope moments `m` toward the eye looking along `d`: the
    /// glint lobe of [`glint`] with the Fresnel reflectance of its mirroring facet, in the image's
    /// unit (`π L`, as [`sky`](Self::sky)).
    fn glint(&self, d: DVec3, m: &SlopeMoments, ior: f64) -> DVec3 {
        let (g, h) = glint(-d, -self.sun, m, self.sun_variance);
        if g <= 0.0 {
            return DVec3::ZERO;
        }
        let f = 1.0 - fresnel_transmittance(-d.dot(h), 1.0, ior);
        self.sun_radiance() * (std::f64::consts::PI * f * g)
    }

    fn nearest_object(&self, o: DVec3, d: DVec3, t_max: f64) -> Option<(f64, DVec3, usize)> {
        let mut best: Option<(f64, DVec3, usize)> = None;
        for (k, (obj, bvh)) in self.scene.objects.iter().zip(&self.bvhs).enumerate() {
            let limit = best.map_or(t_max, |b| b.0);
            if let Some((t, n)) = bvh.intersect(&obj.mesh, o, d, limit) {
                best = Some((t, n, k));
            }
        }
        best
    }

    fn occluded(&self, o: DVec3, d: DVec3, t_max: f64) -> bool {
        self.scene.objects.iter().zip(&self.bvhs).any(|(obj, bvh)| {
            matches!(obj.material, Material::Diffuse { .. })
                && bvh.intersect(&obj.mesh, o, d, t_max).is_some()
        })
    }

    /// Any object, glass included, between `o` and the sun.
    fn occluded_by_any(&self, o: DVec3, d: DVec3, t_max: f64) -> bool {
        self.scene
            .objects
            .iter()
            .zip(&self.bvhs)
            .any(|(obj, bvh)| bvh.intersect(&obj.mesh, o, d, t_max).is_some())
    }

    fn trace(&self, o: DVec3, d: DVec3, depth: u32, spread: Spread) -> DVec3 {
        if depth > 6 {
            return DVec3::ZERO;
        }
        let scene = self.scene;
        let Some(water) = &scene.water else {
            return self.trace_air(o, d, depth, spread);
        };
        let size = water.size;
        let level = water.depth;
        // Water surface hit, searched in the slab |z - level| <= h_max.
        let water_hit = self.surface.and_then(|s| self.hit_water(s, o, d, level));
        let obj = self.nearest_object(o, d, water_hit.map_or(f64::INFINITY, |w| w.0));
        if let Some((t, n, k)) = obj {
            return self.shade_object(o + d * t, n, d, k, depth, false);
        }
        let Some((t, p)) = water_hit else {
            // A pool is sunk into a deck around it; beyond the terrain's square the world goes on.
            return self.shade_above(o, d);
        };
        if self.pool && !inside(p.truncate(), size) {
            return self.shade_above(o, d);
        }
        let s = self.surface.expect("a water hit implies a surface");
        let (reflected, t_view, n) = match &self.slopes {
            Some(pyramid) => self.rough_water(pyramid, s, p, d, water.ior),
            None => {
                let n = height_field_normal(s.gradient(p.truncate()));
                let t_view = fresnel_transmittance(-d.dot(n), 1.0, water.ior);
                (self.sky(reflect(d, n)) * (1.0 - t_view), t_view, n)
            }
        };
        let Some(r) = refract(d, n, 1.0 / water.ior) else {
            return reflected;
        };
        debug_assert!(t >= 0.0);
        let spread = spread.bent(
            |q| height_field_normal(s.gradient(q)),
            (p, d, t, n),
            |d, m| refract(d, m, 1.0 / water.ior),
        );
        reflected + self.trace_under(p, r, depth, spread) * t_view
    }

    /// Radiance arriving along `d` at point `o` under the water.
    fn trace_under(&self, o: DVec3, d: DVec3, depth: u32, spread: Spread) -> DVec3 {
        // The same bound as `trace`: a ray reflected inside a glass object under water would
        // otherwise recurse until the stack overflows.
        if depth > 6 {
            return DVec3::ZERO;
        }
        let scene = self.scene;
        let water = scene.water.as_ref().expect("under water");
        let size = water.size;
        let (t_floor, floor_p) = self.hit_floor(o, d);
        // A ray going up ends at the surface seen from below instead; the branches below read
        // `t_floor` and `floor_p` as the ray's end, wherever it is.
        let ceiling = self.hit_water_from_below(o, d, water.depth);
        let (t_floor, floor_p) = ceiling.unwrap_or((t_floor, floor_p));
        let obj = self.nearest_object(o, d, t_floor);
        let (dist, colour) = if let Some((t, n, k)) = obj {
            (t, self.shade_object(o + d * t, n, d, k, depth, true))
        } else if self.pool && !inside(floor_p.truncate(), size) {
            // The ray meets a pool wall first: tiles lit by the ambient light, and by the sun
            // through the wall's map where the technique lit the walls.
            let t = wall_distance(o, d, size);
            let p = o + d * t;
            // The wall's tiles as the floor's, along the wall and up it, filtered over the
            // sample's footprint on the wall's plane.
            let [fa, fb] = spread.on_plane3(d, t, wall_at(p, size).normal());
            let extent = DVec2::new(
                (fa.x + fa.y).abs() + (fb.x + fb.y).abs(),
                fa.z.abs() + fb.z.abs(),
            );
            let a = scene
                .floor
                .albedo
                .filtered(DVec2::new(p.x + p.y, p.z), size, extent);
            (
                t,
                a * (self.ambient * self.scene.light.color + self.wall_light(p, size)),
            )
        } else if ceiling.is_some() {
            (
                t_floor,
                self.leave_water(floor_p, d, depth, t_floor, spread),
            )
        } else {
            let (_, g) = scene.floor.height_gradient(floor_p.truncate(), scene.size);
            let footprint = spread.on_plane(d, t_floor, height_field_normal(g));
            (t_floor, self.shade_floor(floor_p, footprint))
        };
        colour * (-water.absorption * dist).exp()
    }

    /// The floor at `p`, its caustics and albedo filtered over the sample's `footprint` there.
    fn shade_floor(&self, p: DVec3, footprint: [DVec2; 2]) -> DVec3 {
        let scene = self.scene;
        let water = scene.water.as_ref().expect("under water");
        let size = water.size;
        let albedo = scene
            .floor
            .albedo
            .filtered(p.truncate(), size, extent(footprint));
        let e_h = scene.light.intensity * -self.sun.z;
        let flat = || (-water.absorption * ((water.depth - p.z) / -self.sun_water.z)).exp();
        let wrap = water.wrap && scene.floor.terrain.is_none();
        let relative = match (&self.caustics, &self.eye_space) {
            // Beyond a map that does not tile (a terrain's, clamped at its edges) nothing says
            // where the light focuses: the floor there gets the flat water's light, the mean of
            // any pattern (stretching the map's edge texels to the horizon drew streaks); a
            // footprint across the map's edge reads the flat light for its taps beyond it.
            (Some((_, pyramid)), _) => {
                let f = flat().as_vec3().to_array();
                let c = pyramid.filtered(p.truncate(), footprint, wrap, Some(f));
                DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)
            }
            (None, Some((image, eye))) => image.sample(eye, p).unwrap_or_else(flat),
            (None, None) => flat(),
        };
        let shadow = if self.occluded(p + DVec3::Z * 1e-4, -self.sun_water, f64::INFINITY) {
            0.0
        } else {
            1.0
        };
        let direct = relative * (e_h * self.t_flat * shadow);
        let ambient = self.ambient * (-water.absorption * water.depth).exp();
        albedo * (direct + ambient) * scene.light.color
    }

    /// The sun's light on wall point `p` through its wall's map, or an eye-space technique's
    /// image where the wall point projects (cascaded lights the walls it sees); none without
    /// either; shadowed by the objects as the floor is.
    fn wall_light(&self, p: DVec3, size: f64) -> DVec3 {
        let wall = wall_at(p, size);
        let c = match (self.walls, &self.eye_space) {
            (Some(maps), _) => maps.get(wall).sample(wall.along(p), p.z),
            (None, Some((image, eye))) => match image.sample(eye, p) {
                Some(v) => [v.x as f32, v.y as f32, v.z as f32],
                None => return DVec3::ZERO,
            },
            (None, None) => return DVec3::ZERO,
        };
        if self.occluded(p + wall.normal() * 1e-4, -self.sun_water, f64::INFINITY) {
            return DVec3::ZERO;
        }
        let e_h = self.scene.light.intensity * -self.sun.z;
        DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64)
            * (e_h * self.t_flat)
            * self.scene.light.color
    }

    fn shade_object(
        &self,
        p: DVec3,
        n: DVec3,
        d: DVec3,
        k: usize,
        depth: u32,
        under: bool,
    ) -> DVec3 {
        let obj = &self.scene.objects[k];
        // Closed meshes with outward normals: the ray enters where it meets the outside.
        let entering = n.dot(d) < 0.0;
        let n = if entering { n } else { -n };
        match &obj.material {
            Material::Diffuse { color } => {
                let (sun_dir, t) = if under {
                    (self.sun_water, self.t_flat)
                } else {
                    (self.sun, 1.0)
                };
                let lambert = n.dot(-sun_dir).max(0.0);
                let lit = if lambert > 0.0 && !self.occluded(p + n * 1e-4, -sun_dir, f64::INFINITY)
                {
                    1.0
                } else {
                    0.0
                };
                let water_path = match (&self.scene.water, under) {
                    (Some(w), true) => {
                        (-w.absorption * ((w.depth - p.z).max(0.0) / -sun_dir.z)).exp()
                    }
                    _ => DVec3::ONE,
                };
                *color
                    * (water_path * (self.scene.light.intensity * lambert * lit * t) + self.ambient)
                    * self.scene.light.color
            }
            Material::Glass { ior, tint } => {
                let outside_ior = if under {
                    self.scene.water.as_ref().map_or(1.0, |w| w.ior)
                } else {
                    1.0
                };
                let (n1, n2) = if entering {
                    (outside_ior, *ior)
                } else {
                    (*ior, outside_ior)
                };
                let cos_i = -d.dot(n);
                let t = fresnel_transmittance(cos_i, n1, n2);
                let none = Spread::default();
                let refl = self.trace_from(p + n * 1e-5, reflect(d, n), depth + 1, under, none);
                let refr = match refract(d, n, n1 / n2) {
                    Some(r) => self.trace_from(p - n * 1e-5, r, depth + 1, under, none) * *tint,
                    None => DVec3::ZERO,
                };
                refl * (1.0 - t) + refr * t
            }
        }
    }

    fn trace_from(&self, o: DVec3, d: DVec3, depth: u32, under: bool, spread: Spread) -> DVec3 {
        if under {
            self.trace_under(o, d, depth, spread)
        } else {
            self.trace(o, d, depth, spread)
        }
    }

    /// No water in the scene: objects over the floor plane in open air.
    fn trace_air(&self, o: DVec3, d: DVec3, depth: u32, spread: Spread) -> DVec3 {
        let t_floor = if d.z < 0.0 { -o.z / d.z } else { f64::INFINITY };
        if let Some((t, n, k)) = self.nearest_object(o, d, t_floor) {
            return self.shade_object(o + d * t, n, d, k, depth, false);
        }
        if t_floor.is_finite() {
            let p = o + d * t_floor;
            let footprint = spread.on_plane(d, t_floor, DVec3::Z);
            let albedo =
                self.scene
                    .floor
                    .albedo
                    .filtered(p.truncate(), self.scene.size, extent(footprint));
            let from = p + DVec3::Z * 1e-5;
            // With a caustics map of the light through the glass (relative to the unobstructed
            // sun), every object shadows the direct sun and the map brings back what the glass
            // transmitted; without one, glass lets the sun through unchanged.
            let (lit, caustic) = match &self.caustics {
                Some((_, pyramid)) => {
                    let c = pyramid.filtered(p.truncate(), footprint, false, None);
                    let blocked = self.occluded_by_any(from, -self.sun, f64::INFINITY);
                    (
                        if blocked { 0.0 } else { 1.0 },
                        DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64),
                    )
                }
                None => {
                    let blocked = self.occluded(from, -self.sun, f64::INFINITY);
                    (if blocked { 0.0 } else { 1.0 }, DVec3::ZERO)
                }
            };
            let e = (DVec3::splat(lit) + caustic) * (self.scene.light.intensity * -self.sun.z)
                + self.ambient;
            return albedo * e * self.scene.light.color;
        }
        self.sky(d)
    }

    /// Above the water, outside the pool: the deck, or the sky.
    fn shade_above(&self, o: DVec3, d: DVec3) -> DVec3 {
        let water = self.scene.water.as_ref().expect("water");
        if self.pool && d.z < 0.0 {
            let deck = water.depth + 0.1 * water.size.min(1.0) + self.h_max;
            let t = (deck - o.z) / d.z;
            if t > 0.0 {
                let p = o + d * t;
                // A sample's footprint on the deck, stretched by the grazing angle.
                let footprint = (p - o).length() * self.spread / d.z.abs().max(0.05);
                let albedo = self
                    .scene
                    .floor
                    .deck
                    .albedo(p.truncate(), water.size, footprint);
                return albedo
                    * (DVec3::splat(self.scene.light.intensity * -self.sun.z) + self.ambient)
                    * self.scene.light.color;
            }
        }
        if !self.pool && d.z < 0.0 {
            // Beyond the surface's slab the open sea: the flat-water Fresnel reflection of the sky.
            let r = fresnel_transmittance(-d.z, 1.0, water.ior);
            return self.sky(reflect(d, DVec3::Z)) * (1.0 - r);
        }
        self.sky(d)
    }

    /// How a ray along `d` marches through the water's slab ([`first_crossing`]): its height
    /// above the surface changes by at most `|d_z| + slope · |d_xy|` per unit of distance.
    fn march(&self, d: DVec3) -> March {
        March {
            rate: d.z.abs() + self.slope_max * d.truncate().length(),
            min_step: self.min_step,
        }
    }

    /// The first crossing of the ray with `z = level + h(x, y)`.
    fn hit_water(&self, s: &dyn Surface, o: DVec3, d: DVec3, level: f64) -> Option<(f64, DVec3)> {
        let top = level + self.h_max;
        let bottom = level - self.h_max;
        if o.z < bottom || d.z >= 0.0 {
            return None; // `trace` follows rays in the air, which meet the surface from above
        }
        let t0 = ((top - o.z) / d.z).max(0.0);
        let t1 = (bottom - o.z) / d.z;
        let f = |t: f64| {
            let p = o + d * t;
            p.z - level - s.height(p.truncate())
        };
        let t = first_crossing(f, t0, t1, self.march(d));
        Some((t, o + d * t))
    }

    /// The first crossing of a rising underwater ray with `z = level + h(x, y)` (the rest plane
    /// without a surface); `None` for a ray going down or level, or starting over the surface's
    /// slab, which cannot meet it from below.
    fn hit_water_from_below(&self, o: DVec3, d: DVec3, level: f64) -> Option<(f64, DVec3)> {
        if d.z <= 0.0 {
            return None;
        }
        let Some(s) = self.surface else {
            let t = ((level - o.z) / d.z).max(0.0);
            return Some((t, o + d * t));
        };
        let (bottom, top) = (level - self.h_max, level + self.h_max);
        if o.z > top {
            return None;
        }
        let t0 = ((bottom - o.z) / d.z).max(0.0);
        let t1 = (top - o.z) / d.z;
        // Depth of the ray below the surface at distance t.
        let f = |t: f64| {
            let p = o + d * t;
            level + s.height(p.truncate()) - p.z
        };
        let t = first_crossing(f, t0, t1, self.march(d));
        Some((t, o + d * t))
    }

    /// Radiance arriving along `d` at point `p` of the surface, seen from below: the air's through
    /// Snell's window, weighted by the Fresnel transmittance from the dense side, plus the water's
    /// mirrored in the surface (all of it beyond the window).
    /// The ray met the surface at `p` after `t` along `d`; `spread` is its own, which the reflected
    /// ray carries on (the mirror image beyond Snell's window is filtered as a direct view is).
    fn leave_water(&self, p: DVec3, d: DVec3, depth: u32, t: f64, spread: Spread) -> DVec3 {
        let water = self.scene.water.as_ref().expect("under water");
        let n = match self.surface {
            Some(s) => match &self.slopes {
                Some(pyramid) => height_field_normal(self.water_slopes(pyramid, s, p, d).mean),
                None => height_field_normal(s.gradient(p.truncate())),
            },
            None => DVec3::Z,
        };
        let split = from_below(d, n, water.ior);
        let mirrored = spread.bent(
            |q| {
                self.surface
                    .map_or(DVec3::Z, |s| height_field_normal(s.gradient(q)))
            },
            (p, d, t, n),
            |d, m| Some(reflect(d, m)),
        );
        let mut c = self.trace_under(p - n * 1e-5, split.reflected, depth + 1, mirrored)
            * (1.0 - split.transmittance);
        if let Some(r) = split.refracted {
            let none = Spread::default();
            c += self.trace(p + n * 1e-5, r, depth + 1, none) * split.transmittance;
        }
        c
    }

    /// Distance to and point on the floor or terrain along an underwater ray.
    fn hit_floor(&self, o: DVec3, d: DVec3) -> (f64, DVec3) {
        if d.z >= 0.0 {
            return (f64::INFINITY, o);
        }
        match &self.scene.floor.terrain {
            None => {
                let t = -o.z / d.z;
                (t, o + d * t)
            }
            Some(_) => {
                let size = self.scene.size;
                let gap = |t: f64| {
                    let p = o + d * t;
                    p.z - self.scene.floor.height_gradient(p.truncate(), size).0
                };
                let t_end = -o.z / d.z;
                let steps = 64;
                let mut a = 0.0;
                for k in 1..=steps {
                    let b = t_end * k as f64 / steps as f64;
                    if gap(b) <= 0.0 {
                        let (mut lo, mut hi) = (a, b);
                        for _ in 0..30 {
                            let m = 0.5 * (lo + hi);
                            if gap(m) > 0.0 {
                                lo = m;
                            } else {
                                hi = m;
                            }
                        }
                        let t = 0.5 * (lo + hi);
                        return (t, o + d * t);
                    }
                    a = b;
                }
                (t_end, o + d * t_end)
            }
        }
    }
}

/// The widths along x and y of the box around a footprint spanned by `axes`.
fn extent(axes: [DVec2; 2]) -> DVec2 {
    axes[0].abs() + axes[1].abs()
}

fn inside(p: DVec2, size: f64) -> bool {
    p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size
}

/// A ray's march through the water's slab ([`first_crossing`]).
#[derive(Clone, Copy, Debug)]
struct March {
    /// A bound on how fast the ray's height above the surface changes per unit distance.
    rate: f64,
    /// The shortest step.
    min_step: f64,
}

/// Most steps of [`first_crossing`]'s march: no step is shorter than 1/`MARCH_STEPS` of the slab's
/// interval.
pub const MARCH_STEPS: usize = 512;

/// No step of [`first_crossing`]'s march is longer than 1/`EVEN_STEPS` of the slab's interval (or
/// its shortest step), so that a slope bound estimated too low (waves two
/// lattice spacings long, seen only at their crests and troughs) cannot send it across the slab in
/// one step.
pub const EVEN_STEPS: usize = 24;

/// The first `t` in `[t0, t1]` where `f` (a ray's height above the water surface, positive on the
/// side it starts) reaches 0. Each step is the height over its bound rate of change,
/// `f / march.rate`, which cannot pass a crossing (sphere tracing a height field of bounded
/// slope): a grazing ray meets the first crest that rises into it, not one it would have passed
/// through between evenly spaced steps (24 even steps over a far ray's slab are a metre apart on
/// the shore, where the waves are a few decimetres long: they see the far water through its
/// nearer crests). Steps are at least `march.min_step` and 1/[`MARCH_STEPS`] of the interval, and
/// at most 1/[`EVEN_STEPS`] of it or `min_step`, whichever is longer (a slab thinner than a few
/// shortest steps, as flat water's, is crossed in one: steps of 1/24 of its micrometres would not
/// move an f32 distance of metres on the GPU); then 30 bisections of the step that crossed, or of
/// what is left of the interval when the march ends without a crossing (the slab's far side lies
/// beyond the surface: only rounding, or the steps spent, leave it uncrossed). Both crossings,
/// from above and from below, use it; the GPU twin is `first_crossing` in final_image.wgsl.
fn first_crossing(f: impl Fn(f64) -> f64, t0: f64, t1: f64, march: March) -> f64 {
    let shortest = march.min_step.max((t1 - t0) / MARCH_STEPS as f64);
    let longest = ((t1 - t0) / EVEN_STEPS as f64).max(march.min_step);
    let mut a = t0;
    let mut gap = f(a);
    if gap <= 0.0 {
        return t0;
    }
    // The slab's far side lies beyond the surface, so a crossing lies in [a, t1] even when the
    // march ends without one (rounding at the far side, or the steps spent): bisect the rest.
    let mut hi = t1;
    // Each step is at least 1/MARCH_STEPS of the interval; two more for rounding, as the GPU's.
    for _ in 0..MARCH_STEPS + 2 {
        if a >= t1 {
            break;
        }
        let b = (a + (gap / march.rate).max(shortest).min(longest)).min(t1);
        let next = f(b);
        if next <= 0.0 {
            hi = b;
            break;
        }
        a = b;
        gap = next;
    }
    let mut lo = a;
    for _ in 0..30 {
        let m = 0.5 * (lo + hi);
        if f(m) > 0.0 {
            lo = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo + hi)
}

/// Distance along the ray to the wall of the pool square it leaves through.
fn wall_distance(o: DVec3, d: DVec3, size: f64) -> f64 {
    let mut t = f64::INFINITY;
    for (oc, dc) in [(o.x, d.x), (o.y, d.y)] {
        if dc > 0.0 {
            t = t.min((size - oc) / dc);
        } else if dc < 0.0 {
            t = t.min(-oc / dc);
        }
    }
    t.max(0.0)
}

/// The wall of the pool square nearest to `p` (the one a view ray leaving the square met).
fn wall_at(p: DVec3, size: f64) -> Wall {
    let d = [p.x, size - p.x, p.y, size - p.y];
    let k = (1..4).fold(0, |k, i| if d[i] < d[k] { i } else { k });
    Wall::ALL[k]
}

/// Tone map (the final image's curve, [`tone_map`]) and sRGB-encode linear radiance.
pub fn to_rgb8(linear: &[[f32; 3]], exposure: f64, curve: ToneMap) -> Vec<u8> {
    linear
        .iter()
        .flat_map(|c| {
            let c = glam::DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) * exposure;
            tone_map(c, curve)
        })
        .collect()
}

/// Tone map linear radiance ([`to_rgb8`]) and write it as an sRGB PNG.
pub fn write_png(
    path: &std::path::Path,
    width: u32,
    height: u32,
    linear: &[[f32; 3]],
    exposure: f64,
    curve: crate::render::ToneMap,
) -> crate::Result<()> {
    image::save_buffer(
        path,
        &to_rgb8(linear, exposure, curve),
        width,
        height,
        image::ExtendedColorType::Rgb8,
    )
    .map_err(|e| crate::Error::BadFile {
        path: path.to_path_buf(),
        problem: e.to_string(),
    })
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{ReferenceInput, ReferenceOptions, reference};
    use crate::techniques::cascaded::{CascadedParams, CascadedSetup, eye_pass};

    /// A pixel's samples are n-rooks on its n² x n² sub-grid, each at a sub-cell's centre: their
    /// coordinates along each axis are exactly the n² sub-cells' centres, so they average to the
    /// pixel's centre.
    #[test]
    fn samples_are_n_rooks_about_the_pixels_centre() {
        assert_eq!(sample_offset(0, 0, 1), (0.5, 0.5));
        for n in 2..=8 {
            let cells = (n * n) as f64;
            let mut xs = Vec::new();
            let mut ys = Vec::new();
            for sy in 0..n {
                for sx in 0..n {
                    let (x, y) = sample_offset(sx, sy, n);
                    xs.push((x * cells - 0.5).round() as i64);
                    ys.push((y * cells - 0.5).round() as i64);
                    for v in [x, y] {
                        let k = v * cells - 0.5;
                        assert!((k - k.round()).abs() < 1e-9, "{n}: {v}");
                    }
                }
            }
            xs.sort();
            ys.sort();
            let all: Vec<i64> = (0..(n * n) as i64).collect();
            assert_eq!((xs, ys), (all.clone(), all), "{n}");
        }
    }

    /// A ray grazing the water (1 in 100) meets the first crest that rises into it: the march's
    /// steps, the ray's height over the surface's bound on its rate of change, cannot pass a
    /// crossing. The ray dips 5 mm into a 1 m sine wave's crest 5 m along (a 10 cm chord) after
    /// clearing the crest before it by 5 mm; with a shortest step of 0.1 mm, only the slope
    /// bound keeps the steps short near the crest, and the crossing found is the fine scan's
    /// first root. Evenly spaced steps over the slab (24 steps 1.3 m apart here) go through that
    /// crest and two more, to meet the water at x = 8.07 m (measured).
    #[test]
    fn a_grazing_ray_meets_the_first_crest_it_dips_into() {
        use crate::water::waves::{Wave, Waves};
        let size = 32.0;
        let surface = Waves::new(
            &[Wave {
                amplitude: 0.1,
                wavelength: 1.0,
                direction: [1.0, 0.0],
                phase: 0.3,
                period: None,
            }],
            size,
            0.0,
        );
        let slab = slab_bounds(&surface, size);
        // The crest nearest x = 5 and the ray that dips 5 mm under it, descending 1 in 100.
        let crest = (0..100_000)
            .map(|k| 4.5 + k as f64 * 1e-5)
            .max_by(|a, b| {
                let h = |x: f64| surface.height(DVec2::new(x, 3.0));
                h(*a).total_cmp(&h(*b))
            })
            .unwrap();
        let d = DVec3::new(1.0, 0.0, -0.01).normalize();
        let z_crest = surface.height(DVec2::new(crest, 3.0)) - 0.005;
        let o = DVec3::new(0.0, 3.0, z_crest + 0.01 * crest);
        let gap = |t: f64| {
            let p = o + d * t;
            p.z - surface.height(p.truncate())
        };
        let t0 = (slab.half_height - o.z) / d.z;
        let t1 = (-slab.half_height - o.z) / d.z;
        let march = March {
            rate: d.z.abs() + slab.slope * d.truncate().length(),
            // Short, so that the slope bound has to keep the steps from passing the crest.
            min_step: 1e-4,
        };
        let found = first_crossing(gap, t0.max(0.0), t1, march);
        let steps = 4_000_000;
        let scan = (0..=steps)
            .map(|k| t0.max(0.0) + (t1 - t0.max(0.0)) * k as f64 / steps as f64)
            .find(|&t| gap(t) <= 0.0)
            .expect("the scan's crossing");
        let x = (o + d * found).x;
        eprintln!(
            "crossing at x = {x:.6} (crest {crest:.6}), t {found:.9} against the scan's {scan:.9}"
        );
        assert!(
            (x - crest).abs() < 0.05,
            "met at x = {x}, not the crest at {crest}"
        );
        // The scan's spacing is 7.6e-6 along the ray: the two agree within it.
        assert!((found - scan).abs() < 1e-5, "{found} against {scan}");
    }

    /// The march's two ends: a slab as thin as flat water's (2 µm here, with a 4 mm shortest
    /// step) is crossed in one step, so the whole search is the start, that step and the
    /// bisections (32 heights; steps of 1/24 of the slab, which do not move an f32 distance of
    /// metres on the GPU, took 44); and a march that ends without a crossing, as rounding
    /// can leave the far side, returns that far side instead of a miss.
    #[test]
    fn the_march_crosses_a_thin_slab_in_one_step_and_never_misses() {
        let march = March {
            rate: 1.0,
            min_step: 0.004,
        };
        let calls = std::cell::Cell::new(0);
        let flat = |t: f64| {
            calls.set(calls.get() + 1);
            5.000_001 - t
        };
        let t = first_crossing(flat, 5.0, 5.000_002, march);
        assert!((t - 5.000_001).abs() < 1e-12, "{t}");
        assert_eq!(calls.get(), 32, "heights read crossing a thin slab");
        let t = first_crossing(|_| 1e-9, 2.0, 3.0, march);
        assert!((t - 3.0).abs() < 1e-8, "an uncrossed march ends at {t}");
    }

    /// Beyond a terrain's caustics map (which does not tile) the floor gets the flat water's
    /// light, not the map's edge stretched to the horizon: with a map that is dark everywhere,
    /// the shore's far rows (whose floor lies beyond the 32 m square) render as without a map,
    /// while the near rows, inside the map, are darker.
    #[test]
    fn beyond_a_terrain_map_the_floor_is_lit_as_under_flat_water() {
        let mut scene = Scene::builtin("shore").unwrap();
        scene.camera.width = 160;
        scene.camera.height = 90;
        let water = scene.water.as_ref().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let dark = CausticsMap::new(32, 32, water.size);
        let options = RenderOptions {
            supersampling: 1,
            ..Default::default()
        };
        let s = Some(surface.as_ref());
        let none = |_: usize, _: usize| {};
        let flat = render(&scene, s, None, &options, &none);
        let mapped = render(&scene, s, Some(&dark), &options, &none);
        fn row(img: &Image, y: usize) -> &[u8] {
            &img.rgb[y * 160 * 3..(y + 1) * 160 * 3]
        }
        // Rows 26-28: the water just below the horizon (row 25 at 90 rows), far enough that every
        // refracted view ray there meets the floor beyond the map (row 29 already has a few
        // inside it).
        for y in 26..29 {
            assert_eq!(row(&flat, y), row(&mapped, y), "row {y}");
        }
        let near = |img: &Image| row(img, 80).iter().map(|&v| v as u64).sum::<u64>();
        assert!(
            near(&mapped) < near(&flat),
            "the dark map darkens the near floor"
        );
    }

    /// The reference's walls' maps light the pool's walls the camera sees under a low sun, and
    /// only where the scene's walls are on.
    #[test]
    fn walls_maps_light_the_walls() {
        let mut scene = Scene::builtin("pool").unwrap();
        scene.camera.width = 160;
        scene.camera.height = 90;
        scene.caustics.width = 64;
        scene.caustics.height = 64;
        scene.light.direction = DVec3::new(0.8, 0.6, -0.6).normalize();
        let water = scene.water.as_ref().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let input = ReferenceInput::from_scene(&scene, surface.as_ref()).unwrap();
        let options = ReferenceOptions {
            cells_per_texel: 2,
            ..Default::default()
        };
        let out = crate::reference::reference_with_walls(&input, &options, &|_, _| {}).unwrap();
        let walls = out.walls.as_ref().unwrap();
        let caustics = Some(Caustics::Floor(&out.floor));
        let options = RenderOptions {
            supersampling: 1,
            ..Default::default()
        };
        let s = Some(surface.as_ref());
        let none = |_: usize, _: usize| {};
        let unlit = render_with(&scene, s, caustics, &options, &none);
        let lit = render_with_walls(&scene, s, caustics, Some(walls), &options, &none);
        let (mut brighter, mut darker, mut sum) = (0, 0, 0.0);
        for (a, b) in unlit.rgb.iter().zip(&lit.rgb) {
            brighter += (b > a) as usize;
            darker += (b < a) as usize;
            sum += a.abs_diff(*b) as f64;
        }
        let mean = sum / lit.rgb.len() as f64;
        eprintln!(
            "walls' maps: mean change {mean:.2} steps, {brighter} channels brighter, {darker} darker"
        );
        // Measured 1.90 steps, every changed channel brighter: light is only added.
        assert!(mean > 0.5, "{mean}");
        assert_eq!(darker, 0);
        scene.floor.walls = false;
        let off = render_with_walls(&scene, s, caustics, Some(walls), &options, &none);
        assert_eq!(
            off.rgb,
            render_with(&scene, s, caustics, &options, &none).rgb
        );
    }

    /// All the light is the sun's: its direct light, the sky and the sky's ambient light scale with
    /// its intensity together, so twice the intensity at half the exposure is the same picture
    /// (the pool with its walls in view, the objects, the shore's terrain and sky). Measured: the
    /// same bytes.
    #[test]
    fn every_light_scales_with_the_suns_intensity() {
        for name in ["pool", "objects", "shore"] {
            let mut scene = Scene::builtin(name).unwrap();
            scene.camera.width = 96;
            scene.camera.height = 54;
            let water = scene.water.clone().unwrap();
            let surface = water.surface_at(scene.time).unwrap();
            let options = RenderOptions {
                supersampling: 1,
                ..Default::default()
            };
            let none = |_: usize, _: usize| {};
            let once = render(&scene, Some(surface.as_ref()), None, &options, &none);
            scene.light.intensity *= 2.0;
            let halved = RenderOptions {
                exposure: options.exposure * 0.5,
                ..options
            };
            let twice = render(&scene, Some(surface.as_ref()), None, &halved, &none);
            let off = once
                .rgb
                .iter()
                .zip(&twice.rgb)
                .filter(|(a, b)| a.abs_diff(**b) > 1)
                .count();
            assert_eq!(off, 0, "{name}: {off} channels differ by more than a step");
        }
    }

    /// A floor map projected to the eye (each pixel holds the map at its straight ray's floor
    /// point, as `cascaded` makes its image) and read back as eye-space caustics lights the final
    /// image as the map itself does: the two differ only where a refracted ray's floor point is
    /// hidden from the eye's straight rays and by the extra bilinear read.
    #[test]
    fn eye_space_caustics_read_where_the_floor_projects() {
        // The shore with a 5 m/s ocean on a 128 grid, whose caustics a 128² map resolves
        // (the built-in light breeze's wavelets alias at this size, which the test does not
        // measure).
        let text = crate::scene::BUILTIN_SCENES
            .iter()
            .find(|(n, _)| *n == "shore")
            .unwrap()
            .1
            .replace(
                "resolution = 256, wind_speed = 2.0",
                "resolution = 128, wind_speed = 5.0",
            );
        let mut scene = Scene::from_toml(&text, std::path::Path::new("."), "shore").unwrap();
        assert!(matches!(
            &scene.water.as_ref().unwrap().source,
            crate::scene::WaterSource::Ocean(o) if o.params().wind_speed == 5.0
        ));
        scene.camera.width = 160;
        scene.camera.height = 90;
        scene.caustics.width = 128;
        scene.caustics.height = 128;
        let water = scene.water.as_ref().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let input = ReferenceInput::from_scene(&scene, surface.as_ref()).unwrap();
        let options = ReferenceOptions {
            cells_per_texel: 2,
            ..Default::default()
        };
        let map = reference(&input, &options, &|_, _| {}).unwrap();
        let setup = CascadedSetup::from_scene(&scene, &CascadedParams::default()).unwrap();
        let eye = eye_pass(&setup, scene.floor.terrain.as_ref());
        let e = &setup.eye;
        let texels = eye
            .iter()
            .enumerate()
            .map(|(p, t)| {
                if t[3] == 0.0 {
                    return [0.0, 0.0, 0.0, -1.0];
                }
                let (x, y) = ((p % e.width) as f64 + 0.5, (p / e.width) as f64 + 0.5);
                let f = e.position + e.ray(x, y) * t[0] as f64;
                let c = map.sample(f.x, f.y, false);
                [c[0], c[1], c[2], 0.0]
            })
            .collect();
        let image = EyeSpaceCaustics {
            width: e.width,
            height: e.height,
            texels,
        };
        let options = RenderOptions {
            supersampling: 1,
            ..Default::default()
        };
        let s = Some(surface.as_ref());
        let a = render_with(&scene, s, Some(Caustics::Floor(&map)), &options, &|_, _| {});
        let b = render_with(
            &scene,
            s,
            Some(Caustics::EyeSpace(&image)),
            &options,
            &|_, _| {},
        );
        let flat = render_with(&scene, s, None, &options, &|_, _| {});
        // The nearer half of the floor, where a pixel sees less than a map texel (in the distance
        // the two sample the map's detail at different points: aliasing, not a misplaced read),
        // without the last rows, whose refracted floor points project below the image.
        let rows = (scene.camera.height as usize / 2) * 160 * 3
            ..(scene.camera.height as usize - 3) * 160 * 3;
        let mean = |x: &Image, y: &Image| {
            x.rgb[rows.clone()]
                .iter()
                .zip(&y.rgb[rows.clone()])
                .map(|(p, q)| p.abs_diff(*q) as f64)
                .sum::<f64>()
                / rows.len() as f64
        };
        let (same, caustics) = (mean(&a, &b), mean(&a, &flat));
        eprintln!(
            "map vs the same map through the eye: mean |Δ| {same:.3} steps; map vs flat-water \
             lighting {caustics:.3} steps"
        );
        assert!(caustics > 0.5, "{caustics}");
        assert!(same < 0.2 * caustics, "{same} vs {caustics}");
    }
}
