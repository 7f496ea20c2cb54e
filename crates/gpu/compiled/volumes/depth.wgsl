@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let view = obj.view;
    let res = u32(view.a.w);
    if id.x >= res || id.y >= res {
        return;
    }
    let m = view.b.w;
    let o = package_volumes_common__1texel_point(view, id.y, id.x, -m);
    var t_best = view.texel.z + 2.0 * m;
    var best = vec4<f32>(0.0);
    for (var k = 0u; k < obj.root_count; k++) {
        let hit = package_shaders_bvh__1bvh_intersect(roots[obj.root_first + k], o, view.v.xyz, t_best, false);
        if hit.found {
            t_best = hit.t;
            best = vec4<f32>(hit.t - m, hit.normal);
        }
    }
    textureStore(out_depth, vec2<i32>(id.xy), best);
}

@group(0) @binding(0)
var<uniform> obj: package_volumes_common_Pass;

@group(0) @binding(2)
var out_depth: texture_storage_2d<rgba32float, write>;

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

struct package_volumes_common_Pass {
    view: package_volumes_common_View,
    cells: vec4<u32>,
    planes: u32,
    root_first: u32,
    root_count: u32,
    _pad: u32,
    albedo: vec4<f32>
}

struct package_volumes_common_View {
    a: vec4<f32>,
    b: vec4<f32>,
    v: vec4<f32>,
    lo: vec4<f32>,
    texel: vec4<f32>
}

fn package_volumes_common__1texel_point(view: package_volumes_common_View, i: u32, j: u32, depth: f32) -> vec3<f32> {
    let u = view.lo.x + (f32(j) + 0.5) * view.texel.x;
    let w = view.lo.y + (f32(i) + 0.5) * view.texel.y;
    return view.a.xyz * u + view.b.xyz * w + view.v.xyz * (view.lo.z + depth);
}

@group(0) @binding(1)
var<storage, read> roots: array<u32>;
