// Technique `procedural` (paper 2, Sanchez-Crespo): the uniform block, the bindings and the per-point
// caustic every evaluating pass shares. Mirrors `ProceduralUniform` in procedural/mod.rs and
// `ProceduralSetup`, `trace` and `caustic_at` in caustics-core/src/techniques/procedural/.

import package::shaders::optics::{height_field_normal, refract_dir};
import package::shaders::water::{ProceduralWave, grid_sample, procedural_wave};

struct Procedural {
    sun_x: vec4<f32>,      // xyz: e1 of the sun frame (its tangent plane)
    sun_y: vec4<f32>,      // xyz: e2
    sun_z: vec4<f32>,      // xyz: unit direction toward the sun
    up: vec4<f32>,         // xyz: unit gathering ray, floor to surface ((0, 0, 1): the paper's)
    absorption: vec4<f32>, // rgb: K per channel (0 without the option); w: `ground`
    wave: ProceduralWave,  // the paper's wave function (source 1)
    size: f32,             // the floor square's side
    depth: f32,            // rest depth
    ior: f32,              // water to air: eta = ior
    extent: f32,           // E: the light map spans uv in [-E, E]^2
    width: u32,            // the map
    height: u32,
    target_size: u32,      // the texture variant's target
    mesh: u32,             // the vertex variant's quads per side
    source: u32,           // 0: height grid (bicubic), 1: the paper's wave function
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
}

@group(0) @binding(0) var<uniform> u: Procedural;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var light_map: texture_2d<f32>;

// Height and gradient of the water at p.
fn water_at(p: vec2<f32>) -> vec3<f32> {
    if u.source == 1u {
        return procedural_wave(u.wave, p);
    }
    return grid_sample(heights, p, u.size, u.wrap != 0u);
}

fn light_texel(c: vec2<i32>, dims: vec2<i32>) -> f32 {
    if any(c < vec2<i32>(0)) || any(c >= dims) {
        return 0.0;
    }
    return textureLoad(light_map, c, 0).r;
}

// Bilinear lookup of the light map at texel centres, 0 beyond it (by hand: the same arithmetic as
// the CPU twin, and an R32Float map needs no float filtering).
fn light_lookup(uv: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(light_map));
    let t = (uv / u.extent * 0.5 + 0.5) * vec2<f32>(dims) - 0.5;
    let b = floor(t);
    let f = t - b;
    let c = vec2<i32>(b);
    let top = mix(light_texel(c, dims), light_texel(c + vec2<i32>(1, 0), dims), f.x);
    let bottom = mix(light_texel(c + vec2<i32>(0, 1), dims), light_texel(c + vec2<i32>(1, 1), dims), f.x);
    return mix(top, bottom, f.y);
}

// The caustic at floor point p: up the gathering ray to the surface (line-plane intercept with the
// rest level; exact for the vertical ray), the normal from the exact gradient, Snell reversed from
// the water into the air, the light map in the refracted direction, the absorption on the way.
fn procedural_caustic(p: vec2<f32>) -> vec3<f32> {
    let up = u.up.xyz;
    let s = p + up.xy * (u.depth / up.z);
    let hg = water_at(s);
    let n = height_field_normal(hg.yz);
    let r = refract_dir(up, -n, u.ior);
    var e = 0.0;
    let z = dot(r.xyz, u.sun_z.xyz);
    if r.w != 0.0 && z > 0.0 {
        let uv = vec2<f32>(dot(r.xyz, u.sun_x.xyz), dot(r.xyz, u.sun_y.xyz)) / z;
        e = light_lookup(uv);
    }
    let d = (u.depth + hg.x) / up.z;
    // The paper's additive blend over the lit ground; `absorption.w` holds `ground`.
    let ground = u.absorption.w;
    return (ground + (1.0 - ground) * e) * exp(-u.absorption.rgb * d);
}

// One triangle covering the render target.
fn full_screen(v: u32) -> vec4<f32> {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - 1.0;
    return vec4<f32>(xy, 0.0, 1.0);
}
