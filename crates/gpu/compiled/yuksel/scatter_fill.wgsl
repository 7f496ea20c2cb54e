@group(0) @binding(4)
var<storage, read> fill_args: array<u32, 4>;

@group(0) @binding(5)
var<storage, read> fill_list: array<u32>;

@compute @workgroup_size(package_yuksel_fill__1FILL_GROUP)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = package_yuksel_common__1level_subsamples(package_yuksel_scatter_region.level);
    let area = package_yuksel_common__1prepass_area(package_yuksel_scatter_region.n, package_yuksel_scatter_region.m, package_yuksel_scatter_region.level);
    let pixel = package_yuksel_common_u.pixel * f32(1u << package_yuksel_scatter_region.level);
    for (var entry = id.x; entry < fill_args[3]; entry += package_yuksel_fill__1FILL_STRIDE) {
        let q = package_yuksel_common__2prepass_level_pixel(package_yuksel_fill__1fill_listed(fill_list[entry], area), package_yuksel_scatter_region);
        for (var b = 0u; b < k; b++) {
            package_yuksel_fill__2yuksel_fill_row(q, b, k, pixel);
            for (var a = 0u; a < k; a++) {
                package_yuksel_scatter__1add_record(package_yuksel_fill__1fill_row[a], q);
            }
        }
    }
}

fn package_shaders_optics__1fresnel_transmittance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = min(abs(cos_i_in), 1.0);
    let sin_t = n1 / n2 * sqrt(max(1.0 - cos_i * cos_i, 0.0));
    if sin_t >= 1.0 {
        return 0.0;
    }
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 1.0 - 0.5 * (rs * rs + rp * rp);
}

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
}

struct package_shaders_receivers_Bracket {
    a: f32,
    ga: f32,
    b: f32,
    gb: f32,
    kept: i32
}

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn package_shaders_receivers__1light_space(p: vec3<f32>, t0: vec3<f32>) -> vec2<f32> {
    return p.xy + t0.xy * (p.z / -t0.z);
}

fn package_shaders_receivers__1meet_receivers(map: texture_2d<f32>, r: package_shaders_receivers_Receivers, s: vec3<f32>, t: vec3<f32>) -> f32 {
    if t.z >= 0.0 {
        return -1.0;
    }
    let t0 = r.t0.xyz;
    let drift = length(t.xy - t0.xy * (t.z / t0.z));
    let rate = -t.z + r.view.w * drift;
    var g = s.z - package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(s, t0));
    if g <= 0.0 {
        return -1.0;
    }
    let tol = 0.0001 * r.view.z;
    var d = 0.0;
    for (var k = 0; k < 256; k++) {
        let step = max(g / rate, tol);
        let p = s + t * (d + step);
        let g_next = p.z - package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(p, t0));
        if g_next <= 0.0 {
            var br = package_shaders_receivers_Bracket(d, g, d + step, g_next, 0);
            var m = br.b;
            for (var n = 0; n < 24; n++) {
                m = package_shaders_receivers_chord(br);
                let pm = s + t * m;
                let gm = pm.z - package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(pm, t0));
                br = package_shaders_receivers_narrowed(br, m, gm);
                if abs(gm) < tol || br.b - br.a < tol {
                    break;
                }
            }
            return m;
        }
        d += step;
        g = g_next;
        if g < tol {
            return d;
        }
    }
    return d;
}

fn package_shaders_receivers__1receiver_height(map: texture_2d<f32>, r: package_shaders_receivers_Receivers, q: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(map));
    let u = (q - r.view.xy) / r.view.z - 0.5;
    let c = floor(u);
    let f = u - c;
    let i = vec2<i32>(c);
    let a = textureLoad(map, clamp(i, vec2<i32>(0), dims - 1), 0).x;
    let b = textureLoad(map, clamp(i + vec2<i32>(1, 0), vec2<i32>(0), dims - 1), 0).x;
    let d = textureLoad(map, clamp(i + vec2<i32>(0, 1), vec2<i32>(0), dims - 1), 0).x;
    let e = textureLoad(map, clamp(i + vec2<i32>(1, 1), vec2<i32>(0), dims - 1), 0).x;
    return mix(mix(a, b, f.x), mix(d, e, f.x), f.y);
}

fn package_shaders_receivers_chord(br: package_shaders_receivers_Bracket) -> f32 {
    return (br.a * br.gb - br.b * br.ga) / (br.gb - br.ga);
}

fn package_shaders_receivers_narrowed(br: package_shaders_receivers_Bracket, m: f32, gm: f32) -> package_shaders_receivers_Bracket {
    var out = br;
    if gm > 0.0 {
        out.a = m;
        out.ga = gm;
        if br.kept == 1 {
            out.gb *= 0.5;
        }
        out.kept = 1;
    }
    else {
        out.b = m;
        out.gb = gm;
        if br.kept == -1 {
            out.ga *= 0.5;
        }
        out.kept = -1;
    }
    return out;
}

fn package_shaders_water__2grid_sample_hermite(patches: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(patches));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let n = vec2<i32>(dims);
    var c0 = vec2<i32>(base);
    var c1 = c0 + 1;
    var keep = vec4<f32>(1.0);
    if wrap {
        c0 = ((c0 % n) + n) % n;
        c1 = select(c0 + 1, c0 + 1 - n, c0 + 1 >= n);
    }
    else {
        keep = vec4<f32>(select(0.0, 1.0, c0.x >= 0 && c0.x < n.x), select(0.0, 1.0, c0.y >= 0 && c0.y < n.y), select(0.0, 1.0, c1.x >= 0 && c1.x < n.x), select(0.0, 1.0, c1.y >= 0 && c1.y < n.y));
        c0 = clamp(c0, vec2<i32>(0), n - 1);
        c1 = clamp(c1, vec2<i32>(0), n - 1);
    }
    let k00 = vec4<f32>(1.0, keep.x, keep.y, keep.x * keep.y);
    let k10 = vec4<f32>(1.0, keep.z, keep.y, keep.z * keep.y);
    let k01 = vec4<f32>(1.0, keep.x, keep.w, keep.x * keep.w);
    let k11 = vec4<f32>(1.0, keep.z, keep.w, keep.z * keep.w);
    let p00 = textureLoad(patches, c0, 0) * k00;
    let p10 = textureLoad(patches, vec2<i32>(c1.x, c0.y), 0) * k10;
    let p01 = textureLoad(patches, vec2<i32>(c0.x, c1.y), 0) * k01;
    let p11 = textureLoad(patches, c1, 0) * k11;
    let bu = package_shaders_water_hermite(f.x);
    let bv = package_shaders_water_hermite(f.y);
    let row0 = bu[0].x * vec2<f32>(p00.x, p00.z) + bu[0].y * vec2<f32>(p10.x, p10.z) + bu[0].z * vec2<f32>(p00.y, p00.w) + bu[0].w * vec2<f32>(p10.y, p10.w);
    let row1 = bu[0].x * vec2<f32>(p01.x, p01.z) + bu[0].y * vec2<f32>(p11.x, p11.z) + bu[0].z * vec2<f32>(p01.y, p01.w) + bu[0].w * vec2<f32>(p11.y, p11.w);
    let drow0 = bu[1].x * vec2<f32>(p00.x, p00.z) + bu[1].y * vec2<f32>(p10.x, p10.z) + bu[1].z * vec2<f32>(p00.y, p00.w) + bu[1].w * vec2<f32>(p10.y, p10.w);
    let drow1 = bu[1].x * vec2<f32>(p01.x, p01.z) + bu[1].y * vec2<f32>(p11.x, p11.z) + bu[1].z * vec2<f32>(p01.y, p01.w) + bu[1].w * vec2<f32>(p11.y, p11.w);
    let h = bv[0].x * row0.x + bv[0].y * row1.x + bv[0].z * row0.y + bv[0].w * row1.y;
    let hu = bv[0].x * drow0.x + bv[0].y * drow1.x + bv[0].z * drow0.y + bv[0].w * drow1.y;
    let hv = bv[1].x * row0.x + bv[1].y * row1.x + bv[1].z * row0.y + bv[1].w * row1.y;
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

fn package_shaders_water_hermite(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = vec4<f32>(2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2, t3 - 2.0 * t2 + t, t3 - t2);
    let dw = vec4<f32>(6.0 * t2 - 6.0 * t, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

struct package_yuksel_common_Yuksel {
    light: vec4<f32>,
    pixel: vec2<f32>,
    centre_offset: vec2<f32>,
    attenuation: vec4<f32>,
    size: f32,
    depth: f32,
    ior: f32,
    fresnel: u32,
    width: u32,
    height: u32,
    n: u32,
    m: u32,
    wrap: u32,
    channel_base: u32,
    subsamples: u32,
    footprint: u32,
    phase: u32,
    split: f32,
    pre_tiles: u32,
    walls: u32,
    receivers: package_shaders_receivers_Receivers
}

struct package_yuksel_common_YukselRegion {
    n: u32,
    m: u32,
    shift: vec2<i32>,
    level: u32,
    clamped: u32,
    _pad0: u32,
    _pad1: u32
}

fn package_yuksel_common__1box_share(c: f32, h: f32) -> f32 {
    return max(min(c + h, 0.5) - max(c - h, -0.5), 0.0) / (2.0 * h);
}

fn package_yuksel_common__1half_widths(packed: f32) -> vec2<f32> {
    return abs(unpack2x16float(bitcast<u32>(packed)));
}

fn package_yuksel_common__1level_size(width: u32, height: u32, level: u32) -> vec2<u32> {
    return vec2<u32>(width >> level, height >> level);
}

fn package_yuksel_common__1level_subsamples(level: u32) -> u32 {
    return min(package_yuksel_common_u.subsamples << level, max(package_yuksel_common_u.subsamples, 8u));
}

fn package_yuksel_common__1prepass_area(n: u32, m: u32, level: u32) -> vec2<u32> {
    return package_yuksel_common__1level_size(package_yuksel_common_u.width, package_yuksel_common_u.height, level) + vec2<u32>(n - 1u, m);
}

fn package_yuksel_common__1tier_bits(t: u32, k: u32) -> u32 {
    if t >= k {
        return 0u;
    }
    if t == 1u {
        return 32768u;
    }
    if t == 2u {
        return 2147483648u;
    }
    return 2147516416u;
}

fn package_yuksel_common__2prepass_level_pixel(p: vec2<u32>, r: package_yuksel_common_YukselRegion) -> vec2<i32> {
    return vec2<i32>(p) - vec2<i32>(i32(r.n / 2u), i32(r.m / 2u)) + r.shift;
}

@group(0) @binding(0)
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;

const package_yuksel_fill__1FILL_GROUP: u32 = 64u;

const package_yuksel_fill__1FILL_STRIDE: u32 = package_yuksel_fill__1FILL_GROUP * package_yuksel_fill__2FILL_MAX_GROUPS;

const package_yuksel_fill__1MAX_FILL: u32 = 8u;

var<private> package_yuksel_fill__1fill_below: array<vec4<f32>, package_yuksel_fill__1MAX_FILL>;

fn package_yuksel_fill__1fill_listed(entry: u32, area: vec2<u32>) -> vec2<u32> {
    return vec2<u32>(entry % area.x, entry / area.x);
}

var<private> package_yuksel_fill__1fill_row: array<vec4<f32>, package_yuksel_fill__1MAX_FILL>;

const package_yuksel_fill__2FILL_MAX_GROUPS: u32 = 65535u;

const package_yuksel_fill__2MAX_FILL_EDGES: u32 = 9u;

fn package_yuksel_fill__2yuksel_fill_row(q: vec2<i32>, b: u32, k: u32, pixel: vec2<f32>) {
    if package_yuksel_common_u.footprint == 0u {
        for (var a = 0u; a < k; a++) {
            package_yuksel_fill__1fill_row[a] = package_yuksel_sample__1yuksel_record(package_yuksel_sample__1yuksel_part(q.x, q.y, a, b, k, pixel), q.x, q.y, a, b, k, k, pixel);
        }
        return;
    }
    if b == 0u {
        for (var a = 0u; a < k; a++) {
            package_yuksel_fill__1fill_below[a] = package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(q.x, q.y, 2u * a + 1u, 0u, k, pixel));
        }
    }
    let j = 2u * b + 1u;
    var across: array<vec4<f32>, package_yuksel_fill__2MAX_FILL_EDGES>;
    for (var a = 0u; a <= k; a++) {
        across[a] = package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(q.x, q.y, 2u * a, j, k, pixel));
    }
    for (var a = 0u; a < k; a++) {
        let h = package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(q.x, q.y, 2u * a + 1u, j, k, pixel));
        let above = package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(q.x, q.y, 2u * a + 1u, j + 1u, k, pixel));
        var f = package_yuksel_sample_YukselFootprint(vec4<f32>(0.0), 0.0);
        if h.w != 0.0 {
            f = package_yuksel_sample__1yuksel_footprint(h, across[a], across[a + 1u], package_yuksel_fill__1fill_below[a], above, pixel);
        }
        package_yuksel_fill__1fill_row[a] = package_yuksel_sample__1yuksel_record(f, q.x, q.y, a, b, k, k, pixel);
        package_yuksel_fill__1fill_below[a] = above;
    }
}

struct package_yuksel_sample_YukselFootprint {
    rec: vec4<f32>,
    misfit: f32
}

const package_yuksel_sample__1RAMP_WEIGHT: f32 = 4.0;

@group(0) @binding(8)
var package_yuksel_sample__1receiver_heights: texture_2d<f32>;

fn package_yuksel_sample__1yuksel_edge(h: vec4<f32>, own: vec4<f32>) -> vec4<f32> {
    if h.w == 0.0 {
        return vec4<f32>(own.xyz, 0.0);
    }
    return h;
}

fn package_yuksel_sample__1yuksel_footprint(h: vec4<f32>, raw_xm: vec4<f32>, raw_xp: vec4<f32>, raw_ym: vec4<f32>, raw_yp: vec4<f32>, pixel: vec2<f32>) -> package_yuksel_sample_YukselFootprint {
    let exm = package_yuksel_sample__1yuksel_edge(raw_xm, h);
    let exp = package_yuksel_sample__1yuksel_edge(raw_xp, h);
    let eym = package_yuksel_sample__1yuksel_edge(raw_ym, h);
    let eyp = package_yuksel_sample__1yuksel_edge(raw_yp, h);
    let unlit = exm.w == 0.0 || exp.w == 0.0 || eym.w == 0.0 || eyp.w == 0.0;
    let xm = exm.xy;
    let xp = exp.xy;
    let ym = eym.xy;
    let yp = eyp.xy;
    let mid_x = (xm + xp) * 0.5;
    let mid_y = (ym + yp) * 0.5;
    let half = abs(vec2<f32>(xp.x - xm.x, yp.y - ym.y)) * 0.5 / pixel;
    let bend = abs(h.xy - mid_x) + abs(h.xy - mid_y);
    let shear = vec2<f32>(abs(yp.x - ym.x), abs(xp.y - xm.y)) * 0.5;
    let off = (bend + shear) / pixel;
    let width = max(2.0 * half, vec2<f32>(package_yuksel_common_u.pixel.x / pixel.x));
    let ramp = max(abs(exp.z - exm.z), abs(eyp.z - eym.z)) / max(h.z, 1e-30);
    var misfit = max(max(off.x / width.x, off.y / width.y), package_yuksel_sample__1RAMP_WEIGHT * ramp);
    if unlit {
        misfit = 3e38;
    }
    let packed = pack2x16float(clamp(half, vec2<f32>(package_yuksel_sample__2MIN_HALF_WIDTH), vec2<f32>(60000.0)));
    let centroid = h.xy + (mid_x - h.xy + mid_y - h.xy) / 3.0 + ((xp - xm) * (exp.z - exm.z) + (yp - ym) * (eyp.z - eym.z)) / (12.0 * h.z);
    return package_yuksel_sample_YukselFootprint(vec4<f32>(centroid, bitcast<f32>(packed), h.z), misfit);
}

fn package_yuksel_sample__1yuksel_hit(s: vec2<f32>) -> vec4<f32> {
    let hg = package_shaders_water__2grid_sample_hermite(package_yuksel_sample_patches, s, package_yuksel_common_u.size, package_yuksel_common_u.wrap != 0u);
    let l = package_yuksel_common_u.light.xyz;
    let normal = package_shaders_optics__2height_field_normal(hg.yz);
    let cos_i = -dot(l, normal);
    let seen = 1.0 + dot(l.xy, hg.yz) / -l.z;
    let t = package_shaders_optics__1refract_dir(l, normal, package_yuksel_common_u.light.w);
    if t.w == 0.0 || cos_i <= 0.0 || seen <= 0.0 {
        return vec4<f32>(0.0);
    }
    let z = package_yuksel_common_u.depth + hg.x;
    var fresnel = 1.0;
    if package_yuksel_common_u.fresnel != 0u {
        fresnel = package_shaders_optics__1fresnel_transmittance(cos_i, 1.0, package_yuksel_common_u.ior) / package_yuksel_common_u.attenuation.w;
    }
    if package_yuksel_common_u.receivers.t0.w != 0.0 {
        let start = vec3<f32>(s, z);
        let d = package_shaders_receivers__1meet_receivers(package_yuksel_sample__1receiver_heights, package_yuksel_common_u.receivers, start, t.xyz);
        if d < 0.0 {
            return vec4<f32>(0.0);
        }
        return vec4<f32>(package_shaders_receivers__1light_space(start + t.xyz * d, package_yuksel_common_u.receivers.t0.xyz), seen * fresnel, 1.0);
    }
    return vec4<f32>(s + t.xy * (z / -t.z), seen * fresnel, 1.0);
}

fn package_yuksel_sample__1yuksel_lattice(c: i32, r: i32, i: u32, j: u32, t: u32, pixel: vec2<f32>) -> vec2<f32> {
    let within = vec2<f32>(f32(i), f32(j)) / f32(2u * t) - 0.5;
    return package_yuksel_sample__2yuksel_pixel_centre(c, r, pixel) + within * pixel + package_yuksel_common_u.centre_offset;
}

fn package_yuksel_sample__1yuksel_part(c: i32, r: i32, a: u32, b: u32, t: u32, pixel: vec2<f32>) -> package_yuksel_sample_YukselFootprint {
    let i = 2u * a + 1u;
    let j = 2u * b + 1u;
    let h = package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(c, r, i, j, t, pixel));
    if h.w == 0.0 {
        return package_yuksel_sample_YukselFootprint(vec4<f32>(0.0), 0.0);
    }
    if package_yuksel_common_u.footprint == 0u {
        return package_yuksel_sample__2yuksel_pixel_box(h, pixel / f32(t), pixel);
    }
    return package_yuksel_sample__1yuksel_footprint(h, package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(c, r, i - 1u, j, t, pixel)), package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(c, r, i + 1u, j, t, pixel)), package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(c, r, i, j - 1u, t, pixel)), package_yuksel_sample__1yuksel_hit(package_yuksel_sample__1yuksel_lattice(c, r, i, j + 1u, t, pixel)), pixel);
}

fn package_yuksel_sample__1yuksel_record(f: package_yuksel_sample_YukselFootprint, c: i32, r: i32, a: u32, b: u32, t: u32, k: u32, pixel: vec2<f32>) -> vec4<f32> {
    let bits = package_yuksel_common__1tier_bits(t, k);
    let s = package_yuksel_sample__1yuksel_lattice(c, r, 2u * a + 1u, 2u * b + 1u, t, pixel);
    let beyond = package_yuksel_common_u.walls != 0u && (any(s < vec2<f32>(0.0)) || any(s > vec2<f32>(package_yuksel_common_u.size)));
    if f.rec.w == 0.0 || beyond {
        return vec4<f32>(0.0, 0.0, bitcast<f32>(pack2x16float(vec2<f32>(0.5)) | bits), 0.0);
    }
    let d = (f.rec.xy - package_yuksel_sample__2yuksel_pixel_centre(c, r, pixel)) / pixel;
    return vec4<f32>(d, bitcast<f32>(bitcast<u32>(f.rec.z) | bits), f.rec.w / f32(t * t));
}

const package_yuksel_sample__2MIN_HALF_WIDTH: f32 = 0.001;

fn package_yuksel_sample__2yuksel_pixel_box(h: vec4<f32>, area: vec2<f32>, pixel: vec2<f32>) -> package_yuksel_sample_YukselFootprint {
    let half = 0.5 * area / pixel;
    let packed = pack2x16float(clamp(half, vec2<f32>(package_yuksel_sample__2MIN_HALF_WIDTH), vec2<f32>(60000.0)));
    return package_yuksel_sample_YukselFootprint(vec4<f32>(h.xy, bitcast<f32>(packed), h.z), 0.0);
}

fn package_yuksel_sample__2yuksel_pixel_centre(c: i32, r: i32, pixel: vec2<f32>) -> vec2<f32> {
    return (vec2<f32>(f32(c), f32(r)) + 0.5) * pixel;
}

@group(0) @binding(1)
var package_yuksel_sample_patches: texture_2d<f32>;

const package_yuksel_scatter_FIXED: f32 = 1048576.0;

fn package_yuksel_scatter__1add_record(rec: vec4<f32>, q: vec2<i32>) {
    if rec.w == 0.0 {
        return;
    }
    let f = i32(1u << package_yuksel_scatter_region.level);
    let scale = f32(f);
    let base = q * f;
    let c = rec.xy * scale + (scale - 1.0) * 0.5;
    let half = package_yuksel_common__1half_widths(rec.z) * scale;
    let w = rec.w * scale * scale;
    let reach = vec2<i32>(i32(package_yuksel_scatter_region.n / 2u), i32(package_yuksel_scatter_region.m / 2u));
    let own = q - package_yuksel_scatter_region.shift;
    let size = vec2<i32>(i32(package_yuksel_common_u.width), i32(package_yuksel_common_u.height));
    let lo = max(base + vec2<i32>(floor(c - half + 0.5)), max((own - reach) * f, vec2<i32>(0)));
    let hi = min(base + vec2<i32>(ceil(c + half - 0.5)), min((own + reach) * f + f - 1, size - 1));
    for (var y = lo.y; y <= hi.y; y++) {
        let ay = package_yuksel_common__1box_share(c.y - f32(y - base.y), half.y) * w;
        if ay == 0.0 {
            continue;
        }
        for (var x = lo.x; x <= hi.x; x++) {
            let a = package_yuksel_common__1box_share(c.x - f32(x - base.x), half.x) * ay;
            if a > 0.0 {
                atomicAdd(&package_yuksel_scatter_sums[u32(y) * package_yuksel_common_u.width + u32(x)], u32(a * package_yuksel_scatter_FIXED + 0.5));
            }
        }
    }
}

@group(0) @binding(3)
var<storage, read> package_yuksel_scatter_region: package_yuksel_common_YukselRegion;

@group(0) @binding(2)
var<storage, read_write> package_yuksel_scatter_sums: array<atomic<u32>>;
