//! Device limits: every registered technique, on a device created with smaller limits than the
//! adapter's, refuses a map, cube map, cascade or texture larger than the device allows with one
//! `GpuError::TooLarge` naming what, before wgpu sees it, and still configures at sizes that fit.
//! A GPU with a 2048 or 4096 texture limit (WebGPU's default is 8192) is what this stands for.

#[macro_use]
mod common;

use caustics_core::grid::Grid;
use caustics_core::scene::Scene;
use caustics_core::water::sample_grid;
use caustics_gpu::context::GpuOptions;
use caustics_gpu::registry::{self, REGISTRY};
use caustics_gpu::{GpuContext, GpuError, WaterTextures};

/// The device's largest texture side.
const MAX_2D: u32 = 1024;
/// The device's largest storage buffer binding: 16 MiB, an eighth of WebGPU's default.
const MAX_STORAGE: u64 = 16 << 20;

/// A device on the test adapter with `MAX_2D` and `MAX_STORAGE` in place of the adapter's limits,
/// wrapped as an application would wrap its own.
fn small_device() -> GpuContext {
    device_with(|adapter| wgpu::Limits {
        max_texture_dimension_2d: MAX_2D,
        max_storage_buffer_binding_size: MAX_STORAGE,
        ..adapter
    })
}

/// A device on the test adapter with the limits `limits` makes of the adapter's.
fn device_with(limits: impl Fn(wgpu::Limits) -> wgpu::Limits) -> GpuContext {
    let _ = caustics_gpu::context::test_gpu();
    let instance = GpuContext::instance(&GpuOptions::default()).unwrap();
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).unwrap();
    let limits = limits(adapter.limits());
    let features = adapter.features()
        & (wgpu::Features::FLOAT32_FILTERABLE | wgpu::Features::FLOAT32_BLENDABLE);
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("small limits"),
        required_features: features,
        required_limits: limits,
        ..Default::default()
    }))
    .unwrap();
    GpuContext::from_parts(instance, adapter, device, queue)
}

/// The built-in scene `name` with a `side`² caustics map and camera image.
fn scene(name: &str, side: u32) -> Scene {
    let mut s = Scene::builtin(name).unwrap();
    s.caustics.width = side;
    s.caustics.height = side;
    s.camera.width = side;
    s.camera.height = side;
    s
}

/// The scene each registered technique is tried on: glass objects where it takes them.
fn scene_for(name: &str) -> &'static str {
    match name {
        "caustic-triangles" => "glass",
        "volumes" => "objects",
        _ => "pool",
    }
}

/// Small parameters for the techniques whose defaults are large, so that the fitting case is fast.
const SMALL: &str = "volumes = { texture = 64, shadow = 128, planes = 5 }\n\
                     caustic-triangles = { photon_image = 64, cube_resolution = 64 }\n\
                     cascaded = { resolution = 128 }\n\
                     procedural = { mesh_resolution = 64, target_resolution = 128 }";

/// Create `name` with `params` over `SMALL` and configure it on `scene`.
fn configure(ctx: &GpuContext, name: &str, scene: &Scene, params: &str) -> Result<(), GpuError> {
    let mut table: toml::Table = SMALL.parse().unwrap();
    let over: toml::Table = params.parse().unwrap();
    for (k, v) in over {
        match (table.get_mut(&k), v) {
            (Some(toml::Value::Table(into)), toml::Value::Table(from)) => into.extend(from),
            (_, v) => {
                table.insert(k, v);
            }
        }
    }
    let mut t = registry::create(ctx, name, &table)?;
    // The water as large as the technique reads it, within the device's limit: the refusals
    // tested here are the technique's own.
    let (cols, rows) = t.water_resolution(scene);
    let (cols, rows) = (cols.min(MAX_2D), rows.min(MAX_2D));
    let grid = match &scene.water {
        Some(water) => {
            let surface = water.surface_at(scene.time).unwrap();
            sample_grid(surface.as_ref(), cols as usize, rows as usize, water.size)
        }
        // The glass scene has no water: a still surface stands in for the texture.
        None => Grid::from_fn(cols.max(1) as usize, rows.max(1) as usize, |_, _| 0.0),
    };
    let texture = ctx.upload_grid("heights", &grid)?;
    t.configure(ctx, scene, &WaterTextures::of(&texture))?;
    t.update(ctx, scene)?;
    ctx.wait()
}

/// `result` is one `TooLarge` whose `what` contains `names`.
fn assert_too_large(result: Result<(), GpuError>, case: &str, names: &str) {
    match result {
        Err(GpuError::TooLarge { what, size, limit }) => {
            assert!(
                what.contains(names),
                "{case}: names `{what}` ({size}, {limit})"
            );
        }
        Err(e) => panic!("{case}: expected TooLarge naming `{names}`, got: {e}"),
        Ok(()) => panic!("{case}: configured beyond the device's limits"),
    }
}

/// WebGPU's default limits (a browser's, unless a page asks for more): both yuksel variants run.
/// The scatter variant needs no workgroup memory; the gather it replaced needed 31,468 bytes, over
/// these limits' 16 KiB, and was refused here.
fn yuksel_runs_within_webgpus_default_limits() {
    let ctx = device_with(|_| wgpu::Limits::default());
    for technique in ["yuksel", "yuksel-targets"] {
        configure(&ctx, technique, &scene("pool", 64), "")
            .unwrap_or_else(|e| panic!("{technique}: {e}"));
    }
    ctx.check().expect("wgpu saw nothing");
}

/// A device whose textures are at most 256 a side: yuksel's pre-pass texture for a 96 x 64 map
/// (its capacity over the levels: 624 x 496 texels) is cut into 3 x 2 layers of 208 x 248, every
/// pixel's 4 x 4 samples reach into the second row of layers, and the map is to the bit the one a
/// device holding it whole makes (and it is not flat water's).
fn yuksel_tiles_a_prepass_wider_than_the_device() {
    use caustics_core::techniques::yuksel::{YukselParams, YukselSetup};
    use caustics_gpu::yuksel::{PrepassTiling, Variant, Yuksel};
    let small = device_with(|adapter| wgpu::Limits {
        max_texture_dimension_2d: 256,
        ..adapter
    });
    let full = device_with(|adapter| adapter);
    let (n, rows) = (96, 64);
    let heights = Grid::from_fn(n, rows, |i, j| {
        let (x, y) = ((j as f64 + 0.5) / n as f64, (i as f64 + 0.5) / rows as f64);
        let tau = std::f64::consts::TAU;
        (0.004 * (tau * (3.0 * x + y)).sin() + 0.002 * (tau * (-2.0 * x + 5.0 * y)).sin()) as f32
    });
    // The pool's depth and sun on the unit square, a map of `w` x `h`.
    let setup_of = |w: usize, h: usize| {
        YukselSetup::new(
            // Every pixel 4 x 4: the pre-pass fills its texture's second row of tiles.
            &YukselParams {
                split: 0.0,
                ..Default::default()
            },
            w,
            h,
            1.0,
            0.35,
            1.333,
            glam::DVec3::ZERO,
            true,
            glam::DVec3::new(0.3, 0.1, -1.0).normalize(),
        )
        .unwrap()
    };
    let setup = setup_of(n, rows);
    assert_eq!(
        PrepassTiling::new((624, 496), 256),
        PrepassTiling {
            tiles: (3, 2),
            tile: (208, 248)
        }
    );
    let map = |ctx: &GpuContext| {
        Yuksel::new(ctx)
            .unwrap()
            .caustics(ctx, &setup, &heights, Variant::RenderTargets, None)
            .unwrap()
    };
    let (tiled, whole) = (map(&small), map(&full));
    assert_eq!(tiled.texels, whole.texels);
    let max = whole.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
    assert!(max > 1.1, "the waves focus: {max}");
    // The pixels' spans are not tiled: a map within the device whose width plus the region's
    // N − 1 columns is beyond it is refused by name, before wgpu sees it.
    let wide = setup_of(240, 64);
    let refused = Yuksel::new(&small)
        .unwrap()
        .caustics(&small, &wide, &heights, Variant::RenderTargets, None)
        .map(|_| ());
    assert_too_large(refused, "240 x 64 map", "pre-pass spans");
    small.check().expect("wgpu saw nothing");
}

fn every_technique_fits_a_small_map_and_refuses_one_beyond_the_limit() {
    let ctx = small_device();
    assert_eq!(ctx.limits().max_texture_dimension_2d, MAX_2D);
    for r in REGISTRY {
        let home = scene_for(r.name());
        configure(&ctx, r.name(), &scene(home, 64), "")
            .unwrap_or_else(|e| panic!("{} at 64²: {e}", r.name()));
        // A map (or, for the eye-space technique, a screen image) one texel past the limit.
        let result = configure(&ctx, r.name(), &scene(home, MAX_2D + 1), "");
        let names = if r.name() == "cascaded" {
            "screen"
        } else {
            "map"
        };
        assert_too_large(result, r.name(), names);
        // Nothing reached wgpu's validation: the refusal came first.
        ctx.check()
            .unwrap_or_else(|e| panic!("{}: wgpu saw it: {e}", r.name()));
    }
}

fn cascades_cube_maps_and_technique_textures_beyond_the_limit_are_refused() {
    let ctx = small_device();
    let cases = [
        (
            "cascaded",
            "cascaded = { resolution = 2048 }",
            "cascaded caustic map",
        ),
        (
            "procedural-texture",
            "procedural = { target_resolution = 2048 }",
            "texture-space target",
        ),
        (
            "volumes",
            "volumes = { texture = 2048 }",
            "volumes depth texture",
        ),
        ("volumes", "volumes = { shadow = 2048 }", "shadow"),
        (
            "caustic-triangles",
            "caustic-triangles = { cube_resolution = 1024 }",
            "distance map",
        ),
        (
            "caustic-triangles",
            "caustic-triangles = { photon_image = 2048 }",
            "photon image",
        ),
    ];
    for (name, params, names) in cases {
        let result = configure(&ctx, name, &scene(scene_for(name), 64), params);
        assert_too_large(result, &format!("{name} with {params}"), names);
        ctx.check()
            .unwrap_or_else(|e| panic!("{name} with {params}: wgpu saw it: {e}"));
    }
}

/// The GPU frame on `ctx` with `scene`'s water.
fn renderer_with_water(ctx: &GpuContext, scene: &Scene) -> caustics_gpu::renderer::Renderer {
    use caustics_gpu::renderer::{FrameWater, Renderer};
    let mut renderer = Renderer::new(ctx).expect("renderer");
    renderer
        .set_water(ctx, scene.water.as_ref(), &FrameWater::Scene)
        .expect("water");
    renderer
}

/// A side running technique `name` with the parameter tables `params` (TOML).
fn spec(name: &str, params: &str) -> Option<caustics_gpu::renderer::TechniqueSpec> {
    Some(caustics_gpu::renderer::TechniqueSpec {
        name: name.into(),
        params: params.parse().unwrap(),
    })
}

/// One side of the split frame asks for a water grid beyond the device (`procedural-texture`
/// reads the water at its 2048² target): that side fails with the size named, the other renders
/// on, and the frame goes on being drawn: a size error is the side's, never the viewer's end.
fn a_side_beyond_the_device_fails_alone() {
    use caustics_core::render::RenderOptions;
    use caustics_gpu::renderer::WaterClock;
    let ctx = small_device();
    let scene = scene("pool", 64);
    let mut renderer = renderer_with_water(&ctx, &scene);
    renderer.set_techniques(
        &ctx,
        &[
            spec("yuksel", ""),
            spec(
                "procedural-texture",
                "procedural = { target_resolution = 2048 }",
            ),
        ],
    );
    for frame in 0..3 {
        let clock = WaterClock {
            time: frame as f64 / 30.0,
            amplitude: 1.0,
            steps: 0,
        };
        renderer
            .render(&ctx, &scene, clock, &RenderOptions::default())
            .unwrap_or_else(|e| panic!("frame {frame}: one side's size ended the frame: {e}"));
        assert_eq!(renderer.error(0), None, "frame {frame}");
        assert!(renderer.caustics(0).is_some() && renderer.image(0).is_some());
        let error = renderer.error(1).expect("the side beyond the device fails");
        assert!(
            error.contains("water height texture") && error.contains("2048"),
            "{error}"
        );
        assert!(renderer.caustics(1).is_none());
    }
    ctx.check().expect("wgpu saw nothing");
}

/// A device lost mid-run (here destroyed, as a driver reset or a removed GPU would lose it) gives
/// `GpuError::DeviceLost` from the next frame, from a technique created or configured after it,
/// from a readback and from a wait on the queue: one error naming the loss, never a panic and never a validation
/// error about the resources the lost device no longer holds.
fn a_lost_device_gives_device_lost_errors() {
    use caustics_core::render::RenderOptions;
    use caustics_gpu::renderer::WaterClock;
    let ctx = small_device();
    let scene = scene("pool", 64);
    let mut renderer = renderer_with_water(&ctx, &scene);
    let spec = |name: &str| spec(name, SMALL);
    renderer.set_techniques(&ctx, &[spec("yuksel"), spec("procedural")]);
    let clock = |time| WaterClock {
        time,
        amplitude: 1.0,
        steps: 0,
    };
    let options = RenderOptions::default();
    renderer
        .render(&ctx, &scene, clock(0.0), &options)
        .expect("a frame before the loss");
    ctx.wait().expect("the frame before the loss finishes");
    assert_eq!(renderer.error(0), None);

    let map = renderer
        .caustics(0)
        .expect("yuksel's map")
        .texture()
        .clone();

    ctx.device.destroy();
    let lost = |what: &str, r: Result<(), GpuError>| match r {
        Err(GpuError::DeviceLost(reason)) => eprintln!("{what}: device lost ({reason})"),
        other => panic!("{what}: expected DeviceLost, got {other:?}"),
    };
    lost(
        "the next frame",
        renderer.render(&ctx, &scene, clock(0.1), &options),
    );
    lost(
        "a frame after that",
        renderer.render(&ctx, &scene, clock(0.2), &options),
    );
    renderer.set_techniques(&ctx, &[spec("volumes")]);
    lost(
        "a technique switched to after the loss",
        renderer.render(&ctx, &scene, clock(0.3), &options),
    );
    lost(
        "a technique configured after the loss",
        configure(&ctx, "yuksel", &scene, ""),
    );
    lost(
        "reading a map back",
        ctx.read_rgba_f32(&map)
            .map(|texels| assert!(texels.is_empty())),
    );
    lost("waiting on the queue", ctx.wait());
}

test_main! {
    gpu yuksel_runs_within_webgpus_default_limits,
    gpu yuksel_tiles_a_prepass_wider_than_the_device,
    gpu every_technique_fits_a_small_map_and_refuses_one_beyond_the_limit,
    gpu cascades_cube_maps_and_technique_textures_beyond_the_limit_are_refused,
    gpu a_side_beyond_the_device_fails_alone,
    gpu a_lost_device_gives_device_lost_errors,
}
