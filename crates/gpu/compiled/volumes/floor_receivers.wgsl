@group(0) @binding(0)
var<uniform> c: package_volumes_common_Volumes;

@fragment
fn fs_main(in: package_volumes_common_SliceOut) -> @location(0) vec4<f32> {
    let size = vec2<f32>(c.dims.zw);
    let q = in.position.xy * c.lattice.w / size;
    let z = package_shaders_receivers__1receiver_height(receiver_heights, r, q);
    let p = vec3<f32>(q - r.t0.xy * (z / -r.t0.z), z);
    if !package_volumes_common_lit(c, shadow, p, package_volumes_common__1FLOOR_BIAS) {
        discard;
    }
    return vec4<f32>(in.intensity, 0.0);
}

@group(0) @binding(5)
var<storage, read> hits: array<vec4<f32>>;

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn package_shaders_receivers__1receiver_height(map: texture_2d<f32>, r: package_shaders_receivers_Receivers, q: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(map));
    let u = (q - r.view.xy) / r.view.z - 0.5;
    let c = floor(u);
    let f = u - c;
    let i = vec2<i32>(c);
    let a = textureLoad(map, clamp(i, vec2<i32>(0), dims - 1), 0).x;
    let b = textureLoad(map, clamp(i + vec2<i32>(1, 0), vec2<i32>(0), dims - 1), 0).x;
    let d = textureLoad(map, clamp(i + vec2<i32>(0, 1), vec2<i32>(0), dims - 1), 0).x;
    let e = textureLoad(map, clamp(i + vec2<i32>(1, 1), vec2<i32>(0), dims - 1), 0).x;
    return mix(mix(a, b, f.x), mix(d, e, f.x), f.y);
}

const package_volumes_common_CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

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

@group(0) @binding(3)
var<uniform> r: package_shaders_receivers_Receivers;

@group(0) @binding(4)
var receiver_heights: texture_2d<f32>;

@group(0) @binding(2)
var shadow: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vi: u32) -> package_volumes_common_SliceOut {
    let cols = c.dims.x;
    let tri_index = vi / 3u;
    let cell = tri_index / 2u;
    let idx = package_volumes_common__1lattice_triangle(c, cell / cols, cell % cols, tri_index % 2u);
    var out = package_volumes_common__1culled_slice(0.0);
    let h = array<vec4<f32>, 3>(hits[idx.x], hits[idx.y], hits[idx.z]);
    if h[0].w == 0.0 || h[1].w == 0.0 || h[2].w == 0.0 {
        return out;
    }
    let s0 = water[idx.x].pos.xyz;
    let l = c.light.xyz;
    let flux = -dot(l, cross(water[idx.y].pos.xyz - s0, water[idx.z].pos.xyz - s0)) / (2.0 * -l.z);
    let e1 = h[1].xy - h[0].xy;
    let e2 = h[2].xy - h[0].xy;
    let area = 0.5 * abs(e1.x * e2.y - e1.y * e2.x);
    if flux <= 0.0 || !(area > 0.0) {
        return out;
    }
    let k = vi % 3u;
    let weight = water[array<u32, 3>(idx.x, idx.y, idx.z)[k]].pos.w;
    let size = vec2<f32>(c.dims.zw);
    out.position = package_volumes_common__2pixel_to_clip(h[k].xy * size / c.lattice.w, size);
    out.intensity = exp(-c.absorption.xyz * h[k].z) * (flux * weight / area);
    return out;
}

@group(0) @binding(1)
var<storage, read> water: array<package_volumes_common_WaterVertex>;
