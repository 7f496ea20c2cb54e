// The waves' normals filtered by each sample's footprint: the GPU twin of
// caustics-core's water/slopes.rs (`SlopePyramid::filtered`, `visible_facets`, `glint`) and
// render.rs `Tracer::rough_water`, where the filter is written down and its sources cited (LEAN
// mapping; Heitz 2014's visible normals; Cox and Munk's glint with Smith's masking).

import package::final_image::final_image_inputs::{
    FLAG_WRAP_SURFACE, has, params, sky_without_sun, slope_moments, sun_radiance,
    water_height_gradient,
};
import package::shaders::optics::{fresnel_transmittance, height_field_normal};

// slopes.rs `MAX_TAPS`.
const MAX_SLOPE_TAPS: u32 = 16u;

// slopes.rs `SlopeMoments`: the mean slope and E[h_x²], E[h_y²], E[h_x h_y].
struct Moments {
    mean: vec2<f32>,
    second: vec3<f32>,
}

fn exact_moments(g: vec2<f32>) -> Moments {
    return Moments(g, vec3<f32>(g.x * g.x, g.y * g.y, g.x * g.y));
}

fn water_gradient(p: vec2<f32>) -> vec2<f32> {
    return water_height_gradient(p).yz;
}

// Level k of slope_moments: its first texel, columns and rows.
fn slope_level(k: u32) -> vec3<u32> {
    var l = vec3<u32>(0u, max(params.slope_cols, 1u), max(params.slope_rows, 1u));
    for (var i = 0u; i < k; i++) {
        l = vec3<u32>(l.x + l.y * l.z, (l.y + 1u) / 2u, (l.z + 1u) / 2u);
    }
    return l;
}

fn slope_level_count() -> u32 {
    var l = vec2<u32>(max(params.slope_cols, 1u), max(params.slope_rows, 1u));
    var n = 1u;
    while l.x > 1u || l.y > 1u {
        l = (l + 1u) / 2u;
        n++;
    }
    return n;
}

// `Level::fetch`, with the water's edge rule.
fn slope_fetch(l: vec3<u32>, i: i32, j: i32) -> Moments {
    let r = i32(l.z);
    let c = i32(l.y);
    var ii = clamp(i, 0, r - 1);
    var jj = clamp(j, 0, c - 1);
    if has(FLAG_WRAP_SURFACE) {
        ii = ((i % r) + r) % r;
        jj = ((j % c) + c) % c;
    }
    let k = (l.x + u32(ii * c + jj)) * 5u;
    return Moments(
        vec2<f32>(slope_moments[k], slope_moments[k + 1u]),
        vec3<f32>(slope_moments[k + 2u], slope_moments[k + 3u], slope_moments[k + 4u]),
    );
}

// `SlopePyramid::bilinear`.
fn slope_bilinear(l: vec3<u32>, p: vec2<f32>) -> Moments {
    let u = p.x / (params.water_size / f32(l.y)) - 0.5;
    let v = p.y / (params.water_size / f32(l.z)) - 0.5;
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

fn lerp_moments(a: Moments, b: Moments, t: f32) -> Moments {
    return Moments(a.mean + (b.mean - a.mean) * t, a.second + (b.second - a.second) * t);
}

// The two levels a footprint's taps read at `lod` (`SlopePyramid::at_lod`), found once for all
// its taps: k = floor(lod) and k + 1, or the top alone (in both) at or past it.
struct SlopeLevels {
    lod: f32,
    k: u32,
    top: bool,
    fine: vec3<u32>,
    coarse: vec3<u32>,
}

fn slope_levels(lod: f32) -> SlopeLevels {
    let top = slope_level_count() - 1u;
    let k = min(u32(floor(lod)), top);
    return SlopeLevels(lod, k, lod >= f32(top), slope_level(k), slope_level(min(k + 1u, top)));
}

// `SlopePyramid::at_lod`.
fn slope_at_lod(p: vec2<f32>, l: SlopeLevels) -> Moments {
    if l.top {
        return slope_bilinear(l.fine, p);
    }
    var below: Moments;
    if l.k == 0u {
        below = exact_moments(water_gradient(p));
    } else {
        below = slope_bilinear(l.fine, p);
    }
    return lerp_moments(below, slope_bilinear(l.coarse, p), l.lod - f32(l.k));
}

// Level 0's texel: the larger of its two sides (`SlopePyramid::texel`).
fn slope_texel() -> f32 {
    return params.water_size / f32(min(max(params.slope_cols, 1u), max(params.slope_rows, 1u)));
}

// `Tracer::water_slopes`: the moments over the footprint (`Footprint::of_ray`) of the sample that
// meets the water at `p` along `d`, through `SlopePyramid::filtered`.
fn water_slopes(p: vec3<f32>, d: vec3<f32>) -> Moments {
    let width = length(p - params.camera_position) * params.slope_spread;
    let len = width / max(abs(d.z), 1e-3);
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

// `SlopeMoments::covariance`: (σ_xx, σ_yy, σ_xy), positive semi-definite.
fn slope_covariance(m: Moments) -> vec3<f32> {
    let sxx = max(m.second.x - m.mean.x * m.mean.x, 0.0);
    let syy = max(m.second.y - m.mean.y * m.mean.y, 0.0);
    let limit = sqrt(sxx * syy);
    return vec3<f32>(sxx, syy, clamp(m.second.z - m.mean.x * m.mean.y, -limit, limit));
}

// slopes.rs `FACETS` and its Gauss-Legendre rule on [-1, 1].
const FACETS: u32 = 6u;
const LEGENDRE_X = array<f32, 6>(-0.932469514, -0.661209386, -0.238619186, 0.238619186, 0.661209386, 0.932469514);
const LEGENDRE_W = array<f32, 6>(0.171324492, 0.360761573, 0.467913935, 0.467913935, 0.360761573, 0.171324492);

// `visible_facets`: the facets a view along `d` sees of water with moments `m`, each with the share
// of the footprint the eye sees of it (count 1: the mean facet alone).
struct Facets {
    normal: array<vec3<f32>, 6>,
    weight: array<f32, 6>,
    count: u32,
}

fn mean_facet(m: Moments) -> Facets {
    var f: Facets;
    f.normal[0] = height_field_normal(m.mean);
    f.weight[0] = 1.0;
    f.count = 1u;
    return f;
}

fn visible_facets(d: vec3<f32>, m: Moments) -> Facets {
    let c = slope_covariance(m);
    let run = length(d.xy);
    // Straight down the CPU's weights are all infinite and it keeps the mean facet.
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
        f.normal[k] = height_field_normal(m.mean + step * u);
        f.weight[k] = seen;
        total += seen;
    }
    if !(total > 0.0 && total <= 3.0e38) {
        return mean_facet(m);
    }
    for (var k = 0u; k < FACETS; k++) {
        f.weight[k] = f.weight[k] / total;
    }
    f.count = FACETS;
    return f;
}

// slopes.rs `smith_masking`.
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

// `Tracer::glint` through slopes.rs `glint`: the sun's reflection off water of moments `m` toward
// the eye looking along `d`, with its mirroring facet's Fresnel reflectance, in the image's unit.
fn glint(d: vec3<f32>, m: Moments) -> vec3<f32> {
    let to_eye = -d;
    let to_sun = -params.sun;
    let hv = to_eye + to_sun;
    if to_eye.z <= 0.0 || hv.z <= 0.0 {
        return vec3<f32>(0.0);
    }
    let h = normalize(hv);
    var c = slope_covariance(m);
    c = vec3<f32>(c.x + params.sun_variance, c.y + params.sun_variance, c.z);
    let det = c.x * c.y - c.z * c.z;
    let e = vec2<f32>(-h.x / h.z, -h.y / h.z) - m.mean;
    let q = (c.y * e.x * e.x - 2.0 * c.z * e.x * e.y + c.x * e.y * e.y) / det;
    let density = exp(-0.5 * q) / (2.0 * 3.14159265 * sqrt(det));
    let masking = smith_masking(to_eye.z, variance_along(c, to_eye))
        * smith_masking(to_sun.z, variance_along(c, to_sun));
    let cos2 = h.z * h.z;
    let g = density * masking / (4.0 * to_eye.z * cos2 * cos2);
    if g <= 0.0 {
        return vec3<f32>(0.0);
    }
    let f = 1.0 - fresnel_transmittance(dot(to_eye, h), 1.0, params.ior);
    return sun_radiance() * (3.14159265 * f * g);
}

// `Tracer::rough_water`: the reflected light (xyz) and the transmittance (w) of water met at `p`
// along `d`, its normals filtered by the sample's footprint; `n` takes the normal to refract at.
fn rough_water(p: vec3<f32>, d: vec3<f32>, n: ptr<function, vec3<f32>>) -> vec4<f32> {
    let m = water_slopes(p, d);
    let f = visible_facets(d, m);
    var reflected = glint(d, m);
    var t_view = 0.0;
    var mean = vec3<f32>(0.0);
    for (var k = 0u; k < f.count; k++) {
        let facet = f.normal[k];
        let w = f.weight[k];
        let t = fresnel_transmittance(-dot(d, facet), 1.0, params.ior);
        reflected += sky_without_sun(reflect(d, facet)) * ((1.0 - t) * w);
        t_view += t * w;
        mean += facet * w;
    }
    *n = normalize(mean);
    return vec4<f32>(reflected, t_view);
}
