// The slab the water surface lies in and its steepest slope, found each frame from the heights the
// techniques read, for the final image's water search (`hit_surface`, `crossing_after`) and the pool
// deck's height. CPU twin: caustics-core/src/render.rs `slab_bounds`, 1.5 times the largest |h|
// and |∇h| at the centres of a 128² lattice over the water square plus 1e-6; the maxima are taken
// here, the final image scales them.
//
// |h| and |∇h| are non-negative, and the bits of non-negative f32 order as u32 do, so atomicMax
// on the bits is a max on the values. Each workgroup reduces its 64 samples first, so the storage buffer sees
// one atomic per workgroup.

import package::shaders::water::grid_sample;

struct Slab {
    // The water square's side.
    size: f32,
    // The water's edge rule (1: periodic), per bicubic tap as the CPU's `Grid::sample` takes it.
    wrap: u32,
    // Samples along each side (128, as render.rs).
    lattice: u32,
    _pad: u32,
}

@group(0) @binding(0) var<uniform> slab: Slab;
@group(0) @binding(1) var water_height: texture_2d<f32>;
// Bits of the largest |h| and of the largest |∇h|; cleared to 0 before this pass.
@group(0) @binding(2) var<storage, read_write> slab_max: array<atomic<u32>>;

var<workgroup> group_max: atomic<u32>;
var<workgroup> group_slope: atomic<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if local == 0u {
        atomicStore(&group_max, 0u);
        atomicStore(&group_slope, 0u);
    }
    workgroupBarrier();
    let n = slab.lattice;
    if id.x < n && id.y < n {
        let p = (vec2<f32>(id.xy) + 0.5) * (slab.size / f32(n));
        let h = grid_sample(water_height, p, slab.size, slab.wrap != 0u);
        atomicMax(&group_max, bitcast<u32>(abs(h.x)));
        atomicMax(&group_slope, bitcast<u32>(length(h.yz)));
    }
    workgroupBarrier();
    if local == 0u {
        atomicMax(&slab_max[0], atomicLoad(&group_max));
        atomicMax(&slab_max[1], atomicLoad(&group_slope));
    }
}
