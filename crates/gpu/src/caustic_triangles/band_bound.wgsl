// Technique `caustic-triangles` with tiling water as the generator, the copy band's bound (before
// the copy band pass): the grid's steepest finite-difference slope and its height range, one texel
// an invocation and one atomic per workgroup and value (reduce.wgsl), so no single workgroup walks
// the heights. CPU twin: the slope and range `water::copy_band` takes (the same texels, exact).

import package::caustic_triangles::water_setup::WaterPhoton;
import package::shaders::reduce::ordered;

@group(0) @binding(0) var<uniform> w: WaterPhoton;
@group(0) @binding(1) var heights: texture_2d<f32>;
// ordered(slope), ordered(-lo), ordered(hi); cleared to 0 before this pass.
@group(0) @binding(2) var<storage, read_write> bound: array<atomic<u32>, 4>;

var<workgroup> group_bound: array<atomic<u32>, 3>;

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if local < 3u {
        atomicStore(&group_bound[local], 0u);
    }
    workgroupBarrier();
    let dims = textureDimensions(heights);
    if id.x < dims.x && id.y < dims.y {
        let cols = dims.x;
        let rows = dims.y;
        let dx = w.water.y / f32(cols);
        let dy = w.water.y / f32(rows);
        let i = id.y;
        let j = id.x;
        let h = textureLoad(heights, vec2<u32>(j, i), 0).x;
        let hx = textureLoad(heights, vec2<u32>((j + 1u) % cols, i), 0).x;
        let hy = textureLoad(heights, vec2<u32>(j, (i + 1u) % rows), 0).x;
        atomicMax(&group_bound[0], ordered(max(abs(hx - h) / dx, abs(hy - h) / dy)));
        atomicMax(&group_bound[1], ordered(-h));
        atomicMax(&group_bound[2], ordered(h));
    }
    workgroupBarrier();
    if local < 3u {
        atomicMax(&bound[local], atomicLoad(&group_bound[local]));
    }
}
