// Technique `yuksel`, pre-pass (paper §5): every sample's floor hit, computed once. Pre-pass texel
// (c, r) is sample (c % k, r % k) of map pixel (c / k - N/2 + shift.x, r / k - M/2 + shift.y).
// The texture is sized for the largest region; texels beyond this frame's are left alone.

@group(0) @binding(2) var pre_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(pre_out);
    let size = level_size(u.width, u.height, region.level);
    let k = level_subsamples(region.level);
    let used = vec2<u32>(size.x + region.n - 1u, size.y + region.m) * k;
    if id.x >= min(dims.x, used.x) || id.y >= min(dims.y, used.y) {
        return;
    }
    let c = i32(id.x / k) - i32(region.n / 2u) + region.shift.x;
    let r = i32(id.y / k) - i32(region.m / 2u) + region.shift.y;
    let pixel = u.pixel * f32(1u << region.level);
    textureStore(pre_out, vec2<i32>(id.xy), yuksel_sample(c, r, id.x % k, id.y % k, k, pixel));
}
