// Technique `caustic-triangles`, the per-vertex irradiance pass (paper §5: "a separate pass ... at the
// resolution of the photon hit location image ... computes the area of triangles adjacent to a
// single vertex"): E = power / dA, -1 where invalid. Only neighbours with the vertex's path
// signature (w) count. CPU twin: `vertex_irradiance` in
// caustics-core/src/techniques/caustic_triangles/mod.rs, where both area rules are derived.

import package::caustic_triangles::common::{CausticTriangles, tri_area};

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(1) var<storage, read> photons: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> irradiance: array<f32>;

fn photon_at(i: i32, j: i32) -> vec4<f32> {
    let p = i32(u.p);
    if i < 0 || j < 0 || i >= p || j >= p {
        return vec4<f32>(0.0, 0.0, -1.0, 0.0);
    }
    return photons[u32(i * p + j)];
}

fn quad_valid(qi: i32, qj: i32) -> bool {
    let p = i32(u.p);
    if qi < 0 || qj < 0 || qi + 1 >= p || qj + 1 >= p {
        return false;
    }
    let a = photon_at(qi, qj);
    let b = photon_at(qi, qj + 1);
    let c = photon_at(qi + 1, qj);
    let d = photon_at(qi + 1, qj + 1);
    return a.z >= 0.0 && b.z >= 0.0 && c.z >= 0.0 && d.z >= 0.0 && b.w == a.w && c.w == a.w
        && d.w == a.w;
}

// The share of photon (i, j)'s power the hat rule draws: 1 for glass and for a periodic water
// image (an edge vertex's ring reaches across the edge, its twin draws the other side), else 1/2
// per lattice edge the photon lies on (CPU twin: `CausticTrianglesSetup::lattice_share`, where it
// is derived).
fn lattice_share(i: i32, j: i32) -> f32 {
    if u.lattice == 0u || u.periodic != 0u {
        return 1.0;
    }
    let l = i32(u.lattice);
    return select(1.0, 0.5, i == 0 || i == l) * select(1.0, 0.5, j == 0 || j == l);
}

fn vertex_irradiance(i: i32, j: i32) -> f32 {
    let me = photon_at(i, j);
    if me.z < 0.0 {
        return -1.0;
    }
    let v = me.xy;
    var sum = 0.0;
    var count = 0u;
    if u.area_rule == 0u {
        // Right, up, left, down: consecutive pairs span the four corner triangles.
        var ring = array<vec4<f32>, 4>(photon_at(i, j + 1), photon_at(i + 1, j), photon_at(i, j - 1), photon_at(i - 1, j));
        for (var k = 0u; k < 4u; k++) {
            let a = ring[k];
            let b = ring[(k + 1u) % 4u];
            if a.z >= 0.0 && b.z >= 0.0 && a.w == me.w && b.w == me.w {
                sum += tri_area(v, a.xy, b.xy);
                count += 1u;
            }
        }
        if count == 0u {
            return -1.0;
        }
        return me.z / max(2.0 * sum / f32(count), 1e-30);
    }
    var corners = array<vec2<i32>, 4>(vec2<i32>(0, 0), vec2<i32>(0, 1), vec2<i32>(1, 0), vec2<i32>(1, 1));
    for (var k = 0u; k < 4u; k++) {
        let cc = corners[k];
        var qi = i - cc.x;
        var qj = j - cc.y;
        if u.periodic != 0u {
            // The quads past an edge are those at the opposite edge (areas ignore the shift).
            let l = i32(u.lattice);
            qi = (qi + l) % l;
            qj = (qj + l) % l;
        }
        if !quad_valid(qi, qj) {
            continue;
        }
        let c00 = photon_at(qi, qj).xy;
        let c01 = photon_at(qi, qj + 1).xy;
        let c10 = photon_at(qi + 1, qj).xy;
        let c11 = photon_at(qi + 1, qj + 1).xy;
        // Triangle 1: 00, 01, 11; triangle 2: 00, 11, 10.
        if !(cc.x == 1 && cc.y == 0) {
            sum += tri_area(c00, c01, c11);
            count += 1u;
        }
        if !(cc.x == 0 && cc.y == 1) {
            sum += tri_area(c00, c11, c10);
            count += 1u;
        }
    }
    if count == 0u {
        return -1.0;
    }
    return me.z * lattice_share(i, j) / max(sum / 3.0, 1e-30);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= u.p || id.y >= u.p {
        return;
    }
    irradiance[id.y * u.p + id.x] = vertex_irradiance(i32(id.y), i32(id.x));
}
