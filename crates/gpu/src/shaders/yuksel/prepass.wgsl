// Technique `yuksel`, pre-pass (paper §5): every sample's floor hit, computed once. Pre-pass texel
// (c, r) is the sample of map pixel (c - N/2, r - M/2).

@group(0) @binding(2) var pre_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(pre_out);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let c = i32(id.x) - i32(u.n / 2u);
    let r = i32(id.y) - i32(u.m / 2u);
    textureStore(pre_out, vec2<i32>(id.xy), yuksel_sample(c, r));
}
