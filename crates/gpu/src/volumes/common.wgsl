// Technique `volumes` (paper 3): the uniform blocks and the math every pass shares. Mirrors
// `VolumesUniform` / `PassUniform` in caustics-gpu/src/volumes/mod.rs and `VolumesSetup`,
// `OrthoView`, `Lattice`, `slice` and `lit` in caustics-core/src/techniques/volumes/.

// An orthographic view (`OrthoView`): frame (a, b, v), box `lo .. lo + extent`, res x res texels.
struct View {
    a: vec4<f32>,       // xyz: a; w: res
    b: vec4<f32>,       // xyz: b; w: how far before the front face depth rays start
    v: vec4<f32>,       // xyz: v (direction of projection); w: plane spacing Δ
    lo: vec4<f32>,      // xyz: lo (frame coordinates of the box's corner)
    texel: vec4<f32>,   // xy: texel size in (u, w); z: box depth
}

struct Volumes {
    light: vec4<f32>,       // xyz: direction the sunlight travels; w: 1 / ior
    absorption: vec4<f32>,  // xyz: K per channel (0 without absorption); w: T(θ0)
    lattice: vec4<f32>,     // xy: origin; z: cell; w: scene size
    params: vec4<f32>,      // x: water depth; y: ior; z: shadow bias; w: 1 with Fresnel
    dims: vec4<u32>,        // x, y: lattice cells; z, w: floor map size
    flags: vec4<u32>,       // x: wrapped surface; y: shadows on; z: walls on; w: wall map rows
    shadow: View,
}

// One object (or the shadow map) for one pass.
struct Pass {
    view: View,
    cells: vec4<u32>,       // i0, i1, j0, j1: the lattice cells drawn
    planes: u32,
    root_first: u32,        // the objects whose trees the depth pass traces
    root_count: u32,
    _pad: u32,
    albedo: vec4<f32>,      // xyz: albedo; w: ambient Ia
}

fn to_frame(view: View, p: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(view.a.xyz, p), dot(view.b.xyz, p), dot(view.v.xyz, p)) - view.lo.xyz;
}

fn texel_point(view: View, i: u32, j: u32, depth: f32) -> vec3<f32> {
    let u = view.lo.x + (f32(j) + 0.5) * view.texel.x;
    let w = view.lo.y + (f32(i) + 0.5) * view.texel.y;
    return view.a.xyz * u + view.b.xyz * w + view.v.xyz * (view.lo.z + depth);
}

fn covered(t: vec4<f32>) -> bool {
    return t.y != 0.0 || t.z != 0.0 || t.w != 0.0;
}

// Whether `p` sees the refracted sun past the objects of the shadow map: no stored surface more
// than `bias` in front of it (FLOOR_BIAS on the floor: any surface over it occludes it).
const FLOOR_BIAS: f32 = -1e30;

fn lit(c: Volumes, shadow: texture_2d<f32>, p: vec3<f32>, bias: f32) -> bool {
    if c.flags.y == 0u {
        return true;
    }
    let q = to_frame(c.shadow, p);
    let px = q.xy / c.shadow.texel.xy;
    let res = c.shadow.a.w;
    if !(px.x >= 0.0 && px.y >= 0.0 && px.x < res && px.y < res) {
        return true;
    }
    let t = textureLoad(shadow, vec2<i32>(floor(px)), 0);
    if !covered(t) {
        return true;
    }
    return t.x >= q.z - bias;
}

// Vertex indices of triangle `which` of lattice cell (i, j): diagonals alternate in a checkerboard.
fn lattice_triangle(c: Volumes, i: u32, j: u32, which: u32) -> vec3<u32> {
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

// One refracted lattice vertex: xyz the surface point, w the Fresnel weight (0: no light);
// dir.xyz the refracted direction.
struct WaterVertex {
    pos: vec4<f32>,
    dir: vec4<f32>,
}

// An illumination volume cut by the plane n · x = c (Eq. 3 at each vertex).
struct Slice {
    ok: bool,
    points: array<vec3<f32>, 3>,
    intensity: array<vec3<f32>, 3>,
    dirs: array<vec3<f32>, 3>,
}

fn cut_volume(c: Volumes, corners: array<WaterVertex, 3>, n: vec3<f32>, plane: f32) -> Slice {
    var tri = corners;
    var out: Slice;
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

// A vertex every rejected primitive collapses to, outside the clip volume.
const CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

// Pixel coordinates of a target of `size` to clip space: row 0 is framebuffer row 0.
fn pixel_to_clip(px: vec2<f32>, size: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(2.0 * px.x / size.x - 1.0, 1.0 - 2.0 * px.y / size.y, 0.0, 1.0);
}

// What the slice and floor vertex shaders hand the rasteriser.
struct SliceOut {
    @builtin(position) position: vec4<f32>,
    @location(0) intensity: vec3<f32>,
    @location(1) dir: vec3<f32>,
    @location(2) @interpolate(flat) plane: f32,
}

// A slice vertex at `plane` that draws nothing until the caller fills it in.
fn culled_slice(plane: f32) -> SliceOut {
    return SliceOut(CULLED, vec3<f32>(0.0), vec3<f32>(0.0), plane);
}
