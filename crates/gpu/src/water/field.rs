//! The water on the GPU: every water source of a scene written as `R32Float` height textures each
//! frame, with no CPU sampling, no readback and nothing created after the first frame. The
//! techniques read these textures ([`WaterTextures`]); the CPU twin of each is
//! `caustics_core::water::sample_grid(water.surface_at(t), cols, rows, size)`.
//!
//! A frame is the source's own passes, then one output pass per requested size:
//!
//! - sine waves and paper 2's wave function are analytic, so the output pass evaluates them exactly
//!   at each texel centre (`water_field_waves`, `water_field_procedural`); flat water is the sum of
//!   no waves;
//! - the FFT ocean ([`GpuOcean`], Tessendorf §4.3), the ripple simulation ([`GpuRipples`]) and a
//!   height field file are grids, which the output pass reads through the bicubic interpolant their
//!   CPU twin (`GridSurface`) uses, with its edge rule (`water_field_grid`).
//!
//! The output is scaled by a height factor (the viewer's amplitude slider), which is how one
//! slider reaches every source alike.
//!
//! **Time.** The CPU reduces every phase that grows with time modulo 2π in `f64` before it
//! travels to the GPU as `f32` (each wave's `φ − ω t`, paper 2's `s t`; the ocean's time modulo its
//! repeat period where it has one), so a long-running clock loses no precision where it need not.
//! The scene's ripple simulation follows the clock as `Water::surface_at` does: its initial drops,
//! its settling steps, then `round(t / Δt)` further steps; a clock that runs backwards starts it
//! again.

use std::f64::consts::TAU;

use caustics_core::scene::{Water, WaterSource};
use caustics_core::water::procedural::ProceduralParams;
use caustics_core::water::ripple::{Drop, RippleParams};
use caustics_core::water::waves::{Wave, Waves};

use super::ocean::GpuOcean;
use super::ripple::GpuRipples;
use super::{GpuProceduralWave, GpuSineWave};
use crate::pass::{Bind, Binding, STORAGE_OUT, begin_compute, bind_group, compute_pipeline};
use crate::shaders::{PassSource, passes};
use crate::{GpuContext, GpuError, GpuTimer, WaterTextures};
use wgpu::BufferUsages as B;

passes! {
    WAVES = "water_field_waves", "water/water_field_waves.wgsl";
    PROCEDURAL = "water_field_procedural", "water/water_field_procedural.wgsl";
    GRID = "water_field_grid", "water/water_field_grid.wgsl";
    RIPPLE_CLEAR = "ripple_clear", "water/ripple_clear.wgsl";
}

/// Mirrors `FieldParams` in `water/water_field.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FieldParams {
    /// Side of the square the output covers.
    pub size: f32,
    /// Side of the square a grid source covers.
    pub grid_size: f32,
    /// Height factor, multiplying every height (the viewer's amplitude slider; 0: flat water).
    pub amplitude: f32,
    /// Sine waves in use, read by the waves pass only.
    pub wave_count: u32,
    /// 1 for `Edge::Wrap`, 0 for `Edge::Clamp`.
    pub wrap: u32,
    /// Pads the struct to 32 bytes, a multiple of 16 for the uniform layout; zero.
    pub _pad: [u32; 3],
}

/// The water's source as the GPU holds it.
enum Source {
    /// Sine waves; flat water is the sum of none. `terms` holds at least one (unused) entry, as a
    /// storage binding cannot be empty.
    Waves {
        waves: Vec<Wave>,
        /// The square the wave vectors snap to, as `Waves::new` takes it.
        size: f64,
        terms: wgpu::Buffer,
    },
    Procedural {
        params: ProceduralParams,
        wave: wgpu::Buffer,
    },
    Ocean {
        ocean: Box<GpuOcean>,
        repeat_period: Option<f64>,
    },
    Ripples(Box<RippleSource>),
    HeightField {
        texture: wgpu::Texture,
    },
}

/// The ripple simulation and what drives it.
struct RippleSource {
    sim: GpuRipples,
    params: RippleParams,
    /// The scene's source, stepped by the clock given to [`GpuWater::update`]; otherwise the
    /// viewer's simulation, stepped by [`GpuWater::step_ripples`] alone.
    clocked: bool,
    /// Steps past the settling steps that the clock has asked for so far.
    clock_steps: u64,
    /// Steps the next encode records.
    queued_steps: u64,
    clear_pipeline: wgpu::ComputePipeline,
    clear_group: wgpu::BindGroup,
}

/// One output texture and its output pass's bind groups: one, or for the ripples one per state
/// texture (the current one alternates).
struct FieldOutput {
    cols: u32,
    rows: u32,
    /// Handed out on every request: one view, so that consumers can tell the texture is the same.
    textures: WaterTextures,
    groups: Vec<wgpu::BindGroup>,
}

/// A water source on the GPU and the height textures it writes every frame.
///
/// Per frame: [`update`](Self::update) (uniform writes), then [`encode`](Self::encode) into the
/// frame's encoder before the techniques that read [`output`](Self::output).
pub struct GpuWater {
    source: Source,
    field: FieldParams,
    field_buffer: wgpu::Buffer,
    pipeline: wgpu::ComputePipeline,
    outputs: Vec<FieldOutput>,
}

impl GpuWater {
    /// The scene's own source. Builds everything once: the waves' and paper 2's parameters into
    /// buffers, the ocean's spectrum and FFT passes, the ripple simulation with the scene's
    /// parameters, its initial drops and settling steps run at once, a height field
    /// file uploaded once. The source starts at time 0 and amplitude 1.
    pub fn new(ctx: &GpuContext, water: &Water) -> Result<Self, GpuError> {
        let wrap = water.wrap as u32;
        let mut field = FieldParams {
            size: water.size as f32,
            grid_size: water.size as f32,
            amplitude: 1.0,
            wrap,
            ..Default::default()
        };
        let (source, pass) = match &water.source {
            WaterSource::Flat => (waves_source(ctx, &[], water.size)?, &WAVES),
            WaterSource::Waves(w) => (waves_source(ctx, w, water.size)?, &WAVES),
            WaterSource::Procedural(p) => {
                let wave = ctx.uniform_buffer::<GpuProceduralWave>("water field procedural wave");
                let params = p.clone();
                (Source::Procedural { params, wave }, &PROCEDURAL)
            }
            WaterSource::Ocean(o) => {
                // The ocean tiles its own square and is periodic whatever the scene says, as
                // `Ocean::surface` is.
                field.grid_size = o.size() as f32;
                field.wrap = 1;
                let ocean = Box::new(GpuOcean::new(ctx, o)?);
                let repeat_period = o.params().repeat_period;
                (
                    Source::Ocean {
                        ocean,
                        repeat_period,
                    },
                    &GRID,
                )
            }
            WaterSource::Ripple(p) => (ripple_source(ctx, water, p, true)?, &GRID),
            WaterSource::HeightField(g) => {
                let texture = ctx.upload_grid("water height field", g)?;
                (Source::HeightField { texture }, &GRID)
            }
        };
        Self::build(ctx, source, field, pass)
    }

    /// The interactive ripple simulation as the source (the viewer's ripple mode), whatever the
    /// scene's source, over the scene's square with its edge rule. The parameters' initial drops
    /// and settling steps run at once; after that it moves only
    /// by [`drop_ripple`](Self::drop_ripple) and [`step_ripples`](Self::step_ripples), and the time
    /// given to [`update`](Self::update) is ignored.
    pub fn ripples(
        ctx: &GpuContext,
        water: &Water,
        params: &RippleParams,
    ) -> Result<Self, GpuError> {
        let field = FieldParams {
            size: water.size as f32,
            grid_size: water.size as f32,
            amplitude: 1.0,
            wrap: water.wrap as u32,
            ..Default::default()
        };
        let source = ripple_source(ctx, water, params, false)?;
        Self::build(ctx, source, field, &GRID)
    }

    fn build(
        ctx: &GpuContext,
        source: Source,
        field: FieldParams,
        pass: &PassSource,
    ) -> Result<Self, GpuError> {
        let field_buffer = ctx.uniform_buffer::<FieldParams>("water field params");
        let pipeline = compute_pipeline(ctx, pass);
        let mut water = GpuWater {
            source,
            field,
            field_buffer,
            pipeline,
            outputs: Vec::new(),
        };
        water.update(ctx, 0.0, 1.0);
        ctx.check()?;
        Ok(water)
    }

    /// An output texture of `cols × rows` heights (`R32Float`, `TEXTURE_BINDING |
    /// STORAGE_BINDING | COPY_SRC`), texel `(j, i)` at `((j + ½) size / cols, (i + ½) size /
    /// rows)`. Created on the first request of that size and kept; every [`encode`](Self::encode)
    /// writes every output.
    pub fn output(
        &mut self,
        ctx: &GpuContext,
        cols: u32,
        rows: u32,
    ) -> Result<WaterTextures, GpuError> {
        if let Some(o) = self
            .outputs
            .iter()
            .find(|o| (o.cols, o.rows) == (cols, rows))
        {
            return Ok(o.textures.clone());
        }
        ctx.check_texture_size("water height texture", cols, rows)?;
        let texture = ctx.texture_2d(
            "water heights",
            (cols, rows, 1),
            wgpu::TextureFormat::R32Float,
            STORAGE_OUT,
        );
        let view = texture.create_view(&Default::default());
        let layout = self.pipeline.get_bind_group_layout(0);
        let group = |input: &dyn Binding| {
            bind_group(
                ctx,
                "water field",
                &layout,
                &[&self.field_buffer, input, &view],
            )
        };
        let texture_view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let groups = match &self.source {
            Source::Waves { terms, .. } => vec![group(terms)],
            Source::Procedural { wave, .. } => vec![group(wave)],
            Source::Ocean { ocean, .. } => {
                let v = texture_view(ocean.height_slopes_texture());
                vec![group(&v)]
            }
            Source::Ripples(r) => r
                .sim
                .textures()
                .iter()
                .map(|t| group(&texture_view(t)))
                .collect(),
            Source::HeightField { texture } => {
                let v = texture_view(texture);
                vec![group(&v)]
            }
        };
        ctx.check()?;
        let textures = WaterTextures::of(&texture);
        self.outputs.push(FieldOutput {
            cols,
            rows,
            textures: textures.clone(),
            groups,
        });
        Ok(textures)
    }

    /// Drop the outputs of sizes not in `keep`: they are no longer written, and their textures
    /// live only as long as someone holds their view.
    pub fn retain_outputs(&mut self, keep: &[(u32, u32)]) {
        self.outputs.retain(|o| keep.contains(&(o.cols, o.rows)));
    }

    /// Per frame: the source's time in seconds and a height factor (the viewer's amplitude
    /// slider; 0 = flat). Buffer writes only: 32 bytes, plus 16 per sine wave, 32 for paper 2's
    /// wave, 16 for the ocean, 48 per waiting ripple drop. The scene's ripple simulation queues
    /// the steps that bring it to `time`; if `time` went back, it starts again (its textures
    /// cleared, its initial drops and settling steps run at once, in submissions of their own).
    pub fn update(&mut self, ctx: &GpuContext, time: f64, amplitude: f64) {
        self.field.amplitude = amplitude as f32;
        match &mut self.source {
            Source::Waves { waves, size, terms } => {
                self.field.wave_count = waves.len() as u32;
                if !waves.is_empty() {
                    let now: Vec<GpuSineWave> = Waves::new(waves, *size, time)
                        .terms()
                        .iter()
                        .map(|t| GpuSineWave {
                            k: [t.k.x as f32, t.k.y as f32],
                            amplitude: t.amplitude as f32,
                            phase: t.phase.rem_euclid(TAU) as f32,
                        })
                        .collect();
                    ctx.write_buffer(terms, 0, bytemuck::cast_slice(&now));
                }
            }
            Source::Procedural { params, wave } => {
                // Every octave's argument is `s t + x y w / f`: `s t` reduced mod 2π travels as
                // the time, with speed 1.
                let gpu = GpuProceduralWave {
                    origin: [params.origin[0] as f32, params.origin[1] as f32],
                    amplitude: params.amplitude as f32,
                    frequency: params.frequency as f32,
                    octave_base: params.octave_base as f32,
                    speed: 1.0,
                    time: (params.speed * time).rem_euclid(TAU) as f32,
                    octaves: params.octaves,
                };
                ctx.write_pod(wave, &gpu);
            }
            Source::Ocean {
                ocean,
                repeat_period,
            } => {
                let t = match repeat_period {
                    Some(period) if *period > 0.0 => time.rem_euclid(*period),
                    _ => time,
                };
                ocean.set_time(ctx, t as f32);
            }
            Source::Ripples(r) => {
                if r.clocked {
                    // As `Water::surface_at` counts them.
                    let target = (time / r.params.time_step).round().max(0.0) as u64;
                    if target >= r.clock_steps {
                        r.queued_steps += target - r.clock_steps;
                    } else {
                        r.restart(ctx);
                        r.queued_steps = target;
                    }
                    r.clock_steps = target;
                }
                r.sim.place_waiting_drops(ctx);
            }
            Source::HeightField { .. } => {}
        }
        ctx.write_pod(&self.field_buffer, &self.field);
    }

    /// Ripple sources only (the scene's and [`ripples`](Self::ripples)): queue a drop for the next
    /// encode, which applies it before that encode's steps. No-op for other sources.
    pub fn drop_ripple(&mut self, ctx: &GpuContext, d: &Drop) {
        if let Source::Ripples(r) = &mut self.source {
            r.sim.queue_drop(ctx, d);
        }
    }

    /// Ripple sources only: queue `steps` simulation steps for the next encode. No-op for other
    /// sources.
    pub fn step_ripples(&mut self, steps: u32) {
        if let Source::Ripples(r) = &mut self.source {
            r.queued_steps += steps as u64;
        }
    }

    /// Record the source's passes (the ocean's spectrum and FFT at the time given to
    /// [`update`](Self::update); the queued ripple drops and steps), then one output pass per
    /// output, into the caller's encoder, each timed when a `timer` is given.
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder, mut timer: Option<&mut GpuTimer>) {
        let mut current = 0;
        match &mut self.source {
            Source::Ocean { ocean, .. } => ocean.encode(encoder, timer.as_deref_mut()),
            Source::Ripples(r) => {
                // At least once, for the queued drops.
                loop {
                    let steps = u32::try_from(r.queued_steps).unwrap_or(u32::MAX);
                    r.sim.encode(encoder, steps, timer.as_deref_mut());
                    r.queued_steps -= steps as u64;
                    if r.queued_steps == 0 {
                        break;
                    }
                }
                current = r.sim.current_index();
            }
            Source::Waves { .. } | Source::Procedural { .. } | Source::HeightField { .. } => {}
        }
        for o in &self.outputs {
            let mut pass = begin_compute(encoder, &mut timer, "water field");
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &o.groups[current.min(o.groups.len() - 1)], &[]);
            pass.dispatch_workgroups(o.cols.div_ceil(8), o.rows.div_ceil(8), 1);
        }
    }
}

/// The waves' buffer, one term per wave (at least one), rewritten each frame.
fn waves_source(ctx: &GpuContext, waves: &[Wave], size: f64) -> Result<Source, GpuError> {
    let bytes = (waves.len().max(1) * std::mem::size_of::<GpuSineWave>()) as u64;
    ctx.check_buffer_size(&format!("water waves ({} waves)", waves.len()), bytes)?;
    let terms = ctx.buffer("water field waves", bytes, B::STORAGE | B::COPY_DST);
    Ok(Source::Waves {
        waves: waves.to_vec(),
        size,
        terms,
    })
}

/// The simulation over the water's square, its initial drops and settling steps run.
fn ripple_source(
    ctx: &GpuContext,
    water: &Water,
    params: &RippleParams,
    clocked: bool,
) -> Result<Source, GpuError> {
    let sim = GpuRipples::new(ctx, params, water.size, water.edge())?;
    let clear_pipeline = compute_pipeline(ctx, &RIPPLE_CLEAR);
    let views = sim
        .textures()
        .each_ref()
        .map(|t| t.create_view(&Default::default()));
    let clear_group = clear_pipeline.bind(ctx, "ripple clear", &[&views[0], &views[1]]);
    let mut r = RippleSource {
        sim,
        params: params.clone(),
        clocked,
        clock_steps: 0,
        queued_steps: 0,
        clear_pipeline,
        clear_group,
    };
    r.settle(ctx);
    Ok(Source::Ripples(Box::new(r)))
}

impl RippleSource {
    /// The initial drops and the settling steps, as `Ripples::run_initial`, submitted now: they
    /// come before anything a caller queues (the frame's encoder is not at hand here, and the
    /// drops may outnumber the queued-drop slots).
    fn settle(&mut self, ctx: &GpuContext) {
        for d in &self.params.drops {
            self.sim.drop(ctx, d);
        }
        let mut encoder = ctx.encoder("ripple settling steps");
        self.sim.step(ctx, &mut encoder, self.params.steps);
        ctx.queue.submit([encoder.finish()]);
    }

    /// The surface at rest again, then [`settle`](Self::settle).
    fn restart(&mut self, ctx: &GpuContext) {
        let mut encoder = ctx.encoder("ripple restart");
        {
            let mut pass = begin_compute(&mut encoder, &mut None, "ripple clear");
            pass.set_pipeline(&self.clear_pipeline);
            pass.set_bind_group(0, &self.clear_group, &[]);
            let groups = self.sim.resolution().div_ceil(8);
            pass.dispatch_workgroups(groups, groups, 1);
        }
        ctx.queue.submit([encoder.finish()]);
        self.settle(ctx);
    }
}
