//! `GpuWater` against the CPU: for every water source, the heights it writes on the GPU, read back
//! here, against `sample_grid(water.surface_at(t), cols, rows, size)` (or the CPU `Ripples` twin
//! stepped the same way), at two times and at an output size other than the source's own grid.
//! Then what a frame costs once built: nothing created, nothing read back, a few uniforms uploaded.

#[macro_use]
mod common;
mod wgsl;

use caustics_core::grid::{Edge, Grid};
use caustics_core::scene::{Water, WaterSource};
use caustics_core::water::ocean::{Ocean, OceanParams};
use caustics_core::water::procedural::ProceduralParams;
use caustics_core::water::ripple::{Drop, RippleParams, Ripples};
use caustics_core::water::sample_grid;
use caustics_core::water::waves::Wave;
use caustics_gpu::GpuContext;
use caustics_gpu::context::test_gpu;
use caustics_gpu::water::field::{FieldParams, GpuWater};
use glam::DVec3;

/// The output size of every comparison: neither the ocean's 64², the ripples' 64² nor the height
/// field's 37 x 29, and not square.
const COLS: u32 = 48;
const ROWS: u32 = 40;

fn water(source: WaterSource, size: f64, wrap: bool) -> Water {
    Water {
        source,
        size,
        depth: 1.0,
        ior: 1.333,
        wrap,
        absorption: DVec3::ZERO,
    }
}

fn waves_water() -> Water {
    let wave = |amplitude, wavelength, direction: [f64; 2], phase| Wave {
        amplitude,
        wavelength,
        direction,
        phase,
        period: None,
    };
    water(
        WaterSource::Waves(vec![
            wave(0.01, 0.5, [1.0, 0.2], 0.0),
            wave(0.005, 0.23, [-0.3, 1.0], 1.1),
            wave(0.003, 0.9, [0.7, -0.7], 2.5),
        ]),
        2.0,
        true,
    )
}

fn procedural_water() -> Water {
    water(
        WaterSource::Procedural(ProceduralParams {
            origin: [0.4, 0.3],
            ..ProceduralParams::default()
        }),
        1.0,
        true,
    )
}

fn ocean_water() -> Water {
    let params = OceanParams {
        resolution: 64,
        seed: 5,
        ..OceanParams::default()
    };
    water(
        WaterSource::Ocean(Box::new(Ocean::new(&params, 3.0).unwrap())),
        3.0,
        true,
    )
}

fn ripple_params() -> RippleParams {
    RippleParams {
        resolution: 64,
        steps: 20,
        ..RippleParams::default()
    }
}

/// Clamped, so that the walls' edge rule is what the output pass must follow.
fn ripple_water() -> Water {
    water(WaterSource::Ripple(ripple_params()), 1.0, false)
}

fn height_field_water() -> Water {
    let grid = Grid::from_fn(37, 29, |i, j| {
        let (x, y) = (j as f32 / 37.0, i as f32 / 29.0);
        0.02 * (7.0 * x + 3.0 * y * y).sin() + 0.01 * ((13.0 * x * y).cos() - 0.3)
    });
    water(WaterSource::HeightField(grid), 2.0, false)
}

/// One frame: update, encode, submit.
fn frame(ctx: &GpuContext, w: &mut GpuWater, time: f64, amplitude: f64) {
    w.update(ctx, time, amplitude);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    w.encode(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
}

fn read(ctx: &GpuContext, w: &mut GpuWater, cols: u32, rows: u32) -> Grid {
    let out = w.output(ctx, cols, rows).unwrap();
    let data = ctx.read_texture::<f32>(out.heights.texture()).unwrap();
    Grid {
        cols: cols as usize,
        rows: rows as usize,
        data,
    }
}

/// max |gpu − cpu| / max |cpu|.
fn relative_error(gpu: &Grid, cpu: &Grid) -> f64 {
    assert_eq!((gpu.cols, gpu.rows), (cpu.cols, cpu.rows));
    let peak = cpu.data.iter().map(|v| v.abs() as f64).fold(0.0, f64::max);
    assert!(peak > 0.0, "the CPU surface is flat");
    let err = gpu
        .data
        .iter()
        .zip(&cpu.data)
        .map(|(&g, &c)| (g as f64 - c as f64).abs())
        .fold(0.0, f64::max);
    err / peak
}

fn cpu_at(water: &Water, t: f64, cols: u32, rows: u32) -> Grid {
    let surface = water.surface_at(t).unwrap();
    sample_grid(surface.as_ref(), cols as usize, rows as usize, water.size)
}

/// The scene's source at two times (the second far enough on for the phases to wrap many times)
/// against `surface_at`.
fn check_source(name: &str, water: &Water, times: [f64; 2], tolerance: f64) {
    let ctx = test_gpu();
    let mut w = GpuWater::new(&ctx, water).expect("GPU water");
    w.output(&ctx, COLS, ROWS).unwrap();
    for t in times {
        frame(&ctx, &mut w, t, 1.0);
        let gpu = read(&ctx, &mut w, COLS, ROWS);
        let err = relative_error(&gpu, &cpu_at(water, t, COLS, ROWS));
        eprintln!("{name}, t {t}: max error {err:.3e} of the peak height");
        assert!(err <= tolerance, "{name}, t {t}: error {err:.3e}");
    }
}

fn flat_water_is_zero() {
    let ctx = test_gpu();
    let mut w = GpuWater::new(&ctx, &water(WaterSource::Flat, 1.0, true)).unwrap();
    w.output(&ctx, COLS, ROWS).unwrap();
    for t in [0.0, 3.0] {
        frame(&ctx, &mut w, t, 1.0);
        let gpu = read(&ctx, &mut w, COLS, ROWS);
        assert!(gpu.data.iter().all(|&h| h == 0.0));
    }
}

fn waves_match_the_cpu() {
    // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 2.1e-6 at t 0.3, 2.3e-6 at t 41.7 (f32 sines of arguments up to
    // ~60 rad; the phases reduced mod 2π on the CPU keep the late time as close as the early one).
    check_source("waves", &waves_water(), [0.3, 41.7], 2e-5);
}

fn procedural_matches_the_cpu() {
    // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 1.25e-6 at t 0.5, 1.34e-6 at t 37.2.
    check_source("procedural", &procedural_water(), [0.5, 37.2], 1.2e-5);
}

fn ocean_matches_the_cpu() {
    // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 4.0e-7 at t 0.5, 1.5e-6 at t 2.75 (the FFT's f32 stages, then the
    // bicubic interpolant in f32).
    check_source("ocean", &ocean_water(), [0.5, 2.75], 1.5e-5);
}

fn height_field_matches_the_cpu() {
    // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 4.5e-7 at both times (the file does not move).
    check_source("height field", &height_field_water(), [0.0, 5.0], 4e-6);
}

fn the_scene_ripples_follow_the_clock() {
    let ctx = test_gpu();
    let water = ripple_water();
    let mut w = GpuWater::new(&ctx, &water).unwrap();
    w.output(&ctx, COLS, ROWS).unwrap();
    // 12 steps, then 18 more, then back to 12: the simulation starts again.
    for t in [0.05, 0.125, 0.05] {
        frame(&ctx, &mut w, t, 1.0);
        let gpu = read(&ctx, &mut w, COLS, ROWS);
        let err = relative_error(&gpu, &cpu_at(&water, t, COLS, ROWS));
        eprintln!("scene ripples, t {t}: max error {err:.3e} of the peak height");
        // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 1.17e-6, 2.05e-6, 1.17e-6 (the restart lands exactly where the
        // first run was).
        assert!(err <= 2e-5, "t {t}: error {err:.3e}");
    }
}

fn interactive_ripples_match_the_cpu_twin() {
    let ctx = test_gpu();
    let params = RippleParams {
        steps: 10,
        ..ripple_params()
    };
    let water = water(WaterSource::Flat, 1.0, true);
    let mut w = GpuWater::ripples(&ctx, &water, &params).unwrap();
    w.output(&ctx, COLS, ROWS).unwrap();
    let mut cpu = Ripples::new(&params, 1.0, Edge::Wrap).unwrap();
    cpu.run_initial();
    let drop = |x, y, strength| Drop {
        position: [x, y],
        radius: 0.07,
        strength,
    };
    // A drop across the corner (it wraps), 25 steps; then two drops in one frame, 15 steps.
    let frames = [
        (vec![drop(0.97, 0.03, 0.01)], 25),
        (vec![drop(0.5, 0.5, -0.008), drop(0.2, 0.7, 0.006)], 15),
    ];
    for (k, (drops, steps)) in frames.iter().enumerate() {
        for d in drops {
            w.drop_ripple(&ctx, d);
            cpu.drop(d);
        }
        w.step_ripples(*steps);
        for _ in 0..*steps {
            cpu.step();
        }
        // The clock is not the interactive simulation's: a time changes nothing.
        frame(&ctx, &mut w, 100.0 * k as f64, 1.0);
        let gpu = read(&ctx, &mut w, COLS, ROWS);
        let want = sample_grid(&cpu.surface(), COLS as usize, ROWS as usize, 1.0);
        let err = relative_error(&gpu, &want);
        eprintln!("interactive ripples, frame {k}: max error {err:.3e} of the peak height");
        // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 1.40e-6, 1.75e-6.
        assert!(err <= 1.5e-5, "frame {k}: error {err:.3e}");
    }
}

/// More drops in one frame than an encode has slots for: the first `DROPS_PER_ENCODE` land in
/// that frame, the rest in the next, in order.
fn drops_beyond_the_slots_wait_for_the_next_frame() {
    use caustics_gpu::water::ripple::DROPS_PER_ENCODE;
    let ctx = test_gpu();
    let params = RippleParams {
        drops: Vec::new(),
        steps: 0,
        ..ripple_params()
    };
    let water = water(WaterSource::Flat, 1.0, true);
    let mut w = GpuWater::ripples(&ctx, &water, &params).unwrap();
    w.output(&ctx, COLS, ROWS).unwrap();
    let drops: Vec<Drop> = (0..DROPS_PER_ENCODE + 4)
        .map(|k| Drop {
            position: [0.05 * k as f64, 0.5 + 0.02 * k as f64],
            radius: 0.06,
            strength: if k % 2 == 0 { 0.004 } else { -0.003 },
        })
        .collect();
    for d in &drops {
        w.drop_ripple(&ctx, d);
    }
    for applied in [DROPS_PER_ENCODE, drops.len()] {
        frame(&ctx, &mut w, 0.0, 1.0);
        let mut cpu = Ripples::new(&params, 1.0, Edge::Wrap).unwrap();
        for d in &drops[..applied] {
            cpu.drop(d);
        }
        let want = sample_grid(&cpu.surface(), COLS as usize, ROWS as usize, 1.0);
        let err = relative_error(&read(&ctx, &mut w, COLS, ROWS), &want);
        eprintln!("{applied} drops: max error {err:.3e} of the peak height");
        // Measured on lavapipe (Mesa 22.3.6 and 25.0.7 alike): 1.20e-6 (16 drops), 1.36e-6 (20).
        assert!(err <= 1e-5, "{applied} drops: error {err:.3e}");
    }
}

/// Every source, with two outputs (one of them asked for again each frame): after the first
/// frame, ten frames of update + encode + submit create nothing, read nothing back and upload at
/// most 4096 bytes each; then the height factor scales the heights exactly.
fn frames_create_nothing_and_amplitude_scales() {
    let ctx = test_gpu();
    let sources = [
        ("flat", water(WaterSource::Flat, 1.0, true)),
        ("waves", waves_water()),
        ("procedural", procedural_water()),
        ("ocean", ocean_water()),
        ("scene ripples", ripple_water()),
        ("height field", height_field_water()),
    ];
    let mut worlds: Vec<(&str, GpuWater)> = sources
        .iter()
        .map(|(name, water)| (*name, GpuWater::new(&ctx, water).unwrap()))
        .collect();
    let params = ripple_params();
    worlds.push((
        "interactive ripples",
        GpuWater::ripples(&ctx, &sources[0].1, &params).unwrap(),
    ));
    let d = Drop {
        position: [0.3, 0.6],
        radius: 0.05,
        strength: -0.01,
    };
    for (name, w) in &mut worlds {
        w.output(&ctx, 32, 32).unwrap();
        w.output(&ctx, COLS, ROWS).unwrap();
        frame(&ctx, w, 0.0, 1.0);
        ctx.wait().unwrap();
        let start = ctx.traffic();
        for k in 1..=10 {
            let before = ctx.traffic();
            w.drop_ripple(&ctx, &d);
            w.step_ripples(3);
            w.output(&ctx, COLS, ROWS).unwrap();
            frame(&ctx, w, 0.02 * k as f64, 0.5 + 0.1 * k as f64);
            let this = ctx.traffic().since(&before);
            assert!(
                this.uploaded_bytes <= 4096,
                "{name}, frame {k}: uploaded {} bytes",
                this.uploaded_bytes
            );
        }
        ctx.wait().unwrap();
        let span = ctx.traffic().since(&start);
        eprintln!(
            "{name}: 10 frames created {}, uploaded {} bytes, read back {}",
            span.created(),
            span.uploaded_bytes,
            span.readbacks
        );
        assert_eq!(span.created(), 0, "{name}: {span:?}");
        assert_eq!(span.readbacks, 0, "{name}: {span:?}");

        // The same surface at amplitudes 1, 2 and 0 (the time stays, so no source moves).
        let t = 0.2;
        frame(&ctx, w, t, 1.0);
        let one = read(&ctx, w, COLS, ROWS);
        frame(&ctx, w, t, 2.0);
        let two = read(&ctx, w, COLS, ROWS);
        frame(&ctx, w, t, 0.0);
        let zero = read(&ctx, w, COLS, ROWS);
        if *name != "flat" {
            assert!(one.data.iter().any(|&h| h != 0.0), "{name}: flat at 1");
        }
        assert!(
            one.data.iter().zip(&two.data).all(|(&a, &b)| b == 2.0 * a),
            "{name}: amplitude 2 does not double the heights"
        );
        assert!(
            zero.data.iter().all(|&h| h == 0.0),
            "{name}: amplitude 0 is not flat"
        );
    }
}

fn field_params_match_their_wgsl_size() {
    let pass = &caustics_gpu::water::field::GRID;
    assert_eq!(
        wgsl::wgsl_struct_size(pass, "FieldParams"),
        std::mem::size_of::<FieldParams>()
    );
}

fn an_output_beyond_the_device_limits_is_refused() {
    let ctx = test_gpu();
    let mut w = GpuWater::new(&ctx, &waves_water()).unwrap();
    let too_wide = ctx.limits().max_texture_dimension_2d + 1;
    let err = w.output(&ctx, too_wide, 8).unwrap_err().to_string();
    assert!(err.contains("water height texture"), "{err}");
    let err = w.output(&ctx, 0, 8).unwrap_err().to_string();
    assert!(err.contains("water height texture"), "{err}");
}

/// Outputs nobody reads any more are dropped: the kept one stays (asked for again, nothing is
/// created, and it still holds the surface), the dropped one is made anew when asked for.
fn unused_outputs_are_dropped() {
    let ctx = test_gpu();
    let water = waves_water();
    let mut w = GpuWater::new(&ctx, &water).unwrap();
    let kept = w.output(&ctx, 48, 40).unwrap();
    w.output(&ctx, 32, 32).unwrap();
    w.retain_outputs(&[(48, 40)]);
    frame(&ctx, &mut w, 0.3, 1.0);
    let before = ctx.traffic();
    assert_eq!(w.output(&ctx, 48, 40).unwrap().heights, kept.heights);
    assert_eq!(ctx.traffic().since(&before).created(), 0);
    // Measured 2.1e-6 for this surface in `waves_match_the_cpu`, held to the same bound there.
    let error = relative_error(&read(&ctx, &mut w, 48, 40), &cpu_at(&water, 0.3, 48, 40));
    assert!(error < 2e-5, "the kept output is stale: {error}");
    let before = ctx.traffic();
    w.output(&ctx, 32, 32).unwrap();
    assert!(
        ctx.traffic().since(&before).textures == 1,
        "the dropped output was kept"
    );
}

test_main! {
    gpu flat_water_is_zero,
    gpu waves_match_the_cpu,
    gpu procedural_matches_the_cpu,
    gpu ocean_matches_the_cpu,
    gpu height_field_matches_the_cpu,
    gpu the_scene_ripples_follow_the_clock,
    gpu interactive_ripples_match_the_cpu_twin,
    gpu drops_beyond_the_slots_wait_for_the_next_frame,
    gpu frames_create_nothing_and_amplitude_scales,
    cpu field_params_match_their_wgsl_size,
    gpu an_output_beyond_the_device_limits_is_refused,
    gpu unused_outputs_are_dropped,
}
