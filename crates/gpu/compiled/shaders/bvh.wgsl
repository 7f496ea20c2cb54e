const BVH_STACK: u32 = 61u;

const BVH_WIDEN: f32 = 1.0 + 4.0 * 1.1920929e-7;

struct BvhNode {
    min: vec3<f32>,
    start: u32,
    max: vec3<f32>,
    count: u32
}

struct BvhTriangle {
    p0: vec4<f32>,
    e1: vec4<f32>,
    e2: vec4<f32>,
    n0: vec4<f32>,
    n1: vec4<f32>,
    n2: vec4<f32>
}

struct MeshHit {
    t: f32,
    normal: vec3<f32>,
    found: bool
}

fn bvh_enter(node: u32, o: vec3<f32>, inv_dir: vec3<f32>, t_max: f32) -> f32 {
    let n = bvh_nodes[node];
    let t1 = (n.min - o) * inv_dir;
    let t2 = (n.max - o) * inv_dir;
    let lo = min(t1, t2);
    let hi = max(t1, t2);
    let near = max(max(max(lo.x, lo.y), lo.z), 0.0);
    let far = min(min(min(hi.x, hi.y), hi.z) * BVH_WIDEN, t_max);
    if near <= far {
        return near;
    }
    return -1.0;
}

fn bvh_intersect(root: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32, any_hit: bool) -> MeshHit {
    var result: MeshHit;
    result.found = false;
    result.t = t_max;
    let inv_dir = bvh_inverse_direction(d);
    if bvh_enter(root, o, inv_dir, t_max) < 0.0 {
        return result;
    }
    var stack_node: array<u32, BVH_STACK>;
    var stack_t: array<f32, BVH_STACK>;
    var top = 0u;
    var t_best = t_max;
    var best_slot = 0u;
    var best_uv = vec2<f32>(0.0);
    var node = root;
    loop {
        let n = bvh_nodes[node];
        if n.count > 0u {
            for (var k = n.start; k < n.start + n.count; k++) {
                let tri = bvh_triangles[k];
                let h = intersect_triangle(o, d, tri.p0.xyz, tri.e1.xyz, tri.e2.xyz, t_best);
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
            let l = bvh_enter(left, o, inv_dir, t_best);
            let r = bvh_enter(right, o, inv_dir, t_best);
            if l >= 0.0 && r >= 0.0 {
                var near = left;
                var far = right;
                var t_far = r;
                if l > r {
                    near = right;
                    far = left;
                    t_far = l;
                }
                if top < BVH_STACK {
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
        result.normal = bvh_normal(best_slot, best_uv.x, best_uv.y);
    }
    return result;
}

fn bvh_inverse_direction(d: vec3<f32>) -> vec3<f32> {
    let tiny = 1e-20;
    let safe = select(d, select(vec3<f32>(tiny), vec3<f32>(-tiny), d < vec3<f32>(0.0)), abs(d) < vec3<f32>(tiny));
    return 1.0 / safe;
}

@group(1) @binding(0)
var<storage, read> bvh_nodes: array<BvhNode>;

fn bvh_normal(slot: u32, u: f32, v: f32) -> vec3<f32> {
    let tri = bvh_triangles[slot];
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
var<storage, read> bvh_triangles: array<BvhTriangle>;

fn intersect_triangle(o: vec3<f32>, d: vec3<f32>, p0: vec3<f32>, e1: vec3<f32>, e2: vec3<f32>, t_max: f32) -> vec4<f32> {
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
