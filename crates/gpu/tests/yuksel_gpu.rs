//! Technique `yuksel`: the GPU passes against their CPU twin (the scatter against its own,
//! `yuksel::scatter`, as well as against pass 1 and pass 2), and the two GPU variants against each
//! other.

#[macro_use]
mod common;

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::yuksel::{self, YukselParams, YukselSetup};
use caustics_gpu::context::test_gpu;
use caustics_gpu::yuksel::{Variant, Yuksel};
use glam::DVec3;

fn surface(n: usize) -> Grid {
    Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64;
        let y = (i as f64 + 0.5) / n as f64;
        let tau = std::f64::consts::TAU;
        (0.004 * (tau * (3.0 * x + y)).sin() + 0.002 * (tau * (-2.0 * x + 5.0 * y) + 1.0).sin())
            as f32
    })
}

/// Waves whose slopes lean one way (steep fronts, long backs), so the light leans too.
fn lopsided(n: usize) -> Grid {
    Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64;
        let y = (i as f64 + 0.5) / n as f64;
        let tau = std::f64::consts::TAU;
        (0.02 * ((tau * 2.0 * x).sin() + 0.5 * (tau * 4.0 * x).sin()) + 0.001 * (tau * y).sin())
            as f32
    })
}

/// Mean difference relative to the map's mean, and the share of texels more than 10⁻³ of it off:
/// with adaptive footprints a pixel whose misfit lies within f32's rounding of `split` may take
/// another tier on the GPU than in the CPU twin's f64, and its few texels differ by up to the
/// misfit's share of their light.
fn spread(a: &CausticsMap, b: &CausticsMap) -> (f32, f32) {
    let mean = a.texels.iter().map(|t| t[0]).sum::<f32>() / a.texels.len() as f32;
    let d: Vec<f32> = a
        .texels
        .iter()
        .zip(&b.texels)
        .map(|(x, y)| (x[0] - y[0]).abs() / mean)
        .collect();
    let n = d.len() as f32;
    (
        d.iter().sum::<f32>() / n,
        d.iter().filter(|&&v| v > 1e-3).count() as f32 / n,
    )
}

/// Largest difference relative to the map's mean (f32 sums in different orders).
fn worst(a: &CausticsMap, b: &CausticsMap) -> f32 {
    let mean = a.texels.iter().map(|t| t[0]).sum::<f32>() / a.texels.len() as f32;
    a.texels
        .iter()
        .zip(&b.texels)
        .flat_map(|(x, y)| (0..3).map(move |c| (x[c] - y[c]).abs()))
        .fold(0.0, f32::max)
        / mean
}

fn gpu_variants_match_the_cpu_twin() {
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let heights = surface(48);
    for (params, wrap, light, (w, h)) in [
        (
            YukselParams::default(),
            true,
            DVec3::new(0.3, 0.1, -1.0),
            (64, 40),
        ),
        // A sun 5° above the horizon: the flux changes steeply across the patches, which takes
        // finer tiers (`RAMP_WEIGHT`).
        (
            YukselParams::default(),
            true,
            DVec3::new(0.9464, 0.3108, -0.0872),
            (64, 40),
        ),
        // Every pixel's 4 x 4 footprints.
        (
            YukselParams {
                split: 0.0,
                ..Default::default()
            },
            true,
            DVec3::new(0.3, 0.1, -1.0),
            (64, 40),
        ),
        // A map 2,048 wide: the scatter places each box from its own pixel, not from map pixel
        // 0, or its position loses f32's precision (about 1e-4 of a pixel out there).
        (
            YukselParams::default(),
            true,
            DVec3::new(0.3, 0.1, -1.0),
            (2048, 16),
        ),
        // Three samples a side at most: tiers 1, 2 and 3 (not a power of two).
        (
            YukselParams {
                subsamples: Some(3),
                ..Default::default()
            },
            true,
            DVec3::new(-0.2, 0.4, -1.0),
            (48, 40),
        ),
        (
            YukselParams {
                n: Some(9),
                m: Some(10),
                ..Default::default()
            },
            false,
            DVec3::new(-0.5, 0.4, -1.0),
            (50, 70),
        ),
        (
            YukselParams {
                n: Some(3),
                m: Some(30),
                fresnel: false,
                ..Default::default()
            },
            true,
            DVec3::new(0.0, 0.0, -1.0),
            (33, 33),
        ),
        // The paper's method exactly: one sample per pixel landing as a pixel box.
        (
            YukselParams::paper(),
            true,
            DVec3::new(0.2, -0.3, -1.0),
            (40, 48),
        ),
        // Boxes the size of the sample, 2 x 2 per pixel.
        (
            YukselParams {
                subsamples: Some(2),
                footprint: Some(false),
                ..Default::default()
            },
            false,
            DVec3::new(0.4, 0.3, -1.0),
            (36, 36),
        ),
    ] {
        let setup = YukselSetup::new(
            &params,
            w,
            h,
            1.0,
            0.35,
            1.333,
            DVec3::new(0.4, 0.1, 0.05),
            wrap,
            light.normalize(),
        )
        .unwrap();
        let cpu = yuksel::caustics(&setup, &heights);
        let mrt = yuksel
            .caustics(&ctx, &setup, &heights, Variant::RenderTargets, None)
            .expect("render targets");
        let scatter = yuksel
            .caustics(&ctx, &setup, &heights, Variant::Scatter, None)
            .expect("scatter");
        eprintln!(
            "{params:?}: CPU vs render targets {:.2e}, render targets vs scatter {:.2e}",
            worst(&cpu, &mrt),
            worst(&mrt, &scatter)
        );
        let (mean, share) = spread(&cpu, &mrt);
        eprintln!("  CPU vs render targets: mean {mean:.2e}, texels off {share:.2e}");
        if setup.split.is_some() && setup.subsamples > 1 {
            // Adaptive footprints: measured at most 4.25e-4 of the mean in a texel, 2.68e-6 on
            // average, no texel 10⁻³ off (no pixel took another tier here) on lavapipe 25.0.7.
            let d = worst(&cpu, &mrt);
            assert!(d < 4.2e-3, "{params:?}: CPU vs render targets {d}");
            assert!(mean < 2.6e-5, "{params:?}: mean {mean}");
        } else {
            // f32 on both sides; the GPU's bicubic and refraction round differently from the CPU's f64.
            // measured at most 5.29e-5 (CPU vs render targets) on lavapipe 25.0.7 (Mesa), 4 x 4
            // footprints; the paper's preset 6.68e-6
            assert!(
                worst(&cpu, &mrt) < 9.6e-5,
                "{params:?}: CPU vs render targets {}",
                worst(&cpu, &mrt)
            );
        }
        // The scatter sums in 20-bit fixed point (each share rounded by up to 5e-7): measured
        // 1.92e-6 to 7.02e-6 (the 2,048-wide map) over these eight setups on lavapipe 25.0.7. The
        // bound fails the boxes placed from map pixel 0 instead of their own pixel (2.20e-5 on
        // the 2,048-wide map, 8.21e-6 at most on the others).
        assert!(
            worst(&mrt, &scatter) < 1.6e-5,
            "{params:?}: render targets vs scatter {}",
            worst(&mrt, &scatter)
        );
        let max = cpu.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
        assert!(max > 1.1, "the test surface makes caustics: {max}");
    }
}

/// The samples' light meets the receivers on the GPU as on the CPU: over the beach, and over a
/// slab held above a flat floor (an overhang, an object in the receivers' map) whose top takes the
/// light and under which the floor is dark.
fn receivers_match_the_cpu_twin() {
    use caustics_core::scene::{Material, Object, Solids};
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let heights = surface(48);
    let depth = 0.35;
    let beach = common::beach_floor(depth);
    let slab = caustics_core::mesh::cuboid(DVec3::new(0.2, 0.15, 0.02))
        .transformed(glam::DAffine3::from_translation(DVec3::new(0.5, 0.5, 0.2)));
    let mut overhang = common::beach_floor(depth);
    overhang.terrain = None;
    overhang.solids = Solids::of(&[Object {
        mesh: slab,
        material: Material::Diffuse { color: DVec3::ONE },
    }]);
    let light = DVec3::new(0.3, 0.1, -1.0).normalize();
    for (name, floor) in [("terrain", &beach), ("overhang", &overhang)] {
        let setup = YukselSetup::new(
            &YukselParams::default(),
            64,
            64,
            1.0,
            depth,
            1.333,
            DVec3::new(0.4, 0.1, 0.05),
            true,
            light,
        )
        .unwrap()
        .with_floor(floor, None);
        assert!(setup.receivers.is_some());
        let cpu = yuksel::caustics(&setup, &heights);
        let dark = cpu.texels.iter().filter(|t| t[0] == 0.0).count();
        assert!(
            name == "terrain" || dark > 64 * 64 / 20,
            "{dark} texels under the slab"
        );
        for variant in [Variant::RenderTargets, Variant::Scatter] {
            let gpu = yuksel
                .caustics(&ctx, &setup, &heights, variant, None)
                .expect("gpu");
            let (mean, share) = spread(&cpu, &gpu);
            eprintln!(
                "{name}, {variant:?}: worst {:.2e}, mean {mean:.2e}, texels off {share:.2e}",
                worst(&cpu, &gpu)
            );
            // f32 marching against f64 (lavapipe 25.0.7), both variants: the terrain worst
            // 2.74e-4 of the mean, 3.3e-6 on average; the overhang 6.19e-4, 3.5e-6; no texel
            // 1e-3 off.
            assert!(worst(&cpu, &gpu) < 2.7e-3, "{name}, {variant:?}");
            assert!(
                mean < 3.5e-5 && share == 0.0,
                "{name}, {variant:?}: {mean} {share}"
            );
        }
    }
}

/// Through the `Technique` trait on the pool over the beach: frames of moving water under a steady
/// sun reuse the receivers (nothing created, uploaded past the heights, or read back), and the
/// last floor map is the CPU twin's run on the same job.
fn a_terrain_through_the_trait_creates_and_reads_nothing() {
    use caustics_gpu::WaterTextures;
    let ctx = test_gpu();
    let mut scene = common::with_gentle_ripples("pool");
    scene.floor.walls = false;
    scene.caustics.width = 64;
    scene.caustics.height = 64;
    let w = scene.water.clone().unwrap();
    scene.floor.terrain = Some(common::beach_under(w.depth));
    let mut t = caustics_gpu::registry::create(&ctx, "yuksel", &toml::Table::new()).unwrap();
    let (cols, rows) = t.water_resolution(&scene);
    let grid = |time: f64| {
        let surface = w.surface_at(time).unwrap();
        caustics_core::water::sample_grid(surface.as_ref(), cols as usize, rows as usize, w.size)
    };
    let tex = ctx.upload_grid("test heights", &grid(0.0)).unwrap();
    t.configure(&ctx, &scene, &WaterTextures::of(&tex)).unwrap();
    let run = |t: &dyn caustics_gpu::Technique| {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        t.encode(&mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
    };
    t.update(&ctx, &scene).unwrap();
    run(t.as_ref());
    ctx.wait().unwrap();
    let before = ctx.traffic();
    let mut heights = grid(0.0);
    for f in 1..=3 {
        scene.time = 0.1 * f as f64;
        heights = grid(scene.time);
        common::write_heights(&ctx, &tex, &heights);
        t.update(&ctx, &scene).unwrap();
        run(t.as_ref());
    }
    ctx.wait().unwrap();
    let d = ctx.traffic().since(&before);
    eprintln!("three yuksel frames over a terrain: {d:?}");
    assert_eq!(
        (d.created(), d.readbacks, d.uploaded_bytes),
        (0, 0, 0),
        "{d:?}"
    );
    let texels: Vec<[f32; 4]> = ctx.read_texture(t.output().unwrap().texture()).unwrap();
    let gpu = CausticsMap {
        width: 64,
        height: 64,
        size: w.size,
        texels: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
    };
    let surface = w.surface_at(scene.time).unwrap();
    let job = caustics_core::techniques::Job::new(&scene, Some(surface.as_ref()), 1);
    let (setup, cpu_heights) = yuksel::job_setup(&job, &toml::Table::new()).unwrap();
    assert_eq!(cpu_heights, heights);
    let cpu = yuksel::scatter(&setup, &cpu_heights);
    let (mean, _) = spread(&cpu, &gpu);
    let worst = worst(&cpu, &gpu);
    eprintln!("through the trait over a terrain: worst {worst:.2e}, mean {mean:.2e}");
    // Measured on lavapipe: worst 3.7e-4 of the mean. Bounds 10x, the mean's as the direct test's.
    assert!(
        worst < 3.7e-3 && mean < 3.3e-5,
        "worst {worst}, mean {mean}"
    );
}

/// The scatter variant against its CPU twin, `yuksel::scatter` (the same loops: each record added
/// into the map pixels its box covers, clipped to its region, in the same fixed point, then
/// resolved): the defaults, every pixel at 4 x 4, at most 3 x 3, the paper's preset, a fixed
/// region over clamped edges without Fresnel, a map 2,048 wide, and regions the water puts at
/// levels 1 to 3 (a level pixel's light into its 2^level x 2^level map pixels).
fn the_scatter_matches_its_cpu_twin() {
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let heights = surface(48);
    let grazing = |depth: f64| {
        let z = 80f64.to_radians();
        (
            YukselParams::default(),
            true,
            DVec3::new(0.8 * z.sin(), 0.6 * z.sin(), -z.cos()),
            (96, 96),
            depth,
        )
    };
    let mut levels = Vec::new();
    for (params, wrap, light, (w, h), depth) in [
        (
            YukselParams::default(),
            true,
            DVec3::new(0.3, 0.1, -1.0),
            (64, 40),
            0.35,
        ),
        (
            YukselParams {
                split: 0.0,
                ..Default::default()
            },
            true,
            DVec3::new(0.3, 0.1, -1.0),
            (64, 40),
            0.35,
        ),
        (
            YukselParams {
                subsamples: Some(3),
                ..Default::default()
            },
            true,
            DVec3::new(-0.2, 0.4, -1.0),
            (48, 40),
            0.35,
        ),
        (
            YukselParams::paper(),
            true,
            DVec3::new(0.2, -0.3, -1.0),
            (40, 48),
            0.35,
        ),
        (
            YukselParams {
                n: Some(9),
                m: Some(10),
                fresnel: false,
                ..Default::default()
            },
            false,
            DVec3::new(-0.5, 0.4, -1.0),
            (50, 70),
            0.35,
        ),
        (
            YukselParams::default(),
            true,
            DVec3::new(0.3, 0.1, -1.0),
            (2048, 16),
            0.35,
        ),
        // A fixed region the waves overfill: the light beyond it is clipped on both sides.
        (
            YukselParams {
                n: Some(5),
                m: Some(4),
                ..Default::default()
            },
            true,
            DVec3::new(0.3, -0.2, -1.0),
            (40, 40),
            3.0,
        ),
        grazing(0.8),
        grazing(1.5),
        grazing(2.5),
        grazing(4.0),
    ] {
        let setup = YukselSetup::new(
            &params,
            w,
            h,
            1.0,
            depth,
            1.333,
            DVec3::new(0.4, 0.1, 0.05),
            wrap,
            light.normalize(),
        )
        .unwrap();
        let region = setup.region_for(&heights);
        levels.push(region.level);
        let cpu = yuksel::scatter(&setup, &heights);
        let gpu = yuksel
            .caustics(&ctx, &setup, &heights, Variant::Scatter, None)
            .expect("scatter");
        let d = worst(&cpu, &gpu);
        let (mean, share) = spread(&cpu, &gpu);
        eprintln!(
            "{w}x{h}, depth {depth}, {region:?}: CPU scatter vs GPU scatter {d:.2e}, mean {mean:.2e}, texels off {share:.2e}"
        );
        if setup.split.is_none() {
            // Every pixel's k x k, no tier to choose: the records' f32 against f64 alone.
            // measured 3.90e-5 (every pixel 4 x 4) and 8.68e-6 (the paper's) on lavapipe 25.0.7
            assert!(d < 3.9e-4, "{params:?}: CPU vs GPU scatter {d}");
        } else {
            // Adaptive footprints: as against the render targets, a pixel whose misfit lies
            // within f32's rounding of `split` may take another tier. Measured on lavapipe
            // 25.0.7: at most 4.50e-3 of the mean in a texel (the level-3 region, depth 4, where
            // the absorption darkens the first channel whose mean it is taken of), on average at
            // most 3.37e-5, one texel of 9,216 over 10⁻³ off (depth 0.8).
            assert!(
                d < 9e-3,
                "{params:?} at depth {depth}: CPU vs GPU scatter {d}"
            );
            assert!(mean < 3.3e-4, "{params:?} at depth {depth}: mean {mean}");
            assert!(
                share < 1.0e-3,
                "{params:?} at depth {depth}: {share} of the texels off"
            );
        }
    }
    assert!(
        (1..=3).all(|l| levels.contains(&l)),
        "levels 1 to 3 among {levels:?}"
    );
}

/// Where the adapter allows fewer render targets than the channels need, pass 1 draws again for the
/// remaining layers: same map.
fn fewer_render_targets_give_the_same_map() {
    let ctx = test_gpu();
    let mut yuksel = Yuksel::new(&ctx).expect("pipelines");
    let params = YukselParams {
        n: Some(7),
        m: Some(22),
        ..Default::default()
    };
    let setup = YukselSetup::new(
        &params,
        40,
        40,
        1.0,
        0.3,
        1.333,
        DVec3::ZERO,
        true,
        DVec3::new(0.2, 0.3, -1.0),
    )
    .unwrap();
    let heights = surface(40);
    let all = yuksel
        .caustics(&ctx, &setup, &heights, Variant::RenderTargets, None)
        .unwrap();
    yuksel.targets_per_draw = 2;
    let split = yuksel
        .caustics(&ctx, &setup, &heights, Variant::RenderTargets, None)
        .unwrap();
    assert_eq!(all, split);
}

fn a_map_beyond_the_device_limit_is_refused() {
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let max = ctx.limits().max_texture_dimension_2d as usize;
    let setup = YukselSetup::new(
        &YukselParams::default(),
        max + 1,
        4,
        1.0,
        0.3,
        1.333,
        DVec3::ZERO,
        true,
        DVec3::NEG_Z,
    )
    .unwrap();
    let err = yuksel
        .frame(&ctx, &setup, &surface(8), Variant::Scatter)
        .err()
        .expect("refused")
        .to_string();
    assert!(err.contains("yuksel caustics map"), "{err}");
}

/// The region pass chooses on the GPU the region the CPU twin fits from the same heights (N, M, the
/// shift along the refracted sun and the level), at suns from overhead to 85 degrees from the
/// zenith (levels 0 to 3) and over lopsided waves (a shifted region), and both variants then agree
/// with the CPU map.
fn the_gpu_chooses_the_cpus_region() {
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let (waves, leaning) = (surface(48), lopsided(48));
    let mut shifted = false;
    for (zenith, depth) in [
        (0.0f64, 0.2),
        (60.0, 0.6),
        (80.0, 0.4),
        (80.0, 0.8),
        (60.0, 0.02),
        (80.0, 1.5),
        (80.0, 0.6),
        (85.0, 0.35),
        (80.0, 4.0),
        (0.0, 0.5),
    ] {
        // The last case: the lopsided waves under an overhead sun.
        let heights = if depth == 0.5 { &leaning } else { &waves };
        let z = zenith.to_radians();
        let light = DVec3::new(0.8 * z.sin(), 0.6 * z.sin(), -z.cos());
        let setup = YukselSetup::new(
            &YukselParams::default(),
            96,
            96,
            1.0,
            depth,
            1.333,
            DVec3::ZERO,
            true,
            light,
        )
        .unwrap();
        let cpu_region = setup.region_for(heights);
        shifted |= cpu_region.shift != [0, 0];
        let cpu = yuksel::caustics(&setup, heights);
        for variant in [Variant::RenderTargets, Variant::Scatter] {
            let frame = yuksel.frame(&ctx, &setup, heights, variant).unwrap();
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            let texture = yuksel.encode(&frame, &mut encoder, None);
            ctx.queue.submit([encoder.finish()]);
            let gpu_region = yuksel.read_region(&ctx, &frame).unwrap();
            assert_eq!(gpu_region, cpu_region, "sun {zenith}, {variant:?}");
            let texels: Vec<[f32; 4]> = ctx.read_texture(texture).unwrap();
            let gpu = CausticsMap {
                width: 96,
                height: 96,
                size: 1.0,
                texels: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
            };
            let d = worst(&cpu, &gpu);
            let (mean, share) = spread(&cpu, &gpu);
            eprintln!("sun {zenith}, {variant:?}: {d:.2e} mean {mean:.2e} texels off {share:.2e}");
            // Adaptive footprints (the default): a pixel whose misfit lies within rounding of
            // `split` may take another tier than the CPU's. Measured on lavapipe 25.0.7 (Mesa): on
            // average at most 4.19e-5 of the mean (sun 80, depth 4, level 3), at most 2.17e-4 of
            // the texels over 10⁻³ off, the largest 5.12e-2 (sun 80, depth 0.4: such a pixel);
            // without one, 1.14e-3. A texel off by more than 0.2 of the mean would be a pixel's
            // light misplaced, not a tier taken at the rounding of `split`.
            assert!(mean < 4.1e-4, "sun {zenith}, {variant:?}: mean {mean}");
            assert!(
                share < 2.1e-3,
                "sun {zenith}, {variant:?}: {share} of the texels off"
            );
            assert!(d < 0.2, "sun {zenith}, {variant:?}: {d}");
        }
        eprintln!("sun {zenith}, depth {depth}: {cpu_region:?}");
    }
    assert!(shifted, "a case with a shifted region");
}

/// The region pass's bound to a fraction of a pixel: over 161 depths at one sun the region grows
/// through many sizes, and at every depth the GPU's is the CPU twin's; a margin or a deflection
/// bound a fraction of a percent off moves some of the steps to other depths.
fn the_region_steps_at_the_cpus_depths() {
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let heights = surface(48);
    let z = 70f64.to_radians();
    let light = DVec3::new(0.8 * z.sin(), 0.6 * z.sin(), -z.cos());
    let mut regions = Vec::new();
    for k in 0..161 {
        let depth = 0.2 + 0.005 * k as f64;
        let setup = YukselSetup::new(
            &YukselParams::default(),
            64,
            64,
            1.0,
            depth,
            1.333,
            DVec3::ZERO,
            true,
            light,
        )
        .unwrap();
        let cpu = setup.region_for(&heights);
        let frame = yuksel
            .frame(&ctx, &setup, &heights, Variant::Scatter)
            .unwrap();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        yuksel.encode(&frame, &mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
        let gpu = yuksel.read_region(&ctx, &frame).unwrap();
        assert_eq!(gpu, cpu, "depth {depth}");
        regions.push((cpu.n, cpu.m, cpu.shift, cpu.level));
    }
    regions.dedup();
    eprintln!("{} regions over the sweep: {regions:?}", regions.len());
    // The sweep passes through many region sizes (measured: 17, every one equal to the CPU's).
    assert!(regions.len() >= 10, "only {} regions", regions.len());
}

/// A fixed region that the waves overfill: light reaches its first and last rows and columns, so
/// pass 2 must sum every channel (dropping channel M loses the light the samples send M/2 rows on).
fn light_at_the_regions_edge_counts_in_every_channel() {
    let ctx = test_gpu();
    let yuksel = Yuksel::new(&ctx).expect("pipelines");
    let heights = surface(40);
    let params = YukselParams {
        n: Some(5),
        m: Some(4),
        ..Default::default()
    };
    let setup = YukselSetup::new(
        &params,
        40,
        40,
        1.0,
        3.0,
        1.333,
        DVec3::ZERO,
        true,
        DVec3::new(0.3, -0.2, -1.0).normalize(),
    )
    .unwrap();
    let pre = yuksel::prepass(&setup, &heights);
    let p1 = yuksel::pass1(&setup, &pre, 0);
    let ch = setup.region.m + 1;
    let channel = |k: usize| {
        p1.iter()
            .skip(k)
            .step_by(ch)
            .map(|&v| v as f64)
            .sum::<f64>()
    };
    let total: f64 = (0..ch).map(channel).sum();
    eprintln!(
        "first and last channels: {:.3} and {:.3} of the light",
        channel(0) / total,
        channel(ch - 1) / total
    );
    // measured: the first and last channels carry 23.4 % and 23.2 % of the light.
    for k in [0, ch - 1] {
        assert!(
            channel(k) > 0.1 * total,
            "channel {k}: {} of {total}",
            channel(k)
        );
    }
    let cpu = yuksel::caustics(&setup, &heights);
    for variant in [Variant::RenderTargets, Variant::Scatter] {
        let gpu = yuksel
            .caustics(&ctx, &setup, &heights, variant, None)
            .unwrap();
        // measured 2.17e-4 (render targets) and 2.16e-4 (scatter) on lavapipe 25.0.7 (Mesa)
        let d = worst(&cpu, &gpu);
        eprintln!("edge of the region, {variant:?}: {d:.2e}");
        assert!(d < 3.2e-4, "{variant:?}: {d}");
    }
}

test_main! {
    gpu gpu_variants_match_the_cpu_twin,
    gpu the_scatter_matches_its_cpu_twin,
    gpu receivers_match_the_cpu_twin,
    gpu a_terrain_through_the_trait_creates_and_reads_nothing,
    gpu fewer_render_targets_give_the_same_map,
    gpu a_map_beyond_the_device_limit_is_refused,
    gpu the_gpu_chooses_the_cpus_region,
    gpu light_at_the_regions_edge_counts_in_every_channel,
    gpu the_region_steps_at_the_cpus_depths,
}
