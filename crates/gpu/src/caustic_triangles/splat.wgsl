// Technique `caustic-triangles`, the splatting baseline (the method of the paper's Fig. 1): each valid
// photon as a square of fixed side (u.w.w texels) holding power / (side^2 texel area); a water
// generator's splats attenuated by exp(-K d) of their own path, at nine offsets for tiling water, the
// lattice's repeated last row and column left out. CPU twin: `splat_pass_with_paths` in
// caustics-core/src/techniques/caustic_triangles/mod.rs.

import package::caustic_triangles::common::{
    CULLED, CausticTriangles, copy_offset, pixel_to_clip, to_pixel,
};

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(1) var<storage, read> photons: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> paths: array<f32>;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) e: vec3<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) copy: u32) -> VsOut {
    let n = vi / 6u;
    let ph = photons[n];
    var corners = array<vec2<f32>, 6>(vec2<f32>(-0.5, -0.5), vec2<f32>(0.5, -0.5), vec2<f32>(0.5, 0.5),
                                      vec2<f32>(-0.5, -0.5), vec2<f32>(0.5, 0.5), vec2<f32>(-0.5, 0.5));
    var out: VsOut;
    out.e = vec3<f32>(0.0);
    out.position = CULLED;
    let repeated = u.lattice > 0u && (n / u.p >= u.lattice || n % u.p >= u.lattice);
    if ph.z < 0.0 || repeated {
        return out;
    }
    let s = u.w.w;
    out.position = pixel_to_clip(u, to_pixel(u, ph.xy + copy_offset(u, copy)) + corners[vi % 6u] * s);
    out.e = ph.z / (s * s * u.floor.w) * exp(-u.absorption.xyz * paths[n]);
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.e, 1.0);
}
