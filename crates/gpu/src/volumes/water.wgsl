// Technique `volumes`, the water pass: refraction at every lattice vertex of the surface (the
// bicubic interpolant of the height texture). CPU twin: `water_vertex` in
// caustics-core/src/techniques/volumes/illumination.rs.

import package::shaders::optics::{fresnel_transmittance, height_field_normal, refract_dir};
import package::shaders::water::grid_sample;
import package::volumes::common::{Volumes, WaterVertex};

@group(0) @binding(0) var<uniform> c: Volumes;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> water: array<WaterVertex>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = c.dims.x + 1u;
    let count = w * (c.dims.y + 1u);
    if id.x >= count {
        return;
    }
    let i = id.x / w;
    let j = id.x % w;
    let p = c.lattice.xy + vec2<f32>(f32(j), f32(i)) * c.lattice.z;
    let hg = grid_sample(heights, p, c.lattice.w, c.flags.x != 0u);
    let n = height_field_normal(hg.yz);
    let l = c.light.xyz;
    let cos_i = -dot(l, n);
    let z = c.params.x + hg.x;
    let t = refract_dir(l, n, c.light.w);
    var v: WaterVertex;
    v.pos = vec4<f32>(p, z, 0.0);
    v.dir = vec4<f32>(0.0, 0.0, -1.0, 0.0);
    if t.w != 0.0 && cos_i > 0.0 {
        var weight = 1.0;
        if c.params.w != 0.0 {
            weight = fresnel_transmittance(cos_i, 1.0, c.params.y) / c.absorption.w;
        }
        v.pos.w = weight;
        v.dir = vec4<f32>(t.xyz, 0.0);
    }
    water[id.x] = v;
}
