// Technique `yuksel`, the region pass (ours, before the pre-pass): the gather region for this
// frame's water, so that no frame reads heights on the CPU. One workgroup refracts the sun through
// every height texel's normal (central differences) and reduces the range of the floor hits'
// sideways offsets, as caustic-triangles' copy band reduces its slope; thread 0 widens it by an
// eighth of the span each way and takes, at the finest level that holds it, the smallest odd run
// of offsets along each axis not fixed by the uniform. CPU twin: `region_bound` and
// `YukselSetup::region_from_bound` in caustics-core's yuksel.rs, step for step.

@group(0) @binding(0) var<uniform> u: Yuksel;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> out: YukselRegion;

const THREADS: u32 = 256u;
const BIG: f32 = 3.0e38;
// `MAX_N`, `MAX_M` and `MAX_LEVEL` in yuksel.rs.
const MAX_N: u32 = 31u;
const MAX_M: u32 = 30u;
const MAX_LEVEL: u32 = 3u;

var<workgroup> lows: array<vec2<f32>, 256>;
var<workgroup> highs: array<vec2<f32>, 256>;

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

@compute @workgroup_size(256)
fn main(@builtin(local_invocation_index) t: u32) {
    let dims = textureDimensions(heights);
    let cols = max(dims.x, 1u);
    let rows = max(dims.y, 1u);
    let dx = u.size / f32(cols);
    let dy = u.size / f32(rows);
    let l = u.light.xyz;
    let t0 = refract_dir(l, vec3<f32>(0.0, 0.0, 1.0), u.light.w);
    let flat = t0.xy / -t0.z * u.depth;
    var lo = flat;
    var hi = flat;
    for (var k = t; k < dims.x * dims.y; k += THREADS) {
        let i = k / dims.x;
        let j = k % dims.x;
        let h = textureLoad(heights, vec2<u32>(j, i), 0).x;
        let e = textureLoad(heights, vec2<u32>((j + 1u) % cols, i), 0).x;
        let w = textureLoad(heights, vec2<u32>((j + cols - 1u) % cols, i), 0).x;
        let n = textureLoad(heights, vec2<u32>(j, (i + 1u) % rows), 0).x;
        let s = textureLoad(heights, vec2<u32>(j, (i + rows - 1u) % rows), 0).x;
        let normal = height_field_normal(vec2<f32>((e - w) / (2.0 * dx), (n - s) / (2.0 * dy)));
        let tr = refract_dir(l, normal, u.light.w);
        if -dot(l, normal) > 0.0 && tr.w != 0.0 && tr.z < 0.0 {
            let d = tr.xy / -tr.z * max(u.depth + h, 0.0);
            lo = min(lo, d);
            hi = max(hi, d);
        }
    }
    lows[t] = lo;
    highs[t] = hi;
    workgroupBarrier();
    for (var s = THREADS / 2u; s > 0u; s /= 2u) {
        if t < s {
            lows[t] = min(lows[t], lows[t + s]);
            highs[t] = max(highs[t], highs[t + s]);
        }
        workgroupBarrier();
    }
    if t != 0u {
        return;
    }
    let margin = (highs[0] - lows[0]) * 0.125;
    let w_lo = lows[0] - margin - flat;
    let w_hi = highs[0] + margin - flat;
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
