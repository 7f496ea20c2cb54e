// Technique `caustic-triangles`, what a photon-image quad draws under hierarchical merging (paper
// §5): (level, flat irradiance), level -1 for nothing; level 0 is the quad itself, Gouraud shaded;
// level l > 0 the merged block of 2^l x 2^l quads it is the corner of, flat shaded at power / area.
// Without merging (u.merge_levels == 0) the quad's own validity. CPU twin: `merge::quad_draw`.

import package::caustic_triangles::common::{CausticTriangles, pyr_offset, pyr_side};

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(1) var<storage, read> photons: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> pyramid: array<vec4<f32>>;

fn quad_draw(qi: u32, qj: u32) -> vec2<f32> {
    if u.merge_levels == 0u {
        let k00 = qi * u.p + qj;
        let p00 = photons[k00];
        let p01 = photons[k00 + 1u];
        let p10 = photons[k00 + u.p];
        let p11 = photons[k00 + u.p + 1u];
        let ok = p00.z >= 0.0 && p01.z >= 0.0 && p10.z >= 0.0 && p11.z >= 0.0 && p01.w == p00.w
            && p10.w == p00.w && p11.w == p00.w;
        return vec2<f32>(select(-1.0, 0.0, ok), 0.0);
    }
    let n0 = pyr_side(u.p, 0u);
    if pyramid[qi * n0 + qj].z <= 0.0 {
        return vec2<f32>(-1.0, 0.0);
    }
    var lvl = 0u;
    for (var k = 1u; k <= u.merge_levels; k++) {
        let n = pyr_side(u.p, k);
        let a = qi >> k;
        let b = qj >> k;
        if a >= n || b >= n || pyramid[pyr_offset(u.p, k) + a * n + b].z <= 0.0 {
            break;
        }
        lvl = k;
    }
    if lvl == 0u {
        return vec2<f32>(0.0, 0.0);
    }
    let s = 1u << lvl;
    if qi % s != 0u || qj % s != 0u {
        return vec2<f32>(-1.0, 0.0);
    }
    let n = pyr_side(u.p, lvl);
    let t = pyramid[pyr_offset(u.p, lvl) + (qi >> lvl) * n + (qj >> lvl)];
    return vec2<f32>(f32(lvl), t.x / t.y);
}
