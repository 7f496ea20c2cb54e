//! The built-in shore in Bevy: a Tessendorf FFT ocean over a sandy beach that shelves up towards
//! the camera, its caustics made by paper 5's cascaded eye-space technique from Bevy's camera.
//! Right-drag turns the view, the wheel moves it.
//!
//! `cargo run --example ocean -- [--technique NAME] [--flat] [--frames N --screenshot PATH]`
//! (`--flat`: still water, the picture caustics are measured against).

mod common;

use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::light::NotShadowCaster;

use bevy::prelude::*;
use bevy_caustics::{
    CausticMaps, CausticWater, CausticsExtension, CausticsMaterial, CausticsPlugin, Receiver,
};
use caustics_core::scene::{Scene, WaterSource};

fn main() -> AppExit {
    let args = match common::parse_args("cascaded") {
        Ok(a) => a,
        Err(e) => {
            eprintln!("ocean: {e}");
            return AppExit::from_code(2);
        }
    };
    let mut scene = match Scene::builtin("shore") {
        Ok(s) => s,
        Err(e) => {
            eprintln!("ocean: {e}");
            return AppExit::from_code(1);
        }
    };
    if args.flat
        && let Some(w) = scene.water.as_mut()
    {
        w.source = WaterSource::Flat;
    }
    // The eye-space image: a third of the window's pixels (paper 5's cost grows with them).
    scene.camera.width = 480;
    scene.camera.height = 270;
    let water = match CausticWater::new(scene, &args.technique) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("ocean: {e}");
            return AppExit::from_code(2);
        }
    };
    App::new()
        .add_plugins(common::plugins("bevy_caustics: ocean", &args))
        .add_plugins(CausticsPlugin)
        .insert_resource(common::Run::new(&args))
        .insert_resource(common::clock(&args))
        .insert_resource(common::Setup(Some(water)))
        .insert_resource(ClearColor(Color::srgb(0.55, 0.72, 0.92)))
        .insert_resource(common::sky_light())
        .add_systems(Startup, setup)
        .add_systems(Update, (look, common::frames))
        .run()
}

#[derive(Component)]
struct Look {
    yaw: f32,
    pitch: f32,
}

fn setup(
    mut commands: Commands,
    mut setup: ResMut<common::Setup>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut images: ResMut<Assets<Image>>,
    mut standard: ResMut<Assets<StandardMaterial>>,
    mut caustic: ResMut<Assets<CausticsMaterial>>,
) {
    let water = setup.0.take().expect("set up once");
    let size = water.size();
    let depth = water.depth();
    // The scene's square from the world's origin along +x and −z.
    let at = Transform::default();
    let maps = CausticMaps::new(&water, &mut images);
    let sand_color = StandardMaterial {
        base_color: Color::srgb(0.78, 0.70, 0.52),
        perceptual_roughness: 0.95,
        ..default()
    };
    let sand = caustic.add(CausticsExtension::material(
        sand_color.clone(),
        &water,
        &maps,
        &GlobalTransform::from(at),
        Receiver::Mesh,
    ));
    let sea_bed = caustic.add(CausticsExtension::material(
        sand_color,
        &water,
        &maps,
        &GlobalTransform::from(at),
        Receiver::Mesh,
    ));
    commands.spawn((
        Mesh3d(meshes.add(common::terrain_mesh(&water.scene, 192))),
        MeshMaterial3d(sand),
    ));
    let c = size / 2.0;
    // Beyond the scene's square: more sea bed a little below the beach's deep end, and the sea
    // out to the horizon (the ocean tiles, so it lies under the same water).
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::new(Vec3::Y, Vec2::splat(500.0)))),
        MeshMaterial3d(sea_bed),
        Transform::from_xyz(c, -0.05, -c),
    ));
    commands.spawn((
        NotShadowCaster,
        Mesh3d(meshes.add(Plane3d::new(Vec3::Y, Vec2::splat(500.0)))),
        MeshMaterial3d(standard.add(StandardMaterial {
            base_color: Color::srgba(0.10, 0.35, 0.45, 0.25),
            alpha_mode: AlphaMode::Blend,
            perceptual_roughness: 0.05,
            reflectance: 0.3,
            ..default()
        })),
        Transform::from_xyz(c, depth, -c),
    ));
    commands.spawn((water, maps, at));
    // The shore scene's sun, (−0.35, 0.2, −1) in its z-up frame. Nothing stands in the water to
    // cast a shadow, and the sea bed's own shadow map would only add acne on its ripples.
    commands.spawn(common::sun(Vec3::new(-0.35, 0.2, -1.0), false));
    // The shore scene's camera: from above the water line at (30.5, 9, 5) towards (14, 18, 0).
    let eye = common::scene_to_world(Vec3::new(30.5, 9.0, 5.0));
    let target = common::scene_to_world(Vec3::new(14.0, 18.0, 0.0));
    let d = (target - eye).normalize();
    commands.spawn((
        common::camera(Transform::from_translation(eye).looking_to(d, Vec3::Y)),
        Projection::Perspective(PerspectiveProjection {
            fov: 60f32.to_radians(),
            ..default()
        }),
        Look {
            yaw: d.x.atan2(-d.z),
            pitch: d.y.asin(),
        },
    ));
}

/// Right-drag turns the view, the wheel moves along it.
fn look(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut camera: Query<(&mut Look, &mut Transform)>,
) {
    let Ok((mut l, mut t)) = camera.single_mut() else {
        return;
    };
    if buttons.pressed(MouseButton::Right) {
        l.yaw += motion.delta.x * 0.004;
        l.pitch = (l.pitch - motion.delta.y * 0.004).clamp(-1.4, 1.4);
    }
    let d = Vec3::new(
        l.pitch.cos() * l.yaw.sin(),
        l.pitch.sin(),
        -l.pitch.cos() * l.yaw.cos(),
    );
    t.translation += d * scroll.delta.y * 0.5;
    *t = t.looking_to(d, Vec3::Y);
}
