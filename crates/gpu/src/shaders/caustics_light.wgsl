// How a surface under the water turns the caustics maps into the sun's light: the rule the final
// image's floor and walls and bevy_caustics' material share, and that an application's own
// material uses. Functions of their arguments alone, with no binding and no import: the module
// imports as WESL (`package::shaders::caustics_light`, Bevy's `caustics_gpu::caustics_light`) and
// also works pasted ahead of any WGSL (`caustics_gpu::shaders::CAUSTICS_LIGHT`).
//
// A technique's map holds the irradiance on its receiver relative to what flat, clear water lets
// through onto a horizontal surface: 1 there, the water's absorption along the refracted paths
// included (caustics-core's `CausticsMap`, whatever the technique). Flat water transmits E cos θi T(θi) per unit of horizontal area
// (E: the sun's irradiance across its beam, θi its zenith angle, T the Fresnel transmittance), so
// a receiver's direct light is that times the map, times the sun's shadow. Where no map holds a
// surface it is lit as under flat water. CPU twins: `caustics_core::optics::sun_under_water` and
// `flat_water_light`; caustics-core/src/render/shade.rs applies them as this file's importers do.

// Unit direction towards the sun under flat water, from `to_sun` (unit, towards it in air, z > 0)
// and the water's index of refraction `ior` (Snell's law at a horizontal surface): its horizontal
// part is the air's over `ior`, its z = cos θt.
fn sun_under_water(to_sun: vec3<f32>, ior: f32) -> vec3<f32> {
    let cos_i = max(to_sun.z, 0.0);
    let cos_t = sqrt(max(1.0 - (1.0 - cos_i * cos_i) / (ior * ior), 0.0));
    return vec3<f32>(to_sun.xy / ior, cos_t);
}

// Flat water's light on a surface of unit normal `n` at `depth` below the surface, relative to a
// horizontal surface just under clear water: Beer-Lambert extinction `absorption` (per metre)
// along the refracted path (depth / cos θt), times the beam's cosine on the surface over its
// cosine on the horizontal (the refracted beam is 1 / cos θt times denser across itself than
// over the horizontal). `toward_sun` is `sun_under_water`'s direction; a horizontal receiver
// gets exp(-absorption · depth / cos θt).
fn flat_water_light(absorption: vec3<f32>, depth: f32, toward_sun: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let cos_t = max(toward_sun.z, 1e-3);
    return exp(-absorption * (depth / cos_t)) * (max(dot(n, toward_sun), 0.0) / cos_t);
}

// The sun's direct irradiance on a receiver whose light relative to flat, clear water is
// `relative` (a map's value, or `flat_water_light`'s): the horizontal irradiance above the water
// `horizontal` (E cos θi), times the flat surface's Fresnel transmittance, times `shadow` (1 in
// the sun, 0 where something blocks its refracted path).
fn sun_through_water(relative: vec3<f32>, horizontal: f32, transmittance: f32, shadow: f32) -> vec3<f32> {
    return relative * (horizontal * transmittance * shadow);
}

// The wall of the pool's square [0, size]² nearest to floor point `p`: 0 at x = 0, 1 at
// x = size, 2 at y = 0, 3 at y = size (caustics-core's `Wall::ALL` order, its `wall_at`).
fn pool_wall_at(p: vec2<f32>, size: f32) -> u32 {
    let d = array<f32, 4>(p.x, size - p.x, p.y, size - p.y);
    var k = 0u;
    for (var i = 1u; i < 4u; i++) {
        if d[i] < d[k] {
            k = i;
        }
    }
    return k;
}

// How far along wall `k` point `p` lies: y on the walls x = 0 and x = size, x on the others (the
// walls' maps' columns, `Wall::along`).
fn pool_wall_along(k: u32, p: vec2<f32>) -> f32 {
    return select(p.x, p.y, k < 2u);
}
