// Technique `caustic-triangles`, the splatting baseline (the method of the paper's Fig. 1): each valid
// photon as a square of fixed side (u.w.w texels) holding power / (side^2 texel area). CPU twin:
// `splat_pass` in caustics-core/src/techniques/caustic_triangles/mod.rs.

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(1) var<storage, read> photons: array<vec4<f32>>;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) e: f32,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> VsOut {
    let ph = photons[vi / 6u];
    var corners = array<vec2<f32>, 6>(vec2<f32>(-0.5, -0.5), vec2<f32>(0.5, -0.5), vec2<f32>(0.5, 0.5),
                                      vec2<f32>(-0.5, -0.5), vec2<f32>(0.5, 0.5), vec2<f32>(-0.5, 0.5));
    var out: VsOut;
    out.e = 0.0;
    out.position = CULLED;
    if ph.z < 0.0 {
        return out;
    }
    let s = u.w.w;
    out.position = pixel_to_clip(u, to_pixel(u, ph.xy) + corners[vi % 6u] * s);
    out.e = ph.z / (s * s * u.floor.w);
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.e, in.e, in.e, 1.0);
}
