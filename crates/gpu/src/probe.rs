//! A compute pass that evaluates the shared WGSL math (`optics.wgsl`, `water.wgsl`,
//! `caustics_light.wgsl`) on chosen inputs,
//! so that tests can hold every function against its CPU twin in `caustics-core`.

use crate::pass::{Bind, begin_compute, storage_buffer};
use crate::shaders::passes;
use crate::water::{GpuProceduralWave, GpuSineWave};
use crate::{GpuContext, GpuError};
use wgpu::BufferUsages as B;

passes! {
    PROBE = "probe", "probe.wgsl";
}

/// Mirrors `ProbeIn` in `probe.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ProbeIn {
    /// Direction, then `eta`.
    pub incident: [f32; 4],
    /// Normal, then `n2` for the Fresnel transmittance from `n1 = 1`.
    pub normal: [f32; 4],
    /// xy: the point on the water the surfaces are evaluated at, world units (`[0, size]²`);
    /// z: the depth `flat_light` is evaluated at; w unused.
    pub point: [f32; 4],
}

/// Mirrors `ProbeOut` in `probe.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ProbeOut {
    /// `refract_dir` of the input: xyz the refracted unit direction, w 1 where it exists and 0 on
    /// total internal reflection.
    pub refracted: [f32; 4],
    /// x: the Fresnel transmittance from `n1 = 1` into `n2`; yzw: the sum of the sine waves at
    /// `point` (height, ∂h/∂x, ∂h/∂y). `fresnel_sine_procedural` in the WGSL.
    pub fresnel_sine: [f32; 4],
    /// xyz: paper 2's procedural wave at `point` (height, ∂h/∂x, ∂h/∂y); w 0.
    pub procedural: [f32; 4],
    /// xyz: the bicubic interpolant of the height grid at `point` (height, ∂h/∂x, ∂h/∂y); w 0.
    pub grid: [f32; 4],
    /// The same surface from the heights' Hermite form ([`crate::water::patches`]).
    pub hermite: [f32; 4],
    /// xyz: `sun_under_water` for the sun opposite `incident` (towards `-incident`) under water of
    /// index `normal.w`; w 0.
    pub sun_under: [f32; 4],
    /// xyz: `flat_water_light` on a surface of normal `normal` at depth `point.z` under water of
    /// absorption [`PROBE_ABSORPTION`], for that sun; w 0.
    pub flat_light: [f32; 4],
}

/// The absorption (per metre) `ProbeOut::flat_light` is evaluated with: the pool scene's.
pub const PROBE_ABSORPTION: [f64; 3] = [0.45, 0.09, 0.05];

/// Mirrors `ProbeParams` in `probe.wgsl` (uniform layout, padded to 16 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct ProbeParams {
    procedural: GpuProceduralWave,
    wave_count: u32,
    size: f32,
    wrap: u32,
    _pad: u32,
}

/// The surfaces the probe evaluates at each input's `point`.
pub struct ProbeSetup<'a> {
    /// The sine waves whose sum is [`ProbeOut::fresnel_sine`]'s yzw (none gives zero).
    pub waves: &'a [GpuSineWave],
    /// Paper 2's wave, with its clock, for [`ProbeOut::procedural`].
    pub procedural: GpuProceduralWave,
    /// The height grid, samples at texel centres over `[0, size]²`, for [`ProbeOut::grid`] and
    /// [`ProbeOut::hermite`].
    pub grid: &'a caustics_core::grid::Grid,
    /// Side of the square the grid covers, world units.
    pub size: f32,
    /// Whether the grid tiles (periodic) or clamps at its edges.
    pub wrap: bool,
}

/// Evaluate the shared WGSL math on each of `inputs` in one compute dispatch and read the results
/// back, one [`ProbeOut`] per input, in order.
pub fn run(
    ctx: &GpuContext,
    inputs: &[ProbeIn],
    setup: &ProbeSetup,
) -> Result<Vec<ProbeOut>, GpuError> {
    let device = &ctx.device;
    let module = PROBE.module(device);
    let pipeline = ctx.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("probe"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let input = ctx.buffer_init("probe inputs", bytemuck::cast_slice(inputs), B::STORAGE);
    let output = ctx.buffer(
        "probe outputs",
        (inputs.len() * std::mem::size_of::<ProbeOut>()) as u64,
        B::STORAGE | B::COPY_SRC,
    );
    let waves = storage_buffer(ctx, "probe waves", setup.waves)?;
    let params = ProbeParams {
        procedural: setup.procedural,
        wave_count: setup.waves.len() as u32,
        size: setup.size,
        wrap: setup.wrap as u32,
        _pad: 0,
    };
    let params = ctx.uniform("probe params", &params);
    let height = ctx.upload_grid("probe height field", setup.grid)?;
    let height_view = height.create_view(&Default::default());
    let water_patches = crate::water::patches::WaterPatches::new(ctx);
    let patches = water_patches.frame(ctx, &height_view, setup.wrap);
    let bind = pipeline.bind(
        ctx,
        "probe",
        &[
            &input,
            &output,
            &waves,
            &params,
            &height_view,
            &patches.view,
        ],
    );
    let mut encoder = device.create_command_encoder(&Default::default());
    water_patches.encode(&patches, &mut encoder, &mut None);
    {
        let mut pass = begin_compute(&mut encoder, &mut None, "probe");
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups((inputs.len() as u32).div_ceil(64), 1, 1);
    }
    ctx.queue.submit([encoder.finish()]);
    ctx.check()?;
    ctx.read_buffer(&output)
}
