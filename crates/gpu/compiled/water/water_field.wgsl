struct FieldParams {
    size: f32,
    grid_size: f32,
    amplitude: f32,
    wave_count: u32,
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32
}

fn field_point(params: FieldParams, id: vec2<u32>, dims: vec2<u32>) -> vec2<f32> {
    return (vec2<f32>(id) + 0.5) * params.size / vec2<f32>(dims);
}
