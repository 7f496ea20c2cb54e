// A height texture in Hermite form (`grid_hermite_texel` in water.wgsl), one invocation per texel,
// written each frame before the passes that sample the water many times a pixel (yuksel's rays,
// the final image's search for the surface): `grid_sample_hermite` then reads 4 texels where
// `grid_sample` reads 16, for the same bicubic surface.

import package::shaders::water::grid_hermite_texel;

struct Patches {
    // The water's edge rule (1: periodic), as `grid_sample` takes it.
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> patches_params: Patches;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var patches_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(heights)) {
        return;
    }
    let texel = grid_hermite_texel(heights, vec2<i32>(id.xy), patches_params.wrap != 0u);
    textureStore(patches_out, vec2<i32>(id.xy), texel);
}
