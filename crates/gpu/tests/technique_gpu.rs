//! The `Technique` interface: every registered technique through it against its CPU twin, and the
//! steady state of a real-time frame (nothing created, nothing read back, a few uniform bytes up).

#[macro_use]
mod common;
#[path = "../examples/minimal.rs"]
#[allow(dead_code)]
mod minimal;

use caustics_core::grid::Grid;
use caustics_core::scene::Scene;
use caustics_core::techniques::yuksel::{self, YukselParams, YukselSetup};
use caustics_core::water::sample_grid;
use caustics_gpu::context::test_gpu;
use caustics_gpu::registry::{self, REGISTRY};
use caustics_gpu::{GpuContext, Output, WaterTextures};
use glam::DVec3;

/// The pool with a 64² map, its surface sampled at `resolution`.
fn pool(resolution: (u32, u32)) -> (Scene, Grid) {
    let mut scene = Scene::builtin("pool").unwrap();
    scene.caustics.width = 64;
    scene.caustics.height = 64;
    let water = scene.water.as_ref().unwrap();
    let surface = water.surface_at(scene.time).unwrap();
    let grid = sample_grid(
        surface.as_ref(),
        resolution.0 as usize,
        resolution.1 as usize,
        water.size,
    );
    (scene, grid)
}

fn read_floor(ctx: &GpuContext, out: Output) -> Vec<[f32; 4]> {
    match out {
        Output::Floor(t) => ctx.read_texture(t).unwrap(),
        Output::EyeSpace(_) => panic!("yuksel makes a floor map"),
    }
}

fn the_registry_names_are_unique_and_unknown_names_are_refused() {
    for (k, r) in REGISTRY.iter().enumerate() {
        assert!(
            REGISTRY[..k].iter().all(|o| o.name() != r.name()),
            "{} twice",
            r.name()
        );
    }
    let ctx = test_gpu();
    let err = registry::create(&ctx, "no-such", &toml::Table::new())
        .err()
        .expect("refused");
    assert!(err.to_string().contains("no-such") && err.to_string().contains("yuksel"));
    let mut misnamed = toml::Table::new();
    misnamed.insert(
        "yuksel-targets".into(),
        toml::Value::Table(toml::Table::new()),
    );
    let err = registry::create(&ctx, "yuksel-targets", &misnamed)
        .err()
        .expect("a table named after no technique is refused");
    assert!(err.to_string().contains("yuksel-targets"), "{err}");
    let err = registry::from_spec(&ctx, "yuksel:no_such_key=1")
        .err()
        .expect("refused");
    assert!(err.to_string().contains("no_such_key"), "{err}");
}

/// The README's example (`examples/minimal.rs`): an application's own device, heights and floor
/// pass around one technique named by its spec. Its floor averages what flat water gives (the
/// map's flux conserved; the brightest caustics clip at 255), and the waves focus light.
fn the_minimal_example_lights_its_floor() {
    for spec in ["yuksel", "caustic-triangles"] {
        let red: Vec<f64> = minimal::floor(spec, 128)
            .unwrap()
            .iter()
            .map(|p| p[0] as f64)
            .collect();
        let mean = red.iter().sum::<f64>() / red.len() as f64;
        let brightest = red.iter().cloned().fold(0.0, f64::max);
        println!("minimal {spec}: mean red {mean:.2}, brightest {brightest}");
        // Flat water gives 0.4 * 0.9 * 255 = 91.8 everywhere; measured 91.80 (yuksel) and 91.74
        // (caustic-triangles) on lavapipe, brightest 173 and 170.
        assert!((mean - 91.8).abs() < 0.6, "{spec}: mean {mean}");
        assert!(brightest > 1.5 * 91.8, "{spec}: brightest {brightest}");
    }
}

/// The README's wgpu snippet is lines of the minimal example, which the test above runs: each of
/// its lines that is not a comment is one of the example's, in the example's order.
fn the_readme_shows_lines_of_the_minimal_example() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let example = include_str!("../examples/minimal.rs");
    let shown: Vec<&str> = readme
        .lines()
        .skip_while(|l| *l != "## In your own wgpu code")
        .skip_while(|l| *l != "```rust")
        .skip(1)
        .take_while(|l| *l != "```")
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("//"))
        .collect();
    assert!(
        shown.len() > 10,
        "{} lines in the README's snippet",
        shown.len()
    );
    let mut lines = example.lines().map(str::trim);
    for line in &shown {
        assert!(
            lines.any(|l| l == *line),
            "README.md's wgpu snippet: `{line}` is not the next line of examples/minimal.rs"
        );
    }
}

fn yuksel_through_the_interface_matches_its_cpu_twin() {
    let ctx = test_gpu();
    // The pool's own sun, and one 80 degrees from the zenith: the region the GPU chooses from the
    // heights gives the CPU twin's map.
    let grazing = DVec3::new(
        0.8 * 80f64.to_radians().sin(),
        0.6 * 80f64.to_radians().sin(),
        -80f64.to_radians().cos(),
    );
    for (name, sun) in [
        ("yuksel", None),
        ("yuksel-targets", None),
        ("yuksel", Some(grazing)),
        ("yuksel-targets", Some(grazing)),
    ] {
        let mut t = registry::create(&ctx, name, &toml::Table::new()).unwrap();
        let (mut scene, grid) = pool((64, 64));
        if let Some(sun) = sun {
            scene.light.direction = sun;
        }
        assert_eq!(t.water_resolution(&scene), (64, 64));
        let texture = ctx.upload_grid("heights", &grid).unwrap();
        t.configure(&ctx, &scene, &WaterTextures::of(&texture))
            .unwrap();
        t.update(&ctx, &scene).unwrap();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        t.encode(&mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
        let gpu = read_floor(&ctx, t.output().unwrap());
        let w = scene.water.as_ref().unwrap();
        let setup = YukselSetup::new(
            &YukselParams::default(),
            64,
            64,
            w.size,
            w.depth,
            w.ior,
            w.absorption,
            w.wrap,
            scene.light.direction,
        )
        .unwrap()
        .with_floor(&scene.floor, None);
        let cpu = yuksel::caustics(&setup, &grid);
        let worst = gpu
            .iter()
            .zip(&cpu.texels)
            .flat_map(|(g, c)| (0..3).map(move |k| (g[k] - c[k]).abs()))
            .fold(0.0f32, f32::max);
        // measured 1.12e-4 at the pool's sun, 1.10e-4 at 80 degrees on lavapipe 25.0.7 (Mesa),
        // both variants (f32 against f64, texels near 1, adaptive footprints centred on their
        // light's centroid)
        let bound = 1.1e-3;
        eprintln!("{name} {sun:?}: worst texel difference {worst:.2e}");
        assert!(
            worst < bound,
            "{name} {sun:?}: worst texel difference {worst}"
        );
    }
}

fn yuksel_steady_frames_create_nothing_and_read_nothing_back() {
    let ctx = test_gpu();
    for name in ["yuksel", "yuksel-targets"] {
        let mut t = registry::create(&ctx, name, &toml::Table::new()).unwrap();
        let (mut scene, grid) = pool((64, 64));
        let texture = ctx.upload_grid("heights", &grid).unwrap();
        t.configure(&ctx, &scene, &WaterTextures::of(&texture))
            .unwrap();
        let frame = |t: &mut Box<dyn caustics_gpu::Technique>, scene: &Scene| {
            t.update(&ctx, scene).unwrap();
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            t.encode(&mut encoder, None);
            ctx.queue.submit([encoder.finish()]);
        };
        frame(&mut t, &scene);
        let before = ctx.traffic();
        let frames = 10;
        for k in 0..frames {
            // The sun moves a little every frame: uniform writes, the region keeps its size.
            scene.light.direction = DVec3::new(0.2 + 0.01 * k as f64, 0.1, -1.0).normalize();
            frame(&mut t, &scene);
        }
        ctx.wait().unwrap();
        let d = ctx.traffic().since(&before);
        assert_eq!(d.created(), 0, "{name}: {d:?}");
        assert_eq!(d.readbacks, 0, "{name}: {d:?}");
        // One 96-byte uniform per pass-1 draw and pass 2's: 96 (scatter) or 192 bytes a frame.
        assert!(
            d.uploaded_bytes <= 4096 * frames,
            "{name}: {} bytes in {frames} frames",
            d.uploaded_bytes
        );
        assert!(
            d.uploaded_bytes > 0,
            "{name}: the sun's moves never reached the GPU"
        );
        // A still frame uploads nothing at all.
        let before = ctx.traffic();
        frame(&mut t, &scene);
        assert_eq!(ctx.traffic().since(&before).uploaded_bytes, 0, "{name}");
    }
}

/// The water grows steeper between frames (the caller rewrites its texture): the region pass
/// widens the region on the GPU (here past the largest region at the map's pixels, to a coarser
/// level) with nothing created and nothing read back, and the map is the CPU twin's on the new
/// heights.
fn yuksel_follows_steeper_water_without_new_resources() {
    let ctx = test_gpu();
    for name in ["yuksel", "yuksel-targets"] {
        let mut t = registry::create(&ctx, name, &toml::Table::new()).unwrap();
        let (mut scene, grid) = pool((64, 64));
        scene.light.direction = DVec3::new(0.6, 0.45, -0.66).normalize();
        let texture = ctx.upload_grid("heights", &grid).unwrap();
        t.configure(&ctx, &scene, &WaterTextures::of(&texture))
            .unwrap();
        let steep = Grid {
            data: grid.data.iter().map(|h| 20.0 * h).collect(),
            ..grid.clone()
        };
        let w = scene.water.as_ref().unwrap();
        let setup = YukselSetup::new(
            &YukselParams::default(),
            64,
            64,
            w.size,
            w.depth,
            w.ior,
            w.absorption,
            w.wrap,
            scene.light.direction,
        )
        .unwrap()
        .with_floor(&scene.floor, None);
        let (calm, rough) = (setup.region_for(&grid), setup.region_for(&steep));
        assert!(rough.level > calm.level, "{calm:?} {rough:?}");
        t.update(&ctx, &scene).unwrap();
        let before = ctx.traffic();
        ctx.write_grid(&texture, &steep);
        t.update(&ctx, &scene).unwrap();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        t.encode(&mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
        ctx.wait().unwrap();
        let d = ctx.traffic().since(&before);
        assert_eq!((d.created(), d.readbacks), (0, 0), "{name}: {d:?}");
        let gpu = read_floor(&ctx, t.output().unwrap());
        let cpu = yuksel::caustics(&setup, &steep);
        let mean = cpu.texels.iter().map(|t| t[0]).sum::<f32>() / cpu.texels.len() as f32;
        let worst = gpu
            .iter()
            .zip(&cpu.texels)
            .flat_map(|(g, c)| (0..3).map(move |k| (g[k] - c[k]).abs()))
            .fold(0.0f32, f32::max)
            / mean;
        // measured 3.21e-4 of the mean on lavapipe 25.0.7 (Mesa), both variants (5 x 5 at level 0
        // -> 17 x 19, shifted, at level 1: the level's offsets count twice in map pixels)
        eprintln!("{name}: worst texel difference {worst:.2e} of the mean");
        assert!(worst < 2.0e-3, "{name}: worst texel difference {worst}");
    }
}

/// New parameters for the technique a side already runs are taken in place: no pipeline is
/// built again (a panel's slider costs a configure, not a shader compile), and the map is the one
/// a technique created with those parameters makes. For every technique (procedural through its
/// texture variant), a uniform knob and a size changed together.
fn new_parameters_keep_the_pipelines_and_give_a_fresh_techniques_map() {
    use caustics_core::render::RenderOptions;
    use caustics_gpu::renderer::{FrameWater, Renderer, TechniqueSpec, WaterClock};
    let ctx = test_gpu();
    let cases = [
        (
            "yuksel",
            "yuksel = { subsamples = 2 }",
            "yuksel = { fresnel = false, subsamples = 1 }",
            "pool",
        ),
        (
            "caustic-triangles",
            "caustic-triangles = { photon_image = 32 }",
            "caustic-triangles = { photon_image = 48, fresnel = false }",
            "pool",
        ),
        (
            "volumes",
            "volumes = { planes = 3, texture = 32, shadow = 0 }",
            "volumes = { planes = 3, texture = 48, shadow = 0, fresnel = false }",
            "objects",
        ),
        (
            "cascaded",
            "cascaded = { resolution = 64 }",
            "cascaded = { resolution = 128 }",
            "pool",
        ),
    ];
    for (name, before, after, scene_name) in cases {
        let mut scene = Scene::builtin(scene_name).unwrap();
        scene.caustics.width = 64;
        scene.caustics.height = 64;
        scene.camera.width = 64;
        scene.camera.height = 36;
        let spec = |params: &str| {
            Some(TechniqueSpec {
                name: name.into(),
                params: params.parse().unwrap(),
            })
        };
        let frame = |renderer: &mut Renderer| {
            let clock = WaterClock {
                time: 0.0,
                amplitude: 1.0,
                steps: 0,
            };
            renderer
                .render(&ctx, &scene, clock, &RenderOptions::default())
                .unwrap();
            assert_eq!(renderer.error(0), None, "{name}");
            let texture = renderer.caustics(0).expect("a map").texture().clone();
            ctx.read_rgba_f32(&texture).unwrap()
        };
        let renderer = || {
            let mut r = Renderer::new(&ctx).unwrap();
            r.set_water(&ctx, scene.water.as_ref(), &FrameWater::Scene)
                .unwrap();
            r
        };
        let mut changed = renderer();
        changed.set_techniques(&ctx, &[spec(before)]);
        let first = frame(&mut changed);
        let start = ctx.traffic();
        changed.set_techniques(&ctx, &[spec(after)]);
        let map = frame(&mut changed);
        let d = ctx.traffic().since(&start);
        assert_eq!(d.pipelines, 0, "{name}: pipelines built again");
        assert!(first != map, "{name}: the new parameters changed nothing");
        let mut fresh = renderer();
        fresh.set_techniques(&ctx, &[spec(after)]);
        assert!(
            map == frame(&mut fresh),
            "{name}: not a fresh technique's map"
        );
    }
}

/// `yuksel` runs the scatter by default (no pre-pass texture, no render targets) and the paper's
/// passes for the paper's preset; `yuksel-targets` runs the render targets whatever the preset and
/// refuses a table that asks it to scatter; `yuksel-gather`, the scatter's former name, is
/// `yuksel`. Told apart by the memory each frame allocates (the pool, a 64² map).
fn yuksel_chooses_its_passes_from_the_preset() {
    let ctx = test_gpu();
    let (scene, grid) = pool((64, 64));
    let texture = ctx.upload_grid("heights", &grid).unwrap();
    let bytes = |name: &str, table: &str| {
        let params: toml::Table = table.parse().unwrap();
        let mut t = registry::create(&ctx, name, &params).unwrap();
        t.configure(&ctx, &scene, &WaterTextures::of(&texture))
            .unwrap();
        (t.name().to_string(), t.bytes())
    };
    let scatter = bytes("yuksel", "");
    let targets = bytes("yuksel-targets", "");
    let paper = bytes("yuksel", "yuksel = { preset = \"paper\" }");
    let paper_scatter = bytes(
        "yuksel",
        "yuksel = { preset = \"paper\", passes = \"scatter\" }",
    );
    eprintln!("{scatter:?} {targets:?} {paper:?} {paper_scatter:?}");
    assert_eq!(scatter.0, "yuksel");
    assert_eq!(targets.0, "yuksel-targets");
    // The scatter's frame: the map, one sum per map pixel and one list entry per pixel of the map
    // and its apron; the render targets' adds the pre-pass texture and pass 1's channels (both hold
    // the heights in Hermite form, 64 KiB here). Measured: 182,960 against 4,978,912 bytes at the
    // defaults, 167,216 against 431,392 at the paper's preset.
    assert!(scatter.1 * 10 < targets.1, "{scatter:?} {targets:?}");
    assert!(paper_scatter.1 * 2 < paper.1, "{paper_scatter:?} {paper:?}");
    assert_eq!(bytes("yuksel-gather", ""), scatter);
    let asks_scatter: toml::Table = "yuksel = { passes = \"scatter\" }".parse().unwrap();
    let err = registry::create(&ctx, "yuksel-targets", &asks_scatter)
        .err()
        .expect("refused");
    assert!(err.to_string().contains("passes"), "{err}");
    ctx.check().expect("wgpu saw nothing");
}

test_main! {
    gpu yuksel_chooses_its_passes_from_the_preset,
    gpu new_parameters_keep_the_pipelines_and_give_a_fresh_techniques_map,
    gpu the_registry_names_are_unique_and_unknown_names_are_refused,
    gpu the_minimal_example_lights_its_floor,
    cpu the_readme_shows_lines_of_the_minimal_example,
    gpu yuksel_through_the_interface_matches_its_cpu_twin,
    gpu yuksel_steady_frames_create_nothing_and_read_nothing_back,
    gpu yuksel_follows_steeper_water_without_new_resources,
}
