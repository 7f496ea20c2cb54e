@group(0) @binding(0)
var<uniform> c: package_volumes_common_Volumes;

@fragment
fn fs_main(in: package_volumes_common_SliceOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(c.dims.zw);
    let p = vec3<f32>(in.position.xy * c.lattice.w / size, 0.0);
    if !package_volumes_common_lit(c, shadow, p, package_volumes_common__1FLOOR_BIAS) {
        discard;
    }
    return vec4<f32>(in.intensity * -normalize(in.dir).z, 0.0);
}

const package_volumes_common_CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

struct package_volumes_common_Slice {
    ok: bool,
    points: array<vec3<f32>, 3>,
    intensity: array<vec3<f32>, 3>,
    dirs: array<vec3<f32>, 3>
}

struct package_volumes_common_SliceOut {
    @builtin(position)
    position: vec4<f32>,
    @location(0)
    intensity: vec3<f32>,
    @location(1)
    dir: vec3<f32>,
    @location(2) @interpolate(flat)
    plane: f32
}

struct package_volumes_common_View {
    a: vec4<f32>,
    b: vec4<f32>,
    v: vec4<f32>,
    lo: vec4<f32>,
    texel: vec4<f32>
}

struct package_volumes_common_Volumes {
    light: vec4<f32>,
    absorption: vec4<f32>,
    lattice: vec4<f32>,
    params: vec4<f32>,
    dims: vec4<u32>,
    flags: vec4<u32>,
    shadow: package_volumes_common_View
}

struct package_volumes_common_WaterVertex {
    pos: vec4<f32>,
    dir: vec4<f32>
}

const package_volumes_common__1FLOOR_BIAS: f32 = -1e30;

fn package_volumes_common__1culled_slice(plane: f32) -> package_volumes_common_SliceOut {
    return package_volumes_common_SliceOut(package_volumes_common_CULLED, vec3<f32>(0.0), vec3<f32>(0.0), plane);
}

fn package_volumes_common__1cut_volume(c: package_volumes_common_Volumes, corners: array<package_volumes_common_WaterVertex, 3>, n: vec3<f32>, plane: f32) -> package_volumes_common_Slice {
    var tri = corners;
    var out: package_volumes_common_Slice;
    out.ok = false;
    if tri[0].pos.w <= 0.0 || tri[1].pos.w <= 0.0 || tri[2].pos.w <= 0.0 {
        return out;
    }
    let l = c.light.xyz;
    let s0 = tri[0].pos.xyz;
    let flux = -dot(l, cross(tri[1].pos.xyz - s0, tri[2].pos.xyz - s0)) / (2.0 * -l.z);
    if flux <= 0.0 {
        return out;
    }
    var path: array<f32, 3>;
    var cos_t: array<f32, 3>;
    for (var k = 0; k < 3; k++) {
        let t = tri[k].dir.xyz;
        cos_t[k] = dot(n, t);
        if cos_t[k] <= 1e-6 {
            return out;
        }
        path[k] = (plane - dot(n, tri[k].pos.xyz)) / cos_t[k];
        if path[k] < 0.0 {
            return out;
        }
        out.points[k] = tri[k].pos.xyz + t * path[k];
        out.dirs[k] = t;
    }
    let area = 0.5 * length(cross(out.points[1] - out.points[0], out.points[2] - out.points[0]));
    if !(area > 0.0) {
        return out;
    }
    for (var k = 0; k < 3; k++) {
        out.intensity[k] = exp(-c.absorption.xyz * path[k]) * (flux * tri[k].pos.w / (area * cos_t[k]));
    }
    out.ok = true;
    return out;
}

fn package_volumes_common__1lattice_triangle(c: package_volumes_common_Volumes, i: u32, j: u32, which: u32) -> vec3<u32> {
    let w = c.dims.x + 1u;
    let v00 = i * w + j;
    let v01 = v00 + 1u;
    let v10 = v00 + w;
    let v11 = v10 + 1u;
    if (i + j) % 2u == 0u {
        if which == 0u {
            return vec3<u32>(v00, v01, v11);
        }
        return vec3<u32>(v00, v11, v10);
    }
    if which == 0u {
        return vec3<u32>(v00, v01, v10);
    }
    return vec3<u32>(v01, v11, v10);
}

fn package_volumes_common__1to_frame(view: package_volumes_common_View, p: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(view.a.xyz, p), dot(view.b.xyz, p), dot(view.v.xyz, p)) - view.lo.xyz;
}

fn package_volumes_common__2pixel_to_clip(px: vec2<f32>, size: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(2.0 * px.x / size.x - 1.0, 1.0 - 2.0 * px.y / size.y, 0.0, 1.0);
}

fn package_volumes_common_covered(t: vec4<f32>) -> bool {
    return t.y != 0.0 || t.z != 0.0 || t.w != 0.0;
}

fn package_volumes_common_lit(c: package_volumes_common_Volumes, shadow: texture_2d<f32>, p: vec3<f32>, bias: f32) -> bool {
    if c.flags.y == 0u {
        return true;
    }
    let q = package_volumes_common__1to_frame(c.shadow, p);
    let px = q.xy / c.shadow.texel.xy;
    let res = c.shadow.a.w;
    if !(px.x >= 0.0 && px.y >= 0.0 && px.x < res && px.y < res) {
        return true;
    }
    let t = textureLoad(shadow, vec2<i32>(floor(px)), 0);
    if !package_volumes_common_covered(t) {
        return true;
    }
    return t.x >= q.z - bias;
}

@group(0) @binding(2)
var shadow: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> package_volumes_common_SliceOut {
    let cols = c.dims.x;
    let tri_index = vi / 3u;
    let cell = tri_index / 2u;
    let idx = package_volumes_common__1lattice_triangle(c, cell / cols, cell % cols, tri_index % 2u);
    let tri = array<package_volumes_common_WaterVertex, 3>(water[idx.x], water[idx.y], water[idx.z]);
    var out = package_volumes_common__1culled_slice(0.0);
    let s = package_volumes_common__1cut_volume(c, tri, vec3<f32>(0.0, 0.0, -1.0), 0.0);
    if !s.ok {
        return out;
    }
    let k = vi % 3u;
    let size = vec2<f32>(c.dims.zw);
    out.position = package_volumes_common__2pixel_to_clip(s.points[k].xy * size / c.lattice.w, size);
    out.intensity = s.intensity[k];
    out.dir = s.dirs[k];
    return out;
}

@group(0) @binding(1)
var<storage, read> water: array<package_volumes_common_WaterVertex>;
