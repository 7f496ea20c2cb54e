//! The render world's side: one `caustics_gpu` context wrapping Bevy's device and queue, and per
//! water its source (`GpuWater`) and technique. Extracted from the main world each frame
//! ([`extract`]), brought up to date in `Render`'s `Prepare` set (uniform writes; a build only when
//! the technique or the water changed), and recorded into Bevy's command encoder in the
//! `RenderGraph` schedule before `camera_driver` draws the cameras ([`record`]), ending in GPU
//! copies into the [`CausticMaps`](crate::CausticMaps)' images. A new technique, new parameters
//! or a new heights texture rebuild the water's state; a change to its scene does not (spawn a new
//! water, with new maps, for that).

use std::sync::{Arc, Mutex};

use bevy::core_pipeline::schedule::camera_driver;
use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy::render::render_asset::RenderAssets;
use bevy::render::render_resource::TextureId;
use bevy::render::renderer::{
    RenderAdapter, RenderContext, RenderDevice, RenderGraph, RenderInstance, RenderQueue,
};
use bevy::render::texture::GpuImage;
use bevy::render::{Extract, Render, RenderSystems};

use caustics_core::scene::Scene;
use caustics_core::water::ripple::Drop;
use caustics_gpu::map_mips::{MapMips, mips_pipeline};
use caustics_gpu::water::field::GpuWater;
use caustics_gpu::{GpuContext, Output, Technique, TrafficCounts, WaterTextures};

use caustics_core::scene::Solids;

use crate::receivers::{self, ReceiverMeshes};
use crate::{CausticMaps, CausticWater, Heights, PendingDrops, scene_from_world};

/// What the plugin did, shared by the main and the render world: frames recorded, and what the
/// techniques and water sources created, uploaded and read back in steady frames (those that
/// built nothing). A real-time frame creates nothing and reads nothing back.
#[derive(Resource, Clone, Default)]
pub struct CausticsStats(Arc<Mutex<Stats>>);

/// A snapshot of [`CausticsStats`].
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Frames whose caustics were recorded.
    pub frames: u64,
    /// Of those, frames that built nothing (no technique or water created or configured).
    pub steady_frames: u64,
    /// The traffic of the steady frames, summed.
    pub steady: TrafficCounts,
    /// The technique recorded last, per water (by name).
    pub techniques: Vec<String>,
    /// The last error, for the application to show.
    pub error: Option<String>,
}

impl CausticsStats {
    pub fn get(&self) -> Stats {
        self.0.lock().map(|s| s.clone()).unwrap_or_default()
    }

    fn update(&self, f: impl FnOnce(&mut Stats)) {
        if let Ok(mut s) = self.0.lock() {
            f(&mut s);
        }
    }
}

/// One water as the main world left it this frame: its component only when it changed (the render
/// world keeps the last one), so that a scene is not copied every frame.
struct Extracted {
    entity: Entity,
    water: Option<CausticWater>,
    /// The receivers its meshes make, when they changed.
    receivers: Option<Option<Arc<Solids>>>,
    maps: CausticMaps,
    scene_from_world: Mat4,
    drops: Vec<Drop>,
}

#[derive(Resource, Default)]
pub(crate) struct ExtractedWaters {
    waters: Vec<Extracted>,
    /// Direction of travel of the sun's light, world coordinates.
    sun: Option<Vec3>,
    /// The first active 3D camera: its transform and vertical field of view (radians), for
    /// eye-space techniques.
    camera: Option<(GlobalTransform, f32)>,
    time: f64,
}

/// A water as extracted: its component and its maps with their change ticks, and where it stands.
type WaterItems = (
    Entity,
    Ref<'static, CausticWater>,
    Ref<'static, CausticMaps>,
    &'static GlobalTransform,
    Option<Ref<'static, ReceiverMeshes>>,
);

/// What an eye-space technique takes from Bevy's 3D cameras.
type Cameras = (
    &'static Camera,
    &'static GlobalTransform,
    &'static Projection,
);

pub(crate) fn extract(
    mut commands: Commands,
    waters: Extract<Query<WaterItems>>,
    lights: Extract<Query<&GlobalTransform, With<DirectionalLight>>>,
    cameras: Extract<Query<Cameras, With<Camera3d>>>,
    drops: Extract<Res<PendingDrops>>,
    time: Extract<Res<Time>>,
) {
    let sun = lights.iter().next().map(|t| t.forward().as_vec3());
    let camera = cameras
        .iter()
        .filter(|(c, _, _)| c.is_active)
        .find_map(|(_, at, projection)| match projection {
            Projection::Perspective(p) => Some((*at, p.fov)),
            _ => None,
        });
    let waters = waters
        .iter()
        .map(|(entity, water, maps, at, receivers)| {
            let m = scene_from_world(at);
            let renewed = water.is_changed() || maps.is_changed();
            Extracted {
                entity,
                receivers: receivers
                    .filter(|r| r.is_changed() || renewed)
                    .map(|r| r.solids.clone()),
                // Also when the maps are new: a water that got them after its component (or got
                // new ones) enters the query then, and the render world must learn it anew.
                water: renewed.then(|| water.as_ref().clone()),
                maps: maps.as_ref().clone(),
                scene_from_world: m,
                drops: drops
                    .0
                    .iter()
                    .filter(|(e, _)| *e == entity)
                    .map(|(_, d)| d.clone())
                    .collect(),
            }
        })
        .collect();
    commands.insert_resource(ExtractedWaters {
        waters,
        sun,
        camera,
        time: time.elapsed_secs_f64(),
    });
}

pub(crate) fn build(render_app: &mut SubApp) {
    render_app
        .init_resource::<ExtractedWaters>()
        .init_resource::<Waters>()
        .add_systems(Render, prepare.in_set(RenderSystems::Prepare))
        .add_systems(RenderGraph, record.before(camera_driver));
}

/// What a water's state was built from: a new one of any part builds it again.
#[derive(Clone, PartialEq, Debug)]
struct Key {
    technique: String,
    params: toml::Table,
    heights: HeightsKey,
}

/// A water's GPU state.
struct WaterState {
    key: Key,
    source: Option<GpuWater>,
    technique: Box<dyn Technique>,
    scene: Scene,
    maps: CausticMaps,
    /// The floor image's mips from its first level, for the texture Bevy holds for it now.
    floor_mips: Option<(TextureId, MapMips)>,
    /// The receivers whose heights and view the light images hold, by identity (`Some(None)`:
    /// none, the view says so), and the textures Bevy holds for those images.
    light_written: Option<(Option<usize>, TextureId, TextureId)>,
    /// The scene's source sampled for the water's surface ([`crate::SURFACE_TEXELS`]²).
    surface: Option<wgpu::Texture>,
}

/// Where the heights of a built state come from.
#[derive(Clone, PartialEq, Debug)]
enum HeightsKey {
    Scene,
    /// The image, and the texture Bevy holds for it now (a new one when the image was remade).
    Image(AssetId<Image>, TextureId),
}

#[derive(Resource, Default)]
pub(crate) struct Waters {
    ctx: Option<GpuContext>,
    /// `caustics_mips.wgsl`'s pipeline, made with the context.
    mips: Option<wgpu::ComputePipeline>,
    states: HashMap<Entity, WaterState>,
    /// Each water's component as last extracted.
    known: HashMap<Entity, CausticWater>,
    /// Each water's receivers from its meshes as last extracted.
    solids: HashMap<Entity, Option<Arc<Solids>>>,
    /// Waters whose build failed, with the key it failed for: not tried again until it changes.
    failed: HashMap<Entity, Key>,
    /// The traffic counts when the last frame's `prepare` began, and whether that frame built
    /// anything: a frame is counted from one `prepare` to the next, its `record` included.
    last: Option<(TrafficCounts, bool)>,
}

#[allow(clippy::too_many_arguments)]
fn prepare(
    mut waters: ResMut<Waters>,
    mut extracted: ResMut<ExtractedWaters>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    adapter: Res<RenderAdapter>,
    instance: Res<RenderInstance>,
    images: Res<RenderAssets<GpuImage>>,
    stats: Res<CausticsStats>,
) {
    let Waters {
        ctx,
        mips,
        states,
        known,
        solids,
        failed,
        last,
    } = &mut *waters;
    let ctx = ctx.get_or_insert_with(|| {
        GpuContext::shared(
            (**instance).clone(),
            (**adapter).clone(),
            device.wgpu_device().clone(),
            (**queue).clone(),
        )
    });
    let before = ctx.traffic();
    if let Some((start, built)) = last.take() {
        let spent = before.since(&start);
        stats.update(|s| {
            s.frames += 1;
            if !built {
                s.steady_frames += 1;
                s.steady += spent;
            }
        });
    }
    let mut built = false;
    for w in &mut extracted.waters {
        if let Some(water) = w.water.take() {
            known.insert(w.entity, water);
        }
        if let Some(r) = w.receivers.take() {
            solids.insert(w.entity, r);
        }
    }
    let alive = |e: &Entity| extracted.waters.iter().any(|w| w.entity == *e);
    states.retain(|e, _| alive(e));
    failed.retain(|e, _| alive(e));
    known.retain(|e, _| alive(e));
    solids.retain(|e, _| alive(e));
    for w in &extracted.waters {
        let Some(known) = known.get(&w.entity) else {
            continue;
        };
        // The meshes' receivers in place of the scene's own objects, where there are any.
        let meshes = solids.get(&w.entity).cloned().flatten();
        let with_meshes;
        let water = match &meshes {
            None => known,
            Some(s) => {
                let mut water = known.clone();
                water.scene.floor.solids = Some(s.clone());
                with_meshes = water;
                &with_meshes
            }
        };
        let heights = match &water.heights {
            Heights::Scene => HeightsKey::Scene,
            Heights::Image(h) => match images.get(h) {
                Some(g) => HeightsKey::Image(h.id(), g.texture.id()),
                None => continue,
            },
        };
        let key = Key {
            technique: water.technique.clone(),
            params: water.params.clone(),
            heights,
        };
        let stale = states.get(&w.entity).is_none_or(|s| s.key != key);
        if stale {
            if failed.get(&w.entity) == Some(&key) {
                continue;
            }
            built = true;
            match build_state(ctx, water, &w.maps, key.clone(), &images) {
                Ok(state) => {
                    info!(
                        "bevy_caustics: {} on {:?} ({:.1} MiB on the GPU)",
                        state.key.technique,
                        w.entity,
                        state.technique.bytes() as f64 / (1024.0 * 1024.0)
                    );
                    failed.remove(&w.entity);
                    states.insert(w.entity, state);
                }
                Err(e) => {
                    let e = format!("bevy_caustics: {} on {:?}: {e}", water.technique, w.entity);
                    error!("{e}");
                    stats.update(|s| s.error = Some(e));
                    states.remove(&w.entity);
                    failed.insert(w.entity, key);
                    continue;
                }
            }
        }
        let state = states.get_mut(&w.entity).expect("built above");
        state.maps = w.maps.clone();
        state.scene.floor.solids = water.scene.floor.solids.clone();
        if let Some(floor) = images.get(&state.maps.floor) {
            let id = floor.texture.id();
            if state.floor_mips.as_ref().is_none_or(|(t, _)| *t != id) {
                let pipeline = mips.get_or_insert_with(|| mips_pipeline(ctx));
                built = true;
                state.floor_mips = Some((id, MapMips::in_place(ctx, pipeline, &floor.texture)));
            }
        }
        if let Some(sun) = extracted.sun {
            let d = w
                .scene_from_world
                .transform_vector3(sun)
                .normalize_or_zero();
            if d.z < -1e-3 {
                state.scene.light.direction = d.as_dvec3().to_array().into();
            }
        }
        if let Some((at, fov)) = extracted.camera {
            // The eye-space image's camera: Bevy's pose and vertical field of view, the size of
            // the image it is copied into (`CausticMaps::eye`).
            let m = w.scene_from_world;
            let position = m.transform_point3(at.translation());
            let forward = m.transform_vector3(at.forward().as_vec3());
            let camera = &mut state.scene.camera;
            camera.position = position.as_dvec3().to_array().into();
            camera.target = (position + forward).as_dvec3().to_array().into();
            camera.fov_y = fov.to_degrees() as f64;
        }
        state.scene.time = extracted.time;
        if let Some(source) = &mut state.source {
            for d in &w.drops {
                source.drop_ripple(ctx, d);
            }
            source.update(ctx, extracted.time, 1.0);
        }
        let had = ctx.traffic().created();
        if let Err(e) = state.technique.update(ctx, &state.scene) {
            let e = format!("bevy_caustics: {}: {e}", state.key.technique);
            error!("{e}");
            stats.update(|s| s.error = Some(e));
        }
        built |= ctx.traffic().created() != had;
        write_light_view(ctx, state, &images, &stats);
    }
    *last = Some((before, built));
    let names = states.values().map(|s| s.key.technique.clone()).collect();
    stats.update(|s| s.techniques = names);
}

fn build_state(
    ctx: &GpuContext,
    water: &CausticWater,
    maps: &CausticMaps,
    key: Key,
    images: &RenderAssets<GpuImage>,
) -> Result<WaterState, String> {
    let mut scene = water.scene.clone();
    scene.caustics.technique = water.technique.clone();
    let mut technique = caustics_gpu::registry::create(ctx, &water.technique, &water.params)
        .map_err(|e| e.to_string())?;
    let mut surface = None;
    let (source, textures) = match &water.heights {
        Heights::Scene => {
            let spec = scene.water.as_ref().ok_or("the scene has no water")?;
            let mut source = GpuWater::new(ctx, spec).map_err(|e| e.to_string())?;
            let (cols, rows) = technique.water_resolution(&scene);
            let textures = source.output(ctx, cols, rows).map_err(|e| e.to_string())?;
            let n = crate::SURFACE_TEXELS;
            let sampled = source.output(ctx, n, n).map_err(|e| e.to_string())?;
            surface = Some(sampled.heights.texture().clone());
            (Some(source), textures)
        }
        Heights::Image(h) => {
            let g = images
                .get(h)
                .ok_or("the heights image is not on the GPU yet")?;
            if g.texture.format() != bevy::render::render_resource::TextureFormat::R32Float {
                return Err(format!(
                    "the heights image is {:?}; it must be R32Float",
                    g.texture.format()
                ));
            }
            (None, WaterTextures::of(&g.texture))
        }
    };
    technique
        .configure(ctx, &scene, &textures)
        .map_err(|e| e.to_string())?;
    ctx.check().map_err(|e| e.to_string())?;
    Ok(WaterState {
        key,
        source,
        technique,
        scene,
        maps: maps.clone(),
        floor_mips: None,
        light_written: None,
        surface,
    })
}

/// The receivers' heights and view into the water's light images, when the technique's receivers
/// (or Bevy's textures for the images) changed: an upload then, nothing in a steady frame.
fn write_light_view(
    ctx: &GpuContext,
    state: &mut WaterState,
    images: &RenderAssets<GpuImage>,
    stats: &CausticsStats,
) {
    let (Some(heights), Some(view)) = (
        images.get(&state.maps.receivers),
        images.get(&state.maps.light_view),
    ) else {
        return;
    };
    let frame = state.technique.receivers();
    let id = frame.map(|f| Arc::as_ptr(&f.receivers) as usize);
    let key = (id, heights.texture.id(), view.texture.id());
    if state.light_written == Some(key) {
        return;
    }
    state.light_written = Some(key);
    let side = heights.texture.width();
    let r = frame.and_then(|f| {
        let texels = receivers::heights_image(&f.receivers, side);
        if texels.is_none() {
            let e = format!(
                "bevy_caustics: the receivers' {} x {} heights exceed their {side}² image",
                f.receivers.cols, f.receivers.rows
            );
            error!("{e}");
            stats.update(|s| s.error = Some(e));
        }
        Some((f, texels?))
    });
    if let Some((_, texels)) = &r {
        write(ctx, &heights.texture, bytemuck_f32(texels), side * 4);
    }
    let texels = receivers::light_view(r.map(|(f, _)| (&*f.receivers, f.absorption)));
    let bytes: Vec<f32> = texels.iter().flatten().copied().collect();
    write(ctx, &view.texture, bytemuck_f32(&bytes), 3 * 16);
}

fn bytemuck_f32(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn write(ctx: &GpuContext, texture: &wgpu::Texture, bytes: Vec<u8>, row: u32) {
    ctx.write_texture(
        texture.as_image_copy(),
        &bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(row),
            rows_per_image: None,
        },
        texture.size(),
    );
}

/// Records each water's passes into Bevy's encoder, then copies the maps into the images the
/// materials sample: GPU to GPU, nothing read back.
fn record(
    mut render_context: RenderContext,
    mut waters: ResMut<Waters>,
    images: Res<RenderAssets<GpuImage>>,
    stats: Res<CausticsStats>,
) {
    if waters.states.is_empty() {
        return;
    }
    let encoder = render_context.command_encoder();
    for state in waters.states.values_mut() {
        if let Some(source) = &mut state.source {
            source.encode(encoder, None);
        }
        state.technique.encode(encoder, None);
        let (map, image, floor) = match state.technique.output() {
            Some(Output::Floor(map)) => (map, &state.maps.floor, true),
            Some(Output::EyeSpace(map)) => (map, &state.maps.eye, false),
            None => continue,
        };
        if let Some(image) = images.get(image) {
            if let Err(e) = copy(encoder, map, &image.texture) {
                stats.update(|s| s.error = Some(format!("caustics map: {e}")));
            } else if let (true, Some((_, mips))) = (floor, &state.floor_mips) {
                // The floor map's mips, from the level just copied.
                mips.encode_pass(encoder, "bevy_caustics floor mips");
            }
        }
        if let (Some(heights), Some(image)) = (&state.surface, images.get(&state.maps.surface))
            && let Err(e) = copy(encoder, heights, &image.texture)
        {
            stats.update(|s| s.error = Some(format!("water surface: {e}")));
        }
        if let (Some(r), Some(image)) = (state.technique.receivers(), images.get(&state.maps.light))
            && let Err(e) = copy(encoder, &r.deposit, &image.texture)
        {
            stats.update(|s| s.error = Some(format!("light-space deposit: {e}")));
        }
        if let (Some(walls), Some(image)) = (state.technique.walls(), images.get(&state.maps.walls))
            && let Err(e) = copy(encoder, walls.texture, &image.texture)
        {
            stats.update(|s| s.error = Some(format!("wall maps: {e}")));
        }
    }
}

/// `from`'s texels into `to`, over the extent both have; an error (and no copy) where their
/// formats differ.
fn copy(
    encoder: &mut wgpu::CommandEncoder,
    from: &wgpu::Texture,
    to: &wgpu::Texture,
) -> Result<(), String> {
    if from.format() != to.format() {
        return Err(format!(
            "the technique writes {:?}, the image is {:?}",
            from.format(),
            to.format()
        ));
    }
    let extent = wgpu::Extent3d {
        width: from.width().min(to.width()),
        height: from.height().min(to.height()),
        depth_or_array_layers: from.depth_or_array_layers().min(to.depth_or_array_layers()),
    };
    encoder.copy_texture_to_texture(from.as_image_copy(), to.as_image_copy(), extent);
    Ok(())
}
