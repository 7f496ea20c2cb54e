//! One frame of the scene: the water's surface, each shown technique's caustics map (through
//! [`Runner`], so every technique the CLI runs appears here as it lands), and the final image of
//! each side traced by [`FinalImage`] from the orbit camera.
//!
//! A scene with water runs the techniques that map the floor from the water surface; a scene
//! without water and with glass objects (`glass`) runs those whose caustic generators are the
//! glass objects (`caustic-triangles`), beside the glass reference (paper 4's photon tracer
//! against the exact geometry).
//!
//! A technique runs again only when its input changed (surface, sun, map size, its parameters):
//! orbiting the camera re-traces the image and leaves the maps alone, which on a software
//! adapter is the difference between a fluid and a sluggish viewer.

use std::time::Instant;

use anyhow::{Context, Result};
use glam::DVec3;

use caustics_core::map::CausticsMap;
use caustics_core::render::{Caustics, Image, RenderOptions, render};
use caustics_core::scene::Scene;
use caustics_core::techniques::{self, Descriptor};
use caustics_core::walls::WallMaps;
use caustics_core::water::Surface;
use caustics_gpu::final_image::FinalImage;
use caustics_gpu::renderer::{FrameWater, Renderer, WaterClock};
use caustics_gpu::{GpuContext, GpuTimer, PassTime};

use super::water::{SurfaceKey, WaterState};
use crate::techniques::{Job, Runner, SceneCaustics, Spec};
use caustics_core::orbit::OrbitCamera;

/// A snapshot of the frame's traffic ([`SceneRenderer::traffic`]).
pub struct Traffic {
    pub total: caustics_gpu::TrafficCounts,
    pub sides: Vec<caustics_gpu::TrafficCounts>,
}

/// A technique with its parameters as the panel edits them: a registered entry and its own
/// table (`n`, `m`, ...), turned into a [`Spec`] when run.
#[derive(Clone, Debug)]
pub struct TechniqueChoice {
    pub entry: &'static Descriptor,
    /// Its table, its defaults filled in (a parameter whose default is chosen by the technique
    /// is absent until set).
    pub params: toml::Table,
    /// The reference's triangulation cells per map texel along each axis (its quality knob, a
    /// `Job` field rather than a technique parameter).
    pub cells_per_texel: u32,
}

impl PartialEq for TechniqueChoice {
    fn eq(&self, other: &Self) -> bool {
        self.entry.name == other.entry.name
            && self.params == other.params
            && self.cells_per_texel == other.cells_per_texel
    }
}

impl TechniqueChoice {
    /// From the CLI's spelling, `name` or `name:key=value,...`, with the defaults filled in.
    pub fn parse(s: &str, cells_per_texel: u32) -> Result<Self> {
        let spec: Spec = s.parse()?;
        let mut params = spec.entry.defaults();
        params.extend(spec.own());
        Ok(TechniqueChoice {
            entry: spec.entry,
            params,
            cells_per_texel,
        })
    }

    /// As registered (`yuksel-targets`).
    pub fn name(&self) -> &'static str {
        self.entry.name
    }

    /// The key of its parameter table, which its variants share.
    pub fn base(&self) -> &'static str {
        self.entry.table
    }

    /// `name:key=value,...`, as `--technique` takes it.
    pub fn label(&self) -> String {
        if self.params.is_empty() {
            return self.entry.name.to_string();
        }
        let kv: Vec<String> = self
            .params
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .collect();
        format!("{}:{}", self.entry.name, kv.join(","))
    }

    pub fn spec(&self) -> Result<Spec> {
        Ok(self.label().parse()?)
    }
}

/// Whether technique `name` computes its caustics in the eye camera's screen space: its image
/// follows the camera and the view's size, not only the water and the sun.
pub fn eye_space(name: &str) -> bool {
    techniques::find(name).is_some_and(|d| d.eye_space())
}

/// What a map was computed from: while it holds, the map is reused.
#[derive(Clone, Debug, PartialEq)]
struct MapKey {
    label: String,
    cells_per_texel: u32,
    /// The water's state; `None` in a scene without water.
    surface: Option<SurfaceKey>,
    sun: [u64; 3],
    map_size: u32,
    /// The camera and image size, for an eye-space technique (its image is made for them).
    view: Option<String>,
}

/// What a technique run made: its caustics, where it ran ("GPU" or "CPU"), the walls' maps.
type Made = (SceneCaustics, &'static str, Option<WallMaps>);

/// Maps kept for reuse: switching back to a technique, or showing the same one on both sides,
/// while the water stands still costs no run (and the memory is bounded: 8 maps of 1024² are
/// 100 MB).
const MAP_CACHE: usize = 8;

/// One side of the view: a technique, its latest caustics (a floor map, or `cascaded`'s eye-space
/// image), and what running it said.
pub struct Slot {
    pub choice: TechniqueChoice,
    pub caustics: Option<SceneCaustics>,
    /// The pool's walls' maps that came with the caustics (the reference's, when the scene's
    /// walls are on), which the final image lights the walls with.
    pub walls: Option<WallMaps>,
    key: Option<MapKey>,
    pub error: Option<String>,
    /// "GPU" or "CPU", and milliseconds, of the last run that happened.
    pub backend: &'static str,
    pub technique_ms: Option<f64>,
    /// Whether the map changed in the last frame (the map and buffer views refresh then).
    pub map_changed: bool,
}

impl Slot {
    pub fn new(choice: TechniqueChoice) -> Self {
        Slot {
            choice,
            caustics: None,
            walls: None,
            key: None,
            error: None,
            backend: "",
            technique_ms: None,
            map_changed: false,
        }
    }

    /// Whether the map window must read this slot's map back from the GPU frame: a GPU
    /// technique's map after a frame that `rendered` it, or one never read since (its window
    /// opened on a still frame). A map made on the CPU is the slot's already.
    pub fn needs_read(&self, rendered: bool) -> bool {
        match (&self.caustics, self.backend) {
            (None, _) => true,
            (Some(_), "GPU") => rendered,
            (Some(_), _) => false,
        }
    }

    /// Show what a run made.
    fn set(&mut self, (caustics, backend, walls): Made) {
        self.caustics = Some(caustics);
        self.walls = walls;
        self.backend = backend;
        self.error = None;
    }

    /// No caustics to show: `error` says why, where something failed.
    fn clear(&mut self, error: Option<String>) {
        self.caustics = None;
        self.walls = None;
        self.error = error;
    }

    /// The floor map, for a technique that makes one.
    pub fn floor_map(&self) -> Option<&CausticsMap> {
        self.caustics.as_ref()?.floor()
    }
}

/// What the quality controls set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quality {
    /// Side of the square caustics map, texels.
    pub map_size: u32,
    /// Samples per pixel along each axis of the final image.
    pub supersampling: u32,
    pub exposure: f64,
    /// Trace the final image with `caustics_core::render` rather than [`FinalImage`]: on a
    /// software adapter the CPU renderer is measured at about 2.5 times faster (it needs no
    /// texture fetches, and no SIMD lane waits on another).
    pub cpu_image: bool,
    /// Shade the water with normals filtered by each sample's footprint
    /// (`RenderOptions::filter_water`).
    pub filter_water: bool,
}

/// Where the time of a frame went.
#[derive(Clone, Debug, Default)]
pub struct FrameStats {
    pub water_ms: f64,
    pub image_ms: f64,
    /// GPU time per timed pass, where the adapter has timestamps.
    pub gpu: Vec<PassTime>,
}

/// What a frame's render left for the window: CPU images to upload, or the GPU frame's own
/// textures ([`SceneRenderer::gpu_image`]), shown as they are.
pub enum Rendered {
    Cpu(Vec<Image>),
    Gpu,
}

/// Renders the view's images; owns the device through its [`Runner`].
pub struct SceneRenderer {
    /// The GPU-resident frame: water, techniques and final images on the GPU, nothing read back
    /// (`caustics_gpu::renderer`). Used whenever the final image is on the GPU; the CPU twins
    /// and [`Runner`] serve the rest (the CPU final image, the reference, the buffer views).
    pub gpu_frame: Option<Renderer>,
    pub runner: Runner,
    final_image: Option<FinalImage>,
    /// Why the final image is traced on the CPU, when it is.
    pub final_note: Option<String>,
    timer: Option<GpuTimer>,
    /// The scene as loaded, with the camera, sun and map size of the latest frame.
    pub scene: Scene,
    /// The latest frame's surface, for the buffer views.
    pub surface: Option<Box<dyn Surface>>,
    /// Recent maps, oldest first.
    maps: Vec<(MapKey, Made)>,
}

impl SceneRenderer {
    pub fn new(runner: Runner, scene: Scene) -> Self {
        let ctx = runner.compute();
        let (final_image, final_note) = match ctx.map(FinalImage::new) {
            Some(Ok(f)) => (Some(f), None),
            Some(Err(e)) => (None, Some(format!("final image on the CPU: {e}"))),
            None if runner.gpu.is_some() => {
                (None, Some("final image on the CPU: --cpu".to_string()))
            }
            None => (None, Some("final image on the CPU: no GPU".to_string())),
        };
        // Two sides, four final-image passes each (the water's patches, slab bound and surface,
        // the image).
        let timer = ctx.filter(|c| c.timestamps).map(|c| GpuTimer::new(c, 8));
        let gpu_frame = ctx.map(Renderer::new).transpose().unwrap_or_else(|e| {
            eprintln!("no GPU frame, the viewer runs the techniques one by one: {e}");
            None
        });
        let mut runner = runner;
        runner.time_passes();
        SceneRenderer {
            gpu_frame,
            runner,
            final_image,
            final_note,
            timer,
            scene,
            surface: None,
            maps: Vec::new(),
        }
    }

    pub fn gpu(&self) -> Option<&GpuContext> {
        self.runner.gpu.as_ref()
    }

    /// Render every slot at `size` pixels each: run its technique if its inputs changed, then
    /// trace its final image. Returns one image per slot and the frame's timings. A technique
    /// that fails leaves its slot's error set and its image lit as if through flat water.
    pub fn render(
        &mut self,
        mut water: Option<&mut WaterState>,
        camera: &OrbitCamera,
        sun: DVec3,
        size: (u32, u32),
        slots: &mut [Slot],
        quality: Quality,
    ) -> Result<(Rendered, FrameStats)> {
        if !quality.cpu_image && self.gpu_frame.is_some() {
            return self.render_gpu(water, camera, sun, size, slots, quality);
        }
        if let Some(w) = water.as_deref_mut() {
            w.set_resident(false);
        }
        let mut stats = FrameStats::default();
        let started = Instant::now();
        let surface = match water.as_deref_mut() {
            Some(w) if self.scene.water.is_some() => Some(w.surface(self.runner.compute())?),
            _ => None,
        };
        stats.water_ms = ms(started);

        let options = self.frame_scene(camera, sun, size, quality);
        for slot in slots.iter_mut() {
            slot.map_changed = false;
            let water_input = match (surface.as_deref(), water.as_deref()) {
                (Some(surface), Some(water)) => Some((surface, water)),
                _ if self.scene.water.is_none() => None,
                _ => {
                    slot.clear(None);
                    continue;
                }
            };
            let eye = eye_space(slot.choice.base());
            let key = MapKey {
                label: slot.choice.label(),
                cells_per_texel: slot.choice.cells_per_texel,
                surface: water_input.map(|(_, w)| w.key()),
                sun: sun.to_array().map(f64::to_bits),
                map_size: quality.map_size,
                view: eye.then(|| format!("{:?}", self.scene.camera)),
            };
            if slot.key.as_ref() == Some(&key) {
                slot.technique_ms = None;
                continue;
            }
            slot.map_changed = true;
            if let Some(k) = self.maps.iter().position(|c| c.0 == key) {
                // Seen a moment ago (the other side, or before a switch): most recent last.
                let cached = self.maps.remove(k);
                slot.set(cached.1.clone());
                slot.technique_ms = None;
                slot.key = Some(key);
                self.maps.push(cached);
                continue;
            }
            let started = Instant::now();
            let outcome = slot.choice.spec().and_then(|spec| {
                self.run_technique(
                    &spec,
                    slot.choice.cells_per_texel,
                    water_input,
                    sun,
                    quality,
                )
            });
            slot.technique_ms = Some(ms(started));
            slot.key = Some(key.clone());
            match outcome {
                Ok(made) => {
                    // An eye-space image made for another view of the same input is stale (the
                    // camera rarely comes back to the same spot): replace it rather than push a
                    // floor map that would be reused out of the cache.
                    self.maps
                        .retain(|c| !(c.0.view.is_some() && c.0.label == key.label));
                    if self.maps.len() >= MAP_CACHE {
                        self.maps.remove(0);
                    }
                    self.maps.push((key, made.clone()));
                    slot.set(made);
                }
                Err(e) => {
                    let e = format!("{e:#}");
                    if slot.error.as_ref() != Some(&e) {
                        // Once per new error: the panel shows it, a scripted run's log too.
                        eprintln!("technique `{}`: {e}", slot.choice.label());
                    }
                    slot.clear(Some(e));
                }
            }
        }

        stats.gpu = self.runner.take_gpu_times()?;
        let started = Instant::now();
        let mut images = Vec::with_capacity(slots.len());
        for slot in slots.iter() {
            let caustics = slot.caustics.as_ref().map(SceneCaustics::caustics);
            let walls = slot.walls.as_ref().filter(|_| caustics.is_some());
            images.push(if quality.cpu_image {
                render(
                    &self.scene,
                    surface.as_deref(),
                    caustics,
                    walls,
                    &options,
                    &|_, _| {},
                )
            } else {
                self.final_image(surface.as_deref(), caustics, walls, &options)?
            });
        }
        if let (Some(timer), Some(ctx)) = (self.timer.as_mut(), self.runner.compute()) {
            stats
                .gpu
                .extend(timer.read(ctx).context("reading the GPU timestamps")?);
        }
        stats.image_ms = ms(started);
        self.surface = surface;
        Ok((Rendered::Cpu(images), stats))
    }

    /// The scene set to the frame's sun, map size and camera, and the final images' options. The
    /// techniques of a scene without water read the scene itself: its sun and map size; the camera
    /// is the one the final images are traced from, which eye-space techniques are made for.
    fn frame_scene(
        &mut self,
        camera: &OrbitCamera,
        sun: DVec3,
        size: (u32, u32),
        quality: Quality,
    ) -> RenderOptions {
        self.scene.light.direction = sun;
        self.scene.caustics.width = quality.map_size;
        self.scene.caustics.height = quality.map_size;
        self.scene.camera = camera.camera(size.0, size.1);
        RenderOptions {
            supersampling: quality.supersampling.max(1),
            exposure: quality.exposure,
            tone_map: self.scene.look.tone_map,
            filter_water: quality.filter_water,
        }
    }

    /// The frame on the GPU: the water source, each side's technique and final image recorded into
    /// one submission (`caustics_gpu::renderer::Renderer`). A side whose technique has no GPU
    /// implementation (the CPU reference) has its map made by the [`Runner`] when its inputs
    /// change, as on the CPU path, and uploaded for its final image.
    fn render_gpu(
        &mut self,
        mut water: Option<&mut WaterState>,
        camera: &OrbitCamera,
        sun: DVec3,
        size: (u32, u32),
        slots: &mut [Slot],
        quality: Quality,
    ) -> Result<(Rendered, FrameStats)> {
        let mut stats = FrameStats::default();
        let started = Instant::now();
        let options = self.frame_scene(camera, sun, size, quality);
        let ctx = self.runner.gpu.as_ref().expect("a GPU frame has a GPU");
        let frame = self.gpu_frame.as_mut().expect("checked by render");

        // The water: the scene's source at the viewer's clock, or the resident ripple simulation.
        let mut clock = WaterClock {
            time: 0.0,
            amplitude: 1.0,
            steps: 0,
        };
        let mut drops = Vec::new();
        if let Some(w) = water.as_deref_mut() {
            w.set_resident(true);
            let (steps, d) = w.take_pending();
            drops = d;
            clock = WaterClock {
                time: w.time,
                amplitude: w.amplitude,
                steps,
            };
            let spec = match w.mode {
                super::water::Mode::Scene => FrameWater::Scene,
                super::water::Mode::Ripple => {
                    let (params, generation) = w.ripple_spec();
                    FrameWater::Ripples {
                        params: params.clone(),
                        generation,
                    }
                }
            };
            frame
                .set_water(ctx, Some(w.water()), &spec)
                .context("the water on the GPU")?;
        } else {
            frame.set_water(ctx, None, &FrameWater::Scene)?;
        }
        for d in &drops {
            frame.drop_ripple(ctx, d);
        }
        stats.water_ms = ms(started);

        // The techniques: registered GPU ones record into the frame; the others (the reference)
        // run on the CPU when their input changes and hand the frame their map.
        let mut specs = Vec::with_capacity(slots.len());
        for slot in slots.iter_mut() {
            slot.map_changed = false;
            slot.technique_ms = None;
            let spec = slot.choice.spec()?;
            if caustics_gpu::registry::find(slot.choice.name()).is_some() {
                specs.push(Some((&spec).into()));
                slot.backend = "GPU";
                continue;
            }
            specs.push(None);
            let key = MapKey {
                label: slot.choice.label(),
                cells_per_texel: slot.choice.cells_per_texel,
                surface: water.as_deref().map(|w| w.key()),
                sun: sun.to_array().map(f64::to_bits),
                map_size: quality.map_size,
                view: None,
            };
            if slot.key.as_ref() == Some(&key) {
                continue;
            }
            let t0 = Instant::now();
            let outcome = (|| -> Result<Made> {
                let surface = water
                    .as_deref_mut()
                    .map(|w| self.cpu_surface(w))
                    .transpose()?;
                let input = match (surface.as_deref(), water.as_deref()) {
                    (Some(s), Some(w)) => Some((s, w)),
                    _ => None,
                };
                self.run_technique(&spec, slot.choice.cells_per_texel, input, sun, quality)
            })();
            slot.technique_ms = Some(ms(t0));
            slot.key = Some(key);
            slot.map_changed = true;
            match outcome {
                Ok(made) => slot.set(made),
                Err(e) => slot.clear(Some(format!("{e:#}"))),
            }
        }
        let ctx = self.runner.gpu.as_ref().expect("a GPU frame has a GPU");
        let frame = self.gpu_frame.as_mut().expect("checked by render");
        frame.set_techniques(ctx, &specs);
        for (k, slot) in slots.iter().enumerate() {
            if specs[k].is_none() && slot.map_changed {
                frame.set_caustics(ctx, k, slot.floor_map())?;
                frame.set_walls(ctx, k, slot.walls.as_ref())?;
            }
        }
        let t0 = Instant::now();
        frame
            .render(ctx, &self.scene, clock, &options)
            .context("the GPU frame")?;
        stats.image_ms = ms(t0);
        for (k, slot) in slots.iter_mut().enumerate() {
            if specs[k].is_some() {
                // The map window reads the GPU's map back only while it is open (`read_maps`).
                slot.clear(frame.error(k).map(str::to_string));
                slot.key = None;
                slot.map_changed = true;
            }
        }
        if let Some(t) = frame.timer.as_mut() {
            stats.gpu = t.latest(ctx).to_vec();
        }
        stats.gpu.extend(self.runner.take_gpu_times()?);
        self.surface = None;
        Ok((Rendered::Gpu, stats))
    }

    /// The counts so far: the device's total (the frame's shared work, the viewer's own and the
    /// timestamp reads included) and each of the first `sides` sides' own.
    pub fn traffic(&self, sides: usize) -> Traffic {
        let total = self.gpu().map(|c| c.traffic()).unwrap_or_default();
        let sides = (0..sides)
            .map(|k| {
                self.gpu_frame
                    .as_ref()
                    .and_then(|f| f.side_traffic(k))
                    .unwrap_or_default()
            })
            .collect();
        Traffic { total, sides }
    }

    /// The GPU technique on side `k` as the registry names it (its variant included).
    pub fn gpu_technique_name(&self, k: usize) -> Option<&str> {
        self.gpu_frame.as_ref()?.technique_name(k)
    }

    /// Side `k`'s final image on the GPU, after a [`Rendered::Gpu`] frame.
    pub fn gpu_image(&self, k: usize) -> Option<&wgpu::Texture> {
        self.gpu_frame.as_ref()?.image(k)
    }

    /// Read the GPU techniques' maps back into the slots, for the map window (while it is open: a
    /// readback per rendered frame, which the steady frame without it does not make). After a
    /// frame that `rendered` nothing, only a slot not read since its last render is read.
    pub fn read_maps(&mut self, slots: &mut [Slot], rendered: bool) -> Result<()> {
        let (Some(frame), Some(ctx)) = (&self.gpu_frame, self.runner.gpu.as_ref()) else {
            return Ok(());
        };
        for (k, slot) in slots.iter_mut().enumerate() {
            if !slot.needs_read(rendered) {
                continue;
            }
            let Some(output) = frame.caustics(k) else {
                continue;
            };
            let size = self.scene.water.as_ref().map_or(1.0, |w| w.size);
            let caustics = crate::techniques::read_output(ctx, output, size)?;
            slot.walls = match (frame.walls(k), &caustics, &self.scene.water) {
                (Some(out), SceneCaustics::Floor(m), Some(water)) => {
                    let mut maps = WallMaps::for_floor_map(m.width, m.height, size, water.depth);
                    out.read(ctx, &mut maps)?;
                    Some(maps)
                }
                _ => None,
            };
            slot.caustics = Some(caustics);
            slot.map_changed = true;
        }
        Ok(())
    }

    /// The CPU surface of this frame, for the CPU techniques and the buffer views: the scene's
    /// source at the clock, or, with the ripple simulation on the GPU, its heights read back.
    pub fn cpu_surface(&mut self, water: &mut WaterState) -> Result<Box<dyn Surface>> {
        if water.mode == super::water::Mode::Ripple
            && let (Some(frame), Some(ctx)) = (self.gpu_frame.as_mut(), self.runner.gpu.as_ref())
            && let Some(w) = frame.water_texture(ctx, &self.scene)
        {
            let texture = w.heights.texture();
            let data: Vec<f32> = ctx.read_texture(texture)?;
            let grid = caustics_core::grid::Grid {
                cols: texture.width() as usize,
                rows: texture.height() as usize,
                data,
            };
            let water = water.water();
            return Ok(Box::new(caustics_core::water::GridSurface {
                grid,
                size: water.size,
                edge: water.edge(),
            }));
        }
        water.surface(self.runner.compute())
    }

    /// Run one technique on this frame's input: a water job for the floor-map techniques of a
    /// water scene (objects and all, for `volumes`, whose floor map holds their shadows), the
    /// animated surface as a height grid for `cascaded`, the scene itself for glass generators.
    fn run_technique(
        &mut self,
        spec: &Spec,
        cells_per_texel: u32,
        water_input: Option<(&dyn Surface, &WaterState)>,
        sun: DVec3,
        quality: Quality,
    ) -> Result<Made> {
        let cells = cells_per_texel.max(1);
        let Some((surface, water)) = water_input else {
            let o = self
                .runner
                .run(spec, &Job::new(&self.scene, None, cells), &|_, _| {})?;
            return Ok((o.caustics, o.backend, o.walls));
        };
        // The scene as the technique sees it: the water as animated (the sun, map size and
        // camera are the frame's already), its objects as receivers.
        let mut scene = self.scene.clone();
        scene.water = Some(water.technique_water().clone());
        scene.light.direction = sun;
        scene.caustics.width = quality.map_size;
        scene.caustics.height = quality.map_size;
        let o = self
            .runner
            .run(spec, &Job::new(&scene, Some(surface), cells), &|_, _| {})?;
        Ok((o.caustics, o.backend, o.walls))
    }

    fn final_image(
        &mut self,
        surface: Option<&dyn Surface>,
        caustics: Option<Caustics>,
        walls: Option<&WallMaps>,
        options: &RenderOptions,
    ) -> Result<Image> {
        if let (Some(f), Some(ctx)) = (&self.final_image, self.runner.compute()) {
            match f.render(
                ctx,
                &self.scene,
                surface,
                caustics,
                walls,
                options,
                self.timer.as_mut(),
            ) {
                Ok(image) => return Ok(image),
                Err(e) => {
                    // E.g. an image beyond the device's texture limits: say why once, carry on.
                    self.final_note = Some(format!("final image on the CPU: {e}"));
                    self.final_image = None;
                }
            }
        }
        Ok(render(
            &self.scene,
            surface,
            caustics,
            walls,
            options,
            &|_, _| {},
        ))
    }
}

pub fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn choices_round_trip_through_specs() {
        let c = TechniqueChoice::parse("yuksel:n=15", 2).unwrap();
        assert_eq!(c.name(), "yuksel");
        assert_eq!(c.params.get("n").and_then(|v| v.as_integer()), Some(15));
        // The defaults fill the rest: M is not given, so the region's height comes from the water.
        assert_eq!(c.params.get("m"), None);
        assert_eq!(
            c.params.get("preset").and_then(|v| v.as_str()),
            Some("water")
        );
        let spec = c.spec().unwrap();
        assert_eq!(spec.name(), "yuksel");
        let g = TechniqueChoice::parse("yuksel-targets", 2).unwrap();
        assert_eq!(g.base(), "yuksel");
        assert_eq!(g.spec().unwrap().name(), "yuksel-targets");
        assert_eq!(
            TechniqueChoice::parse("reference", 2).unwrap().label(),
            "reference"
        );
        assert!(TechniqueChoice::parse("no-such", 2).is_err());
    }

    /// Every technique with parameters shows them in the panel, and its defaults run as given.
    #[test]
    fn procedural_starts_with_its_parameters() {
        let c = TechniqueChoice::parse("procedural:variant=texture", 2).unwrap();
        assert_eq!(
            c.params.get("variant").and_then(|v| v.as_str()),
            Some("texture")
        );
        assert_eq!(
            c.params.get("mesh_resolution").and_then(|v| v.as_integer()),
            Some(128)
        );
        let spec = c.spec().unwrap();
        let table = spec
            .params
            .get("procedural")
            .and_then(|v| v.as_table())
            .unwrap();
        // The technique's own reading of the table accepts it.
        (spec.entry.validate)(&spec.params).unwrap();
        assert_eq!(
            table.get("variant").and_then(|v| v.as_str()),
            Some("texture")
        );
    }

    #[test]
    fn eye_space_techniques_are_told_apart() {
        assert!(eye_space("cascaded") && !eye_space("yuksel") && !eye_space("no-such"));
    }

    #[test]
    fn every_technique_starts_with_its_whole_parameter_table() {
        for (name, key) in [
            ("volumes", "planes"),
            ("cascaded", "resolution"),
            ("cascaded", "dispersion"),
            ("caustic-triangles", "photon_image"),
        ] {
            let c = TechniqueChoice::parse(name, 1).unwrap();
            assert!(
                c.params.contains_key(key),
                "{name}: no `{key}` in {:?}",
                c.params
            );
            // What the panel shows runs: the table goes back through the CLI's spelling.
            let spec = c.spec().unwrap();
            assert_eq!(
                spec.params.get(name),
                Some(&toml::Value::Table(c.params.clone()))
            );
        }
        // Every registered entry's panel table is one its technique reads.
        for d in techniques::REGISTRY {
            let spec = TechniqueChoice::parse(d.name, 1).unwrap().spec().unwrap();
            (d.validate)(&spec.params).unwrap_or_else(|e| panic!("{}: {e}", d.name));
        }
    }
}
