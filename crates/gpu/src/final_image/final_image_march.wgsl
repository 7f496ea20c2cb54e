// The view ray's search for the water surface and the floor, and the surface seen from below: the
// GPU twin of caustics-core/src/render/march.rs (and trace.rs's `leave_water`). A module of the
// final image pass.

import package::final_image::final_image_inputs::{
    BISECTIONS, EVEN_STEPS, FAR, FLAG_FILTER_WATER, FLAG_SURFACE, FLAG_TERRAIN, FLAG_WATER,
    FLOOR_STEPS, MARCH_STEPS, NO_GUIDE, ROOT_TOLERANCE, SLAB_LATTICE, floor_height, guide, h_max,
    has, is_pool, params, push_ray, slope_max, water_height_gradient,
};
import package::final_image::final_image_receivers::inside;
import package::final_image::final_image_rough_water::water_slopes;
import package::final_image::final_image_spread::{
    bent_spread, push_ray_spread, spread, water_normal,
};
import package::shaders::optics::{fresnel_transmittance, height_field_normal, refract_dir};
import package::shaders::receivers::{Bracket, chord, narrowed};

// The search's last read of the surface: the distance along the ray it was read at (-1: none
// yet), and the surface's height and gradient there. The search ends on a read at the crossing but
// where its interval was empty, so the normal there is read once, not twice.
var<private> last_read: vec4<f32>;

// Height of the ray above the water surface at distance t.
fn water_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    let h = water_height_gradient(p.xy);
    last_read = vec4<f32>(t, h);
    return p.z - params.water_level - h.x;
}

// The surface's gradient at the point `p` a search for the surface returned at distance `t`.
fn crossing_gradient(p: vec3<f32>, t: f32) -> vec2<f32> {
    if last_read.x == t {
        return last_read.zw;
    }
    return water_height_gradient(p.xy).yz;
}

// The first crossing of the ray with z = level + h(x, y): from above for a ray in the air
// (render.rs `hit_water`), from below for one under the water (`hit_water_from_below`, the rest
// plane without a surface): xyz the point, w the distance (-1: none). One search for both, so that
// the march has one call site: a driver that runs every branch's code for every pixel
// (SwiftShader) would otherwise run a second one for every ray.
fn hit_surface(o: vec3<f32>, d: vec3<f32>, under: bool) -> vec4<f32> {
    let raster = guide;
    guide = NO_GUIDE;
    last_read.x = -1.0;
    let none = vec4<f32>(o, -1.0);
    let top = params.water_level + h_max;
    let bottom = params.water_level - h_max;
    var start = Start(0.0, 0.0, false);
    var t1: f32;
    var side = 1.0;
    if under {
        if d.z <= 0.0 {
            return none;
        }
        if !has(FLAG_SURFACE) {
            let t = max((params.water_level - o.z) / d.z, 0.0);
            return vec4<f32>(o + d * t, t);
        }
        if o.z > top {
            return none;
        }
        start.t = max((bottom - o.z) / d.z, 0.0);
        t1 = (top - o.z) / d.z;
        side = -1.0;
    } else {
        if !has(FLAG_SURFACE) || o.z < bottom || d.z >= 0.0 {
            return none;
        }
        let t0 = max((top - o.z) / d.z, 0.0);
        t1 = (bottom - o.z) / d.z;
        start.t = t0;
        if raster != NO_GUIDE {
            start = guided_start(o, d, t0, t1, raster);
        }
    }
    // `first_crossing` from the start. An empty interval's answer is t1 whatever the gap there (at
    // or below 0: the start is t1; above: the march's end), so it is given without reading the
    // surface.
    var t = start.t;
    if t != t1 {
        var gap = start.gap;
        if !start.known {
            gap = side * water_gap(o, d, t);
        }
        if gap > 0.0 {
            t = crossing_after(o, d, t, gap, t1, side);
        }
    }
    return vec4<f32>(o + d * t, t);
}

// Where a search starts, and the ray's gap to the surface there where it was read on the way.
struct Start {
    t: f32,
    gap: f32,
    known: bool,
}

// Where a primary ray's search for the surface may start, given the distance `raster` along it to
// the rasterised grid, which lies above the surface: there, where the ray entered the slab over the
// water square (so that the march it skips lay over the grid) and is still above the surface (its
// gap there kept for the march); the slab's bottom for a pool's ray that misses the grid and
// crosses the slab wholly on one side of the square (a crossing there is the deck's, as no
// crossing is); else the slab's top, `t0`.
fn guided_start(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32, raster: f32) -> Start {
    let size = params.water_size;
    let a = o.xy + d.xy * t0;
    let top = Start(t0, 0.0, false);
    if raster < 0.0 {
        let b = o.xy + d.xy * t1;
        let outside = (a.x < 0.0 && b.x < 0.0) || (a.y < 0.0 && b.y < 0.0)
            || (a.x > size && b.x > size) || (a.y > size && b.y > size);
        if is_pool() && outside {
            return Start(t1, 0.0, false);
        }
        return top;
    }
    // The rasterised distance is interpolated across the triangle in f32.
    let start = raster * (1.0 - 1e-5);
    if start <= t0 || !inside(a, size) {
        return top;
    }
    let gap = water_gap(o, d, start);
    if gap <= 0.0 {
        return top;
    }
    return Start(start, gap, true);
}

// render.rs `first_crossing`: the first t in [t0, t1] where the ray's signed distance to the
// surface, `side * water_gap` (side 1: from above, -1: from below), reaches 0; -1 for none. Each
// step is that distance over the bound on its rate of change, `|d_z| + slope_max |d_xy|` (no
// step can pass a crossing), at least a quarter of the slab lattice's spacing and 1/MARCH_STEPS
// of the interval, at most 1/EVEN_STEPS of it or the shortest step, whichever is longer (a slab
// of micrometres, flat water's, in one step: 1/24 of it would not move an f32 distance of metres);
// then regula falsi in its Illinois form on the step that crossed, or on what is left of [t0, t1]
// when the march ends without one (the slab's far side lies beyond the surface: only rounding, or
// the steps spent, leave it uncrossed): within a step the gap is nearly linear, so a few guesses
// reach it.
// Here from `t0`, where that distance is already known: `gap0` > 0.
fn crossing_after(o: vec3<f32>, d: vec3<f32>, t0: f32, gap0: f32, t1: f32, side: f32) -> f32 {
    let rate = abs(d.z) + slope_max * length(d.xy);
    let min_step = params.water_size / f32(4u * SLAB_LATTICE);
    let shortest = max(min_step, (t1 - t0) / f32(MARCH_STEPS));
    let longest = max((t1 - t0) / f32(EVEN_STEPS), min_step);
    var a = t0;
    var gap = gap0;
    var hi = t1;
    var g_hi = 1.0;
    var crossed = false;
    // Each step is at least 1/MARCH_STEPS of the interval; two more for rounding.
    for (var k = 0u; k < MARCH_STEPS + 2u && a < t1; k++) {
        let b = min(a + min(max(gap / rate, shortest), longest), t1);
        let next = side * water_gap(o, d, b);
        if next <= 0.0 {
            hi = b;
            g_hi = next;
            crossed = true;
            break;
        }
        a = b;
        gap = next;
    }
    if !crossed {
        g_hi = side * water_gap(o, d, hi);
        if g_hi > 0.0 {
            return hi;
        }
    }
    return regula_falsi(o, d, side, a, gap, hi, g_hi, ROOT_TOLERANCE * min_step);
}

// receivers.rs `regula_falsi` on the ray's gap to the surface between `a` (gap `ga` > 0) and `b`
// (gap `gb` ≤ 0).
fn regula_falsi(o: vec3<f32>, d: vec3<f32>, side: f32, a: f32, ga: f32, b: f32, gb: f32, tol: f32) -> f32 {
    var br = Bracket(a, ga, b, gb, 0);
    var m = b;
    for (var s = 0u; s < BISECTIONS; s++) {
        m = chord(br);
        let gm = side * water_gap(o, d, m);
        br = narrowed(br, m, gm);
        if abs(gm) < tol || br.b - br.a < tol {
            break;
        }
    }
    return m;
}

// render.rs `leave_water` with `from_below`: a ray meeting the surface at `p` from below splits by
// the Fresnel equations from the dense side: out to the air through Snell's window, the rest (all of
// it beyond the window) mirrored back into the water.
fn leave_water(p: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, t_ray: f32) {
    var n = water_normal(p.xy);
    if has(FLAG_FILTER_WATER) && has(FLAG_SURFACE) {
        n = height_field_normal(water_slopes(p, d).mean);
    }
    let mirrored = bent_spread(spread, p, d, t_ray, n, true);
    let r = refract_dir(d, -n, params.ior);
    var t = 0.0;
    if r.w != 0.0 {
        t = fresnel_transmittance(dot(d, n), params.ior, 1.0);
        push_ray(p + n * 1e-5, r.xyz, w * t, depth + 1u, false);
    }
    push_ray_spread(p - n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, true, mirrored);
}

// render.rs `camera_under_water`: inside the water's square and below the surface there.
fn camera_under_water() -> bool {
    if !has(FLAG_WATER) {
        return false;
    }
    let c = params.camera_position;
    var h = 0.0;
    if has(FLAG_SURFACE) {
        h = water_height_gradient(c.xy).x;
    }
    return inside(c.xy, params.water_size) && c.z < params.water_level + h;
}

// Height of the ray above the floor or terrain at distance t.
fn floor_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    return p.z - floor_height(p.xy);
}

// Where an underwater ray meets the floor or terrain: xyz the point, w the distance (FAR, at `o`,
// for a ray going up).
fn hit_floor(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    if d.z >= 0.0 {
        return vec4<f32>(o, FAR);
    }
    let t_end = -o.z / d.z;
    if !has(FLAG_TERRAIN) {
        return vec4<f32>(o + d * t_end, t_end);
    }
    let step = t_end / f32(FLOOR_STEPS);
    var a = 0.0;
    var ga = floor_gap(o, d, 0.0);
    if ga <= 0.0 {
        return vec4<f32>(o, 0.0);
    }
    for (var k = 1u; k <= FLOOR_STEPS; k++) {
        let b = step * f32(k);
        let gb = floor_gap(o, d, b);
        if gb <= 0.0 {
            // Within a step the gap is nearly linear: regula falsi, as for the water.
            var br = Bracket(a, ga, b, gb, 0);
            var m = b;
            for (var s = 0u; s < BISECTIONS; s++) {
                m = chord(br);
                let gm = floor_gap(o, d, m);
                br = narrowed(br, m, gm);
                if abs(gm) < ROOT_TOLERANCE * step || br.b - br.a < ROOT_TOLERANCE * step {
                    break;
                }
            }
            return vec4<f32>(o + d * m, m);
        }
        a = b;
        ga = gb;
    }
    return vec4<f32>(o + d * t_end, t_end);
}
