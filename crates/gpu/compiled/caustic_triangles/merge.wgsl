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

fn package__1caustic_triangles_common__1pyr_offset(p: u32, k: u32) -> u32 {
    var off = 0u;
    for (var j = 0u; j < k; j++) {
        let n = package__1caustic_triangles_common__1pyr_side(p, j);
        off += n * n;
    }
    return off;
}

fn package__1caustic_triangles_common__1pyr_side(p: u32, k: u32) -> u32 {
    return (p - 1u) >> k;
}

@group(0) @binding(1)
var<storage, read> photons: array<vec4<f32>>;

@group(0) @binding(3)
var<storage, read> pyramid: array<vec4<f32>>;

fn quad_draw(qi: u32, qj: u32) -> vec2<f32> {
    if u.merge_levels == 0u {
        let k00 = qi * u.p + qj;
        let p00 = photons[k00];
        let p01 = photons[k00 + 1u];
        let p10 = photons[k00 + u.p];
        let p11 = photons[k00 + u.p + 1u];
        let ok = p00.z >= 0.0 && p01.z >= 0.0 && p10.z >= 0.0 && p11.z >= 0.0 && p01.w == p00.w && p10.w == p00.w && p11.w == p00.w;
        return vec2<f32>(select(-1.0, 0.0, ok), 0.0);
    }
    let n0 = package__1caustic_triangles_common__1pyr_side(u.p, 0u);
    if pyramid[qi * n0 + qj].z <= 0.0 {
        return vec2<f32>(-1.0, 0.0);
    }
    var lvl = 0u;
    for (var k = 1u; k <= u.merge_levels; k++) {
        let n = package__1caustic_triangles_common__1pyr_side(u.p, k);
        let a = qi >> k;
        let b = qj >> k;
        if a >= n || b >= n || pyramid[package__1caustic_triangles_common__1pyr_offset(u.p, k) + a * n + b].z <= 0.0 {
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
    let n = package__1caustic_triangles_common__1pyr_side(u.p, lvl);
    let t = pyramid[package__1caustic_triangles_common__1pyr_offset(u.p, lvl) + (qi >> lvl) * n + (qj >> lvl)];
    return vec2<f32>(f32(lvl), t.x / t.y);
}

@group(0) @binding(0)
var<uniform> u: package__1caustic_triangles_common_CausticTriangles;
