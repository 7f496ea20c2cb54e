@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= package__1final_image__2final_image_inputs_params.width || id.y >= package__1final_image__2final_image_inputs_params.height {
        return;
    }
    package__1final_image__2final_image_inputs__1h_max = package__1final_image__2final_image_inputs__2slab_half_height();
    package__1final_image__2final_image_inputs__1slope_max = package__1final_image__2final_image_inputs__1slab_slope();
    let under = package__1final_image__2final_image_march__2camera_under_water();
    let n = max(package__1final_image__2final_image_inputs_params.supersampling, 1u);
    var raster = package__1final_image__2final_image_inputs__1NO_GUIDE;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) && !under {
        raster = nearest_raster(vec2<i32>(id.xy), n > 1u);
    }
    var c = vec3<f32>(0.0);
    for (var sy = 0u; sy < n; sy++) {
        for (var sx = 0u; sx < n; sx++) {
            let o = sample_offset(sx, sy, n);
            let x = f32(id.x) + o.x - 0.5;
            let y = f32(id.y) + o.y - 0.5;
            let s = package__1final_image__2final_image_spread__1camera_spread(x, y, 1.0 / f32(n));
            package__1final_image__2final_image_inputs_guide = raster;
            c += radiance(package__1final_image__2final_image_inputs_params.camera_position, package__1final_image__2final_image_spread__1camera_ray(x, y), under, s);
        }
    }
    c = c / f32(n * n) * package__1final_image__2final_image_inputs_params.exposure;
    textureStore(package__1final_image__2final_image_inputs_image, id.xy, vec4<f32>(package_shaders_shading__1tone_map(c, package__1final_image__2final_image_inputs_params.tone_map), 1.0));
}

fn nearest_raster(p: vec2<i32>, around: bool) -> f32 {
    if !around {
        return textureLoad(package__1final_image__2final_image_inputs__1surface_hits, p, 0).r;
    }
    let last = vec2<i32>(i32(package__1final_image__2final_image_inputs_params.width) - 1, i32(package__1final_image__2final_image_inputs_params.height) - 1);
    var nearest = package__1final_image__2final_image_inputs_FAR;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let t = textureLoad(package__1final_image__2final_image_inputs__1surface_hits, clamp(p + vec2<i32>(dx, dy), vec2<i32>(0), last), 0).r;
            if t >= 0.0 {
                nearest = min(nearest, t);
            }
        }
    }
    return select(-1.0, nearest, nearest < package__1final_image__2final_image_inputs_FAR);
}

const package__1final_image__2final_image_inputs_BISECTIONS: u32 = 30u;

const package__1final_image__2final_image_inputs_FAR: f32 = 3e38;

@id(0)
override package__1final_image__2final_image_inputs_FLAGS: u32;

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
    _pad: u32,
    tone_map: u32,
    ambient: vec3<f32>,
    sun_cos_radius: f32,
    sky: array<vec4<f32>, 6>,
    slope_spread: f32,
    sun_variance: f32,
    slope_cols: u32,
    slope_rows: u32
}

struct package__1final_image__2final_image_inputs_LightSpace {
    receivers: package_shaders_receivers_Receivers,
    absorption: vec4<f32>
}

struct package__1final_image__2final_image_inputs_Object {
    color: vec3<f32>,
    ior: f32,
    root: u32,
    glass: u32,
    _pad: vec2<u32>
}

struct package__1final_image__2final_image_inputs_Ray {
    o: vec3<f32>,
    d: vec3<f32>,
    weight: vec3<f32>,
    depth: u32,
    under: bool
}

const package__1final_image__2final_image_inputs__1ALBEDO_SHIFT: u32 = 18u;

const package__1final_image__2final_image_inputs__1DECK_SHIFT: u32 = 8u;

const package__1final_image__2final_image_inputs__1EVEN_STEPS: u32 = 24u;

const package__1final_image__2final_image_inputs__1FLAG_CAUSTICS: u32 = 4u;

const package__1final_image__2final_image_inputs__1FLAG_OBJECTS: u32 = 1048576u;

const package__1final_image__2final_image_inputs__1FLAG_SURFACE: u32 = 2u;

const package__1final_image__2final_image_inputs__1FLAG_TERRAIN: u32 = 8u;

const package__1final_image__2final_image_inputs__1FLAG_WATER: u32 = 1u;

const package__1final_image__2final_image_inputs__1FLOOR_STEPS: u32 = 64u;

const package__1final_image__2final_image_inputs__1MARCH_STEPS: u32 = 512u;

const package__1final_image__2final_image_inputs__1MAX_DEPTH: u32 = 6u;

const package__1final_image__2final_image_inputs__1NO_GUIDE: f32 = -2.0;

const package__1final_image__2final_image_inputs__1RAY_STACK: u32 = 16u;

const package__1final_image__2final_image_inputs__1ROOT_TOLERANCE: f32 = 0.0001;

const package__1final_image__2final_image_inputs__1SLAB_LATTICE: u32 = 128u;

fn package__1final_image__2final_image_inputs__1albedo_at(p: vec2<f32>, size: f32, extent: vec2<f32>) -> vec3<f32> {
    return package_shaders_shading__1floor_albedo(package__1final_image__2final_image_inputs__1albedo_kind(), package__1final_image__2final_image_inputs__1albedo_image, p, size, extent);
}

@group(0) @binding(4)
var package__1final_image__2final_image_inputs__1albedo_image: texture_2d<f32>;

fn package__1final_image__2final_image_inputs__1albedo_kind() -> u32 {
    return (package__1final_image__2final_image_inputs_FLAGS >> package__1final_image__2final_image_inputs__1ALBEDO_SHIFT) & 3u;
}

@group(0) @binding(3)
var package__1final_image__2final_image_inputs__1caustics_map: texture_2d<f32>;

@group(0) @binding(10)
var package__1final_image__2final_image_inputs__1caustics_mips: texture_2d<f32>;

fn package__1final_image__2final_image_inputs__1deck_kind() -> u32 {
    return (package__1final_image__2final_image_inputs_FLAGS >> package__1final_image__2final_image_inputs__1DECK_SHIFT) & 255u;
}

fn package__1final_image__2final_image_inputs__1floor_height(p: vec2<f32>) -> f32 {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN) {
        return 0.0;
    }
    return package__1final_image__2final_image_inputs__2terrain_height_gradient(p).x;
}

var<private> package__1final_image__2final_image_inputs__1h_max: f32;

fn package__1final_image__2final_image_inputs__1is_pool() -> bool {
    return !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN);
}

@group(0) @binding(12)
var package__1final_image__2final_image_inputs__1light_deposit: texture_2d<f32>;

@group(0) @binding(13)
var package__1final_image__2final_image_inputs__1light_heights: texture_2d<f32>;

@group(0) @binding(11)
var<uniform> package__1final_image__2final_image_inputs__1light_space: package__1final_image__2final_image_inputs_LightSpace;

var<private> package__1final_image__2final_image_inputs__1pixel_radiance: vec3<f32>;

fn package__1final_image__2final_image_inputs__1push_ray(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        package__1final_image__2final_image_inputs_rays[package__1final_image__2final_image_inputs__1ray_count] = package__1final_image__2final_image_inputs_Ray(o, d, weight, depth, under);
        package__1final_image__2final_image_inputs__1ray_count++;
    }
}

var<private> package__1final_image__2final_image_inputs__1ray_count: u32;

fn package__1final_image__2final_image_inputs__1sky_radiance(d: vec3<f32>) -> vec3<f32> {
    var disk = 0.0;
    if dot(d, -package__1final_image__2final_image_inputs_params.sun) >= package__1final_image__2final_image_inputs_params.sun_cos_radius {
        disk = package__1final_image__2final_image_inputs_params.sun_disk;
    }
    return package__1final_image__2final_image_inputs__2sky_without_sun(d) + vec3<f32>(disk * 3.14159265) * package__1final_image__2final_image_inputs__1sun_radiance();
}

@group(0) @binding(7)
var<storage, read> package__1final_image__2final_image_inputs__1slab_max: array<u32>;

fn package__1final_image__2final_image_inputs__1slab_slope() -> f32 {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        return 0.0;
    }
    return package__1final_image__2final_image_inputs__1slope_bound();
}

fn package__1final_image__2final_image_inputs__1slope_bound() -> f32 {
    return bitcast<f32>(package__1final_image__2final_image_inputs__1slab_max[1]) * 1.5 + 1e-6;
}

var<private> package__1final_image__2final_image_inputs__1slope_max: f32;

@group(2) @binding(0)
var<storage, read> package__1final_image__2final_image_inputs__1slope_moments: array<f32>;

fn package__1final_image__2final_image_inputs__1sun_radiance() -> vec3<f32> {
    return package__1final_image__2final_image_inputs_params.light_color * package__1final_image__2final_image_inputs_params.sun_intensity;
}

@group(0) @binding(14)
var package__1final_image__2final_image_inputs__1surface_hits: texture_2d<f32>;

@group(0) @binding(2)
var package__1final_image__2final_image_inputs__1terrain_height: texture_2d<f32>;

@group(0) @binding(9)
var<storage, read> package__1final_image__2final_image_inputs__1wall_cols: array<u32>;

@group(0) @binding(8)
var package__1final_image__2final_image_inputs__1wall_maps: texture_2d_array<f32>;

@group(0) @binding(1)
var package__1final_image__2final_image_inputs__1water_height: texture_2d<f32>;

const package__1final_image__2final_image_inputs__2FLAG_AIR_CAUSTICS: u32 = 64u;

const package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS: u32 = 128u;

const package__1final_image__2final_image_inputs__2FLAG_FILTER_WATER: u32 = 65536u;

const package__1final_image__2final_image_inputs__2FLAG_LIGHT_SPACE: u32 = 131072u;

const package__1final_image__2final_image_inputs__2FLAG_WRAP_CAUSTICS: u32 = 32u;

const package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE: u32 = 16u;

fn package__1final_image__2final_image_inputs__2sample_caustics_filtered(p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    return package_shaders__1caustics_sampling__1caustics_filtered(package__1final_image__2final_image_inputs__1caustics_map, package__1final_image__2final_image_inputs__1caustics_mips, 1u, p, fa, fb, package__1final_image__2final_image_inputs_params.map_size, wrap, beyond, has_beyond);
}

fn package__1final_image__2final_image_inputs__2sky_without_sun(d: vec3<f32>) -> vec3<f32> {
    let s = package__1final_image__2final_image_inputs_params.sky;
    let yxy = package_shaders_shading__1perez_sky(d, -package__1final_image__2final_image_inputs_params.sun, s[0].xyz, s[1].xyz, s[2].xyz, s[3].xyz, s[4].xyz, s[5].xyz);
    return package_shaders_shading__2xyy_to_rgb(yxy) * (3.14159265 * package__1final_image__2final_image_inputs__1sun_radiance());
}

fn package__1final_image__2final_image_inputs__2slab_half_height() -> f32 {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        return 0.0;
    }
    return bitcast<f32>(package__1final_image__2final_image_inputs__1slab_max[0]) * 1.5 + 1e-6;
}

fn package__1final_image__2final_image_inputs__2terrain_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return package_shaders_water__2grid_sample_hermite(package__1final_image__2final_image_inputs__1terrain_height, p, package__1final_image__2final_image_inputs_params.scene_size, false);
}

fn package__1final_image__2final_image_inputs__2water_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return package_shaders_water__2grid_sample_hermite(package__1final_image__2final_image_inputs__1water_height, p, package__1final_image__2final_image_inputs_params.water_size, package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE));
}

const package__1final_image__2final_image_inputs__3SET_AT_RUN_TIME: u32 = package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE | package__1final_image__2final_image_inputs__2FLAG_WRAP_CAUSTICS;

fn package__1final_image__2final_image_inputs_absorbed(distance: f32) -> vec3<f32> {
    return exp(-package__1final_image__2final_image_inputs_params.absorption * distance);
}

fn package__1final_image__2final_image_inputs_emit(weight: vec3<f32>, colour: vec3<f32>) {
    package__1final_image__2final_image_inputs__1pixel_radiance += weight * colour;
}

var<private> package__1final_image__2final_image_inputs_guide: f32;

fn package__1final_image__2final_image_inputs_has(flag: u32) -> bool {
    if (flag & package__1final_image__2final_image_inputs__3SET_AT_RUN_TIME) != 0u {
        return (package__1final_image__2final_image_inputs_params.flags & flag) != 0u;
    }
    return (package__1final_image__2final_image_inputs_FLAGS & flag) != 0u;
}

@group(0) @binding(6)
var package__1final_image__2final_image_inputs_image: texture_storage_2d<rgba8unorm, write>;

@group(0) @binding(5)
var<storage, read> package__1final_image__2final_image_inputs_objects: array<package__1final_image__2final_image_inputs_Object>;

@group(0) @binding(0)
var<uniform> package__1final_image__2final_image_inputs_params: package__1final_image__2final_image_inputs_FinalImage;

var<private> package__1final_image__2final_image_inputs_rays: array<package__1final_image__2final_image_inputs_Ray, package__1final_image__2final_image_inputs__1RAY_STACK>;

struct package__1final_image__2final_image_march_Start {
    t: f32,
    gap: f32,
    known: bool
}

fn package__1final_image__2final_image_march__1crossing_after(o: vec3<f32>, d: vec3<f32>, t0: f32, gap0: f32, t1: f32, side: f32) -> f32 {
    let rate = abs(d.z) + package__1final_image__2final_image_inputs__1slope_max * length(d.xy);
    let min_step = package__1final_image__2final_image_inputs_params.water_size / f32(4u * package__1final_image__2final_image_inputs__1SLAB_LATTICE);
    let shortest = max(min_step, (t1 - t0) / f32(package__1final_image__2final_image_inputs__1MARCH_STEPS));
    let longest = max((t1 - t0) / f32(package__1final_image__2final_image_inputs__1EVEN_STEPS), min_step);
    var a = t0;
    var gap = gap0;
    var hi = t1;
    var g_hi = 1.0;
    var crossed = false;
    for (var k = 0u; k < package__1final_image__2final_image_inputs__1MARCH_STEPS + 2u && a < t1; k++) {
        let b = min(a + min(max(gap / rate, shortest), longest), t1);
        let next = side * package__1final_image__2final_image_march__1water_gap(o, d, b);
        if next <= 0.0 {
            hi = b;
            g_hi = next;
            crossed = true;
            break;
        }
        a = b;
        gap = next;
    }
    if !crossed {
        g_hi = side * package__1final_image__2final_image_march__1water_gap(o, d, hi);
        if g_hi > 0.0 {
            return hi;
        }
    }
    return package__1final_image__2final_image_march__1regula_falsi(o, d, side, a, gap, hi, g_hi, package__1final_image__2final_image_inputs__1ROOT_TOLERANCE * min_step);
}

fn package__1final_image__2final_image_march__1crossing_gradient(p: vec3<f32>, t: f32) -> vec2<f32> {
    if package__1final_image__2final_image_march__1last_read.x == t {
        return package__1final_image__2final_image_march__1last_read.zw;
    }
    return package__1final_image__2final_image_inputs__2water_height_gradient(p.xy).yz;
}

fn package__1final_image__2final_image_march__1floor_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    return p.z - package__1final_image__2final_image_inputs__1floor_height(p.xy);
}

fn package__1final_image__2final_image_march__1guided_start(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32, raster: f32) -> package__1final_image__2final_image_march_Start {
    let size = package__1final_image__2final_image_inputs_params.water_size;
    let a = o.xy + d.xy * t0;
    let top = package__1final_image__2final_image_march_Start(t0, 0.0, false);
    if raster < 0.0 {
        let b = o.xy + d.xy * t1;
        let outside = (a.x < 0.0 && b.x < 0.0) || (a.y < 0.0 && b.y < 0.0) || (a.x > size && b.x > size) || (a.y > size && b.y > size);
        if package__1final_image__2final_image_inputs__1is_pool() && outside {
            return package__1final_image__2final_image_march_Start(t1, 0.0, false);
        }
        return top;
    }
    let start = raster * (1.0 - 1e-5);
    if start <= t0 || !package__1final_image__2final_image_receivers_inside(a, size) {
        return top;
    }
    let gap = package__1final_image__2final_image_march__1water_gap(o, d, start);
    if gap <= 0.0 {
        return top;
    }
    return package__1final_image__2final_image_march_Start(start, gap, true);
}

fn package__1final_image__2final_image_march__1hit_floor(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    if d.z >= 0.0 {
        return vec4<f32>(o, package__1final_image__2final_image_inputs_FAR);
    }
    let t_end = -o.z / d.z;
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN) {
        return vec4<f32>(o + d * t_end, t_end);
    }
    let step = t_end / f32(package__1final_image__2final_image_inputs__1FLOOR_STEPS);
    var a = 0.0;
    var ga = package__1final_image__2final_image_march__1floor_gap(o, d, 0.0);
    if ga <= 0.0 {
        return vec4<f32>(o, 0.0);
    }
    for (var k = 1u; k <= package__1final_image__2final_image_inputs__1FLOOR_STEPS; k++) {
        let b = step * f32(k);
        let gb = package__1final_image__2final_image_march__1floor_gap(o, d, b);
        if gb <= 0.0 {
            var br = package_shaders_receivers_Bracket(a, ga, b, gb, 0);
            var m = b;
            for (var s = 0u; s < package__1final_image__2final_image_inputs_BISECTIONS; s++) {
                m = package_shaders_receivers_chord(br);
                let gm = package__1final_image__2final_image_march__1floor_gap(o, d, m);
                br = package_shaders_receivers_narrowed(br, m, gm);
                if abs(gm) < package__1final_image__2final_image_inputs__1ROOT_TOLERANCE * step || br.b - br.a < package__1final_image__2final_image_inputs__1ROOT_TOLERANCE * step {
                    break;
                }
            }
            return vec4<f32>(o + d * m, m);
        }
        a = b;
        ga = gb;
    }
    return vec4<f32>(o + d * t_end, t_end);
}

fn package__1final_image__2final_image_march__1hit_surface(o: vec3<f32>, d: vec3<f32>, under: bool) -> vec4<f32> {
    let raster = package__1final_image__2final_image_inputs_guide;
    package__1final_image__2final_image_inputs_guide = package__1final_image__2final_image_inputs__1NO_GUIDE;
    package__1final_image__2final_image_march__1last_read.x = -1.0;
    let none = vec4<f32>(o, -1.0);
    let top = package__1final_image__2final_image_inputs_params.water_level + package__1final_image__2final_image_inputs__1h_max;
    let bottom = package__1final_image__2final_image_inputs_params.water_level - package__1final_image__2final_image_inputs__1h_max;
    var start = package__1final_image__2final_image_march_Start(0.0, 0.0, false);
    var t1: f32;
    var side = 1.0;
    if under {
        if d.z <= 0.0 {
            return none;
        }
        if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
            let t = max((package__1final_image__2final_image_inputs_params.water_level - o.z) / d.z, 0.0);
            return vec4<f32>(o + d * t, t);
        }
        if o.z > top {
            return none;
        }
        start.t = max((bottom - o.z) / d.z, 0.0);
        t1 = (top - o.z) / d.z;
        side = -1.0;
    }
    else {
        if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) || o.z < bottom || d.z >= 0.0 {
            return none;
        }
        let t0 = max((top - o.z) / d.z, 0.0);
        t1 = (bottom - o.z) / d.z;
        start.t = t0;
        if raster != package__1final_image__2final_image_inputs__1NO_GUIDE {
            start = package__1final_image__2final_image_march__1guided_start(o, d, t0, t1, raster);
        }
    }
    var t = start.t;
    if t != t1 {
        var gap = start.gap;
        if !start.known {
            gap = side * package__1final_image__2final_image_march__1water_gap(o, d, t);
        }
        if gap > 0.0 {
            t = package__1final_image__2final_image_march__1crossing_after(o, d, t, gap, t1, side);
        }
    }
    return vec4<f32>(o + d * t, t);
}

var<private> package__1final_image__2final_image_march__1last_read: vec4<f32>;

fn package__1final_image__2final_image_march__1leave_water(p: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, t_ray: f32) {
    var n = package__1final_image__2final_image_spread__1water_normal(p.xy);
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_FILTER_WATER) && package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        n = package_shaders_optics__2height_field_normal(package__1final_image__3final_image_rough_water__1water_slopes(p, d).mean);
    }
    let mirrored = package__1final_image__2final_image_spread__1bent_spread(package__1final_image__2final_image_spread_spread, p, d, t_ray, n, true);
    let r = package_shaders_optics__1refract_dir(d, -n, package__1final_image__2final_image_inputs_params.ior);
    var t = 0.0;
    if r.w != 0.0 {
        t = package_shaders_optics__1fresnel_transmittance(dot(d, n), package__1final_image__2final_image_inputs_params.ior, 1.0);
        package__1final_image__2final_image_inputs__1push_ray(p + n * 1e-5, r.xyz, w * t, depth + 1u, false);
    }
    package__1final_image__2final_image_spread__2push_ray_spread(p - n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, true, mirrored);
}

fn package__1final_image__2final_image_march__1regula_falsi(o: vec3<f32>, d: vec3<f32>, side: f32, a: f32, ga: f32, b: f32, gb: f32, tol: f32) -> f32 {
    var br = package_shaders_receivers_Bracket(a, ga, b, gb, 0);
    var m = b;
    for (var s = 0u; s < package__1final_image__2final_image_inputs_BISECTIONS; s++) {
        m = package_shaders_receivers_chord(br);
        let gm = side * package__1final_image__2final_image_march__1water_gap(o, d, m);
        br = package_shaders_receivers_narrowed(br, m, gm);
        if abs(gm) < tol || br.b - br.a < tol {
            break;
        }
    }
    return m;
}

fn package__1final_image__2final_image_march__1water_gap(o: vec3<f32>, d: vec3<f32>, t: f32) -> f32 {
    let p = o + d * t;
    let h = package__1final_image__2final_image_inputs__2water_height_gradient(p.xy);
    package__1final_image__2final_image_march__1last_read = vec4<f32>(t, h);
    return p.z - package__1final_image__2final_image_inputs_params.water_level - h.x;
}

fn package__1final_image__2final_image_march__2camera_under_water() -> bool {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_WATER) {
        return false;
    }
    let c = package__1final_image__2final_image_inputs_params.camera_position;
    var h = 0.0;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        h = package__1final_image__2final_image_inputs__2water_height_gradient(c.xy).x;
    }
    return package__1final_image__2final_image_receivers_inside(c.xy, package__1final_image__2final_image_inputs_params.water_size) && c.z < package__1final_image__2final_image_inputs_params.water_level + h;
}

struct package__1final_image__2final_image_receivers_ObjectHit {
    t: f32,
    normal: vec3<f32>,
    k: u32,
    found: bool
}

fn package__1final_image__2final_image_receivers__1nearest_object(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> package__1final_image__2final_image_receivers_ObjectHit {
    var best: package__1final_image__2final_image_receivers_ObjectHit;
    best.found = false;
    best.t = t_max;
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        let h = package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, best.t, false);
        if h.found {
            best = package__1final_image__2final_image_receivers_ObjectHit(h.t, h.normal, k, true);
        }
    }
    return best;
}

fn package__1final_image__2final_image_receivers__1wall_distance(o: vec3<f32>, d: vec3<f32>, size: f32) -> f32 {
    var t = package__1final_image__2final_image_inputs_FAR;
    for (var a = 0; a < 2; a++) {
        if d[a] > 0.0 {
            t = min(t, (size - o[a]) / d[a]);
        }
        else if d[a] < 0.0 {
            t = min(t, -o[a] / d[a]);
        }
    }
    return max(t, 0.0);
}

fn package__1final_image__2final_image_receivers__1wall_light(p: vec3<f32>, size: f32) -> vec3<f32> {
    let k = package_shaders__1caustics_light__2pool_wall_at(p.xy, size);
    var eye = vec4<f32>(0.0);
    if package__1final_image__2final_image_inputs__1wall_cols[k] == 0u {
        if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS) {
            return vec3<f32>(0.0);
        }
        eye = package__1final_image__2final_image_receivers__2sample_eye_space(p);
        if eye.w == 0.0 {
            return vec3<f32>(0.0);
        }
    }
    var c = eye.rgb;
    if package__1final_image__2final_image_inputs__1wall_cols[k] != 0u {
        c = package_shaders__1caustics_sampling__1wall_sample(package__1final_image__2final_image_inputs__1wall_maps, package__1final_image__2final_image_inputs__1wall_cols[k], k, package_shaders__1caustics_light__2pool_wall_along(k, p.xy), p.z, package__1final_image__2final_image_inputs_params.water_size, package__1final_image__2final_image_inputs_params.water_level);
    }
    var normals = array<vec3<f32>, 4>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(-1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, -1.0, 0.0));
    var shadow = 1.0;
    if package__1final_image__2final_image_receivers_occluded(p + normals[k] * 0.0001, -package__1final_image__2final_image_inputs_params.sun_water, package__1final_image__2final_image_inputs_FAR, false) {
        shadow = 0.0;
    }
    return package_shaders__1caustics_light__2sun_through_water(c, package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z, package__1final_image__2final_image_inputs_params.t_flat, shadow) * package__1final_image__2final_image_inputs_params.light_color;
}

fn package__1final_image__2final_image_receivers__2sample_eye_space(p: vec3<f32>) -> vec4<f32> {
    let v = p - package__1final_image__2final_image_inputs_params.camera_position;
    let z = dot(v, package__1final_image__2final_image_inputs_params.camera_forward);
    if z <= 0.0 {
        return vec4<f32>(0.0);
    }
    let sx = dot(v, package__1final_image__2final_image_inputs_params.camera_right) / dot(package__1final_image__2final_image_inputs_params.camera_right, package__1final_image__2final_image_inputs_params.camera_right) / z;
    let sy = dot(v, package__1final_image__2final_image_inputs_params.camera_up) / dot(package__1final_image__2final_image_inputs_params.camera_up, package__1final_image__2final_image_inputs_params.camera_up) / z;
    return package_shaders__1caustics_sampling__2eye_space_bilinear(package__1final_image__2final_image_inputs__1caustics_map, vec2<f32>(sx, sy));
}

fn package__1final_image__2final_image_receivers_inside(p: vec2<f32>, size: f32) -> bool {
    return p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size;
}

fn package__1final_image__2final_image_receivers_occluded(o: vec3<f32>, d: vec3<f32>, t_max: f32, with_glass: bool) -> bool {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_OBJECTS) {
        return false;
    }
    for (var k = 0u; k < package__1final_image__2final_image_inputs_params.object_count; k++) {
        let casts = with_glass || package__1final_image__2final_image_inputs_objects[k].glass == 0u;
        if casts && package_shaders_bvh__1bvh_intersect(package__1final_image__2final_image_inputs_objects[k].root, o, d, t_max, true).found {
            return true;
        }
    }
    return false;
}

fn package__1final_image__2final_image_shade__1deposited_light(p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let r = package__1final_image__2final_image_inputs__1light_space.receivers;
    let share = package_shaders_receivers__1receiver_share(package__1final_image__2final_image_inputs__1light_heights, r, p, n);
    if share <= 0.0 {
        return vec3<f32>(0.0);
    }
    let t0 = r.t0.xyz;
    let q = package_shaders_receivers__1light_space(p, t0);
    let wrap = package__1final_image__2final_image_inputs__1light_space.absorption.w != 0.0;
    let e = package_shaders__1caustics_sampling__1caustics_bilinear(package__1final_image__2final_image_inputs__1light_deposit, package__1final_image__2final_image_inputs__1light_deposit, 0u, 0u, q, package__1final_image__2final_image_inputs_params.map_size, wrap);
    let path = (package__1final_image__2final_image_inputs_params.water_level - p.z) / -t0.z;
    return e * share * exp(-package__1final_image__2final_image_inputs__1light_space.absorption.xyz * path);
}

fn package__1final_image__2final_image_shade__1shade_above(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    if package__1final_image__2final_image_inputs__1is_pool() && d.z < 0.0 {
        let deck = package__1final_image__2final_image_inputs_params.water_level + 0.1 * min(package__1final_image__2final_image_inputs_params.water_size, 1.0) + package__1final_image__2final_image_inputs__1h_max;
        let t = (deck - o.z) / d.z;
        if t > 0.0 {
            let p = o + d * t;
            let spread = 2.0 * length(package__1final_image__2final_image_inputs_params.camera_up) / f32(package__1final_image__2final_image_inputs_params.height) / f32(max(package__1final_image__2final_image_inputs_params.supersampling, 1u));
            let footprint = length(p - o) * spread / max(abs(d.z), 0.05);
            let albedo = package_shaders_shading__1deck_albedo(package__1final_image__2final_image_inputs__1deck_kind(), p.xy, package__1final_image__2final_image_inputs_params.water_size, footprint);
            return albedo * (vec3<f32>(package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z) + package__1final_image__2final_image_inputs_params.ambient) * package__1final_image__2final_image_inputs_params.light_color;
        }
    }
    if !package__1final_image__2final_image_inputs__1is_pool() && d.z < 0.0 {
        let r = package_shaders_optics__1fresnel_transmittance(-d.z, 1.0, package__1final_image__2final_image_inputs_params.ior);
        return package__1final_image__2final_image_inputs__1sky_radiance(reflect(d, vec3<f32>(0.0, 0.0, 1.0))) * (1.0 - r);
    }
    return package__1final_image__2final_image_inputs__1sky_radiance(d);
}

fn package__1final_image__2final_image_shade__1shade_floor(p: vec3<f32>, fa: vec2<f32>, fb: vec2<f32>) -> vec3<f32> {
    let size = package__1final_image__2final_image_inputs_params.water_size;
    let albedo = package__1final_image__2final_image_inputs__1albedo_at(p.xy, size, abs(fa) + abs(fb));
    let e_h = package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z;
    let flat = package_shaders__1caustics_light__2flat_water_light(package__1final_image__2final_image_inputs_params.absorption, package__1final_image__2final_image_inputs_params.water_level - p.z, -package__1final_image__2final_image_inputs_params.sun_water, vec3<f32>(0.0, 0.0, 1.0));
    var relative = flat;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_CAUSTICS) {
        relative = package__1final_image__2final_image_inputs__2sample_caustics_filtered(p.xy, fa, fb, package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_CAUSTICS), flat, true);
    }
    else if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_EYE_CAUSTICS) {
        let e = package__1final_image__2final_image_receivers__2sample_eye_space(p);
        if e.w != 0.0 {
            relative = e.rgb;
        }
    }
    var shadow = 1.0;
    if package__1final_image__2final_image_receivers_occluded(p + vec3<f32>(0.0, 0.0, 0.0001), -package__1final_image__2final_image_inputs_params.sun_water, package__1final_image__2final_image_inputs_FAR, false) {
        shadow = 0.0;
    }
    let direct = package_shaders__1caustics_light__2sun_through_water(relative, e_h, package__1final_image__2final_image_inputs_params.t_flat, shadow);
    let ambient = package__1final_image__2final_image_inputs_params.ambient * package__1final_image__2final_image_inputs_absorbed(package__1final_image__2final_image_inputs_params.water_level);
    return albedo * (direct + ambient) * package__1final_image__2final_image_inputs_params.light_color;
}

fn package__1final_image__2final_image_shade__1shade_object(p: vec3<f32>, n_out: vec3<f32>, d: vec3<f32>, k: u32, depth: u32, under: bool, w: vec3<f32>) {
    let obj = package__1final_image__2final_image_inputs_objects[k];
    let entering = dot(n_out, d) < 0.0;
    let n = select(-n_out, n_out, entering);
    if obj.glass == 0u {
        var sun_dir = package__1final_image__2final_image_inputs_params.sun;
        if under {
            sun_dir = package__1final_image__2final_image_inputs_params.sun_water;
        }
        let lambert = max(dot(n, -sun_dir), 0.0);
        var lit = 0.0;
        if lambert > 0.0 && !package__1final_image__2final_image_receivers_occluded(p + n * 0.0001, -sun_dir, package__1final_image__2final_image_inputs_FAR, false) {
            lit = 1.0;
        }
        var direct = vec3<f32>(package__1final_image__2final_image_inputs_params.sun_intensity * lambert * lit);
        if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_WATER) && under {
            let e_h = package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z;
            if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_LIGHT_SPACE) {
                direct = package_shaders__1caustics_light__2sun_through_water(package__1final_image__2final_image_shade__1deposited_light(p, n), e_h, package__1final_image__2final_image_inputs_params.t_flat, 1.0);
            }
            else {
                let flat = package_shaders__1caustics_light__2flat_water_light(package__1final_image__2final_image_inputs_params.absorption, max(package__1final_image__2final_image_inputs_params.water_level - p.z, 0.0), -package__1final_image__2final_image_inputs_params.sun_water, n);
                direct = package_shaders__1caustics_light__2sun_through_water(flat, e_h, package__1final_image__2final_image_inputs_params.t_flat, lit);
            }
        }
        package__1final_image__2final_image_inputs_emit(w, obj.color * (direct + package__1final_image__2final_image_inputs_params.ambient) * package__1final_image__2final_image_inputs_params.light_color);
        return;
    }
    var outside_ior = 1.0;
    if under {
        outside_ior = package__1final_image__2final_image_inputs_params.ior;
    }
    var n1 = outside_ior;
    var n2 = obj.ior;
    if !entering {
        n1 = obj.ior;
        n2 = outside_ior;
    }
    let cos_i = -dot(d, n);
    let t = package_shaders_optics__1fresnel_transmittance(cos_i, n1, n2);
    package__1final_image__2final_image_inputs__1push_ray(p + n * 1e-5, reflect(d, n), w * (1.0 - t), depth + 1u, under);
    let r = package_shaders_optics__1refract_dir(d, n, n1 / n2);
    if r.w != 0.0 {
        package__1final_image__2final_image_inputs__1push_ray(p - n * 1e-5, r.xyz, w * t * obj.color, depth + 1u, under);
    }
}

fn package__1final_image__2final_image_shade__1trace_air(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>) {
    var t_floor = package__1final_image__2final_image_inputs_FAR;
    if d.z < 0.0 {
        t_floor = -o.z / d.z;
    }
    let obj = package__1final_image__2final_image_receivers__1nearest_object(o, d, t_floor);
    if obj.found {
        package__1final_image__2final_image_shade__1shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
        return;
    }
    if t_floor < package__1final_image__2final_image_inputs_FAR {
        let p = o + d * t_floor;
        let fa = package__1final_image__2final_image_spread__1on_plane(package__1final_image__2final_image_spread_spread.a, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let fb = package__1final_image__2final_image_spread__1on_plane(package__1final_image__2final_image_spread_spread.b, d, t_floor, vec3<f32>(0.0, 0.0, 1.0));
        let albedo = package__1final_image__2final_image_inputs__1albedo_at(p.xy, package__1final_image__2final_image_inputs_params.scene_size, abs(fa) + abs(fb));
        let start = p + vec3<f32>(0.0, 0.0, 1e-5);
        var lit = 1.0;
        var caustic = vec3<f32>(0.0);
        if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_AIR_CAUSTICS) {
            caustic = package__1final_image__2final_image_inputs__2sample_caustics_filtered(p.xy, fa, fb, false, vec3<f32>(0.0), false);
            if package__1final_image__2final_image_receivers_occluded(start, -package__1final_image__2final_image_inputs_params.sun, package__1final_image__2final_image_inputs_FAR, true) {
                lit = 0.0;
            }
        }
        else if package__1final_image__2final_image_receivers_occluded(start, -package__1final_image__2final_image_inputs_params.sun, package__1final_image__2final_image_inputs_FAR, false) {
            lit = 0.0;
        }
        let e = (vec3<f32>(lit) + caustic) * (package__1final_image__2final_image_inputs_params.sun_intensity * -package__1final_image__2final_image_inputs_params.sun.z) + package__1final_image__2final_image_inputs_params.ambient;
        package__1final_image__2final_image_inputs_emit(w, albedo * e * package__1final_image__2final_image_inputs_params.light_color);
        return;
    }
    package__1final_image__2final_image_inputs_emit(w, package__1final_image__2final_image_inputs__1sky_radiance(d));
}

struct package__1final_image__2final_image_spread_Axis {
    o: vec3<f32>,
    d: vec3<f32>
}

struct package__1final_image__2final_image_spread_Spread {
    a: package__1final_image__2final_image_spread_Axis,
    b: package__1final_image__2final_image_spread_Axis
}

const package__1final_image__2final_image_spread__1NO_SLOT: u32 = 4294967295u;

fn package__1final_image__2final_image_spread__1bent_axis(x: package__1final_image__2final_image_spread_Axis, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> package__1final_image__2final_image_spread_Axis {
    let v = x.o + x.d * t;
    var dp = v;
    let cos_n = dot(n, d);
    if abs(cos_n) > 1e-9 {
        dp = v - d * (dot(n, v) / cos_n);
    }
    let ra = package__1final_image__2final_image_spread_bend(normalize(d - x.d * 0.5), package__1final_image__2final_image_spread__1water_normal((p - dp * 0.5).xy), reflect_it);
    let rb = package__1final_image__2final_image_spread_bend(normalize(d + x.d * 0.5), package__1final_image__2final_image_spread__1water_normal((p + dp * 0.5).xy), reflect_it);
    var out = package__1final_image__2final_image_spread_Axis(dp, vec3<f32>(0.0));
    if ra.w != 0.0 && rb.w != 0.0 {
        out.d = rb.xyz - ra.xyz;
    }
    return out;
}

fn package__1final_image__2final_image_spread__1bent_spread(s: package__1final_image__2final_image_spread_Spread, p: vec3<f32>, d: vec3<f32>, t: f32, n: vec3<f32>, reflect_it: bool) -> package__1final_image__2final_image_spread_Spread {
    return package__1final_image__2final_image_spread_Spread(package__1final_image__2final_image_spread__1bent_axis(s.a, p, d, t, n, reflect_it), package__1final_image__2final_image_spread__1bent_axis(s.b, p, d, t, n, reflect_it));
}

fn package__1final_image__2final_image_spread__1camera_ray(x: f32, y: f32) -> vec3<f32> {
    let sx = 2.0 * (x + 0.5) / f32(package__1final_image__2final_image_inputs_params.width) - 1.0;
    let sy = 1.0 - 2.0 * (y + 0.5) / f32(package__1final_image__2final_image_inputs_params.height);
    return normalize(package__1final_image__2final_image_inputs_params.camera_forward + package__1final_image__2final_image_inputs_params.camera_right * sx + package__1final_image__2final_image_inputs_params.camera_up * sy);
}

fn package__1final_image__2final_image_spread__1camera_spread(x: f32, y: f32, h: f32) -> package__1final_image__2final_image_spread_Spread {
    let zero = vec3<f32>(0.0);
    return package__1final_image__2final_image_spread_Spread(package__1final_image__2final_image_spread_Axis(zero, package__1final_image__2final_image_spread__1camera_ray(x + 0.5 * h, y) - package__1final_image__2final_image_spread__1camera_ray(x - 0.5 * h, y)), package__1final_image__2final_image_spread_Axis(zero, package__1final_image__2final_image_spread__1camera_ray(x, y + 0.5 * h) - package__1final_image__2final_image_spread__1camera_ray(x, y - 0.5 * h)));
}

fn package__1final_image__2final_image_spread__1no_spread() -> package__1final_image__2final_image_spread_Spread {
    let zero = package__1final_image__2final_image_spread_Axis(vec3<f32>(0.0), vec3<f32>(0.0));
    return package__1final_image__2final_image_spread_Spread(zero, zero);
}

fn package__1final_image__2final_image_spread__1on_plane(x: package__1final_image__2final_image_spread_Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec2<f32> {
    return package__1final_image__2final_image_spread__1on_plane3(x, d, t, m).xy;
}

fn package__1final_image__2final_image_spread__1on_plane3(x: package__1final_image__2final_image_spread_Axis, d: vec3<f32>, t: f32, m: vec3<f32>) -> vec3<f32> {
    let cos_m = dot(m, d);
    var v = x.o + x.d * t;
    if abs(cos_m) > 1e-9 {
        v = v - d * (dot(m, v) / cos_m);
    }
    return v;
}

var<private> package__1final_image__2final_image_spread__1pending_slot: u32;

var<private> package__1final_image__2final_image_spread__1pending_spread: package__1final_image__2final_image_spread_Spread;

fn package__1final_image__2final_image_spread__1water_normal(q: vec2<f32>) -> vec3<f32> {
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_SURFACE) {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return package_shaders_optics__2height_field_normal(package__1final_image__2final_image_inputs__2water_height_gradient(q).yz);
}

fn package__1final_image__2final_image_spread__2push_ray_spread(o: vec3<f32>, d: vec3<f32>, weight: vec3<f32>, depth: u32, under: bool, s: package__1final_image__2final_image_spread_Spread) {
    if package__1final_image__2final_image_inputs__1ray_count < package__1final_image__2final_image_inputs__1RAY_STACK {
        package__1final_image__2final_image_spread__1pending_slot = package__1final_image__2final_image_inputs__1ray_count;
        package__1final_image__2final_image_spread__1pending_spread = s;
    }
    package__1final_image__2final_image_inputs__1push_ray(o, d, weight, depth, under);
}

fn package__1final_image__2final_image_spread_bend(d: vec3<f32>, m: vec3<f32>, reflect_it: bool) -> vec4<f32> {
    if reflect_it {
        return vec4<f32>(reflect(d, m), 1.0);
    }
    return package_shaders_optics__1refract_dir(d, m, 1.0 / package__1final_image__2final_image_inputs_params.ior);
}

var<private> package__1final_image__2final_image_spread_spread: package__1final_image__2final_image_spread_Spread;

const package__1final_image__3final_image_rough_water_FACETS: u32 = 6u;

struct package__1final_image__3final_image_rough_water_Facets {
    normal: array<vec3<f32>, 6>,
    weight: array<f32, 6>,
    count: u32
}

struct package__1final_image__3final_image_rough_water_Moments {
    mean: vec2<f32>,
    second: vec3<f32>
}

struct package__1final_image__3final_image_rough_water_SlopeLevels {
    lod: f32,
    k: u32,
    top: bool,
    fine: vec3<u32>,
    coarse: vec3<u32>
}

const package__1final_image__3final_image_rough_water__1LEGENDRE_W = array<f32, 6>(0.171324492, 0.360761573, 0.467913935, 0.467913935, 0.360761573, 0.171324492);

const package__1final_image__3final_image_rough_water__1LEGENDRE_X = array<f32, 6>(-0.932469514, -0.661209386, -0.238619186, 0.238619186, 0.661209386, 0.932469514);

fn package__1final_image__3final_image_rough_water__1exact_moments(g: vec2<f32>) -> package__1final_image__3final_image_rough_water_Moments {
    return package__1final_image__3final_image_rough_water_Moments(g, vec3<f32>(g.x * g.x, g.y * g.y, g.x * g.y));
}

fn package__1final_image__3final_image_rough_water__1lerp_moments(a: package__1final_image__3final_image_rough_water_Moments, b: package__1final_image__3final_image_rough_water_Moments, t: f32) -> package__1final_image__3final_image_rough_water_Moments {
    return package__1final_image__3final_image_rough_water_Moments(a.mean + (b.mean - a.mean) * t, a.second + (b.second - a.second) * t);
}

fn package__1final_image__3final_image_rough_water__1mean_facet(m: package__1final_image__3final_image_rough_water_Moments) -> package__1final_image__3final_image_rough_water_Facets {
    var f: package__1final_image__3final_image_rough_water_Facets;
    f.normal[0] = package_shaders_optics__2height_field_normal(m.mean);
    f.weight[0] = 1.0;
    f.count = 1u;
    return f;
}

fn package__1final_image__3final_image_rough_water__1rough_water(p: vec3<f32>, d: vec3<f32>, n: ptr<function, vec3<f32>>) -> vec4<f32> {
    let m = package__1final_image__3final_image_rough_water__1water_slopes(p, d);
    let f = package__1final_image__3final_image_rough_water__1visible_facets(d, m);
    var reflected = package__1final_image__3final_image_rough_water_glint(d, m);
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

fn package__1final_image__3final_image_rough_water__1slope_bilinear(l: vec3<u32>, p: vec2<f32>) -> package__1final_image__3final_image_rough_water_Moments {
    let u = p.x / (package__1final_image__2final_image_inputs_params.water_size / f32(l.y)) - 0.5;
    let v = p.y / (package__1final_image__2final_image_inputs_params.water_size / f32(l.z)) - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    var m = package__1final_image__3final_image_rough_water_Moments(vec2<f32>(0.0), vec3<f32>(0.0));
    for (var di = 0; di < 2; di++) {
        let wy = select(1.0 - fv, fv, di == 1);
        for (var dj = 0; dj < 2; dj++) {
            let wx = select(1.0 - fu, fu, dj == 1);
            let t = package__1final_image__3final_image_rough_water__1slope_fetch(l, i32(i0) + di, i32(j0) + dj);
            m.mean += t.mean * (wx * wy);
            m.second += t.second * (wx * wy);
        }
    }
    return m;
}

fn package__1final_image__3final_image_rough_water__1slope_covariance(m: package__1final_image__3final_image_rough_water_Moments) -> vec3<f32> {
    let sxx = max(m.second.x - m.mean.x * m.mean.x, 0.0);
    let syy = max(m.second.y - m.mean.y * m.mean.y, 0.0);
    let limit = sqrt(sxx * syy);
    return vec3<f32>(sxx, syy, clamp(m.second.z - m.mean.x * m.mean.y, -limit, limit));
}

fn package__1final_image__3final_image_rough_water__1slope_fetch(l: vec3<u32>, i: i32, j: i32) -> package__1final_image__3final_image_rough_water_Moments {
    let r = i32(l.z);
    let c = i32(l.y);
    var ii = clamp(i, 0, r - 1);
    var jj = clamp(j, 0, c - 1);
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE) {
        ii = ((i % r) + r) % r;
        jj = ((j % c) + c) % c;
    }
    let k = (l.x + u32(ii * c + jj)) * 5u;
    return package__1final_image__3final_image_rough_water_Moments(vec2<f32>(package__1final_image__2final_image_inputs__1slope_moments[k], package__1final_image__2final_image_inputs__1slope_moments[k + 1u]), vec3<f32>(package__1final_image__2final_image_inputs__1slope_moments[k + 2u], package__1final_image__2final_image_inputs__1slope_moments[k + 3u], package__1final_image__2final_image_inputs__1slope_moments[k + 4u]));
}

fn package__1final_image__3final_image_rough_water__1slope_level(k: u32) -> vec3<u32> {
    var l = vec3<u32>(0u, max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u));
    for (var i = 0u; i < k; i++) {
        l = vec3<u32>(l.x + l.y * l.z, (l.y + 1u) / 2u, (l.z + 1u) / 2u);
    }
    return l;
}

fn package__1final_image__3final_image_rough_water__1slope_levels(lod: f32) -> package__1final_image__3final_image_rough_water_SlopeLevels {
    let top = package__1final_image__3final_image_rough_water__2slope_level_count() - 1u;
    let k = min(u32(floor(lod)), top);
    return package__1final_image__3final_image_rough_water_SlopeLevels(lod, k, lod >= f32(top), package__1final_image__3final_image_rough_water__1slope_level(k), package__1final_image__3final_image_rough_water__1slope_level(min(k + 1u, top)));
}

fn package__1final_image__3final_image_rough_water__1slope_texel() -> f32 {
    return package__1final_image__2final_image_inputs_params.water_size / f32(min(max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u)));
}

fn package__1final_image__3final_image_rough_water__1smith_masking(cos_theta: f32, sigma2: f32) -> f32 {
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

fn package__1final_image__3final_image_rough_water__1variance_along(c: vec3<f32>, d: vec3<f32>) -> f32 {
    var a = vec2<f32>(1.0, 0.0);
    if length(d.xy) > 0.0 {
        a = normalize(d.xy);
    }
    return c.x * a.x * a.x + 2.0 * c.z * a.x * a.y + c.y * a.y * a.y;
}

fn package__1final_image__3final_image_rough_water__1visible_facets(d: vec3<f32>, m: package__1final_image__3final_image_rough_water_Moments) -> package__1final_image__3final_image_rough_water_Facets {
    let c = package__1final_image__3final_image_rough_water__1slope_covariance(m);
    let run = length(d.xy);
    if run <= 0.0 {
        return package__1final_image__3final_image_rough_water__1mean_facet(m);
    }
    let a = d.xy / run;
    let along = vec2<f32>(c.x * a.x + c.z * a.y, c.z * a.x + c.y * a.y);
    let sigma = sqrt(max(dot(a, along), 0.0));
    if sigma <= 0.0 {
        return package__1final_image__3final_image_rough_water__1mean_facet(m);
    }
    let u0 = -(abs(d.z) + run * dot(m.mean, a)) / (run * sigma);
    let lo = max(u0, -4.0);
    let hi = max(lo, 0.0) + 4.0;
    let step = along / sigma;
    var f: package__1final_image__3final_image_rough_water_Facets;
    var total = 0.0;
    for (var k = 0u; k < package__1final_image__3final_image_rough_water_FACETS; k++) {
        let u = lo + (hi - lo) * 0.5 * (package__1final_image__3final_image_rough_water__1LEGENDRE_X[k] + 1.0);
        let seen = package__1final_image__3final_image_rough_water__1LEGENDRE_W[k] * max(u - u0, 0.0) * exp(-0.5 * u * u);
        f.normal[k] = package_shaders_optics__2height_field_normal(m.mean + step * u);
        f.weight[k] = seen;
        total += seen;
    }
    if !(total > 0.0 && total <= 3e38) {
        return package__1final_image__3final_image_rough_water__1mean_facet(m);
    }
    for (var k = 0u; k < package__1final_image__3final_image_rough_water_FACETS; k++) {
        f.weight[k] = f.weight[k] / total;
    }
    f.count = package__1final_image__3final_image_rough_water_FACETS;
    return f;
}

fn package__1final_image__3final_image_rough_water__1water_gradient(p: vec2<f32>) -> vec2<f32> {
    return package__1final_image__2final_image_inputs__2water_height_gradient(p).yz;
}

fn package__1final_image__3final_image_rough_water__1water_slopes(p: vec3<f32>, d: vec3<f32>) -> package__1final_image__3final_image_rough_water_Moments {
    let width = length(p - package__1final_image__2final_image_inputs_params.camera_position) * package__1final_image__2final_image_inputs_params.slope_spread;
    let len = width / max(abs(d.z), 0.001);
    var along = vec2<f32>(1.0, 0.0);
    if length(d.xy) > 0.0 {
        along = normalize(d.xy);
    }
    let taps = clamp(ceil(len / max(width, 1e-12)), 1.0, f32(package__1final_image__3final_image_rough_water__2MAX_SLOPE_TAPS));
    let side = max(width, len / taps);
    let lod = log2(side / package__1final_image__3final_image_rough_water__1slope_texel());
    if lod <= 0.0 {
        return package__1final_image__3final_image_rough_water__1exact_moments(package__1final_image__3final_image_rough_water__1water_gradient(p.xy));
    }
    var m = package__1final_image__3final_image_rough_water_Moments(vec2<f32>(0.0), vec3<f32>(0.0));
    let levels = package__1final_image__3final_image_rough_water__1slope_levels(lod);
    let n = u32(taps);
    for (var k = 0u; k < n; k++) {
        let offset = ((f32(k) + 0.5) / taps - 0.5) * len;
        let t = package__1final_image__3final_image_rough_water__2slope_at_lod(p.xy + along * offset, levels);
        m.mean += t.mean / taps;
        m.second += t.second / taps;
    }
    return m;
}

const package__1final_image__3final_image_rough_water__2MAX_SLOPE_TAPS: u32 = 16u;

fn package__1final_image__3final_image_rough_water__2slope_at_lod(p: vec2<f32>, l: package__1final_image__3final_image_rough_water_SlopeLevels) -> package__1final_image__3final_image_rough_water_Moments {
    if l.top {
        return package__1final_image__3final_image_rough_water__1slope_bilinear(l.fine, p);
    }
    var below: package__1final_image__3final_image_rough_water_Moments;
    if l.k == 0u {
        below = package__1final_image__3final_image_rough_water__1exact_moments(package__1final_image__3final_image_rough_water__1water_gradient(p));
    }
    else {
        below = package__1final_image__3final_image_rough_water__1slope_bilinear(l.fine, p);
    }
    return package__1final_image__3final_image_rough_water__1lerp_moments(below, package__1final_image__3final_image_rough_water__1slope_bilinear(l.coarse, p), l.lod - f32(l.k));
}

fn package__1final_image__3final_image_rough_water__2slope_level_count() -> u32 {
    var l = vec2<u32>(max(package__1final_image__2final_image_inputs_params.slope_cols, 1u), max(package__1final_image__2final_image_inputs_params.slope_rows, 1u));
    var n = 1u;
    while l.x > 1u || l.y > 1u {
        l = (l + 1u) / 2u;
        n++;
    }
    return n;
}

fn package__1final_image__3final_image_rough_water_glint(d: vec3<f32>, m: package__1final_image__3final_image_rough_water_Moments) -> vec3<f32> {
    let to_eye = -d;
    let to_sun = -package__1final_image__2final_image_inputs_params.sun;
    let hv = to_eye + to_sun;
    if to_eye.z <= 0.0 || hv.z <= 0.0 {
        return vec3<f32>(0.0);
    }
    let h = normalize(hv);
    var c = package__1final_image__3final_image_rough_water__1slope_covariance(m);
    c = vec3<f32>(c.x + package__1final_image__2final_image_inputs_params.sun_variance, c.y + package__1final_image__2final_image_inputs_params.sun_variance, c.z);
    let det = c.x * c.y - c.z * c.z;
    let e = vec2<f32>(-h.x / h.z, -h.y / h.z) - m.mean;
    let q = (c.y * e.x * e.x - 2.0 * c.z * e.x * e.y + c.x * e.y * e.y) / det;
    let density = exp(-0.5 * q) / (2.0 * 3.14159265 * sqrt(det));
    let masking = package__1final_image__3final_image_rough_water__1smith_masking(to_eye.z, package__1final_image__3final_image_rough_water__1variance_along(c, to_eye)) * package__1final_image__3final_image_rough_water__1smith_masking(to_sun.z, package__1final_image__3final_image_rough_water__1variance_along(c, to_sun));
    let cos2 = h.z * h.z;
    let g = density * masking / (4.0 * to_eye.z * cos2 * cos2);
    if g <= 0.0 {
        return vec3<f32>(0.0);
    }
    let f = 1.0 - package_shaders_optics__1fresnel_transmittance(dot(to_eye, h), 1.0, package__1final_image__2final_image_inputs_params.ior);
    return package__1final_image__2final_image_inputs__1sun_radiance() * (3.14159265 * f * g);
}

fn package_shaders__1caustics_light__2flat_water_light(absorption: vec3<f32>, depth: f32, toward_sun: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let cos_t = max(toward_sun.z, 0.001);
    return exp(-absorption * (depth / cos_t)) * (max(dot(n, toward_sun), 0.0) / cos_t);
}

fn package_shaders__1caustics_light__2pool_wall_along(k: u32, p: vec2<f32>) -> f32 {
    return select(p.x, p.y, k < 2u);
}

fn package_shaders__1caustics_light__2pool_wall_at(p: vec2<f32>, size: f32) -> u32 {
    let d = array<f32, 4>(p.x, size - p.x, p.y, size - p.y);
    var k = 0u;
    for (var i = 1u; i < 4u; i++) {
        if d[i] < d[k] {
            k = i;
        }
    }
    return k;
}

fn package_shaders__1caustics_light__2sun_through_water(relative: vec3<f32>, horizontal: f32, transmittance: f32, shadow: f32) -> vec3<f32> {
    return relative * (horizontal * transmittance * shadow);
}

fn package_shaders__1caustics_sampling__1caustics_bilinear(map: texture_2d<f32>, mips: texture_2d<f32>, mips_from: u32, level: u32, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = package_shaders__1caustics_sampling__1caustics_dims(map, level);
    let u = p.x / size * f32(dims.x) - 0.5;
    let v = p.y / size * f32(dims.y) - 0.5;
    let j0 = floor(u);
    let i0 = floor(v);
    let fu = u - j0;
    let fv = v - i0;
    var c0 = vec2<i32>(i32(j0), i32(i0));
    var c1 = c0 + 1;
    if wrap {
        c0 = ((c0 % dims) + dims) % dims;
        c1 = select(c0 + 1, vec2<i32>(0), c0 + 1 == dims);
    }
    else {
        c0 = clamp(c0, vec2<i32>(0), dims - 1);
        c1 = clamp(c1, vec2<i32>(0), dims - 1);
    }
    var a: vec3<f32>;
    var b: vec3<f32>;
    var c: vec3<f32>;
    var d: vec3<f32>;
    if level == 0u {
        a = textureLoad(map, c0, 0).rgb;
        b = textureLoad(map, vec2<i32>(c1.x, c0.y), 0).rgb;
        c = textureLoad(map, vec2<i32>(c0.x, c1.y), 0).rgb;
        d = textureLoad(map, c1, 0).rgb;
    }
    else {
        let m = level - mips_from;
        a = textureLoad(mips, c0, m).rgb;
        b = textureLoad(mips, vec2<i32>(c1.x, c0.y), m).rgb;
        c = textureLoad(mips, vec2<i32>(c0.x, c1.y), m).rgb;
        d = textureLoad(mips, c1, m).rgb;
    }
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

fn package_shaders__1caustics_sampling__1wall_sample(walls: texture_2d_array<f32>, cols: u32, k: u32, along: f32, z: f32, size: f32, depth: f32) -> vec3<f32> {
    let rows = textureDimensions(walls).y;
    let u = clamp(along / size * f32(cols) - 0.5, 0.0, f32(cols - 1u));
    let v = clamp(z / depth * f32(rows) - 0.5, 0.0, f32(rows - 1u));
    let j0 = u32(floor(u));
    let i0 = u32(floor(v));
    let j1 = min(j0 + 1u, cols - 1u);
    let i1 = min(i0 + 1u, rows - 1u);
    let fu = u - f32(j0);
    let fv = v - f32(i0);
    let layer = i32(k);
    let a = textureLoad(walls, vec2<u32>(j0, i0), layer, 0).rgb;
    let b = textureLoad(walls, vec2<u32>(j1, i0), layer, 0).rgb;
    let c = textureLoad(walls, vec2<u32>(j0, i1), layer, 0).rgb;
    let d = textureLoad(walls, vec2<u32>(j1, i1), layer, 0).rgb;
    return (a * (1.0 - fu) + b * fu) * (1.0 - fv) + (c * (1.0 - fu) + d * fu) * fv;
}

const package_shaders__1caustics_sampling__2CAUSTICS_MAX_TAPS: f32 = 8.0;

fn package_shaders__1caustics_sampling__2eye_space_bilinear(eye: texture_2d<f32>, s: vec2<f32>) -> vec4<f32> {
    let dims = vec2<i32>(textureDimensions(eye));
    let u = (s.x + 1.0) * 0.5 * f32(dims.x) - 0.5;
    let w = (1.0 - s.y) * 0.5 * f32(dims.y) - 0.5;
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
            let t = textureLoad(eye, c, 0);
            if t.w < 0.0 {
                continue;
            }
            let wx = select(1.0 - f.x, f.x, dx == 1);
            let wy = select(1.0 - f.y, f.y, dy == 1);
            sum += t.rgb * (wx * wy);
            weight += wx * wy;
        }
    }
    if weight < 0.001 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(sum / weight, 1.0);
}

struct package_shaders_bvh_BvhNode {
    min: vec3<f32>,
    start: u32,
    max: vec3<f32>,
    count: u32
}

struct package_shaders_bvh_BvhTriangle {
    p0: vec4<f32>,
    e1: vec4<f32>,
    e2: vec4<f32>,
    n0: vec4<f32>,
    n1: vec4<f32>,
    n2: vec4<f32>
}

struct package_shaders_bvh_MeshHit {
    t: f32,
    normal: vec3<f32>,
    found: bool
}

const package_shaders_bvh__1BVH_STACK: u32 = 61u;

const package_shaders_bvh__1BVH_WIDEN: f32 = 1.0 + 4.0 * 1.1920929e-7;

fn package_shaders_bvh__1bvh_enter(node: u32, o: vec3<f32>, inv_dir: vec3<f32>, t_max: f32) -> f32 {
    let n = package_shaders_bvh__1bvh_nodes[node];
    let t1 = (n.min - o) * inv_dir;
    let t2 = (n.max - o) * inv_dir;
    let lo = min(t1, t2);
    let hi = max(t1, t2);
    let near = max(max(max(lo.x, lo.y), lo.z), 0.0);
    let far = min(min(min(hi.x, hi.y), hi.z) * package_shaders_bvh__1BVH_WIDEN, t_max);
    if near <= far {
        return near;
    }
    return -1.0;
}

fn package_shaders_bvh__1bvh_intersect(root: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32, any_hit: bool) -> package_shaders_bvh_MeshHit {
    var result: package_shaders_bvh_MeshHit;
    result.found = false;
    result.t = t_max;
    let inv_dir = package_shaders_bvh__2bvh_inverse_direction(d);
    if package_shaders_bvh__1bvh_enter(root, o, inv_dir, t_max) < 0.0 {
        return result;
    }
    var stack_node: array<u32, package_shaders_bvh__1BVH_STACK>;
    var stack_t: array<f32, package_shaders_bvh__1BVH_STACK>;
    var top = 0u;
    var t_best = t_max;
    var best_slot = 0u;
    var best_uv = vec2<f32>(0.0);
    var node = root;
    loop {
        let n = package_shaders_bvh__1bvh_nodes[node];
        if n.count > 0u {
            for (var k = n.start; k < n.start + n.count; k++) {
                let tri = package_shaders_bvh__1bvh_triangles[k];
                let h = package_shaders_bvh__1intersect_triangle(o, d, tri.p0.xyz, tri.e1.xyz, tri.e2.xyz, t_best);
                if h.w != 0.0 {
                    t_best = h.x;
                    best_slot = k;
                    best_uv = h.yz;
                    result.found = true;
                    if any_hit {
                        result.t = t_best;
                        return result;
                    }
                }
            }
        }
        else {
            let left = n.start;
            let right = n.start + 1u;
            let l = package_shaders_bvh__1bvh_enter(left, o, inv_dir, t_best);
            let r = package_shaders_bvh__1bvh_enter(right, o, inv_dir, t_best);
            if l >= 0.0 && r >= 0.0 {
                var near = left;
                var far = right;
                var t_far = r;
                if l > r {
                    near = right;
                    far = left;
                    t_far = l;
                }
                if top < package_shaders_bvh__1BVH_STACK {
                    stack_node[top] = far;
                    stack_t[top] = t_far;
                    top++;
                }
                node = near;
                continue;
            }
            else if l >= 0.0 {
                node = left;
                continue;
            }
            else if r >= 0.0 {
                node = right;
                continue;
            }
        }
        var resumed = false;
        loop {
            if top == 0u {
                break;
            }
            top--;
            if stack_t[top] < t_best {
                node = stack_node[top];
                resumed = true;
                break;
            }
        }
        if !resumed {
            break;
        }
    }
    if result.found {
        result.t = t_best;
        result.normal = package_shaders_bvh__1bvh_normal(best_slot, best_uv.x, best_uv.y);
    }
    return result;
}

@group(1) @binding(0)
var<storage, read> package_shaders_bvh__1bvh_nodes: array<package_shaders_bvh_BvhNode>;

fn package_shaders_bvh__1bvh_normal(slot: u32, u: f32, v: f32) -> vec3<f32> {
    let tri = package_shaders_bvh__1bvh_triangles[slot];
    let n = (1.0 - u - v) * tri.n0.xyz + u * tri.n1.xyz + v * tri.n2.xyz;
    if dot(n, n) > 0.0 {
        return normalize(n);
    }
    let f = cross(tri.e1.xyz, tri.e2.xyz);
    if dot(f, f) > 0.0 {
        return normalize(f);
    }
    return vec3<f32>(0.0);
}

@group(1) @binding(1)
var<storage, read> package_shaders_bvh__1bvh_triangles: array<package_shaders_bvh_BvhTriangle>;

fn package_shaders_bvh__1intersect_triangle(o: vec3<f32>, d: vec3<f32>, p0: vec3<f32>, e1: vec3<f32>, e2: vec3<f32>, t_max: f32) -> vec4<f32> {
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det == 0.0 {
        return vec4<f32>(0.0);
    }
    let inv_det = 1.0 / det;
    let s = o - p0;
    let u = dot(s, p) * inv_det;
    if u < 0.0 || u > 1.0 {
        return vec4<f32>(0.0);
    }
    let q = cross(s, e1);
    let v = dot(d, q) * inv_det;
    if v < 0.0 || u + v > 1.0 {
        return vec4<f32>(0.0);
    }
    let t = dot(e2, q) * inv_det;
    if t > 0.0 && t < t_max {
        return vec4<f32>(t, u, v, 1.0);
    }
    return vec4<f32>(0.0);
}

fn package_shaders_bvh__2bvh_inverse_direction(d: vec3<f32>) -> vec3<f32> {
    let tiny = 1e-20;
    let safe = select(d, select(vec3<f32>(tiny), vec3<f32>(-tiny), d < vec3<f32>(0.0)), abs(d) < vec3<f32>(tiny));
    return 1.0 / safe;
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

fn package_shaders_receivers__1receiver_share(map: texture_2d<f32>, r: package_shaders_receivers_Receivers, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let t0 = r.t0.xyz;
    let bias = 0.5 * r.view.z * max(r.view.w, 1.0);
    if p.z < package_shaders_receivers__1receiver_height(map, r, package_shaders_receivers__1light_space(p, t0)) - bias {
        return 0.0;
    }
    return max(dot(n, -t0), 0.0) / -t0.z;
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

const package_shaders_shading_COPING: f32 = 0.3;

const package_shaders_shading_JOINT: f32 = 0.01;

const package_shaders_shading_PAVER: f32 = 0.6;

const package_shaders_shading__1ALBEDO_PLAIN: u32 = 2u;

const package_shaders_shading__1ALBEDO_SAND: u32 = 1u;

const package_shaders_shading__1ALBEDO_TILES: u32 = 0u;

const package_shaders_shading__1DECK_CONCRETE: u32 = 1u;

const package_shaders_shading__1GROUT_COLOUR: vec3<f32> = vec3<f32>(0.18, 0.2, 0.22);

const package_shaders_shading__1NOISE_POINT: f32 = 0.001;

const package_shaders_shading__1SAND_GRAIN: f32 = 0.05;

const package_shaders_shading__1SAND_PATCH: f32 = 0.5;

const package_shaders_shading__1TILE_COLOUR: vec3<f32> = vec3<f32>(0.62, 0.78, 0.82);

const package_shaders_shading__1TONE_ACES: u32 = 0u;

const package_shaders_shading__1TONE_AGX: u32 = 1u;

fn package_shaders_shading__1deck_albedo(kind: u32, p: vec2<f32>, size: f32, footprint: f32) -> vec3<f32> {
    let out = max(max(-p.x, p.x - size), max(-p.y, p.y - size));
    let coping = min(package_shaders_shading_COPING, 0.1 * size);
    if out <= coping {
        if out < min(package_shaders_shading_JOINT, 0.1 * coping) {
            return vec3<f32>(0.3, 0.29, 0.27);
        }
        return vec3<f32>(0.78, 0.76, 0.71);
    }
    if kind == package_shaders_shading__1DECK_CONCRETE {
        return vec3<f32>(0.55, 0.55, 0.53);
    }
    let row = floor(p.y / package_shaders_shading_PAVER);
    let x = p.x / package_shaders_shading_PAVER + 0.5 * (row - 2.0 * floor(row / 2.0));
    let col = floor(x);
    let w = footprint / package_shaders_shading_PAVER;
    let joint = package_shaders_shading_JOINT / package_shaders_shading_PAVER;
    let grout = 1.0 - (1.0 - package_shaders_shading__1joint_cover(x, w, joint)) * (1.0 - package_shaders_shading__1joint_cover(p.y / package_shaders_shading_PAVER, w, joint));
    let shade = 0.85 + 0.3 * package_shaders_shading_hash01(i32(col), i32(row));
    return vec3<f32>(0.6, 0.53, 0.43) * (shade * (1.0 - grout)) + vec3<f32>(0.32, 0.31, 0.29) * grout;
}

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

fn package_shaders_shading__1tone_curve(c: vec3<f32>, curve: u32) -> vec3<f32> {
    var y = c;
    if curve == package_shaders_shading__1TONE_ACES {
        let v = package_shaders_shading_rows3(vec3<f32>(0.59719, 0.35458, 0.04823), vec3<f32>(0.076, 0.90834, 0.01566), vec3<f32>(0.0284, 0.13383, 0.83777), c);
        let a = v * (v + 0.0245786) - 9.0537e-5;
        let b = v * (0.983729 * v + 0.432951) + 0.238081;
        y = package_shaders_shading_rows3(vec3<f32>(1.60475, -0.53108, -0.07367), vec3<f32>(-0.10208, 1.10813, -0.00605), vec3<f32>(-0.00327, -0.07276, 1.07602), a / b);
    }
    else if curve == package_shaders_shading__1TONE_AGX {
        let min_ev = -12.47393;
        let max_ev = 4.026069;
        let v = max(package_shaders_shading_rows3(vec3<f32>(0.842479062253094, 0.0784335999999992, 0.0792237451477643), vec3<f32>(0.0423282422610123, 0.878468636469772, 0.0791661274605434), vec3<f32>(0.0423756549057051, 0.0784336, 0.879142973793104), c), vec3<f32>(1e-10));
        let x = (clamp(log2(v), vec3<f32>(min_ev), vec3<f32>(max_ev)) - min_ev) / (max_ev - min_ev);
        let x2 = x * x;
        let x4 = x2 * x2;
        let s = 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
        let d = max(package_shaders_shading_rows3(vec3<f32>(1.19687900512017, -0.0980208811401368, -0.0990297440797205), vec3<f32>(-0.0528968517574562, 1.15190312990417, -0.0989611768448433), vec3<f32>(-0.0529716355144438, -0.0980434501171241, 1.15107367264116), s), vec3<f32>(0.0));
        y = pow(d, vec3<f32>(2.2));
    }
    return clamp(y, vec3<f32>(0.0), vec3<f32>(1.0));
}

fn package_shaders_shading__1tone_map(c: vec3<f32>, curve: u32) -> vec3<f32> {
    let y = package_shaders_shading__1tone_curve(c, curve);
    var s: vec3<f32>;
    for (var k = 0; k < 3; k++) {
        if y[k] <= 0.0031308 {
            s[k] = 12.92 * y[k];
        }
        else {
            s[k] = 1.055 * pow(y[k], 1.0 / 2.4) - 0.055;
        }
    }
    return floor(s * 255.0 + 0.5) / 255.0;
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

fn package_shaders_shading_rows3(r0: vec3<f32>, r1: vec3<f32>, r2: vec3<f32>, c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(r0, c), dot(r1, c), dot(r2, c));
}

fn package_shaders_shading_sinc(x: f32) -> f32 {
    if abs(x) < 1e-6 {
        return 1.0;
    }
    return sin(x) / x;
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

fn radiance(o: vec3<f32>, d: vec3<f32>, under: bool, s: package__1final_image__2final_image_spread_Spread) -> vec3<f32> {
    package__1final_image__2final_image_inputs__1pixel_radiance = vec3<f32>(0.0);
    package__1final_image__2final_image_inputs__1ray_count = 0u;
    package__1final_image__2final_image_spread__1pending_slot = package__1final_image__2final_image_spread__1NO_SLOT;
    package__1final_image__2final_image_spread__2push_ray_spread(o, d, vec3<f32>(1.0), 0u, under, s);
    while package__1final_image__2final_image_inputs__1ray_count > 0u {
        package__1final_image__2final_image_inputs__1ray_count--;
        let r = package__1final_image__2final_image_inputs_rays[package__1final_image__2final_image_inputs__1ray_count];
        package__1final_image__2final_image_spread_spread = package__1final_image__2final_image_spread__1no_spread();
        if package__1final_image__2final_image_inputs__1ray_count == package__1final_image__2final_image_spread__1pending_slot {
            package__1final_image__2final_image_spread_spread = package__1final_image__2final_image_spread__1pending_spread;
            package__1final_image__2final_image_spread__1pending_slot = package__1final_image__2final_image_spread__1NO_SLOT;
        }
        if r.depth > package__1final_image__2final_image_inputs__1MAX_DEPTH {
            continue;
        }
        var crossing = vec4<f32>(r.o, -1.0);
        if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_WATER) {
            crossing = package__1final_image__2final_image_march__1hit_surface(r.o, r.d, r.under);
        }
        var below = r;
        if !r.under {
            below = trace(r.o, r.d, r.depth, r.weight, crossing);
            crossing = vec4<f32>(below.o, -1.0);
        }
        if below.under {
            trace_under(below.o, below.d, below.depth, below.weight, crossing);
        }
    }
    return package__1final_image__2final_image_inputs__1pixel_radiance;
}

fn sample_offset(sx: u32, sy: u32, n: u32) -> vec2<f32> {
    let m = f32(n);
    return vec2<f32>((f32(sx) + (f32(sy) + 0.5) / m) / m, (f32(sy) + (m - 1.0 - f32(sx) + 0.5) / m) / m);
}

fn trace(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, water: vec4<f32>) -> package__1final_image__2final_image_inputs_Ray {
    let none = package__1final_image__2final_image_inputs_Ray(o, d, vec3<f32>(0.0), depth, false);
    if !package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_WATER) {
        package__1final_image__2final_image_shade__1trace_air(o, d, depth, w);
        return none;
    }
    let size = package__1final_image__2final_image_inputs_params.water_size;
    let hit = water.w >= 0.0;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_OBJECTS) {
        let obj = package__1final_image__2final_image_receivers__1nearest_object(o, d, select(package__1final_image__2final_image_inputs_FAR, water.w, hit));
        if obj.found {
            package__1final_image__2final_image_shade__1shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, false, w);
            return none;
        }
    }
    if !hit {
        package__1final_image__2final_image_inputs_emit(w, package__1final_image__2final_image_shade__1shade_above(o, d));
        return none;
    }
    let p = water.xyz;
    if package__1final_image__2final_image_inputs__1is_pool() && !package__1final_image__2final_image_receivers_inside(p.xy, size) {
        package__1final_image__2final_image_inputs_emit(w, package__1final_image__2final_image_shade__1shade_above(o, d));
        return none;
    }
    var n = package_shaders_optics__2height_field_normal(package__1final_image__2final_image_march__1crossing_gradient(p, water.w));
    var t_view: f32;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__2FLAG_FILTER_WATER) {
        let rough = package__1final_image__3final_image_rough_water__1rough_water(p, d, &n);
        t_view = rough.w;
        package__1final_image__2final_image_inputs_emit(w, rough.xyz);
    }
    else {
        t_view = package_shaders_optics__1fresnel_transmittance(-dot(d, n), 1.0, package__1final_image__2final_image_inputs_params.ior);
        package__1final_image__2final_image_inputs_emit(w, package__1final_image__2final_image_inputs__1sky_radiance(reflect(d, n)) * (1.0 - t_view));
    }
    let r = package_shaders_optics__1refract_dir(d, n, 1.0 / package__1final_image__2final_image_inputs_params.ior);
    if r.w == 0.0 {
        return none;
    }
    package__1final_image__2final_image_spread_spread = package__1final_image__2final_image_spread__1bent_spread(package__1final_image__2final_image_spread_spread, p, d, water.w, n, false);
    if r.z > 0.0 {
        package__1final_image__2final_image_spread__2push_ray_spread(p, r.xyz, w * t_view, depth, true, package__1final_image__2final_image_spread_spread);
        return none;
    }
    return package__1final_image__2final_image_inputs_Ray(p, r.xyz, w * t_view, depth, true);
}

fn trace_under(o: vec3<f32>, d: vec3<f32>, depth: u32, w: vec3<f32>, ceiling: vec4<f32>) {
    let size = package__1final_image__2final_image_inputs_params.water_size;
    var floor_hit = package__1final_image__2final_image_march__1hit_floor(o, d);
    if ceiling.w >= 0.0 {
        floor_hit = ceiling;
    }
    let t_floor = floor_hit.w;
    if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_OBJECTS) {
        let obj = package__1final_image__2final_image_receivers__1nearest_object(o, d, t_floor);
        if obj.found {
            package__1final_image__2final_image_shade__1shade_object(o + d * obj.t, obj.normal, d, obj.k, depth, true, w * package__1final_image__2final_image_inputs_absorbed(obj.t));
            return;
        }
    }
    if package__1final_image__2final_image_inputs__1is_pool() && !package__1final_image__2final_image_receivers_inside(floor_hit.xy, size) {
        let t = package__1final_image__2final_image_receivers__1wall_distance(o, d, size);
        let p = o + d * t;
        let m = select(vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(1.0, 0.0, 0.0), package_shaders__1caustics_light__2pool_wall_at(p.xy, size) < 2u);
        let fa = package__1final_image__2final_image_spread__1on_plane3(package__1final_image__2final_image_spread_spread.a, d, t, m);
        let fb = package__1final_image__2final_image_spread__1on_plane3(package__1final_image__2final_image_spread_spread.b, d, t, m);
        let extent = vec2<f32>(abs(fa.x + fa.y) + abs(fb.x + fb.y), abs(fa.z) + abs(fb.z));
        let a = package__1final_image__2final_image_inputs__1albedo_at(vec2<f32>(p.x + p.y, p.z), size, extent);
        package__1final_image__2final_image_inputs_emit(w * package__1final_image__2final_image_inputs_absorbed(t), a * (package__1final_image__2final_image_inputs_params.ambient * package__1final_image__2final_image_inputs_params.light_color + package__1final_image__2final_image_receivers__1wall_light(p, size)));
    }
    else if ceiling.w >= 0.0 {
        package__1final_image__2final_image_march__1leave_water(floor_hit.xyz, d, depth, w * package__1final_image__2final_image_inputs_absorbed(t_floor), t_floor);
    }
    else {
        var m = vec3<f32>(0.0, 0.0, 1.0);
        if package__1final_image__2final_image_inputs_has(package__1final_image__2final_image_inputs__1FLAG_TERRAIN) {
            m = package_shaders_optics__2height_field_normal(package__1final_image__2final_image_inputs__2terrain_height_gradient(floor_hit.xy).yz);
        }
        let fa = package__1final_image__2final_image_spread__1on_plane(package__1final_image__2final_image_spread_spread.a, d, t_floor, m);
        let fb = package__1final_image__2final_image_spread__1on_plane(package__1final_image__2final_image_spread_spread.b, d, t_floor, m);
        package__1final_image__2final_image_inputs_emit(w * package__1final_image__2final_image_inputs_absorbed(t_floor), package__1final_image__2final_image_shade__1shade_floor(floor_hit.xyz, fa, fb));
    }
}
