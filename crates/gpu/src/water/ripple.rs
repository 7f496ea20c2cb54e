//! Interactive ripples on the GPU, twin of [`caustics_core::water::ripple::Ripples`]: the damped wave
//! equation advanced by the leapfrog scheme, one invocation per cell (`ripple_step`), and drops
//! added as cosine bumps (`ripple_drop`). The state is a ping-pong pair of `R32Float` textures,
//! `previous` and `current`, as on the CPU; a step overwrites `previous` with the next heights and
//! the pair swaps. Both passes repeat the CPU's `f32` arithmetic, so the two agree to rounding.

use std::collections::VecDeque;

use caustics_core::grid::{Edge, Grid};
use caustics_core::water::ripple::{Drop, RippleParams, Ripples};

use crate::pass::{Bind, STORAGE_OUT, begin_compute, compute_pipeline};
use crate::shaders::passes;
use crate::{GpuContext, GpuError, GpuTimer};

passes! {
    RIPPLE_STEP = "ripple_step", "water/ripple_step.wgsl";
    RIPPLE_DROP = "ripple_drop", "water/ripple_drop.wgsl";
}

/// Most queued drops one [`GpuRipples::encode`] records: each needs its own uniform slot, because
/// every `write_buffer` lands before the submission and a shared slot would hold only the last
/// drop. Drops beyond these wait for the next encode.
pub const DROPS_PER_ENCODE: usize = 16;

/// Mirrors `RippleStep` in `water/ripple_step.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RippleStep {
    /// `(c Δt / Δx)²`.
    pub courant2: f32,
    /// `d Δt / 2`.
    pub gamma: f32,
    /// 1 for [`Edge::Wrap`], 0 for [`Edge::Clamp`].
    pub wrap: u32,
    /// Pads the struct to 16 bytes; zero.
    pub _pad: u32,
}

/// Mirrors `RippleDrop` in `water/ripple_drop.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RippleDrop {
    /// The bump's centre on the water square, world units.
    pub centre: [f32; 2],
    /// The bump's radius, world units.
    pub radius: f32,
    /// Height added at the centre, world units; negative for a dent.
    pub strength: f32,
    /// First cell (column, row) of the box the bump can reach.
    pub first: [i32; 2],
    /// Cells of the box per axis.
    pub count: [u32; 2],
    /// Side of a cell, world units (`size / resolution`).
    pub dx: f32,
    /// Side of the water square, world units: the period a wrapping drop's offsets are taken
    /// modulo.
    pub size: f32,
    /// 1 for [`Edge::Wrap`], 0 for [`Edge::Clamp`].
    pub wrap: u32,
    /// Pads the struct to 48 bytes, a multiple of 16; zero.
    pub _pad: u32,
}

/// The GPU ripple state and its two passes.
pub struct GpuRipples {
    n: u32,
    size: f64,
    edge: Edge,
    textures: [wgpu::Texture; 2],
    /// Which texture holds the latest step.
    current: usize,
    step_pipeline: wgpu::ComputePipeline,
    /// `step_groups[c]` advances the state whose current heights are in `textures[c]`.
    step_groups: [wgpu::BindGroup; 2],
    drop_pipeline: wgpu::ComputePipeline,
    drop_group: wgpu::BindGroup,
    drop_params: wgpu::Buffer,
    /// [`DROPS_PER_ENCODE`] uniform slots for the drops [`encode`](Self::encode) records, one
    /// bind group per slot.
    queued_params: wgpu::Buffer,
    queued_groups: Vec<wgpu::BindGroup>,
    queued_stride: u64,
    /// The cell box of each slot written since the last encode.
    queued: Vec<[u32; 2]>,
    /// Drops queued while every slot was taken, in order.
    waiting: VecDeque<RippleDrop>,
}

impl GpuRipples {
    /// A still surface over a square of side `size`, with the checks (Courant number included) and
    /// the constants of the CPU [`Ripples::new`]. The parameters' drops are not applied.
    pub fn new(
        ctx: &GpuContext,
        params: &RippleParams,
        size: f64,
        edge: Edge,
    ) -> Result<Self, GpuError> {
        let side = u32::try_from(params.resolution).unwrap_or(u32::MAX);
        ctx.check_texture_size("ripple height texture", side, side)?;
        let cpu = Ripples::new(params, size, edge)?;
        let n = side;
        let texture =
            |label| ctx.texture_2d(label, (n, n, 1), wgpu::TextureFormat::R32Float, STORAGE_OUT);
        // Textures start zeroed: the surface at rest.
        let textures = [texture("ripple heights A"), texture("ripple heights B")];
        let views = textures
            .each_ref()
            .map(|t| t.create_view(&Default::default()));

        let step = RippleStep {
            courant2: cpu.courant2(),
            gamma: cpu.gamma(),
            wrap: (edge == Edge::Wrap) as u32,
            _pad: 0,
        };
        let step_params = ctx.uniform("ripple step params", &step);
        let step_pipeline = compute_pipeline(ctx, &RIPPLE_STEP);
        let step_group = |c: usize| {
            step_pipeline.bind(
                ctx,
                "ripple step",
                &[&step_params, &views[c], &views[1 - c]],
            )
        };
        let step_groups = [step_group(0), step_group(1)];

        let drop_params = ctx.uniform_buffer::<RippleDrop>("ripple drop params");
        let drop_pipeline = compute_pipeline(ctx, &RIPPLE_DROP);
        let drop_group =
            drop_pipeline.bind(ctx, "ripple drop", &[&drop_params, &views[0], &views[1]]);
        let drop_bytes = std::mem::size_of::<RippleDrop>() as u64;
        let queued_stride =
            drop_bytes.next_multiple_of(ctx.limits().min_uniform_buffer_offset_alignment as u64);
        let queued_params = ctx.buffer(
            "ripple queued drops",
            queued_stride * DROPS_PER_ENCODE as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        let queued_groups = (0..DROPS_PER_ENCODE as u64)
            .map(|slot| {
                drop_pipeline.bind(
                    ctx,
                    "ripple queued drop",
                    &[
                        &wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: &queued_params,
                            offset: slot * queued_stride,
                            size: wgpu::BufferSize::new(drop_bytes),
                        }),
                        &views[0],
                        &views[1],
                    ],
                )
            })
            .collect();
        ctx.check()?;
        Ok(GpuRipples {
            n,
            size,
            edge,
            textures,
            current: 0,
            step_pipeline,
            step_groups,
            drop_pipeline,
            drop_group,
            drop_params,
            queued_params,
            queued_groups,
            queued_stride,
            queued: Vec::with_capacity(DROPS_PER_ENCODE),
            waiting: VecDeque::new(),
        })
    }

    /// The drop pass's parameters for `d`: the box of cells the bump can reach, as
    /// [`Ripples::drop`] spans them; `None` when it reaches no cell.
    fn drop_params(&self, d: &Drop) -> Option<RippleDrop> {
        let n = self.n as i64;
        let dx = self.size / n as f64;
        let span = |c: f64| -> (i64, i64) {
            let lo = ((c - d.radius) / dx - 0.5).floor() as i64;
            let hi = ((c + d.radius) / dx - 0.5).ceil() as i64;
            match self.edge {
                Edge::Wrap if hi - lo + 1 >= n => (0, n),
                Edge::Wrap => (lo, hi - lo + 1),
                Edge::Clamp => (lo.max(0), hi.min(n - 1) - lo.max(0) + 1),
            }
        };
        let ((x0, nx), (y0, ny)) = (span(d.position[0]), span(d.position[1]));
        if nx <= 0 || ny <= 0 {
            return None;
        }
        Some(RippleDrop {
            centre: [d.position[0] as f32, d.position[1] as f32],
            radius: d.radius as f32,
            strength: d.strength as f32,
            first: [x0 as i32, y0 as i32],
            count: [nx as u32, ny as u32],
            dx: dx as f32,
            size: self.size as f32,
            wrap: (self.edge == Edge::Wrap) as u32,
            _pad: 0,
        })
    }

    /// Add a drop to the surface at rest, into both textures, as [`Ripples::drop`] does; submitted
    /// at once.
    pub fn drop(&mut self, ctx: &GpuContext, d: &Drop) {
        let Some(params) = self.drop_params(d) else {
            return;
        };
        ctx.write_pod(&self.drop_params, &params);
        let mut encoder = ctx.encoder("ripple drop");
        {
            let mut pass = begin_compute(&mut encoder, &mut None, "ripple drop");
            pass.set_pipeline(&self.drop_pipeline);
            pass.set_bind_group(0, &self.drop_group, &[]);
            pass.dispatch_workgroups(params.count[0].div_ceil(8), params.count[1].div_ceil(8), 1);
        }
        ctx.queue.submit([encoder.finish()]);
    }

    /// Record `steps` time steps (one compute pass, one dispatch per step). The pair swaps as they
    /// are recorded: [`current_texture`](Self::current_texture) names the texture that holds the
    /// result once the encoder has been submitted.
    pub fn step(&mut self, _ctx: &GpuContext, encoder: &mut wgpu::CommandEncoder, steps: u32) {
        if steps == 0 {
            return;
        }
        let mut pass = begin_compute(encoder, &mut None, "ripple step");
        self.record_steps(&mut pass, steps);
    }

    /// Queue a drop for the next [`encode`](Self::encode), which records it before its steps (the
    /// drop lands on the surface as it is then, as [`Ripples::drop`] between steps does). Its
    /// parameters are written now; past [`DROPS_PER_ENCODE`] drops it waits for a slot (see
    /// [`place_waiting_drops`](Self::place_waiting_drops)).
    pub fn queue_drop(&mut self, ctx: &GpuContext, d: &Drop) {
        if let Some(params) = self.drop_params(d) {
            self.waiting.push_back(params);
            self.place_waiting_drops(ctx);
        }
    }

    /// Write waiting drops into the slots the last encode freed (call once a frame before
    /// encoding; [`queue_drop`](Self::queue_drop) does it too).
    pub fn place_waiting_drops(&mut self, ctx: &GpuContext) {
        while self.queued.len() < DROPS_PER_ENCODE {
            let Some(params) = self.waiting.pop_front() else {
                break;
            };
            let offset = self.queued.len() as u64 * self.queued_stride;
            ctx.write_buffer(&self.queued_params, offset, bytemuck::bytes_of(&params));
            self.queued.push(params.count);
        }
    }

    /// Record the queued drops (one pass, `ripple drops`), then `steps` time steps (one pass,
    /// `ripple step`), each pass timed when a `timer` is given and recorded only when it has
    /// work. As with [`step`](Self::step), [`current_texture`](Self::current_texture) names the
    /// result's texture once the encoder has been submitted.
    pub fn encode(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        steps: u32,
        mut timer: Option<&mut GpuTimer>,
    ) {
        if !self.queued.is_empty() {
            let mut pass = begin_compute(encoder, &mut timer, "ripple drops");
            pass.set_pipeline(&self.drop_pipeline);
            for (group, count) in self.queued_groups.iter().zip(self.queued.drain(..)) {
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(count[0].div_ceil(8), count[1].div_ceil(8), 1);
            }
        }
        if steps > 0 {
            let mut pass = begin_compute(encoder, &mut timer, "ripple step");
            self.record_steps(&mut pass, steps);
        }
    }

    fn record_steps(&mut self, pass: &mut wgpu::ComputePass, steps: u32) {
        pass.set_pipeline(&self.step_pipeline);
        let groups = self.n.div_ceil(8);
        for _ in 0..steps {
            pass.set_bind_group(0, &self.step_groups[self.current], &[]);
            pass.dispatch_workgroups(groups, groups, 1);
            self.current = 1 - self.current;
        }
    }

    /// Both state textures (`R32Float`, `N × N`, storage and sampled), for passes that read
    /// whichever is current or reset them.
    pub fn textures(&self) -> &[wgpu::Texture; 2] {
        &self.textures
    }

    /// Which of [`textures`](Self::textures) holds the latest step.
    pub fn current_index(&self) -> usize {
        self.current
    }

    /// Grid cells per side.
    pub fn resolution(&self) -> u32 {
        self.n
    }

    /// The heights at the latest step: `R32Float`, `N × N`, texel `(j, i)` at grid sample `(i, j)`.
    pub fn current_texture(&self) -> &wgpu::Texture {
        &self.textures[self.current]
    }

    /// Read the heights at the latest step back (after submitting what [`step`](Self::step)
    /// recorded).
    pub fn read(&self, ctx: &GpuContext) -> Result<Grid, GpuError> {
        let data = ctx.read_texture(self.current_texture())?;
        Ok(Grid {
            cols: self.n as usize,
            rows: self.n as usize,
            data,
        })
    }
}
