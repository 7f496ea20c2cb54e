// Technique `caustic-triangles`, one level of the merge pyramid (paper §5, hierarchical merging of
// small caustic triangles): level 0 per photon-image quad (power of its two Gouraud triangles, area,
// valid, signature); level k per block of 2^k x 2^k quads (children's power summed, area of its
// corner quad, merged when its children are valid / merged with one signature and the area is below
// u.merge_small). One dispatch per level, lowest first. CPU twin: `merge::pyramid_pass` in
// caustics-core/src/techniques/caustic_triangles/merge.rs.

import package::caustic_triangles::common::{CausticTriangles, pyr_offset, pyr_side, tri_area};

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(1) var<storage, read> photons: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> irradiance: array<f32>;
@group(0) @binding(3) var<storage, read_write> pyramid: array<vec4<f32>>;
@group(0) @binding(4) var<uniform> level: vec4<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level.x;
    let n = pyr_side(u.p, k);
    if id.x >= n || id.y >= n {
        return;
    }
    let a = id.y;
    let b = id.x;
    let s = 1u << k;
    let k00 = (a * s) * u.p + b * s;
    let p00 = photons[k00];
    let p01 = photons[k00 + s];
    let p11 = photons[k00 + s * u.p + s];
    let p10 = photons[k00 + s * u.p];
    let area = tri_area(p00.xy, p01.xy, p11.xy) + tri_area(p00.xy, p11.xy, p10.xy);
    if k == 0u {
        let ok = p00.z >= 0.0 && p01.z >= 0.0 && p10.z >= 0.0 && p11.z >= 0.0 && p01.w == p00.w
            && p10.w == p00.w && p11.w == p00.w;
        if !ok {
            pyramid[a * n + b] = vec4<f32>(0.0);
            return;
        }
        let e00 = irradiance[k00];
        let e01 = irradiance[k00 + 1u];
        let e11 = irradiance[k00 + u.p + 1u];
        let e10 = irradiance[k00 + u.p];
        let a1 = tri_area(p00.xy, p01.xy, p11.xy);
        let a2 = tri_area(p00.xy, p11.xy, p10.xy);
        let phi = a1 * (e00 + e01 + e11) / 3.0 + a2 * (e00 + e11 + e10) / 3.0;
        pyramid[a * n + b] = vec4<f32>(phi, a1 + a2, 1.0, p00.w);
        return;
    }
    let m = pyr_side(u.p, k - 1u);
    let base = pyr_offset(u.p, k - 1u);
    let c0 = pyramid[base + (2u * a) * m + 2u * b];
    let c1 = pyramid[base + (2u * a) * m + 2u * b + 1u];
    let c2 = pyramid[base + (2u * a + 1u) * m + 2u * b];
    let c3 = pyramid[base + (2u * a + 1u) * m + 2u * b + 1u];
    let phi = c0.x + c1.x + c2.x + c3.x;
    let uniform_path = c0.z > 0.0 && c1.z > 0.0 && c2.z > 0.0 && c3.z > 0.0 && c1.w == c0.w
        && c2.w == c0.w && c3.w == c0.w;
    let merged = uniform_path && area > 0.0 && area < u.merge_small;
    pyramid[pyr_offset(u.p, k) + a * n + b] = vec4<f32>(phi, area, select(0.0, 1.0, merged), c0.w);
}
