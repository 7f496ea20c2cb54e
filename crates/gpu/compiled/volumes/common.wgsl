const CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

const FLOOR_BIAS: f32 = -1e30;

struct Pass {
    view: View,
    cells: vec4<u32>,
    planes: u32,
    root_first: u32,
    root_count: u32,
    _pad: u32,
    albedo: vec4<f32>
}

struct Slice {
    ok: bool,
    points: array<vec3<f32>, 3>,
    intensity: array<vec3<f32>, 3>,
    dirs: array<vec3<f32>, 3>
}

struct SliceOut {
    @builtin(position)
    position: vec4<f32>,
    @location(0)
    intensity: vec3<f32>,
    @location(1)
    dir: vec3<f32>,
    @location(2) @interpolate(flat)
    plane: f32
}

struct View {
    a: vec4<f32>,
    b: vec4<f32>,
    v: vec4<f32>,
    lo: vec4<f32>,
    texel: vec4<f32>
}

struct Volumes {
    light: vec4<f32>,
    absorption: vec4<f32>,
    lattice: vec4<f32>,
    params: vec4<f32>,
    dims: vec4<u32>,
    flags: vec4<u32>,
    shadow: View
}

struct WaterVertex {
    pos: vec4<f32>,
    dir: vec4<f32>
}

fn covered(t: vec4<f32>) -> bool {
    return t.y != 0.0 || t.z != 0.0 || t.w != 0.0;
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

fn pixel_to_clip(px: vec2<f32>, size: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(2.0 * px.x / size.x - 1.0, 1.0 - 2.0 * px.y / size.y, 0.0, 1.0);
}

fn texel_point(view: View, i: u32, j: u32, depth: f32) -> vec3<f32> {
    let u = view.lo.x + (f32(j) + 0.5) * view.texel.x;
    let w = view.lo.y + (f32(i) + 0.5) * view.texel.y;
    return view.a.xyz * u + view.b.xyz * w + view.v.xyz * (view.lo.z + depth);
}

fn to_frame(view: View, p: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(view.a.xyz, p), dot(view.b.xyz, p), dot(view.v.xyz, p)) - view.lo.xyz;
}
