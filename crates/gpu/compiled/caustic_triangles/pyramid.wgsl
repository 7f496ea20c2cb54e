@group(0) @binding(2)
var<storage, read> irradiance: array<f32>;

@group(0) @binding(4)
var<uniform> level: vec4<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level.x;
    let n = package__1caustic_triangles_common__1pyr_side(u.p, k);
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
    let area = package__1caustic_triangles_common__1tri_area(p00.xy, p01.xy, p11.xy) + package__1caustic_triangles_common__1tri_area(p00.xy, p11.xy, p10.xy);
    if k == 0u {
        let ok = p00.z >= 0.0 && p01.z >= 0.0 && p10.z >= 0.0 && p11.z >= 0.0 && p01.w == p00.w && p10.w == p00.w && p11.w == p00.w;
        if !ok {
            pyramid[a * n + b] = vec4<f32>(0.0);
            return;
        }
        let e00 = irradiance[k00];
        let e01 = irradiance[k00 + 1u];
        let e11 = irradiance[k00 + u.p + 1u];
        let e10 = irradiance[k00 + u.p];
        let a1 = package__1caustic_triangles_common__1tri_area(p00.xy, p01.xy, p11.xy);
        let a2 = package__1caustic_triangles_common__1tri_area(p00.xy, p11.xy, p10.xy);
        let phi = a1 * (e00 + e01 + e11) / 3.0 + a2 * (e00 + e11 + e10) / 3.0;
        pyramid[a * n + b] = vec4<f32>(phi, a1 + a2, 1.0, p00.w);
        return;
    }
    let m = package__1caustic_triangles_common__1pyr_side(u.p, k - 1u);
    let base = package__1caustic_triangles_common__1pyr_offset(u.p, k - 1u);
    let c0 = pyramid[base + (2u * a) * m + 2u * b];
    let c1 = pyramid[base + (2u * a) * m + 2u * b + 1u];
    let c2 = pyramid[base + (2u * a + 1u) * m + 2u * b];
    let c3 = pyramid[base + (2u * a + 1u) * m + 2u * b + 1u];
    let phi = c0.x + c1.x + c2.x + c3.x;
    let uniform_path = c0.z > 0.0 && c1.z > 0.0 && c2.z > 0.0 && c3.z > 0.0 && c1.w == c0.w && c2.w == c0.w && c3.w == c0.w;
    let merged = uniform_path && area > 0.0 && area < u.merge_small;
    pyramid[package__1caustic_triangles_common__1pyr_offset(u.p, k) + a * n + b] = vec4<f32>(phi, area, select(0.0, 1.0, merged), c0.w);
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

fn package__1caustic_triangles_common__1tri_area(a: vec2<f32>, b: vec2<f32>, c: vec2<f32>) -> f32 {
    let e = b - a;
    let f = c - a;
    return 0.5 * abs(e.x * f.y - e.y * f.x);
}

@group(0) @binding(1)
var<storage, read> photons: array<vec4<f32>>;

@group(0) @binding(3)
var<storage, read_write> pyramid: array<vec4<f32>>;

@group(0) @binding(0)
var<uniform> u: package__1caustic_triangles_common_CausticTriangles;
