struct VsOut {
    @builtin(position)
    position: vec4<f32>,
    @location(0)
    light: vec3<f32>
}

@group(0) @binding(5)
var<storage, read> copy_band: package__1caustic_triangles_common_CopyBand;

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.light, 1.0);
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

struct package__1caustic_triangles_common_CopyBand {
    band: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    draw: array<u32, 4>
}

fn package__1caustic_triangles_common__1copy_offset(c: package__1caustic_triangles_common_CausticTriangles, k: u32) -> vec2<f32> {
    if c.wrap == 0u {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(f32(k % 3u) - 1.0, f32(k / 3u) - 1.0) * c.floor.z;
}

fn package__1caustic_triangles_common__1copy_rect(c: package__1caustic_triangles_common_CausticTriangles, k: u32) -> vec4<u32> {
    let quads = c.p - 1u;
    if c.wrap == 0u {
        return vec4<u32>(0u, quads, 0u, quads);
    }
    let block = 1u << c.merge_levels;
    let band = (c.band + block - 1u) / block * block;
    var r = array<vec2<u32>, 3>(vec2<u32>((quads - min(band, quads)) / block * block, quads), vec2<u32>(0u, quads), vec2<u32>(0u, min(band, quads)));
    let rows = r[k / 3u];
    let cols = r[k % 3u];
    return vec4<u32>(rows.x, rows.y, cols.x, cols.y);
}

fn package__1caustic_triangles_common__1meets_square(c: package__1caustic_triangles_common_CausticTriangles, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    return all(hi >= c.floor.xy) && all(lo <= c.floor.xy + c.floor.z);
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

fn package__1caustic_triangles_common__1to_pixel(c: package__1caustic_triangles_common_CausticTriangles, p: vec2<f32>) -> vec2<f32> {
    return (p - c.floor.xy) / c.floor.z * vec2<f32>(f32(c.width), f32(c.height));
}

fn package__1caustic_triangles_common__1with_band(c: package__1caustic_triangles_common_CausticTriangles, b: package__1caustic_triangles_common_CopyBand) -> package__1caustic_triangles_common_CausticTriangles {
    var n = c;
    n.band = min(c.band, b.band);
    return n;
}

fn package__1caustic_triangles_common__2copy_of_instance(instance: u32) -> u32 {
    if instance == 8u {
        return 4u;
    }
    return instance + select(0u, 1u, instance >= 4u);
}

fn package__1caustic_triangles_common__2pixel_to_clip(c: package__1caustic_triangles_common_CausticTriangles, px: vec2<f32>) -> vec4<f32> {
    let ndc = vec2<f32>(2.0 * px.x / f32(c.width) - 1.0, 1.0 - 2.0 * px.y / f32(c.height));
    return vec4<f32>(ndc, 0.0, 1.0);
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

@group(0) @binding(4)
var<storage, read> paths: array<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) instance: u32) -> VsOut {
    let copy = package__1caustic_triangles_common__2copy_of_instance(instance);
    let r = package__1caustic_triangles_common__1copy_rect(package__1caustic_triangles_common__1with_band(package__1caustic_triangles_merge_u, copy_band), copy);
    let cols = max(r.w - r.z, 1u);
    let quad = vi / 6u;
    let qi = r.x + quad / cols;
    let qj = r.z + quad % cols;
    var corners = array<vec2<u32>, 6>(vec2<u32>(0u, 0u), vec2<u32>(0u, 1u), vec2<u32>(1u, 1u), vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(1u, 0u));
    let c = corners[vi % 6u];
    var out: VsOut;
    out.light = vec3<f32>(0.0);
    out.position = package__1caustic_triangles_common_CULLED;
    if qi >= r.y || qj >= r.w {
        return out;
    }
    let draw = package__1caustic_triangles_merge__1quad_draw(qi, qj);
    if draw.x < 0.0 {
        return out;
    }
    let s = 1u << u32(draw.x);
    let off = package__1caustic_triangles_common__1copy_offset(package__1caustic_triangles_merge_u, copy);
    let k00 = qi * package__1caustic_triangles_merge_u.p + qj;
    let q = array<vec2<f32>, 4>(package__1caustic_triangles_merge_photons[k00].xy, package__1caustic_triangles_merge_photons[k00 + s].xy, package__1caustic_triangles_merge_photons[k00 + s * package__1caustic_triangles_merge_u.p].xy, package__1caustic_triangles_merge_photons[k00 + s * package__1caustic_triangles_merge_u.p + s].xy);
    let lo = min(min(q[0], q[1]), min(q[2], q[3])) + off;
    let hi = max(max(q[0], q[1]), max(q[2], q[3])) + off;
    if !package__1caustic_triangles_common__1meets_square(package__1caustic_triangles_merge_u, lo, hi) {
        return out;
    }
    let k = (qi + c.x * s) * package__1caustic_triangles_merge_u.p + qj + c.y * s;
    out.position = package__1caustic_triangles_common__2pixel_to_clip(package__1caustic_triangles_merge_u, package__1caustic_triangles_common__1to_pixel(package__1caustic_triangles_merge_u, package__1caustic_triangles_merge_photons[k].xy + off));
    let e = select(irradiance[k], draw.y, draw.x > 0.0);
    out.light = e * exp(-package__1caustic_triangles_merge_u.absorption.xyz * paths[k]);
    return out;
}
