struct Lookup {
    floor: vec4<f32>,
    absorption: vec4<f32>
}

@group(0) @binding(1)
var deposit: texture_2d<f32>;

fn deposit_at(q: vec2<f32>) -> vec3<f32> {
    let dims = vec2<i32>(textureDimensions(deposit));
    let x = q / u.floor.x * vec2<f32>(dims) - 0.5;
    let c = floor(x);
    let f = x - c;
    var a = vec2<i32>(c);
    var b = a + 1;
    if u.floor.y != 0.0 {
        a = ((a % dims) + dims) % dims;
        b = select(a + 1, vec2<i32>(0), a + 1 == dims);
    }
    else {
        a = clamp(a, vec2<i32>(0), dims - 1);
        b = clamp(b, vec2<i32>(0), dims - 1);
    }
    let t00 = textureLoad(deposit, a, 0).xyz;
    let t10 = textureLoad(deposit, vec2<i32>(b.x, a.y), 0).xyz;
    let t01 = textureLoad(deposit, vec2<i32>(a.x, b.y), 0).xyz;
    let t11 = textureLoad(deposit, b, 0).xyz;
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

@group(0) @binding(3)
var floor_map: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let dims = textureDimensions(floor_map);
    if id.x >= dims.x || id.y >= dims.y {
        return;
    }
    let t = textureLoad(texels, vec2<i32>(id.xy), 0);
    var rgb = vec3<f32>(0.0);
    if t.z > 0.0 {
        rgb = deposit_at(t.xy) * t.z * exp(-u.absorption.xyz * t.w);
    }
    textureStore(floor_map, vec2<i32>(id.xy), vec4<f32>(rgb, 1.0));
}

@group(0) @binding(2)
var texels: texture_2d<f32>;

@group(0) @binding(0)
var<uniform> u: Lookup;
