//! `bevy_caustics`: water caustics in a Bevy game, computed every frame from the actual water by
//! one of the caustics techniques (the five papers' and ours), on Bevy's own device, queue and
//! command encoder.
//!
//! A user spawns a water entity with a [`CausticWater`] (the scene's optics, the technique, where
//! the heights come from) and the [`CausticMaps`] it renders into, and gives what lies under the
//! water a [`CausticsMaterial`]: Bevy's `StandardMaterial` whose sun light there is replaced by
//! the light the technique says arrives through the waves, with the water's absorption and Bevy's
//! shadows. `docs/bevy.md` tells where the work sits in Bevy's frame and what it costs.
//!
//! The scene's coordinates are z-up, the water square `[0, size]²` with the floor at z = 0; Bevy
//! is y-up. The water entity's transform places the scene: scene `(x, y, z)` is the entity's
//! local `(x, z, −y)`, so the square runs along +x and −z from the entity's origin, the floor at
//! its height and the rest water level `depth` above it.
//!
//! A pool's floor lit by `caustic-triangles` from the built-in pool's moving water:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_caustics::{CausticMaps, CausticWater, CausticsExtension, CausticsMaterial};
//! use bevy_caustics::{CausticsPlugin, Receiver};
//! use caustics_core::scene::Scene;
//!
//! fn main() {
//!     App::new()
//!         .add_plugins((DefaultPlugins, CausticsPlugin))
//!         .add_systems(Startup, setup)
//!         .run();
//! }
//!
//! fn setup(
//!     mut commands: Commands,
//!     mut images: ResMut<Assets<Image>>,
//!     mut meshes: ResMut<Assets<Mesh>>,
//!     mut materials: ResMut<Assets<CausticsMaterial>>,
//! ) -> Result {
//!     let water = CausticWater::new(Scene::builtin("pool")?, "caustic-triangles")?;
//!     let maps = CausticMaps::new(&water, &mut images); // the images the technique fills
//!     let at = Transform::from_xyz(-2.0, 0.0, 2.0); // the 4 m square runs along +x and -z
//!     let floor = materials.add(CausticsExtension::material(
//!         StandardMaterial::default(),
//!         &water,
//!         &maps,
//!         &GlobalTransform::from(at),
//!         Receiver::Pool,
//!     ));
//!     commands.spawn((water, maps, at));
//!     let plane = meshes.add(Plane3d::default().mesh().size(4.0, 4.0));
//!     commands.spawn((Mesh3d(plane), MeshMaterial3d(floor)));
//!     let sun = Vec3::new(0.3, -1.0, -0.1);
//!     commands.spawn((DirectionalLight::default(), Transform::default().looking_to(sun, Vec3::Y)));
//!     let eye = Transform::from_xyz(0.0, 5.0, 6.0).looking_at(Vec3::ZERO, Vec3::Y);
//!     commands.spawn((Camera3d::default(), eye));
//!     Ok(())
//! }
//! ```

mod material;
mod receivers;
mod render;
mod surface;

use bevy::asset::{RenderAssetUsages, embedded_asset, uuid_handle};
use bevy::prelude::*;
use bevy::render::render_resource::{
    Extent3d, TextureDimension, TextureFormat, TextureUsages, TextureViewDescriptor,
    TextureViewDimension,
};
use bevy::render::{ExtractSchedule, RenderApp};
use bevy::transform::TransformSystems;

use caustics_core::map::pyramid_levels;
use caustics_core::scene::Scene;
use caustics_core::techniques::describe::Receiver as Receives;
use caustics_core::walls::WallMaps;
use caustics_core::water::ripple::Drop;
use caustics_gpu::shaders;

pub use material::{CausticsExtension, CausticsMaterial, CausticsUniform, Receiver};
pub use render::CausticsStats;
pub use surface::{WaterSurfaceExtension, WaterSurfaceMaterial, water_surface_mesh};

/// The plugin: the technique of every [`CausticWater`] recorded into Bevy's render world each
/// frame, before the cameras draw, and the material that shows its light.
pub struct CausticsPlugin;

impl Plugin for CausticsPlugin {
    fn build(&self, app: &mut App) {
        embedded_asset!(app, "caustics.wesl");
        embedded_asset!(app, "water_surface.wesl");
        if let Some(mut assets) = app.world_mut().get_resource_mut::<Assets<Shader>>() {
            for (handle, source, path) in SHARED_WGSL {
                if let Err(e) = assets.insert(handle.id(), Shader::from_wesl(source, path)) {
                    warn!("bevy_caustics: {path} was not registered: {e}");
                }
            }
        }
        let stats = CausticsStats::default();
        app.add_plugins((
            MaterialPlugin::<CausticsMaterial>::default(),
            MaterialPlugin::<WaterSurfaceMaterial>::default(),
        ))
        .add_message::<DropRipple>()
        .init_resource::<PendingDrops>()
        .insert_resource(stats.clone())
        .add_systems(First, clear_drops)
        .add_systems(
            PostUpdate,
            (
                queue_drops,
                material::follow_water.after(TransformSystems::Propagate),
                receivers::gather.after(TransformSystems::Propagate),
            ),
        );
        let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
            warn!("bevy_caustics: no render app (headless without rendering): no caustics");
            return;
        };
        render_app
            .insert_resource(stats)
            .add_systems(ExtractSchedule, render::extract);
        render::build(render_app);
    }
}

/// caustics-gpu's shared WGSL that `caustics.wesl` imports, the final image's own copies: each as
/// the WESL module its path names (Bevy names an `embedded://` shader `caustics_gpu::<file>`).
const SHARED_WGSL: [(Handle<Shader>, &str, &str); 4] = [
    (
        uuid_handle!("3e9a5c71-2d4b-4f86-a0c3-7b1e9d2f6a58"),
        shaders::CAUSTICS_LIGHT,
        "embedded://caustics_gpu/caustics_light.wesl",
    ),
    (
        uuid_handle!("6f0c1d52-8a3e-4b7f-9c21-3d5e7a9b1c40"),
        shaders::CAUSTICS_SAMPLING,
        "embedded://caustics_gpu/caustics_sampling.wesl",
    ),
    (
        uuid_handle!("0b7d4e21-5c9a-4f3e-8d62-1a4f6c8e2b95"),
        shaders::OPTICS,
        "embedded://caustics_gpu/optics.wesl",
    ),
    (
        uuid_handle!("9d2e6b14-7f3a-4c85-b1e0-5a8c2f7d3e61"),
        shaders::RECEIVERS,
        "embedded://caustics_gpu/receivers.wesl",
    ),
];

/// Where a [`CausticWater`]'s heights come from.
#[derive(Clone, Debug, Default)]
pub enum Heights {
    /// The scene's own source (`scene.water.source`: sine waves, paper 2's waves, the FFT ocean,
    /// the ripple simulation, a height field file), evaluated on the GPU every frame at Bevy's
    /// `Time` by `caustics_gpu::water::field::GpuWater`.
    #[default]
    Scene,
    /// The application's own heights: an `R32Float` image (usage `TEXTURE_BINDING | COPY_DST`, so
    /// that Bevy rewrites the same texture when the application changes it) of the
    /// displacement above the rest level over the water square, texel `(j, i)` at `((j + ½) size /
    /// width, (i + ½) size / height)` in scene coordinates (row `i` along the scene's y, that is
    /// along Bevy's −z from the entity). The application may rewrite it every frame.
    Image(Handle<Image>),
}

/// A body of water whose caustics are computed: put it on an entity with a [`Transform`] (which
/// places the scene, see the crate's docs) and the [`CausticMaps`] made for it.
#[derive(Component, Clone, Debug)]
#[require(Transform)]
pub struct CausticWater {
    /// The optics and sizes: `water` (size, depth, index, absorption, wrap, source), `floor.walls`
    /// (whether the pool's walls get maps), `caustics.width` x `caustics.height` (the floor map).
    /// The sun is taken from the world's first `DirectionalLight` every frame, the time from
    /// Bevy's `Time`.
    pub scene: Scene,
    /// A registered technique that makes a floor map or an eye-space image
    /// ([`CausticWater::techniques`]).
    pub technique: String,
    /// Parameter tables keyed by technique, as in a scene file's `[caustics]`
    /// (`{ yuksel = { n = 15 } }`); empty means every technique's defaults.
    pub params: toml::Table,
    pub heights: Heights,
}

/// What [`CausticWater::new`] refuses.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CausticsError(pub String);

impl std::fmt::Display for CausticsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for CausticsError {}

impl CausticWater {
    /// The scene's water with `technique`; an error naming the problem when the scene has no
    /// water or the technique is not one of [`CausticWater::techniques`].
    pub fn new(scene: Scene, technique: &str) -> Result<Self, CausticsError> {
        if scene.water.is_none() {
            return Err(CausticsError(format!(
                "scene `{}` has no [water]: there is nothing to make caustics from",
                scene.name
            )));
        }
        check_technique(technique)?;
        Ok(CausticWater {
            scene,
            technique: technique.to_string(),
            params: toml::Table::new(),
            heights: Heights::Scene,
        })
    }

    /// The registered techniques a [`CausticWater`] can use, in the registry's order: those that
    /// make a floor map, and paper 5's eye-space image (made from Bevy's first 3D camera).
    pub fn techniques() -> Vec<&'static str> {
        caustics_gpu::registry::REGISTRY
            .iter()
            .filter(|r| {
                let receives = r.describe.receivers;
                receives.contains(&Receives::Floor) || receives.contains(&Receives::EyeSpace)
            })
            .map(|r| r.name())
            .collect()
    }

    /// Whether the technique makes an image in the camera's screen space (paper 5) rather than a
    /// map of the floor.
    pub fn eye_space(&self) -> bool {
        caustics_gpu::registry::find(&self.technique)
            .is_some_and(|r| r.describe.receivers.contains(&Receives::EyeSpace))
    }

    /// Whether the technique makes maps of the pool's walls and the scene has walls.
    pub fn lights_walls(&self) -> bool {
        self.scene.floor.walls
            && caustics_gpu::registry::find(&self.technique)
                .is_some_and(|r| r.describe.receivers.contains(&Receives::Walls))
    }

    /// The rest water level above the floor.
    pub fn depth(&self) -> f32 {
        self.scene.water.as_ref().map_or(0.0, |w| w.depth as f32)
    }

    /// The side of the water square.
    pub fn size(&self) -> f32 {
        self.scene.size as f32
    }
}

fn check_technique(name: &str) -> Result<(), CausticsError> {
    let usable = CausticWater::techniques();
    if usable.contains(&name) {
        return Ok(());
    }
    Err(CausticsError(format!(
        "technique `{name}` cannot light a Bevy scene (usable: {})",
        usable.join(", ")
    )))
}

/// The images a [`CausticWater`]'s technique renders into each frame, on the GPU (copies of its
/// output, never read back), for [`CausticsExtension`] and anything else that samples them:
/// `Rgba32Float`, not filterable (read with `textureLoad`), relative irradiance per channel (1 =
/// what the sun gives through flat, clear water; the water's absorption included). The floor
/// map has its whole mip chain, made on the GPU each frame: each mip the mean of the 2 x 2 texels
/// under it (caustics-core's `CausticsMap::pyramid`; alpha 0 in the mips), so a reader can take
/// the map's mean over a pixel's footprint, as the material does.
#[derive(Component, Clone, Debug)]
pub struct CausticMaps {
    /// The floor map: `caustics.width` x `caustics.height` texels over the water square, row 0
    /// at scene y = 0.
    pub floor: Handle<Image>,
    /// The walls' maps: four layers (x = 0, x = size, y = 0, y = size), each wall's map in its
    /// first `wall_cols[k]` columns, row 0 at the floor; a 1 x 1 x 4 image without walls.
    pub walls: Handle<Image>,
    pub wall_cols: [u32; 4],
    /// An eye-space technique's image (`cascaded`): `scene.camera.width` x `height` texels over
    /// Bevy's first 3D camera's view (its pose and vertical field of view, this image's aspect),
    /// row 0 at the top; `w` is −1 where a pixel has no value.
    pub eye: Handle<Image>,
    /// The technique's light-space deposit where its light meets receivers (docs/receivers.md):
    /// flux per unit area of the plane z = 0 along the flat-water refracted sun, the floor map's
    /// size and window; what [`Receiver::Mesh`] surfaces look their light up in.
    pub light: Handle<Image>,
    /// The receivers' heights the technique's light met, seen from the sun through flat water
    /// (`R32Float`, scene units; their texels in the first columns and rows, the rest far
    /// below any receiver).
    pub receivers: Handle<Image>,
    /// Where `light` and `receivers` lie, three `Rgba32Float` texels: the heights' light-space corner,
    /// texel side and 1 (0: no light-space deposit this frame); the refracted sun and the heights'
    /// steepest slope; the absorption along a receiver's flat-water path.
    pub light_view: Handle<Image>,
    /// The water's heights above the rest level over the square, `R32Float`,
    /// [`SURFACE_TEXELS`]² texels (texel `(j, i)` at `((j + ½), (i + ½)) size / SURFACE_TEXELS`),
    /// written on the GPU each frame from the scene's source: what [`WaterSurfaceMaterial`]
    /// displaces its mesh by.
    pub surface: Handle<Image>,
}

/// Texels along a side of [`CausticMaps::surface`].
pub const SURFACE_TEXELS: u32 = 128;

impl CausticMaps {
    /// The images for `water`, added to `images`.
    pub fn new(water: &CausticWater, images: &mut Assets<Image>) -> Self {
        let scene = &water.scene;
        let (width, height) = (scene.caustics.width.max(1), scene.caustics.height.max(1));
        // Until the technique's first frame: the floor as under flat, clear water (1), and no
        // eye-space value (w = -1), which the material lights as under flat water.
        let mut floor = map_image(width, height, 1, 1.0);
        with_mips(&mut floor);
        let floor = images.add(floor);
        let (cols, rows, wall_cols) = if scene.floor.walls {
            let layout = WallMaps::for_floor_map(
                width as usize,
                height as usize,
                scene.size,
                water.depth() as f64,
            );
            let cols = layout.maps.each_ref().map(|m| m.cols as u32);
            (
                cols.iter().copied().max().unwrap_or(1),
                layout.maps[0].rows as u32,
                cols,
            )
        } else {
            (1, 1, [0; 4])
        };
        let mut walls = map_image(cols, rows, 4, 1.0);
        walls.texture_view_descriptor = Some(TextureViewDescriptor {
            dimension: Some(TextureViewDimension::D2Array),
            ..default()
        });
        let eye = map_image(
            scene.camera.width.max(1),
            scene.camera.height.max(1),
            1,
            -1.0,
        );
        let light = map_image(width, height, 1, 1.0);
        let side = receivers::heights_side(water);
        let receivers = Image::new_fill(
            Extent3d {
                width: side,
                height: side,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &receivers::BELOW_ALL.to_le_bytes(),
            TextureFormat::R32Float,
            RenderAssetUsages::RENDER_WORLD,
        );
        let surface = Image::new_fill(
            Extent3d {
                width: SURFACE_TEXELS,
                height: SURFACE_TEXELS,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            &0f32.to_le_bytes(),
            TextureFormat::R32Float,
            RenderAssetUsages::RENDER_WORLD,
        );
        let mut light_view = map_image(3, 1, 1, 0.0);
        light_view.data = Some(vec![0; 3 * 16]);
        CausticMaps {
            floor,
            walls: images.add(walls),
            wall_cols,
            eye: images.add(eye),
            light: images.add(light),
            receivers: images.add(receivers),
            light_view: images.add(light_view),
            surface: images.add(surface),
        }
    }
}

/// A map image filled with `(1, 1, 1, w)`.
fn map_image(width: u32, height: u32, layers: u32, w: f32) -> Image {
    let texel: Vec<u8> = [1.0f32, 1.0, 1.0, w]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let mut image = Image::new_fill(
        Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        TextureDimension::D2,
        &texel,
        TextureFormat::Rgba32Float,
        RenderAssetUsages::RENDER_WORLD,
    );
    // COPY_SRC: an application (or a test) may read a map back, e.g. to bake it.
    image.texture_descriptor.usage =
        TextureUsages::TEXTURE_BINDING | TextureUsages::COPY_DST | TextureUsages::COPY_SRC;
    image
}

/// `image` (one level, filled) with its whole mip chain, every level filled as its first, and
/// writable by a compute pass (the map's pyramid, `caustics_gpu::map_mips::MapMips`).
fn with_mips(image: &mut Image) {
    let size = image.texture_descriptor.size;
    let levels = pyramid_levels(size.width as usize, size.height as usize) as u32;
    let texel = image
        .texture_descriptor
        .format
        .block_copy_size(None)
        .unwrap_or(16) as usize;
    if let Some(data) = &mut image.data {
        let first = data[..texel].to_vec();
        let texels: u32 = (1..levels)
            .map(|k| {
                let s = size.mip_level_size(k, TextureDimension::D2);
                s.width * s.height
            })
            .sum();
        for _ in 0..texels {
            data.extend_from_slice(&first);
        }
    }
    image.texture_descriptor.mip_level_count = levels;
    image.texture_descriptor.usage |= TextureUsages::STORAGE_BINDING;
}

/// A drop into a [`CausticWater`] whose heights are the scene's ripple simulation (ignored by
/// other sources): a cosine bump at a world point over the water.
#[derive(Message, Clone, Debug)]
pub struct DropRipple {
    pub water: Entity,
    /// Where it falls, in world coordinates (only its position over the square counts).
    pub at: Vec3,
    /// The bump's radius, world units.
    pub radius: f32,
    /// Height added at its centre; negative for a dent.
    pub strength: f32,
}

/// The drops of this frame, in scene coordinates, waiting for the render world to take them.
#[derive(Resource, Default, Clone)]
pub(crate) struct PendingDrops(pub Vec<(Entity, Drop)>);

fn clear_drops(mut pending: ResMut<PendingDrops>) {
    pending.0.clear();
}

fn queue_drops(
    mut messages: MessageReader<DropRipple>,
    waters: Query<&GlobalTransform, With<CausticWater>>,
    mut pending: ResMut<PendingDrops>,
) {
    for m in messages.read() {
        let Ok(at) = waters.get(m.water) else {
            warn!(
                "a ripple dropped into {:?}, which is no CausticWater",
                m.water
            );
            continue;
        };
        let p = scene_from_world(at).transform_point3(m.at);
        pending.0.push((
            m.water,
            Drop {
                position: [p.x as f64, p.y as f64],
                radius: m.radius as f64,
                strength: m.strength as f64,
            },
        ));
    }
}

/// Scene coordinates (z up, the square from the origin) from world coordinates, for a water
/// entity at `at`.
pub fn scene_from_world(at: &GlobalTransform) -> Mat4 {
    scene_from_local() * Mat4::from(at.affine()).inverse()
}

/// The entity's local y-up frame to the scene's z-up one: local `(x, y, z)` is scene `(x, −z, y)`.
fn scene_from_local() -> Mat4 {
    Mat4::from_cols(Vec4::X, Vec4::Z, -Vec4::Y, Vec4::W)
}

#[cfg(test)]
mod tests {
    /// The plugin builds caustics-core without its `formats` feature (it reads no file; Bevy's
    /// assets do): a height field, an albedo image or an OBJ mesh named in a scene is refused
    /// with the feature to turn on, whatever the file holds.
    #[test]
    fn files_this_build_cannot_read_are_refused_naming_the_feature() {
        use caustics_core::scene::Scene;
        let dir =
            std::env::temp_dir().join(format!("bevy-caustics-formats-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for file in [
            "heights.npy",
            "heights.exr",
            "heights.png",
            "sand.png",
            "rock.obj",
        ] {
            std::fs::write(dir.join(file), b"never read").unwrap();
        }
        let water = "[light]\ndirection = [-0.3, 0.2, -1.0]\n[water]\nsize = 4.0\ndepth = 1.0\n";
        let scenes = [
            (
                format!("{water}heightfield = \"heights.npy\"\n"),
                "a .npy height field",
            ),
            (
                format!("{water}heightfield = \"heights.exr\"\n"),
                "an .exr height field",
            ),
            (
                format!("{water}heightfield = \"heights.png\"\n"),
                "a PNG height field",
            ),
            (
                format!("{water}[floor]\nalbedo = \"sand.png\"\n"),
                "an albedo image",
            ),
        ];
        for (text, what) in scenes {
            let err = Scene::from_toml_with(&text, &dir, "formats", |_| Ok(()))
                .expect_err(what)
                .to_string();
            assert!(
                err.contains(what) && err.contains("`formats` feature"),
                "{what}: {err}"
            );
        }
        let err = caustics_core::mesh::load_obj(&dir.join("rock.obj"))
            .expect_err("an OBJ mesh")
            .to_string();
        assert!(
            err.contains("an OBJ mesh") && err.contains("`formats` feature"),
            "{err}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The lines of the first `rust` block under `heading` in the Markdown file `path` (from the
    /// repository's root).
    fn rust_block_under(path: &str, heading: &str) -> Vec<String> {
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path);
        let text = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{path}: {e}"));
        text.lines()
            .skip_while(|l| *l != heading)
            .skip_while(|l| *l != "```rust")
            .skip(1)
            .take_while(|l| *l != "```")
            .map(String::from)
            .collect()
    }

    /// docs/bevy.md's and the README's example is this crate's front-page example, which `cargo
    /// test` compiles.
    #[test]
    fn the_guide_and_the_readme_show_the_compiled_example() {
        let lib = include_str!("lib.rs");
        let front: Vec<&str> = lib
            .lines()
            .filter_map(|l| l.strip_prefix("//!"))
            .map(|l| l.strip_prefix(' ').unwrap_or(l))
            .skip_while(|l| !l.starts_with("```no_run"))
            .skip(1)
            .take_while(|l| !l.starts_with("```"))
            .collect();
        assert!(
            front.len() > 20,
            "{} lines in the front page's example",
            front.len()
        );
        assert_eq!(rust_block_under("docs/bevy.md", "## Using it"), front);
        assert_eq!(rust_block_under("README.md", "## In Bevy"), front);
    }
}
