@group(0) @binding(2)
var<storage, read_write> irradiance: array<f32>;

fn lattice_share(i: i32, j: i32) -> f32 {
    if u.lattice == 0u || u.periodic != 0u {
        return 1.0;
    }
    let l = i32(u.lattice);
    return select(1.0, 0.5, i == 0 || i == l) * select(1.0, 0.5, j == 0 || j == l);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= u.p || id.y >= u.p {
        return;
    }
    irradiance[id.y * u.p + id.x] = vertex_irradiance(i32(id.y), i32(id.x));
}

struct package__1caustic_triangles_common_CausticTriangles {
    centre: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    w: vec4<f32>,
    rect: vec4<f32>,
    floor: vec4<f32>,
    p: u32,
    cube: u32,
    layers: u32,
    depth: u32,
    linear_steps: u32,
    secant_iterations: u32,
    fresnel: u32,
    area_rule: u32,
    width: u32,
    height: u32,
    light_cube: u32,
    dm_base: u32,
    light: vec4<f32>,
    spot: vec4<f32>,
    merge_levels: u32,
    merge_small: f32,
    lattice: u32,
    wrap: u32,
    absorption: vec4<f32>,
    band: u32,
    periodic: u32
}

fn package__1caustic_triangles_common__1tri_area(a: vec2<f32>, b: vec2<f32>, c: vec2<f32>) -> f32 {
    let e = b - a;
    let f = c - a;
    return 0.5 * abs(e.x * f.y - e.y * f.x);
}

fn photon_at(i: i32, j: i32) -> vec4<f32> {
    let p = i32(u.p);
    if i < 0 || j < 0 || i >= p || j >= p {
        return vec4<f32>(0.0, 0.0, -1.0, 0.0);
    }
    return photons[u32(i * p + j)];
}

@group(0) @binding(1)
var<storage, read> photons: array<vec4<f32>>;

fn quad_valid(qi: i32, qj: i32) -> bool {
    let p = i32(u.p);
    if qi < 0 || qj < 0 || qi + 1 >= p || qj + 1 >= p {
        return false;
    }
    let a = photon_at(qi, qj);
    let b = photon_at(qi, qj + 1);
    let c = photon_at(qi + 1, qj);
    let d = photon_at(qi + 1, qj + 1);
    return a.z >= 0.0 && b.z >= 0.0 && c.z >= 0.0 && d.z >= 0.0 && b.w == a.w && c.w == a.w && d.w == a.w;
}

@group(0) @binding(0)
var<uniform> u: package__1caustic_triangles_common_CausticTriangles;

fn vertex_irradiance(i: i32, j: i32) -> f32 {
    let me = photon_at(i, j);
    if me.z < 0.0 {
        return -1.0;
    }
    let v = me.xy;
    var sum = 0.0;
    var count = 0u;
    if u.area_rule == 0u {
        var ring = array<vec4<f32>, 4>(photon_at(i, j + 1), photon_at(i + 1, j), photon_at(i, j - 1), photon_at(i - 1, j));
        for (var k = 0u; k < 4u; k++) {
            let a = ring[k];
            let b = ring[(k + 1u) % 4u];
            if a.z >= 0.0 && b.z >= 0.0 && a.w == me.w && b.w == me.w {
                sum += package__1caustic_triangles_common__1tri_area(v, a.xy, b.xy);
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
        if !(cc.x == 1 && cc.y == 0) {
            sum += package__1caustic_triangles_common__1tri_area(c00, c01, c11);
            count += 1u;
        }
        if !(cc.x == 0 && cc.y == 1) {
            sum += package__1caustic_triangles_common__1tri_area(c00, c11, c10);
            count += 1u;
        }
    }
    if count == 0u {
        return -1.0;
    }
    return me.z * lattice_share(i, j) / max(sum / 3.0, 1e-30);
}
