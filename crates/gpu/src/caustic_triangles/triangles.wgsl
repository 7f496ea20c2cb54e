// Technique `caustic-triangles`, the caustic triangles (paper §4.2, Fig. 6): 2 (P-1)^2 triangles
// sent with no vertex buffer; the vertex shader pulls its photon hit and vertex irradiance from the
// photon image, collapses the triangles of quads with an invalid corner or corners of different
// path signatures (photon w) outside the clip volume,
// and the irradiance is Gouraud shaded and added into the floor map. A water generator's vertices
// carry their irradiance attenuated by exp(-K d) per channel along their own refracted paths, which
// the triangle interpolates, and tiling water draws each at nine offsets (instances: the shifted ones over the
// quads along the edge their light crosses, `copy_rect`; copies whose quad misses the square are
// collapsed; the band is the narrower of the uniform's and the one `band.wgsl` fitted on the GPU,
// and instances map to copies by `copy_of_instance`). CPU twin: `triangles_pass_with_paths` in
// caustics-core/src/techniques/caustic_triangles/mod.rs.

import package::caustic_triangles::common::{
    CULLED, CopyBand, copy_of_instance, copy_offset, copy_rect, meets_square, pixel_to_clip,
    to_pixel, with_band,
};
import package::caustic_triangles::merge::{photons, quad_draw, u};

@group(0) @binding(2) var<storage, read> irradiance: array<f32>;
@group(0) @binding(4) var<storage, read> paths: array<f32>;
@group(0) @binding(5) var<storage, read> copy_band: CopyBand;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    // The vertex's irradiance, absorbed along its path.
    @location(0) light: vec3<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) instance: u32) -> VsOut {
    // Copy `copy`'s quads, row-major over its rectangle (every quad for the unshifted copy).
    let copy = copy_of_instance(instance);
    let r = copy_rect(with_band(u, copy_band), copy);
    let cols = max(r.w - r.z, 1u);
    let quad = vi / 6u;
    let qi = r.x + quad / cols;
    let qj = r.z + quad % cols;
    // Triangle 1: 00, 01, 11; triangle 2: 00, 11, 10 (row offset, column offset).
    var corners = array<vec2<u32>, 6>(vec2<u32>(0u, 0u), vec2<u32>(0u, 1u), vec2<u32>(1u, 1u),
                                      vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(1u, 0u));
    let c = corners[vi % 6u];
    var out: VsOut;
    out.light = vec3<f32>(0.0);
    out.position = CULLED;
    if qi >= r.y || qj >= r.w {
        return out;
    }
    let draw = quad_draw(qi, qj);
    if draw.x < 0.0 {
        return out;
    }
    let s = 1u << u32(draw.x);
    let off = copy_offset(u, copy);
    let k00 = qi * u.p + qj;
    let q = array<vec2<f32>, 4>(photons[k00].xy, photons[k00 + s].xy, photons[k00 + s * u.p].xy,
                                photons[k00 + s * u.p + s].xy);
    let lo = min(min(q[0], q[1]), min(q[2], q[3])) + off;
    let hi = max(max(q[0], q[1]), max(q[2], q[3])) + off;
    if !meets_square(u, lo, hi) {
        return out;
    }
    let k = (qi + c.x * s) * u.p + qj + c.y * s;
    out.position = pixel_to_clip(u, to_pixel(u, photons[k].xy + off));
    let e = select(irradiance[k], draw.y, draw.x > 0.0);
    out.light = e * exp(-u.absorption.xyz * paths[k]);
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.light, 1.0);
}
