//! One renderer for the whole frame, water to pixels, on the GPU: the water source writes its height
//! textures ([`GpuWater`]), each side's technique reads them and writes its caustics texture
//! ([`Technique`]), and each side's final image samples that texture and the water directly
//! ([`FinalImageFrame`]). Everything is built when the scene, a size or a technique changes and
//! lives across frames; a steady frame is uniform writes and one submission, nothing created and
//! nothing read back. The viewer shows [`Renderer::image`] through egui without a CPU copy, and
//! `caustics render` reads it back once, as its output.
//!
//! Two sides, because the viewer puts a technique beside another (or beside nothing: a side without
//! a technique is lit as if through flat water).

use caustics_core::render::RenderOptions;
use caustics_core::scene::{Scene, Water};
use caustics_core::water::ripple::{Drop, RippleParams};

use crate::final_image::{
    FinalImage, FinalImageFrame, ImageInputs, upload_walls, water_grid_resolution,
};
use crate::registry;
use crate::technique::{Output, Technique, WallsOutput, WaterTextures};
use crate::water::field::GpuWater;
use crate::{GpuContext, GpuError, GpuTimer, TrafficCounts};

/// A technique as the application names it: a registered name and its parameter tables, keyed by
/// technique as in a scene file's `[caustics]`.
#[derive(Clone, Debug, PartialEq)]
pub struct TechniqueSpec {
    /// The registered name, with its variant (`yuksel-targets`, `procedural-texture`).
    pub name: String,
    /// Parameter tables keyed by technique (`{ yuksel = { n = 15 } }`); a missing one means the
    /// defaults.
    pub params: toml::Table,
}

impl From<&caustics_core::techniques::registry::Spec> for TechniqueSpec {
    fn from(spec: &caustics_core::techniques::registry::Spec) -> Self {
        TechniqueSpec {
            name: spec.name().to_string(),
            params: spec.params.clone(),
        }
    }
}

/// Where the frame's water comes from: the scene's own source, or the interactive ripple
/// simulation in its place.
#[derive(Clone, Debug, PartialEq)]
pub enum FrameWater {
    /// The scene's own source (waves, paper 2's wave function, the FFT ocean, a ripple simulation, a
    /// height field).
    Scene,
    /// The interactive ripple simulation with these parameters; `generation` tells a restart.
    Ripples {
        /// The simulation's grid, wave speed, damping, time step and initial drops.
        params: RippleParams,
        /// Bumped by the application to restart the simulation with the same parameters: a
        /// different value makes [`Renderer::set_water`] build the water again.
        generation: u64,
    },
}

/// This frame's clock and the viewer's height factor.
#[derive(Clone, Copy, Debug)]
pub struct WaterClock {
    /// Seconds, for the scene's source.
    pub time: f64,
    /// Multiplies the heights (0: flat water).
    pub amplitude: f64,
    /// Ripple simulation steps to take this frame.
    pub steps: u32,
}

struct Side {
    spec: TechniqueSpec,
    technique: Result<Box<dyn Technique>, String>,
    /// The water texture and map size the technique was configured with.
    configured: Option<(wgpu::TextureView, (u32, u32))>,
    /// Why configuring (or updating) failed, and for what: tried again when any of it changes.
    failed: Option<(String, FailKey)>,
    /// The map of a technique with no GPU implementation (the CPU reference), uploaded by the
    /// application when it changes.
    external: Option<wgpu::Texture>,
    /// The walls' maps of that technique (the reference's, when the scene's walls are on) and
    /// each wall's column count, uploaded by the application when they change.
    external_walls: Option<(wgpu::Texture, [u32; 4])>,
    image: Option<FinalImageFrame>,
    /// What the image frame was built from: caustics texture, water texture, image size.
    image_key: Option<ImageKey>,
    /// Why the side's final image could not be made (a size beyond the device), for that key.
    image_failed: Option<(String, ImageKey)>,
    /// What this side's technique, its water grid, its uploaded maps and its image frame have
    /// created and uploaded so far ([`Renderer::side_traffic`]).
    traffic: TrafficCounts,
}

/// What a technique's configuration depends on beyond its parameters: the water texture, the map
/// size, and the camera's image size and the sun (an eye-space image's size, a gather region).
#[derive(Clone, PartialEq)]
struct FailKey {
    /// The water texture, `None` when the side's grid could not be made.
    water: Option<wgpu::TextureView>,
    grid: (u32, u32),
    map: (u32, u32),
    view: (u32, u32),
    sun: [u64; 3],
}

#[derive(Clone, PartialEq)]
struct ImageKey {
    caustics: Option<wgpu::Texture>,
    /// The light-space deposit and the receivers' heights, where the objects take their light
    /// from them.
    light: Option<(wgpu::Texture, wgpu::Texture)>,
    walls: Option<wgpu::Texture>,
    water: Option<wgpu::TextureView>,
    size: (u32, u32),
}

/// Configure (or update) one side's technique for this frame. Whatever fails here (its water grid
/// or its textures beyond the device, its parameters) fails this side alone, until what it
/// depends on changes.
fn configure_side(
    ctx: &GpuContext,
    scene: &Scene,
    side: &mut Side,
    water: Option<&mut (GpuWater, FrameWater)>,
    no_water: &WaterTextures,
    grids: &mut Vec<(u32, u32)>,
) {
    let Ok(technique) = &mut side.technique else {
        side.configured = None;
        return;
    };
    let map = (scene.caustics.width, scene.caustics.height);
    let grid = technique.water_resolution(scene);
    let water = match water {
        Some((w, _)) => {
            grids.push(grid);
            w.output(ctx, grid.0, grid.1)
        }
        None => Ok(no_water.clone()),
    };
    let key = |water: Option<&WaterTextures>| FailKey {
        water: water.map(|w| w.heights.clone()),
        grid,
        map,
        view: (scene.camera.width, scene.camera.height),
        sun: scene.light.direction.to_array().map(f64::to_bits),
    };
    let water = match water {
        Ok(w) => w,
        Err(e) => {
            side.configured = None;
            side.failed = Some((e.to_string(), key(None)));
            return;
        }
    };
    let fail_key = key(Some(&water));
    if side.failed.as_ref().is_some_and(|(_, k)| *k == fail_key) {
        return;
    }
    let fresh = side
        .configured
        .as_ref()
        .is_some_and(|(view, size)| *view == water.heights && *size == map);
    let result = if fresh {
        technique.update(ctx, scene)
    } else {
        technique
            .configure(ctx, scene, &water)
            .and_then(|()| technique.update(ctx, scene))
    };
    match result {
        Ok(()) => {
            side.configured = Some((water.heights.clone(), map));
            side.failed = None;
        }
        Err(e) => {
            side.configured = None;
            side.failed = Some((e.to_string(), fail_key));
        }
    }
}

/// The GPU frame: water, up to two techniques, their final images.
pub struct Renderer {
    final_image: FinalImage,
    water: Option<(GpuWater, FrameWater)>,
    /// Bound as the water of a scene without any (glass generators need none).
    no_water: WaterTextures,
    sides: Vec<Side>,
    /// Techniques switched away from, most recent last.
    parked: Vec<Side>,
    /// Times every pass of a frame (water, techniques, final images), read a frame or two late;
    /// `None` where the device has no timestamp queries.
    pub timer: Option<GpuTimer>,
}

/// Techniques kept configured after a switch: the viewer's picker cycles through about ten.
pub const PARKED: usize = 12;

/// Passes a frame can time: the water's (ocean spectrum and FFT stages, ripple steps, outputs) and
/// two techniques' (procedural's texture variant has the most) and two images.
const TIMED_PASSES: u32 = 96;

impl Renderer {
    /// The final image's pipelines and an empty frame: no water, no side until
    /// [`set_water`](Self::set_water) and [`set_techniques`](Self::set_techniques).
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let empty = ctx.texture_2d(
            "no water",
            (1, 1, 1),
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        ctx.write_texture(
            empty.as_image_copy(),
            bytemuck::bytes_of(&0f32),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4),
                rows_per_image: Some(1),
            },
            empty.size(),
        );
        Ok(Renderer {
            final_image: FinalImage::new(ctx)?,
            water: None,
            no_water: WaterTextures::of(&empty),
            sides: Vec::new(),
            parked: Vec::new(),
            timer: ctx.timestamps.then(|| GpuTimer::new(ctx, TIMED_PASSES)),
        })
    }

    /// Choose the sides' techniques. A technique is created (its pipelines built) only the first
    /// time its name and parameters are asked for: one switched away from is kept, configured, for
    /// a while ([`PARKED`] of them), so switching back costs nothing. A technique that cannot be
    /// created leaves its side's error set.
    pub fn set_techniques(&mut self, ctx: &GpuContext, specs: &[Option<TechniqueSpec>]) {
        while self.sides.len() > specs.len() {
            let side = self.sides.pop().expect("longer");
            self.park(side);
        }
        for (k, spec) in specs.iter().enumerate() {
            let spec = spec.clone().unwrap_or(TechniqueSpec {
                name: String::new(),
                params: toml::Table::new(),
            });
            if self.sides.get(k).is_some_and(|s| s.spec == spec) {
                continue;
            }
            // The same technique with other parameters: taken in place where it can, so that
            // its pipelines stay (configured again at the next frame).
            if let Some(side) = self.sides.get_mut(k)
                && side.spec.name == spec.name
                && let Ok(t) = &mut side.technique
                && let Ok(true) = t.set_params(&spec.params)
            {
                side.spec = spec;
                side.configured = None;
                side.failed = None;
                continue;
            }
            let side = match self.parked.iter().position(|s| s.spec == spec) {
                Some(p) => self.parked.remove(p),
                None => Side {
                    technique: if spec.name.is_empty() {
                        Err(String::new())
                    } else {
                        registry::create(ctx, &spec.name, &spec.params).map_err(|e| e.to_string())
                    },
                    spec,
                    configured: None,
                    failed: None,
                    external: None,
                    external_walls: None,
                    image: None,
                    image_key: None,
                    image_failed: None,
                    traffic: TrafficCounts::default(),
                },
            };
            if k < self.sides.len() {
                let old = std::mem::replace(&mut self.sides[k], side);
                self.park(old);
            } else {
                self.sides.push(side);
            }
        }
    }

    fn park(&mut self, side: Side) {
        if side.technique.is_err() {
            return;
        }
        if self.parked.len() >= PARKED {
            self.parked.remove(0);
        }
        self.parked.push(side);
    }

    /// Make the water source (again) when it changes: the scene's own, or the ripple simulation.
    pub fn set_water(
        &mut self,
        ctx: &GpuContext,
        water: Option<&Water>,
        spec: &FrameWater,
    ) -> Result<(), GpuError> {
        let Some(water) = water else {
            self.water = None;
            return Ok(());
        };
        if self.water.as_ref().is_some_and(|(_, s)| s == spec) {
            return Ok(());
        }
        let source = match spec {
            FrameWater::Scene => GpuWater::new(ctx, water)?,
            FrameWater::Ripples { params, .. } => GpuWater::ripples(ctx, water, params)?,
        };
        self.water = Some((source, spec.clone()));
        // New textures: every technique configures again.
        for side in self.sides.iter_mut().chain(&mut self.parked) {
            side.configured = None;
        }
        Ok(())
    }

    /// Drop a ripple into the simulation (the ripple source only).
    pub fn drop_ripple(&mut self, ctx: &GpuContext, d: &Drop) {
        if let Some((w, _)) = &mut self.water {
            w.drop_ripple(ctx, d);
        }
    }

    /// Record and submit one frame of `scene` (its camera, sun, map size and water optics) at
    /// `clock`: the water's passes, each side's technique, each side's final image.
    pub fn render(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        clock: WaterClock,
        options: &RenderOptions,
    ) -> Result<(), GpuError> {
        if let Some((w, _)) = &mut self.water {
            w.update(ctx, clock.time, clock.amplitude);
            w.step_ripples(clock.steps);
        }
        let image_grid = water_grid_resolution(scene) as u32;
        let mut grids = vec![(image_grid, image_grid)];
        let image_water = match &mut self.water {
            Some((w, _)) => Some(w.output(ctx, image_grid, image_grid)?),
            None => None,
        };
        for side in &mut self.sides {
            let before = ctx.traffic();
            configure_side(
                ctx,
                scene,
                side,
                self.water.as_mut(),
                &self.no_water,
                &mut grids,
            );
            side.traffic += ctx.traffic().since(&before);
        }
        // Heights no side reads any more (an old map size, a technique switched away from) are
        // neither written nor kept.
        if let Some((w, _)) = &mut self.water {
            w.retain_outputs(&grids);
        }
        for side in &mut self.sides {
            let caustics = match &side.technique {
                Ok(t) if side.configured.is_some() => t.output(),
                Ok(_) => None,
                Err(_) => side.external.as_ref().map(Output::Floor),
            };
            let walls = match &side.technique {
                Ok(t) if side.configured.is_some() => t.walls(),
                Ok(_) => None,
                Err(_) => side
                    .external_walls
                    .as_ref()
                    .map(|(texture, cols)| WallsOutput {
                        texture,
                        cols: *cols,
                    }),
            };
            let light = match &side.technique {
                Ok(t) if side.configured.is_some() => t.receivers().and_then(|r| r.light_space()),
                _ => None,
            };
            let key = ImageKey {
                caustics: caustics.map(|o| o.texture().clone()),
                light: light.map(|l| (l.deposit.clone(), l.heights.clone())),
                walls: walls.map(|w| w.texture.clone()),
                water: image_water.as_ref().map(|w| w.heights.clone()),
                size: (scene.camera.width, scene.camera.height),
            };
            let before = ctx.traffic();
            if side.image_key.as_ref() == Some(&key)
                && let Some(image) = &mut side.image
            {
                image.update(ctx, scene, options);
            } else if side.image_failed.as_ref().is_none_or(|(_, k)| *k != key) {
                // A size beyond the device fails this side alone; a lost device ends the frame.
                let inputs = ImageInputs {
                    water: image_water.as_ref(),
                    caustics,
                    walls,
                    light,
                    map_size: None,
                };
                match self.final_image.frame(ctx, scene, inputs, options) {
                    Ok(image) => {
                        side.image = Some(image);
                        side.image_key = Some(key);
                        side.image_failed = None;
                    }
                    Err(e @ GpuError::DeviceLost(_)) => return Err(e),
                    Err(e) => {
                        side.image = None;
                        side.image_key = None;
                        side.image_failed = Some((e.to_string(), key));
                    }
                }
            }
            side.traffic += ctx.traffic().since(&before);
        }

        let mut encoder = ctx.encoder("caustics frame");
        let mut timer = self.timer.as_mut();
        if let Some((w, _)) = &mut self.water {
            w.encode(&mut encoder, timer.as_deref_mut());
        }
        for side in &self.sides {
            if let (Ok(t), Some(_)) = (&side.technique, &side.configured) {
                t.encode(&mut encoder, timer.as_deref_mut());
            }
        }
        for side in &self.sides {
            if let Some(image) = &side.image {
                image.encode(&mut encoder, timer.as_deref_mut());
            }
        }
        if let Some(t) = timer {
            t.resolve_frame(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        if let Some(t) = self.timer.as_mut() {
            t.frame_submitted();
        }
        ctx.check()
    }

    /// The floor map of side `k` when its technique runs elsewhere (the CPU reference): uploaded
    /// now, into a texture kept while the map's size holds. `None` lights the side as flat water.
    pub fn set_caustics(
        &mut self,
        ctx: &GpuContext,
        k: usize,
        map: Option<&caustics_core::map::CausticsMap>,
    ) -> Result<(), GpuError> {
        let Some(side) = self.sides.get_mut(k) else {
            return Ok(());
        };
        let Some(map) = map else {
            side.external = None;
            return Ok(());
        };
        let before = ctx.traffic();
        let (w, h) = (map.width as u32, map.height as u32);
        if side
            .external
            .as_ref()
            .is_none_or(|t| (t.width(), t.height()) != (w, h))
        {
            ctx.check_texture_size("caustics map", w, h)?;
            side.external = Some(ctx.texture_2d(
                "uploaded caustics map",
                (w, h, 1),
                wgpu::TextureFormat::Rgba32Float,
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            ));
        }
        let texture = side.external.as_ref().expect("just made");
        crate::final_image::write_map(ctx, texture, map);
        side.traffic += ctx.traffic().since(&before);
        Ok(())
    }

    /// The walls' maps of side `k` when its technique runs elsewhere (the CPU reference on a scene
    /// with walls): uploaded now, once per new set of maps (a new texture, so the side's image
    /// frame binds it at the next render). `None` leaves the walls to the ambient light.
    pub fn set_walls(
        &mut self,
        ctx: &GpuContext,
        k: usize,
        walls: Option<&caustics_core::walls::WallMaps>,
    ) -> Result<(), GpuError> {
        let Some(side) = self.sides.get_mut(k) else {
            return Ok(());
        };
        let before = ctx.traffic();
        side.external_walls = walls.map(|w| upload_walls(ctx, w)).transpose()?;
        side.traffic += ctx.traffic().since(&before);
        Ok(())
    }

    /// Side `k`'s final image (`Rgba8Unorm`, sRGB-encoded values), once rendered.
    pub fn image(&self, k: usize) -> Option<&wgpu::Texture> {
        self.sides.get(k)?.image.as_ref().map(|i| i.output())
    }

    /// Side `k`'s caustics texture, once its technique ran.
    pub fn caustics(&self, k: usize) -> Option<Output<'_>> {
        let side = self.sides.get(k)?;
        side.configured.as_ref()?;
        side.technique.as_ref().ok()?.output()
    }

    /// Side `k`'s GPU technique's maps of the pool's walls, when it lights them.
    pub fn walls(&self, k: usize) -> Option<WallsOutput<'_>> {
        let side = self.sides.get(k)?;
        side.configured.as_ref()?;
        side.technique.as_ref().ok()?.walls()
    }

    /// Why side `k` has no caustics or no image: a technique that could not be made or
    /// configured (its water grid or a texture beyond the device included), or an image the
    /// device cannot hold. The other side renders on.
    pub fn error(&self, k: usize) -> Option<&str> {
        let side = self.sides.get(k)?;
        match (&side.technique, &side.failed, &side.image_failed) {
            (Err(e), _, _) if !e.is_empty() => Some(e),
            (Ok(_), Some((e, _)), _) => Some(e),
            (_, _, Some((e, _))) => Some(e),
            _ => None,
        }
    }

    /// What side `k` has created and uploaded since its technique was made: its technique's
    /// configuration and uniform writes, its water grid, its uploaded maps, its image frame. The
    /// frame's shared work (the water source, the images' water) is in the context's total only.
    pub fn side_traffic(&self, k: usize) -> Option<TrafficCounts> {
        self.sides.get(k).map(|s| s.traffic)
    }

    /// The technique's registered name on side `k`.
    pub fn technique_name(&self, k: usize) -> Option<&str> {
        self.sides.get(k)?.technique.as_ref().ok().map(|t| t.name())
    }

    /// The heights the final images read, for the buffer views (read them back only on demand).
    pub fn water_texture(&mut self, ctx: &GpuContext, scene: &Scene) -> Option<WaterTextures> {
        let n = water_grid_resolution(scene) as u32;
        self.water.as_mut()?.0.output(ctx, n, n).ok()
    }

    /// GPU memory of the techniques' frames, bytes.
    pub fn technique_bytes(&self) -> u64 {
        self.sides
            .iter()
            .filter_map(|s| s.technique.as_ref().ok())
            .map(|t| t.bytes())
            .sum()
    }
}
