//! What the examples share: their command line and the counted run that saves a screenshot.

use std::path::PathBuf;

use bevy::camera::Exposure;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::light::light_consts::lux;
use bevy::prelude::*;
use bevy::render::RenderPlugin;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::time::TimeUpdateStrategy;
use bevy::window::WindowResolution;
use bevy_caustics::{CausticWater, CausticsStats};

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
