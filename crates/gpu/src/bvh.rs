//! The objects' bounding-volume hierarchies for the GPU: the very trees the CPU builds
//! ([`caustics_core::mesh::MeshBvh`]), so that both sides visit the same nodes, flattened into the
//! shared node and triangle-slot buffers that `shaders/bvh.wgsl` walks.

use crate::pass::{f3, v4};
use caustics_core::mesh::TriangleMesh;

/// Mirrors `BvhNode` in `shaders/bvh.wgsl`; `start` is global (node or triangle-slot buffer).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuBvhNode {
    /// The box's lower corner, world units (z up).
    pub min: [f32; 3],
    /// A leaf's first triangle slot, or an interior node's left child (the right one follows it).
    pub start: u32,
    /// The box's upper corner, world units.
    pub max: [f32; 3],
    /// Triangles in a leaf; 0 marks an interior node.
    pub count: u32,
}

/// Mirrors `BvhTriangle` in `shaders/bvh.wgsl`: `p0`, the edges, the vertex normals (`w` unused).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuBvhTriangle {
    /// xyz: the first vertex, world units.
    pub p0: [f32; 4],
    /// xyz: the edge from `p0` to the second vertex.
    pub e1: [f32; 4],
    /// xyz: the edge from `p0` to the third vertex.
    pub e2: [f32; 4],
    /// xyz: the first vertex's unit outward normal.
    pub n0: [f32; 4],
    /// xyz: the second vertex's unit outward normal.
    pub n1: [f32; 4],
    /// xyz: the third vertex's unit outward normal.
    pub n2: [f32; 4],
}

/// Every mesh's tree appended to one node and one triangle-slot buffer, its indices made global.
#[derive(Default)]
pub struct FlatBvhs {
    /// Every mesh's nodes, each tree's root first and its `start`s made global.
    pub nodes: Vec<GpuBvhNode>,
    /// Every mesh's triangle slots, in its leaves' order.
    pub triangles: Vec<GpuBvhTriangle>,
    /// Each mesh's root in `nodes`.
    pub roots: Vec<u32>,
}

impl FlatBvhs {
    /// Append `mesh`'s tree; returns its root.
    pub fn push(&mut self, mesh: &TriangleMesh) -> u32 {
        let (flat, order) = mesh.bvh().flatten();
        let node_base = self.nodes.len() as u32;
        let slot_base = self.triangles.len() as u32;
        self.roots.push(node_base);
        self.nodes.extend(flat.iter().map(|n| GpuBvhNode {
            min: f3(n.min),
            max: f3(n.max),
            start: n.start + if n.count > 0 { slot_base } else { node_base },
            count: n.count,
        }));
        self.triangles.extend(order.iter().map(|&t| {
            let [a, b, c] = mesh.indices[t as usize].map(|i| i as usize);
            let p0 = mesh.positions[a];
            GpuBvhTriangle {
                p0: v4(p0, 0.0),
                e1: v4(mesh.positions[b] - p0, 0.0),
                e2: v4(mesh.positions[c] - p0, 0.0),
                n0: v4(mesh.normals[a], 0.0),
                n1: v4(mesh.normals[b], 0.0),
                n2: v4(mesh.normals[c], 0.0),
            }
        }));
        node_base
    }

    /// The trees of `meshes`, in order.
    pub fn of<'m>(meshes: impl IntoIterator<Item = &'m TriangleMesh>) -> Self {
        let mut flat = FlatBvhs::default();
        for mesh in meshes {
            flat.push(mesh);
        }
        flat
    }
}
