@group(0) @binding(0)
var finer: texture_2d<f32>;

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let c = vec2<i32>(frag.xy) * 2;
    let a = textureLoad(finer, c, 0);
    let b = textureLoad(finer, c + vec2<i32>(1, 0), 0);
    let d = textureLoad(finer, c + vec2<i32>(0, 1), 0);
    let e = textureLoad(finer, c + vec2<i32>(1, 1), 0);
    return (a + b + d + e) * 0.25;
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}
