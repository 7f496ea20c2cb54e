//! The Tessendorf FFT ocean on the GPU (J. Tessendorf, "Simulating Ocean Water", SIGGRAPH 2001
//! course notes, §4.3), twin of [`caustics_core::water::ocean::Ocean`]: the CPU draws the random sea
//! once (`h̃0(k)`, `conj(h̃0(−k))`, `ω(k)`) and the GPU evaluates it at any time in three passes,
//!
//! 1. `ocean_spectrum`: `h̃(k, t)` and the slope spectrum `i k h̃`, with the half-texel shift;
//! 2. `ocean_fft`: the 2-D inverse FFT, `log2 N` radix-2 Stockham stages over the rows, then
//!    `log2 N` over the columns;
//! 3. `ocean_output`: `(h, ∂h/∂x, ∂h/∂y, 0)` into an `Rgba32Float` texture.
//!
//! **Why a multi-pass Stockham FFT.** One dispatch per stage, ping-ponging two storage buffers, works
//! for every resolution the CPU ocean accepts (up to 4096), needs no shared memory or workgroup size
//! beyond WebGPU's defaults, and keeps each stage a dozen lines that read like the textbook
//! butterfly. A one-workgroup-per-row shared-memory FFT saves the passes' memory traffic but stops
//! at the workgroup limits: a row of N elements of 16 bytes (two complex signals) must fit the
//! 16 KiB of workgroup memory WebGPU guarantees, so N ≤ 1024. At the resolutions a caustics scene
//! uses (≤ 512) the 2 log2 N small dispatches are cheap. The Stockham form sorts itself, so there is
//! no bit-reversal pass; the twiddles come from a table computed in f64, so the f32 error grows only
//! with the `log2 N` roundings of the data.

use caustics_core::water::ocean::Ocean;

use crate::pass::{Bind, Binding, STORAGE_OUT, begin_compute, compute_pipeline};
use crate::shaders::{PassSource, passes};
use crate::timing::GpuTimer;
use crate::{GpuContext, GpuError};

passes! {
    OCEAN_SPECTRUM = "ocean_spectrum", "water/ocean_spectrum.wgsl";
    OCEAN_FFT = "ocean_fft", "water/ocean_fft.wgsl";
    OCEAN_OUTPUT = "ocean_output", "water/ocean_output.wgsl";
}

/// Mirrors `SpectrumParams` in `water/ocean_spectrum.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SpectrumParams {
    /// The grid's side `N`: modes (and output texels) along each axis, a power of two.
    pub n: u32,
    /// The instant `t` the spectrum is evaluated at, seconds.
    pub time: f32,
    /// `2π / size`.
    pub dk: f32,
    /// Pads the struct to 16 bytes; zero.
    pub _pad: u32,
}

/// Mirrors `FftStage` in `water/ocean_fft.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FftStage {
    /// The grid's side `N`: the length of each row's and column's transform.
    pub n: u32,
    /// Length of the transforms the stage merges: 1, 2, 4, …, N/2.
    pub p: u32,
    /// 0: rows, 1: columns.
    pub axis: u32,
    /// Pads the struct to 16 bytes; zero.
    pub _pad: u32,
}

/// Bytes per element of the FFT buffers: two complex `f32` numbers (height, slopes).
const ELEMENT_BYTES: u64 = 16;

/// The GPU ocean: its buffers, pipelines and bind groups, built once for one [`Ocean`].
pub struct GpuOcean {
    n: u32,
    dk: f32,
    params: wgpu::Buffer,
    spectrum: Pass,
    /// The row stages, then the column stages.
    fft: Vec<wgpu::BindGroup>,
    fft_pipeline: wgpu::ComputePipeline,
    output: Pass,
    texture: wgpu::Texture,
}

struct Pass {
    pipeline: wgpu::ComputePipeline,
    bind: wgpu::BindGroup,
}

impl GpuOcean {
    /// Refuse a resolution whose texture or FFT buffers this device cannot hold, before any work
    /// (drawing a large [`Ocean`] on the CPU takes a while).
    pub fn check_size(ctx: &GpuContext, resolution: usize) -> Result<(), GpuError> {
        let side = u32::try_from(resolution).unwrap_or(u32::MAX);
        ctx.check_texture_size("ocean height and slope texture", side, side)?;
        let n = resolution as u64;
        ctx.check_buffer_size(
            &format!("ocean FFT buffer ({resolution} x {resolution} x 2 complex f32)"),
            n * n * ELEMENT_BYTES,
        )
    }

    /// Upload the ocean's spectrum and build the passes.
    pub fn new(ctx: &GpuContext, ocean: &Ocean) -> Result<Self, GpuError> {
        let resolution = ocean.params().resolution;
        Self::check_size(ctx, resolution)?;
        let n = resolution as u32;
        let buffer = |label: &str, contents: &[u8], usage| ctx.buffer_init(label, contents, usage);

        let h0: Vec<[f32; 4]> = ocean
            .h0()
            .iter()
            .zip(ocean.h0_minus_conj())
            .map(|(a, b)| [a.re as f32, a.im as f32, b.re as f32, b.im as f32])
            .collect();
        let omega: Vec<f32> = ocean.omega().iter().map(|&w| w as f32).collect();
        // e^{iπ a / N}, a in [0, 2N): the half-texel shifts and the FFT twiddles.
        let roots: Vec<[f32; 2]> = (0..2 * resolution)
            .map(|a| {
                let (s, c) = (std::f64::consts::PI * a as f64 / resolution as f64).sin_cos();
                [c as f32, s as f32]
            })
            .collect();
        let storage = wgpu::BufferUsages::STORAGE;
        let h0 = buffer("ocean h0", bytemuck::cast_slice(&h0), storage);
        let omega = buffer("ocean omega", bytemuck::cast_slice(&omega), storage);
        let roots = buffer(
            "ocean roots of unity",
            bytemuck::cast_slice(&roots),
            storage,
        );
        let field = |label| ctx.buffer(label, n as u64 * n as u64 * ELEMENT_BYTES, storage);
        let ping = field("ocean FFT ping");
        let pong = field("ocean FFT pong");

        let dk = (std::f64::consts::TAU / ocean.size()) as f32;
        let params = ctx.uniform_buffer::<SpectrumParams>("ocean spectrum params");
        let spectrum = Pass::new(ctx, &OCEAN_SPECTRUM, &[&params, &h0, &omega, &roots, &ping]);

        // One uniform slot per stage, each at the device's uniform offset alignment; stage s reads
        // ping and writes pong when s is even, the other way round when odd. There are 2 log2 N
        // stages, an even number, so the result ends in `ping`.
        let log2n = n.trailing_zeros();
        let stages: Vec<FftStage> = (0..2)
            .flat_map(|axis| {
                (0..log2n).map(move |s| FftStage {
                    n,
                    p: 1 << s,
                    axis,
                    _pad: 0,
                })
            })
            .collect();
        let stride = (std::mem::size_of::<FftStage>() as u64)
            .next_multiple_of(ctx.limits().min_uniform_buffer_offset_alignment as u64);
        let mut table = vec![0u8; stride as usize * stages.len()];
        for (s, stage) in stages.iter().enumerate() {
            let at = s * stride as usize;
            table[at..at + std::mem::size_of::<FftStage>()]
                .copy_from_slice(bytemuck::bytes_of(stage));
        }
        let table = buffer("ocean FFT stages", &table, wgpu::BufferUsages::UNIFORM);
        let fft_pipeline = compute_pipeline(ctx, &OCEAN_FFT);
        let fft = (0..stages.len())
            .map(|s| {
                let (src, dst) = if s % 2 == 0 {
                    (&ping, &pong)
                } else {
                    (&pong, &ping)
                };
                fft_pipeline.bind(
                    ctx,
                    "ocean FFT stage",
                    &[
                        &wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: &table,
                            offset: s as u64 * stride,
                            size: wgpu::BufferSize::new(std::mem::size_of::<FftStage>() as u64),
                        }),
                        &roots,
                        &src,
                        &dst,
                    ],
                )
            })
            .collect();

        let texture = ctx.texture_2d(
            "ocean height and slopes",
            (n, n, 1),
            wgpu::TextureFormat::Rgba32Float,
            STORAGE_OUT,
        );
        let view = texture.create_view(&Default::default());
        let output = Pass::new(ctx, &OCEAN_OUTPUT, &[&ping, &view]);
        ctx.check()?;
        Ok(GpuOcean {
            n,
            dk,
            params,
            spectrum,
            fft,
            fft_pipeline,
            output,
            texture,
        })
    }

    /// Grid size `N`.
    pub fn resolution(&self) -> u32 {
        self.n
    }

    /// Record the passes that evaluate the surface at time `t` (seconds) into
    /// [`height_slopes_texture`](Self::height_slopes_texture), each timed when a `timer` is given
    /// (four passes: spectrum, FFT rows, FFT columns, output).
    ///
    /// `t` travels by `queue.write_buffer`, which lands before the next submission: record one
    /// update per submission. It is an `f32`, so `ω t` loses precision as `t` grows (a few 1e-4 rad
    /// for the fastest, faintest modes of a 256 grid on a unit tile after a minute): wrap
    /// long-running times by the repeat period where one is set.
    pub fn update(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        t: f32,
        timer: Option<&mut GpuTimer>,
    ) {
        self.set_time(ctx, t);
        self.encode(encoder, timer);
    }

    /// The first half of [`update`](Self::update): write the time the next submitted
    /// [`encode`](Self::encode) evaluates the surface at (16 bytes of uniform).
    pub fn set_time(&self, ctx: &GpuContext, t: f32) {
        let params = SpectrumParams {
            n: self.n,
            time: t,
            dk: self.dk,
            _pad: 0,
        };
        ctx.write_pod(&self.params, &params);
    }

    /// The second half of [`update`](Self::update): record the four passes, for a caller that
    /// writes the time apart from recording (per frame: [`set_time`](Self::set_time), then this).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, mut timer: Option<&mut GpuTimer>) {
        let (n, half) = (self.n, self.n / 2);
        {
            let mut pass = begin_compute(encoder, &mut timer, "ocean spectrum");
            self.spectrum.bind(&mut pass);
            pass.dispatch_workgroups(n.div_ceil(8), n.div_ceil(8), 1);
        }
        let stages = self.fft.len() / 2;
        for (label, groups) in [
            ("ocean FFT rows", &self.fft[..stages]),
            ("ocean FFT columns", &self.fft[stages..]),
        ] {
            let mut pass = begin_compute(encoder, &mut timer, label);
            pass.set_pipeline(&self.fft_pipeline);
            for group in groups {
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(half.div_ceil(64), n, 1);
            }
        }
        {
            let mut pass = begin_compute(encoder, &mut timer, "ocean output");
            self.output.bind(&mut pass);
            pass.dispatch_workgroups(n.div_ceil(8), n.div_ceil(8), 1);
        }
    }

    /// `Rgba32Float`, `N × N`: `(h, ∂h/∂x, ∂h/∂y, 0)`, texel `(j, i)` at the grid sample `(i, j)`,
    /// i.e. at `((j + 0.5) dx, (i + 0.5) dx)`, as after the last [`update`](Self::update).
    pub fn height_slopes_texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// Evaluate the surface at time `t` and read it back: `(h, ∂h/∂x, ∂h/∂y, 0)` per sample,
    /// row-major like [`caustics_core::grid::Grid`].
    pub fn compute(&self, ctx: &GpuContext, t: f32) -> Result<Vec<[f32; 4]>, GpuError> {
        let mut encoder = ctx.encoder("ocean");
        self.update(ctx, &mut encoder, t, None);
        ctx.queue.submit([encoder.finish()]);
        ctx.read_texture(&self.texture)
    }
}

impl Pass {
    fn new(ctx: &GpuContext, source: &PassSource, entries: &[&dyn Binding]) -> Self {
        let pipeline = compute_pipeline(ctx, source);
        let bind = pipeline.bind(ctx, source.name, entries);
        Pass { pipeline, bind }
    }

    fn bind(&self, pass: &mut wgpu::ComputePass) {
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind, &[]);
    }
}
