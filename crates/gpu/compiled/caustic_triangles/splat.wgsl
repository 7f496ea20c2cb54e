struct VsOut {
    @builtin(position)
    position: vec4<f32>,
    @location(0) @interpolate(flat)
    e: vec3<f32>
}

@fragment
fn fs_main(in: VsOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.e, 1.0);
}

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

fn package__1caustic_triangles_common__1copy_offset(c: package__1caustic_triangles_common_CausticTriangles, k: u32) -> vec2<f32> {
    if c.wrap == 0u {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(f32(k % 3u) - 1.0, f32(k / 3u) - 1.0) * c.floor.z;
}

fn package__1caustic_triangles_common__1to_pixel(c: package__1caustic_triangles_common_CausticTriangles, p: vec2<f32>) -> vec2<f32> {
    return (p - c.floor.xy) / c.floor.z * vec2<f32>(f32(c.width), f32(c.height));
}

fn package__1caustic_triangles_common__2pixel_to_clip(c: package__1caustic_triangles_common_CausticTriangles, px: vec2<f32>) -> vec4<f32> {
    let ndc = vec2<f32>(2.0 * px.x / f32(c.width) - 1.0, 1.0 - 2.0 * px.y / f32(c.height));
    return vec4<f32>(ndc, 0.0, 1.0);
}

@group(0) @binding(2)
var<storage, read> paths: array<f32>;

@group(0) @binding(1)
var<storage, read> photons: array<vec4<f32>>;

@group(0) @binding(0)
var<uniform> u: package__1caustic_triangles_common_CausticTriangles;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) copy: u32) -> VsOut {
    let n = vi / 6u;
    let ph = photons[n];
    var corners = array<vec2<f32>, 6>(vec2<f32>(-0.5, -0.5), vec2<f32>(0.5, -0.5), vec2<f32>(0.5, 0.5), vec2<f32>(-0.5, -0.5), vec2<f32>(0.5, 0.5), vec2<f32>(-0.5, 0.5));
    var out: VsOut;
    out.e = vec3<f32>(0.0);
    out.position = package__1caustic_triangles_common_CULLED;
    let repeated = u.lattice > 0u && (n / u.p >= u.lattice || n % u.p >= u.lattice);
    if ph.z < 0.0 || repeated {
        return out;
    }
    let s = u.w.w;
    out.position = package__1caustic_triangles_common__2pixel_to_clip(u, package__1caustic_triangles_common__1to_pixel(u, ph.xy + package__1caustic_triangles_common__1copy_offset(u, copy)) + corners[vi % 6u] * s);
    out.e = ph.z / (s * s * u.floor.w) * exp(-u.absorption.xyz * paths[n]);
    return out;
}
