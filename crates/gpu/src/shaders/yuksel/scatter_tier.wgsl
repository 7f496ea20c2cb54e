// Technique `yuksel`, scatter variant (ours), first of three: one invocation per pixel of the
// level's map and its region's apron finds its tier (`yuksel_tier`) and adds the records it made
// into the map (`add_record`): below k all t x t, at k its first, `scatter_fill.wgsl` adding the
// others one per invocation (so that neighbouring invocations do the same work). No pre-pass
// texture and no render targets: the records are added where they are made.

// Per pixel, its records a side t.
@group(0) @binding(4) var tiers_out: texture_storage_2d<r32uint, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = level_subsamples(region.level);
    if !in_prepass_area(id.xy, textureDimensions(tiers_out), region) {
        return;
    }
    let q = prepass_level_pixel(id.xy, region);
    let pixel = u.pixel * f32(1u << region.level);
    let t = yuksel_tier(q.x, q.y, k, pixel, 1u);
    textureStore(tiers_out, vec2<i32>(id.xy), vec4<u32>(t));
    for (var r = 0u; r < select(t * t, 1u, t == k); r++) {
        add_record(tier_records[r], q);
    }
}
