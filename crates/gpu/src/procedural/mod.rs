//! Technique `procedural` on the GPU: "Inexpensive Underwater Caustics Using Cg" (Sánchez-Crespo
//! Dalmau). The method, its light map, its options and where it departs from the reference are
//! documented with its CPU twin, `caustics_core::techniques::procedural`, which these passes mirror
//! one for one:
//!
//! | variant | pass | WGSL | CPU twin |
//! |---|---|---|---|
//! | vertex | caustic per mesh vertex (vertex shader), linear over the triangles (rasteriser) | `procedural/vertex.wgsl` | `vertex::vertex_values` + `vertex::rasterise` |
//! | screen | caustic per map pixel, no filtering (fragment) | `screen.wgsl` | `screen::per_pixel` |
//! | texture | caustic per texel of the fixed-size target, mip level 0 (fragment) | `target.wgsl` | `target::target_pass` (`per_pixel` at the target's size) |
//! | texture | one 2 x 2 box downsample per mip level (fragment) | `downsample.wgsl` | `downsample::mip_chain` |
//! | texture | the map reads the chain: trilinear, `anisotropy_clamp` 16 (fragment) | `resample.wgsl` | `resample::resample` |
//!
//! Every evaluating pass shares `common.wgsl` (`procedural_caustic`), which reuses the shared
//! `refract_dir`, `height_field_normal`, `procedural_wave` and `grid_sample`. The map and the target
//! are `Rgba32Float`; the target falls back to `Rgba16Float` where the adapter cannot filter 32-bit
//! floats (`FLOAT32_FILTERABLE`), at half-float precision.

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::procedural::{ProceduralSetup, SurfaceInput, Variant};

use crate::pass::{Bind, MAP_TARGET, begin_render, mip_view, pulled_pipeline, v4};
use crate::receivers::{ReceiverFrame, ReceiverLookup};
use crate::shaders::{PassSource, passes};
use crate::water::GpuProceduralWave;
use crate::{GpuContext, GpuError, GpuTimer, WaterTextures};

pub mod technique;

passes! {
    VERTEX = "procedural vertex", "procedural/vertex.wgsl";
    SCREEN = "procedural screen", "procedural/screen.wgsl";
    TARGET = "procedural target", "procedural/target.wgsl";
    DOWNSAMPLE = "procedural downsample", "procedural/downsample.wgsl";
    RESAMPLE = "procedural resample", "procedural/resample.wgsl";
}

/// Mirrors `Procedural` in `procedural/common.wgsl` and `ProceduralSetup` in
/// caustics-core/src/techniques/procedural/mod.rs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ProceduralUniform {
    /// xyz: `e1`, the first axis of the sun frame's tangent plane, world frame; w: 0.
    pub sun_x: [f32; 4],
    /// xyz: `e2`, the second tangent axis; w: 0.
    pub sun_y: [f32; 4],
    /// xyz: the unit direction toward the sun (`+z` for the paper's overhead sun); w: 0.
    pub sun_z: [f32; 4],
    /// xyz: the unit gathering ray from the floor up to the surface (`+z`, the paper's vertical
    /// ray, unless the technique follows the sun); w: 0.
    pub up: [f32; 4],
    /// rgb: the absorption `K` per channel along the gathering ray, per world unit (0 without the
    /// option, or over receivers, whose lookup attenuates); w: `ground`, the share of the floor's
    /// light the paper's additive blend leaves unmodulated.
    pub absorption: [f32; 4],
    /// The paper's wave function, read when `source` is 1.
    pub wave: GpuProceduralWave,
    /// Side of the floor's square `[0, size]²`, world units.
    pub size: f32,
    /// The water's rest depth above the floor, world units.
    pub depth: f32,
    /// Water to air, `η = n_water / n_air` (the paper's 1.33333 by default).
    pub ior: f32,
    /// `E`: the light map spans `uv ∈ [−E, E]²` in the sun frame, the tangent of the half-angle it
    /// covers.
    pub extent: f32,
    /// The caustics map's width, texels.
    pub width: u32,
    /// The caustics map's height, texels.
    pub height: u32,
    /// Side of the texture variant's fixed-size target (mip level 0), texels.
    pub target_size: u32,
    /// Quads per side of the vertex variant's ground mesh.
    pub mesh: u32,
    /// Where the water comes from: 0, the bound height grid read bicubically; 1, the paper's wave
    /// function evaluated in the shader.
    pub source: u32,
    /// The heights' edge rule: 1 where they tile, 0 where they clamp.
    pub wrap: u32,
    /// Padding to the uniform's 16-byte multiple.
    pub _pad: [u32; 2],
}

impl ProceduralUniform {
    /// The uniform for `s` over `water`: the wave function evaluated in the shader when the input
    /// is the paper's wave, else the bound height grid.
    pub fn new(s: &ProceduralSetup, water: &SurfaceInput) -> Self {
        Self::with_wave(s, wave_of(water))
    }

    /// The uniform for the paper's wave evaluated in the shader (`Some`), or for the bound height
    /// grid (`None`).
    pub fn with_wave(s: &ProceduralSetup, wave: Option<GpuProceduralWave>) -> Self {
        let (source, wave) = match wave {
            Some(w) => (1, w),
            None => (0, GpuProceduralWave::default()),
        };
        ProceduralUniform {
            sun_x: v4(s.sun_frame[0], 0.0),
            sun_y: v4(s.sun_frame[1], 0.0),
            sun_z: v4(s.sun_frame[2], 0.0),
            up: v4(s.up, 0.0),
            absorption: {
                let mut a = v4(s.gathered_absorption(), 0.0);
                a[3] = s.ground as f32;
                a
            },
            wave,
            size: s.size as f32,
            depth: s.depth as f32,
            ior: s.ior as f32,
            extent: s.light.extent as f32,
            width: s.width as u32,
            height: s.height as u32,
            target_size: s.target as u32,
            mesh: s.mesh as u32,
            source,
            wrap: s.wrap as u32,
            _pad: [0; 2],
        }
    }
}

fn wave_of(water: &SurfaceInput) -> Option<GpuProceduralWave> {
    match water {
        SurfaceInput::Wave(w) => Some(GpuProceduralWave::from(*w)),
        SurfaceInput::Grid(_) => None,
    }
}

const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The technique's pipelines, built once per device.
pub struct ProceduralCaustics {
    vertex: wgpu::RenderPipeline,
    screen: wgpu::RenderPipeline,
    target: wgpu::RenderPipeline,
    downsample: wgpu::RenderPipeline,
    resample: wgpu::RenderPipeline,
    /// The receivers' lookup of a frame over a terrain.
    lookup: ReceiverLookup,
    /// The texture variant's target and mip chain: `Rgba32Float` where the adapter filters it,
    /// `Rgba16Float` otherwise.
    pub chain_format: wgpu::TextureFormat,
}

fn render_pipeline(
    ctx: &GpuContext,
    pass: &PassSource,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let module = pass.module(&ctx.device);
    pulled_pipeline(ctx, pass.name, &module, &[Some(format.into())])
}

/// One frame's resources for a given setup and water, bind groups included: a frame is built once
/// and encoded every time the water moves.
pub struct ProceduralFrame {
    uniform: wgpu::Buffer,
    /// The heights it uploaded itself ([`ProceduralCaustics::frame`]); `None` when it reads the
    /// caller's ([`ProceduralCaustics::frame_with_water`]).
    heights: Option<wgpu::Texture>,
    /// The paper's wave when the shader evaluates it, `None` when it reads the height grid.
    wave: Option<GpuProceduralWave>,
    /// The passes' map: the floor map on the plane `z = 0`, the light-space map over receivers.
    pub map: wgpu::Texture,
    map_view: wgpu::TextureView,
    /// The terrain's receivers where the setup has them: the lookup writes the floor map.
    pub receivers: Option<ReceiverFrame>,
    setup: ProceduralSetup,
    passes: FramePasses,
    bytes: u64,
}

enum FramePasses {
    Vertex {
        bind: wgpu::BindGroup,
        /// The mesh's triangle-list indices and their count.
        indices: wgpu::Buffer,
        count: u32,
    },
    Screen {
        bind: wgpu::BindGroup,
    },
    Texture {
        target: wgpu::BindGroup,
        /// One view per mip level of the target.
        levels: Vec<wgpu::TextureView>,
        /// Per level k >= 1: level k - 1 bound as the source.
        downsample: Vec<wgpu::BindGroup>,
        resample: wgpu::BindGroup,
    },
}

impl ProceduralFrame {
    /// GPU memory this frame's textures and buffers take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// The setup the frame was built for, or last took by [`set_setup`](Self::set_setup).
    pub fn setup(&self) -> &ProceduralSetup {
        &self.setup
    }

    /// The floor map: the receivers' lookup where the frame has receivers, else the map.
    pub fn floor_map(&self) -> &wgpu::Texture {
        self.receivers.as_ref().map_or(&self.map, |r| &r.floor)
    }

    /// Whether `setup` fits this frame's textures, bind groups and sampler (the same variant, map,
    /// mesh, target, filtering, edges and light map), so that [`set_setup`](Self::set_setup) can
    /// take it.
    pub fn fits(&self, setup: &ProceduralSetup) -> bool {
        let s = &self.setup;
        (
            setup.variant,
            setup.width,
            setup.height,
            setup.mesh,
            setup.target,
            setup.anisotropy,
            setup.wrap,
        ) == (
            s.variant,
            s.width,
            s.height,
            s.mesh,
            s.target,
            s.anisotropy,
            s.wrap,
        ) && setup.light == s.light
            && setup.receivers == s.receivers
            && (s.receivers.is_none() || setup.absorption == s.absorption)
    }

    /// Take a new sun, depth or absorption (a setup that [`fits`](Self::fits)): one uniform write.
    pub fn set_setup(&mut self, ctx: &GpuContext, setup: &ProceduralSetup) {
        debug_assert!(self.fits(setup));
        self.setup = setup.clone();
        self.write_uniform(ctx);
    }

    fn write_uniform(&self, ctx: &GpuContext) {
        ctx.write_pod(
            &self.uniform,
            &ProceduralUniform::with_wave(&self.setup, self.wave),
        );
    }
}

/// Triangle-list indices of a mesh of `n`² quads, `(n + 1)²` vertices row-major over `l`; each quad
/// split along its diagonal from vertex `(k, l)` to `(k + 1, l + 1)`, as `rasterise` assumes.
pub fn mesh_indices(n: u32) -> Vec<u32> {
    let mut out = Vec::with_capacity(6 * (n * n) as usize);
    for l in 0..n {
        for k in 0..n {
            let v00 = l * (n + 1) + k;
            let (v10, v01) = (v00 + 1, v00 + n + 1);
            let v11 = v01 + 1;
            out.extend([v00, v10, v11, v00, v11, v01]);
        }
    }
    out
}

impl ProceduralCaustics {
    /// Build the five pipelines and the receivers' lookup; the texture variant's chain is
    /// `Rgba16Float` where the adapter cannot filter 32-bit floats.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let chain_format = if ctx
            .device
            .features()
            .contains(wgpu::Features::FLOAT32_FILTERABLE)
        {
            wgpu::TextureFormat::Rgba32Float
        } else {
            wgpu::TextureFormat::Rgba16Float
        };
        let p = ProceduralCaustics {
            vertex: render_pipeline(ctx, &VERTEX, MAP_FORMAT),
            screen: render_pipeline(ctx, &SCREEN, MAP_FORMAT),
            target: render_pipeline(ctx, &TARGET, chain_format),
            downsample: render_pipeline(ctx, &DOWNSAMPLE, chain_format),
            resample: render_pipeline(ctx, &RESAMPLE, MAP_FORMAT),
            lookup: ReceiverLookup::new(ctx),
            chain_format,
        };
        ctx.check()?;
        Ok(p)
    }

    /// Allocate a frame's textures, buffers and bind groups for the setup's variant, and upload the
    /// water and the light map.
    pub fn frame(
        &self,
        ctx: &GpuContext,
        setup: &ProceduralSetup,
        water: &SurfaceInput,
    ) -> Result<ProceduralFrame, GpuError> {
        let heights = match water {
            SurfaceInput::Grid(g) => ctx.upload_grid("procedural height field", g)?,
            // The wave is evaluated in the shader; the binding still needs a texture.
            SurfaceInput::Wave(_) => {
                ctx.upload_grid("procedural (unused heights)", &Grid::new(1, 1))?
            }
        };
        let mut frame = self.build(
            ctx,
            setup,
            wave_of(water),
            &heights.create_view(&Default::default()),
        )?;
        frame.bytes += (heights.width() * heights.height()) as u64 * 4;
        frame.heights = Some(heights);
        Ok(frame)
    }

    /// Allocate a frame for the setup's variant that reads the caller's heights (any grid size:
    /// the passes sample it bicubically, as the CPU twin samples its grid), and upload the light
    /// map.
    pub fn frame_with_water(
        &self,
        ctx: &GpuContext,
        setup: &ProceduralSetup,
        water: &WaterTextures,
    ) -> Result<ProceduralFrame, GpuError> {
        self.build(ctx, setup, None, &water.heights)
    }

    fn build(
        &self,
        ctx: &GpuContext,
        setup: &ProceduralSetup,
        wave: Option<GpuProceduralWave>,
        heights_view: &wgpu::TextureView,
    ) -> Result<ProceduralFrame, GpuError> {
        use wgpu::TextureUsages as U;
        let (w, h) = (setup.width as u32, setup.height as u32);
        ctx.check_texture_size("procedural caustics map", w, h)?;
        let uniform = ctx.uniform(
            "procedural uniform",
            &ProceduralUniform::with_wave(setup, wave),
        );
        let lm = &setup.light;
        let light = ctx.upload_grid(
            "procedural light map",
            &Grid {
                cols: lm.width,
                rows: lm.height,
                data: lm.texels.clone(),
            },
        )?;
        let light_view = light.create_view(&Default::default());
        let water_bind = |pipeline: &wgpu::RenderPipeline, label: &str| {
            pipeline.bind(ctx, label, &[&uniform, heights_view, &light_view])
        };
        let map = ctx.texture_2d("procedural map", (w, h, 1), MAP_FORMAT, MAP_TARGET);
        let map_view = map.create_view(&Default::default());
        let mut bytes = (w * h) as u64 * 16 + (lm.width * lm.height) as u64 * 4 + uniform.size();
        let passes = match setup.variant {
            Variant::Vertex => {
                let indices = mesh_indices(setup.mesh as u32);
                ctx.check_buffer_size("procedural mesh indices", indices.len() as u64 * 4)?;
                bytes += indices.len() as u64 * 4;
                FramePasses::Vertex {
                    bind: water_bind(&self.vertex, "procedural vertex"),
                    indices: ctx.buffer_init(
                        "procedural mesh indices",
                        bytemuck::cast_slice(&indices),
                        wgpu::BufferUsages::INDEX,
                    ),
                    count: indices.len() as u32,
                }
            }
            Variant::Screen => FramePasses::Screen {
                bind: water_bind(&self.screen, "procedural screen"),
            },
            Variant::Texture => {
                let t = setup.target as u32;
                ctx.check_texture_size("procedural texture-space target", t, t)?;
                let mips = setup.mip_levels() as u32;
                let target = ctx.texture_mips(
                    "procedural target",
                    (t, t),
                    mips,
                    self.chain_format,
                    U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
                );
                let texel = self.chain_format.block_copy_size(None).unwrap_or(16) as u64;
                bytes += (0..mips)
                    .map(|k| ((t >> k) as u64).pow(2) * texel)
                    .sum::<u64>();
                let levels: Vec<_> = (0..mips).map(|k| mip_view(&target, k)).collect();
                let downsample = (1..mips as usize)
                    .map(|k| {
                        self.downsample
                            .bind(ctx, "procedural downsample", &[&levels[k - 1]])
                    })
                    .collect();
                let address = if setup.wrap {
                    wgpu::AddressMode::Repeat
                } else {
                    wgpu::AddressMode::ClampToEdge
                };
                let sampler = ctx.create_sampler(&wgpu::SamplerDescriptor {
                    label: Some("procedural mips"),
                    address_mode_u: address,
                    address_mode_v: address,
                    address_mode_w: address,
                    mag_filter: wgpu::FilterMode::Linear,
                    min_filter: wgpu::FilterMode::Linear,
                    mipmap_filter: wgpu::MipmapFilterMode::Linear,
                    // The paper's anisotropic filtering: 16 by default (all filters linear).
                    anisotropy_clamp: setup.anisotropy as u16,
                    ..Default::default()
                });
                let all = target.create_view(&Default::default());
                let resample = self.resample.bind_at(
                    ctx,
                    "procedural resample",
                    &[(0, &uniform), (3, &all), (4, &sampler)],
                );
                FramePasses::Texture {
                    target: water_bind(&self.target, "procedural target"),
                    levels,
                    downsample,
                    resample,
                }
            }
        };
        let receivers = match &setup.receivers {
            Some(r) => Some(
                self.lookup
                    .frame(ctx, &r.0, &map, setup.wrap, setup.absorption)?,
            ),
            None => None,
        };
        bytes += receivers.as_ref().map_or(0, |r| r.bytes());
        ctx.check()?;
        Ok(ProceduralFrame {
            uniform,
            heights: None,
            wave,
            map,
            map_view,
            receivers,
            setup: setup.clone(),
            passes,
            bytes,
        })
    }

    /// Record the variant's passes for `frame`, and the receivers' lookup over a terrain. Returns
    /// the texture the floor map ends in.
    pub fn encode<'f>(
        &self,
        frame: &'f ProceduralFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) -> &'f wgpu::Texture {
        match &frame.passes {
            FramePasses::Vertex {
                bind,
                indices,
                count,
            } => {
                let mut pass = begin_render(
                    encoder,
                    &mut timer,
                    "procedural vertex",
                    &[&frame.map_view],
                    true,
                );
                pass.set_pipeline(&self.vertex);
                pass.set_bind_group(0, bind, &[]);
                pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..*count, 0, 0..1);
            }
            FramePasses::Screen { bind } => {
                let mut pass = begin_render(
                    encoder,
                    &mut timer,
                    "procedural screen",
                    &[&frame.map_view],
                    true,
                );
                pass.set_pipeline(&self.screen);
                pass.set_bind_group(0, bind, &[]);
                pass.draw(0..3, 0..1);
            }
            FramePasses::Texture {
                target,
                levels,
                downsample,
                resample,
            } => {
                {
                    let mut pass = begin_render(
                        encoder,
                        &mut timer,
                        "procedural target",
                        &[&levels[0]],
                        true,
                    );
                    pass.set_pipeline(&self.target);
                    pass.set_bind_group(0, target, &[]);
                    pass.draw(0..3, 0..1);
                }
                for (k, bind) in downsample.iter().enumerate() {
                    let mut pass = begin_render(
                        encoder,
                        &mut timer,
                        "procedural downsample",
                        &[&levels[k + 1]],
                        true,
                    );
                    pass.set_pipeline(&self.downsample);
                    pass.set_bind_group(0, bind, &[]);
                    pass.draw(0..3, 0..1);
                }
                let mut pass = begin_render(
                    encoder,
                    &mut timer,
                    "procedural resample",
                    &[&frame.map_view],
                    true,
                );
                pass.set_pipeline(&self.resample);
                pass.set_bind_group(0, resample, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        if let Some(r) = &frame.receivers {
            self.lookup.encode(r, encoder, timer);
        }
        frame.floor_map()
    }

    /// Run the technique once and read the map back, writing each pass's timestamps into `timer`
    /// when there is one (resolved in the same submission; read them with [`GpuTimer::read`]).
    pub fn caustics(
        &self,
        ctx: &GpuContext,
        setup: &ProceduralSetup,
        water: &SurfaceInput,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<CausticsMap, GpuError> {
        let frame = self.frame(ctx, setup, water)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let texture = self.encode(&frame, &mut encoder, timer.as_deref_mut());
        ctx.submit_timed(encoder, timer.as_deref());
        ctx.read_map(texture, setup.size)
    }
}
