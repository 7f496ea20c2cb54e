// The final image, one invocation per pixel: the GPU twin of caustics-core/src/render.rs, function
// for function (`render`, `Tracer::trace`, `trace_under`, `shade_floor`, `shade_object`,
// `trace_air`, `shade_above`, `hit_floor`, `inside`, `wall_distance`, `wall_light`, `wall_at`,
// `leave_water`, `camera_under_water`; `hit_water` and `hit_water_from_below` are one
// `hit_surface`). The light
// transport is documented there. This module holds the pass's uniform, bindings and reads of its
// inputs; final_image.wgsl, the pass's main module, imports it and the other parts.
//
// WGSL has no recursion, and the CPU's recursion is linear in what it returns: `trace` returns the
// reflected sky plus `t_view` times what `trace_under` returns, a glass object returns
// `(1 - T)` times one trace plus `T tint` times another, and `trace_under` multiplies all it gets by
// `exp(-K d)`. So each function here takes the weight `w` its CPU twin's result would be multiplied
// by, adds `w * colour` for what it would return directly (`emit`), and pushes the rays it would
// recurse into with their weights on a small stack (`push_ray`) that `radiance` drains. The sum is
// the CPU's up to the order of the additions.

import package::shaders::caustics_sampling::caustics_filtered;
import package::shaders::receivers::Receivers;
import package::shaders::shading::{floor_albedo, perez_sky, xyy_to_rgb};
import package::shaders::water::grid_sample_hermite;

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
    _pad: u32,
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
// The objects under the water take their light from the technique's light-space deposit
// (light_deposit, light_heights, light_space), as a shadow map is read.
const FLAG_LIGHT_SPACE: u32 = 131072u;
// The scene has objects. Without, a pipeline holds none of their code: SwiftShader would run their
// intersection and shading code for every pixel though no ray meets one.
const FLAG_OBJECTS: u32 = 1048576u;
// The floor's ALBEDO_* (shading.wgsl) sits in these two bits of the flags (`flags::ALBEDO_SHIFT`).
const ALBEDO_SHIFT: u32 = 18u;

// The frame's flags (`FinalImageUniform::flags`) but those of SET_AT_RUN_TIME, fixed per pipeline:
// the frame specialises its pipeline by them (`final_image::SPECIALISED`), so the compiler drops
// the code a scene does not run (the rough water, the deck's and the floor's kinds, the terrain's
// march, the other kinds of caustics). A software rasteriser that runs both sides of every branch
// (SwiftShader) otherwise runs all of it for every pixel.
@id(0) override FLAGS: u32;
// Read from the uniform: with the water's edge rule fixed, SwiftShader's compiler takes minutes
// over the pipeline of a water that does not wrap.
const SET_AT_RUN_TIME: u32 = FLAG_WRAP_SURFACE | FLAG_WRAP_CAUSTICS;

fn deck_kind() -> u32 {
    return (FLAGS >> DECK_SHIFT) & 255u;
}

// The floor's ALBEDO_*, fixed per pipeline: SwiftShader would run every kind's code (the sand's
// two noises) for every pixel, twice (the floor's and the walls' tiles).
fn albedo_kind() -> u32 {
    return (FLAGS >> ALBEDO_SHIFT) & 3u;
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
// The terrain's heights in Hermite form (`water_patches.wgsl`, clamped at its edges), read through
// grid_sample_hermite: the CPU's bicubic `Grid::sample`, 4 texels a sample where it reads 16.
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
// Where the light-space deposit and the receivers' heights lie (receivers.rs `LightSpaceUniform`).
struct LightSpace {
    receivers: Receivers,
    absorption: vec4<f32>, // xyz: K along a receiver's flat-water path; w: 1 where the deposit tiles
}
@group(0) @binding(11) var<uniform> light_space: LightSpace;
// The technique's light-space deposit (on the floor map's window and size) and the heights of the
// receivers it met, objects included (caustics-core's `LightSpace`).
@group(0) @binding(12) var light_deposit: texture_2d<f32>;
@group(0) @binding(13) var light_heights: texture_2d<f32>;
// The water's surface rasterised from the camera (final_image_surface.wgsl): per pixel, the
// distance along its central ray to a grid through the heights' lattice (negative where none).
@group(0) @binding(14) var surface_hits: texture_2d<f32>;

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
// the slab (render.rs `MARCH_STEPS`, `EVEN_STEPS`). The terrain's search's steps (`FLOOR_STEPS`),
// and the most guesses of regula falsi after either.
const MARCH_STEPS: u32 = 512u;
const EVEN_STEPS: u32 = 24u;
// render.rs `SLAB_LATTICE`: the march's shortest step is a quarter of its spacing.
const SLAB_LATTICE: u32 = 128u;
const FLOOR_STEPS: u32 = 64u;
const BISECTIONS: u32 = 30u;
// render.rs `ROOT_TOLERANCE`: the surface's crossing is found to this fraction of the march's
// shortest step.
const ROOT_TOLERANCE: f32 = 1e-4;

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
// The rasterised surface's distance for the primary ray about to be traced from above the water
// (`surface_hits`), until `hit_surface` takes it; NO_GUIDE for every other ray.
var<private> guide: f32;
const NO_GUIDE: f32 = -2.0;

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
    if (flag & SET_AT_RUN_TIME) != 0u {
        return (params.flags & flag) != 0u;
    }
    return (FLAGS & flag) != 0u;
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
    return floor_albedo(albedo_kind(), albedo_image, p, size, extent);
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
    return slope_bound();
}

// `slab_slope` where there is a surface.
fn slope_bound() -> f32 {
    return bitcast<f32>(slab_max[1]) * 1.5 + 1e-6;
}

fn floor_height(p: vec2<f32>) -> f32 {
    if !has(FLAG_TERRAIN) {
        return 0.0;
    }
    return terrain_height_gradient(p).x;
}

fn terrain_height_gradient(p: vec2<f32>) -> vec3<f32> {
    return grid_sample_hermite(terrain_height, p, params.scene_size, false);
}

// The floor map's mean over a sample's footprint (`caustics_sampling.wgsl`): its pyramid's levels
// 1.. are the mips of caustics_mips.
fn sample_caustics_filtered(p: vec2<f32>, fa: vec2<f32>, fb: vec2<f32>, wrap: bool, beyond: vec3<f32>, has_beyond: bool) -> vec3<f32> {
    return caustics_filtered(caustics_map, caustics_mips, 1u, p, fa, fb, params.map_size, wrap, beyond, has_beyond);
}
