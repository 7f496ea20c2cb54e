struct Axis {
    o: vec3<f32>,
    d: vec3<f32>
}

const NO_SLOT: u32 = 4294967295u;

struct Spread {
    a: Axis,
    b: Axis
}

fn bend(d: vec3<f32>, m: vec3<f32>, reflect_it: bool) -> vec4<f32> {
    if reflect_it {
        return vec4<f32>(reflect(d, m), 1.0);
    }
    return package_shaders_optics__1refract_dir(d, m, 1.0 / package__1final_image__2final_image_inputs_params.ior);
}

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

fn camera_ray(x: f32, y: f32) -> vec3<f32> {
    let sx = 2.0 * (x + 0.5) / f32(package__1final_image__2final_image_inputs_params.width) - 1.0;
    let sy = 1.0 - 2.0 * (y + 0.5) / f32(package__1final_image__2final_image_inputs_params.height);
    return normalize(package__1final_image__2final_image_inputs_params.camera_forward + package__1final_image__2final_image_inputs_params.camera_right * sx + package__1final_image__2final_image_inputs_params.camera_up * sy);
}

fn camera_spread(x: f32, y: f32, h: f32) -> Spread {
    let zero = vec3<f32>(0.0);
    return Spread(Axis(zero, camera_ray(x + 0.5 * h, y) - camera_ray(x - 0.5 * h, y)), Axis(zero, camera_ray(x, y + 0.5 * h) - camera_ray(x, y - 0.5 * h)));
}

fn no_spread() -> Spread {
    let zero = Axis(vec3<f32>(0.0), vec3<f32>(0.0));
    return Spread(zero, zero);
}

fn on_plane(x: Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec2<f32> {
    return on_plane3(x, d, t, m).xy;
}

fn on_plane3(x: Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec3<f32> {
    let cos_m = dot(m, d);
    var v = x.o + x.d * t;
    if abs(cos_m) > 1e-9 {
        v = v - d * (dot(m, v) / cos_m);
    }
    return v;
}

struct package__1final_image__2final_image_inputs_FinalImage {
    camera_position: vec3<f32>,
    exposure: f32,
    camera_forward: vec3<f32>,
    sun_disk: f32,
    camera_right: vec3<f32>,
    water_size: f32,
    camera_up: vec3<f32>,
    water_level: f32,
    sun: vec3<f32>,
    sun_intensity: f32,
    sun_water: vec3<f32>,
    t_flat: f32,
    light_color: vec3<f32>,
    ior: f32,
    absorption: vec3<f32>,
    scene_size: f32,
    map_size: f32,
    width: u32,
    height: u32,
    supersampling: u32,
    object_count: u32,
    flags: u32,
    albedo: u32,
    tone_map: u32,
    ambient: vec3<f32>,
    sun_cos_radius: f32,
    sky: array<vec4<f32>, 6>,
    slope_spread: f32,
    sun_variance: f32,
    slope_cols: u32,
    slope_rows: u32
}

struct package__1final_image__2final_image_inputs_Ray {
    o: vec3<f32>,
    d: vec3<f32>,
    weight: vec3<f32>,
    depth: u32,
    under: bool
}

const package__1final_image__2final_image_inputs__1FLAG_SURFACE: u32 = 2u;

const package__1final_image__2final_image_inputs__1RAY_STACK: u32 = 16u;

fn package__1final_image__2final_image_inputs__1push_ray(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        package__1final_image__2final_image_inputs_rays[package__1final_image__2final_image_inputs__1ray_count] = package__1final_image__2final_image_inputs_Ray(o, d, weight, depth, under);
        package__1final_image__2final_image_inputs__1ray_count++;
    }
}

var<private> package__1final_image__2final_image_inputs__1ray_count: u32;

@group(0) @binding(1)
var package__1final_image__2final_image_inputs__1water_height: texture_2d<f32>;

const package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE: u32 = 16u;

fn package__1final_image__2final_image_inputs__2water_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return package_shaders_water__2grid_sample_hermite(package__1final_image__2final_image_inputs__1water_height, p, package__1final_image__2final_image_inputs_params.water_size, package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE));
}

fn package__1final_image__2final_image_inputs_has(flag: u32) -> bool {
    return (package__1final_image__2final_image_inputs_params.flags & flag) != 0u;
}

@group(0) @binding(0)
var<uniform> package__1final_image__2final_image_inputs_params: package__1final_image__2final_image_inputs_FinalImage;

var<private> package__1final_image__2final_image_inputs_rays: array<package__1final_image__2final_image_inputs_Ray, package__1final_image__2final_image_inputs__1RAY_STACK>;

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
}

fn package_shaders_water__2grid_sample_hermite(patches: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(patches));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let n = vec2<i32>(dims);
    var c0 = vec2<i32>(base);
    var c1 = c0 + 1;
    var keep = vec4<f32>(1.0);
    if wrap {
        c0 = ((c0 % n) + n) % n;
        c1 = select(c0 + 1, c0 + 1 - n, c0 + 1 >= n);
    }
    else {
        keep = vec4<f32>(select(0.0, 1.0, c0.x >= 0 && c0.x < n.x), select(0.0, 1.0, c0.y >= 0 && c0.y < n.y), select(0.0, 1.0, c1.x >= 0 && c1.x < n.x), select(0.0, 1.0, c1.y >= 0 && c1.y < n.y));
        c0 = clamp(c0, vec2<i32>(0), n - 1);
        c1 = clamp(c1, vec2<i32>(0), n - 1);
    }
    let k00 = vec4<f32>(1.0, keep.x, keep.y, keep.x * keep.y);
    let k10 = vec4<f32>(1.0, keep.z, keep.y, keep.z * keep.y);
    let k01 = vec4<f32>(1.0, keep.x, keep.w, keep.x * keep.w);
    let k11 = vec4<f32>(1.0, keep.z, keep.w, keep.z * keep.w);
    let p00 = textureLoad(patches, c0, 0) * k00;
    let p10 = textureLoad(patches, vec2<i32>(c1.x, c0.y), 0) * k10;
    let p01 = textureLoad(patches, vec2<i32>(c0.x, c1.y), 0) * k01;
    let p11 = textureLoad(patches, c1, 0) * k11;
    let bu = package_shaders_water_hermite(f.x);
    let bv = package_shaders_water_hermite(f.y);
    let row0 = bu[0].x * vec2<f32>(p00.x, p00.z) + bu[0].y * vec2<f32>(p10.x, p10.z) + bu[0].z * vec2<f32>(p00.y, p00.w) + bu[0].w * vec2<f32>(p10.y, p10.w);
    let row1 = bu[0].x * vec2<f32>(p01.x, p01.z) + bu[0].y * vec2<f32>(p11.x, p11.z) + bu[0].z * vec2<f32>(p01.y, p01.w) + bu[0].w * vec2<f32>(p11.y, p11.w);
    let drow0 = bu[1].x * vec2<f32>(p00.x, p00.z) + bu[1].y * vec2<f32>(p10.x, p10.z) + bu[1].z * vec2<f32>(p00.y, p00.w) + bu[1].w * vec2<f32>(p10.y, p10.w);
    let drow1 = bu[1].x * vec2<f32>(p01.x, p01.z) + bu[1].y * vec2<f32>(p11.x, p11.z) + bu[1].z * vec2<f32>(p01.y, p01.w) + bu[1].w * vec2<f32>(p11.y, p11.w);
    let h = bv[0].x * row0.x + bv[0].y * row1.x + bv[0].z * row0.y + bv[0].w * row1.y;
    let hu = bv[0].x * drow0.x + bv[0].y * drow1.x + bv[0].z * drow0.y + bv[0].w * drow1.y;
    let hv = bv[1].x * row0.x + bv[1].y * row1.x + bv[1].z * row0.y + bv[1].w * row1.y;
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

fn package_shaders_water_hermite(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = vec4<f32>(2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2, t3 - 2.0 * t2 + t, t3 - t2);
    let dw = vec4<f32>(6.0 * t2 - 6.0 * t, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

var<private> pending_slot: u32;

var<private> pending_spread: Spread;

fn push_ray_spread(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool, s: Spread) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        pending_slot = package__1final_image__2final_image_inputs__1ray_count;
        pending_spread = s;
    }
    package__1final_image__2final_image_inputs__1push_ray(o, d, weight, depth, under);
}

var<private> spread: Spread;

fn water_normal(q: vec2<f32>) -> vec3<f32> {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return package_shaders_optics__2height_field_normal(package__1final_image__2final_image_inputs__2water_height_gradient(q).yz);
}
