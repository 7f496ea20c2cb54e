struct VsOut {
    @builtin(position)
    position: vec4<f32>,
    @location(0)
    e: f32,
    @location(1)
    d: f32
}

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

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.e, in.e * in.d, 0.0, 0.0);
}

@group(0) @binding(2)
var<storage, read> irradiance: array<f32>;

const package__1caustic_triangles_common_CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

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

fn package__1caustic_triangles_merge__1quad_draw(qi: u32, qj: u32) -> vec2<f32> {
    if package__1caustic_triangles_merge_u.merge_levels == 0u {
        let k00 = qi * package__1caustic_triangles_merge_u.p + qj;
        let p00 = package__1caustic_triangles_merge_photons[k00];
        let p01 = package__1caustic_triangles_merge_photons[k00 + 1u];
        let p10 = package__1caustic_triangles_merge_photons[k00 + package__1caustic_triangles_merge_u.p];
        let p11 = package__1caustic_triangles_merge_photons[k00 + package__1caustic_triangles_merge_u.p + 1u];
        let ok = p00.z >= 0.0 && p01.z >= 0.0 && p10.z >= 0.0 && p11.z >= 0.0 && p01.w == p00.w && p10.w == p00.w && p11.w == p00.w;
        return vec2<f32>(select(-1.0, 0.0, ok), 0.0);
    }
    let n0 = package__1caustic_triangles_common__1pyr_side(package__1caustic_triangles_merge_u.p, 0u);
    if package__1caustic_triangles_merge_pyramid[qi * n0 + qj].z <= 0.0 {
        return vec2<f32>(-1.0, 0.0);
    }
    var lvl = 0u;
    for (var k = 1u; k <= package__1caustic_triangles_merge_u.merge_levels; k++) {
        let n = package__1caustic_triangles_common__1pyr_side(package__1caustic_triangles_merge_u.p, k);
        let a = qi >> k;
        let b = qj >> k;
        if a >= n || b >= n || package__1caustic_triangles_merge_pyramid[package__1caustic_triangles_common__1pyr_offset(package__1caustic_triangles_merge_u.p, k) + a * n + b].z <= 0.0 {
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
    let n = package__1caustic_triangles_common__1pyr_side(package__1caustic_triangles_merge_u.p, lvl);
    let t = package__1caustic_triangles_merge_pyramid[package__1caustic_triangles_common__1pyr_offset(package__1caustic_triangles_merge_u.p, lvl) + (qi >> lvl) * n + (qj >> lvl)];
    return vec2<f32>(f32(lvl), t.x / t.y);
}

@group(0) @binding(1)
var<storage, read> package__1caustic_triangles_merge_photons: array<vec4<f32>>;

@group(0) @binding(3)
var<storage, read> package__1caustic_triangles_merge_pyramid: array<vec4<f32>>;

@group(0) @binding(0)
var<uniform> package__1caustic_triangles_merge_u: package__1caustic_triangles_common_CausticTriangles;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) face: u32) -> VsOut {
    let quads = package__1caustic_triangles_merge_u.p - 1u;
    let quad = vi / 6u;
    let qi = quad / quads;
    let qj = quad % quads;
    var corners = array<vec2<u32>, 6>(vec2<u32>(0u, 0u), vec2<u32>(0u, 1u), vec2<u32>(1u, 1u), vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(1u, 0u));
    let c = corners[vi % 6u];
    var out: VsOut;
    out.e = 0.0;
    out.d = 0.0;
    out.position = package__1caustic_triangles_common_CULLED;
    let draw = package__1caustic_triangles_merge__1quad_draw(qi, qj);
    if draw.x < 0.0 {
        return out;
    }
    let s = 1u << u32(draw.x);
    let k = (qi + c.x * s) * package__1caustic_triangles_merge_u.p + qj + c.y * s;
    let x = vec3<f32>(package__1caustic_triangles_merge_photons[k].xy, 0.0) - package__1caustic_triangles_merge_u.light.xyz;
    let l = face_local(face, x);
    out.position = vec4<f32>(l.x, -l.y, 0.5 * l.z, l.z);
    out.e = select(irradiance[k], draw.y, draw.x > 0.0);
    out.d = length(x);
    return out;
}
