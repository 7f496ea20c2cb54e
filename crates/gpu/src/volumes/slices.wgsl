// Technique `volumes`, the illumination volumes against the reference planes (§3.2, Fig. 4a): one
// triangle per (plane, water triangle of the object's cells), pulled from the water buffer with no
// vertex buffer; the intersection triangle is drawn into the object's caustics map with additive
// blending, and a fragment is kept only where the depth test of §3.1 accepts it (the stored depth
// within Δ/2 of the plane's) and the shadow map lets the sun through. CPU twin: `slice_pass` in
// caustics-core/src/techniques/volumes/illumination.rs.

import package::volumes::common::{
    Pass, SliceOut, Volumes, WaterVertex, covered, culled_slice, cut_volume, lattice_triangle, lit,
    pixel_to_clip, texel_point, to_frame,
};

@group(0) @binding(0) var<uniform> c: Volumes;
@group(0) @binding(1) var<uniform> obj: Pass;
@group(0) @binding(2) var<storage, read> water: array<WaterVertex>;
@group(0) @binding(3) var depth: texture_2d<f32>;
@group(0) @binding(4) var shadow: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> SliceOut {
    let view = obj.view;
    let cols = obj.cells.w - obj.cells.z;
    let per_plane = 2u * (obj.cells.y - obj.cells.x) * cols;
    let tri_index = vi / 3u;
    let plane = tri_index / per_plane;
    let local = tri_index % per_plane;
    let cell = local / 2u;
    let idx = lattice_triangle(c, obj.cells.x + cell / cols, obj.cells.z + cell % cols, local % 2u);
    let tri = array<WaterVertex, 3>(water[idx.x], water[idx.y], water[idx.z]);
    let zk = (f32(plane) + 0.5) * view.v.w;
    var out = culled_slice(zk);
    let s = cut_volume(c, tri, view.v.xyz, view.lo.z + zk);
    if !s.ok {
        return out;
    }
    let k = vi % 3u;
    let res = view.a.w;
    out.position = pixel_to_clip(to_frame(view, s.points[k]).xy / view.texel.xy, vec2<f32>(res));
    out.intensity = s.intensity[k];
    out.dir = s.dirs[k];
    return out;
}

@fragment
fn fs_main(in: SliceOut) -> @location(0) vec4<f32> {
    let view = obj.view;
    let ij = vec2<u32>(in.position.xy);
    let t = textureLoad(depth, vec2<i32>(ij), 0);
    if !covered(t) || abs(t.x - in.plane) > 0.5 * view.v.w {
        discard;
    }
    let cos_n = -dot(normalize(in.dir), t.yzw);
    if cos_n <= 0.0 {
        discard;
    }
    if !lit(c, shadow, texel_point(view, ij.y, ij.x, t.x), c.params.z) {
        discard;
    }
    return vec4<f32>(in.intensity * cos_n, 0.0);
}
