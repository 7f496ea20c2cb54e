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

mod march;
mod shade;
mod sky;
mod spread;
mod trace;

#[cfg(test)]
mod tests;

use glam::DVec3;

use crate::eye::EyeCamera;
use crate::map::{CausticsMap, MapPyramid};
use crate::mesh::MeshBvh;
use crate::optics::{fresnel_transmittance, refract};
use crate::parallel::prelude::*;
use crate::receivers::LightSpace;
use crate::scene::Scene;
use crate::sky::{SUN_RADIUS, Sky, TURBIDITY};
use crate::walls::WallMaps;
use crate::water::Surface;
use crate::water::slopes::{SlopePyramid, sample_spread, sun_slope_variance};

use spread::Spread;

pub use march::{EVEN_STEPS, MARCH_STEPS, SLAB_LATTICE, Slab, slab_bounds};
pub use sky::sky_ambient;
pub use trace::{FromBelow, camera_under_water, from_below};

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

/// How the CPU final image is traced and shown: supersampling, exposure, tone curve and the
/// water's normal filtering (default: 2 × 2 samples, exposure 1, ACES, exact normals).
pub struct RenderOptions {
    /// Samples per pixel along each axis (n² rays per pixel).
    pub supersampling: u32,
    /// Radiance is multiplied by this before the tone curve.
    pub exposure: f64,
    /// The curve from exposed radiance to display light.
    pub tone_map: ToneMap,
    /// Filter the water's normals by each sample's footprint ([`crate::water::slopes`]): far
    /// water shades with the mean slope and the roughness of the waves it cannot resolve. Off
    /// (the default), every sample shades with the exact normal where it meets the surface.
    /// Both final images (caustics-gpu's `final_image` is its twin); not the default, since many
    /// samples' FLIP prefers the exact normals: docs/maintainers/look.md has the measurements.
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
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// sRGB-encoded bytes, three (red, green, blue) a pixel, row by row, top row first.
    pub rgb: Vec<u8>,
}

/// Side of the square grid a GPU front end samples an analytic surface on for the final image
/// (`FinalImage::render` in caustics-gpu), and the lattice the CPU's filtered water normals
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

struct Tracer<'a> {
    scene: &'a Scene,
    surface: Option<&'a dyn Surface>,
    /// The floor's map and its pyramid, read over each sample's footprint on the floor.
    caustics: Option<(&'a CausticsMap, MapPyramid)>,
    /// The technique's light-space deposit, where objects are among its receivers: their light.
    light: Option<&'a LightSpace>,
    eye_space: Option<(&'a EyeSpaceCaustics, EyeCamera)>,
    /// The walls' maps, when the technique lit the pool's walls.
    walls: Option<&'a WallMaps>,
    bvhs: Vec<MeshBvh>,
    /// Bound on |h| of the water, for the slab the surface lies in.
    h_max: f64,
    /// Bound on the water's slope |∇h|, for the march through that slab
    /// ([`first_crossing`](march::first_crossing)).
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

/// Render the scene from its camera. `caustics` lights the floor, from a floor map or an eye-space
/// image (none: the floor is lit as if the water were flat); `walls` lights the pool's walls by
/// the sun through their maps (from a technique that lights them) as well as by the ambient light
/// (none: the ambient light alone). `progress(rows_done, rows)` reports as rows finish.
pub fn render(
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
            Some(Caustics::Floor(m) | Caustics::Received(m, _)) => Some((m, m.pyramid())),
            _ => None,
        },
        light: match caustics {
            Some(Caustics::Received(_, l)) => Some(l),
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
/// grid (docs/maintainers/look.md). For odd `n` one sample sits at the pixel's centre (for `n = 1` the only
/// one). GPU twin: `sample_offset` in final_image.wgsl.
pub fn sample_offset(sx: usize, sy: usize, n: usize) -> (f64, f64) {
    let n = n as f64;
    let (sx, sy) = (sx as f64, sy as f64);
    (
        (sx + (sy + 0.5) / n) / n,
        (sy + (n - 1.0 - sx + 0.5) / n) / n,
    )
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
#[cfg_attr(not(feature = "formats"), allow(unused_variables))]
pub fn write_png(
    path: &std::path::Path,
    width: u32,
    height: u32,
    linear: &[[f32; 3]],
    exposure: f64,
    curve: crate::render::ToneMap,
) -> crate::Result<()> {
    #[cfg(not(feature = "formats"))]
    return Err(crate::Error::feature_off(path, "writing a PNG", "formats"));
    #[cfg(feature = "formats")]
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
