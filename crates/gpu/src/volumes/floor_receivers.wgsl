// Technique `volumes`, the floor map over receivers: every illumination volume ends where its
// vertices' rays meet the receivers and is drawn additively in the light's space, each vertex
// carrying the flux over the drawn triangle's area, attenuated along its own path; fragments kept
// where the shadow map lets the sun reach the receiver point under them. The receivers' lookup
// turns it into the floor map. CPU twin: `received_floor_pass` in
// caustics-core/src/techniques/volumes/illumination.rs.

import package::shaders::receivers::{Receivers, receiver_height};
import package::volumes::common::{
    FLOOR_BIAS, SliceOut, Volumes, WaterVertex, culled_slice, lattice_triangle, lit, pixel_to_clip,
};

@group(0) @binding(0) var<uniform> c: Volumes;
@group(0) @binding(1) var<storage, read> water: array<WaterVertex>;
@group(0) @binding(2) var shadow: texture_2d<f32>;
@group(0) @binding(3) var<uniform> r: Receivers;
@group(0) @binding(4) var receiver_heights: texture_2d<f32>;
@group(0) @binding(5) var<storage, read> hits: array<vec4<f32>>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> SliceOut {
    let cols = c.dims.x;
    let tri_index = vi / 3u;
    let cell = tri_index / 2u;
    let idx = lattice_triangle(c, cell / cols, cell % cols, tri_index % 2u);
    var out = culled_slice(0.0);
    let h = array<vec4<f32>, 3>(hits[idx.x], hits[idx.y], hits[idx.z]);
    if h[0].w == 0.0 || h[1].w == 0.0 || h[2].w == 0.0 {
        return out;
    }
    let s0 = water[idx.x].pos.xyz;
    let l = c.light.xyz;
    let flux = -dot(l, cross(water[idx.y].pos.xyz - s0, water[idx.z].pos.xyz - s0)) / (2.0 * -l.z);
    let e1 = h[1].xy - h[0].xy;
    let e2 = h[2].xy - h[0].xy;
    let area = 0.5 * abs(e1.x * e2.y - e1.y * e2.x);
    if flux <= 0.0 || !(area > 0.0) {
        return out;
    }
    let k = vi % 3u;
    let weight = water[array<u32, 3>(idx.x, idx.y, idx.z)[k]].pos.w;
    let size = vec2<f32>(c.dims.zw);
    out.position = pixel_to_clip(h[k].xy * size / c.lattice.w, size);
    out.intensity = exp(-c.absorption.xyz * h[k].z) * (flux * weight / area);
    return out;
}

@fragment
fn fs_main(in: SliceOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(c.dims.zw);
    let q = in.position.xy * c.lattice.w / size;
    let z = receiver_height(receiver_heights, r, q);
    let p = vec3<f32>(q - r.t0.xy * (z / -r.t0.z), z);
    if !lit(c, shadow, p, FLOOR_BIAS) {
        discard;
    }
    return vec4<f32>(in.intensity, 0.0);
}
