//! Interactive ripples on the GPU, twin of [`caustics_core::water::ripple::Ripples`]: the damped wave
//! equation advanced by the leapfrog scheme, one invocation per cell (`ripple_step`), and drops
//! added as cosine bumps (`ripple_drop`). The state is a ping-pong pair of `R32Float` textures,
//! `previous` and `current`, as on the CPU; a step overwrites `previous` with the next heights and
//! the pair swaps. Both passes repeat the CPU's `f32` arithmetic, so the two agree to rounding.

use caustics_core::grid::{Edge, Grid};
use caustics_core::water::ripple::{Drop, RippleParams, Ripples};

use crate::pass::{bind_group, compute_pipeline};
use crate::{GpuContext, GpuError, shaders};

/// Mirrors `RippleStep` in `shaders/ripple_step.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RippleStep {
    /// `(c Δt / Δx)²`.
    pub courant2: f32,
    /// `d Δt / 2`.
    pub gamma: f32,
    /// 1 for [`Edge::Wrap`], 0 for [`Edge::Clamp`].
    pub wrap: u32,
    pub _pad: u32,
}

/// Mirrors `RippleDrop` in `shaders/ripple_drop.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RippleDrop {
    pub centre: [f32; 2],
    pub radius: f32,
    pub strength: f32,
    /// First cell (column, row) of the box the bump can reach.
    pub first: [i32; 2],
    /// Cells of the box per axis.
    pub count: [u32; 2],
    pub dx: f32,
    pub size: f32,
    /// 1 for [`Edge::Wrap`], 0 for [`Edge::Clamp`].
    pub wrap: u32,
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
        let device = &ctx.device;
        let n = side;
        let texture = |label| {
            ctx.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: n,
                    height: n,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::R32Float,
                usage: wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
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
        let step_params = wgpu::util::DeviceExt::create_buffer_init(
            device,
            &wgpu::util::BufferInitDescriptor {
                label: Some("ripple step params"),
                contents: bytemuck::bytes_of(&step),
                usage: wgpu::BufferUsages::UNIFORM,
            },
        );
        let step_pipeline = compute_pipeline(ctx, &shaders::RIPPLE_STEP);
        let step_group = |c: usize| {
            bind_group(
                ctx,
                "ripple step",
                &step_pipeline.get_bind_group_layout(0),
                &[
                    step_params.as_entire_binding(),
                    wgpu::BindingResource::TextureView(&views[c]),
                    wgpu::BindingResource::TextureView(&views[1 - c]),
                ],
            )
        };
        let step_groups = [step_group(0), step_group(1)];

        let drop_params = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ripple drop params"),
            size: std::mem::size_of::<RippleDrop>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let drop_pipeline = compute_pipeline(ctx, &shaders::RIPPLE_DROP);
        let drop_group = bind_group(
            ctx,
            "ripple drop",
            &drop_pipeline.get_bind_group_layout(0),
            &[
                drop_params.as_entire_binding(),
                wgpu::BindingResource::TextureView(&views[0]),
                wgpu::BindingResource::TextureView(&views[1]),
            ],
        );
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
        })
    }

    /// Add a drop to the surface at rest, into both textures, as [`Ripples::drop`] does; submitted
    /// at once.
    pub fn drop(&mut self, ctx: &GpuContext, d: &Drop) {
        let n = self.n as i64;
        let dx = self.size / n as f64;
        // The cells whose centre can lie within the radius, per axis, as `Ripples::drop` spans them.
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
            return;
        }
        let params = RippleDrop {
            centre: [d.position[0] as f32, d.position[1] as f32],
            radius: d.radius as f32,
            strength: d.strength as f32,
            first: [x0 as i32, y0 as i32],
            count: [nx as u32, ny as u32],
            dx: dx as f32,
            size: self.size as f32,
            wrap: (self.edge == Edge::Wrap) as u32,
            _pad: 0,
        };
        ctx.write_buffer(&self.drop_params, 0, bytemuck::bytes_of(&params));
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("ripple drop"),
            });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("ripple drop"),
                timestamp_writes: None,
            });
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
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("ripple step"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.step_pipeline);
        let groups = self.n.div_ceil(8);
        for _ in 0..steps {
            pass.set_bind_group(0, &self.step_groups[self.current], &[]);
            pass.dispatch_workgroups(groups, groups, 1);
            self.current = 1 - self.current;
        }
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
