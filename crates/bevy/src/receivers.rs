//! The application's meshes as the techniques' receivers (docs/receivers.md): every mesh whose
//! material is a water's [`Receiver::Mesh`] goes, in scene coordinates, into that water's
//! receivers, which the technique's light meets and which shade what lies under them; the
//! material then looks each fragment's light up in the technique's light-space deposit as a
//! shadow map is looked up.

use std::sync::Arc;

use bevy::asset::AssetEvent;
use bevy::mesh::{PrimitiveTopology, VertexAttributeValues};
use bevy::prelude::*;

use caustics_core::glam::DVec3;
use caustics_core::mesh::{TriangleMesh, smooth_normals};
use caustics_core::receivers::ReceiverHeights;
use caustics_core::scene::Solids;

use crate::{CausticMaps, CausticWater, CausticsMaterial, Receiver, scene_from_world};

/// The height the receivers' image holds beyond the technique's heights: below any receiver, so
/// a point whose light-space point falls there is lit.
pub(crate) const BELOW_ALL: f32 = -1.0e30;

/// The receivers a water's meshes make, and what they were made from: the meshes (entity, asset,
/// world transform) and where the water stood.
#[derive(Component, Clone, Default)]
pub(crate) struct ReceiverMeshes {
    key: Vec<(Entity, AssetId<Mesh>, Mat4)>,
    placed: Mat4,
    pub solids: Option<Arc<Solids>>,
}

type Receivers = (
    Entity,
    &'static Mesh3d,
    &'static MeshMaterial3d<CausticsMaterial>,
    &'static GlobalTransform,
);

/// Each water's [`ReceiverMeshes`], made again when a mesh with its `Receiver::Mesh` material
/// comes, goes, moves or changes, or the water moves; nothing while they stay (the technique
/// reuses its receivers and uploads nothing).
pub(crate) fn gather(
    mut commands: Commands,
    waters: Query<
        (
            Entity,
            &CausticMaps,
            &GlobalTransform,
            Option<&ReceiverMeshes>,
        ),
        With<CausticWater>,
    >,
    receivers: Query<Receivers>,
    materials: Res<Assets<CausticsMaterial>>,
    meshes: Res<Assets<Mesh>>,
    mut events: MessageReader<AssetEvent<Mesh>>,
) {
    let modified: Vec<AssetId<Mesh>> = events
        .read()
        .filter_map(|e| match e {
            AssetEvent::Modified { id } => Some(*id),
            _ => None,
        })
        .collect();
    for (entity, maps, at, current) in &waters {
        let mut key: Vec<_> = receivers
            .iter()
            .filter(|(_, _, material, _)| {
                materials.get(&material.0).is_some_and(|m| {
                    m.extension.floor == maps.floor
                        && m.extension.uniform.flags.y == Receiver::Mesh as u32
                })
            })
            .map(|(e, mesh, _, t)| (e, mesh.id(), t.to_matrix()))
            .collect();
        key.sort_by_key(|k| k.0);
        let placed = scene_from_world(at);
        let same = current.is_some_and(|c| c.key == key && c.placed == placed)
            && !key.iter().any(|k| modified.contains(&k.1));
        if same {
            continue;
        }
        // Wait for every mesh's asset: receivers made without one would light what it shades.
        let Some(found): Option<Vec<&Mesh>> = key.iter().map(|k| meshes.get(k.1)).collect() else {
            continue;
        };
        let list: Vec<TriangleMesh> = key
            .iter()
            .zip(found)
            .filter_map(|((e, _, m), mesh)| {
                let t = triangle_mesh(mesh, placed * *m);
                if t.is_none() {
                    warn!(
                        "bevy_caustics: the mesh of {e:?} is no triangle list with positions on \
                         the CPU (RenderAssetUsages::MAIN_WORLD): it receives but shades nothing"
                    );
                }
                t
            })
            .collect();
        commands.entity(entity).insert(ReceiverMeshes {
            key,
            placed,
            solids: Solids::of_meshes(list),
        });
    }
}

/// `mesh`'s triangles with `m` applied (world to scene coordinates included); `None` for a mesh
/// that is not a triangle list or whose positions are not on the CPU.
fn triangle_mesh(mesh: &Mesh, m: Mat4) -> Option<TriangleMesh> {
    if mesh.primitive_topology() != PrimitiveTopology::TriangleList {
        return None;
    }
    let Some(VertexAttributeValues::Float32x3(p)) = mesh.attribute(Mesh::ATTRIBUTE_POSITION) else {
        return None;
    };
    let positions: Vec<DVec3> = p
        .iter()
        .map(|v| {
            DVec3::from_array(
                m.transform_point3(Vec3::from_array(*v))
                    .as_dvec3()
                    .to_array(),
            )
        })
        .collect();
    let flat: Vec<u32> = match mesh.indices() {
        Some(i) => i.iter().map(|k| k as u32).collect(),
        None => (0..positions.len() as u32).collect(),
    };
    let indices: Vec<[u32; 3]> = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let normals = smooth_normals(&positions, &indices);
    Some(TriangleMesh {
        positions,
        normals,
        indices,
    })
}

/// Texels along a side of [`CausticMaps::receivers`](crate::CausticMaps::receivers): the floor map's
/// width plus the widest margin a sun can need (`ReceiverHeights::of_floor`'s, for receivers up
/// to the rest level under the most oblique refracted sun, `tan θt = 1 / √(n² − 1)`).
pub(crate) fn heights_side(water: &CausticWater) -> u32 {
    let scene = &water.scene;
    let width = scene.caustics.width.max(1) as f64;
    let ior = scene.water.as_ref().map_or(1.333, |w| w.ior).max(1.0001);
    let texel = scene.size / width;
    let shift = water.depth() as f64 / (ior * ior - 1.0).sqrt();
    (width + 2.0 * ((shift / texel).ceil() + 3.0)) as u32
}

/// The three texels of [`CausticMaps::light_view`](crate::CausticMaps::light_view) for receivers
/// `r` whose deposit attenuates by `absorption` (`None`: no light-space deposit).
pub(crate) fn light_view(r: Option<(&ReceiverHeights, DVec3)>) -> [[f32; 4]; 3] {
    let Some((r, k)) = r else {
        return [[0.0; 4]; 3];
    };
    let t = r.t0.as_vec3();
    [
        [r.origin.x as f32, r.origin.y as f32, r.texel as f32, 1.0],
        [t.x, t.y, t.z, r.max_slope as f32],
        [k.x as f32, k.y as f32, k.z as f32, 0.0],
    ]
}

/// `r`'s heights laid into a `side`² image, [`BELOW_ALL`] beyond them; `None` where they do not
/// fit.
pub(crate) fn heights_image(r: &ReceiverHeights, side: u32) -> Option<Vec<f32>> {
    let side = side as usize;
    if r.cols > side || r.rows > side {
        return None;
    }
    let mut out = vec![BELOW_ALL; side * side];
    for (i, row) in r.heights.chunks_exact(r.cols).enumerate() {
        out[i * side..i * side + r.cols].copy_from_slice(row);
    }
    Some(out)
}
