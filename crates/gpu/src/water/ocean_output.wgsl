// FFT ocean, pass 3 of 3: the transformed field into a texture of (h, ∂h/∂x, ∂h/∂y, 0), texel (j, i)
// holding sample (i, j) of `Ocean::height_grid` / `Ocean::slope_grids`. The height is the real part
// of the first transform (its imaginary part is rounding noise: the spectrum is Hermitian); the
// slopes are the real and imaginary parts of the second.

@group(0) @binding(0) var<storage, read> field: array<vec4<f32>>;
@group(0) @binding(1) var output: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let v = field[id.y * dims.x + id.x];
    textureStore(output, id.xy, vec4<f32>(v.x, v.z, v.w, 0.0));
}
