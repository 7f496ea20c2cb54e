//! The shared WGSL math against its CPU twins in `caustics-core`, evaluated on the GPU.

#[macro_use]
mod common;

use caustics_core::grid::{Edge, Grid};
use caustics_core::optics::{flat_water_light, fresnel_transmittance, refract, sun_under_water};
use caustics_core::water::Surface;
use caustics_core::water::procedural::{Procedural, ProceduralParams};
use caustics_core::water::waves::{Wave, Waves};
use caustics_gpu::context::test_gpu;
use caustics_gpu::probe::{self, PROBE_ABSORPTION, ProbeIn, ProbeSetup};
use caustics_gpu::water::{GpuProceduralWave, GpuSineWave};
use glam::{DVec2, DVec3};

/// `|gpu − cpu| ≤ tol · (1 + |cpu|)`. Each call's bound is within 10x of the largest such error
/// measured on lavapipe over the 128 probes (written beside it).
fn close(gpu: f32, cpu: f64, tol: f64, what: &str) {
    assert!(
        (gpu as f64 - cpu).abs() <= tol * (1.0 + cpu.abs()),
        "{what}: GPU {gpu}, CPU {cpu}"
    );
}

/// The depth under the water probe `(a, b)` evaluates `flat_water_light` at: 0 to 3 m.
fn depth(a: usize, b: usize) -> f64 {
    (a * 8 + b) as f64 * 3.0 / 128.0
}

fn wgsl_optics_and_water_match_the_cpu() {
    let ctx = test_gpu();
    let size = 2.0;
    let waves = Waves::new(
        &[
            Wave {
                amplitude: 0.01,
                wavelength: 0.3,
                direction: [1.0, 0.4],
                phase: 0.2,
                period: None,
            },
            Wave {
                amplitude: 0.004,
                wavelength: 0.11,
                direction: [-0.5, 1.0],
                phase: 1.0,
                period: None,
            },
        ],
        size,
        0.8,
    );
    let procedural = Procedural {
        params: ProceduralParams::default(),
        t: 0.6,
    };
    let grid = Grid::from_fn(32, 24, |i, j| {
        (0.3 * i as f32).sin() * 0.01 + (0.2 * j as f32).cos() * 0.02
    });

    // Directions over the hemisphere, normals tilted, points over the square and beyond it.
    let mut inputs = Vec::new();
    let mut expect = Vec::new();
    for a in 0..16 {
        for b in 0..8 {
            let theta = 0.05 + 1.5 * b as f64 / 8.0;
            let phi = a as f64 * 0.4;
            let d = DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                -theta.cos(),
            );
            let n =
                DVec3::new(0.1 * (a as f64 - 8.0) / 8.0, 0.05 * (b as f64 - 4.0), 1.0).normalize();
            let eta = if a % 2 == 0 { 1.0 / 1.333 } else { 1.333 };
            let p = DVec2::new(a as f64 * 0.17 - 0.3, b as f64 * 0.31 - 0.2);
            inputs.push(ProbeIn {
                incident: [d.x as f32, d.y as f32, d.z as f32, eta as f32],
                normal: [n.x as f32, n.y as f32, n.z as f32, 1.333],
                point: [p.x as f32, p.y as f32, depth(a, b) as f32, 0.0],
            });
            expect.push((d, n, eta, p, depth(a, b)));
        }
    }
    let out = probe::run(
        &ctx,
        &inputs,
        &ProbeSetup {
            waves: &GpuSineWave::from_waves(&waves),
            procedural: GpuProceduralWave::from(&procedural),
            grid: &grid,
            size: size as f32,
            wrap: true,
        },
    )
    .expect("probe runs");

    let grid_surface = caustics_core::water::GridSurface {
        grid: grid.clone(),
        size,
        edge: Edge::Wrap,
    };
    let absorption = DVec3::from(PROBE_ABSORPTION);
    for (o, (d, n, eta, p, depth)) in out.iter().zip(&expect) {
        // The shading rule (`caustics_light.wgsl`): the sun opposite `d` under water, and flat
        // water's light on `n` at `depth`.
        let toward_sun = sun_under_water(-*d, 1.333);
        for c in 0..3 {
            close(o.sun_under[c], toward_sun[c], 5e-7, "sun under water"); // Measured on lavapipe: 5.2e-8
        }
        let flat = flat_water_light(absorption, *depth, toward_sun, *n);
        for c in 0..3 {
            close(o.flat_light[c], flat[c], 1e-6, "flat water's light"); // Measured on lavapipe: 1.1e-7
        }
        match refract(*d, *n, *eta) {
            Some(t) => {
                assert_eq!(o.refracted[3], 1.0);
                for c in 0..3 {
                    close(o.refracted[c], t[c], 1.5e-6, "refract"); // Measured on lavapipe: 1.9e-7
                }
            }
            None => assert_eq!(o.refracted[3], 0.0, "total internal reflection"),
        }
        close(
            o.fresnel_sine[0],
            fresnel_transmittance(-d.dot(*n), 1.0, 1.333),
            1e-6,
            "fresnel",
        ); // Measured on lavapipe: 1.1e-7
        let (h, g) = waves.height_gradient(*p);
        close(o.fresnel_sine[1], h, 3e-7, "waves h"); // Measured on lavapipe: 3.6e-8
        close(o.fresnel_sine[2], g.x, 1e-5, "waves dh/dx"); // Measured on lavapipe: 1.1e-6
        close(o.fresnel_sine[3], g.y, 1e-5, "waves dh/dy"); // Measured on lavapipe: 1.1e-6
        let (h, g) = procedural.height_gradient(*p);
        close(o.procedural[0], h, 4e-6, "procedural h"); // Measured on lavapipe: 5.0e-7
        close(o.procedural[1], g.x, 1.5e-4, "procedural dh/dx"); // Measured on lavapipe: 1.7e-5
        close(o.procedural[2], g.y, 2e-4, "procedural dh/dy"); // Measured on lavapipe: 2.2e-5
        let (h, g) = grid_surface.height_gradient(*p);
        close(o.grid[0], h, 8e-8, "grid h"); // Measured on lavapipe: 9.2e-9
        close(o.grid[1], g.x, 8e-7, "grid dh/dx"); // Measured on lavapipe: 9.9e-8
        close(o.grid[2], g.y, 1.5e-6, "grid dh/dy"); // Measured on lavapipe: 1.6e-7
    }
}

/// The heights' Hermite form (`water_patches.wgsl`, `grid_sample_hermite`) is the bicubic surface
/// the CPU's grid samples: periodic and clamped, on a grid and on grids of one and two texels a
/// side, at points over the square and beyond it (where the clamped surface has no slope across
/// its edge).
fn hermite_heights_are_the_bicubic_surface() {
    let ctx = test_gpu();
    let size = 1.3;
    let (mut worst, mut bicubic) = ([0f64; 3], [0f64; 3]);
    for (cols, rows) in [(32, 24), (2, 3), (1, 1)] {
        let grid = Grid::from_fn(cols, rows, |i, j| {
            (0.3 * i as f32 + 0.1).sin() * 0.01 + (0.7 * j as f32).cos() * 0.02
        });
        for wrap in [true, false] {
            let points: Vec<DVec2> = (0..400)
                .map(|k| DVec2::new((k % 20) as f64, (k / 20) as f64) * 0.083 - 0.2)
                .collect();
            let inputs: Vec<ProbeIn> = points
                .iter()
                .map(|p| ProbeIn {
                    incident: [0.0, 0.0, -1.0, 1.0],
                    normal: [0.0, 0.0, 1.0, 1.333],
                    point: [p.x as f32, p.y as f32, 0.0, 0.0],
                })
                .collect();
            let out = probe::run(
                &ctx,
                &inputs,
                &ProbeSetup {
                    waves: &[],
                    procedural: GpuProceduralWave::default(),
                    grid: &grid,
                    size: size as f32,
                    wrap,
                },
            )
            .expect("probe runs");
            let surface = caustics_core::water::GridSurface {
                grid: grid.clone(),
                size,
                edge: if wrap { Edge::Wrap } else { Edge::Clamp },
            };
            for (o, p) in out.iter().zip(&points) {
                let (h, g) = surface.height_gradient(*p);
                for (k, want) in [h, g.x, g.y].into_iter().enumerate() {
                    worst[k] = worst[k].max((o.hermite[k] as f64 - want).abs());
                    bicubic[k] = bicubic[k].max((o.grid[k] as f64 - want).abs());
                }
            }
        }
    }
    eprintln!(
        "Hermite against the CPU's bicubic: worst |dh| {:.1e}, |dh/dx| {:.1e}, |dh/dy| {:.1e}; \
         grid_sample's {:.1e}, {:.1e}, {:.1e}",
        worst[0], worst[1], worst[2], bicubic[0], bicubic[1], bicubic[2]
    );
    // Measured on lavapipe: 1.2e-7, 2.9e-6, 2.2e-7 (f32's rounding of the same sums).
    let bounds = [1.2e-6, 2.9e-5, 2.2e-6];
    for k in 0..3 {
        assert!(worst[k] < bounds[k], "{k}: {}", worst[k]);
    }
}

fn textures_beyond_the_device_limit_are_refused() {
    let ctx = test_gpu();
    let max = ctx.limits().max_texture_dimension_2d;
    let err = ctx
        .check_texture_size("caustics map", max + 1, 16)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("caustics map") && err.contains(&format!("{}", max + 1)),
        "{err}"
    );
    assert!(ctx.check_texture_size("caustics map", 0, 16).is_err());
    assert!(ctx.check_texture_size("caustics map", 64, 64).is_ok());
}

test_main! {
    gpu wgsl_optics_and_water_match_the_cpu,
    gpu hermite_heights_are_the_bicubic_surface,
    gpu textures_beyond_the_device_limit_are_refused,
}
