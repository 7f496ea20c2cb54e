// Technique `volumes`, the walls' maps: every illumination volume of the water cut by
// one wall's plane and drawn additively into that wall's layer, in its texel space (along, z), the
// viewport the wall's columns by its rows; fragments kept where the shadow map lets the sun through
// (with the objects' depth bias: an object may lie beyond a wall point along t0). The wall is the
// instance index, in `Wall::ALL`'s order (x = 0, x = size, y = 0, y = size). CPU twin: `wall_pass`
// in caustics-core/src/techniques/volumes/illumination.rs, which argues the clip.

import package::volumes::common::{
    CULLED, Volumes, WaterVertex, cut_volume, lattice_triangle, lit, pixel_to_clip,
};

@group(0) @binding(0) var<uniform> c: Volumes;
@group(0) @binding(1) var<storage, read> water: array<WaterVertex>;
@group(0) @binding(2) var shadow: texture_2d<f32>;

struct WallOut {
    @builtin(position) position: vec4<f32>,
    @location(0) intensity: vec3<f32>,
    @location(1) dir: vec3<f32>,
    @location(2) @interpolate(flat) wall: u32,
}

// The side the light travels to through wall k (its outward normal).
fn wall_normal(k: u32) -> vec3<f32> {
    switch k {
        case 0u: { return vec3<f32>(-1.0, 0.0, 0.0); }
        case 1u: { return vec3<f32>(1.0, 0.0, 0.0); }
        case 2u: { return vec3<f32>(0.0, -1.0, 0.0); }
        default: { return vec3<f32>(0.0, 1.0, 0.0); }
    }
}

// Wall k's texel size: (map texels along it per metre, rows per metre of depth).
fn wall_scale(k: u32) -> vec2<f32> {
    let cols = select(f32(c.dims.z), f32(c.dims.w), k < 2u);
    return vec2<f32>(cols / c.lattice.w, f32(c.flags.w) / c.params.x);
}

fn wall_point(k: u32, along: f32, z: f32) -> vec3<f32> {
    let size = c.lattice.w;
    switch k {
        case 0u: { return vec3<f32>(0.0, along, z); }
        case 1u: { return vec3<f32>(size, along, z); }
        case 2u: { return vec3<f32>(along, 0.0, z); }
        default: { return vec3<f32>(along, size, z); }
    }
}

@vertex
fn vs_main(@builtin(vertex_index) vi: u32, @builtin(instance_index) wall: u32) -> WallOut {
    let cols = c.dims.x;
    let tri_index = vi / 3u;
    let cell = tri_index / 2u;
    let idx = lattice_triangle(c, cell / cols, cell % cols, tri_index % 2u);
    let tri = array<WaterVertex, 3>(water[idx.x], water[idx.y], water[idx.z]);
    var out: WallOut;
    out.position = CULLED;
    out.intensity = vec3<f32>(0.0);
    out.dir = vec3<f32>(0.0);
    out.wall = wall;
    let n = wall_normal(wall);
    let plane = select(0.0, c.lattice.w, wall == 1u || wall == 3u);
    let s = cut_volume(c, tri, n, plane);
    let size = c.lattice.w;
    if !s.ok || s.points[0].z < -size || s.points[1].z < -size || s.points[2].z < -size {
        return out;
    }
    let k = vi % 3u;
    let p = s.points[k];
    let along = select(p.x, p.y, wall < 2u);
    let scale = wall_scale(wall);
    let target_size = vec2<f32>(f32(select(c.dims.z, c.dims.w, wall < 2u)), f32(c.flags.w));
    out.position = pixel_to_clip(vec2<f32>(along, p.z) * scale, target_size);
    out.intensity = s.intensity[k];
    out.dir = s.dirs[k];
    return out;
}

@fragment
fn fs_main(in: WallOut) -> @location(0) vec4<f32> {
    let scale = wall_scale(in.wall);
    let uv = in.position.xy / scale;
    let p = wall_point(in.wall, uv.x, uv.y);
    if !lit(c, shadow, p, c.params.z) {
        discard;
    }
    return vec4<f32>(in.intensity * dot(normalize(in.dir), wall_normal(in.wall)), 0.0);
}
