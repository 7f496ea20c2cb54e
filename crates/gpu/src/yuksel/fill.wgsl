// Technique `yuksel`: the k x k records of a pixel whose tier is k, shared by both variants' fill
// passes (`prepass_fill.wgsl`, `scatter_fill.wgsl`), which take the pixels their tier pass listed,
// one invocation each through an indirect dispatch (so that neighbouring invocations do the same
// work). Footprints side by side share the ray of the edge between them: row by row, the k + 1
// edge midpoints along x and the k above, the k below kept from the row before, so a pixel
// refracts (3k + 1) k + k rays (56 at k = 4) where its footprints one at a time would refract
// 5 k² (80). The same points as `yuksel_part` (`yuksel_lattice` places them), so the same records.
// CPU twin: `prepass` in core's yuksel/prepass.rs.

import package::yuksel::common::u;
import package::yuksel::sample::{
    YukselFootprint, yuksel_footprint, yuksel_hit, yuksel_lattice, yuksel_part, yuksel_record,
};

// The fill's indirect dispatch (workgroups of `FILL_GROUP` along x, 1, 1) and how many pixels the
// tier pass listed; x and the count are cleared every frame.
struct FillArgs {
    groups: atomic<u32>,
    y: u32,
    z: u32,
    count: atomic<u32>,
}

// Listed pixels per workgroup of a fill pass, and the most workgroups its dispatch counts (WebGPU's
// and most devices' limit along one dimension): past their product (a 2048² map with every pixel
// at k lists 4.3 million) each invocation fills every `FILL_GROUP * FILL_MAX_GROUPS`-th entry.
const FILL_GROUP: u32 = 64u;
const FILL_MAX_GROUPS: u32 = 65535u;
const FILL_STRIDE: u32 = FILL_GROUP * FILL_MAX_GROUPS;
// Footprints a side at k, at most (`MAX_LEVEL_SUBSAMPLES` in core's yuksel/mod.rs), and the edges
// between and around them.
const MAX_FILL: u32 = 8u;
const MAX_FILL_EDGES: u32 = 9u;

// Row b's records, made by `yuksel_fill_row`.
var<private> fill_row: array<vec4<f32>, MAX_FILL>;
// Per column, the hit of the next row's edge midpoint on its minus side along y.
var<private> fill_below: array<vec4<f32>, MAX_FILL>;

// Row b of the k x k records of the level's pixel q (rows in order from 0) into `fill_row`.
fn yuksel_fill_row(q: vec2<i32>, b: u32, k: u32, pixel: vec2<f32>) {
    if u.footprint == 0u {
        for (var a = 0u; a < k; a++) {
            fill_row[a] = yuksel_record(yuksel_part(q.x, q.y, a, b, k, pixel), q.x, q.y, a, b, k, k, pixel);
        }
        return;
    }
    if b == 0u {
        for (var a = 0u; a < k; a++) {
            fill_below[a] = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a + 1u, 0u, k, pixel));
        }
    }
    let j = 2u * b + 1u;
    var across: array<vec4<f32>, MAX_FILL_EDGES>;
    for (var a = 0u; a <= k; a++) {
        across[a] = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a, j, k, pixel));
    }
    for (var a = 0u; a < k; a++) {
        let h = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a + 1u, j, k, pixel));
        let above = yuksel_hit(yuksel_lattice(q.x, q.y, 2u * a + 1u, j + 1u, k, pixel));
        var f = YukselFootprint(vec4<f32>(0.0), 0.0);
        if h.w != 0.0 {
            f = yuksel_footprint(h, across[a], across[a + 1u], fill_below[a], above, pixel);
        }
        fill_row[a] = yuksel_record(f, q.x, q.y, a, b, k, k, pixel);
        fill_below[a] = above;
    }
}

// The pixel of the pre-pass's area that listed entry `i` holds (`area`: this frame's, whose rows
// the tier pass counted it in).
fn fill_listed(entry: u32, area: vec2<u32>) -> vec2<u32> {
    return vec2<u32>(entry % area.x, entry / area.x);
}
