//! The GPU water simulations against their CPU twins in `caustics-core`: the FFT ocean
//! (`GpuOcean` vs `Ocean::height_grid` / `slope_grids`) and the ripples (`GpuRipples` vs
//! `Ripples`).

#[macro_use]
mod common;

use caustics_core::grid::{Edge, Grid};
use caustics_core::water::ocean::{Ocean, OceanParams};
use caustics_core::water::ripple::{Drop, RippleParams, Ripples};
use caustics_gpu::GpuTimer;
use caustics_gpu::context::test_gpu;
use caustics_gpu::water::ocean::GpuOcean;
use caustics_gpu::water::ripple::GpuRipples;

fn rms(values: &[f32]) -> f64 {
    (values.iter().map(|&v| (v as f64).powi(2)).sum::<f64>() / values.len() as f64).sqrt()
}

/// The largest difference between the GPU channel and the CPU grid.
fn max_error(gpu: &[[f32; 4]], channel: usize, cpu: &Grid) -> f64 {
    gpu.iter()
        .zip(&cpu.data)
        .map(|(g, &c)| (g[channel] as f64 - c as f64).abs())
        .fold(0.0, f64::max)
}

/// f32 arithmetic through 2 log2 N butterfly stages, against an f64 FFT rounded to f32, as a share
/// of the field's rms. Measured on lavapipe: up to 6.8e-6 (dh/dx, N 64, t 2.75).
const OCEAN_TOLERANCE: f64 = 5e-5;

fn gpu_ocean_matches_the_cpu_fft() {
    let ctx = test_gpu();
    for (n, size) in [(64, 3.0), (256, 20.0)] {
        let params = OceanParams {
            resolution: n,
            seed: 11,
            ..OceanParams::default()
        };
        let ocean = Ocean::new(&params, size).unwrap();
        let gpu = GpuOcean::new(&ctx, &ocean).expect("GPU ocean");
        for t in [0.0f32, 2.75] {
            let got = gpu.compute(&ctx, t).expect("GPU ocean runs");
            assert_eq!(got.len(), n * n);
            let heights = ocean.height_grid(t as f64);
            let (dx, dy) = ocean.slope_grids(t as f64);
            let slope_rms = (rms(&dx.data).powi(2) + rms(&dy.data).powi(2)).sqrt();
            for (what, channel, cpu, scale) in [
                ("height", 0, &heights, rms(&heights.data)),
                ("dh/dx", 1, &dx, slope_rms),
                ("dh/dy", 2, &dy, slope_rms),
            ] {
                let err = max_error(&got, channel, cpu);
                eprintln!(
                    "N {n}, t {t}: {what} max error {err:.3e} = {:.2e} rms",
                    err / scale
                );
                assert!(
                    err <= OCEAN_TOLERANCE * scale,
                    "N {n}, t {t}: {what} differs by {err} (rms {scale})"
                );
            }
            assert!(got.iter().all(|v| v[3] == 0.0));
        }
    }
}

fn ocean_passes_are_timed() {
    let ctx = test_gpu();
    let ocean = Ocean::new(
        &OceanParams {
            resolution: 32,
            ..OceanParams::default()
        },
        2.0,
    )
    .unwrap();
    let gpu = GpuOcean::new(&ctx, &ocean).unwrap();
    let mut timer = GpuTimer::new(&ctx, 4);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    gpu.update(&ctx, &mut encoder, 1.0, Some(&mut timer));
    timer.resolve(&mut encoder);
    ctx.queue.submit([encoder.finish()]);
    let times = timer.read(&ctx).unwrap();
    if timer.enabled() {
        let labels: Vec<&str> = times.iter().map(|t| t.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "ocean spectrum",
                "ocean FFT rows",
                "ocean FFT columns",
                "ocean output"
            ]
        );
        assert!(times.iter().all(|t| t.ms >= 0.0 && t.ms.is_finite()));
    }
    // The texture holds the surface at that time.
    let got = ctx
        .read_texture::<[f32; 4]>(gpu.height_slopes_texture())
        .unwrap();
    let heights = ocean.height_grid(1.0);
    // Measured on lavapipe: 9.3e-7 of the rms.
    assert!(max_error(&got, 0, &heights) <= 5e-6 * rms(&heights.data));
}

fn gpu_ripples_match_the_cpu_scheme() {
    let ctx = test_gpu();
    let params = RippleParams {
        resolution: 96,
        damping: 0.4,
        ..RippleParams::default()
    };
    let drops = [
        Drop {
            position: [0.32, 0.38],
            radius: 0.08,
            strength: -0.012,
        },
        // Across the corner: wraps to the far sides with Edge::Wrap, cut by the walls with Clamp.
        Drop {
            position: [0.97, 0.02],
            radius: 0.1,
            strength: 0.009,
        },
        Drop {
            position: [0.6, 0.7],
            radius: 0.05,
            strength: -0.006,
        },
    ];
    for edge in [Edge::Wrap, Edge::Clamp] {
        let mut cpu = Ripples::new(&params, 1.0, edge).unwrap();
        let mut gpu = GpuRipples::new(&ctx, &params, 1.0, edge).expect("GPU ripples");
        for d in &drops {
            cpu.drop(d);
            gpu.drop(&ctx, d);
        }
        let dropped = gpu.read(&ctx).unwrap();
        let err0 = max_abs_diff(&dropped, cpu.current());
        assert!(err0 <= 1e-7, "{edge:?}: drops differ by {err0}"); // Measured on lavapipe: 1.1e-8

        // 200 steps in two submissions, to cover both the recording within a pass and across them.
        for steps in [120, 80] {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            gpu.step(&ctx, &mut encoder, steps);
            ctx.queue.submit([encoder.finish()]);
            for _ in 0..steps {
                cpu.step();
            }
        }
        let got = gpu.read(&ctx).unwrap();
        let err = max_abs_diff(&got, cpu.current());
        let peak = cpu
            .current()
            .data
            .iter()
            .map(|v| v.abs())
            .fold(0.0, f32::max);
        eprintln!(
            "{edge:?}: drops max error {err0:.3e}, after 200 steps {err:.3e} (peak {peak:.3e})"
        );
        assert!(peak > 5e-4, "{edge:?}: the surface went flat"); // Measured on lavapipe: 2.0e-3
        assert!(err <= 5e-8, "{edge:?}: GPU and CPU differ by {err}"); // Measured on lavapipe: 5.9e-9
    }
}

fn max_abs_diff(a: &Grid, b: &Grid) -> f64 {
    assert_eq!((a.cols, a.rows), (b.cols, b.rows));
    a.data
        .iter()
        .zip(&b.data)
        .map(|(&x, &y)| (x as f64 - y as f64).abs())
        .fold(0.0, f64::max)
}

fn an_ocean_beyond_the_device_limits_is_refused() {
    let ctx = test_gpu();
    let limits = ctx.limits();
    let buffer_max = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    // The smallest power of two whose FFT buffer (two complex f32 per sample) is too large.
    let mut n = 4usize;
    while (n * n * 16) as u64 <= buffer_max {
        n *= 2;
    }
    let err = GpuOcean::check_size(&ctx, n).unwrap_err().to_string();
    assert!(
        err.contains("ocean") && err.contains("beyond what this GPU allows"),
        "{err}"
    );
    eprintln!("N {n}: {err}");
    GpuOcean::check_size(&ctx, 64).unwrap();

    // Where the CPU ocean itself allows the resolution (up to 4096; on lavapipe's 128 MiB binding
    // limit it is 4096, a second of CPU work), `new` refuses it before uploading anything.
    if n <= 4096 {
        let ocean = Ocean::new(
            &OceanParams {
                resolution: n,
                ..OceanParams::default()
            },
            10.0,
        )
        .unwrap();
        let err = GpuOcean::new(&ctx, &ocean)
            .err()
            .expect("refused")
            .to_string();
        assert!(err.contains("ocean FFT buffer"), "{err}");
    }
}

/// A live frame's patches take a new edge rule through `set_wrap` alone: after it they are the
/// patches of a frame made with that rule, to the bit, and differ from the former rule's at the
/// grid's edge; the rule is a 16-byte uniform write when it changes and nothing when it does not.
fn patches_take_a_new_edge_rule() {
    use caustics_gpu::water::patches::WaterPatches;
    let ctx = test_gpu();
    let grid = Grid::from_fn(12, 9, |i, j| {
        (0.7 * i as f32 + 0.2).sin() * 0.03 + (1.1 * j as f32).cos() * 0.02
    });
    let heights = ctx.upload_grid("heights", &grid).expect("upload");
    let view = heights.create_view(&Default::default());
    let pass = WaterPatches::new(&ctx);
    let read = |patches: &caustics_gpu::water::patches::Patches| {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        pass.encode(patches, &mut encoder, &mut None);
        ctx.queue.submit([encoder.finish()]);
        ctx.read_texture::<[f32; 4]>(patches.view.texture())
            .expect("patches")
    };
    let mut live = pass.frame(&ctx, &view, false);
    let clamped = read(&live);
    let periodic = read(&pass.frame(&ctx, &view, true));
    let before = ctx.traffic();
    live.set_wrap(&ctx, true);
    assert_eq!(ctx.traffic().since(&before).uploaded_bytes, 16);
    let before = ctx.traffic();
    live.set_wrap(&ctx, true);
    assert_eq!(ctx.traffic().since(&before).uploaded_bytes, 0);
    let switched = read(&live);
    assert!(clamped != periodic, "the edge rule changes no patch");
    assert!(
        switched == periodic,
        "after set_wrap the patches are not the periodic frame's"
    );
    live.set_wrap(&ctx, false);
    assert!(read(&live) == clamped, "set_wrap back to clamped");
}

test_main! {
    gpu patches_take_a_new_edge_rule,
    gpu gpu_ocean_matches_the_cpu_fft,
    gpu ocean_passes_are_timed,
    gpu gpu_ripples_match_the_cpu_scheme,
    gpu an_ocean_beyond_the_device_limits_is_refused,
}
