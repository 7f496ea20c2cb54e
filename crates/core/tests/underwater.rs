//! The camera under the water (`caustics_core::render`): the surface seen from below splits a view
//! ray by the Fresnel equations from the dense side; inside Snell's window (half-angle
//! asin(1/n) about the normal) the sky comes through, beyond it the surface is a perfect mirror of
//! the pool.

use glam::DVec3;

use caustics_core::optics::fresnel_transmittance;
use caustics_core::render::{Image, RenderOptions, camera_under_water, from_below, render};
use caustics_core::scene::{Albedo, BUILTIN_SCENES, Camera, Scene, WaterSource};
use caustics_core::water::Surface;

const IOR: f64 = 1.333;
/// The test image: square and odd, so that the centre row's rays lie in the x-z plane.
const SIDE: u32 = 201;
const FOV_Y: f64 = 110.0;

/// Fresnel reflectance and transmittance of unpolarised light from water (index `n`) into air at
/// incidence `ti`, from the sine and tangent forms of the amplitude coefficients (Born & Wolf
/// §1.5.2), which share no formula with `optics::fresnel_transmittance`'s.
fn fresnel_sine_tangent(ti: f64, n: f64) -> (f64, f64) {
    if ti == 0.0 {
        let r = ((n - 1.0) / (n + 1.0)).powi(2);
        return (r, 4.0 * n / (n + 1.0).powi(2));
    }
    let tt = (n * ti.sin()).asin();
    let rs = -(ti - tt).sin() / (ti + tt).sin();
    let rp = (ti - tt).tan() / (ti + tt).tan();
    let ts = 2.0 * tt.sin() * ti.cos() / (ti + tt).sin();
    let tp = ts / (ti - tt).cos();
    // Flux: the transmitted beam's index and cross-section, n_air cos θt against n cos θi.
    let flux = tt.cos() / (n * ti.cos());
    (0.5 * (rs * rs + rp * rp), flux * 0.5 * (ts * ts + tp * tp))
}

/// Energy at the interface from below: what the split reflects and transmits adds up to the incident
/// flux at every incidence, agrees with the Fresnel equations from the dense side and with Stokes'
/// reciprocity (the same transmittance as from the air at the refracted angle); beyond the critical
/// angle nothing leaves the water. The directions obey the law of reflection and Snell's law.
#[test]
fn the_surface_from_below_conserves_energy() {
    let critical = (1.0 / IOR).asin();
    let (mut worst_sum, mut worst_t, mut worst_stokes, mut worst_dir) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut inside, mut beyond) = (0, 0);
    for k in 0..1800 {
        let ti = (k as f64 * 0.05).to_radians();
        let d = DVec3::new(ti.sin(), 0.0, ti.cos());
        let split = from_below(d, DVec3::Z, IOR);
        worst_dir = worst_dir.max((split.reflected - DVec3::new(d.x, 0.0, -d.z)).length());
        if ti < critical {
            inside += 1;
            let r = split
                .refracted
                .expect("inside Snell's window the ray leaves the water");
            worst_dir = worst_dir
                .max((r.length() - 1.0).abs())
                .max((r.x - IOR * d.x).abs());
            assert!(r.z > 0.0);
            let (rf, tf) = fresnel_sine_tangent(ti, IOR);
            worst_sum = worst_sum.max((rf + tf - 1.0).abs());
            worst_t = worst_t.max((split.transmittance - tf).abs());
            worst_stokes = worst_stokes
                .max((split.transmittance - fresnel_transmittance(r.z, 1.0, IOR)).abs());
        } else {
            beyond += 1;
            assert!(split.refracted.is_none(), "θ = {ti} beyond the window");
            assert_eq!(split.transmittance, 0.0);
        }
    }
    eprintln!(
        "{inside} angles inside the window, {beyond} beyond: |R + T - 1| {worst_sum:.2e}, \
         |T - T(Fresnel)| {worst_t:.2e}, |T - T(reciprocal)| {worst_stokes:.2e}, directions \
         {worst_dir:.2e}"
    );
    // The window's half-angle, 48.6°, at 0.05° steps: 973 angles inside.
    assert_eq!(inside, 973);
    // Measured: 8.9e-16, 2.9e-14, 2.2e-14, 2.2e-16.
    assert!(worst_sum < 8.9e-15, "{worst_sum}");
    assert!(worst_t < 2.9e-13, "{worst_t}");
    assert!(worst_stokes < 2.2e-13, "{worst_stokes}");
    assert!(worst_dir < 2.2e-15, "{worst_dir}");
}

/// Flat, clear water 1 m deep over the 4 m pool, the sun overhead (so no wall shades the floor
/// and the floor's light does not depend on the depth), the camera at the pool's centre looking
/// straight up from `z` (or down, from above a deeper water).
fn looking(z: f64, up: bool, depth: f64, black_floor: bool) -> (Scene, Box<dyn Surface>) {
    let mut scene = Scene::builtin("underwater").expect("built-in scene");
    let water = scene.water.as_mut().expect("water");
    water.source = WaterSource::Flat;
    water.absorption = DVec3::ZERO;
    water.depth = depth;
    water.ior = IOR;
    let surface = water.surface_at(0.0).expect("flat water");
    scene.light.direction = DVec3::new(0.0, 0.0, -1.0);
    if black_floor {
        scene.floor.albedo = Albedo::Image {
            width: 1,
            height: 1,
            texels: vec![[0.0; 3]],
        };
    }
    let position = DVec3::new(2.0, 2.0, z);
    scene.camera = Camera {
        position,
        target: position + DVec3::Z * if up { 1.0 } else { -1.0 },
        fov_y: FOV_Y,
        width: SIDE,
        height: SIDE,
    };
    (scene, surface)
}

fn draw(scene: &Scene, surface: Option<&dyn Surface>, exposure: f64) -> Image {
    let options = RenderOptions {
        supersampling: 1,
        exposure,
        tone_map: Default::default(),
        ..Default::default()
    };
    render(scene, surface, None, None, &options, &|_, _| {})
}

fn pixel(image: &Image, x: u32, y: u32) -> [u8; 3] {
    let i = 3 * (y * image.width + x) as usize;
    [image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]]
}

/// Angle between a pixel's view ray and the vertical.
fn off_vertical(camera: &Camera, x: u32, y: u32) -> f64 {
    camera.ray(x as f64, y as f64).1.z.abs().acos()
}

/// Looking straight up from 0.5 m under flat water over a black floor, only Snell's window is lit:
/// a disc whose edge lies at the critical angle, to within a pixel; inside it each pixel is the
/// sky (and the sun, overhead) along the refracted ray, times the transmittance from below.
#[test]
fn snells_window_frames_the_sky_at_the_critical_angle() {
    let (scene, surface) = looking(0.5, true, 1.0, true);
    assert!(camera_under_water(&scene, Some(surface.as_ref())));
    let exposure = RenderOptions::default().exposure;
    let image = draw(&scene, Some(surface.as_ref()), exposure);
    let cam = &scene.camera;
    let critical = (1.0 / IOR).asin();

    // The centre row: the lit run's ends against the critical angle's image-plane position.
    let row = SIDE / 2;
    let lit = |x: u32| pixel(&image, x, row) != [0, 0, 0];
    let first = (0..SIDE).find(|&x| lit(x)).expect("the window is in view");
    let last = (0..SIDE)
        .rev()
        .find(|&x| lit(x))
        .expect("the window is in view");
    assert!((first..=last).all(lit), "the window is one run");
    let half = (FOV_Y.to_radians() * 0.5).tan();
    let edge = |sign: f64| (1.0 + sign * critical.tan() / half) * 0.5 * SIDE as f64;
    let (left, right) = (first as f64 - edge(-1.0), (last + 1) as f64 - edge(1.0));
    eprintln!("window edges off the critical angle by {left:.3} and {right:.3} pixels");
    // Measured: 0.339 and -0.339 pixels (the pixel grid's own offset from the edge), and no pixel
    // on the wrong side of it in the whole image.
    assert!(left.abs() < 1.0 && right.abs() < 1.0, "{left} {right}");

    // The whole image: lit exactly inside the cone, but for the pixels the edge crosses.
    let pixel_angle = FOV_Y.to_radians() / SIDE as f64;
    let mut straddling = 0;
    for y in 0..SIDE {
        for x in 0..SIDE {
            let a = off_vertical(cam, x, y);
            let on = pixel(&image, x, y) != [0, 0, 0];
            if on != (a < critical) {
                straddling += 1;
                assert!(
                    (a - critical).abs() < pixel_angle,
                    "pixel ({x}, {y}) at {:.3}° lit {on}",
                    a.to_degrees()
                );
            }
        }
    }
    eprintln!("{straddling} pixels on the window's edge on the other side of it");

    // Inside: the sky along the refracted ray, as a camera in open air sees it through the
    // pixel's refracted direction with the exposure times the transmittance.
    let mut air = scene.clone();
    air.water = None;
    let mut worst = 0u8;
    let mut checked = 0;
    for x in (first..=last).step_by(5) {
        let (_, d) = cam.ray(x as f64, row as f64);
        let split = from_below(d, DVec3::Z, IOR);
        let Some(r) = split.refracted else { continue };
        air.camera = Camera {
            position: cam.position,
            target: cam.position + r,
            fov_y: 10.0,
            width: 1,
            height: 1,
        };
        let sky = draw(&air, None, exposure * split.transmittance);
        let seen = pixel(&image, x, row);
        for (a, b) in seen.iter().zip(&sky.rgb) {
            worst = worst.max(a.abs_diff(*b));
        }
        checked += 1;
    }
    eprintln!(
        "{checked} window pixels against the sky through them: largest difference {worst} steps"
    );
    assert!(checked >= 30);
    // Measured: 0 steps; one step is the rounding of the same radiance summed in another order.
    assert!(worst <= 1, "{worst}");
    // The sun overhead, at the window's centre, is its brightest point.
    let centre = pixel(&image, row, row);
    assert!((first..=last).all(|x| pixel(&image, x, row)[2] <= centre[2]));
}

/// Beyond Snell's window the surface is a perfect mirror: the image there is the one a camera at
/// the mirrored point (above the surface, in water raised over it) sees looking down, flipped top
/// to bottom; inside the window the sky adds to a partial reflection, so the two differ.
#[test]
fn beyond_the_window_the_surface_mirrors_the_pool() {
    let (below, surface) = looking(0.5, true, 1.0, false);
    // The mirror image of the camera 0.5 m under the rest level 1 m: 1.5 m, in water 3 m deep.
    let (mirror, mirror_surface) = looking(1.5, false, 3.0, false);
    assert!(camera_under_water(&mirror, Some(mirror_surface.as_ref())));
    let exposure = RenderOptions::default().exposure;
    let a = draw(&below, Some(surface.as_ref()), exposure);
    let b = draw(&mirror, Some(mirror_surface.as_ref()), exposure);
    let critical = (1.0 / IOR).asin();
    let pixel_angle = FOV_Y.to_radians() / SIDE as f64;
    let (mut outside, mut differ_out, mut worst_out) = (0, 0, 0u8);
    let (mut inside, mut differ_in) = (0, 0);
    for y in 0..SIDE {
        for x in 0..SIDE {
            let angle = off_vertical(&below.camera, x, y);
            let (p, q) = (pixel(&a, x, y), pixel(&b, x, SIDE - 1 - y));
            let diff = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
            if angle > critical + pixel_angle {
                outside += 1;
                differ_out += usize::from(diff > 1);
                worst_out = worst_out.max(diff);
            } else if angle < critical - pixel_angle {
                inside += 1;
                differ_in += usize::from(diff > 8);
            }
        }
    }
    eprintln!(
        "beyond the window: {differ_out} of {outside} pixels differ from the mirror camera's by \
         more than a step (largest {worst_out}); inside: {differ_in} of {inside} differ by more \
         than 8"
    );
    // Measured: 0 of 19600 pixels, the mirror image carrying the sample's footprint on to the floor
    // and the walls as the direct view does. The bound leaves room for rays that graze a grout line
    // or the floor's edge, where the two sides' rounding can pick different sides of it.
    assert!(differ_out <= 15, "{differ_out} of {outside}");
    // Measured: all but 80 of 19285 (next to the edge, where little of the sky comes through).
    assert!(inside - differ_in <= 640, "{differ_in} of {inside}");
}

/// A camera under the water is a valid scene; one under the pool's floor is refused, naming the
/// field.
#[test]
fn a_camera_may_be_under_the_water_but_not_under_the_floor() {
    let (_, text) = BUILTIN_SCENES
        .iter()
        .find(|(n, _)| *n == "underwater")
        .expect("the built-in underwater scene");
    let at = |z: &str| {
        text.replace(
            "position = [0.4, 0.3, 0.6]",
            &format!("position = [0.4, 0.3, {z}]"),
        )
    };
    assert_ne!(at("0.2"), *text, "the camera line is the scene's");
    let dir = std::path::Path::new(".");
    let scene = Scene::from_toml(&at("0.2"), dir, "under").expect("under the water is valid");
    assert!(camera_under_water(&scene, None));
    let err = Scene::from_toml(&at("-0.1"), dir, "below").expect_err("under the floor");
    let message = err.to_string();
    assert!(
        message.contains("camera.position") && message.contains("floor"),
        "{message}"
    );
}
