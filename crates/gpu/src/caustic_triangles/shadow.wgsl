// Technique `caustic-triangles`, the light cube map as a shadow map (paper §4.3): per texel of the
// C x 6C light cube map, the distance from the light to the first surface along the texel centre's
// direction: the floor, or any surface (glass or diffuse) of this generator's distance map, nearer
// than what earlier generators left (the host fills the buffer with f32 max first). CPU twin:
// `shadow_pass` / `first_surface` in caustics-core/src/techniques/caustic_triangles/cube.rs.

import package::caustic_triangles::common::CausticTriangles;
import package::caustic_triangles::distance_map::{
    cube_texel_dir, dm_info, dm_trace_mode, dmg, sphere_span,
};

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(2) var<storage, read_write> shadow: array<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let c = u.light_cube;
    if id.x >= c || id.y >= 6u * c {
        return;
    }
    dmg = dm_info(u, 0u);
    let k = id.y * c + id.x;
    let light = u.light.xyz;
    let d = cube_texel_dir(id.y / c, id.y % c, id.x, c);
    var best = shadow[k];
    if d.z < 0.0 {
        best = min(best, -light.z / d.z);
    }
    let span = sphere_span(light, d);
    if span.y > 0.0 && span.x < best {
        let h = dm_trace_mode(light + d * span.x, d, 0.0, min(span.y, best) - span.x, 0u);
        if h.found {
            best = min(best, span.x + h.d);
        }
    }
    shadow[k] = best;
}
