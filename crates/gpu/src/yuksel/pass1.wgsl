// Technique `yuksel`, pass 1 (paper Fig. 5): for pass-1 texel (j, r), the samples (k x k each) of
// sample row R = r - M/2 + shift.y at columns j + shift.x + [-N/2, N/2], and the share of their
// light in map pixel (j, 2^level (R + k - M/2 - shift.y) + phase) in channel k, R and the columns
// counted in the level's pixels (j / 2^level + shift.x + [-N/2, N/2] at a coarser level). The
// channels leave through multiple render targets; the output struct (`Pass1Out`, one vec4 per
// target) and `fs_main` that fills it are generated for the number of targets one draw writes.

import package::yuksel::common::{
    YukselRegion, box_share, half_widths, level_size, level_subsamples, pre_texel, tier_side, u,
};

@group(0) @binding(1) var pre: texture_2d_array<f32>;
@group(0) @binding(2) var<storage, read> region: YukselRegion;
// Per pixel of the pre-pass, the span along x its records' boxes cover (`prepass.wgsl`,
// `prepass_span.wgsl`).
@group(0) @binding(3) var extents: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the target.
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}

// Channels channel_base .. channel_base + count of texel (j, r), relative to channel_base.
fn pass1_channels(j: i32, r: i32, count: i32) -> array<f32, 32> {
    var intensity: array<f32, 32>;
    // The texture holds the largest region's rows; rows past this frame's are never read.
    // Phases past this frame's level serve no rows.
    if r >= i32(level_size(u.width, u.height, region.level).y + region.m) || u.phase >= (1u << region.level) {
        return intensity;
    }
    // In map pixels: the level's pixel, and the map pixel's centre within the level's.
    let scale = f32(1u << region.level);
    let centre = (scale - 1.0) * 0.5;
    // A level's pixel holds the light of 4^level map pixels.
    let area = scale * scale;
    let jc = j >> region.level;
    let qx = f32(j - (jc << region.level));
    let col0 = region.shift.x - i32(region.n / 2u);
    let row0 = -i32(region.m / 2u) - region.shift.y;
    let base = i32(u.channel_base);
    let last = min(base + count, i32(region.m) + 1);
    let sub = i32(level_subsamples(region.level));
    let tile = textureDimensions(pre);
    for (var col = 0; col < i32(region.n); col++) {
        // A pixel none of whose boxes reaches this map pixel gives it nothing: its records are
        // not read (the margin keeps a box whose share only rounding would zero).
        let span = textureLoad(extents, vec2<i32>(jc + col, r), 0).xy;
        if (f32(col + col0) + span.y) * scale + centre - qx <= -0.5001 || (f32(col + col0) + span.x) * scale + centre - qx >= 0.5001 {
            continue;
        }
        let first = vec2<i32>((jc + col) * sub, r * sub);
        let at0 = pre_texel(first, tile);
        let p0 = textureLoad(pre, at0.xy, at0.z, 0);
        // A pixel's t x t records (`yuksel_tier`), t in its first's sign bits.
        let side = i32(tier_side(p0.z, u32(sub)));
        for (var b = 0; b < side; b++) {
            for (var a = 0; a < side; a++) {
                let at = pre_texel(first + vec2<i32>(a, b), tile);
                let p = textureLoad(pre, at.xy, at.z, 0);
                let half = half_widths(p.z) * scale;
                // In map pixels from the map pixel's centre.
                let ax = box_share((f32(col + col0) + p.x) * scale + centre - qx, half.x);
                if ax == 0.0 {
                    continue;
                }
                // Only the channels whose row the box reaches (a row more each side against
                // rounding): the others' share is 0.
                let reach = (0.5 + half.y) / scale;
                let mid = p.y + (centre - f32(u.phase)) / scale - f32(row0);
                let lo = max(base, i32(floor(mid - reach)) - 1);
                let hi = min(last, i32(ceil(mid + reach)) + 2);
                for (var k = lo; k < hi; k++) {
                    let ay = box_share((p.y - f32(k + row0)) * scale + centre - f32(u.phase), half.y);
                    intensity[k - base] += ax * ay * p.w * area;
                }
            }
        }
    }
    return intensity;
}
