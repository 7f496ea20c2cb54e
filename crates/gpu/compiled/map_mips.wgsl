@group(0) @binding(1)
var coarse: texture_storage_2d<rgba32float, write>;

@group(0) @binding(0)
var fine: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(coarse);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let last = vec2<i32>(textureDimensions(fine)) - 1;
    let c = vec2<i32>(id.xy) * 2;
    let a = textureLoad(fine, min(c, last), 0).rgb;
    let b = textureLoad(fine, min(c + vec2<i32>(1, 0), last), 0).rgb;
    let e = textureLoad(fine, min(c + vec2<i32>(0, 1), last), 0).rgb;
    let d = textureLoad(fine, min(c + vec2<i32>(1, 1), last), 0).rgb;
    textureStore(coarse, id.xy, vec4<f32>((a + b + e + d) * 0.25, 0.0));
}
