//! The objects' bounding-volume hierarchies for the GPU: the very trees the CPU builds
//! ([`caustics_core::mesh::MeshBvh`]), so that both sides visit the same nodes, flattened into the
//! shared node and triangle-slot buffers that `shaders/bvh.wgsl` walks.

use caustics_core::mesh::TriangleMesh;

/// Mirrors `BvhNode` in `shaders/bvh.wgsl`; `start` is global (node or triangle-slot buffer).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuBvhNode {
    pub min: [f32; 3],
    pub start: u32,
    pub max: [f32; 3],
    pub count: u32,
}

/// Mirrors `BvhTriangle` in `shaders/bvh.wgsl`: `p0`, the edges, the vertex normals (`w` unused).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuBvhTriangle {
    pub p0: [f32; 4],
    pub e1: [f32; 4],
    pub e2: [f32; 4],
    pub n0: [f32; 4],
    pub n1: [f32; 4],
    pub n2: [f32; 4],
}

/// Every mesh's tree appended to one node and one triangle-slot buffer, its indices made global.
#[derive(Default)]
pub struct FlatBvhs {
    pub nodes: Vec<GpuBvhNode>,
    pub triangles: Vec<GpuBvhTriangle>,
    /// Each mesh's root in `nodes`.
    pub roots: Vec<u32>,
}

impl FlatBvhs {
    /// Append `mesh`'s tree; returns its root.
    pub fn push(&mut self, mesh: &TriangleMesh) -> u32 {
        let f3 = |v: glam::DVec3| v.as_vec3().to_array();
        let f4 = |v: glam::DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
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
                p0: f4(p0),
                e1: f4(mesh.positions[b] - p0),
                e2: f4(mesh.positions[c] - p0),
                n0: f4(mesh.normals[a]),
                n1: f4(mesh.normals[b]),
                n2: f4(mesh.normals[c]),
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
