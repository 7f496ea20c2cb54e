// Technique `caustic-triangles`, the caustic triangles (paper §4.2, Fig. 6): 2 (P-1)^2 triangles
// sent with no vertex buffer; the vertex shader pulls its photon hit and vertex irradiance from the
// photon image, collapses the triangles of quads with an invalid corner or corners of different
// path signatures (photon w) outside the clip volume,
// and the irradiance is Gouraud shaded and added into the floor map. CPU twin: `triangles_pass` in
// caustics-core/src/techniques/caustic_triangles/mod.rs.

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(1) var<storage, read> photons: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> irradiance: array<f32>;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) e: f32,
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> VsOut {
    let quads = u.p - 1u;
    let quad = vi / 6u;
    let qi = quad / quads;
    let qj = quad % quads;
    // Triangle 1: 00, 01, 11; triangle 2: 00, 11, 10 (row offset, column offset).
    var corners = array<vec2<u32>, 6>(vec2<u32>(0u, 0u), vec2<u32>(0u, 1u), vec2<u32>(1u, 1u),
                                      vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(1u, 0u));
    let c = corners[vi % 6u];
    var out: VsOut;
    out.e = 0.0;
    out.position = CULLED;
    let draw = quad_draw(qi, qj);
    if draw.x < 0.0 {
        return out;
    }
    let s = 1u << u32(draw.x);
    let k = (qi + c.x * s) * u.p + qj + c.y * s;
    out.position = pixel_to_clip(u, to_pixel(u, photons[k].xy));
    out.e = select(irradiance[k], draw.y, draw.x > 0.0);
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.e, in.e, in.e, 1.0);
}
