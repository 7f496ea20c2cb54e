//! The harness of the GPU test files (`harness = false` in Cargo.toml, run by `libtest-mimic`):
//! cargo's own harness can only pass a GPU test that returned early for want of an adapter, so a
//! laptop without Vulkan reported every GPU test as passed. Here a GPU test is reported as
//! *ignored* when no device can be created (the reason printed once), and fails when
//! `CAUSTICS_REQUIRE_GPU=1` (as `.ci/run` sets) or when asked for with `--include-ignored`.
//!
//! Each file lists its tests once with [`test_main!`]; a test function left out of the list is
//! never used, which `-D warnings` refuses, so none can drop out silently.

// Not every test file has every kind of test.
#![allow(dead_code)]

use std::process::ExitCode;

use libtest_mimic::{Arguments, Trial};

/// One test of a file: its name, its body, and whether it needs the GPU or is ignored by default
/// (timings, which are run by hand with `--ignored`).
pub struct Case {
    name: String,
    body: fn(),
    gpu: bool,
    ignored: bool,
}

/// A test that needs no device.
pub fn cpu(name: String, body: fn()) -> Case {
    Case {
        name,
        body,
        gpu: false,
        ignored: false,
    }
}

/// A test that needs a device (it gets one from `caustics_gpu::context::test_gpu`).
pub fn gpu(name: String, body: fn()) -> Case {
    Case {
        name,
        body,
        gpu: true,
        ignored: false,
    }
}

/// A GPU test run only when asked for (`-- --ignored`), as `#[ignore]` does.
pub fn gpu_ignored(name: String, body: fn()) -> Case {
    Case {
        name,
        body,
        gpu: true,
        ignored: true,
    }
}

/// Run the cases under cargo's usual command line (filters, `--ignored`, `--nocapture`, ...).
pub fn run(cases: Vec<Case>) -> ExitCode {
    let args = Arguments::from_args();
    let trial = |c: &Case, ignored: bool| {
        let body = c.body;
        Trial::test(c.name.clone(), move || {
            body();
            Ok(())
        })
        .with_ignored_flag(ignored)
    };
    // Probe for a device only when a GPU test would run, so that CPU tests run alone stay quick.
    let gpu_runs = cases.iter().filter(|c| c.gpu).any(|c| {
        !args.is_filtered_out(&trial(c, c.ignored)) && !args.is_ignored(&trial(c, c.ignored))
    });
    let skip = if gpu_runs {
        caustics_gpu::context::gpu_test_skip()
    } else {
        None
    };
    if let Some(reason) = &skip {
        eprintln!("GPU tests ignored: {reason}");
    }
    let trials = cases
        .iter()
        .map(|c| trial(c, c.ignored || (c.gpu && skip.is_some())))
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}

/// `fn main` of a test file: `test_main! { cpu a, gpu b, gpu_ignored c, gpu module::d }`.
macro_rules! test_main {
    ($($kind:ident $($name:ident)::+),* $(,)?) => {
        fn main() -> std::process::ExitCode {
            common::run(vec![
                $(common::$kind([$(stringify!($name)),+].join("::"), $($name)::+)),*
            ])
        }
    };
}

/// The built-in scene `name` with the gentle ripples the `pool` and `objects` scenes had before
/// their waves were made to focus near the floor: the GPU-vs-CPU precision bounds of
/// the tests that use it were measured on these, and sharper foci (thin triangles, near-zero areas)
/// would measure f32 rounding at caustic cusps instead of the twins' agreement.
pub fn with_gentle_ripples(name: &str) -> caustics_core::scene::Scene {
    use caustics_core::scene::WaterSource;
    use caustics_core::water::waves::Wave;
    let mut scene = caustics_core::scene::Scene::builtin(name).expect("built-in scene");
    let w = |amplitude, wavelength, direction, phase| Wave {
        amplitude,
        wavelength,
        direction,
        phase,
        period: None,
    };
    let waves = match name {
        "pool" => vec![
            w(0.0040, 0.50, [1.0, 0.25], 0.0),
            w(0.0032, 0.36, [-0.4, 1.0], 1.3),
            w(0.0025, 0.27, [0.8, -0.7], 2.1),
            w(0.0020, 0.21, [0.1, 1.0], 0.4),
            w(0.0050, 1.00, [1.0, 0.9], 4.0),
        ],
        "objects" => vec![
            w(0.0045, 0.55, [1.0, 0.2], 0.0),
            w(0.0035, 0.38, [-0.3, 1.0], 0.7),
            w(0.0025, 0.26, [0.7, -0.8], 2.5),
        ],
        _ => return scene,
    };
    if let Some(water) = scene.water.as_mut() {
        water.source = WaterSource::Waves(waves);
    }
    scene
}

/// The shore's beach scaled to water `depth` deep: its far side 80 % of the way up (over any
/// square: the grid's samples cover whatever square the scene has).
pub fn beach_under(depth: f64) -> caustics_core::grid::Grid {
    let shore = caustics_core::scene::Scene::builtin("shore").expect("built-in scene");
    let mut beach = shore.floor.terrain.expect("the shore has a beach");
    let top = beach.min_max().1;
    beach
        .data
        .iter_mut()
        .for_each(|h| *h *= 0.8 * depth as f32 / top);
    beach
}

/// An open floor (no walls) over [`beach_under`]`(depth)`.
pub fn beach_floor(depth: f64) -> caustics_core::scene::Floor {
    caustics_core::scene::Floor {
        terrain: Some(beach_under(depth)),
        solids: None,
        albedo: caustics_core::scene::Albedo::Pattern(Default::default()),
        walls: false,
        deck: Default::default(),
    }
}

/// A test's own upload of new heights into `texture` (an `R32Float` texture of the grid's size),
/// past the context's counters, so that a count of what a frame uploads is the technique's alone.
pub fn write_heights(
    ctx: &caustics_gpu::GpuContext,
    texture: &wgpu::Texture,
    grid: &caustics_core::grid::Grid,
) {
    let bytes: Vec<u8> = grid.data.iter().flat_map(|h| h.to_ne_bytes()).collect();
    ctx.queue.write_texture(
        texture.as_image_copy(),
        &bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(grid.cols as u32 * 4),
            rows_per_image: Some(grid.rows as u32),
        },
        texture.size(),
    );
}
