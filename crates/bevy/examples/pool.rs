//! A pool in Bevy with caustics on its floor and walls from moving water: the ripple simulation on
//! the GPU, a drop every so often, and one wherever you click. Right-drag orbits, the wheel zooms,
//! T switches between the registered techniques.
//!
//! `cargo run --example pool -- [--technique NAME] [--flat] [--frames N --screenshot PATH]`:
//! `--frames N` renders N frames and exits, saving the last to `--screenshot`'s PNG; `--flat`
//! keeps the water still (no drops), the picture caustics are measured against.

mod common;

use bevy::asset::RenderAssetUsages;
use bevy::image::{ImageAddressMode, ImageFilterMode, ImageSampler, ImageSamplerDescriptor};
use bevy::math::Affine2;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy::window::PrimaryWindow;
use bevy_caustics::{
    CausticMaps, CausticWater, CausticsExtension, CausticsMaterial, CausticsPlugin, DropRipple,
    Receiver, WaterSurfaceMaterial,
};
use caustics_core::scene::{Scene, WaterSource};
use caustics_core::water::ripple::{Drop, RippleParams};

fn main() -> AppExit {
    let args = match common::parse_args("caustic-triangles") {
        Ok(a) => a,
        Err(e) => {
            eprintln!("pool: {e}");
            return AppExit::from_code(2);
        }
    };
    let scene = match pool_scene(args.flat) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("pool: {e}");
            return AppExit::from_code(1);
        }
    };
    let water = match CausticWater::new(scene, &args.technique) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("pool: {e}");
            return AppExit::from_code(2);
        }
    };
    App::new()
        .add_plugins(common::plugins("bevy_caustics: pool", &args))
        .add_plugins(CausticsPlugin)
        .insert_resource(common::Setup(Some(water)))
        .insert_resource(common::Run::new(&args))
        .insert_resource(common::clock(&args))
        .insert_resource(Rain {
            on: !args.flat,
            next: 0.0,
        })
        .insert_resource(common::sky_light())
        .add_systems(Startup, setup)
        .add_systems(
            Update,
            (
                common::orbit,
                click_drops,
                rain,
                common::switch_technique,
                common::frames,
            ),
        )
        .run()
}

/// The built-in pool (4 m square, 1 m deep, walls lit) with the ripple simulation as its water:
/// walls that reflect (no wrap), a few drops at the start unless `flat`.
fn pool_scene(flat: bool) -> Result<Scene, String> {
    let mut scene = Scene::builtin("pool").map_err(|e| e.to_string())?;
    let water = scene.water.as_mut().ok_or("the pool has no water")?;
    water.wrap = false;
    let drop = |x, y| Drop {
        position: [x, y],
        radius: 0.08,
        strength: 0.015,
    };
    water.source = WaterSource::Ripple(RippleParams {
        resolution: 256,
        wave_speed: 0.7,
        damping: 0.25,
        time_step: 1.0 / 240.0,
        drops: if flat {
            Vec::new()
        } else {
            vec![
                drop(1.2, 2.6),
                drop(2.8, 1.4),
                drop(2.3, 3.1),
                drop(0.9, 1.0),
                drop(3.3, 3.0),
            ]
        },
        steps: 60,
    });
    scene.caustics.width = 384;
    scene.caustics.height = 384;
    Ok(scene)
}

#[derive(Resource)]
struct Rain {
    on: bool,
    next: f32,
}

#[derive(Component)]
struct Water;

fn setup(
    mut commands: Commands,
    mut setup: ResMut<common::Setup>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut images: ResMut<Assets<Image>>,
    mut standard: ResMut<Assets<StandardMaterial>>,
    mut caustic: ResMut<Assets<CausticsMaterial>>,
    mut surfaces: ResMut<Assets<WaterSurfaceMaterial>>,
) {
    let water = setup.0.take().expect("set up once");
    let size = water.size();
    let depth = water.depth();
    let rim = depth + 0.15;
    // The scene's square from the water entity's origin along +x and −z: centred on the world's.
    let at = Transform::from_xyz(-size / 2.0, 0.0, size / 2.0);
    let maps = CausticMaps::new(&water, &mut images);
    let tile_image = images.add(tile_texture());
    // 25 cm tiles, eight to the texture's side.
    let tiles = |uv_scale: Vec2| StandardMaterial {
        base_color_texture: Some(tile_image.clone()),
        uv_transform: Affine2::from_scale(uv_scale),
        perceptual_roughness: 0.8,
        ..default()
    };
    let here = GlobalTransform::from(at);
    let under = |base, caustic: &mut Assets<CausticsMaterial>| {
        caustic.add(CausticsExtension::material(
            base,
            &water,
            &maps,
            &here,
            Receiver::Pool,
        ))
    };
    let floor = under(tiles(Vec2::splat(size / 2.0)), &mut caustic);
    let local = |x: f32, y: f32, z: f32| at.transform_point(Vec3::new(x, z, -y));
    let c = size / 2.0;
    // The floor, and the walls as thin slabs whose inner faces stand on the square's sides.
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::new(Vec3::Y, Vec2::splat(c)))),
        MeshMaterial3d(floor),
        Transform::from_translation(local(c, c, 0.0)),
    ));
    let t = 0.04;
    let wall = under(tiles(Vec2::new(size / 2.0, rim / 2.0)), &mut caustic);
    for (x, y, sx, sz) in [
        (-t / 2.0, c, t, size + 2.0 * t),
        (size + t / 2.0, c, t, size + 2.0 * t),
        (c, -t / 2.0, size, t),
        (c, size + t / 2.0, size, t),
    ] {
        commands.spawn((
            Mesh3d(meshes.add(Cuboid::new(sx, rim, sz))),
            MeshMaterial3d(wall.clone()),
            Transform::from_translation(local(x, y, rim / 2.0)),
        ));
    }
    // The deck: four slabs around the pool at the rim's height.
    let stone = standard.add(StandardMaterial {
        base_color: Color::srgb(0.80, 0.74, 0.64),
        perceptual_roughness: 0.9,
        ..default()
    });
    let (w, e) = (3.0, c + t + 1.5);
    for (x, z, sx, sz) in [
        (-e, 0.0, w, size + 2.0 * (t + w)),
        (e, 0.0, w, size + 2.0 * (t + w)),
        (0.0, -e, size + 2.0 * t, w),
        (0.0, e, size + 2.0 * t, w),
    ] {
        commands.spawn((
            Mesh3d(meshes.add(Cuboid::new(sx, 0.3, sz))),
            MeshMaterial3d(stone.clone()),
            Transform::from_xyz(x, rim - 0.15, z),
        ));
    }
    // A ball half under the water, lit as under flat water below the surface.
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(0.3).mesh().uv(48, 24))),
        MeshMaterial3d(caustic.add(CausticsExtension::material(
            StandardMaterial {
                base_color: Color::srgb(0.9, 0.35, 0.2),
                perceptual_roughness: 0.5,
                ..default()
            },
            &water,
            &maps,
            &here,
            Receiver::Mesh,
        ))),
        Transform::from_translation(local(2.9, 1.1, depth)),
    ));
    commands.spawn(common::water_surface(
        &water,
        &maps,
        at,
        &mut meshes,
        &mut surfaces,
    ));
    commands.spawn((water, maps, at, Water));
    // The pool scene's sun, (0.3, 0.1, −1) in its z-up frame.
    commands.spawn(common::sun(Vec3::new(0.3, 0.1, -1.0), true));
    let orbit = common::Orbit {
        yaw: -0.5,
        pitch: 0.75,
        distance: 6.5,
        centre: Vec3::new(0.0, 0.3, 0.0),
        farthest: 20.0,
    };
    commands.spawn((common::camera(orbit.transform()), orbit));
}

/// Pale blue pool tiles with grout, eight to a side, with their mip chain (box-filtered) so the far
/// floor does not shimmer.
fn tile_texture() -> Image {
    const N: usize = 256;
    let texel = |x: usize, y: usize| -> [f32; 3] {
        let (i, j) = (x % 32, y % 32);
        if i < 2 || j < 2 {
            return [0.62, 0.66, 0.66];
        }
        // Each tile its own shade, within ±4 %.
        let h = ((x / 32) * 7 + (y / 32) * 13) % 9;
        let s = 0.96 + 0.01 * h as f32;
        [0.62 * s, 0.80 * s, 0.88 * s]
    };
    let mut level: Vec<[f32; 3]> = (0..N * N).map(|k| texel(k % N, k / N)).collect();
    let mut data = Vec::new();
    let mut n = N;
    let mut levels = 0;
    loop {
        levels += 1;
        for c in &level {
            let srgb = Color::linear_rgb(c[0], c[1], c[2]).to_srgba().to_u8_array();
            data.extend_from_slice(&srgb);
        }
        if n == 1 {
            break;
        }
        let m = n / 2;
        level = (0..m * m)
            .map(|k| {
                let (x, y) = (2 * (k % m), 2 * (k / m));
                let mut sum = [0.0; 3];
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let c = level[(y + dy) * n + x + dx];
                    for ch in 0..3 {
                        sum[ch] += c[ch] / 4.0;
                    }
                }
                sum
            })
            .collect();
        n = m;
    }
    let mut image = Image::new(
        Extent3d {
            width: N as u32,
            height: N as u32,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data[..N * N * 4].to_vec(),
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    // The whole chain, level after level (`Image::new` checks the first level's size only).
    image.data = Some(data);
    image.texture_descriptor.mip_level_count = levels;
    image.sampler = ImageSampler::Descriptor(ImageSamplerDescriptor {
        address_mode_u: ImageAddressMode::Repeat,
        address_mode_v: ImageAddressMode::Repeat,
        mipmap_filter: ImageFilterMode::Linear,
        anisotropy_clamp: 8,
        ..ImageSamplerDescriptor::linear()
    });
    image
}

/// A left click drops a ripple where the cursor's ray meets the water's surface.
fn click_drops(
    buttons: Res<ButtonInput<MouseButton>>,
    window: Query<&Window, With<PrimaryWindow>>,
    camera: Query<(&Camera, &GlobalTransform)>,
    water: Query<(Entity, &CausticWater)>,
    mut drops: MessageWriter<DropRipple>,
) {
    if !buttons.just_pressed(MouseButton::Left) {
        return;
    }
    let (Ok(window), Ok((camera, at)), Ok((entity, w))) =
        (window.single(), camera.single(), water.single())
    else {
        return;
    };
    let Some(ray) = window
        .cursor_position()
        .and_then(|c| camera.viewport_to_world(at, c).ok())
    else {
        return;
    };
    let level = w.depth();
    if let Some(d) = ray.intersect_plane(Vec3::Y * level, InfinitePlane3d::new(Vec3::Y)) {
        drops.write(DropRipple {
            water: entity,
            at: ray.get_point(d),
            radius: 0.08,
            strength: 0.02,
        });
    }
}

/// A drop every 0.3 s somewhere on the water, from a fixed sequence.
fn rain(
    time: Res<Time>,
    mut rain: ResMut<Rain>,
    water: Query<(Entity, &CausticWater, &GlobalTransform)>,
    mut drops: MessageWriter<DropRipple>,
) {
    if !rain.on || time.elapsed_secs() < rain.next {
        return;
    }
    rain.next = time.elapsed_secs() + 0.3;
    let Ok((entity, w, at)) = water.single() else {
        return;
    };
    let k = (time.elapsed_secs() * 7.31).fract();
    let l = (time.elapsed_secs() * 3.17 + 0.4).fract();
    let (x, y) = (w.size() * (0.15 + 0.7 * k), w.size() * (0.15 + 0.7 * l));
    drops.write(DropRipple {
        water: entity,
        at: at.transform_point(Vec3::new(x, w.depth(), -y)),
        radius: 0.08,
        strength: 0.015,
    });
}
