// Technique `yuksel`, first pass of a frame: the heights in Hermite form (`grid_hermite_texel`),
// one invocation per height texel, so that every later ray reads 4 texels where `grid_sample`
// reads 16 (the rays are most of a frame's time: docs/yuksel.md). The same surface; no CPU twin
// of its own (the twin samples its grid bicubically).

@group(0) @binding(0) var<uniform> u: Yuksel;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var patches_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(heights)) {
        return;
    }
    textureStore(patches_out, vec2<i32>(id.xy), grid_hermite_texel(heights, vec2<i32>(id.xy), u.wrap != 0u));
}
