// Technique `caustic-triangles`, the caustic triangles drawn onto the light cube map faces (paper
// §4.2): the same two triangles per valid photon-image quad as triangles.wgsl, their floor-hit
// vertices seen from the point light through face `instance_index`'s 90-degree frustum (clip
// position (S, -T, W / 2, W): the near plane is the face's plane through the light, so triangles
// reaching behind it are clipped, not wrapped). Perspective-correct interpolation of E and of the
// distance d to the light is linear interpolation on the floor triangle. Output (E, E d), added.
// CPU twin: `cube_triangles_pass` in caustics-core/src/techniques/caustic_triangles/cube.rs.

import package::caustic_triangles::common::CULLED;
import package::caustic_triangles::merge::{photons, quad_draw, u};

@group(0) @binding(2) var<storage, read> irradiance: array<f32>;

struct VsOut {
    @builtin(position) position: vec4<f32>,
    @location(0) e: f32,
    @location(1) d: f32,
}

// (S, T, W) of d in face `face`'s frame (CPU twin: `cube::face_local`).
fn face_local(face: u32, d: vec3<f32>) -> vec3<f32> {
    let sign = select(-1.0, 1.0, face % 2u == 0u);
    let a = face / 2u;
    if a == 0u {
        return vec3<f32>(d.y, d.z, sign * d.x);
    }
    if a == 1u {
        return vec3<f32>(d.z, d.x, sign * d.y);
    }
    return vec3<f32>(d.x, d.y, sign * d.z);
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) face: u32) -> VsOut {
    let quads = u.p - 1u;
    let quad = vi / 6u;
    let qi = quad / quads;
    let qj = quad % quads;
    var corners = array<vec2<u32>, 6>(vec2<u32>(0u, 0u), vec2<u32>(0u, 1u), vec2<u32>(1u, 1u),
                                      vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(1u, 0u));
    let c = corners[vi % 6u];
    var out: VsOut;
    out.e = 0.0;
    out.d = 0.0;
    out.position = CULLED;
    let draw = quad_draw(qi, qj);
    if draw.x < 0.0 {
        return out;
    }
    let s = 1u << u32(draw.x);
    let k = (qi + c.x * s) * u.p + qj + c.y * s;
    let x = vec3<f32>(photons[k].xy, 0.0) - u.light.xyz;
    let l = face_local(face, x);
    out.position = vec4<f32>(l.x, -l.y, 0.5 * l.z, l.z);
    out.e = select(irradiance[k], draw.y, draw.x > 0.0);
    out.d = length(x);
    return out;
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.e, in.e * in.d, 0.0, 0.0);
}
