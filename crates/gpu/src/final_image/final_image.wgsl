// The final image pass's main module (the uniform and bindings are final_image_inputs.wgsl's): the
// view ray's trace above and under the water, the ray stack's drain and the image loop, the GPU
// twin of caustics-core/src/render/trace.rs and render/mod.rs.

import package::final_image::final_image_inputs::{
    FAR, FLAG_FILTER_WATER, FLAG_OBJECTS, FLAG_SURFACE, FLAG_TERRAIN, FLAG_WATER, MAX_DEPTH, Ray,
    absorbed,
    albedo_at,
    NO_GUIDE, emit, guide, h_max, has, image, is_pool, params, pixel_radiance, ray_count, rays,
    sky_radiance, slab_half_height, slab_slope, slope_max, surface_hits, terrain_height_gradient,
};
import package::final_image::final_image_march::{
    camera_under_water, crossing_gradient, hit_floor, hit_surface, leave_water,
};
import package::final_image::final_image_receivers::{
    inside, nearest_object, wall_distance, wall_light,
};
import package::final_image::final_image_rough_water::rough_water;
import package::final_image::final_image_shade::{shade_above, shade_floor, shade_object, trace_air};
import package::final_image::final_image_spread::{
    NO_SLOT, Spread, bent_spread, camera_ray, camera_spread, no_spread, on_plane, on_plane3,
    pending_slot, pending_spread, push_ray_spread, spread,
};
import package::shaders::caustics_light::pool_wall_at;
import package::shaders::optics::{fresnel_transmittance, height_field_normal, refract_dir};
import package::shaders::shading::tone_map;

// What a ray from above the water meets, `water` its crossing of the surface (`hit_surface`). The
// ray it refracts down into the water is returned (`under` set, `spread` its own) for the same step
// of `radiance` to trace below, rather than pushed: a driver that runs every branch of a step for
// every pixel (SwiftShader) then runs the step once for the common path, the surface and what lies
// under it, instead of twice. One refracted up a steep wave's face meets the surface from below:
// it is pushed, for the next step's search.
fn trace(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, water: vec4<f32>) -> Ray {
    let none = Ray(o, d, vec3<f32>(0.0), depth, false);
    if !has(FLAG_WATER) {
        trace_air(o, d, depth, w);
        return none;
    }
    let size = params.water_size;
    let hit = water.w >= 0.0;
    if has(FLAG_OBJECTS) {
        let obj = nearest_object(o, d, select(FAR, water.w, hit));
        if obj.found {
            shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
            return none;
        }
    }
    if !hit {
        // A pool is sunk into a deck around it; beyond the terrain's square the world goes on.
        emit(w, shade_above(o, d));
        return none;
    }
    let p = water.xyz;
    if is_pool() && !inside(p.xy, size) {
        emit(w, shade_above(o, d));
        return none;
    }
    var n = height_field_normal(crossing_gradient(p, water.w));
    var t_view: f32;
    if has(FLAG_FILTER_WATER) {
        let rough = rough_water(p, d, &n);
        t_view = rough.w;
        emit(w, rough.xyz);
    } else {
        t_view = fresnel_transmittance(-dot(d, n), 1.0, params.ior);
        emit(w, sky_radiance(reflect(d, n)) * (1.0 - t_view));
    }
    let r = refract_dir(d, n, 1.0 / params.ior);
    if r.w == 0.0 {
        return none;
    }
    spread = bent_spread(spread, p, d, water.w, n, false);
    if r.z > 0.0 {
        push_ray_spread(p, r.xyz, w * t_view, depth, true, spread);
        return none;
    }
    return Ray(p, r.xyz, w * t_view, depth, true);
}

// Radiance arriving along `d` at point `o` under the water, `ceiling` the ray's crossing of the
// surface from below (`hit_surface`; none for a ray going down).
fn trace_under(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, ceiling: vec4<f32>) {
    let size = params.water_size;
    var floor_hit = hit_floor(o, d);
    // A ray going up ends at the surface seen from below instead; the branches below read
    // `floor_hit` as the ray's end, wherever it is.
    if ceiling.w >= 0.0 {
        floor_hit = ceiling;
    }
    let t_floor = floor_hit.w;
    if has(FLAG_OBJECTS) {
        let obj = nearest_object(o, d, t_floor);
        if obj.found {
            shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, true, w * absorbed(obj.t));
            return;
        }
    }
    if is_pool() && !inside(floor_hit.xy, size) {
        // The ray meets a pool wall first: tiles lit by the ambient light, and by the sun through
        // the wall's map where the technique lit the walls.
        let t = wall_distance(o, d, size);
        let p = o + d * t;
        // The wall's tiles filtered over the sample's footprint on the wall's plane.
        let m = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), pool_wall_at(p.xy, size) < 2u);
        let fa = on_plane3(spread.a, d, t, m);
        let fb = on_plane3(spread.b, d, t, m);
        let extent = vec2<f32>(abs(fa.x + fa.y) + abs(fb.x + fb.y), abs(fa.z) + abs(fb.z));
        let a = albedo_at(vec2<f32>(p.x + p.y, p.z), size, extent);
        emit(w * absorbed(t), a * (params.ambient * params.light_color + wall_light(p, size)));
    } else if ceiling.w >= 0.0 {
        leave_water(floor_hit.xyz, d, depth, w * absorbed(t_floor), t_floor);
    } else {
        var m = vec3<f32>(0.0, 0.0, 1.0);
        if has(FLAG_TERRAIN) {
            m = height_field_normal(terrain_height_gradient(floor_hit.xy).yz);
        }
        let fa = on_plane(spread.a, d, t_floor, m);
        let fb = on_plane(spread.b, d, t_floor, m);
        emit(w * absorbed(t_floor), shade_floor(floor_hit.xyz, fa, fb));
    }
}

// Everything a primary ray brings back: `Tracer::trace_from(o, d, 0, under)` unrolled.
fn radiance(o: vec3<f32>, d: vec3<f32>, under: bool, s: Spread) -> vec3<f32> {
    pixel_radiance = vec3<f32>(0.0);
    ray_count = 0u;
    pending_slot = NO_SLOT;
    push_ray_spread(o, d, vec3<f32>(1.0), 0u, under, s);
    while ray_count > 0u {
        ray_count--;
        let r = rays[ray_count];
        spread = no_spread();
        if ray_count == pending_slot {
            spread = pending_spread;
            pending_slot = NO_SLOT;
        }
        if r.depth > MAX_DEPTH {
            continue;
        }
        // The step's one search for the surface: from above for a ray in the air, from below for
        // one in the water; a ray refracted into the water in this step goes down, and meets none.
        var crossing = vec4<f32>(r.o, -1.0);
        if has(FLAG_WATER) {
            crossing = hit_surface(r.o, r.d, r.under);
        }
        var below = r;
        if !r.under {
            below = trace(r.o, r.d, r.depth, r.weight, crossing);
            crossing = vec4<f32>(below.o, -1.0);
        }
        if below.under {
            trace_under(below.o, below.d, below.depth, below.weight, crossing);
        }
    }
    return pixel_radiance;
}

// The rasterised surface's distance at pixel `p`, or the nearest over its 3 x 3 neighbourhood
// (negative: the grid met at none of them).
fn nearest_raster(p: vec2<i32>, around: bool) -> f32 {
    if !around {
        return textureLoad(surface_hits, p, 0).r;
    }
    let last = vec2<i32>(i32(params.width) - 1, i32(params.height) - 1);
    var nearest = FAR;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let t = textureLoad(surface_hits, clamp(p + vec2<i32>(dx, dy), vec2<i32>(0), last), 0).r;
            if t >= 0.0 {
                nearest = min(nearest, t);
            }
        }
    }
    return select(-1.0, nearest, nearest < FAR);
}

// render.rs `sample_offset`: sample (sx, sy) of a pixel's n x n on a rotated grid (n-rooks).
fn sample_offset(sx: u32, sy: u32, n: u32) -> vec2<f32> {
    let m = f32(n);
    return vec2<f32>(
        (f32(sx) + (f32(sy) + 0.5) / m) / m,
        (f32(sy) + (m - 1.0 - f32(sx) + 0.5) / m) / m,
    );
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    h_max = slab_half_height();
    slope_max = slab_slope();
    let under = camera_under_water();
    let n = max(params.supersampling, 1u);
    // Where each sample's search for the surface starts: the rasterised surface's distance along
    // the pixel's central ray, or with several samples, the nearest of those of the pixel and its
    // neighbours, which bound the samples' rays between them.
    var raster = NO_GUIDE;
    if has(FLAG_SURFACE) && !under {
        raster = nearest_raster(vec2<i32>(id.xy), n > 1u);
    }
    var c = vec3<f32>(0.0);
    for (var sy = 0u; sy < n; sy++) {
        for (var sx = 0u; sx < n; sx++) {
            let o = sample_offset(sx, sy, n);
            let x = f32(id.x) + o.x - 0.5;
            let y = f32(id.y) + o.y - 0.5;
            let s = camera_spread(x, y, 1.0 / f32(n));
            guide = raster;
            c += radiance(params.camera_position, camera_ray(x, y), under, s);
        }
    }
    c = c / f32(n * n) * params.exposure;
    textureStore(image, id.xy, vec4<f32>(tone_map(c, params.tone_map), 1.0));
}
