const BISECTIONS: u32 = 30u;

const DECK_SHIFT: u32 = 8u;

const EVEN_STEPS: u32 = 24u;

const FAR: f32 = 3e38;

const FLAG_AIR_CAUSTICS: u32 = 64u;

const FLAG_CAUSTICS: u32 = 4u;

const FLAG_EYE_CAUSTICS: u32 = 128u;

const FLAG_FILTER_WATER: u32 = 65536u;

const FLAG_SURFACE: u32 = 2u;

const FLAG_TERRAIN: u32 = 8u;

const FLAG_WATER: u32 = 1u;

const FLAG_WRAP_CAUSTICS: u32 = 32u;

const FLAG_WRAP_SURFACE: u32 = 16u;

const FLOOR_STEPS: u32 = 64u;

struct FinalImage {
    camera_position: vec3<f32>,
    exposure: f32,
    camera_forward: vec3<f32>,
    sun_disk: f32,
    camera_right: vec3<f32>,
    water_size: f32,
    camera_up: vec3<f32>,
    water_level: f32,
    sun: vec3<f32>,
    sun_intensity: f32,
    sun_water: vec3<f32>,
    t_flat: f32,
    light_color: vec3<f32>,
    ior: f32,
    absorption: vec3<f32>,
    scene_size: f32,
    map_size: f32,
    width: u32,
    height: u32,
    supersampling: u32,
    object_count: u32,
    flags: u32,
    albedo: u32,
    tone_map: u32,
    ambient: vec3<f32>,
    sun_cos_radius: f32,
    sky: array<vec4<f32>, 6>,
    slope_spread: f32,
    sun_variance: f32,
    slope_cols: u32,
    slope_rows: u32
}

const MARCH_STEPS: u32 = 512u;

const MAX_DEPTH: u32 = 6u;

struct Object {
    color: vec3<f32>,
    ior: f32,
    root: u32,
    glass: u32,
    _pad: vec2<u32>
}

const RAY_STACK: u32 = 16u;

struct Ray {
    o: vec3<f32>,
    d: vec3<f32>,
    weight: vec3<f32>,
    depth: u32,
    under: bool
}

const SLAB_LATTICE: u32 = 128u;

fn absorbed(distance: f32) -> vec3<f32> {
    return exp(-params.absorption * distance);
}

fn albedo_at(p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    return package_shaders_shading__1floor_albedo(params.albedo, albedo_image, p, size, extent);
}

@group(0) @binding(4)
var albedo_image: texture_2d<f32>;

@group(0) @binding(3)
var caustics_map: texture_2d<f32>;

@group(0) @binding(10)
var caustics_mips: texture_2d<f32>;

fn deck_kind() -> u32 {
    return (params.flags >> DECK_SHIFT) & 255u;
}

fn emit(weight: vec3<f32>, colour: vec3<f32>) {
    pixel_radiance += weight * colour;
}

fn floor_height(p: vec2<f32>) -> f32 {
    if !has(FLAG_TERRAIN) {
        return 0.0;
    }
    return package_shaders_water__1grid_sample(terrain_height, p, params.scene_size, false).x;
}

var<private> h_max: f32;

fn has(flag: u32) -> bool {
    return (params.flags & flag) != 0u;
}

@group(0) @binding(6)
var image: texture_storage_2d<rgba8unorm, write>;

fn is_pool() -> bool {
    return !has(FLAG_TERRAIN);
}

@group(0) @binding(5)
var<storage, read> objects: array<Object>;

fn package_shaders__1caustics_sampling__1caustics_bilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(package_shaders__1caustics_sampling__1caustics_dims(map, level));
    let u = p.x / size * dims.x - 0.5;
    let v = p.y / size * dims.y - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    let i = i32(i0);
    let j = i32(j0);
    let a = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i, j, wrap);
    let b = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i, j + 1, wrap);
    let c = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i + 1, j, wrap);
    let d = package_shaders__1caustics_sampling__1caustics_texel(map, mips, mips_from, level, i + 1, j + 1, wrap);
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

fn package_shaders__1caustics_sampling__1caustics_dims(map: texture_2d<f32>, level: u32) -> vec2<i32> {
    return vec2<i32>(max(textureDimensions(map) >> vec2<u32>(level), vec2<u32>(1u)));
}

fn package_shaders__1caustics_sampling__1caustics_filtered(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, size: f32, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    let texels = vec2<f32>(textureDimensions(map)) / size;
    let a = fa * texels;
    let b = fb * texels;
    var long = a;
    var la = length(a);
    if length(b) > la {
        long = b;
        la = length(b);
    }
    var across = 0.0;
    if la > 0.0 {
        across = abs(a.x * b.y - a.y * b.x) / la;
    }
    la = max(la, 1.0);
    across = max(across, 1.0);
    let taps = clamp(ceil(la / across), 1.0, package_shaders__1caustics_sampling__2CAUSTICS_MAX_TAPS);
    let width = max(la / taps, across);
    let level = max(log2(width / sqrt(3.0)), 0.0);
    let step = long / texels;
    var sum = vec3<f32>(0.0);
    for (var t = 0.0; t < taps; t += 1.0) {
        let q = p + step * ((t + 0.5) / taps - 0.5);
        let off = q.x < 0.0 || q.y < 0.0 || q.x > size || q.y > size;
        if has_beyond && !wrap && off {
            sum += beyond;
        }
        else {
            sum += package_shaders__1caustics_sampling__1caustics_trilinear(map, mips, mips_from, q, level, size, wrap);
        }
    }
    return sum / taps;
}

fn package_shaders__1caustics_sampling__1caustics_texel(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, i: i32, j: i32, wrap: bool) -> vec3<f32> {
    let dims = package_shaders__1caustics_sampling__1caustics_dims(map, level);
    var c = vec2<i32>(j, i);
    if wrap {
        c = ((c % dims) + dims) % dims;
    }
    else {
        c = clamp(c, vec2<i32>(0), dims - 1);
    }
    if level == 0u {
        return textureLoad(map, c, 0).rgb;
    }
    return textureLoad(mips, c, level - mips_from).rgb;
}

fn package_shaders__1caustics_sampling__1caustics_trilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, p: vec2<f32>, level: f32, size: f32, wrap: bool) -> vec3<f32> {
    let dims = textureDimensions(map);
    let last = firstLeadingBit(max(max(dims.x, dims.y), 1u));
    let l0 = min(u32(floor(level)), last);
    var f = level - f32(l0);
    if l0 == last {
        f = 0.0;
    }
    let a = package_shaders__1caustics_sampling__1caustics_bilinear(map, mips, mips_from, l0, p, size, wrap);
    if f == 0.0 {
        return a;
    }
    let b = package_shaders__1caustics_sampling__1caustics_bilinear(map, mips, mips_from, l0 + 1u, p, size, wrap);
    return a * (1.0 - f) + b * f;
}

const package_shaders__1caustics_sampling__2CAUSTICS_MAX_TAPS: f32 = 8.0;

const package_shaders_shading__1ALBEDO_PLAIN: u32 = 2u;

const package_shaders_shading__1ALBEDO_SAND: u32 = 1u;

const package_shaders_shading__1ALBEDO_TILES: u32 = 0u;

const package_shaders_shading__1GROUT_COLOUR: vec3<f32> = vec3<f32>(0.18, 0.2, 0.22);

const package_shaders_shading__1NOISE_POINT: f32 = 0.001;

const package_shaders_shading__1SAND_GRAIN: f32 = 0.05;

const package_shaders_shading__1SAND_PATCH: f32 = 0.5;

const package_shaders_shading__1TILE_COLOUR: vec3<f32> = vec3<f32>(0.62, 0.78, 0.82);

fn package_shaders_shading__1floor_albedo(kind: u32, image: texture_2d<f32>, p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    let u = p / size;
    let w = extent / size;
    switch kind {
        case package_shaders_shading__1ALBEDO_TILES {
            let t = u * 8.0;
            let jx = package_shaders_shading__1joint_cover(t.x, w.x * 8.0, 0.04);
            let jy = package_shaders_shading__1joint_cover(t.y, w.y * 8.0, 0.04);
            let grout = 1.0 - (1.0 - jx) * (1.0 - jy);
            return package_shaders_shading__1TILE_COLOUR * (1.0 - grout) + package_shaders_shading__1GROUT_COLOUR * grout;
        }
        case package_shaders_shading__1ALBEDO_SAND {
            let ripple = sin(u.x * 157.0) * package_shaders_shading_sinc(78.5 * w.x) * sin(u.y * 113.0) * package_shaders_shading_sinc(56.5 * w.y) * 0.03;
            let grain = package_shaders_shading__2SAND_GRAIN_AMPLITUDE * package_shaders_shading__1value_noise(p, package_shaders_shading__1SAND_GRAIN, 0, extent) + package_shaders_shading__2SAND_PATCH_AMPLITUDE * package_shaders_shading__1value_noise(p, package_shaders_shading__1SAND_PATCH, 7919, extent);
            return vec3<f32>(0.76, 0.68, 0.5) * (1.0 + grain) + vec3<f32>(ripple);
        }
        case package_shaders_shading__1ALBEDO_PLAIN {
            return vec3<f32>(0.7);
        }
        case default {
            let dims = textureDimensions(image);
            let j = min(u32(fract(u.x) * f32(dims.x)), dims.x - 1u);
            let i = min(u32(fract(u.y) * f32(dims.y)), dims.y - 1u);
            return textureLoad(image, vec2<u32>(j, i), 0).rgb;
        }
    }
}

fn package_shaders_shading__1hat_integral(t: f32) -> f32 {
    let u = min(abs(t), 1.0);
    return 0.5 + sign(t) * (u - u * u * u + 0.5 * u * u * u * u);
}

fn package_shaders_shading__1joint_cover(x: f32, w: f32, joint: f32) -> f32 {
    if w <= 0.0001 {
        return select(0.0, 1.0, x - floor(x) < joint);
    }
    return clamp((package_shaders_shading__1joint_integral(x + 0.5 * w, joint) - package_shaders_shading__1joint_integral(x - 0.5 * w, joint)) / w, 0.0, 1.0);
}

fn package_shaders_shading__1joint_integral(x: f32, joint: f32) -> f32 {
    let n = floor(x);
    return n * joint + min(x - n, joint);
}

fn package_shaders_shading__1perez_sky(d: vec3<f32>, to_sun: vec3<f32>, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, dd: vec3<f32>, e: vec3<f32>, scale: vec3<f32>) -> vec3<f32> {
    let cos_theta = max(d.z, 0.001);
    let gamma = acos(clamp(dot(d, to_sun), -1.0, 1.0));
    let cos_gamma = cos(gamma);
    return scale * (1.0 + a * exp(b / cos_theta)) * (1.0 + c * exp(dd * gamma) + e * cos_gamma * cos_gamma);
}

fn package_shaders_shading__1value_noise(p: vec2<f32>, cell: f32, seed: i32, w: vec2<f32>) -> f32 {
    let q = p / cell;
    let r = w / cell;
    let exact = min(r, vec2<f32>(package_shaders_shading__2NOISE_EXACT_BOX));
    var i0: i32;
    var j0: i32;
    let wx = package_shaders_shading__2hat_box_weights(q.x, 0.5 * exact.x, &i0);
    let wy = package_shaders_shading__2hat_box_weights(q.y, 0.5 * exact.y, &j0);
    j0 += seed;
    var n = 0.0;
    for (var b = 0; b < 4; b++) {
        if wy[b] == 0.0 {
            continue;
        }
        var row = 0.0;
        for (var a = 0; a < 4; a++) {
            if wx[a] != 0.0 {
                row += wx[a] * (2.0 * package_shaders_shading_hash01(i0 + a, j0 + b) - 1.0);
            }
        }
        n += wy[b] * row;
    }
    let fade = pow(1.0 + r * r, vec2<f32>(-0.25)) / pow(1.0 + exact * exact, vec2<f32>(-0.25));
    return n * fade.x * fade.y;
}

const package_shaders_shading__2NOISE_EXACT_BOX: f32 = 2.0;

const package_shaders_shading__2SAND_GRAIN_AMPLITUDE: f32 = 0.08;

const package_shaders_shading__2SAND_PATCH_AMPLITUDE: f32 = 0.06;

fn package_shaders_shading__2hat_box_weights(x: f32, a: f32, first: ptr<function, i32>) -> vec4<f32> {
    let i0 = floor(x - a);
    *first = i32(i0);
    let t = vec4<f32>(x - i0) - vec4<f32>(0.0, 1.0, 2.0, 3.0);
    if a < package_shaders_shading__1NOISE_POINT {
        let u = min(abs(t), vec4<f32>(1.0));
        return 1.0 - u * u * (3.0 - 2.0 * u);
    }
    return vec4<f32>(package_shaders_shading__1hat_integral(t.x + a) - package_shaders_shading__1hat_integral(t.x - a), package_shaders_shading__1hat_integral(t.y + a) - package_shaders_shading__1hat_integral(t.y - a), package_shaders_shading__1hat_integral(t.z + a) - package_shaders_shading__1hat_integral(t.z - a), package_shaders_shading__1hat_integral(t.w + a) - package_shaders_shading__1hat_integral(t.w - a)) / (2.0 * a);
}

fn package_shaders_shading__2xyy_to_rgb(v: vec3<f32>) -> vec3<f32> {
    let lum = v.x;
    let x = v.y;
    let y = v.z;
    if y <= 0.0 || lum <= 0.0 {
        return vec3<f32>(0.0);
    }
    let xyz = vec3<f32>(x / y * lum, lum, (1.0 - x - y) / y * lum);
    return max(vec3<f32>(dot(vec3<f32>(3.2406, -1.5372, -0.4986), xyz), dot(vec3<f32>(-0.9689, 1.8758, 0.0415), xyz), dot(vec3<f32>(0.0557, -0.204, 1.057), xyz)), vec3<f32>(0.0));
}

fn package_shaders_shading_hash01(x: i32, y: i32) -> f32 {
    var h = (bitcast<u32>(x) * 2376512323u) ^ (bitcast<u32>(y) * 3625334849u);
    h ^= h >> 16u;
    h *= 2146121005u;
    h ^= h >> 15u;
    h *= 2221713035u;
    h ^= h >> 16u;
    return f32(h) / 4294967296.0;
}

fn package_shaders_shading_sinc(x: f32) -> f32 {
    if abs(x) < 1e-6 {
        return 1.0;
    }
    return sin(x) / x;
}

fn package_shaders_water__1catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

fn package_shaders_water__1grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

fn package_shaders_water__1grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = package_shaders_water__1catmull_rom(f.x);
    let wv = package_shaders_water__1catmull_rom(f.y);
    let n = vec2<i32>(dims);
    var first = vec2<i32>(base) - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    var h = 0.0;
    var hu = 0.0;
    var hv = 0.0;
    for (var a = 0; a < 4; a++) {
        let row = package_shaders_water__1grid_index(first.y, a, n.y, wrap);
        for (var b = 0; b < 4; b++) {
            let s = textureLoad(tex, vec2<i32>(package_shaders_water__1grid_index(first.x, b, n.x, wrap), row), 0).r;
            h += wu[0][b] * wv[0][a] * s;
            hu += wu[1][b] * wv[0][a] * s;
            hv += wu[0][b] * wv[1][a] * s;
        }
    }
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
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

@group(0) @binding(0)
var<uniform> params: FinalImage;

var<private> pixel_radiance: vec3<f32>;

fn push_ray(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool) {
    if ray_count < RAY_STACK {
        rays[ray_count] = Ray(o, d, weight, depth, under);
        ray_count++;
    }
}

var<private> ray_count: u32;

var<private> rays: array<Ray, RAY_STACK>;

fn sample_caustics_filtered(p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    return package_shaders__1caustics_sampling__1caustics_filtered(caustics_map, caustics_mips, 1u, p, fa, fb, params.map_size, wrap, beyond, has_beyond);
}

fn sky_radiance(d: vec3<f32>) -> vec3<f32> {
    var disk = 0.0;
    if dot(d, -params.sun) >= params.sun_cos_radius {
        disk = params.sun_disk;
    }
    return sky_without_sun(d) + vec3<f32>(disk * 3.14159265) * sun_radiance();
}

fn sky_without_sun(d: vec3<f32>) -> vec3<f32> {
    let s = params.sky;
    let yxy = package_shaders_shading__1perez_sky(d, -params.sun, s[0].xyz, s[1].xyz, s[2].xyz, s[3].xyz, s[4].xyz, s[5].xyz);
    return package_shaders_shading__2xyy_to_rgb(yxy) * (3.14159265 * sun_radiance());
}

fn slab_half_height() -> f32 {
    if !has(FLAG_SURFACE) {
        return 0.0;
    }
    return bitcast<f32>(slab_max[0]) * 1.5 + 1e-6;
}

@group(0) @binding(7)
var<storage, read> slab_max: array<u32>;

fn slab_slope() -> f32 {
    if !has(FLAG_SURFACE) {
        return 0.0;
    }
    return bitcast<f32>(slab_max[1]) * 1.5 + 1e-6;
}

var<private> slope_max: f32;

@group(2) @binding(0)
var<storage, read> slope_moments: array<f32>;

fn sun_radiance() -> vec3<f32> {
    return params.light_color * params.sun_intensity;
}

@group(0) @binding(2)
var terrain_height: texture_2d<f32>;

@group(0) @binding(9)
var<storage, read> wall_cols: array<u32>;

@group(0) @binding(8)
var wall_maps: texture_2d_array<f32>;

@group(0) @binding(1)
var water_height: texture_2d<f32>;

fn water_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return package_shaders_water__2grid_sample_hermite(water_height, p, params.water_size, has(FLAG_WRAP_SURFACE));
}
