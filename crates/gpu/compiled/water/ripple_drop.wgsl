const PI: f32 = 3.141592653589793;

struct RippleDrop {
    centre: vec2<f32>,
    radius: f32,
    strength: f32,
    first: vec2<i32>,
    count: vec2<u32>,
    dx: f32,
    size: f32,
    wrap: u32,
    _pad: u32
}

@group(0) @binding(1)
var current: texture_storage_2d<r32float, read_write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.count.x || id.y >= params.count.y {
        return;
    }
    let n = vec2<i32>(textureDimensions(current));
    let a = params.first + vec2<i32>(id.xy);
    let cell = vec2<u32>(((a % n) + n) % n);
    var offset = (vec2<f32>(cell) + 0.5) * params.dx - params.centre;
    if params.wrap != 0u {
        offset -= params.size * round(offset / params.size);
    }
    let r = sqrt(offset.x * offset.x + offset.y * offset.y);
    if r < params.radius {
        let bump = params.strength * 0.5 * (1.0 + cos(PI * r / params.radius));
        textureStore(current, cell, textureLoad(current, cell) + vec4<f32>(bump, 0.0, 0.0, 0.0));
        textureStore(previous, cell, textureLoad(previous, cell) + vec4<f32>(bump, 0.0, 0.0, 0.0));
    }
}

@group(0) @binding(0)
var<uniform> params: RippleDrop;

@group(0) @binding(2)
var previous: texture_storage_2d<r32float, read_write>;
