// Technique `procedural`, texture-space variant, one pass per mip level: texel (j, i) of level k + 1
// is the 2 x 2 box average of texels (2j .. 2j + 1, 2i .. 2i + 1) of level k (the paper's "automatic
// mipmap generation", done by hand so the CPU twin sums in the same order). CPU twin: `mip_chain`.

@group(0) @binding(0) var finer: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let c = vec2<i32>(frag.xy) * 2;
    let a = textureLoad(finer, c, 0);
    let b = textureLoad(finer, c + vec2<i32>(1, 0), 0);
    let d = textureLoad(finer, c + vec2<i32>(0, 1), 0);
    let e = textureLoad(finer, c + vec2<i32>(1, 1), 0);
    return (a + b + d + e) * 0.25;
}
