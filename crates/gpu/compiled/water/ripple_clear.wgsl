@group(0) @binding(0)
var a: texture_storage_2d<r32float, write>;

@group(0) @binding(1)
var b: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(a);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    textureStore(a, id.xy, vec4<f32>(0.0));
    textureStore(b, id.xy, vec4<f32>(0.0));
}
