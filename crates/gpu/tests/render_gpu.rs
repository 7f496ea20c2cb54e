//! The final image on the GPU (`caustics_gpu::final_image`) against its CPU twin
//! (`caustics_core::render::render`), scene by scene, from the same inputs: the same frozen water
//! surface (the grid the GPU samples it on, `final_image::water_grid`), the same caustics map (or
//! eye-space caustics image, technique `cascaded`) and the same options.
//!
//! Tolerances, in 8-bit sRGB steps over every channel of every pixel, per scene ([`Bounds`]: each
//! at most 10 times what lavapipe measured, the measurement written beside it: Mesa 22.3.6 and
//! 25.0.7 measured the same in every test; where it measured nothing, 10 channels' or pixels' worth
//! of the 160 x 90 image), never looser than these ceilings:
//! - mean absolute difference below 1 (1/255) over the pixels that are not outliers (below):
//!   rounding between f32 and f64 moves a few channels across a quantisation step, which costs far
//!   less than 1 on average; a real mismatch (a wrong term, constant or edge rule) moves whole
//!   regions by several steps;
//! - at most 1 % of the pixels with a channel off by more than 8: where a ray grazes a silhouette,
//!   a tile's grout line, a deck's joint, the pool's rim or a wave crest, f32 and f64 may pick
//!   different sides and the pixel takes a different colour outright. Those pixels are few and
//!   isolated;
//! - at most 2 % of the channels off by more than 1 step. Rounding alone moves a smooth region by
//!   at most one step (f32 carries ~7 digits, a step is 1/255 of the display range), so this
//!   catches a small systematic error that the mean would average away: a constant off by 3 % in
//!   the tiles' albedo gives a mean of only 0.2 steps but fails here.
//!
//! A caustics map read 2 % too bright (`caustics_texel` times 1.02) passes those ceilings (pool:
//! mean 0.23 steps, 0.94 % of channels drifting, no outliers) but fails every per-scene bound that
//! reads a map (pool, objects, shore, glass under water, both frame tests).
//!
//! On failure (or always, with `CAUSTICS_KEEP_IMAGES=1`) the two images and their difference are
//! written as PPM files to the temp directory.

#[macro_use]
mod common;

use caustics_core::map::CausticsMap;
use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::render::{Caustics, EyeSpaceCaustics, Image, RenderOptions, render};
use caustics_core::scene::{Albedo, Material, Scene};
use caustics_core::water::{GridSurface, Surface};
use caustics_gpu::context::test_gpu;
use caustics_gpu::final_image::{FinalImage, ImageInputs, slab_bounds, water_grid};
use caustics_gpu::{GpuContext, GpuTimer, Output, WaterTextures};

const MEAN_TOLERANCE: f64 = 1.0;
const OUTLIER_STEPS: u8 = 8;
const OUTLIER_FRACTION: f64 = 0.01;
const DRIFT_STEPS: u8 = 1;
const DRIFT_FRACTION: f64 = 0.02;

/// One channel of the 160 x 90 test image, as a fraction of them all: the bound where lavapipe
/// measured no difference at all is 10 of these.
const CHANNEL: f64 = 1.0 / (160.0 * 90.0 * 3.0);
/// One pixel of the 160 x 90 test image.
const PIXEL: f64 = 1.0 / (160.0 * 90.0);

/// How far one scene's GPU image may depart from its CPU twin: the mean absolute difference in
/// steps, the fraction of pixels off by more than `OUTLIER_STEPS`, the fraction of channels off by
/// more than `DRIFT_STEPS`.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    mean: f64,
    outliers: f64,
    drift: f64,
}

struct Difference {
    /// Over every channel: how much one image changes another.
    mean: f64,
    /// Over the pixels that are not outliers, what [`Bounds::mean`] bounds.
    mean_kept: f64,
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
    // The mean is over the pixels that are not outliers: an outlier is a pixel whose samples
    // took the other side of an edge (bounded by `outliers`), the mean what rounding does to the
    // rest.
    let kept: Vec<u8> = diffs
        .chunks(3)
        .filter(|p| p.iter().all(|&d| d <= OUTLIER_STEPS))
        .flatten()
        .copied()
        .collect();
    let mean_kept = kept.iter().map(|&d| d as f64).sum::<f64>() / kept.len().max(1) as f64;
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
        mean_kept,
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
fn check(
    ctx: &GpuContext,
    what: &str,
    scene: &Scene,
    caustics: bool,
    bounds: Bounds,
) -> Difference {
    let (surface, map) = inputs(scene);
    let map = map.filter(|_| caustics);
    check_map(
        ctx,
        what,
        scene,
        surface.as_ref().map(|s| s as &dyn Surface),
        map,
        bounds,
    )
}

/// As [`check`], with the caustics map given.
fn check_map(
    ctx: &GpuContext,
    what: &str,
    scene: &Scene,
    surface: Option<&dyn Surface>,
    map: Option<CausticsMap>,
    bounds: Bounds,
) -> Difference {
    check_caustics(
        ctx,
        what,
        scene,
        surface,
        map.as_ref().map(Caustics::Floor),
        bounds,
    )
}

/// As [`check_map`], with the caustics from either source.
fn check_caustics(
    ctx: &GpuContext,
    what: &str,
    scene: &Scene,
    surface: Option<&dyn Surface>,
    caustics: Option<Caustics>,
    bounds: Bounds,
) -> Difference {
    // One sample a pixel unless the scene's name asks for the default's 2 x 2; the exact normals
    // unless it says the water is filtered.
    let options = RenderOptions {
        supersampling: if what.ends_with("2x2") { 2 } else { 1 },
        filter_water: what.contains("filtered"),
        ..Default::default()
    };
    let cpu = render(scene, surface, caustics, None, &options, &|_, _| {});
    let final_image = FinalImage::new(ctx).expect("pipeline");
    let mut timer = GpuTimer::new(ctx, 4);
    let gpu = final_image
        .render(
            ctx,
            scene,
            surface,
            caustics,
            None,
            &options,
            Some(&mut timer),
        )
        .expect("GPU render");
    let times = timer.read(ctx).expect("timestamps");
    if ctx.timestamps {
        // Every pass is timed, as `FinalImageFrame::encode` says: the water's patches, slab and
        // surface where there is water.
        let labels: Vec<&str> = times.iter().map(|t| t.label.as_str()).collect();
        let slab = caustics_gpu::final_image::FINAL_IMAGE_SLAB.name;
        let raster = caustics_gpu::final_image::FINAL_IMAGE_SURFACE.name;
        let patches = caustics_gpu::water::patches::WATER_PATCHES.name;
        let expected: &[&str] = if surface.is_some() {
            &[patches, slab, raster, "final image"]
        } else {
            &["final image"]
        };
        assert_eq!(labels, expected, "{what}");
    }
    let time = times
        .iter()
        .find(|t| t.label == "final image")
        .map_or("untimed".to_string(), |t| format!("{:.1} ms", t.ms));
    hold(what, &cpu, &gpu, bounds, &time)
}

/// Hold `gpu` to `cpu` within `bounds`, and say how close they came; `note` ends the line.
fn hold(what: &str, cpu: &Image, gpu: &Image, bounds: Bounds, note: &str) -> Difference {
    assert!(
        bounds.mean <= MEAN_TOLERANCE
            && bounds.outliers <= OUTLIER_FRACTION
            && bounds.drift <= DRIFT_FRACTION,
        "{what}: bounds {bounds:?} looser than the ceilings"
    );
    let d = difference(cpu, gpu);
    eprintln!(
        "{what}: mean |GPU - CPU| {:.6} steps (outliers aside), {:.4} % of pixels off by more than \
         {OUTLIER_STEPS}, {:.4} % of channels off by more than {DRIFT_STEPS}, largest {}; {note}",
        d.mean_kept,
        100.0 * d.outliers,
        100.0 * d.drift,
        d.max,
    );
    let failed =
        d.mean_kept > bounds.mean || d.outliers > bounds.outliers || d.drift > bounds.drift;
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
            "{what}: the GPU image departs from the CPU one (mean {:.6} steps, tolerance {:.6}; \
             {:.4} % outliers, tolerance {:.4} %; {:.4} % drifting channels, tolerance {:.4} %); \
             images: {paths:?}",
            d.mean_kept,
            bounds.mean,
            100.0 * d.outliers,
            100.0 * bounds.outliers,
            100.0 * d.drift,
            100.0 * bounds.drift
        );
    }
    // Not blank: the comparison would be empty if both sides drew nothing.
    let mean_level = gpu.rgb.iter().map(|&v| v as f64).sum::<f64>() / gpu.rgb.len() as f64;
    assert!(mean_level > 10.0, "{what}: the image is nearly black");
    d
}

/// Where lavapipe measured at most one channel one step off and no outlier: 10 channels' worth of
/// mean and of drift, 10 pixels' worth of outliers.
const EXACT: Bounds = Bounds {
    mean: 10.0 * CHANNEL,
    outliers: 10.0 * PIXEL,
    drift: 10.0 * CHANNEL,
};

/// Where the pool's stone deck is in view: its joints box-filtered over a sample's footprint
/// (`Deck::albedo`) leave one far pixel 6 or 7 steps off in f32 (the filter's integral differenced
/// over a footprint of millimetres), 10 times the pool's measured mean 0.00044.
const DECK: Bounds = Bounds {
    mean: 0.0044,
    ..EXACT
};

fn pool_matches_the_cpu() {
    let ctx = test_gpu();
    // Measured (outliers aside, as every mean here): mean 0.000440 (one pixel of the far deck 6
    // steps off), no outlier, one channel drifting.
    check(&ctx, "pool", &small("pool"), true, DECK);
}

/// The concrete deck (`[floor] deck = "concrete"`, its code in the uniform's flags) on both sides.
fn pool_with_a_concrete_deck_matches_the_cpu() {
    let ctx = test_gpu();
    let mut scene = small("pool");
    scene.floor.deck = caustics_core::scene::Deck::Concrete;
    // Measured: mean 0.000023 (one channel one step), no outlier, no drift.
    let d = check(&ctx, "pool-concrete", &scene, true, EXACT);
    // The deck is in view: the stone deck's picture differs from this one (measured 3.83 steps
    // on average).
    let cpu = |deck| {
        let mut s = scene.clone();
        s.floor.deck = deck;
        let (surface, map) = inputs(&s);
        let options = RenderOptions {
            supersampling: 1,
            ..Default::default()
        };
        let surface = surface.expect("water");
        render(
            &s,
            Some(&surface),
            map.as_ref().map(Caustics::Floor),
            None,
            &options,
            &|_, _| {},
        )
    };
    let shown = difference(
        &cpu(caustics_core::scene::Deck::Stone),
        &cpu(caustics_core::scene::Deck::Concrete),
    );
    eprintln!(
        "pool-concrete: the deck's paving moves the image by {:.2} steps",
        shown.mean
    );
    assert!(
        shown.mean > 1.0,
        "the deck shows: {} (GPU mean {})",
        shown.mean,
        d.mean_kept
    );
}

/// The pool's walls lit through the reference's walls' maps under a low sun that lights
/// the far walls the camera looks at: `render` on both sides.
fn pool_walls_match_the_cpu() {
    use caustics_core::reference::reference_with_walls;
    let ctx = test_gpu();
    let mut scene = small("pool");
    scene.light.direction = glam::DVec3::new(0.8, 0.6, -0.6).normalize();
    let water = scene.water.as_ref().expect("water");
    let surface = water.surface_at(scene.time).expect("surface");
    let grid = water_grid(&scene, surface.as_ref()).expect("water");
    let input = ReferenceInput::from_scene(&scene, &grid).expect("reference input");
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let out = reference_with_walls(&input, &options, &|_, _| {}).expect("reference");
    let walls = out.walls.as_ref().expect("the pool has walls");
    let caustics = Some(Caustics::Floor(&out.floor));
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let cpu = caustics_core::render::render(
        &scene,
        Some(&grid),
        caustics,
        Some(walls),
        &options,
        &|_, _| {},
    );
    let unlit = render(&scene, Some(&grid), caustics, None, &options, &|_, _| {});
    let lit = difference(&unlit, &cpu);
    eprintln!(
        "pool walls: the walls' maps change the CPU image by {:.2} steps on average",
        lit.mean
    );
    assert!(lit.mean > 1.0, "the walls' light shows: {}", lit.mean);
    let gpu = FinalImage::new(&ctx)
        .expect("pipeline")
        .render(
            &ctx,
            &scene,
            Some(&grid),
            caustics,
            Some(walls),
            &options,
            None,
        )
        .expect("GPU render");
    // Measured: mean 0.000532 (one pixel of the far deck 7 steps off), no outlier, one channel
    // drifting; the walls' light itself moves the image by 1.69 steps on average.
    hold("pool walls", &cpu, &gpu, DECK, "");
}

/// The renderer's side for a CPU technique (the reference): its walls' maps, uploaded once with
/// `set_walls`, light the walls of the frame's image as `FinalImage::render` does, and later frames
/// create nothing.
fn the_renderer_lights_the_walls_with_uploaded_maps() {
    use caustics_core::reference::reference_with_walls;
    use caustics_gpu::renderer::{FrameWater, Renderer, WaterClock};
    let ctx = test_gpu();
    let mut scene = small("pool");
    scene.light.direction = glam::DVec3::new(0.8, 0.6, -0.6).normalize();
    let water = scene.water.as_ref().expect("water");
    let surface = water.surface_at(scene.time).expect("surface");
    let input = ReferenceInput::from_scene(&scene, surface.as_ref()).expect("input");
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let out = reference_with_walls(&input, &options, &|_, _| {}).expect("reference");
    let walls = out.walls.as_ref().expect("the pool has walls");
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let clock = WaterClock {
        time: scene.time,
        amplitude: 1.0,
        steps: 0,
    };
    let mut renderer = Renderer::new(&ctx).expect("renderer");
    renderer
        .set_water(&ctx, scene.water.as_ref(), &FrameWater::Scene)
        .expect("water");
    renderer.set_techniques(&ctx, &[None]);
    renderer
        .set_caustics(&ctx, 0, Some(&out.floor))
        .expect("map");
    renderer
        .render(&ctx, &scene, clock, &options)
        .expect("frame");
    let unlit = read_image(&ctx, renderer.image(0).expect("image"));
    renderer.set_walls(&ctx, 0, Some(walls)).expect("walls");
    renderer
        .render(&ctx, &scene, clock, &options)
        .expect("frame");
    ctx.wait().expect("frame");
    let before = ctx.traffic();
    for _ in 0..3 {
        renderer
            .render(&ctx, &scene, clock, &options)
            .expect("frame");
    }
    ctx.wait().expect("frames");
    let d = ctx.traffic().since(&before);
    assert_eq!(d.created(), 0, "{d:?}");
    let lit = read_image(&ctx, renderer.image(0).expect("image"));
    let shown = difference(&unlit, &lit);
    eprintln!(
        "renderer: the uploaded walls' maps change the image by {:.2} steps on average",
        shown.mean
    );
    // Measured 1.9 steps, as `pool_walls_match_the_cpu` measures on the CPU side.
    assert!(shown.mean > 0.5, "{}", shown.mean);
}

fn objects_match_the_cpu() {
    let ctx = test_gpu();
    // Measured: mean 0.000093 (4 channels one step), no outliers, no drift.
    check(&ctx, "objects", &small("objects"), true, EXACT);
}

/// The objects among a technique's receivers take their light from its light-space deposit, as
/// a shadow map is read (yuksel's CPU twin on the objects scene: the diffuse teapot, ball and box
/// in its receivers' map): the deposit's light moves the image against the flat water's on the
/// objects, the same on both sides.
fn objects_lit_from_the_deposit_match_the_cpu() {
    use caustics_core::techniques::{Job, Spec};
    let ctx = test_gpu();
    let scene = small("objects");
    let water = scene.water.as_ref().expect("water");
    let surface = water.surface_at(scene.time).expect("surface");
    // Both images read the water as the GPU does: sampled on the final image's lattice.
    let grid = water_grid(&scene, surface.as_ref()).expect("water");
    let spec: Spec = "yuksel".parse().expect("yuksel");
    let out = spec
        .run_cpu(&Job::new(&scene, Some(surface.as_ref()), 2), &|_, _| {})
        .expect("yuksel");
    assert!(
        out.light.is_some(),
        "the objects are among yuksel's receivers"
    );
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let cpu = render(
        &scene,
        Some(surface.as_ref()),
        Some(out.lighting()),
        None,
        &options,
        &|_, _| {},
    );
    let floor = out.caustics.caustics();
    let flat = render(
        &scene,
        Some(surface.as_ref()),
        Some(floor),
        None,
        &options,
        &|_, _| {},
    );
    let lit = difference(&flat, &cpu);
    eprintln!(
        "objects from the deposit: the objects' light moves the CPU image by {:.2} steps on average",
        lit.mean
    );
    assert!(lit.mean > 0.3, "the deposit's light shows: {}", lit.mean);
    let gpu = FinalImage::new(&ctx)
        .expect("pipeline")
        .render(
            &ctx,
            &scene,
            Some(&grid),
            Some(out.lighting()),
            None,
            &options,
            None,
        )
        .expect("GPU render");
    let gpu_flat = FinalImage::new(&ctx)
        .expect("pipeline")
        .render(&ctx, &scene, Some(&grid), Some(floor), None, &options, None)
        .expect("GPU render");
    // What the deposit changes in each image, GPU against CPU: the floor's rounding (the same
    // floor map on both sides, 0.10 steps on average between them) cancels and the objects' light
    // remains, on the channels it changed.
    let change = |a: &Image, b: &Image| -> Vec<i32> {
        a.rgb
            .iter()
            .zip(&b.rgb)
            .map(|(&x, &y)| x as i32 - y as i32)
            .collect()
    };
    let (on_cpu, on_gpu) = (change(&cpu, &flat), change(&gpu, &gpu_flat));
    let off: Vec<i32> = on_cpu
        .iter()
        .zip(&on_gpu)
        .filter(|(c, _)| **c != 0)
        .map(|(c, g)| (c - g).abs())
        .collect();
    let mean = off.iter().sum::<i32>() as f64 / off.len().max(1) as f64;
    let far = off.iter().filter(|&&d| d > 2).count() as f64 / off.len().max(1) as f64;
    eprintln!(
        "objects from the deposit: {} channels lit by it; its change GPU against CPU {mean:.4} \
         steps on average, {:.3} % of them more than 2 steps off, worst {}",
        off.len(),
        100.0 * far,
        off.iter().max().unwrap_or(&0)
    );
    assert!(off.len() > 100, "{} channels", off.len());
    // Measured on lavapipe: 1341 channels, 0.204 steps on average (the change itself averages
    // about 12 steps there), 0.52 % beyond 2 steps (pixels where one side's depth test flips at
    // an object's edge), the worst 10.
    assert!(
        mean <= 0.6 && far <= 0.016,
        "mean {mean}, {far} beyond 2 steps"
    );
}

fn glass_matches_the_cpu() {
    let ctx = test_gpu();
    // Measured: mean 0.000232, outliers 0.0139 % (2 pixels), drift 0.0139 % (6 channels).
    let bounds = Bounds {
        mean: 0.0023,
        outliers: 0.00139,
        drift: 0.00139,
    };
    check(&ctx, "glass", &small("glass"), false, bounds);
}

/// The floor map's pyramid the frame builds on the GPU (`caustics_mips.wgsl`) is the CPU's
/// (`CausticsMap::pyramid`), level for level, for a map of odd sizes (the last row and column
/// clamped as on the CPU).
fn the_frames_pyramid_is_the_cpus() {
    let ctx = test_gpu();
    let scene = small("pool");
    let (surface, _) = inputs(&scene);
    let map = odd_map(scene.water.as_ref().expect("water").size);
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let final_image = FinalImage::new(&ctx).expect("pipeline");
    let grid = surface.expect("water");
    let heights = heights_texture(&ctx, &grid);
    let water = WaterTextures::of(&heights);
    let texture = caustics_gpu::final_image::upload_map(&ctx, &map).expect("map");
    let frame = final_image
        .frame(
            &ctx,
            &scene,
            ImageInputs {
                water: Some(&water),
                caustics: Some(Output::Floor(&texture)),
                ..Default::default()
            },
            &options,
        )
        .expect("frame");
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame"),
        });
    frame.encode(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    let gpu = frame.read_pyramid(&ctx).expect("pyramid");
    assert_is_the_pyramid(&gpu, &map);
}

/// A 37 x 20 map (odd and even sides) of hashed values.
fn odd_map(size: f64) -> CausticsMap {
    let mut map = CausticsMap::new(37, 20, size);
    for (k, t) in map.texels.iter_mut().enumerate() {
        let v = ((k * 2_654_435_761) % 1000) as f32 / 250.0;
        *t = [v, 2.0 * v, 1.0];
    }
    map
}

/// `gpu` (the levels below level 0, each with its width) equals `map`'s pyramid to the bit.
fn assert_is_the_pyramid(gpu: &[(u32, Vec<[f32; 4]>)], map: &CausticsMap) {
    let cpu = map.pyramid();
    assert_eq!(gpu.len(), cpu.levels.len() - 1);
    for (k, ((w, g), c)) in gpu.iter().zip(&cpu.levels[1..]).enumerate() {
        assert_eq!(
            (*w as usize, g.len()),
            (c.width, c.texels.len()),
            "level {}",
            k + 1
        );
        for (a, b) in g.iter().zip(&c.texels) {
            // The same f32 additions in the same order: measured equal to the bit.
            assert_eq!([a[0], a[1], a[2]], *b, "level {}", k + 1);
        }
    }
}

/// A map texture with its own mip chain (the Bevy plugin's floor image) filled in place from its
/// mip 0, copied in by the same encoder as the plugin copies a technique's map: each mip the CPU's
/// pyramid level, twice over (under `CAUSTICS_VALIDATION=1` the layer sees each mip in the layout
/// its pass needs, frame after frame).
fn a_maps_own_mips_are_its_pyramid() {
    let ctx = test_gpu();
    let map = odd_map(1.0);
    let levels = caustics_core::map::pyramid_levels(map.width, map.height) as u32;
    let size = (map.width as u32, map.height as u32);
    let chain = |label, levels| {
        caustics_gpu::map_mips::mip_chain(
            &ctx,
            label,
            size,
            levels,
            wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::COPY_SRC,
        )
    };
    let (source, texture) = (chain("technique's map", 1), chain("map with mips", levels));
    caustics_gpu::final_image::write_map(&ctx, &source, &map);
    let pipeline = caustics_gpu::map_mips::mips_pipeline(&ctx);
    let mips = caustics_gpu::map_mips::MapMips::in_place(&ctx, &pipeline, &texture);
    assert_eq!(mips.len() as u32, levels - 1);
    for _ in 0..2 {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_texture(
            source.as_image_copy(),
            texture.as_image_copy(),
            source.size(),
        );
        mips.encode_pass(&mut encoder, "mips");
        ctx.queue.submit([encoder.finish()]);
        ctx.check().expect("no validation message");
    }
    let gpu: Vec<(u32, Vec<[f32; 4]>)> = (1..levels)
        .map(|k| {
            let w = texture
                .size()
                .mip_level_size(k, wgpu::TextureDimension::D2)
                .width;
            (w, ctx.read_texture_mip(&texture, 0, k).expect("mip"))
        })
        .collect();
    assert_is_the_pyramid(&gpu, &map);
}

/// Terrain (read through the clamped bicubic), sand, open sea beyond the surface's slab.
fn shore_matches_the_cpu() {
    let ctx = test_gpu();
    // Measured: mean 0.000671, outliers 0.0139 % (2 pixels), drift 0.0139 % (6 channels), the
    // water met by the march that no crest can pass (0.000694, 1 outlier and 2 channels, before).
    let bounds = Bounds {
        mean: 0.0062,
        ..EXACT
    };
    check(&ctx, "shore", &small("shore"), true, bounds);
}

/// The shore at 2 x 2 samples a pixel: the rotated grid (`sample_offset`) and each sample's
/// footprint, half a pixel's, on both sides.
fn shore_at_two_by_two_samples_matches_the_cpu() {
    let ctx = test_gpu();
    // Measured: mean 0.002616, 3 pixels outliers, 20 channels drifting (four samples a pixel,
    // each with the f32 departures the one-sample image shows: 2 outliers, 6 drifting; at a
    // grazing ray's crest f32 and f64 may stop on different sides of a crest's tip).
    let bounds = Bounds {
        mean: 0.0145,
        outliers: 20.0 * PIXEL,
        drift: 40.0 * CHANNEL,
    };
    check(&ctx, "shore 2x2", &small("shore"), true, bounds);
}

/// The waves' normals filtered by each sample's footprint (`RenderOptions::filter_water`) on
/// both sides: the slope moments' pyramid, the taps along the footprint, the visible facets'
/// Fresnel split and the glint; the far water, where the filter acts, fills the top third of the
/// shore's picture.
fn shore_with_filtered_water_matches_the_cpu() {
    let ctx = test_gpu();
    // Measured: mean 0.000440, no outlier, no channel drifting (the far water's normals are the
    // pyramid's, smooth, where the exact ones leave f32 and f64 on different sides of a crest).
    let bounds = Bounds {
        mean: 0.0044,
        ..EXACT
    };
    check(&ctx, "shore filtered", &small("shore"), true, bounds);
    // The water's edge clamped rather than periodic: the pyramid's edge rule on both sides.
    // Measured: mean 0.000347, no outlier, no channel drifting.
    let mut clamped = small("shore");
    clamped.water.as_mut().expect("water").wrap = false;
    check(&ctx, "shore filtered, clamped", &clamped, true, bounds);
    // A low sun in front: the far water's glint, the roughness's lobe, fills the band under the
    // horizon. Measured: mean 0.001343, no outlier, no channel drifting.
    let mut glint = small("shore");
    glint.light.direction = glam::DVec3::new(0.85, -0.46, -0.4).normalize();
    check(&ctx, "shore filtered, sun in front", &glint, true, bounds);
    // From under the water: the surface met from below takes the filtered mean normal.
    // Measured: mean 0.000301, no outlier, no channel drifting.
    check(
        &ctx,
        "underwater filtered",
        &small("underwater"),
        true,
        bounds,
    );
}

/// A frame built without the filter takes it through `update` alone: the slope moments' pyramid
/// is made then, once, and the image is the one a frame built filtered renders.
fn a_frame_takes_the_filter_through_update() {
    let ctx = test_gpu();
    let scene = small("shore");
    let (surface, map) = inputs(&scene);
    let grid = surface.expect("water");
    let map = map.expect("map");
    let plain = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let filtered = RenderOptions {
        filter_water: true,
        ..plain
    };
    let final_image = FinalImage::new(&ctx).expect("pipeline");
    let expected = final_image
        .render(
            &ctx,
            &scene,
            Some(&grid),
            Some(Caustics::Floor(&map)),
            None,
            &filtered,
            None,
        )
        .expect("filtered render");
    let heights = heights_texture(&ctx, &grid);
    let water = WaterTextures::of(&heights);
    let texture = caustics_gpu::final_image::upload_map(&ctx, &map).expect("map");
    let mut frame = final_image
        .frame(
            &ctx,
            &scene,
            ImageInputs {
                water: Some(&water),
                caustics: Some(Output::Floor(&texture)),
                ..Default::default()
            },
            &plain,
        )
        .expect("frame");
    assert!(frame.read_slopes(&ctx).expect("slopes").is_empty());
    let draw = |frame: &caustics_gpu::final_image::FinalImageFrame| {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        frame.encode(&mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
        read_image(&ctx, frame.output())
    };
    let unfiltered = draw(&frame);
    let before = ctx.traffic();
    frame.update(&ctx, &scene, &filtered);
    let made = ctx.traffic().since(&before).created();
    let image = draw(&frame);
    assert!(made > 0, "the pyramid is made by the update");
    assert!(image.rgb == expected.rgb, "the filtered frame's image");
    assert!(unfiltered.rgb != image.rgb, "the filter changes the image");
    let before = ctx.traffic();
    frame.update(&ctx, &scene, &plain);
    let off = ctx.traffic().since(&before).created();
    let again = draw(&frame);
    let before = ctx.traffic();
    frame.update(&ctx, &scene, &filtered);
    let on = ctx.traffic().since(&before).created();
    assert_eq!((off, on), (0, 0), "made once");
    assert!(again.rgb == unfiltered.rgb, "the filter turned off again");
}

/// The pyramid of the water's slope moments the frame builds on the GPU
/// (`final_image::slopes`) is the CPU's (`SlopePyramid`), level for level, for the shore's
/// waves on a lattice of odd sides, periodic.
fn the_frames_slope_moments_are_the_cpus() {
    use caustics_core::water::slopes::SlopePyramid;
    let ctx = test_gpu();
    let mut scene = small("shore");
    scene.water.as_mut().expect("water").wrap = true;
    let water = scene.water.as_ref().expect("water");
    let surface = water.surface_at(scene.time).expect("surface");
    let grid = GridSurface {
        grid: caustics_core::water::sample_grid(surface.as_ref(), 45, 38, water.size),
        size: water.size,
        edge: water.edge(),
    };
    let options = RenderOptions {
        supersampling: 1,
        filter_water: true,
        ..Default::default()
    };
    let final_image = FinalImage::new(&ctx).expect("pipeline");
    let heights = heights_texture(&ctx, &grid);
    let textures = WaterTextures::of(&heights);
    let frame = final_image
        .frame(
            &ctx,
            &scene,
            ImageInputs {
                water: Some(&textures),
                ..Default::default()
            },
            &options,
        )
        .expect("frame");
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame"),
        });
    frame.encode(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    let gpu = frame.read_slopes(&ctx).expect("slopes");
    let cpu = SlopePyramid::new(&grid, 45, 38, water.size, water.edge());
    assert_eq!(gpu.len(), cpu.levels());
    // Each moment against the scale of its kind at level 0 (the largest |E[h_x]| for the slopes,
    // the largest E[h_x²] for the second moments): coarser levels average the mean slope toward 0.
    let (_, _, finest) = cpu.level(0);
    let most = |m: usize| finest.iter().map(|t| t[m].abs()).fold(1e-30, f64::max);
    let (slope, second) = (most(0).max(most(1)), most(2).max(most(3)));
    let scale = [slope, slope, second, second, second];
    let mut worst: f64 = 0.0;
    for (k, level) in gpu.iter().enumerate() {
        let (cols, rows, texels) = cpu.level(k);
        assert_eq!(level.len(), cols * rows, "level {k}");
        for (g, c) in level.iter().zip(texels) {
            for m in 0..5 {
                worst = worst.max((g[m] as f64 - c[m]).abs() / scale[m]);
            }
        }
    }
    eprintln!("slope moments: GPU against CPU within {worst:.2e} of each moment's scale");
    // Measured: 2.72e-6 (f32 against f64 over 16 gradients a texel and the halvings).
    assert!(worst < 2.7e-5, "{worst}");
}

/// Technique `cascaded` on the pool with its walls: no wall maps, the final image reads
/// the eye-space image on the walls as on the floor, on both sides; the walls the low sun lights
/// are brighter than without caustics.
fn pool_with_cascaded_lights_the_walls_as_the_cpu() {
    use caustics_core::techniques::cascaded::{self, CascadedParams, CascadedSetup};
    let ctx = test_gpu();
    let mut scene = small("pool");
    scene.light.direction = glam::DVec3::new(0.8, 0.6, -0.6).normalize();
    let (surface, _) = inputs(&scene);
    let params = CascadedParams {
        resolution: 256,
        ..Default::default()
    };
    let setup = CascadedSetup::from_scene(&scene, &params).expect("setup");
    let water = cascaded::water_grid(&scene, 128).expect("water grid");
    let frame = cascaded::caustics(&setup, &water, None);
    let eye = EyeSpaceCaustics {
        width: setup.eye.width,
        height: setup.eye.height,
        texels: frame.image,
    };
    let surface = surface.as_ref().map(|s| s as &dyn Surface);
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    // The image's wall texels alone, and none: the walls' share of the picture.
    let (w, e) = (setup.eye.width, &setup.eye);
    let on_wall = |k: usize| {
        let t = frame.eye[k];
        let (x, y) = ((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
        t[3] != 0.0
            && setup
                .receiver_normal(e.position + e.ray(x, y) * t[0] as f64)
                .z
                == 0.0
    };
    let (mut walls, mut dark) = (eye.clone(), eye.clone());
    for (k, t) in walls.texels.iter_mut().enumerate() {
        if !on_wall(k) {
            *t = [0.0, 0.0, 0.0, t[3]];
        }
    }
    for t in &mut dark.texels {
        *t = [0.0, 0.0, 0.0, t[3]];
    }
    let render = |c: &EyeSpaceCaustics| {
        render(
            &scene,
            surface,
            Some(Caustics::EyeSpace(c)),
            None,
            &options,
            &|_, _| {},
        )
    };
    let d = difference(&render(&dark), &render(&walls));
    eprintln!(
        "pool, cascaded: its light on the walls changes the CPU image by {:.2} steps on average",
        d.mean
    );
    assert!(d.mean > 0.5, "{}", d.mean);
    check_caustics(
        &ctx,
        "pool-cascaded",
        &scene,
        surface,
        Some(Caustics::EyeSpace(&eye)),
        // Measured: mean 0.000509 (a far deck pixel 7 steps off), no outlier; the walls' share of cascaded's
        // light moves the image by 1.89 steps.
        Bounds {
            mean: 0.0007,
            ..EXACT
        },
    );
}

/// Technique `cascaded`: caustics in the camera's screen space, read where each refracted view
/// ray's floor point projects. The eye-space image is the CPU twin's (`cascaded_gpu.rs` holds the
/// GPU's to it), made for the final image's camera and size.
fn shore_with_cascaded_eye_space_caustics_matches_the_cpu() {
    use caustics_core::techniques::cascaded::{self, CascadedParams, CascadedSetup};
    let ctx = test_gpu();
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
    check_caustics(
        &ctx,
        "shore-cascaded",
        &scene,
        surface,
        Some(Caustics::EyeSpace(&eye)),
        // Measured: mean 0.000625, outliers 0.0139 % (2 pixels), drift 0.0139 % (6 channels).
        Bounds {
            mean: 0.0062,
            ..EXACT
        },
    );
    // The caustics show: the image departs from the one lit as under flat water.
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let with = render(
        &scene,
        surface,
        Some(Caustics::EyeSpace(&eye)),
        None,
        &options,
        &|_, _| {},
    );
    let flat = render(&scene, surface, None, None, &options, &|_, _| {});
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
fn albedo_image_without_a_map_matches_the_cpu() {
    let ctx = test_gpu();
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
    // Measured: mean 0.000440 (one pixel of the far deck 6 steps off), no outlier, one channel
    // drifting.
    check(&ctx, "albedo-image", &scene, false, DECK);
}

/// No water, a map of the light through the glass (as caustic-triangles makes it): every object
/// shadows the sun and the map adds the transmitted light, on both sides alike.
fn glass_with_an_air_caustics_map_matches_the_cpu() {
    let ctx = test_gpu();
    let scene = small("glass");
    let n = 64;
    let grid = caustics_core::grid::Grid::from_fn(n, n, |i, j| {
        let p = glam::DVec2::new(j as f64 + 0.5, i as f64 + 0.5) / n as f64
            - glam::DVec2::new(0.45, 0.55);
        (3.0 * (-p.length_squared() / 0.004).exp()) as f32
    });
    let map = CausticsMap::from_grid(&grid, scene.size);
    // Measured: mean 0.000162, outliers 0.0139 % (2 pixels), drift 0.0139 % (6 channels).
    let bounds = Bounds {
        mean: 0.0016,
        outliers: 0.00139,
        drift: 0.0021,
    };
    check_map(&ctx, "glass-air-caustics", &scene, None, Some(map), bounds);
}

/// Glass under water: the reflected and refracted branches under the surface, up to the CPU's
/// recursion depth.
fn glass_under_water_matches_the_cpu() {
    let ctx = test_gpu();
    let mut scene = small("objects");
    for obj in &mut scene.objects {
        obj.material = Material::Glass {
            ior: 1.5,
            tint: glam::DVec3::new(0.9, 0.95, 1.0),
        };
    }
    // Measured: mean 0.019745, no outliers, drift 0.419 % (the drift ceiling, 2 %, is 5 times it).
    let bounds = Bounds {
        mean: 0.2,
        outliers: 10.0 * PIXEL,
        drift: DRIFT_FRACTION,
    };
    check(&ctx, "glass-under-water", &scene, true, bounds);
}

/// A camera under the surface (the built-in `underwater`): the primary rays start in the water,
/// the surface seen from below splits them into Snell's window and the totally reflected mirror.
fn underwater_matches_the_cpu() {
    let ctx = test_gpu();
    // Measured with the daylight sky (docs/maintainers/look.md): 20 channels one step off (mean 0.000463
    // steps: the sky's exp and acos in f32 against f64, seen through Snell's window and in the
    // reflections), no outliers, no channel off by more than one; 10x that in the mean.
    const UNDERWATER: Bounds = Bounds {
        mean: 200.0 * CHANNEL,
        ..EXACT
    };
    check(&ctx, "underwater", &small("underwater"), true, UNDERWATER);
}

/// The heights `surface` takes on the GPU (the grid [`FinalImage::render`] uploads), as
/// a texture the techniques and the frame read.
fn heights_texture(ctx: &GpuContext, grid: &GridSurface) -> wgpu::Texture {
    ctx.upload_grid("water heights", &grid.grid)
        .expect("heights")
}

fn read_image(ctx: &GpuContext, texture: &wgpu::Texture) -> Image {
    let texels: Vec<[u8; 4]> = ctx.read_texture(texture).expect("readback");
    Image {
        width: texture.width(),
        height: texture.height(),
        rgb: texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

/// The frame of a real-time loop: built once, then frames with a moving camera and sun that
/// create nothing, read nothing back and upload only the uniform; the slab bound the GPU finds is
/// the CPU's; and the last frame's image is the CPU's for the last camera and sun.
fn a_frame_moves_its_camera_and_sun_through_uniforms_alone() {
    let ctx = test_gpu();
    let mut scene = small("objects");
    let (surface, map) = inputs(&scene);
    let (grid, map) = (surface.expect("water"), map.expect("map"));
    let heights = heights_texture(&ctx, &grid);
    let water = WaterTextures::of(&heights);
    let map_texture = caustics_gpu::final_image::upload_map(&ctx, &map).expect("map");
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let final_image = FinalImage::new(&ctx).expect("pipeline");
    let mut frame = final_image
        .frame(
            &ctx,
            &scene,
            ImageInputs {
                water: Some(&water),
                caustics: Some(Output::Floor(&map_texture)),
                ..Default::default()
            },
            &options,
        )
        .expect("frame");

    let target = scene.camera.target;
    let start = scene.camera.position - target;
    let sun = scene.light.direction;
    let frames = 10;
    let before = ctx.traffic();
    for k in 1..=frames {
        let a = 0.03 * k as f64;
        let (s, c) = a.sin_cos();
        scene.camera.position = target
            + glam::DVec3::new(
                c * start.x - s * start.y,
                s * start.x + c * start.y,
                start.z,
            );
        scene.light.direction =
            glam::DVec3::new(sun.x + 0.02 * k as f64, sun.y - 0.01 * k as f64, sun.z).normalize();
        frame.update(&ctx, &scene, &options);
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        frame.encode(&mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
    }
    ctx.wait().expect("frames");
    let spent = ctx.traffic().since(&before);
    eprintln!(
        "frame: {frames} frames created {}, uploaded {} bytes, read back {}",
        spent.created(),
        spent.uploaded_bytes,
        spent.readbacks
    );
    assert_eq!(spent.created(), 0, "resources created per frame: {spent:?}");
    assert_eq!(spent.readbacks, 0, "readbacks per frame: {spent:?}");
    assert!(
        spent.uploaded_bytes <= 4096 * frames,
        "more than 4096 bytes uploaded per frame: {spent:?}"
    );
    // A frame whose camera, sun and options stand still uploads nothing.
    let before = ctx.traffic();
    frame.update(&ctx, &scene, &options);
    assert_eq!(ctx.traffic().since(&before).uploaded_bytes, 0);

    let gpu = frame.read_slab(&ctx).expect("slab");
    let cpu = slab_bounds(&grid, grid.size);
    eprintln!("frame: slab GPU {gpu:?}, CPU {cpu:?}");
    // Measured: half height 0.026952596 against 0.026952597 and slope 0.43793103 against
    // 0.43793102, each within one f32 ulp (4.4e-8 and 2.9e-8 relative); bound 10 ulps.
    for (g, c, what) in [
        (gpu.half_height, cpu.half_height, "half height"),
        (gpu.slope, cpu.slope, "slope"),
    ] {
        assert!(
            (g - c).abs() <= 10.0 * f32::EPSILON as f64 * c,
            "slab {what}: GPU {g} vs CPU {c}"
        );
    }

    let gpu = read_image(&ctx, frame.output());
    let cpu = render(
        &scene,
        Some(&grid),
        Some(Caustics::Floor(&map)),
        None,
        &options,
        &|_, _| {},
    );
    // Measured: mean 0.000069, one outlier (a deck joint), one channel drifting.
    let bounds = Bounds {
        mean: 20.0 * CHANNEL,
        ..EXACT
    };
    hold("frame-moved", &cpu, &gpu, bounds, "after 10 frames");
}

/// The frame on a technique's own output texture (yuksel's floor map, never on the CPU) gives
/// the image `FinalImage::render` gives from the same map read back, and the map shows in it.
fn a_frame_reads_a_techniques_texture_as_render_with_reads_its_map() {
    let ctx = test_gpu();
    let scene = small("pool");
    let (surface, _) = inputs(&scene);
    let grid = surface.expect("water");
    let heights = heights_texture(&ctx, &grid);
    let water = WaterTextures::of(&heights);
    let mut technique =
        caustics_gpu::registry::create(&ctx, "yuksel", &toml::Table::new()).expect("yuksel");
    technique
        .configure(&ctx, &scene, &water)
        .expect("configure");
    technique.update(&ctx, &scene).expect("update");
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let final_image = FinalImage::new(&ctx).expect("pipeline");
    let mut frame = final_image
        .frame(
            &ctx,
            &scene,
            ImageInputs {
                water: Some(&water),
                caustics: technique.output(),
                ..Default::default()
            },
            &options,
        )
        .expect("frame");
    frame.update(&ctx, &scene, &options);
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("frame"),
        });
    technique.encode(&mut encoder, None);
    frame.encode(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    let from_texture = read_image(&ctx, frame.output());

    let Some(Output::Floor(map_texture)) = technique.output() else {
        panic!("yuksel makes a floor map");
    };
    let texels: Vec<[f32; 4]> = ctx.read_texture(map_texture).expect("map");
    let map = CausticsMap {
        width: map_texture.width() as usize,
        height: map_texture.height() as usize,
        size: grid.size,
        texels: texels.iter().map(|t| [t[0], t[1], t[2]]).collect(),
    };
    let surface = Some(&grid as &dyn Surface);
    let from_map = final_image
        .render(
            &ctx,
            &scene,
            surface,
            Some(Caustics::Floor(&map)),
            None,
            &options,
            None,
        )
        .expect("FinalImage::render");
    let d = difference(&from_map, &from_texture);
    eprintln!(
        "technique texture: mean |frame - render| {:.6} steps, largest {}",
        d.mean, d.max
    );
    // The same map, water and shader: the same codes, bit for bit.
    assert_eq!(
        d.max, 0,
        "the frame on the texture departs from FinalImage::render on its map"
    );

    let flat = final_image
        .render(&ctx, &scene, surface, None, None, &options, None)
        .expect("flat");
    let lit = difference(&flat, &from_texture);
    eprintln!(
        "technique texture: {:.2} % of channels differ from flat-water lighting by > 1 step",
        100.0 * lit.drift
    );
    assert!(
        lit.drift > 0.05,
        "the technique's caustics barely show: {}",
        lit.drift
    );

    let cpu = render(
        &scene,
        surface,
        Some(Caustics::Floor(&map)),
        None,
        &options,
        &|_, _| {},
    );
    hold(
        "technique-texture",
        &cpu,
        &from_texture,
        // Measured: mean 0.000486 (one pixel of the far deck 6 steps off), no outlier, one
        // channel drifting.
        DECK,
        "yuksel's map",
    );
}

/// The time of a full-size render (the scene's 960 x 540, 2 x 2 samples per pixel) on both sides.
/// Slow on a software adapter, so run on demand:
/// `cargo test --release -p caustics-gpu --test render_gpu -- --ignored --nocapture`.
fn full_size_render_times() {
    let ctx = test_gpu();
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
            let mut timer = GpuTimer::new(&ctx, 4);
            let gpu = final_image
                .render(
                    &ctx,
                    &scene,
                    surface,
                    map.as_ref().map(Caustics::Floor),
                    None,
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
                    .iter()
                    .find(|t| t.label == "final image")
                    .map_or("untimed".to_string(), |t| format!("{:.0} ms", t.ms))
            );
        }
        let started = std::time::Instant::now();
        render(
            &scene,
            surface,
            map.as_ref().map(Caustics::Floor),
            None,
            &options,
            &|_, _| {},
        );
        eprintln!("{name}: CPU {:.2} s", started.elapsed().as_secs_f64());
    }
}

test_main! {
    gpu pool_matches_the_cpu,
    gpu pool_with_a_concrete_deck_matches_the_cpu,
    gpu pool_walls_match_the_cpu,
    gpu the_renderer_lights_the_walls_with_uploaded_maps,
    gpu objects_match_the_cpu,
    gpu objects_lit_from_the_deposit_match_the_cpu,
    gpu glass_matches_the_cpu,
    gpu shore_matches_the_cpu,
    gpu shore_at_two_by_two_samples_matches_the_cpu,
    gpu shore_with_filtered_water_matches_the_cpu,
    gpu the_frames_slope_moments_are_the_cpus,
    gpu a_frame_takes_the_filter_through_update,
    gpu shore_with_cascaded_eye_space_caustics_matches_the_cpu,
    gpu pool_with_cascaded_lights_the_walls_as_the_cpu,
    gpu albedo_image_without_a_map_matches_the_cpu,
    gpu glass_with_an_air_caustics_map_matches_the_cpu,
    gpu glass_under_water_matches_the_cpu,
    gpu underwater_matches_the_cpu,
    gpu a_frame_moves_its_camera_and_sun_through_uniforms_alone,
    gpu a_frame_reads_a_techniques_texture_as_render_with_reads_its_map,
    gpu the_frames_pyramid_is_the_cpus,
    gpu a_maps_own_mips_are_its_pyramid,
    gpu_ignored full_size_render_times,
}
