//! The final image on the GPU (`caustics_gpu::final_image`) against its CPU twin
//! (`caustics_core::render::render`), scene by scene, from the same inputs: the same frozen water
//! surface (the grid the GPU samples it on, `final_image::water_grid`), the same caustics map (or
//! eye-space caustics image, technique `cascaded`) and the same options.
//!
//! Tolerances, in 8-bit sRGB steps over every channel of every pixel:
//! - mean absolute difference below 1 (1/255): rounding between f32 and f64 moves a few channels
//!   across a quantisation step, which costs far less than 1 on average; a real mismatch (a wrong
//!   term, constant or edge rule) moves whole regions by several steps;
//! - at most 1 % of the pixels with a channel off by more than 8: where a ray grazes a silhouette,
//!   a tile's grout line, the pool's rim or a wave crest, f32 and f64 may pick different sides and
//!   the pixel takes a different colour outright. Those pixels are few and isolated;
//! - at most 2 % of the channels off by more than 1 step. Rounding alone moves a smooth region by
//!   at most one step (f32 carries ~7 digits, a step is 1/255 of the display range), so this
//!   catches a small systematic error that the mean would average away: a constant off by 3 % in
//!   the tiles' albedo gives a mean of only 0.2 steps but fails here.
//!
//! On failure (or always, with `CAUSTICS_KEEP_IMAGES=1`) the two images and their difference are
//! written as PPM files to the temp directory.

use caustics_core::map::CausticsMap;
use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::render::{
    Caustics, EyeSpaceCaustics, Image, RenderOptions, render, render_with,
};
use caustics_core::scene::{Albedo, Material, Scene};
use caustics_core::water::{GridSurface, Surface};
use caustics_gpu::context::test_context;
use caustics_gpu::final_image::{FinalImage, water_grid};
use caustics_gpu::{GpuContext, GpuTimer};

const MEAN_TOLERANCE: f64 = 1.0;
const OUTLIER_STEPS: u8 = 8;
const OUTLIER_FRACTION: f64 = 0.01;
const DRIFT_STEPS: u8 = 1;
const DRIFT_FRACTION: f64 = 0.02;

struct Difference {
    mean: f64,
    outliers: f64,
    /// The fraction of channels off by more than `DRIFT_STEPS`.
    drift: f64,
    max: u8,
}

fn difference(cpu: &Image, gpu: &Image) -> Difference {
    assert_eq!((cpu.width, cpu.height), (gpu.width, gpu.height));
    assert_eq!(cpu.rgb.len(), gpu.rgb.len());
    let diffs: Vec<u8> = cpu
        .rgb
        .iter()
        .zip(&gpu.rgb)
        .map(|(&a, &b)| a.abs_diff(b))
        .collect();
    let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
    let pixels = diffs.len() / 3;
    let outliers = diffs
        .chunks(3)
        .filter(|p| p.iter().any(|&d| d > OUTLIER_STEPS))
        .count() as f64
        / pixels as f64;
    let drift = diffs.iter().filter(|&&d| d > DRIFT_STEPS).count() as f64 / diffs.len() as f64;
    Difference {
        mean,
        outliers,
        drift,
        max: diffs.iter().copied().max().unwrap_or(0),
    }
}

fn write_ppm(name: &str, width: u32, height: u32, rgb: &[u8]) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(name);
    let mut bytes = format!("P6\n{width} {height}\n255\n").into_bytes();
    bytes.extend_from_slice(rgb);
    std::fs::write(&path, bytes).expect("write the PPM");
    path
}

/// The small version of a scene the test renders: 160 x 90, one sample per pixel, a 64 x 64 map.
fn small(name: &str) -> Scene {
    let mut scene = Scene::builtin(name).expect("built-in scene");
    scene.camera.width = 160;
    scene.camera.height = 90;
    scene.caustics.width = 64;
    scene.caustics.height = 64;
    scene
}

/// The surface both sides render with, and the reference caustics map on it (at 2 cells per texel,
/// as `caustics render --cells-per-texel 2` would make it).
fn inputs(scene: &Scene) -> (Option<GridSurface>, Option<CausticsMap>) {
    let Some(water) = &scene.water else {
        return (None, None);
    };
    let surface = water.surface_at(scene.time).expect("surface");
    let grid = water_grid(scene, surface.as_ref()).expect("water");
    let input = ReferenceInput::from_scene(scene, &grid).expect("reference input");
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let map = reference(&input, &options, &|_, _| {}).expect("reference map");
    (Some(grid), Some(map))
}

/// Render `scene` on both sides and hold the GPU image to the CPU one.
fn check(ctx: &GpuContext, what: &str, scene: &Scene, caustics: bool) -> Difference {
    let (surface, map) = inputs(scene);
    let map = map.filter(|_| caustics);
    check_map(
        ctx,
        what,
        scene,
        surface.as_ref().map(|s| s as &dyn Surface),
        map,
    )
}

/// As [`check`], with the caustics map given.
fn check_map(
    ctx: &GpuContext,
    what: &str,
    scene: &Scene,
    surface: Option<&dyn Surface>,
    map: Option<CausticsMap>,
) -> Difference {
    check_caustics(ctx, what, scene, surface, map.as_ref().map(Caustics::Floor))
}

/// As [`check_map`], with the caustics from either source.
fn check_caustics(
    ctx: &GpuContext,
    what: &str,
    scene: &Scene,
    surface: Option<&dyn Surface>,
    caustics: Option<Caustics>,
) -> Difference {
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let cpu = render_with(scene, surface, caustics, &options, &|_, _| {});
    let final_image = FinalImage::new(ctx).expect("pipeline");
    let mut timer = GpuTimer::new(ctx, 1);
    let gpu = final_image
        .render_with(ctx, scene, surface, caustics, &options, Some(&mut timer))
        .expect("GPU render");
    let times = timer.read(ctx).expect("timestamps");
    let d = difference(&cpu, &gpu);
    eprintln!(
        "{what}: mean |GPU - CPU| {:.4} steps, {:.3} % of pixels off by more than {OUTLIER_STEPS}, \
         {:.3} % of channels off by more than {DRIFT_STEPS}, largest {}; GPU pass {}",
        d.mean,
        100.0 * d.outliers,
        100.0 * d.drift,
        d.max,
        times
            .first()
            .map_or("untimed".to_string(), |t| format!("{:.1} ms", t.ms))
    );
    let failed =
        d.mean >= MEAN_TOLERANCE || d.outliers > OUTLIER_FRACTION || d.drift > DRIFT_FRACTION;
    if failed || std::env::var("CAUSTICS_KEEP_IMAGES").is_ok_and(|v| v == "1") {
        let (w, h) = (cpu.width, cpu.height);
        let diff: Vec<u8> = cpu
            .rgb
            .iter()
            .zip(&gpu.rgb)
            .map(|(&a, &b)| a.abs_diff(b).saturating_mul(16))
            .collect();
        let paths = [
            write_ppm(&format!("render-gpu-{what}-cpu.ppm"), w, h, &cpu.rgb),
            write_ppm(&format!("render-gpu-{what}-gpu.ppm"), w, h, &gpu.rgb),
            write_ppm(&format!("render-gpu-{what}-difference.ppm"), w, h, &diff),
        ];
        assert!(
            !failed,
            "{what}: the GPU image departs from the CPU one (mean {:.3} steps, tolerance \
             {MEAN_TOLERANCE}; {:.2} % outliers, tolerance {:.0} %; {:.2} % drifting channels, \
             tolerance {:.0} %); images: {paths:?}",
            d.mean,
            100.0 * d.outliers,
            100.0 * OUTLIER_FRACTION,
            100.0 * d.drift,
            100.0 * DRIFT_FRACTION
        );
    }
    // Not blank: the comparison would be empty if both sides drew nothing.
    let mean_level = gpu.rgb.iter().map(|&v| v as f64).sum::<f64>() / gpu.rgb.len() as f64;
    assert!(mean_level > 10.0, "{what}: the image is nearly black");
    d
}

#[test]
fn pool_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    check(&ctx, "pool", &small("pool"), true);
}

#[test]
fn objects_match_the_cpu() {
    let Some(ctx) = test_context() else { return };
    check(&ctx, "objects", &small("objects"), true);
}

#[test]
fn glass_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    check(&ctx, "glass", &small("glass"), false);
}

/// Terrain (read through the clamped bicubic), sand, open sea beyond the surface's slab.
#[test]
fn shore_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    check(&ctx, "shore", &small("shore"), true);
}

/// Technique `cascaded`: caustics in the camera's screen space, read where each refracted view
/// ray's floor point projects. The eye-space image is the CPU twin's (`cascaded_gpu.rs` holds the
/// GPU's to it), made for the final image's camera and size.
#[test]
fn shore_with_cascaded_eye_space_caustics_matches_the_cpu() {
    use caustics_core::techniques::cascaded::{self, CascadedParams, CascadedSetup};
    let Some(ctx) = test_context() else { return };
    let scene = small("shore");
    let (surface, _) = inputs(&scene);
    let params = CascadedParams {
        resolution: 256,
        ..Default::default()
    };
    let setup = CascadedSetup::from_scene(&scene, &params).expect("setup");
    let water = cascaded::water_grid(&scene, 128).expect("water grid");
    let frame = cascaded::caustics(&setup, &water, scene.floor.terrain.as_ref());
    let eye = EyeSpaceCaustics {
        width: setup.eye.width,
        height: setup.eye.height,
        texels: frame.image,
    };
    let surface = surface.as_ref().map(|s| s as &dyn Surface);
    let d = check_caustics(
        &ctx,
        "shore-cascaded",
        &scene,
        surface,
        Some(Caustics::EyeSpace(&eye)),
    );
    assert!(d.mean < MEAN_TOLERANCE);
    // The caustics show: the image departs from the one lit as under flat water.
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let with = render_with(
        &scene,
        surface,
        Some(Caustics::EyeSpace(&eye)),
        &options,
        &|_, _| {},
    );
    let flat = render_with(&scene, surface, None, &options, &|_, _| {});
    let changed = with
        .rgb
        .iter()
        .zip(&flat.rgb)
        .filter(|(a, b)| a.abs_diff(**b) > 4)
        .count() as f64
        / with.rgb.len() as f64;
    eprintln!(
        "shore-cascaded: {:.1} % of channels differ from flat-water lighting by > 4 steps",
        100.0 * changed
    );
    assert!(
        changed > 0.05,
        "the eye-space caustics barely show: {changed}"
    );
}

/// An albedo image on the floor, and no caustics map (the floor lit as under flat water).
#[test]
fn albedo_image_without_a_map_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    let mut scene = small("pool");
    let (width, height) = (37, 23);
    scene.floor.albedo = Albedo::Image {
        width,
        height,
        texels: (0..width * height)
            .map(|k| {
                let (i, j) = (k / width, k % width);
                [
                    (j as f32 / width as f32) * 0.8 + 0.1,
                    (i as f32 / height as f32) * 0.8 + 0.1,
                    if (i + j) % 2 == 0 { 0.2 } else { 0.7 },
                ]
            })
            .collect(),
    };
    check(&ctx, "albedo-image", &scene, false);
}

/// Glass under water: the reflected and refracted branches under the surface, up to the CPU's
/// recursion depth.
/// No water, a map of the light through the glass (as caustic-triangles makes it): every object
/// shadows the sun and the map adds the transmitted light, on both sides alike.
#[test]
fn glass_with_an_air_caustics_map_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    let scene = small("glass");
    let n = 64;
    let grid = caustics_core::grid::Grid::from_fn(n, n, |i, j| {
        let p = glam::DVec2::new(j as f64 + 0.5, i as f64 + 0.5) / n as f64
            - glam::DVec2::new(0.45, 0.55);
        (3.0 * (-p.length_squared() / 0.004).exp()) as f32
    });
    let map = CausticsMap::from_grid(&grid, scene.size);
    check_map(&ctx, "glass-air-caustics", &scene, None, Some(map));
}

#[test]
fn glass_under_water_matches_the_cpu() {
    let Some(ctx) = test_context() else { return };
    let mut scene = small("objects");
    for obj in &mut scene.objects {
        obj.material = Material::Glass {
            ior: 1.5,
            tint: glam::DVec3::new(0.9, 0.95, 1.0),
        };
    }
    check(&ctx, "glass-under-water", &scene, true);
}

/// The time of a full-size render (the scene's 960 x 540, 2 x 2 samples per pixel) on both sides.
/// Slow on a software adapter, so run on demand:
/// `cargo test --release -p caustics-gpu --test render_gpu -- --ignored --nocapture`.
#[test]
#[ignore]
fn full_size_render_times() {
    let Some(ctx) = test_context() else { return };
    for name in ["pool", "objects"] {
        let mut scene = Scene::builtin(name).expect("built-in scene");
        scene.caustics.width = 256;
        scene.caustics.height = 256;
        let (surface, map) = inputs(&scene);
        let surface = surface.as_ref().map(|s| s as &dyn Surface);
        let options = RenderOptions::default();
        let final_image = FinalImage::new(&ctx).expect("pipeline");
        // The first dispatch compiles the shader; time the second.
        for _ in 0..2 {
            let started = std::time::Instant::now();
            let mut timer = GpuTimer::new(&ctx, 1);
            let gpu = final_image
                .render(
                    &ctx,
                    &scene,
                    surface,
                    map.as_ref(),
                    &options,
                    Some(&mut timer),
                )
                .expect("GPU render");
            let times = timer.read(&ctx).expect("timestamps");
            eprintln!(
                "{name} {} x {}: GPU {:.2} s (pass {})",
                gpu.width,
                gpu.height,
                started.elapsed().as_secs_f64(),
                times
                    .first()
                    .map_or("untimed".to_string(), |t| format!("{:.0} ms", t.ms))
            );
        }
        let started = std::time::Instant::now();
        render(&scene, surface, map.as_ref(), &options, &|_, _| {});
        eprintln!("{name}: CPU {:.2} s", started.elapsed().as_secs_f64());
    }
}
