// The page's last pass: one side's final image (`Rgba8Unorm` holding sRGB-encoded values, as
// `final_image` writes it) stretched over that side's viewport of the canvas, whose format is
// not sRGB, so the values reach the screen as they are.

@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var linear: sampler;

struct Varyings {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

// One triangle over the viewport.
@vertex
fn vs(@builtin(vertex_index) i: u32) -> Varyings {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: Varyings;
    out.position = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    out.uv = uv;
    return out;
}

@fragment
fn fs(in: Varyings) -> @location(0) vec4<f32> {
    return vec4<f32>(textureSample(image, linear, in.uv).rgb, 1.0);
}
