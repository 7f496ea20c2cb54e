// Technique `yuksel`, the region pass (ours, before the pre-pass): the gather region for this
// frame's water, so that no frame reads heights on the CPU. The bound pass (region_bound.wgsl) has
// reduced the range of the floor hits' sideways offsets over every height texel; one thread adds
// flat water's, widens it by an eighth of the span each way and takes, at the finest level that
// holds it, the smallest odd run of offsets along each axis not fixed by the uniform. CPU twin:
// `region_bound` and `YukselSetup::region_from_bound` in caustics-core's yuksel/region.rs, step
// for step.

import package::shaders::optics::refract_dir;
import package::shaders::reduce::unordered;
import package::yuksel::common::{YukselRegion, u};

// ordered(-lo.x), ordered(-lo.y), ordered(hi.x), ordered(hi.y), or 0 where no texel refracted.
@group(0) @binding(1) var<storage, read> bound: array<u32, 4>;
@group(0) @binding(2) var<storage, read_write> out: YukselRegion;

const BIG: f32 = 3.0e38;
// `MAX_N`, `MAX_M` and `MAX_LEVEL` in core's yuksel/mod.rs.
const MAX_N: u32 = 31u;
const MAX_M: u32 = 30u;
const MAX_LEVEL: u32 = 3u;

// Along one axis: the offsets [-ceil(hi), -floor(lo)] (pixels), padded to an odd length, at most
// `limit` long. x: the length, y: the centre offset, z: 1 where clamped.
fn axis_region(lo: f32, hi: f32, limit: u32) -> vec3<i32> {
    if !(abs(lo) < BIG && abs(hi) < BIG) {
        return vec3<i32>(i32(limit), 0, 1);
    }
    let first = i32(-ceil(hi));
    var last = i32(-floor(lo));
    if ((last - first) & 1) == 1 {
        last += 1;
    }
    let len = last - first + 1;
    let centre = (first + last) / 2;
    if len > i32(limit) {
        return vec3<i32>(i32(limit), centre, 1);
    }
    return vec3<i32>(len, centre, 0);
}

@compute @workgroup_size(1)
fn main() {
    let l = u.light.xyz;
    let t0 = refract_dir(l, vec3<f32>(0.0, 0.0, 1.0), u.light.w);
    let flat = t0.xy / -t0.z * u.depth;
    var lo = flat;
    var hi = flat;
    // A value is 0 only where no texel gave one (the four are set together).
    if bound[2] != 0u {
        lo = min(lo, -vec2<f32>(unordered(bound[0]), unordered(bound[1])));
        hi = max(hi, vec2<f32>(unordered(bound[2]), unordered(bound[3])));
    }
    let margin = (hi - lo) * 0.125;
    let w_lo = lo - margin - flat;
    let w_hi = hi + margin - flat;
    // The finest level whose region holds the bound (both axes from the water only), while the
    // level divides the map's size.
    let from_water = u.n == 0u && u.m == 0xffffffffu;
    var level = 0u;
    loop {
        let pixel = u.pixel * f32(1u << level);
        let d_lo = w_lo / pixel;
        let d_hi = w_hi / pixel;
        var x = vec3<i32>(i32(u.n), 0, 0);
        if u.n == 0u {
            x = axis_region(d_lo.x, d_hi.x, MAX_N);
        }
        var y = vec3<i32>(i32(u.m) + 1, 0, 0);
        if u.m == 0xffffffffu {
            y = axis_region(d_lo.y, d_hi.y, MAX_M + 1u);
        }
        let clamped = (x.z | y.z) != 0;
        let next = 2u << level;
        if !clamped || !from_water || level == MAX_LEVEL || u.width % next != 0u || u.height % next != 0u {
            out.n = u32(x.x);
            out.m = u32(y.x - 1);
            out.shift = vec2<i32>(x.y, y.y);
            out.level = level;
            out.clamped = u32(clamped);
            return;
        }
        level += 1u;
    }
}
