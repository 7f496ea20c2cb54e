@group(0) @binding(0)
var<storage, read> field: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let v = field[id.y * dims.x + id.x];
    textureStore(output, id.xy, vec4<f32>(v.x, v.z, v.w, 0.0));
}

@group(0) @binding(1)
var output: texture_storage_2d<rgba32float, write>;
