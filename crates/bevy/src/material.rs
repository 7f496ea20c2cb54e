//! The material for what lies under the water: Bevy's `StandardMaterial` extended so that, under
//! the water square, the sun's direct light is the light the technique's maps say arrives there
//! (`caustics.wesl`).

use bevy::pbr::{ExtendedMaterial, MaterialExtension};
use bevy::prelude::*;
use bevy::render::render_resource::{AsBindGroup, ShaderType};
use bevy::shader::ShaderRef;

use crate::{CausticMaps, CausticWater, scene_from_world};

/// `StandardMaterial` with the caustic light under the water.
pub type CausticsMaterial = ExtendedMaterial<StandardMaterial, CausticsExtension>;

/// What `caustics.wesl` needs to find a fragment in the maps.
#[derive(Clone, Copy, Debug, Default, ShaderType, Reflect)]
pub struct CausticsUniform {
    /// World to scene coordinates (z up, the water square `[0, size]²` from the origin).
    pub scene_from_world: Mat4,
    /// `x` the square's side, `y` the rest water level above the floor, `z` the water's index of
    /// refraction.
    pub water: Vec4,
    /// The water's absorption per unit of path, per channel (for surfaces that are neither the
    /// floor nor a wall: lit as under flat water).
    pub absorption: Vec4,
    /// The columns of each wall's map in the walls image; 0 where the walls have none.
    pub wall_cols: UVec4,
    /// `x` 1 where the floor map tiles (open water over a flat floor, as the final image's
    /// `WRAP_CAUSTICS`), `y` the [`Receiver`], `z` the technique's kind ([`technique_flags`]: 1 an
    /// eye-space image in [`CausticMaps::eye`], 2 maps of the walls), `w` 1 where the water tiles
    /// (an ocean: beyond the square is more of it).
    pub flags: UVec4,
}

/// How a surface under the water finds its light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Reflect)]
pub enum Receiver {
    /// The pool the scene describes: the floor map on its floor (z = 0), the walls' maps on the
    /// square's sides, the flat water's light on anything else. The surface is the scene's own,
    /// not one of the water's receivers.
    #[default]
    Pool,
    /// Any mesh: a sea bed, a rock, a crate, a hull. The plugin puts every mesh with this
    /// material into its water's receivers (positions read on the CPU, so the mesh keeps
    /// `RenderAssetUsages::MAIN_WORLD`), the technique's light meets them, and each fragment takes
    /// the light deposited at its light-space point times its cosine to the refracted sun, none
    /// where another receiver lies nearer the light: a shadow map's lookup (docs/receivers.md).
    /// Where the technique makes no light-space deposit (`volumes`, which shades objects by its
    /// own depth textures, or no receivers yet) it is lit as a [`Receiver::Pool`] surface; under
    /// an eye-space technique its upward faces take the eye-space image.
    Mesh,
}

/// The extension: the maps of one [`CausticWater`] and where the water is.
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct CausticsExtension {
    #[uniform(100)]
    pub uniform: CausticsUniform,
    #[texture(101, sample_type = "float", filterable = false)]
    pub floor: Handle<Image>,
    #[texture(102, dimension = "2d_array", sample_type = "float", filterable = false)]
    pub walls: Handle<Image>,
    #[texture(103, sample_type = "float", filterable = false)]
    pub eye: Handle<Image>,
    #[texture(104, sample_type = "float", filterable = false)]
    pub light: Handle<Image>,
    #[texture(105, sample_type = "float", filterable = false)]
    pub receivers: Handle<Image>,
    #[texture(106, sample_type = "float", filterable = false)]
    pub light_view: Handle<Image>,
}

impl CausticsExtension {
    /// For surfaces under `water`, whose entity is at `at` (its `GlobalTransform`; a `Transform`
    /// without a parent converts with `GlobalTransform::from`), lit as `receiver`.
    pub fn new(
        water: &CausticWater,
        maps: &CausticMaps,
        at: &GlobalTransform,
        receiver: Receiver,
    ) -> Self {
        let w = water.scene.water.as_ref();
        let ior = w.map_or(1.333, |w| w.ior as f32);
        let absorption = w.map_or(Vec3::ZERO, |w| {
            Vec3::from_array(w.absorption.as_vec3().to_array())
        });
        let wrap = w.is_some_and(|w| w.wrap) && water.scene.floor.terrain.is_none();
        CausticsExtension {
            uniform: CausticsUniform {
                scene_from_world: scene_from_world(at),
                water: Vec4::new(water.size(), water.depth(), ior, 0.0),
                absorption: absorption.extend(0.0),
                wall_cols: UVec4::from_array(maps.wall_cols),
                flags: UVec4::new(
                    u32::from(wrap),
                    receiver as u32,
                    technique_flags(water),
                    u32::from(w.is_some_and(|w| w.wrap)),
                ),
            },
            floor: maps.floor.clone(),
            walls: maps.walls.clone(),
            eye: maps.eye.clone(),
            light: maps.light.clone(),
            receivers: maps.receivers.clone(),
            light_view: maps.light_view.clone(),
        }
    }

    /// `base` under `water`: what an application puts on its pool floor, walls, rocks.
    pub fn material(
        base: StandardMaterial,
        water: &CausticWater,
        maps: &CausticMaps,
        at: &GlobalTransform,
        receiver: Receiver,
    ) -> CausticsMaterial {
        ExtendedMaterial {
            base,
            extension: Self::new(water, maps, at, receiver),
        }
    }
}

impl MaterialExtension for CausticsExtension {
    fn fragment_shader() -> ShaderRef {
        "embedded://bevy_caustics/caustics.wesl".into()
    }
}

/// What the material must know of the technique: 1 when it makes an eye-space image, 2 when it
/// makes maps of the pool's walls (and the scene has walls). A technique without either leaves
/// the walls lit as under flat water.
pub fn technique_flags(water: &CausticWater) -> u32 {
    u32::from(water.eye_space()) | (u32::from(water.lights_walls()) << 1)
}

/// A water, its maps (which name its materials) and where it stands.
type WaterPlaced = (
    &'static CausticWater,
    &'static CausticMaps,
    &'static GlobalTransform,
);

type MovedOrChanged = Or<(Changed<CausticWater>, Changed<GlobalTransform>)>;

/// A water that moved, or whose technique changed kind (floor map, eye-space image, wall maps or
/// not): its materials find their fragments where the water now is, and read what its technique
/// makes, from the next frame on (a uniform write; the bind group is made again only then).
pub(crate) fn follow_water(
    waters: Query<WaterPlaced, MovedOrChanged>,
    mut materials: ResMut<Assets<CausticsMaterial>>,
) {
    for (water, maps, at) in &waters {
        let kind = technique_flags(water);
        let placed = scene_from_world(at);
        let ids: Vec<_> = materials
            .iter()
            .filter(|(_, m)| {
                let u = &m.extension.uniform;
                m.extension.floor == maps.floor
                    && (u.flags.z != kind || u.scene_from_world != placed)
            })
            .map(|(id, _)| id)
            .collect();
        for id in ids {
            if let Some(mut m) = materials.get_mut(id) {
                m.extension.uniform.flags.z = kind;
                m.extension.uniform.scene_from_world = placed;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use caustics_core::scene::Scene;

    use super::*;

    /// The material follows its water: moved, the water's materials map world points to the
    /// scene where the water now stands (a point above the moved floor's corner is the scene's
    /// origin again); another water's materials stay.
    #[test]
    fn materials_follow_their_water_when_it_moves() {
        let mut world = World::new();
        world.init_resource::<Assets<Image>>();
        world.init_resource::<Assets<CausticsMaterial>>();
        let water = CausticWater::new(Scene::builtin("pool").unwrap(), "yuksel").unwrap();
        let (mut ids, mut entities) = (Vec::new(), Vec::new());
        for x in [0.0, 10.0] {
            let at = GlobalTransform::from(Transform::from_xyz(x, 0.0, 0.0));
            let maps = world.resource_scope(|_, mut images: Mut<Assets<Image>>| {
                CausticMaps::new(&water, &mut images)
            });
            let material = CausticsExtension::material(
                StandardMaterial::default(),
                &water,
                &maps,
                &at,
                Receiver::Pool,
            );
            ids.push(
                world
                    .resource_mut::<Assets<CausticsMaterial>>()
                    .add(material),
            );
            entities.push(world.spawn((water.clone(), maps, at)).id());
        }
        let placed = |world: &World, k: usize| {
            let materials = world.resource::<Assets<CausticsMaterial>>();
            materials
                .get(&ids[k])
                .unwrap()
                .extension
                .uniform
                .scene_from_world
        };
        // One system run frame after frame, as the plugin runs it: its change filters hold.
        let follow = world.register_system(follow_water);
        world.run_system(follow).unwrap();
        let before = placed(&world, 0);
        // A water that did not change is left alone: a material written by hand stays so.
        world
            .resource_mut::<Assets<CausticsMaterial>>()
            .get_mut(&ids[1])
            .unwrap()
            .extension
            .uniform
            .scene_from_world = Mat4::IDENTITY;
        let moved = Transform::from_xyz(3.0, -2.0, 7.0).with_rotation(Quat::from_rotation_y(0.4));
        world
            .entity_mut(entities[0])
            .insert(GlobalTransform::from(moved));
        world.run_system(follow).unwrap();
        let corner = placed(&world, 0).transform_point3(moved.translation);
        assert!(corner.length() < 1e-5, "{corner}");
        assert_ne!(placed(&world, 0), before);
        assert_eq!(placed(&world, 1), Mat4::IDENTITY);
    }
}
