// Technique `yuksel`, scatter variant, second of three: the records of the pixels whose tier is k
// but their first (`scatter_tier.wgsl` added that one), one invocation per record, the others
// returning at once. Invocation (c, r) is footprint (c % k, r % k) of its pixel.

@group(0) @binding(4) var tiers: texture_2d<u32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    let at = id.xy / k;
    if k == 1u || (id.x % k == 0u && id.y % k == 0u) || !in_prepass_area(at, textureDimensions(tiers), region) {
        return;
    }
    if textureLoad(tiers, vec2<i32>(at), 0).x != k {
        return;
    }
    let q = prepass_level_pixel(at, region);
    let pixel = u.pixel * f32(1u << region.level);
    let f = yuksel_part(q.x, q.y, id.x % k, id.y % k, k, pixel);
    add_record(yuksel_record(f, q.x, q.y, k, k, pixel), q);
}
