//! What the final-image pass reads, laid out as the structs of `final_image/final_image_inputs.wgsl` and
//! `shaders/bvh.wgsl`: the frame's uniform (camera, sun, water, flags), the objects with their
//! flattened trees, and the frozen water surface as a height grid.
//!
//! Everything the CPU renderer derives once per image (`render/mod.rs`, `render`: the refracted sun and
//! its flat-water transmittance, the camera basis) is derived here in f64 the same way and handed
//! to the shader rounded to f32, so the two sides start from the same numbers. The slab's bounds
//! (`h_max` and the slope bound of the march) depend on the water, which lives on the GPU:
//! `final_image/final_image_slab.wgsl` finds them there each frame ([`slab_bounds`] is its CPU twin).

use caustics_core::optics::{fresnel_transmittance, refract};
use caustics_core::render::{RenderOptions, sky_ambient};
use caustics_core::scene::{Albedo, FloorPattern, Material, Scene};
use caustics_core::sky::{SUN_RADIUS, Sky, TURBIDITY};
use caustics_core::water::slopes::{sample_spread, sun_slope_variance};
use caustics_core::water::{GridSurface, Surface, sample_grid};
use glam::DVec3;

use crate::bvh::FlatBvhs;
use crate::pass::f3;

/// Mirrors `FinalImage` in `final_image/final_image_inputs.wgsl` (uniform layout: each `vec3` is padded by the
/// scalar after it).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FinalImageUniform {
    /// The camera's eye, world coordinates.
    pub camera_position: [f32; 3],
    /// What radiance is multiplied by before the tone curve (`RenderOptions::exposure`).
    pub exposure: f32,
    /// The unit direction the camera looks along, world frame.
    pub camera_forward: [f32; 3],
    /// The sun's disk's radiance per unit of its irradiance (`Sky::sun_disk`).
    pub sun_disk: f32,
    /// The camera's right vector times `tan(fov_y / 2)` times the aspect ratio.
    pub camera_right: [f32; 3],
    /// Side of the square `[0, size]²` the water covers, world units (the scene's square without
    /// water).
    pub water_size: f32,
    /// The camera's up vector times `tan(fov_y / 2)`.
    pub camera_up: [f32; 3],
    /// The water's rest level above z = 0 (`Water::level`), world units; 0 without water.
    pub water_level: f32,
    /// The unit direction the sunlight travels (z < 0), world frame.
    pub sun: [f32; 3],
    /// The light's intensity, the scale of its colour (`Light::intensity`).
    pub sun_intensity: f32,
    /// The sun's direction after refraction into flat water (`sun` itself without water).
    pub sun_water: [f32; 3],
    /// Flat water's Fresnel transmittance for the sun (1 without water).
    pub t_flat: f32,
    /// The light's linear RGB colour.
    pub light_color: [f32; 3],
    /// The water's index of refraction (1 without water).
    pub ior: f32,
    /// The water's Beer-Lambert absorption `K` per RGB channel, per world unit of path (0 without
    /// water).
    pub absorption: [f32; 3],
    /// `Scene::size`: side of the terrain's square, and of the floor's without water, world units.
    pub scene_size: f32,
    /// Side of the square `[0, size]²` the floor's caustics map covers, world units: the caller's
    /// when it gives one, else the water's (the scene's without water); the scene's without a map.
    pub map_size: f32,
    /// The image's width, pixels.
    pub width: u32,
    /// The image's height, pixels.
    pub height: u32,
    /// Samples per pixel along each axis (n² rays a pixel), at least 1.
    pub supersampling: u32,
    /// How many entries the objects' buffer holds.
    pub object_count: u32,
    /// Bits of [`flags`]: what the scene has and how the caustics are bound; the deck's code above
    /// [`flags::DECK_SHIFT`], the floor's albedo, one of [`albedo`], above [`flags::ALBEDO_SHIFT`].
    pub flags: u32,
    /// Keeps `tone_map` in its place in the shader's block.
    pub _pad: u32,
    /// `ToneMap::code` of the options' tone curve.
    pub tone_map: u32,
    /// The sky's irradiance on a horizontal surface (`render::sky_ambient`) times the sun's
    /// intensity, before the light's colour.
    pub ambient: [f32; 3],
    /// The cosine of the sun's angular radius.
    pub sun_cos_radius: f32,
    /// The sky's Perez coefficients `A..E` and scale (`Sky::coefficients`), each over `Y, x, y`.
    pub sky: [[f32; 4]; 6],
    /// The angle one sample covers (`slopes::sample_spread`), which sizes its footprint on the
    /// water when the normals are filtered.
    pub slope_spread: f32,
    /// The slope variance the sun's disk adds to the glint (`slopes::sun_slope_variance`).
    pub sun_variance: f32,
    /// Level 0 of the water's slope moments' pyramid (`final_image::slopes`): the heights' lattice.
    pub slope_cols: u32,
    /// Rows of that level; both are 1 when no pyramid is bound.
    pub slope_rows: u32,
}

/// Mirrors `Slab` in `final_image/final_image_slab.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SlabUniform {
    /// Side of the water's square, world units.
    pub size: f32,
    /// The water's edge rule: 1 where the heights tile, 0 where they clamp.
    pub wrap: u32,
    /// Samples along each side of the lattice the bound is taken on ([`SLAB_LATTICE`]).
    pub lattice: u32,
    /// Padding to the uniform's 16 bytes.
    pub _pad: u32,
}

/// Samples along each side of the lattice the slab bound is taken on (render/mod.rs `render`).
pub const SLAB_LATTICE: u32 = caustics_core::render::SLAB_LATTICE as u32;

/// `FinalImageUniform::flags`, the `FLAG_*` constants of `final_image_inputs.wgsl`.
pub mod flags {
    /// The scene has water.
    pub const WATER: u32 = 1;
    /// A heights texture is bound; without it the water is flat.
    pub const SURFACE: u32 = 2;
    /// A caustics map of the floor is bound, over the square of `map_size`.
    pub const CAUSTICS: u32 = 4;
    /// The scene has a terrain, bound as its height texture.
    pub const TERRAIN: u32 = 8;
    /// The water's heights tile at its edges (periodic) rather than clamp.
    pub const WRAP_SURFACE: u32 = 16;
    /// The caustics map tiles too: tiling water with no terrain.
    pub const WRAP_CAUSTICS: u32 = 32;
    /// No water, and a map of the light through the glass objects (`caustic_triangles`).
    pub const AIR_CAUSTICS: u32 = 64;
    /// The caustics are an eye-space image of this camera (`cascaded`), bound where the map is.
    pub const EYE_CAUSTICS: u32 = 128;
    /// `Deck::code` of the pool's deck, in the bits from this one up (`deck_kind`).
    pub const DECK_SHIFT: u32 = 8;
    /// The waves' normals filtered by each sample's footprint (`RenderOptions::filter_water`),
    /// above the deck's bits.
    pub const FILTER_WATER: u32 = 1 << 16;
    /// The objects under the water take their light from the technique's light-space deposit
    /// (bound with the receivers' heights), as a shadow map is read.
    pub const LIGHT_SPACE: u32 = 1 << 17;
    /// The floor's albedo, one of [`super::albedo`], in the two bits from this one up
    /// (`albedo_kind`).
    pub const ALBEDO_SHIFT: u32 = 18;
    /// The scene has objects (`object_count` > 0).
    pub const OBJECTS: u32 = 1 << 20;
}

/// The floor's albedo in `FinalImageUniform::flags` ([`flags::ALBEDO_SHIFT`]), the `ALBEDO_*`
/// constants of `shading.wgsl`.
pub mod albedo {
    /// The pool's tiles (`FloorPattern::Tiles`).
    pub const TILES: u32 = 0;
    /// Sand (`FloorPattern::Sand`).
    pub const SAND: u32 = 1;
    /// Uniform light grey (`FloorPattern::Plain`).
    pub const PLAIN: u32 = 2;
    /// The floor's albedo image, bound as a texture (`Albedo::Image`).
    pub const IMAGE: u32 = 3;
}

/// Mirrors `Object` in `final_image/final_image_inputs.wgsl` (storage layout).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuObject {
    /// Diffuse colour, or glass tint.
    pub color: [f32; 3],
    /// The glass's index of refraction (1 for a diffuse object).
    pub ior: f32,
    /// The object's root in the node buffer.
    pub root: u32,
    /// 1 for glass, 0 for a diffuse object.
    pub glass: u32,
    /// Padding to the WGSL struct's 32-byte stride.
    pub _pad: [u32; 2],
}

pub use caustics_core::render::water_grid_resolution;

/// The frozen water surface as
/// [`FinalImage::render`](super::FinalImage::render) hands it to the GPU:
/// `surface` sampled on the lattice of [`water_grid_resolution`] over the water's square (uploaded
/// as is, the heights texture of [`crate::WaterTextures`]) and read back through the same bicubic
/// interpolant, with the water's edge rule. `None` without water. Render on the CPU with this
/// surface to get the image the GPU renders.
pub fn water_grid(scene: &Scene, surface: &dyn Surface) -> Option<GridSurface> {
    let water = scene.water.as_ref()?;
    let n = water_grid_resolution(scene);
    Some(GridSurface {
        grid: sample_grid(surface, n, n, water.size),
        size: water.size,
        edge: water.edge(),
    })
}

/// The slab bound of the CPU renderer, which the slab pass (`final_image/final_image_slab.wgsl`) finds
/// on the GPU: both sides search the same slab and put the deck at the same height.
pub use caustics_core::render::{Slab, slab_bounds};

/// Where the floor's light comes from, as the frame binds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Lighting {
    /// No map: lit as under flat water.
    Flat,
    /// A map of the floor covering the square `[0, size]²`; with `light_space`, the deposit it
    /// was looked up from, for the objects among the technique's receivers.
    Floor { size: f64, light_space: bool },
    /// An eye-space image of the scene's camera (`cascaded`).
    EyeSpace,
}

/// The frame's uniform: `surface` whether a heights texture is bound, `slopes` the lattice of its
/// slope moments' pyramid, `object_count` the number of objects uploaded, `(width, height)` the
/// frame's image (the camera's when it was built).
pub(super) fn uniform(
    scene: &Scene,
    surface: bool,
    slopes: Option<(u32, u32)>,
    lighting: Lighting,
    options: &RenderOptions,
    object_count: u32,
    (width, height): (u32, u32),
) -> FinalImageUniform {
    let cam = &scene.camera;
    // `Camera::ray`'s basis, with the field of view and the aspect ratio folded in.
    let forward = (cam.target - cam.position).normalize();
    let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
    let up = right.cross(forward);
    let half = (cam.fov_y.to_radians() * 0.5).tan();
    let aspect = width as f64 / height as f64;

    let water = scene.water.as_ref();
    let ior = water.map_or(1.0, |w| w.ior);
    let sun = scene.light.direction;
    let sun_water = refract(sun, DVec3::Z, 1.0 / ior).unwrap_or(sun);
    let t_flat = fresnel_transmittance(-sun.z, 1.0, ior);
    let sky = Sky::new(sun, TURBIDITY);

    let mut f = 0;
    if let Some(w) = water {
        f |= flags::WATER;
        if surface {
            f |= flags::SURFACE;
        }
        if w.wrap {
            f |= flags::WRAP_SURFACE;
        }
        match lighting {
            Lighting::Floor { light_space, .. } => {
                f |= flags::CAUSTICS;
                if light_space {
                    f |= flags::LIGHT_SPACE;
                }
            }
            Lighting::EyeSpace => f |= flags::EYE_CAUSTICS,
            Lighting::Flat => {}
        }
        if w.wrap && scene.floor.terrain.is_none() {
            f |= flags::WRAP_CAUSTICS;
        }
        f |= scene.floor.deck.code() << flags::DECK_SHIFT;
        if options.filter_water && surface && slopes.is_some() {
            f |= flags::FILTER_WATER;
        }
    }
    if water.is_none() && matches!(lighting, Lighting::Floor { .. }) {
        f |= flags::AIR_CAUSTICS;
    }
    if scene.floor.terrain.is_some() {
        f |= flags::TERRAIN;
    }
    if object_count > 0 {
        f |= flags::OBJECTS;
    }
    f |= match &scene.floor.albedo {
        Albedo::Pattern(FloorPattern::Tiles) => albedo::TILES,
        Albedo::Pattern(FloorPattern::Sand) => albedo::SAND,
        Albedo::Pattern(FloorPattern::Plain) => albedo::PLAIN,
        Albedo::Image { .. } => albedo::IMAGE,
    } << flags::ALBEDO_SHIFT;
    FinalImageUniform {
        camera_position: f3(cam.position),
        exposure: options.exposure as f32,
        camera_forward: f3(forward),
        sun_disk: sky.sun_disk(-sun) as f32,
        camera_right: f3(right * (half * aspect)),
        water_size: water.map_or(scene.size, |w| w.size) as f32,
        camera_up: f3(up * half),
        water_level: water.map_or(0.0, |w| w.level()) as f32,
        sun: f3(sun),
        sun_intensity: scene.light.intensity as f32,
        sun_water: f3(sun_water),
        t_flat: t_flat as f32,
        light_color: f3(scene.light.color),
        ior: ior as f32,
        absorption: f3(water.map_or(DVec3::ZERO, |w| w.absorption)),
        scene_size: scene.size as f32,
        map_size: match lighting {
            Lighting::Floor { size, .. } => size,
            _ => scene.size,
        } as f32,
        width,
        height,
        supersampling: options.supersampling.max(1),
        object_count,
        flags: f,
        _pad: 0,
        tone_map: options.tone_map.code(),
        ambient: f3(sky_ambient(sun) * scene.light.intensity),
        sun_cos_radius: SUN_RADIUS.cos() as f32,
        sky: {
            let c = sky.coefficients();
            std::array::from_fn(|i| [c[0][i] as f32, c[1][i] as f32, c[2][i] as f32, 0.0])
        },
        slope_spread: sample_spread(cam.fov_y, height, options.supersampling) as f32,
        sun_variance: sun_slope_variance(SUN_RADIUS) as f32,
        slope_cols: slopes.map_or(1, |s| s.0),
        slope_rows: slopes.map_or(1, |s| s.1),
    }
}

/// The scene's objects for the GPU: one entry each, and every object's tree appended to shared
/// node and triangle-slot buffers with its indices made global.
pub struct Meshes {
    /// One entry per scene object, in the scene's order.
    pub objects: Vec<GpuObject>,
    /// Every object's tree in the shared node and triangle-slot buffers.
    pub trees: FlatBvhs,
}

/// Every object's tree flattened ([`FlatBvhs`]) and its entry.
pub fn meshes(scene: &Scene) -> Meshes {
    let mut m = Meshes {
        objects: Vec::with_capacity(scene.objects.len()),
        trees: FlatBvhs::default(),
    };
    for obj in &scene.objects {
        let root = m.trees.push(&obj.mesh);
        let (color, ior, glass) = match &obj.material {
            Material::Diffuse { color } => (*color, 1.0, 0),
            Material::Glass { ior, tint } => (*tint, *ior, 1),
        };
        m.objects.push(GpuObject {
            color: f3(color),
            ior: ior as f32,
            root,
            glass,
            _pad: [0; 2],
        });
    }
    m
}
