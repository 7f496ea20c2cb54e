//! What the examples share: their command line and the counted run that saves a screenshot.

// Each example uses its part of it.
#![allow(dead_code)]

use std::path::PathBuf;

use bevy::asset::RenderAssetUsages;
use bevy::camera::Exposure;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::light::NotShadowCaster;
use bevy::light::light_consts::lux;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use bevy::window::WindowResolution;
use bevy_caustics::{
    CausticMaps, CausticWater, CausticsStats, WaterSurfaceExtension, WaterSurfaceMaterial,
    water_surface_mesh,
};
use caustics_core::glam::DVec2;
use caustics_core::scene::Scene;

/// The water, waiting for the startup system.
#[derive(Resource)]
pub struct Setup(pub Option<CausticWater>);

/// Scene coordinates (z up) to Bevy's (y up), for a water entity without rotation.
pub fn scene_to_world(p: Vec3) -> Vec3 {
    Vec3::new(p.x, p.z, -p.y)
}

/// The sky's light, about a quarter of the sun's on a horizontal surface (Preetham's clear sky
/// with the sun high gives 0.26): E = π L.
pub fn sky_light() -> GlobalAmbientLight {
    GlobalAmbientLight {
        color: Color::srgb(0.80, 0.88, 1.0),
        brightness: 0.22 * lux::DIRECT_SUNLIGHT / std::f32::consts::PI,
        ..default()
    }
}

/// The sun along the scene's (z-up) direction of travel `direction`.
pub fn sun(direction: Vec3, shadows: bool) -> impl Bundle {
    (
        DirectionalLight {
            illuminance: lux::DIRECT_SUNLIGHT,
            shadow_maps_enabled: shadows,
            color: Color::srgb(1.0, 0.96, 0.90),
            ..default()
        },
        Transform::default().looking_to(scene_to_world(direction.normalize()), Vec3::Z),
    )
}

/// A 3D camera exposed for sunlight, at `at`.
pub fn camera(at: Transform) -> impl Bundle {
    (
        Camera3d::default(),
        Tonemapping::AcesFitted,
        Exposure::SUNLIGHT,
        at,
    )
}

pub struct Args {
    pub technique: String,
    pub flat: bool,
    pub frames: Option<u32>,
    pub screenshot: Option<PathBuf>,
}

/// `[--technique NAME] [--flat] [--frames N --screenshot PATH]`, `technique` the default.
pub fn parse_args(technique: &str) -> Result<Args, String> {
    parse_args_with(technique, &mut |_| false)
}

/// [`parse_args`], and the example's own flags: `own` takes an argument it knows and says so.
pub fn parse_args_with(technique: &str, own: &mut dyn FnMut(&str) -> bool) -> Result<Args, String> {
    let mut args = Args {
        technique: technique.into(),
        flat: false,
        frames: None,
        screenshot: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match a.as_str() {
            "--technique" => args.technique = value("--technique")?,
            "--flat" => args.flat = true,
            "--frames" => {
                let v = value("--frames")?;
                let n = v
                    .parse::<u32>()
                    .ok()
                    .filter(|n| *n > 0)
                    .ok_or(format!("--frames takes a positive count, not `{v}`"))?;
                args.frames = Some(n);
            }
            "--screenshot" => args.screenshot = Some(PathBuf::from(value("--screenshot")?)),
            other if own(other) => {}
            other => return Err(format!("unknown argument `{other}`")),
        }
    }
    if args.screenshot.is_some() && args.frames.is_none() {
        return Err("--screenshot needs --frames N (the frame to save)".into());
    }
    if let Some(p) = &args.screenshot
        && p.extension().is_none_or(|e| !e.eq_ignore_ascii_case("png"))
    {
        return Err(format!("--screenshot writes a PNG: `{}`", p.display()));
    }
    Ok(args)
}

/// Bevy's default plugins with a window titled `title`; a counted run (`--frames`) compiles its
/// pipelines synchronously, so that its frames show the scene.
pub fn plugins(title: &str, args: &Args) -> impl PluginGroup {
    DefaultPlugins
        .set(WindowPlugin {
            primary_window: Some(Window {
                title: title.into(),
                resolution: WindowResolution::new(960, 540),
                ..default()
            }),
            ..default()
        })
        .set(RenderPlugin {
            synchronous_pipeline_compilation: args.frames.is_some(),
            ..default()
        })
}

/// A counted run steps Bevy's clock by 1/15 s a frame, whatever the frames take, so that its
/// water (and the pool's rain) is the same from run to run; otherwise the clock is the wall's.
pub fn clock(args: &Args) -> TimeUpdateStrategy {
    match args.frames {
        Some(_) => TimeUpdateStrategy::ManualDuration(std::time::Duration::from_secs(1) / 15),
        None => TimeUpdateStrategy::Automatic,
    }
}

/// The counted run's state.
#[derive(Resource)]
pub struct Run {
    pub frames: Option<u32>,
    pub screenshot: Option<PathBuf>,
    pub frame: u32,
}

impl Run {
    pub fn new(args: &Args) -> Self {
        Run {
            frames: args.frames,
            screenshot: args.screenshot.clone(),
            frame: 0,
        }
    }
}

/// `--frames N`: the last frame saved to `--screenshot`, then exit with the plugin's counts.
pub fn frames(
    mut commands: Commands,
    mut run: ResMut<Run>,
    stats: Res<CausticsStats>,
    mut exit: MessageWriter<AppExit>,
) {
    let Some(n) = run.frames else {
        return;
    };
    run.frame += 1;
    if run.frame == n {
        match run.screenshot.clone() {
            Some(path) => {
                commands.spawn(Screenshot::primary_window()).observe(
                    move |shot: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                        let code = match shot.image.clone().try_into_dynamic() {
                            Ok(img) => match img.to_rgb8().save(&path) {
                                Ok(()) => 0,
                                Err(e) => {
                                    eprintln!(
                                        "cannot write the screenshot {}: {e}",
                                        path.display()
                                    );
                                    1
                                }
                            },
                            Err(e) => {
                                eprintln!("the screenshot cannot be converted: {e}");
                                1
                            }
                        };
                        exit.write(AppExit::from_code(code));
                    },
                );
            }
            None => {
                exit.write(AppExit::Success);
            }
        }
    }
    if run.frame >= n {
        let s = stats.get();
        if run.frame == n {
            println!(
                "bevy_caustics: {} frames, {} steady: created {}, readbacks {}, uploaded {} bytes; techniques {:?}{}",
                s.frames,
                s.steady_frames,
                s.steady.created(),
                s.steady.readbacks,
                s.steady.uploaded_bytes,
                s.techniques,
                s.error.map(|e| format!("; error: {e}")).unwrap_or_default()
            );
        }
        // A screenshot that never arrives must not hang a test.
        if run.frame > n + 120 {
            eprintln!("the screenshot did not arrive within 120 frames");
            exit.write(AppExit::from_code(1));
        }
    }
}

/// The scene's terrain as a mesh of `n` x `n` cells over the water square, heights and normals
/// from the same grid the techniques read.
pub fn terrain_mesh(scene: &Scene, n: usize) -> Mesh {
    let size = scene.size;
    height_mesh(size, n, |p| scene.floor.height_gradient(p, size))
}

/// A height field over the `size` square as a mesh of `n` x `n` cells: `height` gives each
/// vertex's height and gradient, scene coordinates. Kept on the CPU too: the plugin reads a
/// receiver's positions.
pub fn height_mesh(size: f64, n: usize, height: impl Fn(DVec2) -> (f64, DVec2)) -> Mesh {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (size * j as f64 / n as f64, size * i as f64 / n as f64);
            let (h, g) = height(DVec2::new(x, y));
            positions.push(scene_to_world(Vec3::new(x as f32, y as f32, h as f32)).to_array());
            let normal = Vec3::new(-g.x as f32, -g.y as f32, 1.0).normalize();
            normals.push(scene_to_world(normal).to_array());
        }
    }
    let mut indices = Vec::new();
    let k = |i: usize, j: usize| (i * (n + 1) + j) as u32;
    for i in 0..n {
        for j in 0..n {
            // Counter-clockwise seen from above (Bevy's front faces).
            indices.extend_from_slice(&[k(i, j), k(i, j + 1), k(i + 1, j)]);
            indices.extend_from_slice(&[k(i, j + 1), k(i + 1, j + 1), k(i + 1, j)]);
        }
    }
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_indices(Indices::U32(indices))
}

/// T switches every water to the next registered technique.
pub fn switch_technique(keys: Res<ButtonInput<KeyCode>>, mut water: Query<&mut CausticWater>) {
    if !keys.just_pressed(KeyCode::KeyT) {
        return;
    }
    let names = CausticWater::techniques();
    for mut w in &mut water {
        let next = names
            .iter()
            .position(|n| *n == w.technique)
            .map_or(0, |i| (i + 1) % names.len());
        w.technique = names[next].to_string();
        info!("technique: {}", w.technique);
    }
}

/// A mesh of `caustics_core`'s (scene coordinates, z up) in Bevy's, for a water entity at the
/// origin.
pub fn scene_mesh(mesh: &caustics_core::mesh::TriangleMesh) -> Mesh {
    let to_world = |p: caustics_core::glam::DVec3| {
        scene_to_world(Vec3::new(p.x as f32, p.y as f32, p.z as f32)).to_array()
    };
    let positions: Vec<[f32; 3]> = mesh.positions.iter().map(|p| to_world(*p)).collect();
    let normals: Vec<[f32; 3]> = mesh.normals.iter().map(|n| to_world(*n)).collect();
    let indices = mesh.indices.iter().flatten().copied().collect();
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_indices(Indices::U32(indices))
}

/// The water's surface over its square, displaced on the GPU by the technique's heights: glassy,
/// mostly see-through, reflecting the sun; the sun's light through it is the technique's, so it
/// casts no shadow map. `at` is the water entity's transform.
pub fn water_surface(
    water: &CausticWater,
    maps: &CausticMaps,
    at: Transform,
    meshes: &mut Assets<Mesh>,
    materials: &mut Assets<WaterSurfaceMaterial>,
) -> impl Bundle {
    let base = StandardMaterial {
        base_color: Color::srgba(0.15, 0.42, 0.52, 0.22),
        alpha_mode: AlphaMode::Blend,
        perceptual_roughness: 0.05,
        reflectance: 0.5,
        ..default()
    };
    (
        NotShadowCaster,
        Mesh3d(meshes.add(water_surface_mesh(water, 128))),
        MeshMaterial3d(materials.add(WaterSurfaceExtension::material(base, water, maps))),
        at,
    )
}

/// A camera orbiting `centre`: right-drag turns it, the wheel moves it in or out (up to
/// `farthest`).
#[derive(Component)]
pub struct Orbit {
    pub yaw: f32,
    pub pitch: f32,
    pub distance: f32,
    pub centre: Vec3,
    pub farthest: f32,
}

impl Orbit {
    pub fn transform(&self) -> Transform {
        let eye = self.centre
            + self.distance
                * Vec3::new(
                    self.pitch.cos() * self.yaw.sin(),
                    self.pitch.sin(),
                    self.pitch.cos() * self.yaw.cos(),
                );
        Transform::from_translation(eye).looking_at(self.centre, Vec3::Y)
    }
}

/// The [`Orbit`] camera follows the mouse.
pub fn orbit(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut camera: Query<(&mut Orbit, &mut Transform)>,
) {
    let Ok((mut o, mut t)) = camera.single_mut() else {
        return;
    };
    if buttons.pressed(MouseButton::Right) {
        o.yaw -= motion.delta.x * 0.005;
        o.pitch = (o.pitch + motion.delta.y * 0.005).clamp(0.1, 1.5);
    }
    o.distance = (o.distance * (1.0 - scroll.delta.y * 0.1)).clamp(2.0, o.farthest);
    *t = o.transform();
}
