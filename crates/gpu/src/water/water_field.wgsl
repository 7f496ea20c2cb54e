// The water field's output passes (crates/gpu/src/water/field.rs): the water's heights at this
// frame into an R32Float texture, texel (j, i) at ((j + ½) size / cols, (i + ½) size / rows) as
// `caustics_core::water::sample_grid` lays a grid out, times the height factor. One pass per kind of
// source, each importing this module.

struct FieldParams {
    // Side of the square the output covers, world units.
    size: f32,
    // Side of the square a grid source covers (the ocean's tile, else the water's square).
    grid_size: f32,
    // Height factor: the viewer's amplitude slider (0: flat).
    amplitude: f32,
    // Sine waves in use (waves pass).
    wave_count: u32,
    // 1: a grid source wraps at its edges; 0: it is clamped (grid pass).
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// The water point of output texel `id` of an output of `dims` texels.
fn field_point(params: FieldParams, id: vec2<u32>, dims: vec2<u32>) -> vec2<f32> {
    return (vec2<f32>(id) + 0.5) * params.size / vec2<f32>(dims);
}
