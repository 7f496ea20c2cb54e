struct RippleStep {
    courant2: f32,
    gamma: f32,
    wrap: u32,
    _pad: u32
}

fn cur_at(i: u32, j: u32) -> f32 {
    return textureLoad(current, vec2<u32>(j, i), 0).r;
}

@group(0) @binding(1)
var current: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(current);
    let i = id.y;
    let j = id.x;
    if i >= size.y || j >= size.x {
        return;
    }
    let north = neighbour(i, 1, size.y);
    let south = neighbour(i, -1, size.y);
    let east = neighbour(j, 1, size.x);
    let west = neighbour(j, -1, size.x);
    let prev = textureLoad(previous, id.xy).r;
    let next = update_cell(prev, cur_at(i, j), cur_at(north, j), cur_at(south, j), cur_at(i, east), cur_at(i, west), params.courant2, params.gamma);
    textureStore(previous, id.xy, vec4<f32>(next, 0.0, 0.0, 0.0));
}

fn neighbour(a: u32, d: i32, n: u32) -> u32 {
    let b = i32(a) + d;
    if params.wrap != 0u {
        return u32((b + i32(n)) % i32(n));
    }
    return u32(clamp(b, 0, i32(n) - 1));
}

@group(0) @binding(0)
var<uniform> params: RippleStep;

@group(0) @binding(2)
var previous: texture_storage_2d<r32float, read_write>;

fn update_cell(prev: f32, cur: f32, n: f32, s: f32, e: f32, w: f32, courant2: f32, gamma: f32) -> f32 {
    let laplacian = (n + s) + (e + w) - 4.0 * cur;
    return (2.0 * cur - (1.0 - gamma) * prev + courant2 * laplacian) / (1.0 + gamma);
}
