// Technique `volumes`, the depth texture (§3.2): per texel, the nearest surface along the view's
// direction among the trees `roots[root_first ..]` (one object, or all of them for the shadow map):
// [depth, outward normal], zero where no surface is. CPU twin: `depth_pass` in
// caustics-core/src/techniques/volumes/representation.rs.

import package::shaders::bvh::bvh_intersect;
import package::volumes::common::{Pass, texel_point};

@group(0) @binding(0) var<uniform> obj: Pass;
@group(0) @binding(1) var<storage, read> roots: array<u32>;
@group(0) @binding(2) var out_depth: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let view = obj.view;
    let res = u32(view.a.w);
    if id.x >= res || id.y >= res {
        return;
    }
    let m = view.b.w;
    let o = texel_point(view, id.y, id.x, -m);
    var t_best = view.texel.z + 2.0 * m;
    var best = vec4<f32>(0.0);
    for (var k = 0u; k < obj.root_count; k++) {
        let hit = bvh_intersect(roots[obj.root_first + k], o, view.v.xyz, t_best, false);
        if hit.found {
            t_best = hit.t;
            best = vec4<f32>(hit.t - m, hit.normal);
        }
    }
    textureStore(out_depth, vec2<i32>(id.xy), best);
}
