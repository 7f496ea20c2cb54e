//! Technique `yuksel` on the GPU: "Fast Real-time Caustics from Height Fields" (Yuksel & Keyser).
//! The method, its passes and where it departs from the reference are documented with its CPU twin,
//! `caustics_core::techniques::yuksel`, which these passes mirror one for one:
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | the heights in Hermite form (compute, one texel an invocation; [`crate::water::patches`]), which every ray reads | `water/water_patches.wgsl` | (the grid's bicubic sample) |
//! | region bound (compute, one texel an invocation) and region (one thread) | `yuksel/region_bound.wgsl`, `region.wgsl` | `YukselSetup::region_for` |
//! | pre-pass (compute: each pixel's tier, listing the pixels at k; their records, one listed pixel an invocation through an indirect dispatch; the spans) | `yuksel/prepass.wgsl`, `prepass_fill.wgsl`, `prepass_span.wgsl` + `sample.wgsl`, `fill.wgsl` | `prepass` |
//! | pass 1 (fragment, multiple render targets) | `yuksel/pass1.wgsl` | `pass1` |
//! | pass 2 (fragment) | `yuksel/pass2.wgsl` | `pass2` |
//! | the scatter, the default `passes` (compute: each pixel's tier and records below k, listing the pixels at k; their records; the sums into the map) | `yuksel/scatter_tier.wgsl`, `scatter_fill.wgsl`, `scatter_resolve.wgsl` + `sample.wgsl`, `fill.wgsl`, `scatter.wgsl` | `caustics` |
//!
//! Pass 1 writes `M + 1` channels into the layers of one `Rgba32Float` array texture, four per
//! layer, as many layers per draw as the adapter's colour-attachment limits allow (8 targets and
//! 128 bytes per sample give all 32 channels in one draw, as the paper's MRT design intends); with
//! fewer it draws again for the remaining layers.
//!
//! The region pass chooses the gather region (N, M and its shift along the refracted sun) on the
//! GPU from the heights, every frame, into a small storage buffer every later pass reads: the
//! textures are allocated once for the largest region ([`YukselSetup::capacity`]), and the
//! passes' loops run over this frame's region only.

use std::collections::HashMap;
use std::sync::Mutex;

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::yuksel::{Region, YukselSetup};

use crate::pass::{begin_compute, bind_group, compute_pipeline};
use crate::shaders::{OPTICS, PassSource, REDUCE, WATER};
use crate::water::patches::{Patches, WaterPatches};
use crate::{GpuContext, GpuError, GpuTimer, WaterTextures};

pub mod technique;

const COMMON: &str = include_str!("common.wgsl");
const SAMPLE: &str = include_str!("sample.wgsl");
const FILL: &str = include_str!("fill.wgsl");

pub const PREPASS: PassSource = PassSource {
    name: "yuksel pre-pass",
    shared: &[OPTICS, WATER, COMMON, SAMPLE, FILL],
    file: "yuksel/prepass.wgsl",
    source: include_str!("prepass.wgsl"),
};
pub const PREPASS_FILL: PassSource = PassSource {
    name: "yuksel pre-pass fill",
    shared: &[OPTICS, WATER, COMMON, SAMPLE, FILL],
    file: "yuksel/prepass_fill.wgsl",
    source: include_str!("prepass_fill.wgsl"),
};
pub const PREPASS_SPAN: PassSource = PassSource {
    name: "yuksel pre-pass span",
    shared: &[COMMON],
    file: "yuksel/prepass_span.wgsl",
    source: include_str!("prepass_span.wgsl"),
};
pub const PASS2: PassSource = PassSource {
    name: "yuksel pass 2",
    shared: &[COMMON],
    file: "yuksel/pass2.wgsl",
    source: include_str!("pass2.wgsl"),
};
pub const REGION_BOUND: PassSource = PassSource {
    name: "yuksel region bound",
    shared: &[OPTICS, COMMON, REDUCE],
    file: "yuksel/region_bound.wgsl",
    source: include_str!("region_bound.wgsl"),
};
pub const REGION: PassSource = PassSource {
    name: "yuksel region",
    shared: &[OPTICS, COMMON, REDUCE],
    file: "yuksel/region.wgsl",
    source: include_str!("region.wgsl"),
};
const SCATTER: &str = include_str!("scatter.wgsl");
pub const SCATTER_TIER: PassSource = PassSource {
    name: "yuksel scatter tiers",
    shared: &[OPTICS, WATER, COMMON, SAMPLE, FILL, SCATTER],
    file: "yuksel/scatter_tier.wgsl",
    source: include_str!("scatter_tier.wgsl"),
};
pub const SCATTER_FILL: PassSource = PassSource {
    name: "yuksel scatter fill",
    shared: &[OPTICS, WATER, COMMON, SAMPLE, FILL, SCATTER],
    file: "yuksel/scatter_fill.wgsl",
    source: include_str!("scatter_fill.wgsl"),
};
pub const SCATTER_RESOLVE: PassSource = PassSource {
    name: "yuksel scatter resolve",
    shared: &[OPTICS, WATER, COMMON, SAMPLE, SCATTER],
    file: "yuksel/scatter_resolve.wgsl",
    source: include_str!("scatter_resolve.wgsl"),
};
/// Pass 1's body: [`pass1_source`] adds the output struct and entry point for a draw's targets.
pub const PASS1: PassSource = PassSource {
    name: "yuksel pass 1",
    shared: &[COMMON],
    file: "yuksel/pass1.wgsl",
    source: include_str!("pass1.wgsl"),
};

/// Every pass of the technique, for its registry entry.
pub const PASSES: &[&PassSource] = &[
    &PREPASS,
    &PREPASS_FILL,
    &PREPASS_SPAN,
    &PASS1,
    &PASS2,
    &REGION_BOUND,
    &REGION,
    &SCATTER_TIER,
    &SCATTER_FILL,
    &SCATTER_RESOLVE,
];

/// Pass 1 for a draw that writes `targets` render targets: the static body plus the generated output
/// struct and entry point.
pub fn pass1_source(targets: u32) -> String {
    let mut s = PASS1.composed();
    s.push_str("\nstruct Pass1Out {\n");
    for t in 0..targets {
        s.push_str(&format!("    @location({t}) c{t}: vec4<f32>,\n"));
    }
    s.push_str("}\n\n@fragment\nfn fs_main(@builtin(position) frag: vec4<f32>) -> Pass1Out {\n");
    s.push_str(&format!(
        "    let v = pass1_channels(i32(frag.x), i32(frag.y), {});\n    var o: Pass1Out;\n",
        4 * targets
    ));
    for t in 0..targets {
        let k = 4 * t;
        s.push_str(&format!(
            "    o.c{t} = vec4<f32>(v[{}], v[{}], v[{}], v[{}]);\n",
            k,
            k + 1,
            k + 2,
            k + 3
        ));
    }
    s.push_str("    return o;\n}\n");
    s
}

/// Which GPU implementation to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    /// The paper's: pre-pass, pass 1 into multiple render targets, pass 2.
    RenderTargets,
    /// Ours (`yuksel`'s default passes): each record added into the map's pixels its box covers
    /// where it is made, with integer atomics: no pre-pass texture, no render targets.
    Scatter,
}

/// Mirrors `Yuksel` in `yuksel/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct YukselUniform {
    pub light: [f32; 4],
    pub pixel: [f32; 2],
    pub centre_offset: [f32; 2],
    pub attenuation: [f32; 4],
    pub size: f32,
    pub depth: f32,
    pub ior: f32,
    pub fresnel: u32,
    pub width: u32,
    pub height: u32,
    pub n: u32,
    pub m: u32,
    pub wrap: u32,
    pub channel_base: u32,
    pub subsamples: u32,
    pub footprint: u32,
    pub phase: u32,
    /// [`YukselSetup::split`], or −1 where every pixel takes its `k × k` samples.
    pub split: f32,
    /// Tiles along x of the pre-pass texture's array ([`PrepassTiling`]); 0 where it is one.
    pub pre_tiles: u32,
    pub _pad: u32,
}

/// Mirrors `YukselRegion` in `yuksel/common.wgsl`: what the region pass writes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct YukselRegion {
    pub n: u32,
    pub m: u32,
    pub shift: [i32; 2],
    pub level: u32,
    pub clamped: u32,
    pub _pad: [u32; 2],
}

impl From<YukselRegion> for Region {
    fn from(r: YukselRegion) -> Region {
        Region {
            n: r.n as usize,
            m: r.m as usize,
            shift: r.shift,
            level: r.level,
            clamped: r.clamped != 0,
        }
    }
}

impl YukselUniform {
    /// `n` = 0 and `m` = `u32::MAX` ask the region pass to choose them from the water.
    pub fn new(s: &YukselSetup, channel_base: u32, phase: u32) -> Self {
        YukselUniform {
            light: [
                s.light.x as f32,
                s.light.y as f32,
                s.light.z as f32,
                s.eta as f32,
            ],
            pixel: [s.pixel.x as f32, s.pixel.y as f32],
            centre_offset: [s.centre_offset.x as f32, s.centre_offset.y as f32],
            attenuation: [
                s.attenuation.x as f32,
                s.attenuation.y as f32,
                s.attenuation.z as f32,
                s.t_flat as f32,
            ],
            size: s.size as f32,
            depth: s.depth as f32,
            ior: s.ior as f32,
            fresnel: s.fresnel as u32,
            width: s.width as u32,
            height: s.height as u32,
            n: s.fixed.0.unwrap_or(0),
            m: s.fixed.1.unwrap_or(u32::MAX),
            wrap: s.wrap as u32,
            channel_base,
            subsamples: s.subsamples as u32,
            footprint: s.footprint as u32,
            phase,
            split: s.split.map_or(-1.0, |v| v as f32),
            pre_tiles: 0,
            _pad: 0,
        }
    }

    /// The uniform of a frame whose pre-pass texture is tiled as `tiling` says.
    fn tiled(s: &YukselSetup, channel_base: u32, phase: u32, tiling: &PrepassTiling) -> Self {
        YukselUniform {
            pre_tiles: if tiling.layers() == 1 {
                0
            } else {
                tiling.tiles.0
            },
            ..Self::new(s, channel_base, phase)
        }
    }
}

/// How the pre-pass texture, `k × k` texels per pixel of the map and its region's apron (8,432 a
/// side for a 2048² map at the default `k` = 4), is cut into the layers of an array where it is
/// wider or taller than the device allows (WebGPU's default and many browsers: 8,192): the fewest
/// equal tiles along each axis that fit, tile `(i, j)` in layer `j · tiles.x + i` (ours; one
/// layer where the texture fits). The shaders find a texel with `pre_texel` (common.wgsl).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PrepassTiling {
    /// Tiles along x and y.
    pub tiles: (u32, u32),
    /// One tile's (layer's) size.
    pub tile: (u32, u32),
}

impl PrepassTiling {
    /// The tiling of a `width` x `height` pre-pass texture on a device whose textures are at most
    /// `max` a side.
    pub fn new((width, height): (u32, u32), max: u32) -> Self {
        let tiles = (width.div_ceil(max.max(1)), height.div_ceil(max.max(1)));
        PrepassTiling {
            tiles,
            tile: (width.div_ceil(tiles.0), height.div_ceil(tiles.1)),
        }
    }

    pub fn layers(&self) -> u32 {
        self.tiles.0 * self.tiles.1
    }
}

/// The technique's pipelines, built once per device.
pub struct Yuksel {
    /// The heights in Hermite form, which every ray reads.
    patches: WaterPatches,
    region: wgpu::ComputePipeline,
    region_bound: wgpu::ComputePipeline,
    prepass: wgpu::ComputePipeline,
    prepass_fill: wgpu::ComputePipeline,
    prepass_span: wgpu::ComputePipeline,
    pass2: wgpu::RenderPipeline,
    /// The scatter variant's tiers, fill and resolve.
    scatter: [wgpu::ComputePipeline; 3],
    /// Pass 1 per number of targets per draw.
    pass1: Mutex<HashMap<u32, wgpu::RenderPipeline>>,
    /// Render targets one pass-1 draw may write on this device.
    pub targets_per_draw: u32,
}

const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

fn render_pipeline(
    ctx: &GpuContext,
    label: &str,
    module: &wgpu::ShaderModule,
    targets: u32,
) -> wgpu::RenderPipeline {
    let target = Some(wgpu::ColorTargetState {
        format: MAP_FORMAT,
        blend: None,
        write_mask: wgpu::ColorWrites::ALL,
    });
    let targets: Vec<_> = (0..targets).map(|_| target.clone()).collect();
    ctx.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// One frame's resources for a given map and height-field size, bind groups included: a frame is
/// built once and encoded every time the water moves (upload new heights with
/// [`Frame::update_heights`]).
pub struct Frame {
    /// The heights it uploaded itself ([`Yuksel::frame`]); `None` when it reads the caller's
    /// ([`Yuksel::frame_with_water`]).
    heights: Option<wgpu::Texture>,
    /// Every uniform buffer with the channel base and row phase it carries (one per pass-1 and
    /// pass-2 draw).
    uniforms: Vec<(wgpu::Buffer, u32, u32)>,
    /// This frame's gather region ([`YukselRegion`]), written by the region pass.
    pub region: wgpu::Buffer,
    region_bind: wgpu::BindGroup,
    /// The floor hits' offset range over the heights (`region_bound.wgsl`), and the heights' size
    /// its dispatch covers.
    bound: wgpu::Buffer,
    bound_bind: wgpu::BindGroup,
    /// The heights in Hermite form, one texel per height texel.
    patches: Patches,
    /// The fill's indirect dispatch and the count of the pixels at k its tier pass lists.
    fill_args: wgpu::Buffer,
    heights_size: wgpu::Extent3d,
    pub map: wgpu::Texture,
    setup: YukselSetup,
    pub variant: Variant,
    passes: FramePasses,
    bytes: u64,
    /// The pre-pass texture's tiling (one tile for the scatter variant, which has no pre-pass texture).
    tiling: PrepassTiling,
}

enum FramePasses {
    Scatter {
        /// One fixed-point sum per map pixel, cleared every frame.
        sums: wgpu::Buffer,
        /// Tiers, fill, resolve.
        binds: [wgpu::BindGroup; 3],
    },
    RenderTargets {
        /// The pre-pass's three passes: tiers, fill, span.
        prepass: [wgpu::BindGroup; 3],
        phases: Vec<Phase>,
        /// The map.
        target: wgpu::TextureView,
    },
}

/// The draws of one row phase: the map's rows `phase` modulo `2^level`.
struct Phase {
    /// Per pass-1 draw: its pipeline, bind group (with its own channel base) and target views.
    draws: Vec<(
        wgpu::RenderPipeline,
        wgpu::BindGroup,
        Vec<wgpu::TextureView>,
    )>,
    pass2: wgpu::BindGroup,
}

impl Frame {
    /// GPU memory this frame's textures and buffers take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Replace the height field (same size) for the next encode, in a frame that uploaded its own.
    pub fn update_heights(&self, ctx: &GpuContext, heights: &Grid) {
        if let Some(t) = &self.heights {
            ctx.write_grid(t, heights);
        }
    }

    pub fn setup(&self) -> &YukselSetup {
        &self.setup
    }

    /// Whether `setup` fits this frame's textures (the same map size, largest region and samples
    /// per pixel),
    /// so that [`set_setup`](Self::set_setup) can take it.
    pub fn fits(&self, setup: &YukselSetup) -> bool {
        let key = |s: &YukselSetup| (s.width, s.height, s.capacity(), s.subsamples);
        key(setup) == key(&self.setup)
    }

    /// Take a new sun or depth (a setup that [`fits`](Self::fits)): uniform writes only.
    pub fn set_setup(&mut self, ctx: &GpuContext, setup: &YukselSetup) {
        debug_assert!(self.fits(setup));
        for (buffer, base, phase) in &self.uniforms {
            ctx.write_buffer(
                buffer,
                0,
                bytemuck::bytes_of(&YukselUniform::tiled(setup, *base, *phase, &self.tiling)),
            );
        }
        self.patches.set_wrap(ctx, setup.wrap);
        self.setup = setup.clone();
    }
}

impl Yuksel {
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let limits = ctx.limits();
        let by_bytes = limits.max_color_attachment_bytes_per_sample / 16;
        let targets_per_draw = limits.max_color_attachments.min(by_bytes).clamp(1, 8);
        let pass2_module = PASS2.module(&ctx.device);
        let y = Yuksel {
            patches: WaterPatches::new(ctx),
            region: compute_pipeline(ctx, &REGION),
            region_bound: compute_pipeline(ctx, &REGION_BOUND),
            prepass: compute_pipeline(ctx, &PREPASS),
            prepass_fill: compute_pipeline(ctx, &PREPASS_FILL),
            prepass_span: compute_pipeline(ctx, &PREPASS_SPAN),
            pass2: render_pipeline(ctx, "yuksel pass 2", &pass2_module, 1),
            scatter: [&SCATTER_TIER, &SCATTER_FILL, &SCATTER_RESOLVE]
                .map(|source| compute_pipeline(ctx, source)),
            pass1: Mutex::new(HashMap::new()),
            targets_per_draw,
        };
        ctx.check()?;
        Ok(y)
    }

    fn pass1_pipeline(&self, ctx: &GpuContext, targets: u32) -> wgpu::RenderPipeline {
        self.pass1
            .lock()
            .expect("pipeline cache")
            .entry(targets)
            .or_insert_with(|| {
                let module = ctx
                    .device
                    .create_shader_module(wgpu::ShaderModuleDescriptor {
                        label: Some("yuksel pass 1"),
                        source: wgpu::ShaderSource::Wgsl(pass1_source(targets).into()),
                    });
                render_pipeline(ctx, "yuksel pass 1", &module, targets)
            })
            .clone()
    }

    /// Allocate a frame's textures and bind groups for `variant` and upload the height field.
    pub fn frame(
        &self,
        ctx: &GpuContext,
        setup: &YukselSetup,
        heights: &Grid,
        variant: Variant,
    ) -> Result<Frame, GpuError> {
        let texture = ctx.upload_grid("yuksel height field", heights)?;
        let mut frame = self.frame_with_water(ctx, setup, &WaterTextures::of(&texture), variant)?;
        frame.heights = Some(texture);
        Ok(frame)
    }

    /// Allocate a frame's textures and bind groups for `variant`, reading the caller's heights
    /// (any grid size: the passes sample it bicubically, as the CPU twin samples its grid).
    pub fn frame_with_water(
        &self,
        ctx: &GpuContext,
        setup: &YukselSetup,
        water: &WaterTextures,
        variant: Variant,
    ) -> Result<Frame, GpuError> {
        use wgpu::BindingResource::TextureView as View;
        use wgpu::TextureUsages as U;
        let (w, h) = (setup.width as u32, setup.height as u32);
        // Sized for the largest region the region pass may choose.
        let (_, cap_m) = setup.capacity();
        let (pw, ph) = prepass_capacity(setup);
        let (p1w, p1h) = (setup.width, setup.height + cap_m);
        ctx.check_texture_size("yuksel caustics map", w, h)?;
        let limits = ctx.limits();
        let tiling = match variant {
            Variant::RenderTargets => {
                PrepassTiling::new((pw as u32, ph as u32), limits.max_texture_dimension_2d)
            }
            Variant::Scatter => PrepassTiling::new((1, 1), 1),
        };
        if tiling.layers() > limits.max_texture_array_layers {
            return Err(GpuError::TooLarge {
                what: "yuksel pre-pass texture".into(),
                size: format!("{pw} x {ph} ({} layers of tiles)", tiling.layers()),
                limit: format!(
                    "{} layers of 1 .. {} per side",
                    limits.max_texture_array_layers, limits.max_texture_dimension_2d
                ),
            });
        }
        // The pixels' spans and tiers: one texel per pixel of the map and its apron.
        let (ew, eh) = prepass_pixels(setup);
        match variant {
            Variant::RenderTargets => {
                ctx.check_texture_size("yuksel pass-1 targets", p1w as u32, p1h as u32)?;
                ctx.check_texture_size("yuksel pre-pass spans", ew, eh)?;
            }
            Variant::Scatter => {
                ctx.check_buffer_size("yuksel scatter sums", (w * h) as u64 * 4)?;
            }
        }
        ctx.check_buffer_size("yuksel fill list", (ew * eh) as u64 * 4)?;
        let mut uniforms = Vec::new();
        let mut uniform_for = |channel_base: u32, phase: u32| {
            let buffer = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("yuksel uniform"),
                contents: bytemuck::bytes_of(&YukselUniform::tiled(
                    setup,
                    channel_base,
                    phase,
                    &tiling,
                )),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
            uniforms.push((buffer.clone(), channel_base, phase));
            buffer
        };
        let uniform = uniform_for(0, 0);
        let heights_view = &water.heights;
        let region = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("yuksel region"),
            size: std::mem::size_of::<YukselRegion>() as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bound = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("yuksel region bound"),
            size: 16,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bound_bind = bind_group(
            ctx,
            "yuksel region bound",
            &self.region_bound.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                View(heights_view),
                bound.as_entire_binding(),
            ],
        );
        let region_bind = bind_group(
            ctx,
            "yuksel region",
            &self.region.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                bound.as_entire_binding(),
                region.as_entire_binding(),
            ],
        );
        let heights_size = heights_view.texture().size();
        let water_patches = self.patches.frame(ctx, heights_view, setup.wrap);
        let patches = &water_patches.view;
        let map = ctx.texture_2d(
            "yuksel map",
            (w, h, 1),
            MAP_FORMAT,
            U::RENDER_ATTACHMENT | U::STORAGE_BINDING | U::COPY_SRC | U::TEXTURE_BINDING,
        );
        let map_view = map.create_view(&Default::default());
        let mut bytes =
            (w * h) as u64 * 16 + uniform.size() + region.size() + water_patches.bytes();
        // The pixels at k, listed for the fill (at most every pixel of the largest region's
        // area), and the fill's indirect dispatch: x and the count cleared every frame, y and z 1.
        let list_bytes = (ew * eh) as u64 * 4;
        let fill_list = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("yuksel fill list"),
            size: list_bytes,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let fill_args = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("yuksel fill dispatch"),
            contents: bytemuck::cast_slice(&[0u32, 1, 1, 0]),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::INDIRECT
                | wgpu::BufferUsages::COPY_DST,
        });
        bytes += list_bytes + fill_args.size();
        let passes = match variant {
            Variant::Scatter => {
                let sums = ctx.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("yuksel scatter sums"),
                    size: (w * h) as u64 * 4,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                bytes += sums.size();
                let [tier, fill, resolve] = &self.scatter;
                let with = |label, pipeline: &wgpu::ComputePipeline| {
                    bind_group(
                        ctx,
                        label,
                        &pipeline.get_bind_group_layout(0),
                        &[
                            uniform.as_entire_binding(),
                            View(patches),
                            sums.as_entire_binding(),
                            region.as_entire_binding(),
                            fill_args.as_entire_binding(),
                            fill_list.as_entire_binding(),
                        ],
                    )
                };
                let binds = [
                    with("yuksel scatter tiers", tier),
                    with("yuksel scatter fill", fill),
                    // The resolve reads neither the heights (1) nor the region (3).
                    ctx.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("yuksel scatter resolve"),
                        layout: &resolve.get_bind_group_layout(0),
                        entries: &[
                            (0, uniform.as_entire_binding()),
                            (2, sums.as_entire_binding()),
                            (4, View(&map_view)),
                        ]
                        .map(|(binding, resource)| wgpu::BindGroupEntry { binding, resource }),
                    }),
                ];
                FramePasses::Scatter { sums, binds }
            }
            Variant::RenderTargets => {
                let layers = (cap_m as u32 + 1).div_ceil(4);
                let pre = ctx.texture_2d(
                    "yuksel pre-pass",
                    (tiling.tile.0, tiling.tile.1, tiling.layers()),
                    MAP_FORMAT,
                    U::STORAGE_BINDING | U::TEXTURE_BINDING,
                );
                let channels = ctx.texture_2d(
                    "yuksel pass-1 channels",
                    (p1w as u32, p1h as u32, layers),
                    MAP_FORMAT,
                    U::RENDER_ATTACHMENT | U::TEXTURE_BINDING,
                );
                // Each pixel's span along x and its tier, one texel per pixel of the pre-pass.
                let (ew, eh) = prepass_pixels(setup);
                let per_pixel = |label, format| {
                    ctx.texture_2d(
                        label,
                        (ew, eh, 1),
                        format,
                        U::STORAGE_BINDING | U::TEXTURE_BINDING,
                    )
                    .create_view(&Default::default())
                };
                let extents_view =
                    per_pixel("yuksel pre-pass extents", wgpu::TextureFormat::Rg32Float);
                let tiers_view = per_pixel("yuksel pre-pass tiers", wgpu::TextureFormat::R32Uint);
                bytes += tiling.tile.0 as u64 * tiling.tile.1 as u64 * tiling.layers() as u64 * 16
                    + (p1w * p1h) as u64 * layers as u64 * 16
                    + (ew * eh) as u64 * (8 + 4);
                tracing::debug!(
                    "yuksel frame {w}x{h}: pre-pass {pw}x{ph}, pass-1 channels {p1w}x{p1h}x{layers}, {:.1} MiB",
                    bytes as f64 / (1u64 << 20) as f64
                );
                let pre_view = pre.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2Array),
                    ..Default::default()
                });
                let prepass = [
                    bind_group(
                        ctx,
                        "yuksel pre-pass",
                        &self.prepass.get_bind_group_layout(0),
                        &[
                            uniform.as_entire_binding(),
                            View(patches),
                            View(&pre_view),
                            region.as_entire_binding(),
                            View(&extents_view),
                            View(&tiers_view),
                            fill_args.as_entire_binding(),
                            fill_list.as_entire_binding(),
                        ],
                    ),
                    bind_group(
                        ctx,
                        "yuksel pre-pass fill",
                        &self.prepass_fill.get_bind_group_layout(0),
                        &[
                            uniform.as_entire_binding(),
                            View(patches),
                            View(&pre_view),
                            region.as_entire_binding(),
                            fill_args.as_entire_binding(),
                            fill_list.as_entire_binding(),
                        ],
                    ),
                    bind_group(
                        ctx,
                        "yuksel pre-pass span",
                        &self.prepass_span.get_bind_group_layout(0),
                        &[
                            uniform.as_entire_binding(),
                            View(&pre_view),
                            region.as_entire_binding(),
                            View(&tiers_view),
                            View(&extents_view),
                        ],
                    ),
                ];
                let channels_view = channels.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2Array),
                    ..Default::default()
                });
                // Per row phase (one at level 0, up to 2^MAX_LEVEL where the water chooses the
                // level; phases past this frame's level draw nothing): pass 1, as many layers per
                // draw as the device allows, then pass 2 into the map's rows of that phase.
                let per_draw = self.targets_per_draw.min(layers);
                let mut phases = Vec::new();
                for phase in 0..setup.phases() {
                    let mut draws = Vec::new();
                    let mut first = 0;
                    while first < layers {
                        let count = per_draw.min(layers - first);
                        let pipeline = self.pass1_pipeline(ctx, count);
                        let draw_uniform = uniform_for(4 * first, phase);
                        let bind = bind_group(
                            ctx,
                            "yuksel pass 1",
                            &pipeline.get_bind_group_layout(0),
                            &[
                                draw_uniform.as_entire_binding(),
                                View(&pre_view),
                                region.as_entire_binding(),
                                View(&extents_view),
                            ],
                        );
                        let views = (first..first + count)
                            .map(|layer| {
                                channels.create_view(&wgpu::TextureViewDescriptor {
                                    dimension: Some(wgpu::TextureViewDimension::D2),
                                    base_array_layer: layer,
                                    array_layer_count: Some(1),
                                    ..Default::default()
                                })
                            })
                            .collect();
                        draws.push((pipeline, bind, views));
                        first += count;
                    }
                    let pass2_uniform = uniform_for(0, phase);
                    let pass2 = bind_group(
                        ctx,
                        "yuksel pass 2",
                        &self.pass2.get_bind_group_layout(0),
                        &[
                            pass2_uniform.as_entire_binding(),
                            View(&channels_view),
                            region.as_entire_binding(),
                        ],
                    );
                    phases.push(Phase { draws, pass2 });
                }
                FramePasses::RenderTargets {
                    prepass,
                    phases,
                    target: map_view,
                }
            }
        };
        ctx.check()?;
        Ok(Frame {
            heights: None,
            uniforms,
            region,
            region_bind,
            bound,
            bound_bind,
            patches: water_patches,
            fill_args,
            heights_size,
            map,
            setup: setup.clone(),
            variant,
            passes,
            bytes,
            tiling,
        })
    }

    /// Record the technique's passes for `frame`. Returns the texture the map ends in.
    pub fn encode<'f>(
        &self,
        frame: &'f Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) -> &'f wgpu::Texture {
        let (w, h) = (frame.setup.width as u32, frame.setup.height as u32);
        encoder.clear_buffer(&frame.bound, 0, None);
        // The fill's dispatch along x and its count; y and z stay 1.
        encoder.clear_buffer(&frame.fill_args, 0, Some(4));
        encoder.clear_buffer(&frame.fill_args, 12, Some(4));
        let size = frame.heights_size;
        self.patches.encode(&frame.patches, encoder, &mut timer);
        {
            let mut pass = begin_compute(encoder, &mut timer, "yuksel region bound");
            pass.set_pipeline(&self.region_bound);
            pass.set_bind_group(0, &frame.bound_bind, &[]);
            pass.dispatch_workgroups(size.width.div_ceil(16), size.height.div_ceil(16), 1);
        }
        {
            let mut pass = begin_compute(encoder, &mut timer, "yuksel region");
            pass.set_pipeline(&self.region);
            pass.set_bind_group(0, &frame.region_bind, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        match &frame.passes {
            FramePasses::Scatter { sums, binds } => {
                encoder.clear_buffer(sums, 0, None);
                let mut pass = begin_compute(encoder, &mut timer, "yuksel scatter");
                let [tier, fill, resolve] = &self.scatter;
                // One invocation per pixel of the level's map and apron; per listed pixel at k;
                // per map pixel.
                let (cols, rows) = prepass_pixels(&frame.setup);
                pass.set_pipeline(tier);
                pass.set_bind_group(0, &binds[0], &[]);
                pass.dispatch_workgroups(cols.div_ceil(8), rows.div_ceil(8), 1);
                pass.set_pipeline(fill);
                pass.set_bind_group(0, &binds[1], &[]);
                pass.dispatch_workgroups_indirect(&frame.fill_args, 0);
                pass.set_pipeline(resolve);
                pass.set_bind_group(0, &binds[2], &[]);
                pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
            }
            FramePasses::RenderTargets {
                prepass,
                phases,
                target,
            } => {
                {
                    let mut pass = begin_compute(encoder, &mut timer, "yuksel pre-pass");
                    pass.set_pipeline(&self.prepass);
                    pass.set_bind_group(0, &prepass[0], &[]);
                    // One invocation per pixel of the level's map and apron.
                    let (cols, rows) = prepass_pixels(&frame.setup);
                    pass.dispatch_workgroups(cols.div_ceil(8), rows.div_ceil(8), 1);
                    // The records of the pixels at k, one invocation per listed pixel.
                    pass.set_pipeline(&self.prepass_fill);
                    pass.set_bind_group(0, &prepass[1], &[]);
                    pass.dispatch_workgroups_indirect(&frame.fill_args, 0);
                    pass.set_pipeline(&self.prepass_span);
                    pass.set_bind_group(0, &prepass[2], &[]);
                    pass.dispatch_workgroups(cols.div_ceil(8), rows.div_ceil(8), 1);
                }
                for phase in phases {
                    for (pipeline, bind, views) in &phase.draws {
                        let attachments: Vec<_> = views
                            .iter()
                            .map(|v| color_attachment(v, wgpu::LoadOp::Clear(Default::default())))
                            .collect();
                        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                            label: Some("yuksel pass 1"),
                            color_attachments: &attachments,
                            depth_stencil_attachment: None,
                            timestamp_writes: timer
                                .as_mut()
                                .and_then(|t| t.render_pass("yuksel pass 1")),
                            occlusion_query_set: None,
                            multiview_mask: None,
                        });
                        pass.set_pipeline(pipeline);
                        pass.set_bind_group(0, bind, &[]);
                        pass.draw(0..3, 0..1);
                    }
                    // Each phase writes its own rows and keeps the others'.
                    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("yuksel pass 2"),
                        color_attachments: &[color_attachment(target, wgpu::LoadOp::Load)],
                        depth_stencil_attachment: None,
                        timestamp_writes: timer
                            .as_mut()
                            .and_then(|t| t.render_pass("yuksel pass 2")),
                        occlusion_query_set: None,
                        multiview_mask: None,
                    });
                    pass.set_pipeline(&self.pass2);
                    pass.set_bind_group(0, &phase.pass2, &[]);
                    pass.draw(0..3, 0..1);
                }
            }
        }
        &frame.map
    }

    /// The region the last encode of `frame` chose, read back (for tests and tools: it waits for
    /// the GPU).
    pub fn read_region(&self, ctx: &GpuContext, frame: &Frame) -> Result<Region, GpuError> {
        let r: Vec<YukselRegion> = ctx.read_buffer(&frame.region)?;
        Ok(r[0].into())
    }

    /// Run the technique once and read the map back.
    pub fn caustics(
        &self,
        ctx: &GpuContext,
        setup: &YukselSetup,
        heights: &Grid,
        variant: Variant,
    ) -> Result<CausticsMap, GpuError> {
        self.caustics_timed(ctx, setup, heights, variant, None)
    }

    /// As [`caustics`](Self::caustics), writing each pass's timestamps into `timer` (resolved in
    /// the same submission; read them with [`GpuTimer::read`]).
    pub fn caustics_timed(
        &self,
        ctx: &GpuContext,
        setup: &YukselSetup,
        heights: &Grid,
        variant: Variant,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<CausticsMap, GpuError> {
        let frame = self.frame(ctx, setup, heights, variant)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let texture = self.encode(&frame, &mut encoder, timer.as_deref_mut());
        if let Some(t) = timer {
            t.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        let texels: Vec<[f32; 4]> = ctx.read_texture(texture)?;
        Ok(CausticsMap {
            width: setup.width,
            height: setup.height,
            size: setup.size,
            texels: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}

/// The pre-pass's pixels for the largest region at any level the setup may choose (level 0 has
/// the most): the map and the region's apron.
fn prepass_pixels(setup: &YukselSetup) -> (u32, u32) {
    let (cap_n, cap_m) = setup.capacity();
    (
        (setup.width + cap_n - 1) as u32,
        (setup.height + cap_m) as u32,
    )
}

/// The pre-pass texture's size for the largest region at any level the setup may choose: the
/// level's `k × k` samples per pixel of the level's map and apron.
fn prepass_capacity(setup: &YukselSetup) -> (usize, usize) {
    let (cap_n, cap_m) = setup.capacity();
    let levels = setup.phases().trailing_zeros();
    (0..=levels).fold((0, 0), |(w, h), level| {
        let k = setup.subsamples_at(level);
        (
            w.max(((setup.width >> level) + cap_n - 1) * k),
            h.max(((setup.height >> level) + cap_m) * k),
        )
    })
}

fn color_attachment(
    view: &wgpu::TextureView,
    load: wgpu::LoadOp<wgpu::Color>,
) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load,
            store: wgpu::StoreOp::Store,
        },
    })
}
