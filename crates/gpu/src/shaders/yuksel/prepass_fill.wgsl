// Technique `yuksel`, pre-pass, second of three: the k x k records of the pixels whose tier is k
// (`prepass.wgsl` wrote their tier), one invocation per record (texel), the others returning at
// once. Texel (c, r) is footprint (c % k, r % k) of its pixel.

@group(0) @binding(2) var pre_out: texture_storage_2d_array<rgba32float, write>;
@group(0) @binding(3) var<storage, read> region: YukselRegion;
@group(0) @binding(4) var tiers: texture_2d<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    let at = id.xy / k;
    if k == 1u || !in_prepass_area(at, textureDimensions(tiers), region) {
        return;
    }
    if textureLoad(tiers, vec2<i32>(at), 0).x != k {
        return;
    }
    let q = prepass_level_pixel(at, region);
    let pixel = u.pixel * f32(1u << region.level);
    let f = yuksel_part(q.x, q.y, id.x % k, id.y % k, k, pixel);
    let texel = pre_texel(vec2<i32>(id.xy), textureDimensions(pre_out));
    textureStore(pre_out, texel.xy, texel.z, yuksel_record(f, q.x, q.y, k, k, pixel));
}
