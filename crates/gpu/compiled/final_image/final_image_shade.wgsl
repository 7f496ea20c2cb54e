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

struct package__1final_image__2final_image_inputs_Object {
    color: vec3<f32>,
    ior: f32,
    root: u32,
    glass: u32,
    _pad: vec2<u32>
}

struct package__1final_image__2final_image_inputs_Ray {
    o: vec3<f32>,
    d: vec3<f32>,
    weight: vec3<f32>,
    depth: u32,
    under: bool
}

const package__1final_image__2final_image_inputs__1DECK_SHIFT: u32 = 8u;

const package__1final_image__2final_image_inputs__1FLAG_CAUSTICS: u32 = 4u;

const package__1final_image__2final_image_inputs__1FLAG_TERRAIN: u32 = 8u;

const package__1final_image__2final_image_inputs__1FLAG_WATER: u32 = 1u;

const package__1final_image__2final_image_inputs__1RAY_STACK: u32 = 16u;

fn package__1final_image__2final_image_inputs__1albedo_at(p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    return package_shaders_shading__1floor_albedo(package__1final_image__2final_image_inputs_params.albedo, package__1final_image__2final_image_inputs__1albedo_image, p, size, extent);
}

@group(0) @binding(4)
var package__1final_image__2final_image_inputs__1albedo_image: texture_2d<f32>;

@group(0) @binding(3)
var package__1final_image__2final_image_inputs__1caustics_map: texture_2d<f32>;

@group(0) @binding(10)
var package__1final_image__2final_image_inputs__1caustics_mips: texture_2d<f32>;

fn package__1final_image__2final_image_inputs__1deck_kind() -> u32 {
    return (package__1final_image__2final_image_inputs_params.flags >> package__1final_image__2final_image_inputs__1DECK_SHIFT) & 255u;
}

var<private> package__1final_image__2final_image_inputs__1h_max: f32;

fn package__1final_image__2final_image_inputs__1is_pool() -> bool {
    return !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN);
}

var<private> package__1final_image__2final_image_inputs__1pixel_radiance: vec3<f32>;

fn package__1final_image__2final_image_inputs__1push_ray(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        package__1final_image__2final_image_inputs_rays[package__1final_image__2final_image_inputs__1ray_count] = package__1final_image__2final_image_inputs_Ray(o, d, weight, depth, under);
        package__1final_image__2final_image_inputs__1ray_count++;
    }
}

var<private> package__1final_image__2final_image_inputs__1ray_count: u32;

fn package__1final_image__2final_image_inputs__1sky_radiance(d: vec3<f32>) -> vec3<f32> {
    var disk = 0.0;
    if dot(d, -package__1final_image__2final_image_inputs_params.sun) >= package__1final_image__2final_image_inputs_params.sun_cos_radius {
        disk = package__1final_image__2final_image_inputs_params.sun_disk;
    }
    return package__1final_image__2final_image_inputs__2sky_without_sun(d) + vec3<f32>(disk * 3.14159265) * package__1final_image__2final_image_inputs__1sun_radiance();
}

fn package__1final_image__2final_image_inputs__1sun_radiance() -> vec3<f32> {
    return package__1final_image__2final_image_inputs_params.light_color * package__1final_image__2final_image_inputs_params.sun_intensity;
}

const package__1final_image__2final_image_inputs__2FLAG_AIR_CAUSTICS: u32 = 64u;

const package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS: u32 = 128u;

const package__1final_image__2final_image_inputs__2FLAG_WRAP_CAUSTICS: u32 = 32u;

fn package__1final_image__2final_image_inputs__2sample_caustics_filtered(p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    return package_shaders__1caustics_sampling__1caustics_filtered(package__1final_image__2final_image_inputs__1caustics_map, package__1final_image__2final_image_inputs__1caustics_mips, 1u, p, fa, fb, package__1final_image__2final_image_inputs_params.map_size, wrap, beyond, has_beyond);
}

fn package__1final_image__2final_image_inputs__2sky_without_sun(d: vec3<f32>) -> vec3<f32> {
    let s = package__1final_image__2final_image_inputs_params.sky;
    let yxy = package_shaders_shading__1perez_sky(d, -package__1final_image__2final_image_inputs_params.sun, s[0].xyz, s[1].xyz, s[2].xyz, s[3].xyz, s[4].xyz, s[5].xyz);
    return package_shaders_shading__2xyy_to_rgb(yxy) * (3.14159265 * package__1final_image__2final_image_inputs__1sun_radiance());
}

fn package__1final_image__2final_image_inputs_absorbed(distance: f32) -> vec3<f32> {
    return exp(-package__1final_image__2final_image_inputs_params.absorption * distance);
}

fn package__1final_image__2final_image_inputs_emit(weight: vec3<f32>, colour: vec3<f32>) {
    package__1final_image__2final_image_inputs__1pixel_radiance += weight * colour;
}

fn package__1final_image__2final_image_inputs_has(flag: u32) -> bool {
    return (package__1final_image__2final_image_inputs_params.flags & flag) != 0u;
}

@group(0) @binding(5)
var<storage, read> package__1final_image__2final_image_inputs_objects: array<package__1final_image__2final_image_inputs_Object>;

@group(0) @binding(0)
var<uniform> package__1final_image__2final_image_inputs_params: package__1final_image__2final_image_inputs_FinalImage;

var<private> package__1final_image__2final_image_inputs_rays: array<package__1final_image__2final_image_inputs_Ray, package__1final_image__2final_image_inputs__1RAY_STACK>;

struct package__1final_image__2final_image_receivers_ObjectHit {
    t: f32,
    normal: vec3<f32>,
    k: u32,
    found: bool
}

fn package__1final_image__2final_image_receivers__1nearest_object(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> package__1final_image__2final_image_receivers_ObjectHit {
    var best: package__1final_image__2final_image_receivers_ObjectHit;
    best.found = false;
    best.t = t_max;
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        let h = package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, best.t, false);
        if h.found {
            best = package__1final_image__2final_image_receivers_ObjectHit(h.t, h.normal, k, true);
        }
    }
    return best;
}

fn package__1final_image__2final_image_receivers__2occluded_by_any(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        if package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

fn package__1final_image__2final_image_receivers__2sample_eye_space(p: vec3<f32>) -> vec4<f32> {
    let v = p - package__1final_image__2final_image_inputs_params.camera_position;
    let z = dot(v, package__1final_image__2final_image_inputs_params.camera_forward);
    if z <= 0.0 {
        return vec4<f32>(0.0);
    }
    let dims = vec2<i32>(textureDimensions(package__1final_image__2final_image_inputs__1caustics_map));
    let sx = dot(v, package__1final_image__2final_image_inputs_params.camera_right) / dot(package__1final_image__2final_image_inputs_params.camera_right, package__1final_image__2final_image_inputs_params.camera_right) / z;
    let sy = dot(v, package__1final_image__2final_image_inputs_params.camera_up) / dot(package__1final_image__2final_image_inputs_params.camera_up, package__1final_image__2final_image_inputs_params.camera_up) / z;
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
            let t = textureLoad(package__1final_image__2final_image_inputs__1caustics_map, c, 0);
            if t.w < 0.0 {
                continue;
            }
            let wx = select(1.0 - f.x, f.x, dx == 1);
            let wy = select(1.0 - f.y, f.y, dy == 1);
            sum += t.rgb * (wx * wy);
            weight += wx * wy;
        }
    }
    if weight < package__1final_image__2final_image_receivers__3EYE_SPACE_MIN_WEIGHT {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(sum / weight, 1.0);
}

const package__1final_image__2final_image_receivers__3EYE_SPACE_MIN_WEIGHT: f32 = 0.001;

fn package__1final_image__2final_image_receivers_occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        if package__1final_image__2final_image_inputs_objects[k].glass == 0u && package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

struct package__1final_image__2final_image_spread_Axis {
    o: vec3<f32>,
    d: vec3<f32>
}

struct package__1final_image__2final_image_spread_Spread {
    a: package__1final_image__2final_image_spread_Axis,
    b: package__1final_image__2final_image_spread_Axis
}

fn package__1final_image__2final_image_spread__1on_plane(x: package__1final_image__2final_image_spread_Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec2<f32> {
    return package__1final_image__2final_image_spread__1on_plane3(x, d, t, m).xy;
}

fn package__1final_image__2final_image_spread__1on_plane3(x: package__1final_image__2final_image_spread_Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec3<f32> {
    let cos_m = dot(m, d);
    var v = x.o + x.d * t;
    if abs(cos_m) > 1e-9 {
        v = v - d * (dot(m, v) / cos_m);
    }
    return v;
}

var<private> package__1final_image__2final_image_spread_spread: package__1final_image__2final_image_spread_Spread;

fn package_shaders__1caustics_sampling__1caustics_bilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(package_shaders__1caustics_sampling__1caustics_dims(map, level));
    let u = p.x / size * dims.x - 0.5;
    let v = p.y / size * dims.y - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    let i = i32(i0);
    let j = i32(j0);
    let a = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i, j, wrap);
    let b = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i, j + 1, wrap);
    let c = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i + 1, j, wrap);
    let d = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i + 1, j + 1, wrap);
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

fn package_shaders__1caustics_sampling__1caustics_dims(map: texture_2d<f32>, level: u32) -> vec2<i32> {
    return vec2<i32>(max(textureDimensions(map) >> vec2<u32>(level), vec2<u32>(1u)));
}

fn package_shaders__1caustics_sampling__1caustics_filtered(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, size: f32, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    let texels = vec2<f32>(textureDimensions(map)) / size;
    let a = fa * texels;
    let b = fb * texels;
    var long = a;
    var la = length(a);
    if length(b) > la {
        long = b;
        la = length(b);
    }
    var across = 0.0;
    if la > 0.0 {
        across = abs(a.x * b.y - a.y * b.x) / la;
    }
    la = max(la, 1.0);
    across = max(across, 1.0);
    let taps = clamp(ceil(la / across), 1.0, package_shaders__1caustics_sampling__2CAUSTICS_MAX_TAPS);
    let width = max(la / taps, across);
    let level = max(log2(width / sqrt(3.0)), 0.0);
    let step = long / texels;
    var sum = vec3<f32>(0.0);
    for (var t = 0.0; t < taps; t += 1.0) {
        let q = p + step * ((t + 0.5) / taps - 0.5);
        let off = q.x < 0.0 || q.y < 0.0 || q.x > size || q.y > size;
        if has_beyond && !wrap && off {
            sum += beyond;
        }
        else {
            sum += package_shaders__1caustics_sampling__1caustics_trilinear(map, mips, mips_from, q, level, size, wrap);
        }
    }
    return sum / taps;
}

fn package_shaders__1caustics_sampling__1caustics_texel(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, i: i32, j: i32, wrap: bool) -> vec3<f32> {
    let dims = package_shaders__1caustics_sampling__1caustics_dims(map, level);
    var c = vec2<i32>(j, i);
    if wrap {
        c = ((c % dims) + dims) % dims;
    }
    else {
        c = clamp(c, vec2<i32>(0), dims - 1);
    }
    if level == 0u {
        return textureLoad(map, c, 0).rgb;
    }
    return textureLoad(mips, c, level - mips_from).rgb;
}

fn package_shaders__1caustics_sampling__1caustics_trilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, p: vec2<f32>, level: f32, size: f32, wrap: bool) -> vec3<f32> {
    let dims = textureDimensions(map);
    let last = firstLeadingBit(max(max(dims.x, dims.y), 1u));
    let l0 = min(u32(floor(level)), last);
    var f = level - f32(l0);
    if l0 == last {
        f = 0.0;
    }
    let a = package_shaders__1caustics_sampling__1caustics_bilinear(map, mips, mips_from, l0, p, size, wrap);
    if f == 0.0 {
        return a;
    }
    let b = package_shaders__1caustics_sampling__1caustics_bilinear(map, mips, mips_from, l0 + 1u, p, size, wrap);
    return a * (1.0 - f) + b * f;
}

const package_shaders__1caustics_sampling__2CAUSTICS_MAX_TAPS: f32 = 8.0;

struct package_shaders_bvh_BvhNode {
    min: vec3<f32>,
    start: u32,
    max: vec3<f32>,
    count: u32
}

struct package_shaders_bvh_BvhTriangle {
    p0: vec4<f32>,
    e1: vec4<f32>,
    e2: vec4<f32>,
    n0: vec4<f32>,
    n1: vec4<f32>,
    n2: vec4<f32>
}

struct package_shaders_bvh_MeshHit {
    t: f32,
    normal: vec3<f32>,
    found: bool
}

const package_shaders_bvh__1BVH_STACK: u32 = 61u;

const package_shaders_bvh__1BVH_WIDEN: f32 = 1.0 + 4.0 * 1.1920929e-7;

fn package_shaders_bvh__1bvh_enter(node: u32, o: vec3<f32>, inv_dir: vec3<f32>, t_max: f32) -> f32 {
    let n = package_shaders_bvh__1bvh_nodes[node];
    let t1 = (n.min - o) * inv_dir;
    let t2 = (n.max - o) * inv_dir;
    let lo = min(t1, t2);
    let hi = max(t1, t2);
    let near = max(max(max(lo.x, lo.y), lo.z), 0.0);
    let far = min(min(min(hi.x, hi.y), hi.z) * package_shaders_bvh__1BVH_WIDEN, t_max);
    if near <= far {
        return near;
    }
    return -1.0;
}

fn package_shaders_bvh__1bvh_intersect(root: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32, any_hit: bool) -> package_shaders_bvh_MeshHit {
    var result: package_shaders_bvh_MeshHit;
    result.found = false;
    result.t = t_max;
    let inv_dir = package_shaders_bvh__2bvh_inverse_direction(d);
    if package_shaders_bvh__1bvh_enter(root, o, inv_dir, t_max) < 0.0 {
        return result;
    }
    var stack_node: array<u32, package_shaders_bvh__1BVH_STACK>;
    var stack_t: array<f32, package_shaders_bvh__1BVH_STACK>;
    var top = 0u;
    var t_best = t_max;
    var best_slot = 0u;
    var best_uv = vec2<f32>(0.0);
    var node = root;
    loop {
        let n = package_shaders_bvh__1bvh_nodes[node];
        if n.count > 0u {
            for (var k = n.start; k < n.start + n.count; k++) {
                let tri = package_shaders_bvh__1bvh_triangles[k];
                let h = package_shaders_bvh__1intersect_triangle(o, d, tri.p0.xyz, tri.e1.xyz, tri.e2.xyz, t_best);
                if h.w != 0.0 {
                    t_best = h.x;
                    best_slot = k;
                    best_uv = h.yz;
                    result.found = true;
                    if any_hit {
                        result.t = t_best;
                        return result;
                    }
                }
            }
        }
        else {
            let left = n.start;
            let right = n.start + 1u;
            let l = package_shaders_bvh__1bvh_enter(left, o, inv_dir, t_best);
            let r = package_shaders_bvh__1bvh_enter(right, o, inv_dir, t_best);
            if l >= 0.0 && r >= 0.0 {
                var near = left;
                var far = right;
                var t_far = r;
                if l > r {
                    near = right;
                    far = left;
                    t_far = l;
                }
                if top < package_shaders_bvh__1BVH_STACK {
                    stack_node[top] = far;
                    stack_t[top] = t_far;
                    top++;
                }
                node = near;
                continue;
            }
            else if l >= 0.0 {
                node = left;
                continue;
            }
            else if r >= 0.0 {
                node = right;
                continue;
            }
        }
        var resumed = false;
        loop {
            if top == 0u {
                break;
            }
            top--;
            if stack_t[top] < t_best {
                node = stack_node[top];
                resumed = true;
                break;
            }
        }
        if !resumed {
            break;
        }
    }
    if result.found {
        result.t = t_best;
        result.normal = package_shaders_bvh__1bvh_normal(best_slot, best_uv.x, best_uv.y);
    }
    return result;
}

@group(1) @binding(0)
var<storage, read> package_shaders_bvh__1bvh_nodes: array<package_shaders_bvh_BvhNode>;

fn package_shaders_bvh__1bvh_normal(slot: u32, u: f32, v: f32) -> vec3<f32> {
    let tri = package_shaders_bvh__1bvh_triangles[slot];
    let n = (1.0 - u - v) * tri.n0.xyz + u * tri.n1.xyz + v * tri.n2.xyz;
    if dot(n, n) > 0.0 {
        return normalize(n);
    }
    let f = cross(tri.e1.xyz, tri.e2.xyz);
    if dot(f, f) > 0.0 {
        return normalize(f);
    }
    return vec3<f32>(0.0);
}

@group(1) @binding(1)
var<storage, read> package_shaders_bvh__1bvh_triangles: array<package_shaders_bvh_BvhTriangle>;

fn package_shaders_bvh__1intersect_triangle(o: vec3<f32>, d: vec3<f32>, p0: vec3<f32>, e1: vec3<f32>, e2: vec3<f32>, t_max: f32) -> vec4<f32> {
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det == 0.0 {
        return vec4<f32>(0.0);
    }
    let inv_det = 1.0 / det;
    let s = o - p0;
    let u = dot(s, p) * inv_det;
    if u < 0.0 || u > 1.0 {
        return vec4<f32>(0.0);
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv_det;
    if v < 0.0 || u + v > 1.0 {
        return vec4<f32>(0.0);
    }
    let t = dot(e2, q) * inv_det;
    if t > 0.0 && t < t_max {
        return vec4<f32>(t, u, v, 1.0);
    }
    return vec4<f32>(0.0);
}

fn package_shaders_bvh__2bvh_inverse_direction(d: vec3<f32>) -> vec3<f32> {
    let tiny = 1e-20;
    let safe = select(d, select(vec3<f32>(tiny), vec3<f32>(-tiny), d < vec3<f32>(0.0)), abs(d) < vec3<f32>(tiny));
    return 1.0 / safe;
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

const package_shaders_shading_COPING: f32 = 0.3;

const package_shaders_shading_JOINT: f32 = 0.01;

const package_shaders_shading_PAVER: f32 = 0.6;

const package_shaders_shading__1ALBEDO_PLAIN: u32 = 2u;

const package_shaders_shading__1ALBEDO_SAND: u32 = 1u;

const package_shaders_shading__1ALBEDO_TILES: u32 = 0u;

const package_shaders_shading__1DECK_CONCRETE: u32 = 1u;

const package_shaders_shading__1GROUT_COLOUR: vec3<f32> = vec3<f32>(0.18, 0.2, 0.22);

const package_shaders_shading__1NOISE_POINT: f32 = 0.001;

const package_shaders_shading__1SAND_GRAIN: f32 = 0.05;

const package_shaders_shading__1SAND_PATCH: f32 = 0.5;

const package_shaders_shading__1TILE_COLOUR: vec3<f32> = vec3<f32>(0.62, 0.78, 0.82);

fn package_shaders_shading__1deck_albedo(kind: u32, p: vec2<f32>, size: f32, footprint: f32) -> vec3<f32> {
    let out = max(max(-p.x, p.x - size), max(-p.y, p.y - size));
    let coping = min(package_shaders_shading_COPING, 0.1 * size);
    if out <= coping {
        if out < min(package_shaders_shading_JOINT, 0.1 * coping) {
            return vec3<f32>(0.3, 0.29, 0.27);
        }
        return vec3<f32>(0.78, 0.76, 0.71);
    }
    if kind == package_shaders_shading__1DECK_CONCRETE {
        return vec3<f32>(0.55, 0.55, 0.53);
    }
    let row = floor(p.y / package_shaders_shading_PAVER);
    let x = p.x / package_shaders_shading_PAVER + 0.5 * (row - 2.0 * floor(row / 2.0));
    let col = floor(x);
    let w = footprint / package_shaders_shading_PAVER;
    let joint = package_shaders_shading_JOINT / package_shaders_shading_PAVER;
    let grout = 1.0 - (1.0 - package_shaders_shading__1joint_cover(x, w, joint)) * (1.0 - package_shaders_shading__1joint_cover(p.y / package_shaders_shading_PAVER, w, joint));
    let shade = 0.85 + 0.3 * package_shaders_shading_hash01(i32(col), i32(row));
    return vec3<f32>(0.6, 0.53, 0.43) * (shade * (1.0 - grout)) + vec3<f32>(0.32, 0.31, 0.29) * grout;
}

fn package_shaders_shading__1floor_albedo(kind: u32, image: texture_2d<f32>, p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    let u = p / size;
    let w = extent / size;
    switch kind {
        case package_shaders_shading__1ALBEDO_TILES {
            let t = u * 8.0;
            let jx = package_shaders_shading__1joint_cover(t.x, w.x * 8.0, 0.04);
            let jy = package_shaders_shading__1joint_cover(t.y, w.y * 8.0, 0.04);
            let grout = 1.0 - (1.0 - jx) * (1.0 - jy);
            return package_shaders_shading__1TILE_COLOUR * (1.0 - grout) + package_shaders_shading__1GROUT_COLOUR * grout;
        }
        case package_shaders_shading__1ALBEDO_SAND {
            let ripple = sin(u.x * 157.0) * package_shaders_shading_sinc(78.5 * w.x) * sin(u.y * 113.0) * package_shaders_shading_sinc(56.5 * w.y) * 0.03;
            let grain = package_shaders_shading__2SAND_GRAIN_AMPLITUDE * package_shaders_shading__1value_noise(p, package_shaders_shading__1SAND_GRAIN, 0, extent) + package_shaders_shading__2SAND_PATCH_AMPLITUDE * package_shaders_shading__1value_noise(p, package_shaders_shading__1SAND_PATCH, 7919, extent);
            return vec3<f32>(0.76, 0.68, 0.5) * (1.0 + grain) + vec3<f32>(ripple);
        }
        case package_shaders_shading__1ALBEDO_PLAIN {
            return vec3<f32>(0.7);
        }
        case default {
            let dims = textureDimensions(image);
            let j = min(u32(fract(u.x) * f32(dims.x)), dims.x - 1u);
            let i = min(u32(fract(u.y) * f32(dims.y)), dims.y - 1u);
            return textureLoad(image, vec2<u32>(j, i), 0).rgb;
        }
    }
}

fn package_shaders_shading__1hat_integral(t: f32) -> f32 {
    let u = min(abs(t), 1.0);
    return 0.5 + sign(t) * (u - u * u * u + 0.5 * u * u * u * u);
}

fn package_shaders_shading__1joint_cover(x: f32, w: f32, joint: f32) -> f32 {
    if w <= 0.0001 {
        return select(0.0, 1.0, x - floor(x) < joint);
    }
    return clamp((package_shaders_shading__1joint_integral(x + 0.5 * w, joint) - package_shaders_shading__1joint_integral(x - 0.5 * w, joint)) / w, 0.0, 1.0);
}

fn package_shaders_shading__1joint_integral(x: f32, joint: f32) -> f32 {
    let n = floor(x);
    return n * joint + min(x - n, joint);
}

fn package_shaders_shading__1perez_sky(d: vec3<f32>, to_sun: vec3<f32>, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, dd: vec3<f32>, e: vec3<f32>, scale: vec3<f32>) -> vec3<f32> {
    let cos_theta = max(d.z, 0.001);
    let gamma = acos(clamp(dot(d, to_sun), -1.0, 1.0));
    let cos_gamma = cos(gamma);
    return scale * (1.0 + a * exp(b / cos_theta)) * (1.0 + c * exp(dd * gamma) + e * cos_gamma * cos_gamma);
}

fn package_shaders_shading__1value_noise(p: vec2<f32>, cell: f32, seed: i32, w: vec2<f32>) -> f32 {
    let q = p / cell;
    let r = w / cell;
    let exact = min(r, vec2<f32>(package_shaders_shading__2NOISE_EXACT_BOX));
    var i0: i32;
    var j0: i32;
    let wx = package_shaders_shading__2hat_box_weights(q.x, 0.5 * exact.x, &i0);
    let wy = package_shaders_shading__2hat_box_weights(q.y, 0.5 * exact.y, &j0);
    j0 += seed;
    var n = 0.0;
    for (var b = 0; b < 4; b++) {
        if wy[b] == 0.0 {
            continue;
        }
        var row = 0.0;
        for (var a = 0; a < 4; a++) {
            if wx[a] != 0.0 {
                row += wx[a] * (2.0 * package_shaders_shading_hash01(i0 + a, j0 + b) - 1.0);
            }
        }
        n += wy[b] * row;
    }
    let fade = pow(1.0 + r * r, vec2<f32>(-0.25)) / pow(1.0 + exact * exact, vec2<f32>(-0.25));
    return n * fade.x * fade.y;
}

const package_shaders_shading__2NOISE_EXACT_BOX: f32 = 2.0;

const package_shaders_shading__2SAND_GRAIN_AMPLITUDE: f32 = 0.08;

const package_shaders_shading__2SAND_PATCH_AMPLITUDE: f32 = 0.06;

fn package_shaders_shading__2hat_box_weights(x: f32, a: f32, first: ptr<function, i32>) -> vec4<f32> {
    let i0 = floor(x - a);
    *first = i32(i0);
    let t = vec4<f32>(x - i0) - vec4<f32>(0.0, 1.0, 2.0, 3.0);
    if a < package_shaders_shading__1NOISE_POINT {
        let u = min(abs(t), vec4<f32>(1.0));
        return 1.0 - u * u * (3.0 - 2.0 * u);
    }
    return vec4<f32>(package_shaders_shading__1hat_integral(t.x + a) - package_shaders_shading__1hat_integral(t.x - a), package_shaders_shading__1hat_integral(t.y + a) - package_shaders_shading__1hat_integral(t.y - a), package_shaders_shading__1hat_integral(t.z + a) - package_shaders_shading__1hat_integral(t.z - a), package_shaders_shading__1hat_integral(t.w + a) - package_shaders_shading__1hat_integral(t.w - a)) / (2.0 * a);
}

fn package_shaders_shading__2xyy_to_rgb(v: vec3<f32>) -> vec3<f32> {
    let lum = v.x;
    let x = v.y;
    let y = v.z;
    if y <= 0.0 || lum <= 0.0 {
        return vec3<f32>(0.0);
    }
    let xyz = vec3<f32>(x / y * lum, lum, (1.0 - x - y) / y * lum);
    return max(vec3<f32>(dot(vec3<f32>(3.2406, -1.5372, -0.4986), xyz), dot(vec3<f32>(-0.9689, 1.8758, 0.0415), xyz), dot(vec3<f32>(0.0557, -0.204, 1.057), xyz)), vec3<f32>(0.0));
}

fn package_shaders_shading_hash01(x: i32, y: i32) -> f32 {
    var h = (bitcast<u32>(x) * 2376512323u) ^ (bitcast<u32>(y) * 3625334849u);
    h ^= h >> 16u;
    h *= 2146121005u;
    h ^= h >> 15u;
    h *= 2221713035u;
    h ^= h >> 16u;
    return f32(h) / 4294967296.0;
}

fn package_shaders_shading_sinc(x: f32) -> f32 {
    if abs(x) < 1e-6 {
        return 1.0;
    }
    return sin(x) / x;
}

fn shade_above(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    if package__1final_image__2final_image_inputs__1is_pool() && d.z < 0.0 {
        let deck = package__1final_image__2final_image_inputs_params.water_level + 0.1 * min(package__1final_image__2final_image_inputs_params.water_size, 1.0) + package__1final_image__2final_image_inputs__1h_max;
        let t = (deck - o.z) / d.z;
        if t > 0.0 {
            let p = o + d * t;
            let spread = 2.0 * length(package__1final_image__2final_image_inputs_params.camera_up) / f32(package__1final_image__2final_image_inputs_params.height) / f32(max(package__1final_image__2final_image_inputs_params.supersampling, 1u));
            let footprint = length(p - o) * spread / max(abs(d.z), 0.05);
            let albedo = package_shaders_shading__1deck_albedo(package__1final_image__2final_image_inputs__1deck_kind(), p.xy, package__1final_image__2final_image_inputs_params.water_size, footprint);
            return albedo * (vec3<f32>(package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z) + package__1final_image__2final_image_inputs_params.ambient) * package__1final_image__2final_image_inputs_params.light_color;
        }
    }
    if !package__1final_image__2final_image_inputs__1is_pool() && d.z < 0.0 {
        let r = package_shaders_optics__1fresnel_transmittance(-d.z, 1.0, package__1final_image__2final_image_inputs_params.ior);
        return package__1final_image__2final_image_inputs__1sky_radiance(reflect(d, vec3<f32>(0.0, 0.0, 1.0))) * (1.0 - r);
    }
    return package__1final_image__2final_image_inputs__1sky_radiance(d);
}

fn shade_floor(p: vec3<f32>, fa: vec2<f32>, fb: vec2<f32>) -> vec3<f32> {
    let size = package__1final_image__2final_image_inputs_params.water_size;
    let albedo = package__1final_image__2final_image_inputs__1albedo_at(p.xy, size, abs(fa) + abs(fb));
    let e_h = package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z;
    let flat = package__1final_image__2final_image_inputs_absorbed((package__1final_image__2final_image_inputs_params.water_level - p.z) / -package__1final_image__2final_image_inputs_params.sun_water.z);
    var relative = flat;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_CAUSTICS) {
        relative = package__1final_image__2final_image_inputs__2sample_caustics_filtered(p.xy, fa, fb, package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_CAUSTICS), flat, true);
    }
    else if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS) {
        let e = package__1final_image__2final_image_receivers__2sample_eye_space(p);
        if e.w != 0.0 {
            relative = e.rgb;
        }
    }
    var shadow = 1.0;
    if package__1final_image__2final_image_receivers_occluded(p + vec3<f32>(0.0, 0.0, 0.0001), -package__1final_image__2final_image_inputs_params.sun_water, package__1final_image__2final_image_inputs_FAR) {
        shadow = 0.0;
    }
    let direct = relative * (e_h * package__1final_image__2final_image_inputs_params.t_flat * shadow);
    let ambient = package__1final_image__2final_image_inputs_params.ambient * package__1final_image__2final_image_inputs_absorbed(package__1final_image__2final_image_inputs_params.water_level);
    return albedo * (direct + ambient) * package__1final_image__2final_image_inputs_params.light_color;
}

fn shade_object(p: vec3<f32>, n_out: vec3<f32>, d: vec3<f32>, k: u32, depth: u32, under: bool, w: vec3<f32>) {
    let obj = package__1final_image__2final_image_inputs_objects[k];
    let entering = dot(n_out, d) < 0.0;
    let n = select(-n_out, n_out, entering);
    if obj.glass == 0u {
        var sun_dir = package__1final_image__2final_image_inputs_params.sun;
        var t = 1.0;
        if under {
            sun_dir = package__1final_image__2final_image_inputs_params.sun_water;
            t = package__1final_image__2final_image_inputs_params.t_flat;
        }
        let lambert = max(dot(n, -sun_dir), 0.0);
        var lit = 0.0;
        if lambert > 0.0 && !package__1final_image__2final_image_receivers_occluded(p + n * 0.0001, -sun_dir, package__1final_image__2final_image_inputs_FAR) {
            lit = 1.0;
        }
        var water_path = vec3<f32>(1.0);
        if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_WATER) && under {
            water_path = package__1final_image__2final_image_inputs_absorbed(max(package__1final_image__2final_image_inputs_params.water_level - p.z, 0.0) / -sun_dir.z);
        }
        package__1final_image__2final_image_inputs_emit(w, obj.color * (water_path * (package__1final_image__2final_image_inputs_params.sun_intensity * lambert * lit * t) + package__1final_image__2final_image_inputs_params.ambient) * package__1final_image__2final_image_inputs_params.light_color);
        return;
    }
    var outside_ior = 1.0;
    if under {
        outside_ior = package__1final_image__2final_image_inputs_params.ior;
    }
    var n1 = outside_ior;
    var n2 = obj.ior;
    if !entering {
        n1 = obj.ior;
        n2 = outside_ior;
    }
    let cos_i = -dot(d, n);
    let t = package_shaders_optics__1fresnel_transmittance(cos_i, n1, n2);
    package__1final_image__2final_image_inputs__1push_ray(p + n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, under);
    let r = package_shaders_optics__1refract_dir(d, n, n1 / n2);
    if r.w != 0.0 {
        package__1final_image__2final_image_inputs__1push_ray(p - n * 1e-5, r.xyz, w * t * obj.color, depth + 1u, under);
    }
}

fn trace_air(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>) {
    var t_floor = package__1final_image__2final_image_inputs_FAR;
    if d.z < 0.0 {
        t_floor = -o.z / d.z;
    }
    let obj = package__1final_image__2final_image_receivers__1nearest_object(o, d, t_floor);
    if obj.found {
        shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
        return;
    }
    if t_floor < package__1final_image__2final_image_inputs_FAR {
        let p = o + d * t_floor;
        let fa = package__1final_image__2final_image_spread__1on_plane(package__1final_image__2final_image_spread_spread.a, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let fb = package__1final_image__2final_image_spread__1on_plane(package__1final_image__2final_image_spread_spread.b, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let albedo = package__1final_image__2final_image_inputs__1albedo_at(p.xy, package__1final_image__2final_image_inputs_params.scene_size, abs(fa) + abs(fb));
        let start = p + vec3<f32>(0.0, 0.0, 1e-5);
        var lit = 1.0;
        var caustic = vec3<f32>(0.0);
        if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_AIR_CAUSTICS) {
            caustic = package__1final_image__2final_image_inputs__2sample_caustics_filtered(p.xy, fa, fb, false, vec3<f32>(0.0), false);
            if package__1final_image__2final_image_receivers__2occluded_by_any(start, -package__1final_image__2final_image_inputs_params.sun, package__1final_image__2final_image_inputs_FAR) {
                lit = 0.0;
            }
        }
        else if package__1final_image__2final_image_receivers_occluded(start, -package__1final_image__2final_image_inputs_params.sun, package__1final_image__2final_image_inputs_FAR) {
            lit = 0.0;
        }
        let e = (vec3<f32>(lit) + caustic) * (package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z) + package__1final_image__2final_image_inputs_params.ambient;
        package__1final_image__2final_image_inputs_emit(w, albedo * e * package__1final_image__2final_image_inputs_params.light_color);
        return;
    }
    package__1final_image__2final_image_inputs_emit(w, package__1final_image__2final_image_inputs__1sky_radiance(d));
}
