// Technique `yuksel`: one water sample refracted to the floor (the pre-pass's work, shared with the
// scatter variant). CPU twin: `hit`, `footprint` and `prepass` in
// caustics-core/src/techniques/yuksel/prepass.rs.

import package::shaders::optics::{fresnel_transmittance, height_field_normal, refract_dir};
import package::shaders::receivers::{light_space, meet_receivers};
import package::shaders::water::grid_sample_hermite;
import package::yuksel::common::{tier_bits, u};

// The heights in Hermite form (`water_patches.wgsl`).
@group(0) @binding(1) var patches: texture_2d<f32>;
// The receivers' heights in the light's space (1 x 1 where the floor is the plane z = 0).
@group(0) @binding(8) var receiver_heights: texture_2d<f32>;

// The narrowest footprint half-width (`MIN_HALF_WIDTH` in prepass.rs): a fold's light keeps a box
// of positive area, and the half-width stays a normal f16 (so the packed channel is a normal f32).
const MIN_HALF_WIDTH: f32 = 1.0e-3;
// How much a patch's flux may change across it against the split (`RAMP_WEIGHT` in prepass.rs).
const RAMP_WEIGHT: f32 = 4.0;

// The water at `s` (world units): xy its floor hit, z the flux its area carries relative to flat
// water, w 1 where the sun lights it (0: nothing reaches the floor).
fn yuksel_hit(s: vec2<f32>) -> vec4<f32> {
    let hg = grid_sample_hermite(patches, s, u.size, u.wrap != 0u);
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
    if u.receivers.t0.w != 0.0 {
        let start = vec3<f32>(s, z);
        let d = meet_receivers(receiver_heights, u.receivers, start, t.xyz);
        if d < 0.0 {
            return vec4<f32>(0.0);
        }
        return vec4<f32>(light_space(start + t.xyz * d, u.receivers.t0.xyz), seen * fresnel, 1.0);
    }
    return vec4<f32>(s + t.xy * (z / -t.z), seen * fresnel, 1.0);
}

// Where the light of a patch of water lands, in `rec`: the footprint's centre (world units) in xy,
// its two half-widths packed in z (in pixels of `pixel`, the level's), the flux it carries
// relative to a flat-water patch in w; and the box's misfit. The box is the footprint (the
// patch's edge midpoints' hits along x and along y, on the light's centroid) or, without
// `footprint`, a box of the patch's size around its hit (the paper). Where the sun cannot light
// the patch, no flux. CPU twin: `footprint` and `misfit` in prepass.rs.
struct YukselFootprint {
    rec: vec4<f32>,
    misfit: f32,
}

// The footprint of a lit patch (`h`, its hit) from its edge midpoints' hits as `yuksel_hit` gives
// them (along x then along y, minus side first), which neighbouring patches share.
fn yuksel_footprint(h: vec4<f32>, raw_xm: vec4<f32>, raw_xp: vec4<f32>, raw_ym: vec4<f32>, raw_yp: vec4<f32>, pixel: vec2<f32>) -> YukselFootprint {
    // An edge the sun cannot light takes the patch's own hit and flux, and the box cannot stand
    // for the patch (below k, a finer tier takes it).
    let exm = yuksel_edge(raw_xm, h);
    let exp = yuksel_edge(raw_xp, h);
    let eym = yuksel_edge(raw_ym, h);
    let eyp = yuksel_edge(raw_yp, h);
    let unlit = exm.w == 0.0 || exp.w == 0.0 || eym.w == 0.0 || eyp.w == 0.0;
    let xm = exm.xy;
    let xp = exp.xy;
    let ym = eym.xy;
    let yp = eyp.xy;
    let mid_x = (xm + xp) * 0.5;
    let mid_y = (ym + yp) * 0.5;
    let half = abs(vec2<f32>(xp.x - xm.x, yp.y - ym.y)) * 0.5 / pixel;
    // The hit off each axis's edge midpoints' mean (the map bends) plus half the shear the box
    // ignores, over the box's width (at least a map pixel: `u.pixel / pixel` of the level's).
    let bend = abs(h.xy - mid_x) + abs(h.xy - mid_y);
    let shear = vec2<f32>(abs(yp.x - ym.x), abs(xp.y - xm.y)) * 0.5;
    let off = (bend + shear) / pixel;
    let width = max(2.0 * half, vec2<f32>(u.pixel.x / pixel.x));
    // The flux's change across the patch, weighted (`RAMP_WEIGHT` in prepass.rs).
    let ramp = max(abs(exp.z - exm.z), abs(eyp.z - eym.z)) / max(h.z, 1.0e-30);
    var misfit = max(max(off.x / width.x, off.y / width.y), RAMP_WEIGHT * ramp);
    if unlit {
        misfit = 3.0e38;
    }
    let packed = pack2x16float(clamp(half, vec2<f32>(MIN_HALF_WIDTH), vec2<f32>(6.0e4)));
    // The box on the light's centroid, for a map quadratic and a flux linear over the patch.
    let centroid = h.xy + (mid_x - h.xy + mid_y - h.xy) / 3.0
        + ((xp - xm) * (exp.z - exm.z) + (yp - ym) * (eyp.z - eym.z)) / (12.0 * h.z);
    return YukselFootprint(vec4<f32>(centroid, bitcast<f32>(packed), h.z), misfit);
}

// A patch edge's `yuksel_hit` `h`, or where the sun cannot light the edge the patch's own hit and
// flux with w = 0.
fn yuksel_edge(h: vec4<f32>, own: vec4<f32>) -> vec4<f32> {
    if h.w == 0.0 {
        return vec4<f32>(own.xyz, 0.0);
    }
    return h;
}

// The centre of pixel (column c, row r) of the level's map (pixel `pixel`), which may lie outside
// the map.
fn yuksel_pixel_centre(c: i32, r: i32, pixel: vec2<f32>) -> vec2<f32> {
    return (vec2<f32>(f32(c), f32(r)) + 0.5) * pixel;
}

// The water at (i, j) halves of a 1/t patch from pixel (c, r)'s corner: (2a + 1, 2b + 1) is
// footprint (a, b)'s centre, (2a, 2b + 1) its edge midpoint on the minus side along x. Every pass
// that refracts a point places it this way, so a point two patches share is one ray, to the bit.
fn yuksel_lattice(c: i32, r: i32, i: u32, j: u32, t: u32, pixel: vec2<f32>) -> vec2<f32> {
    let within = vec2<f32>(f32(i), f32(j)) / f32(2u * t) - 0.5;
    return yuksel_pixel_centre(c, r, pixel) + within * pixel + u.centre_offset;
}

// Footprint (a, b) of the t x t of pixel (c, r): its patch 1/t of the pixel each way.
fn yuksel_part(c: i32, r: i32, a: u32, b: u32, t: u32, pixel: vec2<f32>) -> YukselFootprint {
    let i = 2u * a + 1u;
    let j = 2u * b + 1u;
    let h = yuksel_hit(yuksel_lattice(c, r, i, j, t, pixel));
    if h.w == 0.0 {
        return YukselFootprint(vec4<f32>(0.0), 0.0);
    }
    if u.footprint == 0u {
        return yuksel_pixel_box(h, pixel / f32(t), pixel);
    }
    return yuksel_footprint(
        h,
        yuksel_hit(yuksel_lattice(c, r, i - 1u, j, t, pixel)),
        yuksel_hit(yuksel_lattice(c, r, i + 1u, j, t, pixel)),
        yuksel_hit(yuksel_lattice(c, r, i, j - 1u, t, pixel)),
        yuksel_hit(yuksel_lattice(c, r, i, j + 1u, t, pixel)),
        pixel,
    );
}

// Without `footprint`, the paper's box: the patch's size (`area`) around its hit `h`.
fn yuksel_pixel_box(h: vec4<f32>, area: vec2<f32>, pixel: vec2<f32>) -> YukselFootprint {
    let half = 0.5 * area / pixel;
    let packed = pack2x16float(clamp(half, vec2<f32>(MIN_HALF_WIDTH), vec2<f32>(6.0e4)));
    return YukselFootprint(vec4<f32>(h.xy, bitcast<f32>(packed), h.z), 0.0);
}

// Footprint (a, b) of the t x t of pixel (c, r) as the pre-pass stores it (of k x k at most): its
// centre relative to the pixel's centre (pixels), its packed half-widths with the pixel's tier in
// their sign bits (`tier_bits`), its flux times its share 1/t². Between the pool's walls a patch
// beyond them carries no light, though its footprint still chose the pixel's tier (CPU twin:
// `footprint` in prepass.rs).
fn yuksel_record(f: YukselFootprint, c: i32, r: i32, a: u32, b: u32, t: u32, k: u32, pixel: vec2<f32>) -> vec4<f32> {
    let bits = tier_bits(t, k);
    let s = yuksel_lattice(c, r, 2u * a + 1u, 2u * b + 1u, t, pixel);
    let beyond = u.walls != 0u && (any(s < vec2<f32>(0.0)) || any(s > vec2<f32>(u.size)));
    if f.rec.w == 0.0 || beyond {
        return vec4<f32>(0.0, 0.0, bitcast<f32>(pack2x16float(vec2<f32>(0.5)) | bits), 0.0);
    }
    let d = (f.rec.xy - yuksel_pixel_centre(c, r, pixel)) / pixel;
    return vec4<f32>(d, bitcast<f32>(bitcast<u32>(f.rec.z) | bits), f.rec.w / f32(t * t));
}

// The records `yuksel_tier` made, in the order of their t x t (below k, t is at most 4; at k it
// makes at most one).
var<private> tier_records: array<vec4<f32>, 16>;

// How many footprints a side pixel (c, r) takes (of k at most), its records in `tier_records`:
// with `u.split` >= 0, the first of 1, 2, 4 ... k whose footprints all misfit by no more than
// `u.split` (a tier stops at its first footprint that misfits or that the sun cannot light);
// otherwise k. At k (weighed by
// nothing) only the first `at_k` records are made. CPU twin: `prepass` in prepass.rs.
fn yuksel_tier(c: i32, r: i32, k: u32, pixel: vec2<f32>, at_k: u32) -> u32 {
    var t = select(k, 1u, u.split >= 0.0 && k > 1u);
    loop {
        var misfits = false;
        for (var q = 0u; q < select(t * t, at_k, t >= k); q++) {
            let f = yuksel_part(c, r, q % t, q / t, t, pixel);
            tier_records[q] = yuksel_record(f, c, r, q % t, q / t, t, k, pixel);
            if t < k && (f.rec.w == 0.0 || f.misfit > u.split) {
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
