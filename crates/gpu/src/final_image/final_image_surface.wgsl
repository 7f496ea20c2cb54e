// The water's surface rasterised from the camera: a grid over the water square through the heights
// the final image reads, raised so that it lies above the bicubic surface everywhere, drawn into an
// R32Float target holding, per pixel, the distance from the camera to the grid's nearest point on
// the pixel centre's view ray (negative where the ray misses the grid). A ray from above meets the
// raised grid no later than the surface, so the final image starts its search for the surface
// along a primary ray there (`hit_surface`) instead of marching the whole slab from its top: the grid
// accelerates the search, the crossing it returns is still the first of the bicubic surface, as
// the CPU's march finds it. A render pass of the final image, before its compute pass.

import package::final_image::final_image_inputs::{
    FLAG_WRAP_SURFACE, params, slope_bound, water_height,
};
import package::shaders::water::grid_sample_hermite;

// The grid's most cells along a side: the heights' own lattice where it is finer than this would
// cost more vertices than the search it saves (final_image/mod.rs `SURFACE_CELLS`).
const MAX_CELLS: u32 = 128u;
// The near plane's distance, in metres, and the reversed depth's: depth = NEAR / distance along
// the view axis, so that far points keep their precision.
const NEAR: f32 = 1e-3;

// The grid's cells along each side.
fn cells() -> vec2<u32> {
    return min(textureDimensions(water_height), vec2<u32>(MAX_CELLS));
}

struct Vertex {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> Vertex {
    // Vertices at the cells' centres of a lattice one cell wider than the square on each side, so
    // that the triangles cover all of it; two triangles a quad.
    let n = cells();
    let quad = index / 6u;
    let corner = array<vec2<u32>, 6>(
        vec2<u32>(0u, 0u), vec2<u32>(1u, 0u), vec2<u32>(1u, 1u),
        vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(0u, 1u),
    )[index % 6u];
    let ij = vec2<f32>(vec2<u32>(quad % (n.x + 1u), quad / (n.x + 1u)) + corner) - 0.5;
    let xy = ij * (params.water_size / vec2<f32>(n));
    let wrap = (params.flags & FLAG_WRAP_SURFACE) != 0u;
    let h = grid_sample_hermite(water_height, xy, params.water_size, wrap).x;
    // Within a triangle the surface rises above the plane through its corners by at most its
    // slope times the distance to the farthest corner: the slab's slope bound (render.rs
    // `slab_bounds`) times the cell's diagonal.
    let cell = params.water_size / vec2<f32>(n);
    let raise = slope_bound() * length(cell);
    let world = vec3<f32>(xy, params.water_level + h + raise);
    // `camera_ray`'s inverse: the ray through (sx, sy) runs along forward + right sx + up sy, the
    // three orthogonal, so a point's clip coordinates are its components along them.
    let v = world - params.camera_position;
    let right = params.camera_right;
    let up = params.camera_up;
    let forward = params.camera_forward;
    let w = dot(v, forward) / dot(forward, forward);
    return Vertex(
        vec4<f32>(dot(v, right) / dot(right, right), dot(v, up) / dot(up, up), NEAR, w),
        world,
    );
}

@fragment
fn fs_main(in: Vertex) -> @location(0) vec4<f32> {
    return vec4<f32>(distance(in.world, params.camera_position), 0.0, 0.0, 1.0);
}
