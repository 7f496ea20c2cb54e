//! Technique `procedural`: each GPU variant against its CPU twin, and the texture-space variant's
//! mip chain against point sampling on a surface too fine for the map.

#[macro_use]
mod common;

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::procedural::{
    self, ProceduralCausticsParams, ProceduralSetup, SurfaceInput, Variant,
};
use caustics_core::water::procedural::{Procedural, ProceduralParams};
use caustics_gpu::context::test_gpu;
use caustics_gpu::procedural::ProceduralCaustics;
use glam::DVec3;

/// The share of the floor's light the caustic does not modulate in these tests.
const GROUND: f32 = 0.25;

fn surface(n: usize) -> Grid {
    Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64;
        let y = (i as f64 + 0.5) / n as f64;
        let tau = std::f64::consts::TAU;
        (0.002 * (tau * (3.0 * x + y)).sin() + 0.001 * (tau * (-2.0 * x + 5.0 * y) + 1.0).sin())
            as f32
    })
}

/// Largest and mean absolute difference over every channel.
fn diff(a: &CausticsMap, b: &CausticsMap) -> (f32, f32) {
    let d: Vec<f32> = a
        .texels
        .iter()
        .zip(&b.texels)
        .flat_map(|(x, y)| (0..3).map(move |c| (x[c] - y[c]).abs()))
        .collect();
    let max = d.iter().copied().fold(0.0, f32::max);
    (max, d.iter().sum::<f32>() / d.len() as f32)
}

/// The share of texels differing by more than `tol`.
fn outliers(a: &CausticsMap, b: &CausticsMap, tol: f32) -> f64 {
    let n = a
        .texels
        .iter()
        .zip(&b.texels)
        .filter(|(x, y)| (0..3).any(|c| (x[c] - y[c]).abs() > tol))
        .count();
    n as f64 / a.texels.len() as f64
}

#[allow(clippy::too_many_arguments)]
fn setup(
    variant: Variant,
    (w, h): (usize, usize),
    follow_sun: bool,
    wrap: bool,
    light: DVec3,
    mesh: u32,
    (target, anisotropy): (u32, u32),
) -> ProceduralSetup {
    let params = ProceduralCausticsParams {
        variant,
        follow_sun,
        mesh_resolution: mesh,
        target_resolution: target,
        anisotropy,
        // A quarter of the floor's light unmodulated, so the blend is exercised too.
        ground: GROUND as f64,
        ..Default::default()
    };
    ProceduralSetup::new(
        &params,
        w,
        h,
        1.0,
        0.35,
        DVec3::new(0.4, 0.1, 0.05),
        wrap,
        light,
    )
    .unwrap()
}

/// Screen and vertex variants, height grid and the paper's wave, wrapped and clamped, paper's sun
/// and the scene's: the GPU (f32) against the CPU twin (f64).
///
/// Tolerance: the per-point work agrees to rounding except where a texel's refracted direction falls
/// on the sun disk's edge, where the light map climbs from the halo level to 1 within one of its
/// texels (2.5e-4 rad) and an f32 direction moves the value most. Measured on lavapipe over the
/// eight cases: mean difference up to 7.6e-7, largest 7.6e-5, and at most 1.4 % of the texels
/// differing by more than 1e-5.
fn screen_and_vertex_variants_match_the_cpu_twin() {
    let ctx = test_gpu();
    let gpu = ProceduralCaustics::new(&ctx).expect("pipelines");
    let grid = surface(48);
    let wave = Procedural {
        params: ProceduralParams {
            amplitude: 0.0005,
            ..Default::default()
        },
        t: 0.4,
    };
    let tilted = DVec3::new(0.3, -0.2, -1.0).normalize();
    for variant in [Variant::Screen, Variant::Vertex] {
        for (water, follow_sun, wrap, light, size, mesh) in [
            (SurfaceInput::Grid(&grid), false, true, tilted, (64, 40), 32),
            (SurfaceInput::Grid(&grid), true, false, tilted, (50, 70), 25),
            (
                SurfaceInput::Wave(&wave),
                false,
                true,
                DVec3::NEG_Z,
                (96, 96),
                48,
            ),
            (SurfaceInput::Wave(&wave), true, true, tilted, (33, 33), 11),
        ] {
            let s = setup(variant, size, follow_sun, wrap, light, mesh, (256, 16));
            let cpu = procedural::caustics(&s, &water);
            let out = gpu.caustics(&ctx, &s, &water, None).expect("GPU map");
            let (max, mean) = diff(&cpu, &out);
            let share = outliers(&cpu, &out, 1e-5);
            let what = format!("{variant:?} {size:?} follow_sun {follow_sun} wrap {wrap}");
            eprintln!("{what}: max {max:.2e}, mean {mean:.2e}, share > 1e-5: {share:.4}");
            assert!(mean < 5e-6, "{what}: mean difference {mean}"); // Measured on lavapipe: 7.6e-7
            assert!(max < 5e-4, "{what}: largest difference {max}"); // Measured on lavapipe: 7.6e-5
            // Measured on lavapipe: 0.0138
            assert!(
                share < 0.05,
                "{what}: {share} of the texels differ by > 1e-5"
            );
            let hi = cpu.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
            let lo = cpu.texels.iter().map(|t| t[0]).fold(1.0, f32::min);
            assert!(
                hi > GROUND + 0.5 * (1.0 - GROUND) && lo < GROUND + 0.1 * (1.0 - GROUND),
                "{what}: the water makes a pattern, {lo}..{hi}"
            );
        }
    }
}

/// The texture-space variant: target pass and mip chain exactly as the CPU's (same sums in the same
/// order), then the hardware's sampler against the CPU's reading of it.
///
/// Trilinear (`anisotropy = 1`): where the level of detail is an integer and the footprint square
/// (a 256 target into a 64 or 128 map), or the map magnified (into 300 x 200: level 0, bilinear),
/// the sampler reads the texels the CPU twin reads and the maps agree to rounding. Where the level
/// is fractional (a 128 target into a 96 map: λ = 0.415) or the footprint elongated (into 48 x 96:
/// λ = log2 of the major axis), lavapipe's LOD and weights are approximations of the exact ones.
/// Each case carries its own bounds, within 10x of what lavapipe measured (written beside them).
///
/// Anisotropic (`anisotropy = 16`, the default): the filter is the implementation's. lavapipe's
/// (Mesa's `lp_build_sample_aniso`) is Heckbert's elliptical weighted average: Gaussian weights over
/// the nearest texels of one level inside the footprint's ellipse widened by one texel each way
/// (`A = v² + 1`, `C = u² + 1`), derivatives taken from the coordinates themselves. Even for a square
/// footprint it blurs over about √2 texels of the level where the CPU twin's trilinear reads one:
/// measured mean difference up to 1.9e-2 (0.059 of the map's mean, on the 64² map), largest up to
/// 0.22, and a blur, not a misplacement: the two correlate above 0.98 (measured 0.9869 at worst).
fn texture_variant_matches_the_cpu_twin() {
    let ctx = test_gpu();
    let gpu = ProceduralCaustics::new(&ctx).expect("pipelines");
    let grid = surface(64);
    let water = SurfaceInput::Grid(&grid);
    let tilted = DVec3::new(0.3, -0.2, -1.0).normalize();
    for anisotropy in [1, 16] {
        // Bounds on (largest, mean) difference: [trilinear, anisotropic].
        for (size, target, wrap, bounds) in [
            // Measured on lavapipe: (9.5e-7, 4.7e-8), (0.205, 1.9e-2)
            ((64, 64), 256, true, [(5e-6, 4e-7), (0.4, 0.06)]),
            // Measured on lavapipe: (4.4e-6, 6.1e-8), (0.223, 1.05e-2)
            ((128, 128), 256, false, [(2e-5, 4e-7), (0.4, 0.05)]),
            // Measured on lavapipe: (5.0e-3, 3.4e-4), (8.0e-2, 3.7e-3)
            ((96, 96), 128, true, [(2e-2, 2e-3), (0.4, 0.02)]),
            // Measured on lavapipe: (8.1e-6, 1.1e-7), (0.123, 3.3e-3)
            ((300, 200), 128, true, [(5e-5, 8e-7), (0.4, 0.02)]),
            // Measured on lavapipe: (8.4e-3, 8.8e-4), (8.5e-2, 4.6e-3)
            ((48, 96), 128, false, [(2e-2, 2e-3), (0.4, 0.02)]),
        ] {
            let s = setup(
                Variant::Texture,
                size,
                false,
                wrap,
                tilted,
                16,
                (target, anisotropy),
            );
            let cpu = procedural::caustics(&s, &water);
            let out = gpu.caustics(&ctx, &s, &water, None).expect("GPU map");
            let (max, mean) = diff(&cpu, &out);
            let level = mean_of(&cpu);
            let r = correlation(&cpu, &out);
            let what = format!("{size:?} from {target}², wrap {wrap}, anisotropy {anisotropy}");
            eprintln!(
                "texture {what}: λ, taps = {:?}; max {max:.2e}, mean {mean:.2e} (map mean {level:.3}), correlation {r:.4}",
                procedural::sampling_footprint(&s)
            );
            let (max_bound, mean_bound) = bounds[usize::from(anisotropy > 1)];
            assert!(max < max_bound, "{what}: largest difference {max}");
            assert!(mean < mean_bound, "{what}: mean difference {mean}");
            if anisotropy > 1 {
                assert!(r > 0.98, "{what}: correlation {r}"); // Measured on lavapipe: 0.9869
            }
        }
    }
}

fn mean_of(m: &CausticsMap) -> f32 {
    m.texels.iter().map(|t| t[0]).sum::<f32>() / m.texels.len() as f32
}

fn correlation(a: &CausticsMap, b: &CausticsMap) -> f64 {
    let (ma, mb) = (mean_of(a) as f64, mean_of(b) as f64);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for (x, y) in a.texels.iter().zip(&b.texels) {
        let (x, y) = (x[0] as f64 - ma, y[0] as f64 - mb);
        ab += x * y;
        aa += x * x;
        bb += y * y;
    }
    ab / (aa * bb).sqrt()
}

/// Flat water under the paper's sun gives exactly 1 in every variant on the GPU too (measured on
/// lavapipe: every channel exactly 1.0 in all three variants).
fn flat_water_gives_one_on_the_gpu() {
    let ctx = test_gpu();
    let gpu = ProceduralCaustics::new(&ctx).expect("pipelines");
    let flat = Grid::new(8, 8);
    for variant in Variant::ALL {
        let params = ProceduralCausticsParams {
            variant,
            absorption: false,
            mesh_resolution: 7,
            target_resolution: 64,
            ..Default::default()
        };
        let s = ProceduralSetup::new(
            &params,
            40,
            30,
            2.0,
            0.5,
            DVec3::ONE,
            true,
            DVec3::new(0.5, 0.5, -1.0),
        )
        .unwrap();
        let m = gpu
            .caustics(&ctx, &s, &SurfaceInput::Grid(&flat), None)
            .expect("GPU map");
        for t in &m.texels {
            assert!(
                t.iter().all(|&c| (c - 1.0).abs() < 1e-6),
                "{variant:?}: {t:?}"
            );
        }
    }
}

/// A box average of `fine` (a `k`-times finer square map) down to the map's size.
fn box_down(fine: &CausticsMap, k: usize) -> Vec<f64> {
    let (w, h) = (fine.width / k, fine.height / k);
    let mut out = vec![0.0; w * h];
    for i in 0..fine.height {
        for j in 0..fine.width {
            out[(i / k) * w + j / k] += fine.texels[i * fine.width + j][0] as f64;
        }
    }
    out.iter().map(|v| v / (k * k) as f64).collect()
}

fn rms_against(map: &CausticsMap, truth: &[f64]) -> f64 {
    let s: f64 = map
        .texels
        .iter()
        .zip(truth)
        .map(|(t, r)| (t[0] as f64 - r).powi(2))
        .sum();
    (s / truth.len() as f64).sqrt()
}

/// Energy of the map above half its Nyquist frequency (a 2-D DFT by rows and columns), over the
/// total energy of its fluctuation.
fn high_frequency_share(map: &CausticsMap) -> f64 {
    let (w, h) = (map.width, map.height);
    let mean = map.texels.iter().map(|t| t[0] as f64).sum::<f64>() / (w * h) as f64;
    let data: Vec<f64> = map.texels.iter().map(|t| t[0] as f64 - mean).collect();
    let tau = std::f64::consts::TAU;
    // Rows first, then columns (naive DFT: the maps are 64 x 64).
    let mut rows = vec![(0.0, 0.0); w * h];
    for i in 0..h {
        for u in 0..w {
            let (mut re, mut im) = (0.0, 0.0);
            for j in 0..w {
                let a = -tau * (u * j) as f64 / w as f64;
                re += data[i * w + j] * a.cos();
                im += data[i * w + j] * a.sin();
            }
            rows[i * w + u] = (re, im);
        }
    }
    let (mut high, mut total) = (0.0, 0.0);
    for u in 0..w {
        for v in 0..h {
            let (mut re, mut im) = (0.0, 0.0);
            for i in 0..h {
                let a = -tau * (v * i) as f64 / h as f64;
                let (r, m) = rows[i * w + u];
                re += r * a.cos() - m * a.sin();
                im += r * a.sin() + m * a.cos();
            }
            let e = re * re + im * im;
            let fu = u.min(w - u) as f64 / w as f64;
            let fv = v.min(h - v) as f64 / h as f64;
            total += e;
            if fu.max(fv) > 0.25 {
                high += e;
            }
        }
    }
    high / total
}

/// On a surface much finer than the map (the paper's wave function, whose frequency grows with
/// x·y), point sampling per pixel aliases and the texture-space variant's mip chain does not: far
/// less of the mipmapped map's energy sits above half its Nyquist frequency, and (trilinear) it is
/// much closer to the map's true texel averages (the per-pixel caustic at 16 x 16 points per texel,
/// box-averaged). Both follow from what WGSL and Vulkan specify for a mip-filtered sample: the level
/// of detail comes from the screen-space derivatives (Vulkan 1.3 §16.6.7, "Scale Factor Operation,
/// LOD Operation and Image Level(s) Selection"), so each pixel reads a prefiltered average of about
/// its own footprint. Anisotropic filtering is held only to aliasing no more than trilinear: Vulkan
/// leaves its filter implementation-dependent (§16.6.8, "Texel Anisotropic Filtering", which bounds
/// the level by the footprint's minor axis and the sample count by `maxAnisotropy`), and lavapipe
/// changed it between Mesa 22.3.6 (an elliptical Gaussian wider than the texel, which also blurs
/// away true texel-scale detail) and Mesa 25.0.7 (the same as trilinear on this near-isotropic
/// footprint). Its distance to the box averages is printed, not asserted.
fn the_mip_chain_aliases_less_than_point_sampling() {
    let ctx = test_gpu();
    let gpu = ProceduralCaustics::new(&ctx).expect("pipelines");
    let wave = Procedural {
        params: ProceduralParams {
            amplitude: 0.0005,
            ..Default::default()
        },
        t: 0.3,
    };
    let water = SurfaceInput::Wave(&wave);
    let n = 64;
    let make = |variant, res: usize, anisotropy| {
        setup(
            variant,
            (res, res),
            false,
            true,
            DVec3::NEG_Z,
            16,
            (256, anisotropy),
        )
    };
    let run = |s: &ProceduralSetup| gpu.caustics(&ctx, s, &water, None).expect("GPU map");
    let point = run(&make(Variant::Screen, n, 16));
    let trilinear = run(&make(Variant::Texture, n, 1));
    let anisotropic = run(&make(Variant::Texture, n, 16));
    let truth = box_down(&run(&make(Variant::Screen, 16 * n, 16)), 16);
    let e = |m: &CausticsMap| rms_against(m, &truth);
    let h = high_frequency_share;
    eprintln!(
        "RMS against the 16 x 16 supersampled map: point {:.5}, trilinear mips {:.5}, anisotropic {:.5}; \
         energy above half Nyquist: point {:.5}, trilinear {:.5}, anisotropic {:.5} ({:+.1e} from trilinear)",
        e(&point),
        e(&trilinear),
        e(&anisotropic),
        h(&point),
        h(&trilinear),
        h(&anisotropic),
        h(&anisotropic) - h(&trilinear)
    );
    // Measured, RMS: point 0.0527, trilinear 0.0049 (0.093 of it) on lavapipe from Mesa 22.3.6 and
    // from Mesa 25.0.7 alike.
    assert!(e(&trilinear) < 0.25 * e(&point));
    // Measured, share above half Nyquist: point 0.322, trilinear 0.194 (0.60 of it) on both.
    assert!(h(&trilinear) < 0.7 * h(&point));
    // Measured, anisotropic's share: 0.022 on Mesa 22.3.6 (0.17 below trilinear's), 0.19362 on
    // Mesa 25.0.7 (trilinear's exactly). Not a tolerance on a measurement but the spec's allowance:
    // §16.6.8's level comes from the footprint's minor axis, so on a slightly anisotropic footprint
    // a conforming filter may be a little sharper than trilinear; 5 % of the gap between trilinear
    // and point sampling is left for that.
    assert!(h(&anisotropic) < h(&trilinear) + 0.05 * (h(&point) - h(&trilinear)));
}

fn a_map_beyond_the_device_limit_is_refused() {
    let ctx = test_gpu();
    let gpu = ProceduralCaustics::new(&ctx).expect("pipelines");
    let max = ctx.limits().max_texture_dimension_2d as usize;
    let grid = surface(8);
    let s = setup(
        Variant::Screen,
        (max + 1, 4),
        false,
        true,
        DVec3::NEG_Z,
        8,
        (256, 16),
    );
    let err = gpu
        .frame(&ctx, &s, &SurfaceInput::Grid(&grid))
        .err()
        .expect("refused")
        .to_string();
    assert!(err.contains("procedural caustics map"), "{err}");
}

// ---------------------------------------------------------------------------------------------
// Through the `Technique` interface: the registered names on a scene, the caller's heights.

use caustics_core::scene::Scene;
use caustics_core::water::sample_grid;
use caustics_gpu::GpuContext;
use caustics_gpu::registry;
use caustics_gpu::technique::{Technique, WaterTextures};

/// Every name paper 2 is registered under, with the variant it runs.
const REGISTERED: [(&str, Variant); 4] = [
    ("procedural", Variant::Screen),
    ("procedural-vertex", Variant::Vertex),
    ("procedural-screen", Variant::Screen),
    ("procedural-texture", Variant::Texture),
];

/// The pool's waves with a 64 x 64 map.
fn pool() -> Scene {
    let mut scene = Scene::builtin("pool").expect("built-in scene");
    scene.caustics.width = 64;
    scene.caustics.height = 64;
    scene
}

/// The scene's sun (`follow_sun`, so that a moving sun changes the map), a small mesh and target,
/// and trilinear filtering of the target's chain (64² map from a 128² target: an integer level of
/// detail, where the sampler and the CPU twin read the same texels; see
/// `texture_variant_matches_the_cpu_twin`).
fn trait_params() -> toml::Table {
    "procedural = { follow_sun = true, mesh_resolution = 32, target_resolution = 128, anisotropy = 1, ground = 0.25 }"
        .parse()
        .expect("toml")
}

/// The CPU twin's map for `scene` with `heights`, as the application's Runner makes it.
fn cpu_map(scene: &Scene, variant: Variant, heights: &Grid) -> CausticsMap {
    let mut params = ProceduralCausticsParams::from_table(&trait_params()).expect("params");
    params.variant = variant;
    let w = scene.water.as_ref().expect("water");
    let setup = ProceduralSetup::new(
        &params,
        scene.caustics.width as usize,
        scene.caustics.height as usize,
        w.size,
        w.depth,
        w.absorption,
        w.wrap,
        scene.light.direction,
    )
    .expect("setup")
    .with_floor(&scene.floor, None);
    setup.received(procedural::caustics(&setup, &SurfaceInput::Grid(heights)))
}

/// `name` created through the registry and configured on `scene`, reading the scene's surface
/// sampled at the technique's own `water_resolution` (returned, with the texture it lives in).
fn configured(
    ctx: &GpuContext,
    name: &str,
    scene: &Scene,
) -> (Box<dyn Technique>, Grid, wgpu::Texture) {
    let mut t = registry::create(ctx, name, &trait_params()).expect("registered");
    let (cols, rows) = t.water_resolution(scene);
    let w = scene.water.as_ref().expect("water");
    let surface = w.surface_at(scene.time).expect("surface");
    let heights = sample_grid(surface.as_ref(), cols as usize, rows as usize, w.size);
    let texture = ctx.upload_grid("test heights", &heights).expect("upload");
    t.configure(ctx, scene, &WaterTextures::of(&texture))
        .expect("configure");
    (t, heights, texture)
}

fn frame(ctx: &GpuContext, t: &mut dyn Technique, scene: &Scene) {
    t.update(ctx, scene).expect("update");
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    t.encode(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
}

fn read_output(ctx: &GpuContext, t: &dyn Technique, scene: &Scene) -> CausticsMap {
    let texture = t.output().expect("configured").texture();
    assert_eq!(texture.format(), wgpu::TextureFormat::Rgba32Float);
    let texels: Vec<[f32; 4]> = ctx.read_texture(texture).expect("readback");
    CausticsMap {
        width: scene.caustics.width as usize,
        height: scene.caustics.height as usize,
        size: scene.water.as_ref().expect("water").size,
        texels: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

/// Each registered name through the interface equals the CPU twin on the same heights: the
/// application's grid size (`water_resolution`), the scene's optics and sun.
///
/// Measured on lavapipe (largest, mean absolute difference over every channel; the map spans about
/// 0.16..0.63): screen 5.0e-5, 2.1e-7; vertex 2.0e-5, 2.6e-7; texture 3.8e-5, 2.0e-7. Asserted:
/// largest < 4e-4, mean < 2.5e-6.
fn registered_variants_match_the_cpu_twin_through_the_interface() {
    let ctx = test_gpu();
    let scene = pool();
    for (name, variant) in REGISTERED {
        let (mut t, heights, _texture) = configured(&ctx, name, &scene);
        assert_eq!(t.name(), format!("procedural-{}", variant.name()));
        frame(&ctx, t.as_mut(), &scene);
        let gpu = read_output(&ctx, t.as_ref(), &scene);
        let cpu = cpu_map(&scene, variant, &heights);
        let (max, mean) = diff(&cpu, &gpu);
        eprintln!(
            "{name}: grid {}x{}, max {max:.2e}, mean {mean:.2e}",
            heights.cols, heights.rows
        );
        let hi = cpu.texels.iter().map(|t| t[0]).fold(0.0, f32::max);
        let lo = cpu.texels.iter().map(|t| t[0]).fold(1.0, f32::min);
        assert!(max < 4e-4, "{name}: largest difference {max}"); // Measured on lavapipe: 5.0e-5
        assert!(mean < 2.5e-6, "{name}: mean difference {mean}"); // Measured on lavapipe: 2.6e-7
        assert!(
            hi - lo > 0.3,
            "{name}: the waves make a pattern, {lo}..{hi}"
        );
    }
}

/// A frame after configure creates nothing and reads nothing back. With the sun fixed, `update`
/// writes nothing at all; a moving sun (the scene's, `follow_sun`) is one uniform write a frame
/// (the light map is the sky around the sun, the same whichever way it stands: nothing else is
/// uploaded). After the sun has moved, the map is the CPU twin's for the new sun (measured largest
/// difference 5.6e-5; asserted < 4e-4 as above) and far from the old sun's (0.5..0.7).
fn frames_create_nothing_and_upload_at_most_a_uniform() {
    let ctx = test_gpu();
    for (name, variant) in REGISTERED {
        let mut scene = pool();
        let (mut t, heights, _texture) = configured(&ctx, name, &scene);
        frame(&ctx, t.as_mut(), &scene);

        let before = ctx.traffic();
        for _ in 0..10 {
            frame(&ctx, t.as_mut(), &scene);
        }
        let fixed = ctx.traffic().since(&before);
        assert_eq!(fixed.created(), 0, "{name}, fixed sun: {fixed:?}");
        assert_eq!(fixed.readbacks, 0, "{name}, fixed sun: {fixed:?}");
        assert_eq!(fixed.uploaded_bytes, 0, "{name}, fixed sun: {fixed:?}");

        for k in 1..=10 {
            let before = ctx.traffic();
            scene.light.direction = DVec3::new(0.3 + 0.02 * k as f64, 0.1, -1.0).normalize();
            frame(&ctx, t.as_mut(), &scene);
            let moving = ctx.traffic().since(&before);
            assert_eq!(moving.created(), 0, "{name}, sun step {k}: {moving:?}");
            assert_eq!(moving.readbacks, 0, "{name}, sun step {k}: {moving:?}");
            assert!(
                moving.uploaded_bytes > 0 && moving.uploaded_bytes <= 4096,
                "{name}, sun step {k}: {moving:?}"
            );
        }
        let gpu = read_output(&ctx, t.as_ref(), &scene);
        let cpu = cpu_map(&scene, variant, &heights);
        let before_sun = cpu_map(&pool(), variant, &heights);
        let (max, _) = diff(&cpu, &gpu);
        let (moved, _) = diff(&cpu, &before_sun);
        eprintln!(
            "{name}: after the sun moved, max {max:.2e}; the move changed the map by {moved:.2e}"
        );
        assert!(max < 4e-4, "{name}: after the sun moved, {max}"); // Measured on lavapipe: 5.6e-5
        assert!(
            moved > 10.0 * max,
            "{name}: the sun's move changes the map ({moved})"
        );
    }
}

/// Over a terrain (the shore's beach scaled into the 1 m square) every variant, under the paper's
/// sun and the scene's, against the CPU twin: the passes' light-space map looked up per floor
/// texel (the same lookup for both twins).
fn a_terrain_matches_the_cpu_twin() {
    let ctx = test_gpu();
    let gpu = ProceduralCaustics::new(&ctx).expect("pipelines");
    let grid = surface(48);
    let floor = common::beach_floor(0.35);
    let light = DVec3::new(0.3, -0.2, -1.0).normalize();
    for variant in Variant::ALL {
        for follow_sun in [false, true] {
            let s = setup(variant, (64, 64), follow_sun, true, light, 32, (128, 1))
                .with_floor(&floor, None);
            assert!(s.receivers.is_some());
            let water = SurfaceInput::Grid(&grid);
            let cpu = s.received(procedural::caustics(&s, &water));
            let out = gpu.caustics(&ctx, &s, &water, None).expect("GPU map");
            let (max, mean) = diff(&cpu, &out);
            let what = format!("{variant:?} follow_sun {follow_sun}");
            eprintln!("terrain, {what}: max {max:.2e}, mean {mean:.2e}");
            // Measured on lavapipe: largest 3.95e-5, mean 5.1e-7 (vertex, following the sun).
            assert!(max < 3.9e-4, "{what}: largest difference {max}");
            assert!(mean < 5e-6, "{what}: mean difference {mean}");
        }
    }
}

/// Through the `Technique` trait on the pool over the beach: frames of moving water under a steady
/// sun reuse the receivers (nothing created, uploaded past the heights, or read back), and the
/// last floor map is the CPU twin's on the same heights.
fn a_terrain_through_the_trait_creates_and_reads_nothing() {
    let ctx = test_gpu();
    for (name, variant) in REGISTERED {
        let mut scene = pool();
        scene.floor.walls = false;
        let w = scene.water.clone().expect("water");
        scene.floor.terrain = Some(common::beach_under(w.depth));
        let (mut t, mut heights, texture) = configured(&ctx, name, &scene);
        frame(&ctx, t.as_mut(), &scene);
        ctx.wait().unwrap();
        let before = ctx.traffic();
        for f in 1..=3 {
            scene.time = 0.1 * f as f64;
            let surface = w.surface_at(scene.time).expect("surface");
            heights = sample_grid(surface.as_ref(), heights.cols, heights.rows, w.size);
            common::write_heights(&ctx, &texture, &heights);
            frame(&ctx, t.as_mut(), &scene);
        }
        ctx.wait().unwrap();
        let d = ctx.traffic().since(&before);
        assert_eq!(
            (d.created(), d.readbacks, d.uploaded_bytes),
            (0, 0, 0),
            "{name}: {d:?}"
        );
        let gpu = read_output(&ctx, t.as_ref(), &scene);
        let cpu = cpu_map(&scene, variant, &heights);
        let (max, mean) = diff(&cpu, &gpu);
        eprintln!("{name} over a terrain: max {max:.2e}, mean {mean:.2e}");
        // Measured on lavapipe: largest 1.43e-4, mean 6.1e-7 (procedural-vertex).
        assert!(max < 1.4e-3, "{name}: largest difference {max}");
        assert!(mean < 6e-6, "{name}: mean difference {mean}");
    }
}

/// A scene without water is refused with an error naming the problem; `procedural` runs the
/// variant its table names, a variant's own name refuses a table naming another.
fn the_interface_refuses_no_water() {
    let ctx = test_gpu();
    let mut scene = pool();
    let heights = ctx
        .upload_grid("test heights", &Grid::new(64, 64))
        .expect("upload");
    let water = WaterTextures::of(&heights);
    let mut t = registry::create(&ctx, "procedural", &trait_params()).expect("registered");
    scene.water = None;
    let err = t.configure(&ctx, &scene, &water).unwrap_err().to_string();
    assert!(err.contains("no water"), "{err}");
    let vertex: toml::Table = "procedural = { variant = \"vertex\" }"
        .parse()
        .expect("toml");
    let named = registry::create(&ctx, "procedural", &vertex).expect("registered");
    assert_eq!(named.name(), "procedural-vertex");
    let err = registry::create(&ctx, "procedural-texture", &vertex)
        .err()
        .expect("refused")
        .to_string();
    assert!(err.contains("variant"), "{err}");
}

test_main! {
    gpu screen_and_vertex_variants_match_the_cpu_twin,
    gpu texture_variant_matches_the_cpu_twin,
    gpu flat_water_gives_one_on_the_gpu,
    gpu the_mip_chain_aliases_less_than_point_sampling,
    gpu a_map_beyond_the_device_limit_is_refused,
    gpu registered_variants_match_the_cpu_twin_through_the_interface,
    gpu frames_create_nothing_and_upload_at_most_a_uniform,
    gpu a_terrain_matches_the_cpu_twin,
    gpu a_terrain_through_the_trait_creates_and_reads_nothing,
    gpu the_interface_refuses_no_water,
}
