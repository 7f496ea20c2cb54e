// Technique `yuksel`: one water sample refracted to the floor (the pre-pass's work, shared with the
// fused compute variant). CPU twin: `prepass` in caustics-core/src/techniques/yuksel.rs.

@group(0) @binding(0) var<uniform> u: Yuksel;
@group(0) @binding(1) var heights: texture_2d<f32>;

// The sample of map pixel (column c, row r), which may lie outside the map: the offset of its floor
// hit from its pixel centre in pixels, and the flux it carries relative to flat water.
// `pixel`: the map pixel at the region's level.
fn yuksel_sample(c: i32, r: i32, pixel: vec2<f32>) -> vec4<f32> {
    let pixel_centre = (vec2<f32>(f32(c), f32(r)) + 0.5) * pixel;
    let s = pixel_centre + u.centre_offset;
    let hg = grid_sample(heights, s, u.size, u.wrap != 0u);
    let l = u.light.xyz;
    let normal = height_field_normal(hg.yz);
    let cos_i = -dot(l, normal);
    let seen = 1.0 + dot(l.xy, hg.yz) / -l.z;
    let t = refract_dir(l, normal, u.light.w);
    if t.w == 0.0 || cos_i <= 0.0 || seen <= 0.0 {
        return vec4<f32>(0.0);
    }
    let z = u.depth + hg.x;
    let hit = s + t.xy * (z / -t.z);
    let delta = (hit - pixel_centre) / pixel;
    var fresnel = 1.0;
    if u.fresnel != 0u {
        fresnel = fresnel_transmittance(cos_i, 1.0, u.ior) / u.attenuation.w;
    }
    return vec4<f32>(delta, seen * fresnel, 0.0);
}
