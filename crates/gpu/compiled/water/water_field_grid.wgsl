@group(0) @binding(0)
var<uniform> field: package_water__1water_field_FieldParams;

@group(0) @binding(1)
var grid: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(output);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let p = package_water__1water_field__1field_point(field, id.xy, dims);
    let h = package_shaders_water__1grid_sample(grid, p, field.grid_size, field.wrap != 0u).x;
    textureStore(output, id.xy, vec4<f32>(field.amplitude * h, 0.0, 0.0, 0.0));
}

@group(0) @binding(2)
var output: texture_storage_2d<r32float, write>;

fn package_shaders_water__1catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

fn package_shaders_water__1grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

fn package_shaders_water__1grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = package_shaders_water__1catmull_rom(f.x);
    let wv = package_shaders_water__1catmull_rom(f.y);
    let n = vec2<i32>(dims);
    var first = vec2<i32>(base) - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    var h = 0.0;
    var hu = 0.0;
    var hv = 0.0;
    for (var a = 0; a < 4; a++) {
        let row = package_shaders_water__1grid_index(first.y, a, n.y, wrap);
        for (var b = 0; b < 4; b++) {
            let s = textureLoad(tex, vec2<i32>(package_shaders_water__1grid_index(first.x, b, n.x, wrap), row), 0).r;
            h += wu[0][b] * wv[0][a] * s;
            hu += wu[1][b] * wv[0][a] * s;
            hv += wu[0][b] * wv[1][a] * s;
        }
    }
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

struct package_water__1water_field_FieldParams {
    size: f32,
    grid_size: f32,
    amplitude: f32,
    wave_count: u32,
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32
}

fn package_water__1water_field__1field_point(params: package_water__1water_field_FieldParams, id: vec2<u32>, dims: vec2<u32>) -> vec2<f32> {
    return (vec2<f32>(id) + 0.5) * params.size / vec2<f32>(dims);
}
