//! The application's own heights (`Heights::Image`) in a Bevy app without a window: an `R32Float`
//! image the app fills, the technique reading it on Bevy's device, and the floor map read back
//! (a test's readback, through Bevy's `Readback`) against the physics: still water gives the flat
//! water's light everywhere, the absorbed sun `exp(−K d / cos θ_t)` per channel; a periodic wave
//! focuses it into caustics but keeps its mean (the light crossing a tiling square is conserved).
//!
//! Without a GPU adapter the tests are reported as ignored (the reason printed), unless
//! `CAUSTICS_REQUIRE_GPU=1`, when they fail (libtest-mimic, as `tests/examples.rs`).

use std::sync::{Arc, Mutex};

use bevy::app::PluginsState;
use bevy::asset::RenderAssetUsages;
use bevy::log::LogPlugin;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::gpu_readback::{ReadbackComplete, ReadbackOnce};
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use bevy_caustics::{CausticMaps, CausticWater, CausticsPlugin, CausticsStats, Heights};
use caustics_core::scene::Scene;
use libtest_mimic::{Arguments, Failed, Trial};

const GRID: u32 = 128;
const MAP: u32 = 128;

/// The pool (4 m, 1 m deep, tiling) without walls, its map `MAP`², with `heights` as its water.
fn water(images: &mut Assets<Image>, heights: impl Fn(f32, f32) -> f32) -> CausticWater {
    let mut scene = Scene::builtin("pool").expect("the built-in pool");
    scene.floor.walls = false;
    // Straight down here: the sun the technique uses must be the Bevy light's, (0.3, 0.1, -1),
    // which `flat_light` assumes (straight down would give 1.4 % more red).
    scene.light.direction = [0.0, 0.0, -1.0].into();
    scene.caustics.width = MAP;
    scene.caustics.height = MAP;
    let size = scene.size as f32;
    let data: Vec<u8> = (0..GRID * GRID)
        .flat_map(|k| {
            let (j, i) = (k % GRID, k / GRID);
            let (x, y) = (
                (j as f32 + 0.5) * size / GRID as f32,
                (i as f32 + 0.5) * size / GRID as f32,
            );
            heights(x, y).to_le_bytes()
        })
        .collect();
    let mut image = Image::new(
        Extent3d {
            width: GRID,
            height: GRID,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::R32Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage = TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST;
    let mut w = CausticWater::new(scene, "caustic-triangles").expect("a usable technique");
    w.heights = Heights::Image(images.add(image));
    w
}

/// Runs a windowless app for a few frames with `heights` and reads the floor map back: its texels
/// (RGB) and the plugin's counts.
fn floor_map(heights: fn(f32, f32) -> f32) -> Result<(Vec<[f32; 3]>, CausticsStats), Failed> {
    let (mut maps, stats) = floor_maps(vec![heights])?;
    Ok((maps.remove(0), stats))
}

/// A floor map's texels (RGB).
type Texels = Vec<[f32; 3]>;

/// [`floor_map`] of one water entity per entry of `heights`, all in one world.
fn floor_maps(heights: Vec<fn(f32, f32) -> f32>) -> Result<(Vec<Texels>, CausticsStats), Failed> {
    let n = heights.len();
    let got: Arc<Mutex<Vec<Option<Vec<u8>>>>> = Arc::new(Mutex::new(vec![None; n]));
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .build()
            .disable::<WinitPlugin>()
            // Each test's app in its own thread: one global logger is all there can be.
            .disable::<LogPlugin>()
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            }),
    )
    .add_plugins(CausticsPlugin);
    let sink = got.clone();
    app.add_systems(
        Startup,
        move |mut commands: Commands, mut images: ResMut<Assets<Image>>| {
            let mut floors = Vec::new();
            for (k, &h) in heights.iter().enumerate() {
                let w = water(&mut images, h);
                let maps = CausticMaps::new(&w, &mut images);
                floors.push(maps.floor.clone());
                // Side by side, 5 m apart: where a water stands does not change its map.
                commands.spawn((w, maps, Transform::from_xyz(5.0 * k as f32, 0.0, 0.0)));
            }
            // The pool scene's sun, (0.3, 0.1, −1) in its z-up frame.
            commands.spawn((
                DirectionalLight::default(),
                Transform::default().looking_to(Vec3::new(0.3, -1.0, -0.1), Vec3::Z),
            ));
            commands.insert_resource(Floors(floors));
        },
    );
    app.add_systems(
        Update,
        move |mut commands: Commands, floors: Res<Floors>, mut frame: Local<u32>| {
            *frame += 1;
            if *frame == 4 {
                for (k, floor) in floors.0.iter().enumerate() {
                    let sink = sink.clone();
                    commands
                        .spawn(ReadbackOnce::texture(floor.clone()))
                        .observe(move |done: On<ReadbackComplete>| {
                            sink.lock().unwrap()[k] = Some(done.data.clone());
                        });
                }
            }
        },
    );
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
    for _ in 0..60 {
        app.update();
        if got.lock().unwrap().iter().all(Option::is_some) {
            break;
        }
    }
    let stats = app.world().resource::<CausticsStats>().clone();
    let mut maps = Vec::new();
    for bytes in got.lock().unwrap().iter_mut() {
        let bytes = bytes.take().ok_or("a floor map never came back")?;
        let texels: Vec<[f32; 3]> = bytes
            .chunks_exact(16)
            .map(|t| {
                let f = |k: usize| f32::from_le_bytes(t[4 * k..4 * k + 4].try_into().unwrap());
                [f(0), f(1), f(2)]
            })
            .collect();
        if texels.len() != (MAP * MAP) as usize {
            return Err(
                format!("{} texels came back, {} expected", texels.len(), MAP * MAP).into(),
            );
        }
        maps.push(texels);
    }
    Ok((maps, stats))
}

#[derive(Resource)]
struct Floors(Vec<Handle<Image>>);

/// The flat water's light on the pool's floor, per channel: the sun refracted into the water and
/// absorbed along its path, `exp(−K d / cos θ_t)` (the map's unit).
fn flat_light() -> [f64; 3] {
    let scene = Scene::builtin("pool").unwrap();
    let w = scene.water.as_ref().unwrap();
    let d = scene.light.direction.normalize();
    let cos_i = -d.z;
    let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (w.ior * w.ior)).sqrt();
    let k = w.absorption.to_array();
    k.map(|k| (-k * w.depth / cos_t).exp())
}

fn mean(texels: &[[f32; 3]], c: usize) -> f64 {
    texels.iter().map(|t| t[c] as f64).sum::<f64>() / texels.len() as f64
}

fn still_water() -> Result<(), Failed> {
    let (texels, stats) = floor_map(still)?;
    if let Some(e) = stats.get().error {
        return Err(e.into());
    }
    is_flat("still water", &texels)
}

fn still(_: f32, _: f32) -> f32 {
    0.0
}

/// Every texel the flat water's light.
fn is_flat(what: &str, texels: &[[f32; 3]]) -> Result<(), Failed> {
    let flat = flat_light();
    let mut worst = 0.0f64;
    for t in texels {
        for c in 0..3 {
            worst = worst.max((t[c] as f64 / flat[c] - 1.0).abs());
        }
    }
    println!("{what}: largest texel off the flat water's light: {worst:.2e}");
    // Measured on lavapipe: 2.15e-6 (f32 rounding).
    if worst > 2e-5 {
        return Err(format!("{what}: a texel is {worst:.3} off exp(-K d / cos θ_t)").into());
    }
    Ok(())
}

/// Waves of 0.5 m along x and 0.4 m along y (whole periods over the 4 m square), 5 and 4 mm high:
/// curvatures A k² of 0.79 and 0.99 /m, focusing the sun a few metres down.
fn wave(x: f32, y: f32) -> f32 {
    let tau = std::f32::consts::TAU;
    0.005 * (tau * x / 0.5).sin() + 0.004 * (tau * y / 0.4 + 1.0).sin()
}

fn wave_keeps_the_light() -> Result<(), Failed> {
    let (texels, stats) = floor_map(wave)?;
    if let Some(e) = stats.get().error {
        return Err(e.into());
    }
    keeps_the_light("wave", &texels)
}

/// The floor's mean light is the flat water's, and the waves focus it (contrast).
fn keeps_the_light(what: &str, texels: &[[f32; 3]]) -> Result<(), Failed> {
    let flat = flat_light();
    let g = mean(texels, 1);
    let var = texels
        .iter()
        .map(|t| (t[1] as f64 - g).powi(2))
        .sum::<f64>()
        / texels.len() as f64;
    let contrast = var.sqrt() / g;
    let off = (0..3)
        .map(|c| (mean(texels, c) / flat[c] - 1.0).abs())
        .fold(0.0, f64::max);
    println!("{what}: mean off the flat light by {off:.2e}, contrast {contrast:.3}");
    // Measured on lavapipe: 5.5e-4; contrast 0.241.
    if off > 5e-3 {
        return Err(
            format!("{what}: the floor's mean light is {off:.3} off the flat water's").into(),
        );
    }
    if contrast < 0.1 {
        return Err(format!("{what}: no caustics (contrast {contrast:.3})").into());
    }
    Ok(())
}

/// Two waters in one world, each with its own technique state and maps: still water beside waves,
/// neither's light in the other's map.
fn two_waters_each_light_their_own_floor() -> Result<(), Failed> {
    let (maps, stats) = floor_maps(vec![still, wave])?;
    let s = stats.get();
    if let Some(e) = s.error {
        return Err(e.into());
    }
    if s.techniques.len() != 2 {
        return Err(format!("{} techniques recorded, 2 expected", s.techniques.len()).into());
    }
    is_flat("two waters, the still one", &maps[0])?;
    keeps_the_light("two waters, the waves", &maps[1])
}

/// A round bump (Gaussian, 4 cm high, σ 10 cm: curvature 4 /m at its top, focusing the sun about
/// a metre down) off the square's centre and off its diagonal.
fn bump(x: f32, y: f32) -> f32 {
    let r2 = (x - 1.0).powi(2) + (y - 2.8).powi(2);
    0.04 * (-r2 / (2.0 * 0.1 * 0.1)).exp()
}

/// The map's frame: the bump's focus must land under it, moved along the sun's travel by the
/// refracted ray's drift over the depth; a map transposed, flipped or read in the wrong frame puts
/// it metres away.
fn bump_focuses_under_it() -> Result<(), Failed> {
    let (texels, stats) = floor_map(bump)?;
    if let Some(e) = stats.get().error {
        return Err(e.into());
    }
    let k = (0..texels.len())
        .max_by(|&a, &b| texels[a][1].total_cmp(&texels[b][1]))
        .expect("texels");
    let size = 4.0;
    let (x, y) = (
        ((k as u32 % MAP) as f64 + 0.5) * size / MAP as f64,
        ((k as u32 / MAP) as f64 + 0.5) * size / MAP as f64,
    );
    // The sun (0.3, 0.1, -1) refracted: its horizontal drift over the 1 m depth.
    let d = [0.3f64, 0.1, -1.0];
    let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let sin_i = (d[0] * d[0] + d[1] * d[1]).sqrt() / norm;
    let sin_t = sin_i / 1.333;
    let tan_t = sin_t / (1.0 - sin_t * sin_t).sqrt();
    let h = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let expect = (1.0 + tan_t * d[0] / h, 2.8 + tan_t * d[1] / h);
    let off = ((x - expect.0).powi(2) + (y - expect.1).powi(2)).sqrt();
    println!(
        "bump: brightest texel at ({x:.3}, {y:.3}), expected near ({:.3}, {:.3}): {off:.3} m off",
        expect.0, expect.1
    );
    // Measured on lavapipe: 0.022 m (texels are 3.1 cm).
    if off > 0.15 {
        return Err(format!("bump: the focus is {off:.3} m from under the bump").into());
    }
    Ok(())
}

fn main() {
    let args = Arguments::from_args();
    let skip = caustics_gpu::context::gpu_test_skip();
    if let Some(why) = &skip {
        eprintln!("{why}: the Bevy tests are ignored");
    }
    let trials = vec![
        Trial::test("still_water", still_water).with_ignored_flag(skip.is_some()),
        Trial::test("wave_keeps_the_light", wave_keeps_the_light).with_ignored_flag(skip.is_some()),
        Trial::test("bump_focuses_under_it", bump_focuses_under_it)
            .with_ignored_flag(skip.is_some()),
        Trial::test(
            "two_waters_each_light_their_own_floor",
            two_waters_each_light_their_own_floor,
        )
        .with_ignored_flag(skip.is_some()),
    ];
    libtest_mimic::run(&args, trials).exit();
}
