// Technique `procedural`, per-vertex variant (paper: "Implementation Using OpenGL"): the vertex
// shader computes the caustic at each vertex of a fine ground mesh of `mesh`^2 quads over the floor
// square, and the rasteriser interpolates it linearly over the triangles into the map. The mesh is
// drawn indexed, so a vertex shared by six triangles is shaded once (where the vertex cache allows).
// CPU twin: `vertex_values` + `rasterise`.

import package::procedural::common::{procedural_caustic, u};

struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) caustic: vec3<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> VertexOut {
    let k = v % (u.mesh + 1u);
    let l = v / (u.mesh + 1u);
    let f = vec2<f32>(f32(k), f32(l)) / f32(u.mesh);
    var o: VertexOut;
    // Map row 0 is y = 0 and is the render target's top row.
    o.position = vec4<f32>(2.0 * f.x - 1.0, 1.0 - 2.0 * f.y, 0.0, 1.0);
    o.caustic = procedural_caustic(f * u.size);
    return o;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.caustic, 1.0);
}
