// Technique `procedural`, per-pixel screen-space variant (paper: the first Cg method): every map
// pixel evaluates the caustic at its own centre, at full resolution, with no filtering.
// CPU twin: `per_pixel` at the map's size.

import package::procedural::common::{full_screen, procedural_caustic, u};

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return full_screen(v);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = frag.xy / vec2<f32>(f32(u.width), f32(u.height)) * u.size;
    return vec4<f32>(procedural_caustic(p), 1.0);
}
