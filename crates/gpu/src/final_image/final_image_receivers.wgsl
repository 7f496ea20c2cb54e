// What a view ray reads where it ends besides the floor map: the eye-space caustics image, the
// objects' ray queries and the pool's walls (CPU twins in caustics-core/src/render/shade.rs and
// march.rs). A module of the final image pass.

import package::final_image::final_image_inputs::{
    FAR, FLAG_EYE_CAUSTICS, caustics_map, has, objects, params, wall_cols, wall_maps,
};
import package::shaders::bvh::bvh_intersect;
import package::shaders::caustics_sampling::wall_sample;

// `EyeSpaceCaustics::sample`: the floor point projected through the camera onto the eye-space
// image, bilinear between the centres of the valid texels around it, renormalised; w = 0 where the
// valid texels' weight is below EYE_SPACE_MIN_WEIGHT (the caller lights the point as under flat
// water).
const EYE_SPACE_MIN_WEIGHT: f32 = 1e-3;

fn sample_eye_space(p: vec3<f32>) -> vec4<f32> {
    let v = p - params.camera_position;
    let z = dot(v, params.camera_forward);
    if z <= 0.0 {
        return vec4<f32>(0.0);
    }
    let dims = vec2<i32>(textureDimensions(caustics_map));
    // camera_right and camera_up carry tan(fov / 2) (and the aspect): divide by their squared length.
    let sx = dot(v, params.camera_right) / dot(params.camera_right, params.camera_right) / z;
    let sy = dot(v, params.camera_up) / dot(params.camera_up, params.camera_up) / z;
    let u = (sx + 1.0) * 0.5 * f32(dims.x) - 0.5;
    let w = (1.0 - sy) * 0.5 * f32(dims.y) - 0.5;
    let x0 = floor(u);
    let y0 = floor(w);
    let f = vec2<f32>(u - x0, w - y0);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var dy = 0; dy < 2; dy++) {
        for (var dx = 0; dx < 2; dx++) {
            let c = vec2<i32>(i32(x0) + dx, i32(y0) + dy);
            if any(c < vec2<i32>(0)) || any(c >= dims) {
                continue;
            }
            let t = textureLoad(caustics_map, c, 0);
            if t.w < 0.0 {
                continue;
            }
            let wx = select(1.0 - f.x, f.x, dx == 1);
            let wy = select(1.0 - f.y, f.y, dy == 1);
            sum += t.rgb * (wx * wy);
            weight += wx * wy;
        }
    }
    if weight < EYE_SPACE_MIN_WEIGHT {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(sum / weight, 1.0);
}

struct ObjectHit {
    t: f32,
    normal: vec3<f32>,
    k: u32,
    found: bool,
}

fn nearest_object(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> ObjectHit {
    var best: ObjectHit;
    best.found = false;
    best.t = t_max;
    for (var k = 0u; k < params.object_count; k++) {
        let h = bvh_intersect(objects[k].root, o, d, best.t, false);
        if h.found {
            best = ObjectHit(h.t, h.normal, k, true);
        }
    }
    return best;
}

// Only diffuse objects cast shadows.
fn occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < params.object_count; k++) {
        if objects[k].glass == 0u && bvh_intersect(objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

// Any object, glass included.
fn occluded_by_any(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < params.object_count; k++) {
        if bvh_intersect(objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

fn inside(p: vec2<f32>, size: f32) -> bool {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size;
}

// Distance along the ray to the wall of the pool square it leaves through.
fn wall_distance(o: vec3<f32>, d: vec3<f32>, size: f32) -> f32 {
    var t = FAR;
    for (var a = 0; a < 2; a++) {
        if d[a] > 0.0 {
            t = min(t, (size - o[a]) / d[a]);
        } else if d[a] < 0.0 {
            t = min(t, -o[a] / d[a]);
        }
    }
    return max(t, 0.0);
}

// `wall_at`: the wall of the pool square nearest to p, as its index in `Wall::ALL`.
fn wall_at(p: vec3<f32>, size: f32) -> u32 {
    let d = array<f32, 4>(p.x, size - p.x, p.y, size - p.y);
    var k = 0u;
    for (var i = 1u; i < 4u; i++) {
        if d[i] < d[k] {
            k = i;
        }
    }
    return k;
}

// `Tracer::wall_light`: the sun's light on wall point p through its wall's map, or the eye-space
// image where p projects (cascaded); none without either; shadowed by the objects.
fn wall_light(p: vec3<f32>, size: f32) -> vec3<f32> {
    let k = wall_at(p, size);
    var eye = vec4<f32>(0.0);
    if wall_cols[k] == 0u {
        if !has(FLAG_EYE_CAUSTICS) {
            return vec3<f32>(0.0);
        }
        eye = sample_eye_space(p);
        if eye.w == 0.0 {
            return vec3<f32>(0.0);
        }
    }
    var along = p.x;
    var normal = vec3<f32>(0.0, 1.0, 0.0);
    switch k {
        case 0u: {
            along = p.y;
            normal = vec3<f32>(1.0, 0.0, 0.0);
        }
        case 1u: {
            along = p.y;
            normal = vec3<f32>(-1.0, 0.0, 0.0);
        }
        case 3u: {
            normal = vec3<f32>(0.0, -1.0, 0.0);
        }
        default: {}
    }
    var c = eye.rgb;
    if wall_cols[k] != 0u {
        c = wall_sample(wall_maps, wall_cols[k], k, along, p.z, params.water_size, params.water_level);
    }
    if occluded(p + normal * 1e-4, -params.sun_water, FAR) {
        return vec3<f32>(0.0);
    }
    let e_h = params.sun_intensity * -params.sun.z;
    return c * (e_h * params.t_flat) * params.light_color;
}
