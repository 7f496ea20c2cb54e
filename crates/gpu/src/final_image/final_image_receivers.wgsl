// What a view ray reads where it ends besides the floor map: the eye-space caustics image, the
// objects' ray queries and the pool's walls (CPU twins in caustics-core/src/render/shade.rs and
// march.rs). A module of the final image pass.

import package::final_image::final_image_inputs::{
    FAR, FLAG_EYE_CAUSTICS, FLAG_OBJECTS, caustics_map, has, objects, params, wall_cols, wall_maps,
};
import package::shaders::bvh::bvh_intersect;
import package::shaders::caustics_light::{pool_wall_along, pool_wall_at, sun_through_water};
import package::shaders::caustics_sampling::{eye_space_bilinear, wall_sample};

// `EyeSpaceCaustics::sample`: the floor point projected through the camera onto the eye-space
// image, read as every eye-space reader does (`eye_space_bilinear`); w = 0 where no valid texel is
// near (the caller lights the point as under flat water).
fn sample_eye_space(p: vec3<f32>) -> vec4<f32> {
    let v = p - params.camera_position;
    let z = dot(v, params.camera_forward);
    if z <= 0.0 {
        return vec4<f32>(0.0);
    }
    // camera_right and camera_up carry tan(fov / 2) (and the aspect): divide by their squared length.
    let sx = dot(v, params.camera_right) / dot(params.camera_right, params.camera_right) / z;
    let sy = dot(v, params.camera_up) / dot(params.camera_up, params.camera_up) / z;
    return eye_space_bilinear(caustics_map, vec2<f32>(sx, sy));
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

// Whether an object along the ray casts a shadow: a diffuse one, or any one `with_glass`.
fn occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32, with_glass: bool) -> bool {
    if !has(FLAG_OBJECTS) {
        return false;
    }
    for (var k = 0u; k < params.object_count; k++) {
        let casts = with_glass || objects[k].glass == 0u;
        if casts && bvh_intersect(objects[k].root, o, d, t_max, true).found {
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

// `Tracer::wall_light`: the sun's light on wall point p through its wall's map, or the eye-space
// image where p projects (cascaded); none without either; shadowed by the objects.
fn wall_light(p: vec3<f32>, size: f32) -> vec3<f32> {
    let k = pool_wall_at(p.xy, size);
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
    var c = eye.rgb;
    if wall_cols[k] != 0u {
        c = wall_sample(wall_maps, wall_cols[k], k, pool_wall_along(k, p.xy), p.z, params.water_size, params.water_level);
    }
    // Inward normals, in `pool_wall_at`'s order.
    var normals = array<vec3<f32>, 4>(
        vec3<f32>(1.0, 0.0, 0.0),
        vec3<f32>(-1.0, 0.0, 0.0),
        vec3<f32>(0.0, 1.0, 0.0),
        vec3<f32>(0.0, -1.0, 0.0),
    );
    var shadow = 1.0;
    if occluded(p + normals[k] * 1e-4, -params.sun_water, FAR, false) {
        shadow = 0.0;
    }
    return sun_through_water(c, params.sun_intensity * -params.sun.z, params.t_flat, shadow) * params.light_color;
}
