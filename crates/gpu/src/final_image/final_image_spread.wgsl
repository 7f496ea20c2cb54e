// The final image's ray differentials: the GPU twin of caustics-core/src/render/spread.rs. A module
// of the final image pass.

import package::final_image::final_image_inputs::{
    FLAG_SURFACE, RAY_STACK, has, params, push_ray, ray_count, water_height_gradient,
};
import package::shaders::optics::{height_field_normal, refract_dir};

// One image axis of render.rs `Spread`: how the rays half a sample spacing either side of a
// sample's ray differ from each other, in origin and in direction.
struct Axis {
    o: vec3<f32>,
    d: vec3<f32>,
}

// render.rs `Spread` (secant ray differentials), carried along a sample's first path: its
// primary ray, that ray's refraction, and the surface's mirror image of either from below.
struct Spread {
    a: Axis,
    b: Axis,
}

// The spread of the ray `trace` or `trace_under` is tracing (none: zero), and the one waiting on
// the stack with the ray in slot `pending_slot` (NO_SLOT: none). At most one ray on the stack has
// one: a path that carries a spread pushes one successor with it, and it is the next popped but
// for a ray of the air through Snell's window, which carries none.
var<private> spread: Spread;
var<private> pending_spread: Spread;
var<private> pending_slot: u32;
const NO_SLOT: u32 = 0xffffffffu;

fn no_spread() -> Spread {
    let zero = Axis(vec3<f32>(0.0), vec3<f32>(0.0));
    return Spread(zero, zero);
}

// `push_ray` of a ray carrying spread `s`.
fn push_ray_spread(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool, s: Spread) {
    if ray_count < RAY_STACK {
        pending_slot = ray_count;
        pending_spread = s;
    }
    push_ray(o, d, weight, depth, under);
}

// `Camera::ray`: the primary ray through image point (x + 0.5, y + 0.5), y down the image.
fn camera_ray(x: f32, y: f32) -> vec3<f32> {
    let sx = 2.0 * (x + 0.5) / f32(params.width) - 1.0;
    let sy = 1.0 - 2.0 * (y + 0.5) / f32(params.height);
    return normalize(params.camera_forward + params.camera_right * sx + params.camera_up * sy);
}

// `Spread::of_camera`.
fn camera_spread(x: f32, y: f32, h: f32) -> Spread {
    let zero = vec3<f32>(0.0);
    return Spread(
        Axis(zero, camera_ray(x + 0.5 * h, y) - camera_ray(x - 0.5 * h, y)),
        Axis(zero, camera_ray(x, y + 0.5 * h) - camera_ray(x, y - 0.5 * h)),
    );
}

// `Spread::on_plane`, one axis.
fn on_plane(x: Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec2<f32> {
    return on_plane3(x, d, t, m).xy;
}

// `Spread::on_plane3`, one axis.
fn on_plane3(x: Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec3<f32> {
    let cos_m = dot(m, d);
    var v = x.o + x.d * t;
    if abs(cos_m) > 1e-9 {
        v = v - d * (dot(m, v) / cos_m);
    }
    return v;
}

// The water's normal at `q` (up; flat without a surface).
fn water_normal(q: vec2<f32>) -> vec3<f32> {
    if !has(FLAG_SURFACE) {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return height_field_normal(water_height_gradient(q).yz);
}

// A neighbour's direction `d` bent at a facet of normal `m`: refracted into the water from above
// (`reflect_it` false), or reflected back down from below; w = 0 where it does not refract.
fn bend(d: vec3<f32>, m: vec3<f32>, reflect_it: bool) -> vec4<f32> {
    if reflect_it {
        return vec4<f32>(reflect(d, m), 1.0);
    }
    return refract_dir(d, m, 1.0 / params.ior);
}

// `Spread::bent`, one axis.
fn bent_axis(x: Axis, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> Axis {
    let v = x.o + x.d * t;
    var dp = v;
    let cos_n = dot(n, d);
    if abs(cos_n) > 1e-9 {
        dp = v - d * (dot(n, v) / cos_n);
    }
    let ra = bend(normalize(d - x.d * 0.5), water_normal((p - dp * 0.5).xy), reflect_it);
    let rb = bend(normalize(d + x.d * 0.5), water_normal((p + dp * 0.5).xy), reflect_it);
    var out = Axis(dp, vec3<f32>(0.0));
    if ra.w != 0.0 && rb.w != 0.0 {
        out.d = rb.xyz - ra.xyz;
    }
    return out;
}

fn bent_spread(s: Spread, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> Spread {
    return Spread(bent_axis(s.a, p, d, t, n, reflect_it), bent_axis(s.b, p, d, t, n, reflect_it));
}
