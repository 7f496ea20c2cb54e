// Technique `yuksel`, pass 1 (paper Fig. 5): for pass-1 texel (j, r), the N samples of sample row
// r - M/2 around column j, and their overlap with map pixel (j, r - M/2 + k - M/2) in channel k. The
// channels leave through multiple render targets; the output struct (`Pass1Out`, one vec4 per
// target) and `fs_main` that fills it are generated for the number of targets one draw writes.

@group(0) @binding(0) var<uniform> u: Yuksel;
@group(0) @binding(1) var pre: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the target.
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}

// Channels channel_base .. channel_base + count of texel (j, r), relative to channel_base.
fn pass1_channels(j: i32, r: i32, count: i32) -> array<f32, 32> {
    var intensity: array<f32, 32>;
    let nh = i32(u.n / 2u);
    let mh = i32(u.m / 2u);
    let base = i32(u.channel_base);
    let last = min(base + count, i32(u.m) + 1);
    for (var s = 0; s < i32(u.n); s++) {
        let p = textureLoad(pre, vec2<i32>(j + s, r), 0);
        let ax = box_overlap(f32(s - nh) + p.x);
        if ax == 0.0 {
            continue;
        }
        for (var k = base; k < last; k++) {
            let ay = box_overlap(p.y - f32(k - mh));
            intensity[k - base] += ax * ay * p.z;
        }
    }
    return intensity;
}
