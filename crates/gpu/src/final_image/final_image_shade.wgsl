// Shading where a view ray ends: the floor, the objects, the deck and the sky, and the open air:
// the GPU twin of caustics-core/src/render/shade.rs (and trace.rs's `trace_air`). A module of
// the final image pass.

import package::final_image::final_image_inputs::{
    FAR, FLAG_AIR_CAUSTICS, FLAG_CAUSTICS, FLAG_EYE_CAUSTICS, FLAG_LIGHT_SPACE, FLAG_WATER,
    FLAG_WRAP_CAUSTICS, absorbed, albedo_at, deck_kind, emit, h_max, has, is_pool, light_deposit,
    light_heights, light_space, objects, params, push_ray, sample_caustics_filtered, sky_radiance,
};
import package::final_image::final_image_receivers::{nearest_object, occluded, sample_eye_space};
import package::final_image::final_image_spread::{on_plane, spread};
import package::shaders::caustics_light::{flat_water_light, sun_through_water};
import package::shaders::caustics_sampling::caustics_bilinear;
import package::shaders::optics::{fresnel_transmittance, refract_dir};
import package::shaders::receivers::{light_space as to_light_space, receiver_share};
import package::shaders::shading::deck_albedo;

// The floor at `p`, its caustics and albedo filtered over the sample's footprint `fa`, `fb`.
fn shade_floor(p: vec3<f32>, fa: vec2<f32>, fb: vec2<f32>) -> vec3<f32> {
    let size = params.water_size;
    let albedo = albedo_at(p.xy, size, abs(fa) + abs(fb));
    let e_h = params.sun_intensity * -params.sun.z;
    let flat = flat_water_light(params.absorption, params.water_level - p.z, -params.sun_water, vec3<f32>(0.0, 0.0, 1.0));
    var relative = flat;
    // Beyond a map that does not tile, the flat water's light, tap by tap (render.rs
    // `shade_floor`).
    if has(FLAG_CAUSTICS) {
        relative = sample_caustics_filtered(p.xy, fa, fb, has(FLAG_WRAP_CAUSTICS), flat, true);
    } else if has(FLAG_EYE_CAUSTICS) {
        let e = sample_eye_space(p);
        if e.w != 0.0 {
            relative = e.rgb;
        }
    }
    var shadow = 1.0;
    if occluded(p + vec3<f32>(0.0, 0.0, 1e-4), -params.sun_water, FAR, false) {
        shadow = 0.0;
    }
    let direct = sun_through_water(relative, e_h, params.t_flat, shadow);
    let ambient = params.ambient * absorbed(params.water_level);
    return albedo * (direct + ambient) * params.light_color;
}

// The light receiver point p with unit normal n takes from the technique's light-space deposit
// (caustics-core's `receivers::light_at`): the deposit at its light-space point times its share
// (none under another receiver nearer the light), attenuated along its flat-water path.
fn deposited_light(p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let r = light_space.receivers;
    let share = receiver_share(light_heights, r, p, n);
    if share <= 0.0 {
        return vec3<f32>(0.0);
    }
    let t0 = r.t0.xyz;
    let q = to_light_space(p, t0);
    let wrap = light_space.absorption.w != 0.0;
    let e = caustics_bilinear(light_deposit, light_deposit, 0u, 0u, q, params.map_size, wrap);
    let path = (params.water_level - p.z) / -t0.z;
    return e * share * exp(-light_space.absorption.xyz * path);
}

fn shade_object(p: vec3<f32>, n_out: vec3<f32>, d: vec3<f32>, k: u32, depth: u32, under: bool, w: vec3<f32>) {
    let obj = objects[k];
    // Closed meshes with outward normals: the ray enters where it meets the outside.
    let entering = dot(n_out, d) < 0.0;
    let n = select(-n_out, n_out, entering);
    if obj.glass == 0u {
        var sun_dir = params.sun;
        if under {
            sun_dir = params.sun_water;
        }
        let lambert = max(dot(n, -sun_dir), 0.0);
        var lit = 0.0;
        if lambert > 0.0 && !occluded(p + n * 1e-4, -sun_dir, FAR, false) {
            lit = 1.0;
        }
        // Under the water, the shading rule's light (shade.rs): the technique's light-space
        // deposit where the object is among its receivers, else flat water's.
        var direct = vec3<f32>(params.sun_intensity * lambert * lit);
        if has(FLAG_WATER) && under {
            let e_h = params.sun_intensity * -params.sun.z;
            if has(FLAG_LIGHT_SPACE) {
                direct = sun_through_water(deposited_light(p, n), e_h, params.t_flat, 1.0);
            } else {
                let flat = flat_water_light(params.absorption, max(params.water_level - p.z, 0.0), -params.sun_water, n);
                direct = sun_through_water(flat, e_h, params.t_flat, lit);
            }
        }
        emit(w, obj.color * (direct + params.ambient) * params.light_color);
        return;
    }
    var outside_ior = 1.0;
    if under {
        outside_ior = params.ior;
    }
    var n1 = outside_ior;
    var n2 = obj.ior;
    if !entering {
        n1 = obj.ior;
        n2 = outside_ior;
    }
    let cos_i = -dot(d, n);
    let t = fresnel_transmittance(cos_i, n1, n2);
    push_ray(p + n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, under);
    let r = refract_dir(d, n, n1 / n2);
    if r.w != 0.0 {
        push_ray(p - n * 1e-5, r.xyz, w * t * obj.color, depth + 1u, under);
    }
}

// Above the water, outside the pool: the deck, or the sky.
fn shade_above(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    if is_pool() && d.z < 0.0 {
        let deck = params.water_level + 0.1 * min(params.water_size, 1.0) + h_max;
        let t = (deck - o.z) / d.z;
        if t > 0.0 {
            let p = o + d * t;
            // render.rs `shade_above`: a sample's footprint on the deck, stretched by the
            // grazing angle; the sample's angle is a pixel's over the samples per side
            // (`sample_spread`), |camera_up| being tan(fov_y / 2).
            let spread = 2.0 * length(params.camera_up) / f32(params.height) / f32(max(params.supersampling, 1u));
            let footprint = length(p - o) * spread / max(abs(d.z), 0.05);
            let albedo = deck_albedo(deck_kind(), p.xy, params.water_size, footprint);
            return albedo * (vec3<f32>(params.sun_intensity * -params.sun.z) + params.ambient) * params.light_color;
        }
    }
    if !is_pool() && d.z < 0.0 {
        // Beyond the surface's slab the open sea: the flat-water Fresnel reflection of the sky.
        let r = fresnel_transmittance(-d.z, 1.0, params.ior);
        return sky_radiance(reflect(d, vec3<f32>(0.0, 0.0, 1.0))) * (1.0 - r);
    }
    return sky_radiance(d);
}

// No water in the scene: objects over the floor plane in open air.
fn trace_air(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>) {
    var t_floor = FAR;
    if d.z < 0.0 {
        t_floor = -o.z / d.z;
    }
    let obj = nearest_object(o, d, t_floor);
    if obj.found {
        shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
        return;
    }
    if t_floor < FAR {
        let p = o + d * t_floor;
        let fa = on_plane(spread.a, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let fb = on_plane(spread.b, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let albedo = albedo_at(p.xy, params.scene_size, abs(fa) + abs(fb));
        let start = p + vec3<f32>(0.0, 0.0, 1e-5);
        var lit = 1.0;
        var caustic = vec3<f32>(0.0);
        if has(FLAG_AIR_CAUSTICS) {
            caustic = sample_caustics_filtered(p.xy, fa, fb, false, vec3<f32>(0.0), false);
            if occluded(start, -params.sun, FAR, true) {
                lit = 0.0;
            }
        } else if occluded(start, -params.sun, FAR, false) {
            lit = 0.0;
        }
        let e = (vec3<f32>(lit) + caustic) * (params.sun_intensity * -params.sun.z) + params.ambient;
        emit(w, albedo * e * params.light_color);
        return;
    }
    emit(w, sky_radiance(d));
}
