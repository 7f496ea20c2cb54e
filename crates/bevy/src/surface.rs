//! The water's surface, so that a scene looks like water: a mesh over the square at the rest
//! level, displaced on the GPU by the heights the technique reads each frame and shaded by Bevy's
//! `StandardMaterial` (its reflections, and its transmission where the application turns it on).

use bevy::asset::RenderAssetUsages;
use bevy::mesh::{Indices, PrimitiveTopology};
use bevy::pbr::{ExtendedMaterial, MaterialExtension};
use bevy::prelude::*;
use bevy::render::render_resource::AsBindGroup;
use bevy::shader::ShaderRef;

use crate::{CausticMaps, CausticWater, Heights};

/// `StandardMaterial` on a mesh displaced by the water's heights.
pub type WaterSurfaceMaterial = ExtendedMaterial<StandardMaterial, WaterSurfaceExtension>;

/// The heights a [`water_surface_mesh`] is displaced by (`water_surface.wesl`).
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct WaterSurfaceExtension {
    /// `x` the square's side, `y` 1 where the heights tile.
    #[uniform(100)]
    pub square: Vec4,
    /// `R32Float` heights above the rest level over the square: [`CausticMaps::surface`] for the
    /// scene's own source, the application's image for [`Heights::Image`].
    #[texture(101, sample_type = "float", filterable = false, visibility(vertex))]
    pub heights: Handle<Image>,
}

impl WaterSurfaceExtension {
    /// `base` on the surface of `water`, whose images are `maps`.
    pub fn material(
        base: StandardMaterial,
        water: &CausticWater,
        maps: &CausticMaps,
    ) -> WaterSurfaceMaterial {
        let wrap = water.scene.water.as_ref().is_some_and(|w| w.wrap);
        let heights = match &water.heights {
            Heights::Scene => maps.surface.clone(),
            Heights::Image(h) => h.clone(),
        };
        ExtendedMaterial {
            base,
            extension: WaterSurfaceExtension {
                square: Vec4::new(water.size(), u32::from(wrap) as f32, 0.0, 0.0),
                heights,
            },
        }
    }
}

impl MaterialExtension for WaterSurfaceExtension {
    fn vertex_shader() -> ShaderRef {
        "embedded://bevy_caustics/water_surface.wesl".into()
    }
}

/// A grid of `cells` x `cells` quads over `water`'s square at its rest level, in the water
/// entity's frame (spawn it with the water's `Transform`, or as its child) and facing up, for a
/// [`WaterSurfaceMaterial`] to displace.
pub fn water_surface_mesh(water: &CausticWater, cells: u32) -> Mesh {
    let n = cells.max(1) as usize;
    let (size, depth) = (water.size(), water.depth());
    let mut positions = Vec::with_capacity((n + 1) * (n + 1));
    let mut uvs = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let (u, v) = (j as f32 / n as f32, i as f32 / n as f32);
            // Scene (x, y) at the rest level is local (x, depth, −y).
            positions.push([u * size, depth, -v * size]);
            uvs.push([u, v]);
        }
    }
    let k = |i: usize, j: usize| (i * (n + 1) + j) as u32;
    let mut indices = Vec::with_capacity(6 * n * n);
    for i in 0..n {
        for j in 0..n {
            // Counter-clockwise seen from above.
            indices.extend_from_slice(&[k(i, j), k(i, j + 1), k(i + 1, j)]);
            indices.extend_from_slice(&[k(i, j + 1), k(i + 1, j + 1), k(i + 1, j)]);
        }
    }
    let normals = vec![[0.0, 1.0, 0.0]; positions.len()];
    Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::RENDER_WORLD,
    )
    .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions)
    .with_inserted_attribute(Mesh::ATTRIBUTE_NORMAL, normals)
    .with_inserted_attribute(Mesh::ATTRIBUTE_UV_0, uvs)
    .with_inserted_indices(Indices::U32(indices))
}
