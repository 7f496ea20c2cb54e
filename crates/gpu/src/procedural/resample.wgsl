// Technique `procedural`, texture-space variant, last pass: every map pixel reads the mipmapped
// target at its centre with the footprint of one map pixel, through a trilinear sampler with
// anisotropy_clamp = 16 (the paper: "automatic mipmap generation and anisotropic filtering to reduce
// aliasing"). CPU twin: `resample` (Vulkan's LOD rule and N trilinear taps along the major axis).

import package::procedural::common::{full_screen, u};

@group(0) @binding(3) var target_mips: texture_2d<f32>;
@group(0) @binding(4) var mip_sampler: sampler;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return full_screen(v);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let dims = vec2<f32>(f32(u.width), f32(u.height));
    let uv = frag.xy / dims;
    let c = textureSampleGrad(target_mips, mip_sampler, uv, vec2<f32>(1.0 / dims.x, 0.0), vec2<f32>(0.0, 1.0 / dims.y));
    return vec4<f32>(c.rgb, 1.0);
}
