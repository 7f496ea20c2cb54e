const FACETS: u32 = 6u;

struct Facets {
    normal: array<vec3<f32>, 6>,
    weight: array<f32, 6>,
    count: u32
}

const LEGENDRE_W = array<f32, 6>(0.171324492, 0.360761573, 0.467913935, 0.467913935, 0.360761573, 0.171324492);

const LEGENDRE_X = array<f32, 6>(-0.932469514, -0.661209386, -0.238619186, 0.238619186, 0.661209386, 0.932469514);

const MAX_SLOPE_TAPS: u32 = 16u;

struct Moments {
    mean: vec2<f32>,
    second: vec3<f32>
}

struct SlopeLevels {
    lod: f32,
    k: u32,
    top: bool,
    fine: vec3<u32>,
    coarse: vec3<u32>
}

fn exact_moments(g: vec2<f32>) -> Moments {
    return Moments(g, vec3<f32>(g.x * g.x, g.y * g.y, g.x * g.y));
}

fn glint(d: vec3<f32>, m: Moments) -> vec3<f32> {
    let to_eye = -d;
    let to_sun = -package__1final_image__2final_image_inputs_params.sun;
    let hv = to_eye + to_sun;
    if to_eye.z <= 0.0 || hv.z <= 0.0 {
        return vec3<f32>(0.0);
    }
    let h = normalize(hv);
    var c = slope_covariance(m);
    c = vec3<f32>(c.x + package__1final_image__2final_image_inputs_params.sun_variance, c.y + package__1final_image__2final_image_inputs_params.sun_variance, c.z);
    let det = c.x * c.y - c.z * c.z;
    let e = vec2<f32>(-h.x / h.z, -h.y / h.z) - m.mean;
    let q = (c.y * e.x * e.x - 2.0 * c.z * e.x * e.y + c.x * e.y * e.y) / det;
    let density = exp(-0.5 * q) / (2.0 * 3.14159265 * sqrt(det));
    let masking = smith_masking(to_eye.z, variance_along(c, to_eye)) * smith_masking(to_sun.z, variance_along(c, to_sun));
    let cos2 = h.z * h.z;
    let g = density * masking / (4.0 * to_eye.z * cos2 * cos2);
    if g <= 0.0 {
        return vec3<f32>(0.0);
    }
    let f = 1.0 - package_shaders_optics__1fresnel_transmittance(dot(to_eye, h), 1.0, package__1final_image__2final_image_inputs_params.ior);
    return package__1final_image__2final_image_inputs__1sun_radiance() * (3.14159265 * f * g);
}

fn lerp_moments(a: Moments, b: Moments, t: f32) -> Moments {
    return Moments(a.mean + (b.mean - a.mean) * t, a.second + (b.second - a.second) * t);
}

fn mean_facet(m: Moments) -> Facets {
    var f: Facets;
    f.normal[0] = package_shaders_optics__2height_field_normal(m.mean);
    f.weight[0] = 1.0;
    f.count = 1u;
    return f;
}

struct package__1final_image__2final_image_inputs_FinalImage {
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

@group(2) @binding(0)
var<storage, read> package__1final_image__2final_image_inputs__1slope_moments: array<f32>;

fn package__1final_image__2final_image_inputs__1sun_radiance() -> vec3<f32> {
    return package__1final_image__2final_image_inputs_params.light_color * package__1final_image__2final_image_inputs_params.sun_intensity;
}

@group(0) @binding(1)
var package__1final_image__2final_image_inputs__1water_height: texture_2d<f32>;

const package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE: u32 = 16u;

fn package__1final_image__2final_image_inputs__2sky_without_sun(d: vec3<f32>) -> vec3<f32> {
    let s = package__1final_image__2final_image_inputs_params.sky;
    let yxy = package_shaders_shading__1perez_sky(d, -package__1final_image__2final_image_inputs_params.sun, s[0].xyz, s[1].xyz, s[2].xyz, s[3].xyz, s[4].xyz, s[5].xyz);
    return package_shaders_shading__2xyy_to_rgb(yxy) * (3.14159265 * package__1final_image__2final_image_inputs__1sun_radiance());
}

fn package__1final_image__2final_image_inputs__2water_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return package_shaders_water__2grid_sample_hermite(package__1final_image__2final_image_inputs__1water_height, p, package__1final_image__2final_image_inputs_params.water_size, package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE));
}

fn package__1final_image__2final_image_inputs_has(flag: u32) -> bool {
    return (package__1final_image__2final_image_inputs_params.flags & flag) != 0u;
}

@group(0) @binding(0)
var<uniform> package__1final_image__2final_image_inputs_params: package__1final_image__2final_image_inputs_FinalImage;

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

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
}

fn package_shaders_shading__1perez_sky(d: vec3<f32>, to_sun: vec3<f32>, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, dd: vec3<f32>, e: vec3<f32>, scale: vec3<f32>) -> vec3<f32> {
    let cos_theta = max(d.z, 0.001);
    let gamma = acos(clamp(dot(d, to_sun), -1.0, 1.0));
    let cos_gamma = cos(gamma);
    return scale * (1.0 + a * exp(b / cos_theta)) * (1.0 + c * exp(dd * gamma) + e * cos_gamma * cos_gamma);
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

fn rough_water(p: vec3<f32>, d: vec3<f32>, n: ptr<function, vec3<f32>>) -> vec4<f32> {
    let m = water_slopes(p, d);
    let f = visible_facets(d, m);
    var reflected = glint(d, m);
    var t_view = 0.0;
    var mean = vec3<f32>(0.0);
    for (var k = 0u; k < f.count; k++) {
        let facet = f.normal[k];
        let w = f.weight[k];
        let t = package_shaders_optics__1fresnel_transmittance(-dot(d, facet), 1.0, package__1final_image__2final_image_inputs_params.ior);
        reflected += package__1final_image__2final_image_inputs__2sky_without_sun(reflect(d, facet)) * ((1.0 - t) * w);
        t_view += t * w;
        mean += facet * w;
    }
    *n = normalize(mean);
    return vec4<f32>(reflected, t_view);
}

fn slope_at_lod(p: vec2<f32>, l: SlopeLevels) -> Moments {
    if l.top {
        return slope_bilinear(l.fine, p);
    }
    var below: Moments;
    if l.k == 0u {
        below = exact_moments(water_gradient(p));
    }
    else {
        below = slope_bilinear(l.fine, p);
    }
    return lerp_moments(below, slope_bilinear(l.coarse, p), l.lod - f32(l.k));
}

fn slope_bilinear(l: vec3<u32>, p: vec2<f32>) -> Moments {
    let u = p.x / (package__1final_image__2final_image_inputs_params.water_size / f32(l.y)) - 0.5;
    let v = p.y / (package__1final_image__2final_image_inputs_params.water_size / f32(l.z)) - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    var m = Moments(vec2<f32>(0.0), vec3<f32>(0.0));
    for (var di = 0; di < 2; di++) {
        let wy = select(1.0 - fv, fv, di == 1);
        for (var dj = 0; dj < 2; dj++) {
            let wx = select(1.0 - fu, fu, dj == 1);
            let t = slope_fetch(l, i32(i0) + di, i32(j0) + dj);
            m.mean += t.mean * (wx * wy);
            m.second += t.second * (wx * wy);
        }
    }
    return m;
}

fn slope_covariance(m: Moments) -> vec3<f32> {
    let sxx = max(m.second.x - m.mean.x * m.mean.x, 0.0);
    let syy = max(m.second.y - m.mean.y * m.mean.y, 0.0);
    let limit = sqrt(sxx * syy);
    return vec3<f32>(sxx, syy, clamp(m.second.z - m.mean.x * m.mean.y, -limit, limit));
}

fn slope_fetch(l: vec3<u32>, i: i32, j: i32) -> Moments {
    let r = i32(l.z);
    let c = i32(l.y);
    var ii = clamp(i, 0, r - 1);
    var jj = clamp(j, 0, c - 1);
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE) {
        ii = ((i % r) + r) % r;
        jj = ((j % c) + c) % c;
    }
    let k = (l.x + u32(ii * c + jj)) * 5u;
    return Moments(vec2<f32>(package__1final_image__2final_image_inputs__1slope_moments[k], package__1final_image__2final_image_inputs__1slope_moments[k + 1u]), vec3<f32>(package__1final_image__2final_image_inputs__1slope_moments[k + 2u], package__1final_image__2final_image_inputs__1slope_moments[k + 3u], package__1final_image__2final_image_inputs__1slope_moments[k + 4u]));
}

fn slope_level(k: u32) -> vec3<u32> {
    var l = vec3<u32>(0u, max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u));
    for (var i = 0u; i < k; i++) {
        l = vec3<u32>(l.x + l.y * l.z, (l.y + 1u) / 2u, (l.z + 1u) / 2u);
    }
    return l;
}

fn slope_level_count() -> u32 {
    var l = vec2<u32>(max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u));
    var n = 1u;
    while l.x > 1u || l.y > 1u {
        l = (l + 1u) / 2u;
        n++;
    }
    return n;
}

fn slope_levels(lod: f32) -> SlopeLevels {
    let top = slope_level_count() - 1u;
    let k = min(u32(floor(lod)), top);
    return SlopeLevels(lod, k, lod >= f32(top), slope_level(k), slope_level(min(k + 1u, top)));
}

fn slope_texel() -> f32 {
    return package__1final_image__2final_image_inputs_params.water_size / f32(min(max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u)));
}

fn smith_masking(cos_theta: f32, sigma2: f32) -> f32 {
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    if sin_theta <= 0.0 || sigma2 <= 0.0 {
        return 1.0;
    }
    let a = cos_theta / (sin_theta * sqrt(2.0 * sigma2));
    if a >= 1.6 {
        return 1.0;
    }
    let lambda = (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a);
    return 1.0 / (1.0 + lambda);
}

fn variance_along(c: vec3<f32>, d: vec3<f32>) -> f32 {
    var a = vec2<f32>(1.0, 0.0);
    if length(d.xy) > 0.0 {
        a = normalize(d.xy);
    }
    return c.x * a.x * a.x + 2.0 * c.z * a.x * a.y + c.y * a.y * a.y;
}

fn visible_facets(d: vec3<f32>, m: Moments) -> Facets {
    let c = slope_covariance(m);
    let run = length(d.xy);
    if run <= 0.0 {
        return mean_facet(m);
    }
    let a = d.xy / run;
    let along = vec2<f32>(c.x * a.x + c.z * a.y, c.z * a.x + c.y * a.y);
    let sigma = sqrt(max(dot(a, along), 0.0));
    if sigma <= 0.0 {
        return mean_facet(m);
    }
    let u0 = -(abs(d.z) + run * dot(m.mean, a)) / (run * sigma);
    let lo = max(u0, -4.0);
    let hi = max(lo, 0.0) + 4.0;
    let step = along / sigma;
    var f: Facets;
    var total = 0.0;
    for (var k = 0u; k < FACETS; k++) {
        let u = lo + (hi - lo) * 0.5 * (LEGENDRE_X[k] + 1.0);
        let seen = LEGENDRE_W[k] * max(u - u0, 0.0) * exp(-0.5 * u * u);
        f.normal[k] = package_shaders_optics__2height_field_normal(m.mean + step * u);
        f.weight[k] = seen;
        total += seen;
    }
    if !(total > 0.0 && total <= 3e38) {
        return mean_facet(m);
    }
    for (var k = 0u; k < FACETS; k++) {
        f.weight[k] = f.weight[k] / total;
    }
    f.count = FACETS;
    return f;
}

fn water_gradient(p: vec2<f32>) -> vec2<f32> {
    return package__1final_image__2final_image_inputs__2water_height_gradient(p).yz;
}

fn water_slopes(p: vec3<f32>, d: vec3<f32>) -> Moments {
    let width = length(p - package__1final_image__2final_image_inputs_params.camera_position) * package__1final_image__2final_image_inputs_params.slope_spread;
    let len = width / max(abs(d.z), 0.001);
    var along = vec2<f32>(1.0, 0.0);
    if length(d.xy) > 0.0 {
        along = normalize(d.xy);
    }
    let taps = clamp(ceil(len / max(width, 1e-12)), 1.0, f32(MAX_SLOPE_TAPS));
    let side = max(width, len / taps);
    let lod = log2(side / slope_texel());
    if lod <= 0.0 {
        return exact_moments(water_gradient(p.xy));
    }
    var m = Moments(vec2<f32>(0.0), vec3<f32>(0.0));
    let levels = slope_levels(lod);
    let n = u32(taps);
    for (var k = 0u; k < n; k++) {
        let offset = ((f32(k) + 0.5) / taps - 0.5) * len;
        let t = slope_at_lod(p.xy + along * offset, levels);
        m.mean += t.mean / taps;
        m.second += t.second / taps;
    }
    return m;
}
