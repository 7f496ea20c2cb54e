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

// Where the light of the patch of water `area` (world units) around `s` lands, in `rec`: the
// footprint's centre (world units) in xy, its two half-widths packed in z (in pixels of `pixel`,
// the level's), the flux it carries relative to a flat-water patch in w; and the box's misfit. The
// box is the footprint (the patch's edge midpoints' hits along x and along y, on the light's
// centroid) or, without
// `footprint`, a box of the patch's size around its hit (the paper). Where the sun cannot light the
// patch, no flux. CPU twin: `footprint` and `misfit` in yuksel.rs.
struct YukselFootprint {
    rec: vec4<f32>,
    misfit: f32,
}

fn yuksel_footprint(s: vec2<f32>, area: vec2<f32>, pixel: vec2<f32>) -> YukselFootprint {
    let h = yuksel_hit(s);
    if h.w == 0.0 {
        return YukselFootprint(vec4<f32>(0.0), 0.0);
    }
    if u.footprint == 0u {
        let half = 0.5 * area / pixel;
        let packed = pack2x16float(clamp(half, vec2<f32>(MIN_HALF_WIDTH), vec2<f32>(6.0e4)));
        return YukselFootprint(vec4<f32>(h.xy, bitcast<f32>(packed), h.z), 0.0);
    }
    let xm = yuksel_edge(s - vec2<f32>(0.5 * area.x, 0.0), h.xy);
    let xp = yuksel_edge(s + vec2<f32>(0.5 * area.x, 0.0), h.xy);
    let ym = yuksel_edge(s - vec2<f32>(0.0, 0.5 * area.y), h.xy);
    let yp = yuksel_edge(s + vec2<f32>(0.0, 0.5 * area.y), h.xy);
    let centre = vec2<f32>(xm.x + xp.x, ym.y + yp.y) * 0.5;
    let half = abs(vec2<f32>(xp.x - xm.x, yp.y - ym.y)) * 0.5 / pixel;
    // The hit off the box's centre plus half the shear the box ignores, over the box's width (at
    // least a map pixel: `u.pixel / pixel` of the level's).
    let off = vec2<f32>(
        abs(h.x - centre.x) + 0.5 * abs(yp.x - ym.x),
        abs(h.y - centre.y) + 0.5 * abs(xp.y - xm.y),
    ) / pixel;
    let width = max(2.0 * half, vec2<f32>(u.pixel.x / pixel.x));
    let packed = pack2x16float(clamp(half, vec2<f32>(MIN_HALF_WIDTH), vec2<f32>(6.0e4)));
    // The box on the light's centroid, for a map quadratic over the patch.
    let centroid = h.xy + ((xm + xp) * 0.5 - h.xy + (ym + yp) * 0.5 - h.xy) / 3.0;
    return YukselFootprint(vec4<f32>(centroid, bitcast<f32>(packed), h.z), max(off.x / width.x, off.y / width.y));
}

// The centre of pixel (column c, row r) of the level's map (pixel `pixel`), which may lie outside
// the map.
fn yuksel_pixel_centre(c: i32, r: i32, pixel: vec2<f32>) -> vec2<f32> {
    return (vec2<f32>(f32(c), f32(r)) + 0.5) * pixel;
}

// Footprint (a, b) of the t x t of pixel (c, r): its patch 1/t of the pixel each way.
fn yuksel_part(c: i32, r: i32, a: u32, b: u32, t: u32, pixel: vec2<f32>) -> YukselFootprint {
    let within = (vec2<f32>(f32(a), f32(b)) + 0.5) / f32(t) - 0.5;
    let s = yuksel_pixel_centre(c, r, pixel) + within * pixel + u.centre_offset;
    return yuksel_footprint(s, pixel / f32(t), pixel);
}

// A footprint of pixel (c, r) as the pre-pass stores it, one of its t x t (of k x k at most): its
// centre relative to the pixel's centre (pixels), its packed half-widths with the pixel's tier in
// their sign bits (`tier_bits`), its flux times its share 1/t².
fn yuksel_record(f: YukselFootprint, c: i32, r: i32, t: u32, k: u32, pixel: vec2<f32>) -> vec4<f32> {
    let bits = tier_bits(t, k);
    if f.rec.w == 0.0 {
        return vec4<f32>(0.0, 0.0, bitcast<f32>(pack2x16float(vec2<f32>(0.5)) | bits), 0.0);
    }
    let d = (f.rec.xy - yuksel_pixel_centre(c, r, pixel)) / pixel;
    return vec4<f32>(d, bitcast<f32>(bitcast<u32>(f.rec.z) | bits), f.rec.w / f32(t * t));
}

// The records `yuksel_tier` made, in the order of their t x t (up to 8 x 8).
var<private> tier_records: array<vec4<f32>, 64>;

// How many footprints a side pixel (c, r) takes (of k at most), its records in `tier_records`:
// with `u.split` >= 0, the first of 1, 2, 4 ... k whose footprints all misfit by no more than
// `u.split` (a tier stops at its first footprint that misfits); otherwise k. At k (weighed by
// nothing) only the first `at_k` records are made. CPU twin: `prepass` in yuksel.rs.
fn yuksel_tier(c: i32, r: i32, k: u32, pixel: vec2<f32>, at_k: u32) -> u32 {
    var t = select(k, 1u, u.split >= 0.0 && k > 1u);
    loop {
        var misfits = false;
        for (var q = 0u; q < select(t * t, at_k, t >= k); q++) {
            let f = yuksel_part(c, r, q % t, q / t, t, pixel);
            tier_records[q] = yuksel_record(f, c, r, t, k, pixel);
            if t < k && f.rec.w != 0.0 && f.misfit > u.split {
                misfits = true;
                break;
            }
        }
        if !misfits {
            return t;
        }
        t = min(2u * t, k);
    }
    return t;
}

// A patch edge's floor hit, or the patch's own where the sun cannot light the edge.
fn yuksel_edge(s: vec2<f32>, own: vec2<f32>) -> vec2<f32> {
    let h = yuksel_hit(s);
    if h.w == 0.0 {
        return own;
    }
    return h.xy;
}
