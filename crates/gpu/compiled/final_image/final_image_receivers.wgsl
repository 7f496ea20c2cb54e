const EYE_SPACE_MIN_WEIGHT: f32 = 0.001;

struct ObjectHit {
    t: f32,
    normal: vec3<f32>,
    k: u32,
    found: bool
}

fn inside(p: vec2<f32>, size: f32) -> bool {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size;
}

fn nearest_object(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> ObjectHit {
    var best: ObjectHit;
    best.found = false;
    best.t = t_max;
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        let h = package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, best.t, false);
        if h.found {
            best = ObjectHit(h.t, h.normal, k, true);
        }
    }
    return best;
}

fn occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        if package__1final_image__2final_image_inputs_objects[k].glass == 0u && package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

fn occluded_by_any(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        if package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

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

@group(0) @binding(3)
var package__1final_image__2final_image_inputs__1caustics_map: texture_2d<f32>;

@group(0) @binding(9)
var<storage, read> package__1final_image__2final_image_inputs__1wall_cols: array<u32>;

@group(0) @binding(8)
var package__1final_image__2final_image_inputs__1wall_maps: texture_2d_array<f32>;

const package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS: u32 = 128u;

fn package__1final_image__2final_image_inputs_has(flag: u32) -> bool {
    return (package__1final_image__2final_image_inputs_params.flags & flag) != 0u;
}

@group(0) @binding(5)
var<storage, read> package__1final_image__2final_image_inputs_objects: array<package__1final_image__2final_image_inputs_Object>;

@group(0) @binding(0)
var<uniform> package__1final_image__2final_image_inputs_params: package__1final_image__2final_image_inputs_FinalImage;

fn package_shaders__1caustics_sampling__1wall_sample(walls: texture_2d_array<f32>, cols: u32, k: u32, along: f32, z: f32, size: f32, depth: f32) -> vec3<f32> {
    let rows = textureDimensions(walls).y;
    let u = clamp(along / size * f32(cols) - 0.5, 0.0, f32(cols - 1u));
    let v = clamp(z / depth * f32(rows) - 0.5, 0.0, f32(rows - 1u));
    let j0 = u32(floor(u));
    let i0 = u32(floor(v));
    let j1 = min(j0 + 1u, cols - 1u);
    let i1 = min(i0 + 1u, rows - 1u);
    let fu = u - f32(j0);
    let fv = v - f32(i0);
    let layer = i32(k);
    let a = textureLoad(walls, vec2<u32>(j0, i0), layer, 0).rgb;
    let b = textureLoad(walls, vec2<u32>(j1, i0), layer, 0).rgb;
    let c = textureLoad(walls, vec2<u32>(j0, i1), layer, 0).rgb;
    let d = textureLoad(walls, vec2<u32>(j1, i1), layer, 0).rgb;
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

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

fn sample_eye_space(p: vec3<f32>) -> vec4<f32> {
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
    if weight < EYE_SPACE_MIN_WEIGHT {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(sum / weight, 1.0);
}

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

fn wall_distance(o: vec3<f32>, d: vec3<f32>, size: f32) -> f32 {
    var t = package__1final_image__2final_image_inputs_FAR;
    for (var a = 0; a < 2; a++) {
        if d[a] > 0.0 {
            t = min(t, (size - o[a]) / d[a]);
        }
        else if d[a] < 0.0 {
            t = min(t, -o[a] / d[a]);
        }
    }
    return max(t, 0.0);
}

fn wall_light(p: vec3<f32>, size: f32) -> vec3<f32> {
    let k = wall_at(p, size);
    var eye = vec4<f32>(0.0);
    if package__1final_image__2final_image_inputs__1wall_cols[k] == 0u {
        if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS) {
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
        case 0u {
            along = p.y;
            normal = vec3<f32>(1.0, 0.0, 0.0);
        }
        case 1u {
            along = p.y;
            normal = vec3<f32>(-1.0, 0.0, 0.0);
        }
        case 3u {
            normal = vec3<f32>(0.0, -1.0, 0.0);
        }
        case default {
        
        }
    }
    var c = eye.rgb;
    if package__1final_image__2final_image_inputs__1wall_cols[k] != 0u {
        c = package_shaders__1caustics_sampling__1wall_sample(package__1final_image__2final_image_inputs__1wall_maps, package__1final_image__2final_image_inputs__1wall_cols[k], k, along, p.z, package__1final_image__2final_image_inputs_params.water_size, package__1final_image__2final_image_inputs_params.water_level);
    }
    if occluded(p + normal * 0.0001, -package__1final_image__2final_image_inputs_params.sun_water, package__1final_image__2final_image_inputs_FAR) {
        return vec3<f32>(0.0);
    }
    let e_h = package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z;
    return c * (e_h * package__1final_image__2final_image_inputs_params.t_flat) * package__1final_image__2final_image_inputs_params.light_color;
}
