// Technique `yuksel`, scatter variant, second of three: the k x k records of each pixel whose tier
// is k (`scatter_tier.wgsl` listed them), one invocation per listed pixel, dispatched indirectly.
// Footprints side by side share the ray of the edge between them: row by row, the k + 1 edge
// midpoints along x and the k below, the k above kept from the row before, so a pixel refracts
// (3k + 1) k + k rays (56 at k = 4) where its footprints one at a time would refract 5 k² (80).
// The same rays as `yuksel_part` (`yuksel_lattice` places them), so the same records.

@group(0) @binding(4) var<storage, read> fill_args: array<u32, 4>;
@group(0) @binding(5) var<storage, read> fill_list: array<u32>;

@compute @workgroup_size(FILL_GROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= fill_args[3] {
        return;
    }
    let k = level_subsamples(region.level);
    let area = prepass_area(region.n, region.m, region.level);
    let at = vec2<u32>(fill_list[id.x] % area.x, fill_list[id.x] / area.x);
    let q = prepass_level_pixel(at, region);
    let pixel = u.pixel * f32(1u << region.level);
    if u.footprint == 0u {
        for (var n = 0u; n < k * k; n++) {
            let f = yuksel_part(q.x, q.y, n % k, n / k, k, pixel);
            add_record(yuksel_record(f, q.x, q.y, k, k, pixel), q);
        }
        return;
    }
    // Per column, the hit of the current row's edge midpoint on its minus side along y.
    var below: array<vec4<f32>, MAX_FILL>;
    for (var a = 0u; a < k; a++) {
        below[a] = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a + 1u, 0u, k, pixel));
    }
    var across: array<vec4<f32>, MAX_FILL_EDGES>;
    for (var b = 0u; b < k; b++) {
        let j = 2u * b + 1u;
        for (var a = 0u; a <= k; a++) {
            across[a] = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a, j, k, pixel));
        }
        for (var a = 0u; a < k; a++) {
            let h = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a + 1u, j, k, pixel));
            let above = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a + 1u, j + 1u, k, pixel));
            var f = YukselFootprint(vec4<f32>(0.0), 0.0);
            if h.w != 0.0 {
                f = yuksel_footprint(h, across[a], across[a + 1u], below[a], above, pixel);
            }
            add_record(yuksel_record(f, q.x, q.y, k, k, pixel), q);
            below[a] = above;
        }
    }
}
