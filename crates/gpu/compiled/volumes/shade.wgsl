@group(0) @binding(2)
var caustics: texture_2d<f32>;

@group(0) @binding(1)
var depth: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let res = u32(obj.view.a.w);
    if id.x >= res || id.y >= res {
        return;
    }
    let ij = vec2<i32>(id.xy);
    var d = vec4<f32>(0.0);
    var io = vec4<f32>(0.0);
    if package_volumes_common_covered(textureLoad(depth, ij, 0)) {
        d = vec4<f32>(obj.albedo.xyz, 1.0);
        io = vec4<f32>(d.xyz * (textureLoad(caustics, ij, 0).xyz + obj.albedo.w), 1.0);
    }
    textureStore(out_diffuse, ij, d);
    textureStore(out_image, ij, io);
}

@group(0) @binding(0)
var<uniform> obj: package_volumes_common_Pass;

@group(0) @binding(3)
var out_diffuse: texture_storage_2d<rgba32float, write>;

@group(0) @binding(4)
var out_image: texture_storage_2d<rgba32float, write>;

struct package_volumes_common_Pass {
    view: package_volumes_common_View,
    cells: vec4<u32>,
    planes: u32,
    root_first: u32,
    root_count: u32,
    _pad: u32,
    albedo: vec4<f32>
}

struct package_volumes_common_View {
    a: vec4<f32>,
    b: vec4<f32>,
    v: vec4<f32>,
    lo: vec4<f32>,
    texel: vec4<f32>
}

fn package_volumes_common_covered(t: vec4<f32>) -> bool {
    return t.y != 0.0 || t.z != 0.0 || t.w != 0.0;
}
