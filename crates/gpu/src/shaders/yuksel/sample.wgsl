// Technique `yuksel`: one water sample refracted to the floor (the pre-pass's work, shared with the
// fused compute variant). CPU twin: `hit`, `footprint` and `prepass` in
// caustics-core/src/techniques/yuksel.rs.

@group(0) @binding(0) var<uniform> u: Yuksel;
@group(0) @binding(1) var heights: texture_2d<f32>;

// The narrowest footprint half-width (`MIN_HALF_WIDTH` in yuksel.rs): a fold's light keeps a box of
// positive area, and the half-width stays a normal f16 (so the packed channel is a normal f32).
const MIN_HALF_WIDTH: f32 = 1.0e-3;

// The water at `s` (world units): xy its floor hit, z the flux its area carries relative to flat
// water, w 1 where the sun lights it (0: nothing reaches the floor).
fn yuksel_hit(s: vec2<f32>) -> vec4<f32> {
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
    var fresnel = 1.0;
    if u.fresnel != 0u {
        fresnel = fresnel_transmittance(cos_i, 1.0, u.ior) / u.attenuation.w;
    }
    return vec4<f32>(s + t.xy * (z / -t.z), seen * fresnel, 1.0);
}

// Sample (a, b) of the k x k (k = `sub`) of map pixel (column c, row r), which may lie outside the map: where
// its light lands, x y the box's centre relative to the pixel's centre (pixels), z its two
// half-widths packed, w the flux it carries relative to a flat-water pixel. The box is the
// sample's footprint (its patch of water, 1/k of a pixel each way, maps to the floor between the
// hits of the patch's edge midpoints) or, without `footprint`, a box of the patch's size around
// its hit (the paper). `pixel`: the map pixel at the region's level.
fn yuksel_sample(c: i32, r: i32, a: u32, b: u32, sub: u32, pixel: vec2<f32>) -> vec4<f32> {
    let k = f32(sub);
    let pixel_centre = (vec2<f32>(f32(c), f32(r)) + 0.5) * pixel;
    let within = (vec2<f32>(f32(a), f32(b)) + 0.5) / k - 0.5;
    let s = pixel_centre + within * pixel + u.centre_offset;
    let h = yuksel_hit(s);
    if h.w == 0.0 {
        return vec4<f32>(0.0, 0.0, bitcast<f32>(pack2x16float(vec2<f32>(0.5))), 0.0);
    }
    var centre = h.xy;
    var half = vec2<f32>(0.5 / k);
    if u.footprint != 0u {
        let side = pixel / k;
        let xm = yuksel_edge(s - vec2<f32>(0.5 * side.x, 0.0), h.xy);
        let xp = yuksel_edge(s + vec2<f32>(0.5 * side.x, 0.0), h.xy);
        let ym = yuksel_edge(s - vec2<f32>(0.0, 0.5 * side.y), h.xy);
        let yp = yuksel_edge(s + vec2<f32>(0.0, 0.5 * side.y), h.xy);
        centre = vec2<f32>(xm.x + xp.x, ym.y + yp.y) * 0.5;
        half = vec2<f32>(abs(xp.x - xm.x), abs(yp.y - ym.y)) * 0.5 / pixel;
    }
    let packed = pack2x16float(clamp(half, vec2<f32>(MIN_HALF_WIDTH), vec2<f32>(6.0e4)));
    let d = (centre - pixel_centre) / pixel;
    return vec4<f32>(d, bitcast<f32>(packed), h.z / (k * k));
}

// A patch edge's floor hit, or the sample's own where the sun cannot light the edge.
fn yuksel_edge(s: vec2<f32>, own: vec2<f32>) -> vec2<f32> {
    let h = yuksel_hit(s);
    if h.w == 0.0 {
        return own;
    }
    return h.xy;
}
