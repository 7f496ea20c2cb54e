@group(0) @binding(0)
var<uniform> c: package_volumes_common_Volumes;

@group(0) @binding(3)
var depth: texture_2d<f32>;

@fragment
fn fs_main(in: package_volumes_common_SliceOut) -> @location(0) vec4<f32> {
    let view = obj.view;
    let ij = vec2<u32>(in.position.xy);
    let t = textureLoad(depth, vec2<i32>(ij), 0);
    if !package_volumes_common_covered(t) || abs(t.x - in.plane) > 0.5 * view.v.w {
        discard;
    }
    let cos_n = -dot(normalize(in.dir), t.yzw);
    if cos_n <= 0.0 {
        discard;
    }
    if !package_volumes_common_lit(c, shadow, package_volumes_common__1texel_point(view, ij.y, ij.x, t.x), c.params.z) {
        discard;
    }
    return vec4<f32>(in.intensity * cos_n, 0.0);
}

@group(0) @binding(1)
var<uniform> obj: package_volumes_common_Pass;

const package_volumes_common_CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

struct package_volumes_common_Pass {
    view: package_volumes_common_View,
    cells: vec4<u32>,
    planes: u32,
    root_first: u32,
    root_count: u32,
    _pad: u32,
    albedo: vec4<f32>
}

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

fn package_volumes_common__1texel_point(view: package_volumes_common_View, i: u32, j: u32, depth: f32) -> vec3<f32> {
    let u = view.lo.x + (f32(j) + 0.5) * view.texel.x;
    let w = view.lo.y + (f32(i) + 0.5) * view.texel.y;
    return view.a.xyz * u + view.b.xyz * w + view.v.xyz * (view.lo.z + depth);
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

@group(0) @binding(4)
var shadow: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> package_volumes_common_SliceOut {
    let view = obj.view;
    let cols = obj.cells.w - obj.cells.z;
    let per_plane = 2u * (obj.cells.y - obj.cells.x) * cols;
    let tri_index = vi / 3u;
    let plane = tri_index / per_plane;
    let local = tri_index % per_plane;
    let cell = local / 2u;
    let idx = package_volumes_common__1lattice_triangle(c, obj.cells.x + cell / cols, obj.cells.z + cell % cols, local % 2u);
    let tri = array<package_volumes_common_WaterVertex, 3>(water[idx.x], water[idx.y], water[idx.z]);
    let zk = (f32(plane) + 0.5) * view.v.w;
    var out = package_volumes_common__1culled_slice(zk);
    let s = package_volumes_common__1cut_volume(c, tri, view.v.xyz, view.lo.z + zk);
    if !s.ok {
        return out;
    }
    let k = vi % 3u;
    let res = view.a.w;
    out.position = package_volumes_common__2pixel_to_clip(package_volumes_common__1to_frame(view, s.points[k]).xy / view.texel.xy, vec2<f32>(res));
    out.intensity = s.intensity[k];
    out.dir = s.dirs[k];
    return out;
}

@group(0) @binding(2)
var<storage, read> water: array<package_volumes_common_WaterVertex>;
