// The final image, one invocation per pixel: the GPU twin of caustics-core/src/render.rs, function
// for function (`render`, `Tracer::trace`, `trace_under`, `shade_floor`, `shade_object`,
// `trace_air`, `shade_above`, `hit_water`, `hit_floor`, `inside`, `wall_distance`, `wall_light`,
// `wall_at`, `hit_water_from_below`, `leave_water`, `camera_under_water`). The light
// transport is documented there. Composed after optics.wgsl, water.wgsl, shading.wgsl and bvh.wgsl.
//
// WGSL has no recursion, and the CPU's recursion is linear in what it returns: `trace` returns the
// reflected sky plus `t_view` times what `trace_under` returns, a glass object returns
// `(1 - T)` times one trace plus `T tint` times another, and `trace_under` multiplies all it gets by
// `exp(-K d)`. So each function here takes the weight `w` its CPU twin's result would be multiplied
// by, adds `w * colour` for what it would return directly (`emit`), and pushes the rays it would
// recurse into with their weights on a small stack (`push_ray`) that `radiance` drains. The sum is
// the CPU's up to the order of the additions.

// Mirrors `FinalImageUniform` in crates/gpu/src/final_image/upload.rs.
struct FinalImage {
    camera_position: vec3<f32>,
    exposure: f32,
    camera_forward: vec3<f32>,
    // The sun's disk's radiance per unit of its irradiance (sky.rs `Sky::sun_disk`).
    sun_disk: f32,
    // The camera's right vector times tan(fov_y / 2) times the aspect ratio.
    camera_right: vec3<f32>,
    // The water's square (the scene's without water).
    water_size: f32,
    // The camera's up vector times tan(fov_y / 2).
    camera_up: vec3<f32>,
    // The water's rest level, `water.depth`.
    water_level: f32,
    // Unit direction the sunlight travels.
    sun: vec3<f32>,
    sun_intensity: f32,
    // The sun refracted by flat water, and that water's transmittance for it.
    sun_water: vec3<f32>,
    t_flat: f32,
    light_color: vec3<f32>,
    // The water's index of refraction (1 without water).
    ior: f32,
    absorption: vec3<f32>,
    // `scene.size`: the terrain's square and the floor's without water.
    scene_size: f32,
    // The square the caustics map covers.
    map_size: f32,
    width: u32,
    height: u32,
    supersampling: u32,
    object_count: u32,
    flags: u32,
    // ALBEDO_* of shading.wgsl.
    albedo: u32,
    // TONE_* of shading.wgsl (`ToneMap::code`).
    tone_map: u32,
    // render.rs `sky_ambient` times the sun's intensity: the sky's irradiance on a horizontal
    // surface, before the light's colour.
    ambient: vec3<f32>,
    sun_cos_radius: f32,
    // sky.rs `Sky::coefficients`: the Perez A, B, C, D, E and scale, each over (Y, x, y).
    sky: array<vec4<f32>, 6>,
    // slopes.rs `sample_spread`: the angle one sample covers.
    slope_spread: f32,
    // slopes.rs `sun_slope_variance`.
    sun_variance: f32,
    // Level 0 of slope_moments: the heights' lattice.
    slope_cols: u32,
    slope_rows: u32,
}

// `FinalImageUniform::flags`.
const FLAG_WATER: u32 = 1u;
const FLAG_SURFACE: u32 = 2u;
const FLAG_CAUSTICS: u32 = 4u;
const FLAG_TERRAIN: u32 = 8u;
const FLAG_WRAP_SURFACE: u32 = 16u;
const FLAG_WRAP_CAUSTICS: u32 = 32u;
// No water, and a map of the light through the glass objects (caustic-triangles).
const FLAG_AIR_CAUSTICS: u32 = 64u;
// The caustics are an eye-space image of this camera (cascaded), bound as caustics_map.
const FLAG_EYE_CAUSTICS: u32 = 128u;
// The deck's `Deck::code` sits in these bits of the flags (`flags::DECK_SHIFT`).
const DECK_SHIFT: u32 = 8u;
// The waves' normals filtered by each sample's footprint (render.rs `rough_water`).
const FLAG_FILTER_WATER: u32 = 65536u;

fn deck_kind() -> u32 {
    return (params.flags >> DECK_SHIFT) & 255u;
}

// One object: its material and the root of its tree in bvh_nodes. Mirrors `GpuObject`.
struct Object {
    // Diffuse colour, or glass tint.
    color: vec3<f32>,
    ior: f32,
    root: u32,
    glass: u32,
    _pad: vec2<u32>,
}

@group(0) @binding(0) var<uniform> params: FinalImage;
// The water's heights as the techniques read them (any size, covering the water square) in Hermite
// form (`water_patches.wgsl`), read through grid_sample_hermite with the water's edge rule, as the
// CPU's `Grid::sample`: 4 texels a sample where the bicubic reads 16, for the same surface.
@group(0) @binding(1) var water_height: texture_2d<f32>;
// The terrain's height (R32Float), clamped at its edges.
@group(0) @binding(2) var terrain_height: texture_2d<f32>;
// The caustics map (Rgba32Float or Rgba16Float, rgb used), filtered by hand as `CausticsMap::sample`
// does; or the eye-space caustics (rgb, w < 0 where none, as cascaded's compose.wgsl writes them and
// the CPU twin's texels hold them), read as `EyeSpaceCaustics::sample` does.
@group(0) @binding(3) var caustics_map: texture_2d<f32>;
// The floor's albedo image (Rgba32Float, linear), when there is one.
@group(0) @binding(4) var albedo_image: texture_2d<f32>;
@group(0) @binding(5) var<storage, read> objects: array<Object>;
@group(0) @binding(6) var image: texture_storage_2d<rgba8unorm, write>;
// The bits of the largest |h| and of the largest |∇h| on the slab lattice, as
// final_image_slab.wgsl found them this frame.
@group(0) @binding(7) var<storage, read> slab_max: array<u32>;
// The walls' maps: layer k is wall k of `Wall::ALL` (x = 0, x = size, y = 0, y = size)
// in its first wall_cols[k] columns, row 0 at the floor, the rows up to the rest water level;
// wall_cols is 0 where the technique lit no walls.
@group(0) @binding(8) var wall_maps: texture_2d_array<f32>;
@group(0) @binding(9) var<storage, read> wall_cols: array<u32>;
// The floor map's pyramid below level 0 (caustics_mips.wgsl): its mip k is the pyramid's level
// k + 1 (`CausticsMap::pyramid`).
@group(0) @binding(10) var caustics_mips: texture_2d<f32>;
// The pyramid of the water's slope moments (final_image/slopes.rs), five floats a texel, level
// after level from the heights' lattice up to one texel; read only with FLAG_FILTER_WATER.
@group(2) @binding(0) var<storage, read> slope_moments: array<f32>;

// Stands for the CPU's f64::INFINITY as a ray's range.
const FAR: f32 = 3.0e38;
// render.rs gives up past this recursion depth (`if depth > 6`).
const MAX_DEPTH: u32 = 6u;
// Pending rays: each level of glass, or of the surface met from below, leaves at most one ray
// waiting, so 7 levels need 8 slots.
const RAY_STACK: u32 = 16u;
// The march through the water's slab: its most steps and the fewest steps it may take across
// the slab (render.rs `MARCH_STEPS`, `EVEN_STEPS`). The terrain's search's steps, and bisection
// steps after either.
const MARCH_STEPS: u32 = 512u;
const EVEN_STEPS: u32 = 24u;
// render.rs `SLAB_LATTICE`: the march's shortest step is a quarter of its spacing.
const SLAB_LATTICE: u32 = 128u;
const FLOOR_STEPS: u32 = 64u;
const BISECTIONS: u32 = 30u;

struct Ray {
    o: vec3<f32>,
    d: vec3<f32>,
    // What the CPU would multiply this ray's radiance by on the way back to the pixel.
    weight: vec3<f32>,
    depth: u32,
    // Traced by `trace_under` (else by `trace`).
    under: bool,
}

var<private> rays: array<Ray, RAY_STACK>;
var<private> ray_count: u32;
var<private> pixel_radiance: vec3<f32>;
// Bound on |h| of the water: the slab the surface lies in (render.rs `h_max`), 0 without a surface.
var<private> h_max: f32;
// Bound on the water's slope |∇h| (render.rs `slope_max`), 0 without a surface.
var<private> slope_max: f32;

fn push_ray(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool) {
    if ray_count < RAY_STACK {
        rays[ray_count] = Ray(o, d, weight, depth, under);
        ray_count++;
    }
}

fn emit(weight: vec3<f32>, colour: vec3<f32>) {
    pixel_radiance += weight * colour;
}

fn has(flag: u32) -> bool {
    return (params.flags & flag) != 0u;
}

// A pool (a flat floor) is sunk into a deck; a terrain is open water.
fn is_pool() -> bool {
    return !has(FLAG_TERRAIN);
}

fn sun_radiance() -> vec3<f32> {
    return params.light_color * params.sun_intensity;
}

// render.rs `Tracer::sky_without_sun`: what rough water reflects besides the sun's glint. A
// radiance shows as π times itself in the image's unit (`Tracer::sky`).
fn sky_without_sun(d: vec3<f32>) -> vec3<f32> {
    let s = params.sky;
    let yxy = perez_sky(d, -params.sun, s[0].xyz, s[1].xyz, s[2].xyz, s[3].xyz, s[4].xyz, s[5].xyz);
    return xyy_to_rgb(yxy) * (3.14159265 * sun_radiance());
}

// render.rs `Tracer::sky`: the sky with the sun's disk.
fn sky_radiance(d: vec3<f32>) -> vec3<f32> {
    var disk = 0.0;
    if dot(d, -params.sun) >= params.sun_cos_radius {
        disk = params.sun_disk;
    }
    return sky_without_sun(d) + vec3<f32>(disk * 3.14159265) * sun_radiance();
}

// `Albedo::filtered` over a footprint `extent` wide along x and y (zero: a point).
fn albedo_at(p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    return floor_albedo(params.albedo, albedo_image, p, size, extent);
}

fn absorbed(distance: f32) -> vec3<f32> {
    return exp(-params.absorption * distance);
}

fn water_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return grid_sample_hermite(water_height, p, params.water_size, has(FLAG_WRAP_SURFACE));
}

// render.rs `slab_bounds`: 1.5 times the largest |h| on its lattice, plus 1e-6.
fn slab_half_height() -> f32 {
    if !has(FLAG_SURFACE) {
        return 0.0;
    }
    return bitcast<f32>(slab_max[0]) * 1.5 + 1e-6;
}

// render.rs `slab_bounds`' slope: 1.5 times the largest |∇h| on its lattice, plus 1e-6.
fn slab_slope() -> f32 {
    if !has(FLAG_SURFACE) {
        return 0.0;
    }
    return bitcast<f32>(slab_max[1]) * 1.5 + 1e-6;
}

fn floor_height(p: vec2<f32>) -> f32 {
    if !has(FLAG_TERRAIN) {
        return 0.0;
    }
    return grid_sample(terrain_height, p, params.scene_size, false).x;
}

// Texels of level `level` of the floor map's pyramid (`max(1, size >> level)`, as the mips of
// caustics_mips are sized). Derived, not queried: lavapipe answered textureDimensions at a level
// that varies per invocation with another level's size (measured: wrong texels near the edges).
fn caustics_dims(level: u32) -> vec2<i32> {
    return vec2<i32>(max(textureDimensions(caustics_map) >> vec2<u32>(level), vec2<u32>(1u)));
}

// `CausticsMap::sample` at one level of the pyramid: bilinear between texel centres, clamped or
// wrapped at the edges, by hand with textureLoad (an Rgba32Float texture need not be filterable).
fn caustics_texel(level: u32, i: i32, j: i32, wrap: bool) -> vec3<f32> {
    let dims = caustics_dims(level);
    var c = vec2<i32>(j, i);
    if wrap {
        c = ((c % dims) + dims) % dims;
    } else {
        c = clamp(c, vec2<i32>(0), dims - 1);
    }
    if level == 0u {
        return textureLoad(caustics_map, c, 0).rgb;
    }
    return textureLoad(caustics_mips, c, level - 1u).rgb;
}

fn sample_caustics_level(level: u32, x: f32, y: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(caustics_dims(level));
    let u = x / params.map_size * dims.x - 0.5;
    let v = y / params.map_size * dims.y - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    let i = i32(i0);
    let j = i32(j0);
    let a = caustics_texel(level, i, j, wrap);
    let b = caustics_texel(level, i, j + 1, wrap);
    let c = caustics_texel(level, i + 1, j, wrap);
    let d = caustics_texel(level, i + 1, j + 1, wrap);
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

// map.rs `MapPyramid::trilinear`.
fn caustics_trilinear(p: vec2<f32>, level: f32, wrap: bool) -> vec3<f32> {
    let dims = textureDimensions(caustics_map);
    let last = firstLeadingBit(max(max(dims.x, dims.y), 1u));
    let l0 = min(u32(floor(level)), last);
    var f = level - f32(l0);
    if l0 == last {
        f = 0.0;
    }
    let a = sample_caustics_level(l0, p.x, p.y, wrap);
    if f == 0.0 {
        return a;
    }
    let b = sample_caustics_level(l0 + 1u, p.x, p.y, wrap);
    return a * (1.0 - f) + b * f;
}

// map.rs `MAX_TAPS`.
const MAX_TAPS: f32 = 8.0;

// map.rs `MapPyramid::filtered`: the map's mean over the footprint centred on floor point `p`
// and spanned by `fa`, `fb` (world units), up to MAX_TAPS trilinear taps along its long axis; a
// map that does not wrap reads `beyond` for the taps off its square where `has_beyond`.
fn sample_caustics_filtered(p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    let texels = vec2<f32>(textureDimensions(caustics_map)) / params.map_size;
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
    let taps = clamp(ceil(la / across), 1.0, MAX_TAPS);
    let width = max(la / taps, across);
    let level = max(log2(width / sqrt(3.0)), 0.0);
    let step = long / texels;
    var sum = vec3<f32>(0.0);
    for (var t = 0.0; t < taps; t += 1.0) {
        let q = p + step * ((t + 0.5) / taps - 0.5);
        if has_beyond && !wrap && !inside(q, params.map_size) {
            sum += beyond;
        } else {
            sum += caustics_trilinear(q, level, wrap);
        }
    }
    return sum / taps;
}

// One image axis of render.rs `Spread`: how the rays half a sample spacing either side of a
// sample's ray differ from each other, in origin and in direction.
struct Axis {
    o: vec3<f32>,
    d: vec3<f32>,
}

// render.rs `Spread` (secant ray differentials), carried along a sample's first path: its
// primary ray, that ray's refraction, and the surface's mirror image of either from below.
struct Spread {
    a: Axis,
    b: Axis,
}

// The spread of the ray `trace` or `trace_under` is tracing (none: zero), and the one waiting on
// the stack with the ray in slot `pending_slot` (NO_SLOT: none). At most one ray on the stack has
// one: a path that carries a spread pushes one successor with it, and it is the next popped but
// for a ray of the air through Snell's window, which carries none.
var<private> spread: Spread;
var<private> pending_spread: Spread;
var<private> pending_slot: u32;
const NO_SLOT: u32 = 0xffffffffu;

fn no_spread() -> Spread {
    let zero = Axis(vec3<f32>(0.0), vec3<f32>(0.0));
    return Spread(zero, zero);
}

// `push_ray` of a ray carrying spread `s`.
fn push_ray_spread(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool, s: Spread) {
    if ray_count < RAY_STACK {
        pending_slot = ray_count;
        pending_spread = s;
    }
    push_ray(o, d, weight, depth, under);
}

// `Spread::of_camera`.
fn camera_spread(x: f32, y: f32, h: f32) -> Spread {
    let zero = vec3<f32>(0.0);
    return Spread(
        Axis(zero, camera_ray(x + 0.5 * h, y) - camera_ray(x - 0.5 * h, y)),
        Axis(zero, camera_ray(x, y + 0.5 * h) - camera_ray(x, y - 0.5 * h)),
    );
}

// `Spread::on_plane`, one axis.
fn on_plane(x: Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec2<f32> {
    return on_plane3(x, d, t, m).xy;
}

// `Spread::on_plane3`, one axis.
fn on_plane3(x: Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec3<f32> {
    let cos_m = dot(m, d);
    var v = x.o + x.d * t;
    if abs(cos_m) > 1e-9 {
        v = v - d * (dot(m, v) / cos_m);
    }
    return v;
}

// The water's normal at `q` (up; flat without a surface).
fn water_normal(q: vec2<f32>) -> vec3<f32> {
    if !has(FLAG_SURFACE) {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return height_field_normal(water_height_gradient(q).yz);
}

// A neighbour's direction `d` bent at a facet of normal `m`: refracted into the water from above
// (`reflect_it` false), or reflected back down from below; w = 0 where it does not refract.
fn bend(d: vec3<f32>, m: vec3<f32>, reflect_it: bool) -> vec4<f32> {
    if reflect_it {
        return vec4<f32>(reflect(d, m), 1.0);
    }
    return refract_dir(d, m, 1.0 / params.ior);
}

// `Spread::bent`, one axis.
fn bent_axis(x: Axis, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> Axis {
    let v = x.o + x.d * t;
    var dp = v;
    let cos_n = dot(n, d);
    if abs(cos_n) > 1e-9 {
        dp = v - d * (dot(n, v) / cos_n);
    }
    let ra = bend(normalize(d - x.d * 0.5), water_normal((p - dp * 0.5).xy), reflect_it);
    let rb = bend(normalize(d + x.d * 0.5), water_normal((p + dp * 0.5).xy), reflect_it);
    var out = Axis(dp, vec3<f32>(0.0));
    if ra.w != 0.0 && rb.w != 0.0 {
        out.d = rb.xyz - ra.xyz;
    }
    return out;
}

fn bent_spread(s: Spread, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> Spread {
    return Spread(bent_axis(s.a, p, d, t, n, reflect_it), bent_axis(s.b, p, d, t, n, reflect_it));
}

// `EyeSpaceCaustics::sample`: the floor point projected through the camera onto the eye-space
// image, bilinear between the centres of the valid texels around it, renormalised; w = 0 where the
// valid texels' weight is below EYE_SPACE_MIN_WEIGHT (the caller lights the point as under flat
// water).
const EYE_SPACE_MIN_WEIGHT: f32 = 1e-3;

fn sample_eye_space(p: vec3<f32>) -> vec4<f32> {
    let v = p - params.camera_position;
    let z = dot(v, params.camera_forward);
    if z <= 0.0 {
        return vec4<f32>(0.0);
    }
    let dims = vec2<i32>(textureDimensions(caustics_map));
    // camera_right and camera_up carry tan(fov / 2) (and the aspect): divide by their squared length.
    let sx = dot(v, params.camera_right) / dot(params.camera_right, params.camera_right) / z;
    let sy = dot(v, params.camera_up) / dot(params.camera_up, params.camera_up) / z;
    let u = (sx + 1.0) * 0.5 * f32(dims.x) - 0.5;
    let w = (1.0 - sy) * 0.5 * f32(dims.y) - 0.5;
    let x0 = floor(u);
    let y0 = floor(w);
    let f = vec2<f32>(u - x0, w - y0);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var dy = 0; dy < 2; dy++) {
        for (var dx = 0; dx < 2; dx++) {
            let c = vec2<i32>(i32(x0) + dx, i32(y0) + dy);
            if any(c < vec2<i32>(0)) || any(c >= dims) {
                continue;
            }
            let t = textureLoad(caustics_map, c, 0);
            if t.w < 0.0 {
                continue;
            }
            let wx = select(1.0 - f.x, f.x, dx == 1);
            let wy = select(1.0 - f.y, f.y, dy == 1);
            sum += t.rgb * (wx * wy);
            weight += wx * wy;
        }
    }
    if weight < EYE_SPACE_MIN_WEIGHT {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(sum / weight, 1.0);
}

struct ObjectHit {
    t: f32,
    normal: vec3<f32>,
    k: u32,
    found: bool,
}

fn nearest_object(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> ObjectHit {
    var best: ObjectHit;
    best.found = false;
    best.t = t_max;
    for (var k = 0u; k < params.object_count; k++) {
        let h = bvh_intersect(objects[k].root, o, d, best.t, false);
        if h.found {
            best = ObjectHit(h.t, h.normal, k, true);
        }
    }
    return best;
}

// Only diffuse objects cast shadows.
fn occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < params.object_count; k++) {
        if objects[k].glass == 0u && bvh_intersect(objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

// Any object, glass included.
fn occluded_by_any(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> bool {
    for (var k = 0u; k < params.object_count; k++) {
        if bvh_intersect(objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

fn inside(p: vec2<f32>, size: f32) -> bool {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size;
}

// Distance along the ray to the wall of the pool square it leaves through.
fn wall_distance(o: vec3<f32>, d: vec3<f32>, size: f32) -> f32 {
    var t = FAR;
    for (var a = 0; a < 2; a++) {
        if d[a] > 0.0 {
            t = min(t, (size - o[a]) / d[a]);
        } else if d[a] < 0.0 {
            t = min(t, -o[a] / d[a]);
        }
    }
    return max(t, 0.0);
}

// `wall_at`: the wall of the pool square nearest to p, as its index in `Wall::ALL`.
fn wall_at(p: vec3<f32>, size: f32) -> u32 {
    let d = array<f32, 4>(p.x, size - p.x, p.y, size - p.y);
    var k = 0u;
    for (var i = 1u; i < 4u; i++) {
        if d[i] < d[k] {
            k = i;
        }
    }
    return k;
}

// `WallMap::sample`: bilinear between texel centres, clamped at the wall's edges.
fn sample_wall(k: u32, along: f32, z: f32) -> vec3<f32> {
    let cols = wall_cols[k];
    let rows = textureDimensions(wall_maps).y;
    let u = clamp(along / params.water_size * f32(cols) - 0.5, 0.0, f32(cols - 1u));
    let v = clamp(z / params.water_level * f32(rows) - 0.5, 0.0, f32(rows - 1u));
    let j0 = u32(floor(u));
    let i0 = u32(floor(v));
    let j1 = min(j0 + 1u, cols - 1u);
    let i1 = min(i0 + 1u, rows - 1u);
    let fu = u - f32(j0);
    let fv = v - f32(i0);
    let layer = i32(k);
    let a = textureLoad(wall_maps, vec2<u32>(j0, i0), layer, 0).rgb;
    let b = textureLoad(wall_maps, vec2<u32>(j1, i0), layer, 0).rgb;
    let c = textureLoad(wall_maps, vec2<u32>(j0, i1), layer, 0).rgb;
    let d = textureLoad(wall_maps, vec2<u32>(j1, i1), layer, 0).rgb;
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

// `Tracer::wall_light`: the sun's light on wall point p through its wall's map, or the eye-space
// image where p projects (cascaded); none without either; shadowed by the objects.
fn wall_light(p: vec3<f32>, size: f32) -> vec3<f32> {
    let k = wall_at(p, size);
    var eye = vec4<f32>(0.0);
    if wall_cols[k] == 0u {
        if !has(FLAG_EYE_CAUSTICS) {
            return vec3<f32>(0.0);
        }
        eye = sample_eye_space(p);
        if eye.w == 0.0 {
            return vec3<f32>(0.0);
        }
    }
    var along = p.x;
    var normal = vec3<f32>(0.0, 1.0, 0.0);
    switch k {
        case 0u: {
            along = p.y;
            normal = vec3<f32>(1.0, 0.0, 0.0);
        }
        case 1u: {
            along = p.y;
            normal = vec3<f32>(-1.0, 0.0, 0.0);
        }
        case 3u: {
            normal = vec3<f32>(0.0, -1.0, 0.0);
        }
        default: {}
    }
    var c = eye.rgb;
    if wall_cols[k] != 0u {
        c = sample_wall(k, along, p.z);
    }
    if occluded(p + normal * 1e-4, -params.sun_water, FAR) {
        return vec3<f32>(0.0);
    }
    let e_h = params.sun_intensity * -params.sun.z;
    return c * (e_h * params.t_flat) * params.light_color;
}

// Height of the ray above the water surface at distance t.
fn water_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    return p.z - params.water_level - water_height_gradient(p.xy).x;
}

// The first crossing of the ray with z = level + h(x, y): xyz the point, w the distance (-1: none).
fn hit_water(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    let top = params.water_level + h_max;
    let bottom = params.water_level - h_max;
    if o.z < bottom || d.z >= 0.0 {
        return vec4<f32>(o, -1.0);
    }
    let t0 = max((top - o.z) / d.z, 0.0);
    let t1 = (bottom - o.z) / d.z;
    let t = first_crossing(o, d, t0, t1, 1.0);
    return vec4<f32>(o + d * t, t);
}

// render.rs `first_crossing`: the first t in [t0, t1] where the ray's signed distance to the
// surface, `side * water_gap` (side 1: from above, -1: from below), reaches 0; -1 for none. Each
// step is that distance over the bound on its rate of change, `|d_z| + slope_max |d_xy|` (no
// step can pass a crossing), at least a quarter of the slab lattice's spacing and 1/MARCH_STEPS
// of the interval, at most 1/EVEN_STEPS of it or the shortest step, whichever is longer (a slab
// of micrometres, flat water's, in one step: 1/24 of it would not move an f32 distance of metres);
// then bisections of the step that crossed, or of what is left of [t0, t1] when the march ends
// without one (the slab's far side lies beyond the surface: only rounding, or the steps spent,
// leave it uncrossed).
fn first_crossing(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32, side: f32) -> f32 {
    let rate = abs(d.z) + slope_max * length(d.xy);
    let min_step = params.water_size / f32(4u * SLAB_LATTICE);
    let shortest = max(min_step, (t1 - t0) / f32(MARCH_STEPS));
    let longest = max((t1 - t0) / f32(EVEN_STEPS), min_step);
    var a = t0;
    var gap = side * water_gap(o, d, a);
    if gap <= 0.0 {
        return t0;
    }
    var hi = t1;
    // Each step is at least 1/MARCH_STEPS of the interval; two more for rounding.
    for (var k = 0u; k < MARCH_STEPS + 2u && a < t1; k++) {
        let b = min(a + min(max(gap / rate, shortest), longest), t1);
        let next = side * water_gap(o, d, b);
        if next <= 0.0 {
            hi = b;
            break;
        }
        a = b;
        gap = next;
    }
    var lo = a;
    for (var s = 0u; s < BISECTIONS; s++) {
        let m = 0.5 * (lo + hi);
        if side * water_gap(o, d, m) > 0.0 {
            lo = m;
        } else {
            hi = m;
        }
    }
    return 0.5 * (lo + hi);
}

// render.rs `hit_water_from_below`: the first crossing of a rising underwater ray with
// z = level + h(x, y) (the rest plane without a surface): xyz the point, w the distance (-1: none).
fn hit_water_from_below(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    if d.z <= 0.0 {
        return vec4<f32>(o, -1.0);
    }
    if !has(FLAG_SURFACE) {
        let t = max((params.water_level - o.z) / d.z, 0.0);
        return vec4<f32>(o + d * t, t);
    }
    let top = params.water_level + h_max;
    let bottom = params.water_level - h_max;
    if o.z > top {
        return vec4<f32>(o, -1.0);
    }
    let t0 = max((bottom - o.z) / d.z, 0.0);
    let t1 = (top - o.z) / d.z;
    let t = first_crossing(o, d, t0, t1, -1.0);
    return vec4<f32>(o + d * t, t);
}

// render.rs `leave_water` with `from_below`: a ray meeting the surface at `p` from below splits by
// the Fresnel equations from the dense side: out to the air through Snell's window, the rest (all of
// it beyond the window) mirrored back into the water.
fn leave_water(p: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, t_ray: f32) {
    var n = water_normal(p.xy);
    if has(FLAG_FILTER_WATER) && has(FLAG_SURFACE) {
        n = height_field_normal(water_slopes(p, d).mean);
    }
    let mirrored = bent_spread(spread, p, d, t_ray, n, true);
    let r = refract_dir(d, -n, params.ior);
    var t = 0.0;
    if r.w != 0.0 {
        t = fresnel_transmittance(dot(d, n), params.ior, 1.0);
        push_ray(p + n * 1e-5, r.xyz, w * t, depth + 1u, false);
    }
    push_ray_spread(p - n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, true, mirrored);
}

// render.rs `camera_under_water`: inside the water's square and below the surface there.
fn camera_under_water() -> bool {
    if !has(FLAG_WATER) {
        return false;
    }
    let c = params.camera_position;
    var h = 0.0;
    if has(FLAG_SURFACE) {
        h = water_height_gradient(c.xy).x;
    }
    return inside(c.xy, params.water_size) && c.z < params.water_level + h;
}

// Height of the ray above the floor or terrain at distance t.
fn floor_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    return p.z - floor_height(p.xy);
}

// Where an underwater ray meets the floor or terrain: xyz the point, w the distance (FAR, at `o`,
// for a ray going up).
fn hit_floor(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    if d.z >= 0.0 {
        return vec4<f32>(o, FAR);
    }
    let t_end = -o.z / d.z;
    if !has(FLAG_TERRAIN) {
        return vec4<f32>(o + d * t_end, t_end);
    }
    var a = 0.0;
    for (var k = 1u; k <= FLOOR_STEPS; k++) {
        let b = t_end * f32(k) / f32(FLOOR_STEPS);
        if floor_gap(o, d, b) <= 0.0 {
            var lo = a;
            var hi = b;
            for (var s = 0u; s < BISECTIONS; s++) {
                let m = 0.5 * (lo + hi);
                if floor_gap(o, d, m) > 0.0 {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            let t = 0.5 * (lo + hi);
            return vec4<f32>(o + d * t, t);
        }
        a = b;
    }
    return vec4<f32>(o + d * t_end, t_end);
}

// The floor at `p`, its caustics and albedo filtered over the sample's footprint `fa`, `fb`.
fn shade_floor(p: vec3<f32>, fa: vec2<f32>, fb: vec2<f32>) -> vec3<f32> {
    let size = params.water_size;
    let albedo = albedo_at(p.xy, size, abs(fa) + abs(fb));
    let e_h = params.sun_intensity * -params.sun.z;
    let flat = absorbed((params.water_level - p.z) / -params.sun_water.z);
    var relative = flat;
    // Beyond a map that does not tile, the flat water's light, tap by tap (render.rs
    // `shade_floor`).
    if has(FLAG_CAUSTICS) {
        relative = sample_caustics_filtered(p.xy, fa, fb, has(FLAG_WRAP_CAUSTICS), flat, true);
    } else if has(FLAG_EYE_CAUSTICS) {
        let e = sample_eye_space(p);
        if e.w != 0.0 {
            relative = e.rgb;
        }
    }
    var shadow = 1.0;
    if occluded(p + vec3<f32>(0.0, 0.0, 1e-4), -params.sun_water, FAR) {
        shadow = 0.0;
    }
    let direct = relative * (e_h * params.t_flat * shadow);
    let ambient = params.ambient * absorbed(params.water_level);
    return albedo * (direct + ambient) * params.light_color;
}

fn shade_object(p: vec3<f32>, n_out: vec3<f32>, d: vec3<f32>, k: u32, depth: u32, under: bool, w: vec3<f32>) {
    let obj = objects[k];
    // Closed meshes with outward normals: the ray enters where it meets the outside.
    let entering = dot(n_out, d) < 0.0;
    let n = select(-n_out, n_out, entering);
    if obj.glass == 0u {
        var sun_dir = params.sun;
        var t = 1.0;
        if under {
            sun_dir = params.sun_water;
            t = params.t_flat;
        }
        let lambert = max(dot(n, -sun_dir), 0.0);
        var lit = 0.0;
        if lambert > 0.0 && !occluded(p + n * 1e-4, -sun_dir, FAR) {
            lit = 1.0;
        }
        var water_path = vec3<f32>(1.0);
        if has(FLAG_WATER) && under {
            water_path = absorbed(max(params.water_level - p.z, 0.0) / -sun_dir.z);
        }
        emit(w, obj.color * (water_path * (params.sun_intensity * lambert * lit * t) + params.ambient) * params.light_color);
        return;
    }
    var outside_ior = 1.0;
    if under {
        outside_ior = params.ior;
    }
    var n1 = outside_ior;
    var n2 = obj.ior;
    if !entering {
        n1 = obj.ior;
        n2 = outside_ior;
    }
    let cos_i = -dot(d, n);
    let t = fresnel_transmittance(cos_i, n1, n2);
    push_ray(p + n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, under);
    let r = refract_dir(d, n, n1 / n2);
    if r.w != 0.0 {
        push_ray(p - n * 1e-5, r.xyz, w * t * obj.color, depth + 1u, under);
    }
}

// Above the water, outside the pool: the deck, or the sky.
fn shade_above(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    if is_pool() && d.z < 0.0 {
        let deck = params.water_level + 0.1 * min(params.water_size, 1.0) + h_max;
        let t = (deck - o.z) / d.z;
        if t > 0.0 {
            let p = o + d * t;
            // render.rs `shade_above`: a sample's footprint on the deck, stretched by the
            // grazing angle; the sample's angle is a pixel's over the samples per side
            // (`sample_spread`), |camera_up| being tan(fov_y / 2).
            let spread = 2.0 * length(params.camera_up) / f32(params.height) / f32(max(params.supersampling, 1u));
            let footprint = length(p - o) * spread / max(abs(d.z), 0.05);
            let albedo = deck_albedo(deck_kind(), p.xy, params.water_size, footprint);
            return albedo * (vec3<f32>(params.sun_intensity * -params.sun.z) + params.ambient) * params.light_color;
        }
    }
    if !is_pool() && d.z < 0.0 {
        // Beyond the surface's slab the open sea: the flat-water Fresnel reflection of the sky.
        let r = fresnel_transmittance(-d.z, 1.0, params.ior);
        return sky_radiance(reflect(d, vec3<f32>(0.0, 0.0, 1.0))) * (1.0 - r);
    }
    return sky_radiance(d);
}

// No water in the scene: objects over the floor plane in open air.
fn trace_air(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>) {
    var t_floor = FAR;
    if d.z < 0.0 {
        t_floor = -o.z / d.z;
    }
    let obj = nearest_object(o, d, t_floor);
    if obj.found {
        shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
        return;
    }
    if t_floor < FAR {
        let p = o + d * t_floor;
        let fa = on_plane(spread.a, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let fb = on_plane(spread.b, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let albedo = albedo_at(p.xy, params.scene_size, abs(fa) + abs(fb));
        let start = p + vec3<f32>(0.0, 0.0, 1e-5);
        var lit = 1.0;
        var caustic = vec3<f32>(0.0);
        if has(FLAG_AIR_CAUSTICS) {
            caustic = sample_caustics_filtered(p.xy, fa, fb, false, vec3<f32>(0.0), false);
            if occluded_by_any(start, -params.sun, FAR) {
                lit = 0.0;
            }
        } else if occluded(start, -params.sun, FAR) {
            lit = 0.0;
        }
        let e = (vec3<f32>(lit) + caustic) * (params.sun_intensity * -params.sun.z) + params.ambient;
        emit(w, albedo * e * params.light_color);
        return;
    }
    emit(w, sky_radiance(d));
}

// The waves' normals filtered by each sample's footprint: the GPU twin of
// caustics-core's water/slopes.rs (`SlopePyramid::filtered`, `visible_facets`, `glint`) and
// render.rs `Tracer::rough_water`, where the filter is written down and its sources cited (LEAN
// mapping; Heitz 2014's visible normals; Cox and Munk's glint with Smith's masking).

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

fn trace(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>) {
    if !has(FLAG_WATER) {
        trace_air(o, d, depth, w);
        return;
    }
    let size = params.water_size;
    // Water surface hit, searched in the slab |z - level| <= h_max.
    var water = vec4<f32>(o, -1.0);
    if has(FLAG_SURFACE) {
        water = hit_water(o, d);
    }
    let hit = water.w >= 0.0;
    let obj = nearest_object(o, d, select(FAR, water.w, hit));
    if obj.found {
        shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
        return;
    }
    if !hit {
        // A pool is sunk into a deck around it; beyond the terrain's square the world goes on.
        emit(w, shade_above(o, d));
        return;
    }
    let p = water.xyz;
    if is_pool() && !inside(p.xy, size) {
        emit(w, shade_above(o, d));
        return;
    }
    var n = height_field_normal(water_height_gradient(p.xy).yz);
    var t_view: f32;
    if has(FLAG_FILTER_WATER) {
        let rough = rough_water(p, d, &n);
        t_view = rough.w;
        emit(w, rough.xyz);
    } else {
        t_view = fresnel_transmittance(-dot(d, n), 1.0, params.ior);
        emit(w, sky_radiance(reflect(d, n)) * (1.0 - t_view));
    }
    let r = refract_dir(d, n, 1.0 / params.ior);
    if r.w == 0.0 {
        return;
    }
    push_ray_spread(p, r.xyz, w * t_view, depth, true, bent_spread(spread, p, d, water.w, n, false));
}

// Radiance arriving along `d` at point `o` under the water.
fn trace_under(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>) {
    let size = params.water_size;
    var floor_hit = hit_floor(o, d);
    // A ray going up ends at the surface seen from below instead; the branches below read
    // `floor_hit` as the ray's end, wherever it is.
    let ceiling = hit_water_from_below(o, d);
    if ceiling.w >= 0.0 {
        floor_hit = ceiling;
    }
    let t_floor = floor_hit.w;
    let obj = nearest_object(o, d, t_floor);
    if obj.found {
        shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, true, w * absorbed(obj.t));
    } else if is_pool() && !inside(floor_hit.xy, size) {
        // The ray meets a pool wall first: tiles lit by the ambient light, and by the sun through
        // the wall's map where the technique lit the walls.
        let t = wall_distance(o, d, size);
        let p = o + d * t;
        // The wall's tiles filtered over the sample's footprint on the wall's plane.
        let m = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), wall_at(p, size) < 2u);
        let fa = on_plane3(spread.a, d, t, m);
        let fb = on_plane3(spread.b, d, t, m);
        let extent = vec2<f32>(abs(fa.x + fa.y) + abs(fb.x + fb.y), abs(fa.z) + abs(fb.z));
        let a = albedo_at(vec2<f32>(p.x + p.y, p.z), size, extent);
        emit(w * absorbed(t), a * (params.ambient * params.light_color + wall_light(p, size)));
    } else if ceiling.w >= 0.0 {
        leave_water(floor_hit.xyz, d, depth, w * absorbed(t_floor), t_floor);
    } else {
        var m = vec3<f32>(0.0, 0.0, 1.0);
        if has(FLAG_TERRAIN) {
            m = height_field_normal(grid_sample(terrain_height, floor_hit.xy, params.scene_size, false).yz);
        }
        let fa = on_plane(spread.a, d, t_floor, m);
        let fb = on_plane(spread.b, d, t_floor, m);
        emit(w * absorbed(t_floor), shade_floor(floor_hit.xyz, fa, fb));
    }
}

// Everything a primary ray brings back: `Tracer::trace_from(o, d, 0, under)` unrolled.
fn radiance(o: vec3<f32>, d: vec3<f32>, under: bool, s: Spread) -> vec3<f32> {
    pixel_radiance = vec3<f32>(0.0);
    ray_count = 0u;
    pending_slot = NO_SLOT;
    push_ray_spread(o, d, vec3<f32>(1.0), 0u, under, s);
    while ray_count > 0u {
        ray_count--;
        let r = rays[ray_count];
        spread = no_spread();
        if ray_count == pending_slot {
            spread = pending_spread;
            pending_slot = NO_SLOT;
        }
        if r.depth > MAX_DEPTH {
            continue;
        }
        if r.under {
            trace_under(r.o, r.d, r.depth, r.weight);
        } else {
            trace(r.o, r.d, r.depth, r.weight);
        }
    }
    return pixel_radiance;
}

// `Camera::ray`: the primary ray through image point (x + 0.5, y + 0.5), y down the image.
fn camera_ray(x: f32, y: f32) -> vec3<f32> {
    let sx = 2.0 * (x + 0.5) / f32(params.width) - 1.0;
    let sy = 1.0 - 2.0 * (y + 0.5) / f32(params.height);
    return normalize(params.camera_forward + params.camera_right * sx + params.camera_up * sy);
}

// render.rs `sample_offset`: sample (sx, sy) of a pixel's n x n on a rotated grid (n-rooks).
fn sample_offset(sx: u32, sy: u32, n: u32) -> vec2<f32> {
    let m = f32(n);
    return vec2<f32>(
        (f32(sx) + (f32(sy) + 0.5) / m) / m,
        (f32(sy) + (m - 1.0 - f32(sx) + 0.5) / m) / m,
    );
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    h_max = slab_half_height();
    slope_max = slab_slope();
    let under = camera_under_water();
    let n = max(params.supersampling, 1u);
    var c = vec3<f32>(0.0);
    for (var sy = 0u; sy < n; sy++) {
        for (var sx = 0u; sx < n; sx++) {
            let o = sample_offset(sx, sy, n);
            let x = f32(id.x) + o.x - 0.5;
            let y = f32(id.y) + o.y - 0.5;
            let s = camera_spread(x, y, 1.0 / f32(n));
            c += radiance(params.camera_position, camera_ray(x, y), under, s);
        }
    }
    c = c / f32(n * n) * params.exposure;
    textureStore(image, id.xy, vec4<f32>(tone_map(c, params.tone_map), 1.0));
}
