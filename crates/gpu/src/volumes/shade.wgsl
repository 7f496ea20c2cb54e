// Technique `volumes`, Eq. 4 over the diffuse map: the diffuse map is the object's colour where its
// depth texture is covered, and the final colour Io = Id (Ic + Ia). CPU twins: `diffuse_map` and
// `shade_pass` in caustics-core/src/techniques/volumes/.

import package::volumes::common::{Pass, covered};

@group(0) @binding(0) var<uniform> obj: Pass;
@group(0) @binding(1) var depth: texture_2d<f32>;
@group(0) @binding(2) var caustics: texture_2d<f32>;
@group(0) @binding(3) var out_diffuse: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var out_image: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let res = u32(obj.view.a.w);
    if id.x >= res || id.y >= res {
        return;
    }
    let ij = vec2<i32>(id.xy);
    var d = vec4<f32>(0.0);
    var io = vec4<f32>(0.0);
    if covered(textureLoad(depth, ij, 0)) {
        d = vec4<f32>(obj.albedo.xyz, 1.0);
        io = vec4<f32>(d.xyz * (textureLoad(caustics, ij, 0).xyz + obj.albedo.w), 1.0);
    }
    textureStore(out_diffuse, ij, d);
    textureStore(out_image, ij, io);
}
