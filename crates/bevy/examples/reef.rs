//! A reef in Bevy: a sea bed from a height map, rocks on it, a sunken crate and a slab of rock
//! whose end juts out over the sand, all the application's own meshes, lit by the caustics of a
//! moving swell: the meshes are the water's receivers, so the light lands on the sand, on the
//! rocks' flanks and on the crate where it reaches them, and none under the overhang. The water's
//! surface is a mesh the plugin displaces on the GPU by the heights the technique reads.
//! Right-drag orbits, the wheel zooms, T switches technique.
//!
//! `cargo run --example reef -- [--technique NAME] [--flat] [--no-surface] [--frames N
//! --screenshot PATH]`: `--flat` keeps the water still (the picture caustics are measured
//! against), `--no-surface` leaves the water's surface out of the picture.

mod common;

use bevy::prelude::*;
use bevy_caustics::{
    CausticMaps, CausticWater, CausticsExtension, CausticsMaterial, CausticsPlugin, Receiver,
    WaterSurfaceMaterial,
};
use caustics_core::scene::{Material, Scene, WaterSource};

fn main() -> AppExit {
    let mut surface = true;
    let args = match common::parse_args_with("yuksel", &mut |a| {
        (a == "--no-surface").then(|| surface = false).is_some()
    }) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("reef: {e}");
            return AppExit::from_code(2);
        }
    };
    let (water, reef) = match reef_scene(&args) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("reef: {e}");
            return AppExit::from_code(2);
        }
    };
    App::new()
        .add_plugins(common::plugins("bevy_caustics: reef", &args))
        .add_plugins(CausticsPlugin)
        .insert_resource(common::Setup(Some(water)))
        .insert_resource(Reef {
            scene: reef,
            surface,
        })
        .insert_resource(common::Run::new(&args))
        .insert_resource(common::clock(&args))
        .insert_resource(ClearColor(Color::srgb(0.55, 0.72, 0.92)))
        .insert_resource(common::sky_light())
        .add_systems(Startup, setup)
        .add_systems(
            Update,
            (common::orbit, common::switch_technique, common::frames),
        )
        .run()
}

/// The built-in reef: its sea bed and objects become the application's meshes, and the water the
/// plugin lights them from is the reef's water over nothing of its own.
#[derive(Resource)]
struct Reef {
    scene: Scene,
    surface: bool,
}

fn reef_scene(args: &common::Args) -> Result<(CausticWater, Scene), String> {
    let mut reef = Scene::builtin("reef").map_err(|e| e.to_string())?;
    if args.flat
        && let Some(w) = reef.water.as_mut()
    {
        w.source = WaterSource::Flat;
    }
    let mut scene = reef.clone();
    // The receivers are the meshes the application draws, not the scene's.
    scene.floor.terrain = None;
    scene.floor.solids = None;
    scene.objects.clear();
    scene.caustics.width = 256;
    scene.caustics.height = 256;
    let water = CausticWater::new(scene, &args.technique).map_err(|e| e.to_string())?;
    Ok((water, reef))
}

fn setup(
    mut commands: Commands,
    mut setup: ResMut<common::Setup>,
    reef: Res<Reef>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut images: ResMut<Assets<Image>>,
    mut caustic: ResMut<Assets<CausticsMaterial>>,
    mut surfaces: ResMut<Assets<WaterSurfaceMaterial>>,
) {
    let water = setup.0.take().expect("set up once");
    let at = Transform::default();
    let maps = CausticMaps::new(&water, &mut images);
    let here = GlobalTransform::from(at);
    let mut under = |color: Color, roughness: f32| {
        caustic.add(CausticsExtension::material(
            StandardMaterial {
                base_color: color,
                perceptual_roughness: roughness,
                ..default()
            },
            &water,
            &maps,
            &here,
            Receiver::Mesh,
        ))
    };
    // The sea bed, its rocks in the height map.
    commands.spawn((
        Mesh3d(meshes.add(common::terrain_mesh(&reef.scene, 160))),
        MeshMaterial3d(under(Color::srgb(0.80, 0.72, 0.55), 0.95)),
    ));
    // The crate and the slab.
    for object in &reef.scene.objects {
        let color = match object.material {
            Material::Diffuse { color } => {
                Color::linear_rgb(color[0] as f32, color[1] as f32, color[2] as f32)
            }
            _ => Color::WHITE,
        };
        commands.spawn((
            Mesh3d(meshes.add(common::scene_mesh(&object.mesh))),
            MeshMaterial3d(under(color, 0.9)),
        ));
    }
    if reef.surface {
        commands.spawn(common::water_surface(
            &water,
            &maps,
            at,
            &mut meshes,
            &mut surfaces,
        ));
    }
    let sun = reef.scene.light.direction.as_vec3();
    commands.spawn(common::sun(Vec3::new(sun.x, sun.y, sun.z), false));
    commands.spawn((water, maps, at));
    // From the sun's side: the sunlit faces, and the sand in the overhang's shade beyond it.
    let orbit = common::Orbit {
        yaw: 0.75,
        pitch: 0.8,
        distance: 8.0,
        centre: common::scene_to_world(Vec3::new(5.0, 5.0, 1.2)),
        farthest: 30.0,
    };
    commands.spawn((common::camera(orbit.transform()), orbit));
}
