// Technique `caustic-triangles`, the camera pass (paper §4.3): per pixel, the eye ray against the
// floor plane and every generator's layered distance map; diffuse points lit by the light with the
// light cube map as shadow map and as the source of the caustic irradiance (distance test with the
// relative bias), or for the sun a shadow ray through the distance maps and the floor map; glass
// points shaded by their Fresnel-weighted reflected and refracted rays (traced through the glass in
// its distance map), which end at diffuse points shaded the same way. Linear RGB out.
// CPU twin: caustics-core/src/techniques/caustic_triangles/camera.rs (the model is documented there).

import package::caustic_triangles::common::CausticTriangles;
import package::caustic_triangles::distance_map::{
    dm_info, dm_trace_mode, dmg, face_st, sphere_span,
};
import package::shaders::optics::{fresnel_transmittance, refract_dir};

struct CameraPass {
    position: vec4<f32>,     // xyz: the eye; w: tan(fov_y / 2)
    forward: vec4<f32>,      // w: aspect (width / height)
    right: vec4<f32>,        // w: ambient irradiance
    up: vec4<f32>,           // w: relative bias of the distance tests
    sky: vec4<f32>,          // w: 0 the sun, 1 a point light
    floor_albedo: vec4<f32>, // w: the point light's intensity
    wall_albedo: vec4<f32>,
    light_color: vec4<f32>,
    light: vec4<f32>,        // xyz: sun direction of travel, or the point light; w: spot cos, -2 none
    spot_axis: vec4<f32>,
    floor: vec4<f32>,        // xy: floor map origin; z: its side
    width: u32,
    height: u32,
    generators: u32,
    cube: u32,               // light cube face side
    map_width: u32,
    map_height: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> cam: CameraPass;
@group(0) @binding(2) var<storage, read> gens: array<CausticTriangles>;
@group(0) @binding(3) var<storage, read> shadow: array<f32>;
@group(0) @binding(4) var cube_map: texture_2d<f32>;
@group(0) @binding(5) var floor_map: texture_2d<f32>;
@group(0) @binding(6) var<storage, read_write> image: array<vec4<f32>>;

const EPS: f32 = 1e-4;

struct SceneHit {
    t: f32,
    normal: vec3<f32>,
    glass: bool,
    floor: bool,
    found: bool,
    generator: u32,
}

fn nearest(o: vec3<f32>, d: vec3<f32>, mode: u32) -> SceneHit {
    var best: SceneHit;
    best.found = false;
    best.t = 3.0e38;
    if d.z < 0.0 && o.z > 0.0 {
        best = SceneHit(-o.z / d.z, vec3<f32>(0.0, 0.0, 1.0), false, true, true, 0u);
    }
    for (var g = 0u; g < cam.generators; g++) {
        dmg = dm_info(gens[g], gens[g].dm_base);
        let span = sphere_span(o, d);
        if span.y <= 0.0 || span.x >= best.t {
            continue;
        }
        let h = dm_trace_mode(o + d * span.x, d, 0.0, min(span.y, best.t) - span.x, mode);
        if h.found && span.x + h.d < best.t {
            best = SceneHit(span.x + h.d, h.surface.xyz, h.surface.w > 0.0, false, true, g);
        }
    }
    return best;
}

fn occluded(o: vec3<f32>, d: vec3<f32>) -> bool {
    for (var g = 0u; g < cam.generators; g++) {
        dmg = dm_info(gens[g], gens[g].dm_base);
        let span = sphere_span(o, d);
        if span.y > 0.0 && dm_trace_mode(o + d * span.x, d, 0.0, span.y - span.x, 0u).found {
            return true;
        }
    }
    return false;
}

// The light cube texel nearest to direction d (CPU twin: `LightCube::texel_of`): (col, row in the
// C x 6C target), index in the shadow buffer in z.
fn cube_texel(d: vec3<f32>) -> vec3<u32> {
    let fst = face_st(d);
    let c = f32(cam.cube);
    let col = u32(clamp(i32(floor((fst.y + 1.0) * 0.5 * c)), 0, i32(cam.cube) - 1));
    let row = u32(clamp(i32(floor((fst.z + 1.0) * 0.5 * c)), 0, i32(cam.cube) - 1));
    let y = u32(fst.x) * cam.cube + row;
    return vec3<u32>(col, y, y * cam.cube + col);
}

fn irradiance_at(y: vec3<f32>, n: vec3<f32>, on_floor: bool) -> f32 {
    let b = cam.up.w;
    var e = 0.0;
    if cam.sky.w == 0.0 {
        let l = cam.light.xyz;
        let cos = -dot(n, l);
        if cos > 0.0 && !occluded(y + n * EPS, -l) {
            e += cos / -l.z;
        }
        if on_floor {
            let px = (y.xy - cam.floor.xy) / cam.floor.z * vec2<f32>(f32(cam.map_width), f32(cam.map_height));
            let j = floor(px.x);
            let i = floor(px.y);
            if j >= 0.0 && i >= 0.0 && j < f32(cam.map_width) && i < f32(cam.map_height) {
                e += textureLoad(floor_map, vec2<u32>(u32(j), u32(i)), 0).x;
            }
        }
        return e;
    }
    let v = y - cam.light.xyz;
    let dist = length(v);
    let dir = v / dist;
    let k = cube_texel(dir);
    let cos = -dot(n, dir);
    let in_cone = cam.light.w <= -2.0 || dot(dir, cam.spot_axis.xyz) >= cam.light.w;
    if cos > 0.0 && in_cone && dist <= shadow[k.z] * (1.0 + b) {
        e += cam.floor_albedo.w * cos / (dist * dist);
    }
    let c = textureLoad(cube_map, k.xy, 0);
    if c.x > 0.0 {
        let receiver = c.y / c.x;
        if abs(dist - receiver) <= b * receiver {
            e += c.x;
        }
    }
    return e;
}

fn shade_diffuse(o: vec3<f32>, d: vec3<f32>, h: SceneHit) -> vec3<f32> {
    let y = o + d * h.t;
    var n = h.normal;
    if dot(n, d) > 0.0 {
        n = -n;
    }
    var albedo = cam.wall_albedo.xyz;
    if h.floor {
        albedo = cam.floor_albedo.xyz;
    }
    let e = irradiance_at(y, n, h.floor);
    return albedo * (vec3<f32>(cam.right.w) + cam.light_color.xyz * e);
}

fn secondary(o_in: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let o = o_in + d * EPS;
    let h = nearest(o, d, 2u);
    if !h.found {
        return cam.sky.xyz;
    }
    return shade_diffuse(o, d, h);
}

fn radiance(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let h = nearest(o, d, 0u);
    if !h.found {
        return cam.sky.xyz;
    }
    if !h.glass {
        return shade_diffuse(o, d, h);
    }
    let g = gens[h.generator];
    let ior = g.u.w;
    let p = o + d * h.t;
    let n = h.normal;
    let cos_i = max(-dot(d, n), 0.0);
    let reflected = secondary(p, normalize(reflect(d, n)));
    let t = refract_dir(d, n, 1.0 / ior);
    if t.w == 0.0 {
        return reflected;
    }
    let t_in = fresnel_transmittance(cos_i, 1.0, ior);
    var x = p;
    var r = normalize(t.xyz);
    dmg = dm_info(g, g.dm_base);
    let eps = 1e-4 * dmg.centre.w;
    for (var event = 0u; event < g.depth; event++) {
        let span = sphere_span(x, r);
        if span.y <= 0.0 {
            break;
        }
        let hit = dm_trace_mode(x, r, eps, span.y, 1u);
        if !hit.found || hit.surface.w < 0.0 {
            break;
        }
        x += r * hit.d;
        let n_in = -hit.surface.xyz;
        let cos = -dot(r, n_in);
        let out = refract_dir(r, n_in, ior);
        if out.w != 0.0 {
            let t_out = fresnel_transmittance(cos, ior, 1.0);
            let through = secondary(x, normalize(out.xyz));
            return reflected * (1.0 - t_in) + through * (t_in * t_out);
        }
        r = normalize(reflect(r, n_in));
    }
    return reflected * (1.0 - t_in);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cam.width || id.y >= cam.height {
        return;
    }
    let half = cam.position.w;
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(cam.width) - 1.0) * half * cam.forward.w;
    let sy = (1.0 - 2.0 * (f32(id.y) + 0.5) / f32(cam.height)) * half;
    let d = normalize(cam.forward.xyz + cam.right.xyz * sx + cam.up.xyz * sy);
    image[id.y * cam.width + id.x] = vec4<f32>(radiance(cam.position.xyz, d), 1.0);
}
