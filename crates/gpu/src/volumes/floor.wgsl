// Technique `volumes`, the floor map: every illumination volume of the water cut by the floor z = 0,
// drawn additively, fragments kept where the shadow map lets the sun through. CPU twin: `floor_pass`
// in caustics-core/src/techniques/volumes/illumination.rs.

import package::volumes::common::{
    FLOOR_BIAS, SliceOut, Volumes, WaterVertex, culled_slice, cut_volume, lattice_triangle, lit,
    pixel_to_clip,
};

@group(0) @binding(0) var<uniform> c: Volumes;
@group(0) @binding(1) var<storage, read> water: array<WaterVertex>;
@group(0) @binding(2) var shadow: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> SliceOut {
    let cols = c.dims.x;
    let tri_index = vi / 3u;
    let cell = tri_index / 2u;
    let idx = lattice_triangle(c, cell / cols, cell % cols, tri_index % 2u);
    let tri = array<WaterVertex, 3>(water[idx.x], water[idx.y], water[idx.z]);
    var out = culled_slice(0.0);
    let s = cut_volume(c, tri, vec3<f32>(0.0, 0.0, -1.0), 0.0);
    if !s.ok {
        return out;
    }
    let k = vi % 3u;
    let size = vec2<f32>(c.dims.zw);
    out.position = pixel_to_clip(s.points[k].xy * size / c.lattice.w, size);
    out.intensity = s.intensity[k];
    out.dir = s.dirs[k];
    return out;
}

@fragment
fn fs_main(in: SliceOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(c.dims.zw);
    let p = vec3<f32>(in.position.xy * c.lattice.w / size, 0.0);
    if !lit(c, shadow, p, FLOOR_BIAS) {
        discard;
    }
    return vec4<f32>(in.intensity * -normalize(in.dir).z, 0.0);
}
