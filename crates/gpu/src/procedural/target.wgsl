// Technique `procedural`, texture-space variant, first pass (paper: the second Cg method): the
// caustic per texel of a fixed-size render target over the floor square, mip level 0.
// CPU twin: `per_pixel` at the target's size.

import package::procedural::common::{full_screen, procedural_caustic, u};

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return full_screen(v);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = frag.xy / f32(u.target_size) * u.size;
    return vec4<f32>(procedural_caustic(p), 1.0);
}
