// Technique `yuksel`, the region's bound (ours, before the region pass): refract the sun through
// every height texel's normal (central differences) and reduce the range of the floor hits'
// sideways offsets over the whole texture, one texel an invocation and one atomic per workgroup and
// value (reduce.wgsl), so no single workgroup walks the texture. CPU twin: `region_bound` in
// caustics-core's yuksel/region.rs (the same texels, the same min and max: exact).

import package::shaders::optics::{height_field_normal, refract_dir};
import package::shaders::reduce::ordered;
import package::yuksel::common::u;

@group(0) @binding(1) var heights: texture_2d<f32>;
// ordered(-lo.x), ordered(-lo.y), ordered(hi.x), ordered(hi.y); cleared to 0 before this pass.
@group(0) @binding(2) var<storage, read_write> bound: array<atomic<u32>, 4>;

var<workgroup> group_bound: array<atomic<u32>, 4>;

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if local < 4u {
        atomicStore(&group_bound[local], 0u);
    }
    workgroupBarrier();
    let dims = textureDimensions(heights);
    if id.x < dims.x && id.y < dims.y {
        let cols = dims.x;
        let rows = dims.y;
        let dx = u.size / f32(cols);
        let dy = u.size / f32(rows);
        let l = u.light.xyz;
        let i = id.y;
        let j = id.x;
        let h = textureLoad(heights, vec2<u32>(j, i), 0).x;
        let e = textureLoad(heights, vec2<u32>((j + 1u) % cols, i), 0).x;
        let w = textureLoad(heights, vec2<u32>((j + cols - 1u) % cols, i), 0).x;
        let n = textureLoad(heights, vec2<u32>(j, (i + 1u) % rows), 0).x;
        let s = textureLoad(heights, vec2<u32>(j, (i + rows - 1u) % rows), 0).x;
        let normal = height_field_normal(vec2<f32>((e - w) / (2.0 * dx), (n - s) / (2.0 * dy)));
        let tr = refract_dir(l, normal, u.light.w);
        if -dot(l, normal) > 0.0 && tr.w != 0.0 && tr.z < 0.0 {
            let d = tr.xy / -tr.z * max(u.depth + h, 0.0);
            atomicMax(&group_bound[0], ordered(-d.x));
            atomicMax(&group_bound[1], ordered(-d.y));
            atomicMax(&group_bound[2], ordered(d.x));
            atomicMax(&group_bound[3], ordered(d.y));
        }
    }
    workgroupBarrier();
    if local < 4u {
        atomicMax(&bound[local], atomicLoad(&group_bound[local]));
    }
}
