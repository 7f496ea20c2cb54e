fn camera_under_water() -> bool {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_WATER) {
        return false;
    }
    let c = package__1final_image__2final_image_inputs_params.camera_position;
    var h = 0.0;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        h = package__1final_image__2final_image_inputs__2water_height_gradient(c.xy).x;
    }
    return package__1final_image__2final_image_receivers_inside(c.xy, package__1final_image__2final_image_inputs_params.water_size) && c.z < package__1final_image__2final_image_inputs_params.water_level + h;
}

fn first_crossing(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32, side: f32) -> f32 {
    let rate = abs(d.z) + package__1final_image__2final_image_inputs__1slope_max * length(d.xy);
    let min_step = package__1final_image__2final_image_inputs_params.water_size / f32(4u * package__1final_image__2final_image_inputs__1SLAB_LATTICE);
    let shortest = max(min_step, (t1 - t0) / f32(package__1final_image__2final_image_inputs__1MARCH_STEPS));
    let longest = max((t1 - t0) / f32(package__1final_image__2final_image_inputs__1EVEN_STEPS), min_step);
    var a = t0;
    var gap = side * water_gap(o, d, a);
    if gap <= 0.0 {
        return t0;
    }
    var hi = t1;
    for (var k = 0u; k < package__1final_image__2final_image_inputs__1MARCH_STEPS + 2u && a < t1; k++) {
        let b = min(a + min(max(gap / rate, shortest), longest), t1);
        let next = side * water_gap(o, d, b);
        if next <= 0.0 {
            hi = b;
            break;
        }
        a = b;
        gap = next;
    }
    var lo = a;
    for (var s = 0u; s < package__1final_image__2final_image_inputs_BISECTIONS; s++) {
        let m = 0.5 * (lo + hi);
        if side * water_gap(o, d, m) > 0.0 {
            lo = m;
        }
        else {
            hi = m;
        }
    }
    return 0.5 * (lo + hi);
}

fn floor_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    return p.z - package__1final_image__2final_image_inputs__1floor_height(p.xy);
}

fn hit_floor(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    if d.z >= 0.0 {
        return vec4<f32>(o, package__1final_image__2final_image_inputs_FAR);
    }
    let t_end = -o.z / d.z;
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN) {
        return vec4<f32>(o + d * t_end, t_end);
    }
    var a = 0.0;
    for (var k = 1u; k <= package__1final_image__2final_image_inputs__1FLOOR_STEPS; k++) {
        let b = t_end * f32(k) / f32(package__1final_image__2final_image_inputs__1FLOOR_STEPS);
        if floor_gap(o, d, b) <= 0.0 {
            var lo = a;
            var hi = b;
            for (var s = 0u; s < package__1final_image__2final_image_inputs_BISECTIONS; s++) {
                let m = 0.5 * (lo + hi);
                if floor_gap(o, d, m) > 0.0 {
                    lo = m;
                }
                else {
                    hi = m;
                }
            }
            let t = 0.5 * (lo + hi);
            return vec4<f32>(o + d * t, t);
        }
        a = b;
    }
    return vec4<f32>(o + d * t_end, t_end);
}

fn hit_water(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    let top = package__1final_image__2final_image_inputs_params.water_level + package__1final_image__2final_image_inputs__1h_max;
    let bottom = package__1final_image__2final_image_inputs_params.water_level - package__1final_image__2final_image_inputs__1h_max;
    if o.z < bottom || d.z >= 0.0 {
        return vec4<f32>(o, -1.0);
    }
    let t0 = max((top - o.z) / d.z, 0.0);
    let t1 = (bottom - o.z) / d.z;
    let t = first_crossing(o, d, t0, t1, 1.0);
    return vec4<f32>(o + d * t, t);
}

fn hit_water_from_below(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    if d.z <= 0.0 {
        return vec4<f32>(o, -1.0);
    }
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        let t = max((package__1final_image__2final_image_inputs_params.water_level - o.z) / d.z, 0.0);
        return vec4<f32>(o + d * t, t);
    }
    let top = package__1final_image__2final_image_inputs_params.water_level + package__1final_image__2final_image_inputs__1h_max;
    let bottom = package__1final_image__2final_image_inputs_params.water_level - package__1final_image__2final_image_inputs__1h_max;
    if o.z > top {
        return vec4<f32>(o, -1.0);
    }
    let t0 = max((bottom - o.z) / d.z, 0.0);
    let t1 = (top - o.z) / d.z;
    let t = first_crossing(o, d, t0, t1, -1.0);
    return vec4<f32>(o + d * t, t);
}

fn leave_water(p: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, t_ray: f32) {
    var n = package__1final_image__2final_image_spread__1water_normal(p.xy);
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_FILTER_WATER) && package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        n = package_shaders_optics__2height_field_normal(package__1final_image__3final_image_rough_water__1water_slopes(p, d).mean);
    }
    let mirrored = package__1final_image__2final_image_spread__1bent_spread(package__1final_image__2final_image_spread_spread, p, d, t_ray, n, true);
    let r = package_shaders_optics__1refract_dir(d, -n, package__1final_image__2final_image_inputs_params.ior);
    var t = 0.0;
    if r.w != 0.0 {
        t = package_shaders_optics__1fresnel_transmittance(dot(d, n), package__1final_image__2final_image_inputs_params.ior, 1.0);
        package__1final_image__2final_image_inputs__1push_ray(p + n * 1e-5, r.xyz, w * t, depth + 1u, false);
    }
    package__1final_image__2final_image_spread__2push_ray_spread(p - n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, true, mirrored);
}

const package__1final_image__2final_image_inputs_BISECTIONS: u32 = 30u;

const package__1final_image__2final_image_inputs_FAR: f32 = 3e38;

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

const package__1final_image__2final_image_inputs__1EVEN_STEPS: u32 = 24u;

const package__1final_image__2final_image_inputs__1FLAG_SURFACE: u32 = 2u;

const package__1final_image__2final_image_inputs__1FLAG_TERRAIN: u32 = 8u;

const package__1final_image__2final_image_inputs__1FLAG_WATER: u32 = 1u;

const package__1final_image__2final_image_inputs__1FLOOR_STEPS: u32 = 64u;

const package__1final_image__2final_image_inputs__1MARCH_STEPS: u32 = 512u;

const package__1final_image__2final_image_inputs__1RAY_STACK: u32 = 16u;

const package__1final_image__2final_image_inputs__1SLAB_LATTICE: u32 = 128u;

fn package__1final_image__2final_image_inputs__1floor_height(p: vec2<f32>) -> f32 {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN) {
        return 0.0;
    }
    return package_shaders_water__1grid_sample(package__1final_image__2final_image_inputs__1terrain_height, p, package__1final_image__2final_image_inputs_params.scene_size, false).x;
}

var<private> package__1final_image__2final_image_inputs__1h_max: f32;

fn package__1final_image__2final_image_inputs__1push_ray(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        package__1final_image__2final_image_inputs_rays[package__1final_image__2final_image_inputs__1ray_count] = package__1final_image__2final_image_inputs_Ray(o, d, weight, depth, under);
        package__1final_image__2final_image_inputs__1ray_count++;
    }
}

var<private> package__1final_image__2final_image_inputs__1ray_count: u32;

var<private> package__1final_image__2final_image_inputs__1slope_max: f32;

@group(2) @binding(0)
var<storage, read> package__1final_image__2final_image_inputs__1slope_moments: array<f32>;

@group(0) @binding(2)
var package__1final_image__2final_image_inputs__1terrain_height: texture_2d<f32>;

@group(0) @binding(1)
var package__1final_image__2final_image_inputs__1water_height: texture_2d<f32>;

const package__1final_image__2final_image_inputs__2FLAG_FILTER_WATER: u32 = 65536u;

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

fn package__1final_image__2final_image_receivers_inside(p: vec2<f32>, size: f32) -> bool {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size;
}

struct package__1final_image__2final_image_spread_Axis {
    o: vec3<f32>,
    d: vec3<f32>
}

struct package__1final_image__2final_image_spread_Spread {
    a: package__1final_image__2final_image_spread_Axis,
    b: package__1final_image__2final_image_spread_Axis
}

fn package__1final_image__2final_image_spread__1bent_axis(x: package__1final_image__2final_image_spread_Axis, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> package__1final_image__2final_image_spread_Axis {
    let v = x.o + x.d * t;
    var dp = v;
    let cos_n = dot(n, d);
    if abs(cos_n) > 1e-9 {
        dp = v - d * (dot(n, v) / cos_n);
    }
    let ra = package__1final_image__2final_image_spread_bend(normalize(d - x.d * 0.5), package__1final_image__2final_image_spread__1water_normal((p - dp * 0.5).xy), reflect_it);
    let rb = package__1final_image__2final_image_spread_bend(normalize(d + x.d * 0.5), package__1final_image__2final_image_spread__1water_normal((p + dp * 0.5).xy), reflect_it);
    var out = package__1final_image__2final_image_spread_Axis(dp, vec3<f32>(0.0));
    if ra.w != 0.0 && rb.w != 0.0 {
        out.d = rb.xyz - ra.xyz;
    }
    return out;
}

fn package__1final_image__2final_image_spread__1bent_spread(s: package__1final_image__2final_image_spread_Spread, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> package__1final_image__2final_image_spread_Spread {
    return package__1final_image__2final_image_spread_Spread(package__1final_image__2final_image_spread__1bent_axis(s.a, p, d, t, n, reflect_it), package__1final_image__2final_image_spread__1bent_axis(s.b, p, d, t, n, reflect_it));
}

var<private> package__1final_image__2final_image_spread__1pending_slot: u32;

var<private> package__1final_image__2final_image_spread__1pending_spread: package__1final_image__2final_image_spread_Spread;

fn package__1final_image__2final_image_spread__1water_normal(q: vec2<f32>) -> vec3<f32> {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return package_shaders_optics__2height_field_normal(package__1final_image__2final_image_inputs__2water_height_gradient(q).yz);
}

fn package__1final_image__2final_image_spread__2push_ray_spread(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool, s: package__1final_image__2final_image_spread_Spread) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        package__1final_image__2final_image_spread__1pending_slot = package__1final_image__2final_image_inputs__1ray_count;
        package__1final_image__2final_image_spread__1pending_spread = s;
    }
    package__1final_image__2final_image_inputs__1push_ray(o, d, weight, depth, under);
}

fn package__1final_image__2final_image_spread_bend(d: vec3<f32>, m: vec3<f32>, reflect_it: bool) -> vec4<f32> {
    if reflect_it {
        return vec4<f32>(reflect(d, m), 1.0);
    }
    return package_shaders_optics__1refract_dir(d, m, 1.0 / package__1final_image__2final_image_inputs_params.ior);
}

var<private> package__1final_image__2final_image_spread_spread: package__1final_image__2final_image_spread_Spread;

struct package__1final_image__3final_image_rough_water_Moments {
    mean: vec2<f32>,
    second: vec3<f32>
}

struct package__1final_image__3final_image_rough_water_SlopeLevels {
    lod: f32,
    k: u32,
    top: bool,
    fine: vec3<u32>,
    coarse: vec3<u32>
}

fn package__1final_image__3final_image_rough_water__1exact_moments(g: vec2<f32>) -> package__1final_image__3final_image_rough_water_Moments {
    return package__1final_image__3final_image_rough_water_Moments(g, vec3<f32>(g.x * g.x, g.y * g.y, g.x * g.y));
}

fn package__1final_image__3final_image_rough_water__1lerp_moments(a: package__1final_image__3final_image_rough_water_Moments, b: package__1final_image__3final_image_rough_water_Moments, t: f32) -> package__1final_image__3final_image_rough_water_Moments {
    return package__1final_image__3final_image_rough_water_Moments(a.mean + (b.mean - a.mean) * t, a.second + (b.second - a.second) * t);
}

fn package__1final_image__3final_image_rough_water__1slope_bilinear(l: vec3<u32>, p: vec2<f32>) -> package__1final_image__3final_image_rough_water_Moments {
    let u = p.x / (package__1final_image__2final_image_inputs_params.water_size / f32(l.y)) - 0.5;
    let v = p.y / (package__1final_image__2final_image_inputs_params.water_size / f32(l.z)) - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    var m = package__1final_image__3final_image_rough_water_Moments(vec2<f32>(0.0), vec3<f32>(0.0));
    for (var di = 0; di < 2; di++) {
        let wy = select(1.0 - fv, fv, di == 1);
        for (var dj = 0; dj < 2; dj++) {
            let wx = select(1.0 - fu, fu, dj == 1);
            let t = package__1final_image__3final_image_rough_water__1slope_fetch(l, i32(i0) + di, i32(j0) + dj);
            m.mean += t.mean * (wx * wy);
            m.second += t.second * (wx * wy);
        }
    }
    return m;
}

fn package__1final_image__3final_image_rough_water__1slope_fetch(l: vec3<u32>, i: i32, j: i32) -> package__1final_image__3final_image_rough_water_Moments {
    let r = i32(l.z);
    let c = i32(l.y);
    var ii = clamp(i, 0, r - 1);
    var jj = clamp(j, 0, c - 1);
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE) {
        ii = ((i % r) + r) % r;
        jj = ((j % c) + c) % c;
    }
    let k = (l.x + u32(ii * c + jj)) * 5u;
    return package__1final_image__3final_image_rough_water_Moments(vec2<f32>(package__1final_image__2final_image_inputs__1slope_moments[k], package__1final_image__2final_image_inputs__1slope_moments[k + 1u]), vec3<f32>(package__1final_image__2final_image_inputs__1slope_moments[k + 2u], package__1final_image__2final_image_inputs__1slope_moments[k + 3u], package__1final_image__2final_image_inputs__1slope_moments[k + 4u]));
}

fn package__1final_image__3final_image_rough_water__1slope_level(k: u32) -> vec3<u32> {
    var l = vec3<u32>(0u, max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u));
    for (var i = 0u; i < k; i++) {
        l = vec3<u32>(l.x + l.y * l.z, (l.y + 1u) / 2u, (l.z + 1u) / 2u);
    }
    return l;
}

fn package__1final_image__3final_image_rough_water__1slope_levels(lod: f32) -> package__1final_image__3final_image_rough_water_SlopeLevels {
    let top = package__1final_image__3final_image_rough_water__2slope_level_count() - 1u;
    let k = min(u32(floor(lod)), top);
    return package__1final_image__3final_image_rough_water_SlopeLevels(lod, k, lod >= f32(top), package__1final_image__3final_image_rough_water__1slope_level(k), package__1final_image__3final_image_rough_water__1slope_level(min(k + 1u, top)));
}

fn package__1final_image__3final_image_rough_water__1slope_texel() -> f32 {
    return package__1final_image__2final_image_inputs_params.water_size / f32(min(max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u)));
}

fn package__1final_image__3final_image_rough_water__1water_gradient(p: vec2<f32>) -> vec2<f32> {
    return package__1final_image__2final_image_inputs__2water_height_gradient(p).yz;
}

fn package__1final_image__3final_image_rough_water__1water_slopes(p: vec3<f32>, d: vec3<f32>) -> package__1final_image__3final_image_rough_water_Moments {
    let width = length(p - package__1final_image__2final_image_inputs_params.camera_position) * package__1final_image__2final_image_inputs_params.slope_spread;
    let len = width / max(abs(d.z), 0.001);
    var along = vec2<f32>(1.0, 0.0);
    if length(d.xy) > 0.0 {
        along = normalize(d.xy);
    }
    let taps = clamp(ceil(len / max(width, 1e-12)), 1.0, f32(package__1final_image__3final_image_rough_water__2MAX_SLOPE_TAPS));
    let side = max(width, len / taps);
    let lod = log2(side / package__1final_image__3final_image_rough_water__1slope_texel());
    if lod <= 0.0 {
        return package__1final_image__3final_image_rough_water__1exact_moments(package__1final_image__3final_image_rough_water__1water_gradient(p.xy));
    }
    var m = package__1final_image__3final_image_rough_water_Moments(vec2<f32>(0.0), vec3<f32>(0.0));
    let levels = package__1final_image__3final_image_rough_water__1slope_levels(lod);
    let n = u32(taps);
    for (var k = 0u; k < n; k++) {
        let offset = ((f32(k) + 0.5) / taps - 0.5) * len;
        let t = package__1final_image__3final_image_rough_water__2slope_at_lod(p.xy + along * offset, levels);
        m.mean += t.mean / taps;
        m.second += t.second / taps;
    }
    return m;
}

const package__1final_image__3final_image_rough_water__2MAX_SLOPE_TAPS: u32 = 16u;

fn package__1final_image__3final_image_rough_water__2slope_at_lod(p: vec2<f32>, l: package__1final_image__3final_image_rough_water_SlopeLevels) -> package__1final_image__3final_image_rough_water_Moments {
    if l.top {
        return package__1final_image__3final_image_rough_water__1slope_bilinear(l.fine, p);
    }
    var below: package__1final_image__3final_image_rough_water_Moments;
    if l.k == 0u {
        below = package__1final_image__3final_image_rough_water__1exact_moments(package__1final_image__3final_image_rough_water__1water_gradient(p));
    }
    else {
        below = package__1final_image__3final_image_rough_water__1slope_bilinear(l.fine, p);
    }
    return package__1final_image__3final_image_rough_water__1lerp_moments(below, package__1final_image__3final_image_rough_water__1slope_bilinear(l.coarse, p), l.lod - f32(l.k));
}

fn package__1final_image__3final_image_rough_water__2slope_level_count() -> u32 {
    var l = vec2<u32>(max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u));
    var n = 1u;
    while l.x > 1u || l.y > 1u {
        l = (l + 1u) / 2u;
        n++;
    }
    return n;
}

fn package_shaders_optics__1fresnel_transmittance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = min(abs(cos_i_in), 1.0);
    let sin_t = n1 / n2 * sqrt(max(1.0 - cos_i * cos_i, 0.0));
    if sin_t >= 1.0 {
        return 0.0;
    }
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 1.0 - 0.5 * (rs * rs + rp * rp);
}

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

fn package_shaders_water__1catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

fn package_shaders_water__1grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

fn package_shaders_water__1grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = package_shaders_water__1catmull_rom(f.x);
    let wv = package_shaders_water__1catmull_rom(f.y);
    let n = vec2<i32>(dims);
    var first = vec2<i32>(base) - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    var h = 0.0;
    var hu = 0.0;
    var hv = 0.0;
    for (var a = 0; a < 4; a++) {
        let row = package_shaders_water__1grid_index(first.y, a, n.y, wrap);
        for (var b = 0; b < 4; b++) {
            let s = textureLoad(tex, vec2<i32>(package_shaders_water__1grid_index(first.x, b, n.x, wrap), row), 0).r;
            h += wu[0][b] * wv[0][a] * s;
            hu += wu[1][b] * wv[0][a] * s;
            hv += wu[0][b] * wv[1][a] * s;
        }
    }
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
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

fn water_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    return p.z - package__1final_image__2final_image_inputs_params.water_level - package__1final_image__2final_image_inputs__2water_height_gradient(p.xy).x;
}
