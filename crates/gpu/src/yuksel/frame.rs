//! One frame's resources for a map and height-field size: the textures and buffers each variant's
//! passes read and write, sized for the largest region the region pass may choose
//! ([`YukselSetup::capacity`]), their bind groups, and the memory they take.

use caustics_core::grid::Grid;
use caustics_core::techniques::yuksel::YukselSetup;

use super::{MAP_FORMAT, PrepassTiling, Variant, Yuksel, YukselRegion, YukselUniform};
use crate::pass::{Bind, Binding, array_view, layer_view};
use crate::receivers::{ReceiverFrame, heights_texture};
use crate::water::patches::Patches;
use crate::{GpuContext, GpuError, WaterTextures};
use wgpu::BufferUsages as B;

/// One frame's resources for a given map and height-field size, bind groups included: a frame is
/// built once and encoded every time the water moves.
pub struct Frame {
    /// The heights it uploaded itself ([`Yuksel::frame`]); `None` when it reads the caller's
    /// ([`Yuksel::frame_with_water`]).
    heights: Option<wgpu::Texture>,
    /// Every uniform buffer with the channel base and row phase it carries (one per pass-1 and
    /// pass-2 draw).
    uniforms: Vec<(wgpu::Buffer, u32, u32)>,
    /// This frame's gather region ([`YukselRegion`]), written by the region pass.
    pub region: wgpu::Buffer,
    pub(super) region_bind: wgpu::BindGroup,
    /// The floor hits' offset range over the heights (`region_bound.wgsl`), and the heights' size
    /// its dispatch covers.
    pub(super) bound: wgpu::Buffer,
    pub(super) bound_bind: wgpu::BindGroup,
    /// The heights in Hermite form, one texel per height texel.
    pub(super) patches: Patches,
    /// The fill's indirect dispatch and the count of the pixels at k its tier pass lists.
    pub(super) fill_args: wgpu::Buffer,
    pub(super) heights_size: wgpu::Extent3d,
    /// The map the passes write (`Rgba32Float`, relative irradiance in rgb): the floor map on the
    /// plane `z = 0`, the light-space deposit over receivers ([`Frame::floor_map`]).
    pub map: wgpu::Texture,
    pub(super) setup: YukselSetup,
    /// Which implementation the frame's passes run.
    pub variant: Variant,
    pub(super) passes: FramePasses,
    bytes: u64,
    /// The pre-pass texture's tiling (one tile for the scatter variant, which has no pre-pass texture).
    tiling: PrepassTiling,
    /// The terrain's receivers where the setup has them: the samples meet their heights, the map
    /// is the light's deposit, and the lookup writes the floor map.
    pub receivers: Option<ReceiverFrame>,
}

pub(super) enum FramePasses {
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
pub(super) struct Phase {
    /// Per pass-1 draw: its pipeline, bind group (with its own channel base) and target views.
    pub(super) draws: Vec<(
        wgpu::RenderPipeline,
        wgpu::BindGroup,
        Vec<wgpu::TextureView>,
    )>,
    pub(super) pass2: wgpu::BindGroup,
}

impl Frame {
    /// GPU memory this frame's textures and buffers take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// The setup the frame was built for, or last took by [`set_setup`](Self::set_setup).
    pub fn setup(&self) -> &YukselSetup {
        &self.setup
    }

    /// The floor map: the receivers' lookup where the frame has receivers, else the map.
    pub fn floor_map(&self) -> &wgpu::Texture {
        self.receivers.as_ref().map_or(&self.map, |r| &r.floor)
    }

    /// Whether `setup` fits this frame's textures (the same map size, largest region and samples
    /// per pixel),
    /// so that [`set_setup`](Self::set_setup) can take it.
    pub fn fits(&self, setup: &YukselSetup) -> bool {
        let key = |s: &YukselSetup| (s.width, s.height, s.capacity(), s.subsamples);
        key(setup) == key(&self.setup) && setup.receivers == self.setup.receivers
    }

    /// Take a new sun or depth (a setup that [`fits`](Self::fits)): uniform writes only.
    pub fn set_setup(&mut self, ctx: &GpuContext, setup: &YukselSetup) {
        debug_assert!(self.fits(setup));
        for (buffer, base, phase) in &self.uniforms {
            ctx.write_pod(
                buffer,
                &YukselUniform::tiled(setup, *base, *phase, &self.tiling),
            );
        }
        self.patches.set_wrap(ctx, setup.wrap);
        self.setup = setup.clone();
    }
}

impl Yuksel {
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
            let buffer = ctx.uniform(
                "yuksel uniform",
                &YukselUniform::tiled(setup, channel_base, phase, &tiling),
            );
            uniforms.push((buffer.clone(), channel_base, phase));
            buffer
        };
        let uniform = uniform_for(0, 0);
        let heights_view = &water.heights;
        let region = ctx.buffer(
            "yuksel region",
            std::mem::size_of::<YukselRegion>() as u64,
            B::STORAGE | B::COPY_SRC,
        );
        let bound = ctx.buffer("yuksel region bound", 16, B::STORAGE | B::COPY_DST);
        let bound_bind = self.region_bound.bind(
            ctx,
            "yuksel region bound",
            &[&uniform, heights_view, &bound],
        );
        let region_bind = self
            .region
            .bind(ctx, "yuksel region", &[&uniform, &bound, &region]);
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
        let receivers = match &setup.receivers {
            Some(r) => Some(
                self.lookup
                    .frame(ctx, &r.0, &map, setup.wrap, setup.absorption)?,
            ),
            None => None,
        };
        let receiver_heights = match &receivers {
            Some(r) => r.heights.create_view(&Default::default()),
            None => heights_texture(ctx, None)?.create_view(&Default::default()),
        };
        let with_receivers =
            |label, pipeline: &wgpu::ComputePipeline, resources: &[&dyn Binding]| {
                bind_with_receivers(ctx, label, pipeline, resources, &receiver_heights)
            };
        let mut bytes =
            (w * h) as u64 * 16 + uniform.size() + region.size() + water_patches.bytes();
        // The pixels at k, listed for the fill (at most every pixel of the largest region's
        // area), and the fill's indirect dispatch: x and the count cleared every frame, y and z 1.
        let list_bytes = (ew * eh) as u64 * 4;
        let fill_list = ctx.buffer("yuksel fill list", list_bytes, B::STORAGE);
        let fill_args = ctx.buffer_init(
            "yuksel fill dispatch",
            bytemuck::cast_slice(&[0u32, 1, 1, 0]),
            B::STORAGE | B::INDIRECT | B::COPY_DST,
        );
        bytes += list_bytes + fill_args.size();
        let passes = match variant {
            Variant::Scatter => {
                let sums = ctx.buffer(
                    "yuksel scatter sums",
                    (w * h) as u64 * 4,
                    B::STORAGE | B::COPY_DST,
                );
                bytes += sums.size();
                let [tier, fill, resolve] = &self.scatter;
                let with = |label, pipeline: &wgpu::ComputePipeline| {
                    with_receivers(
                        label,
                        pipeline,
                        &[&uniform, patches, &sums, &region, &fill_args, &fill_list],
                    )
                };
                let binds = [
                    with("yuksel scatter tiers", tier),
                    with("yuksel scatter fill", fill),
                    // The resolve reads neither the heights (1) nor the region (3).
                    resolve.bind_at(
                        ctx,
                        "yuksel scatter resolve",
                        &[(0, &uniform), (2, &sums), (4, &map_view)],
                    ),
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
                let pre_view = array_view(&pre);
                let prepass = [
                    with_receivers(
                        "yuksel pre-pass",
                        &self.prepass,
                        &[
                            &uniform,
                            patches,
                            &pre_view,
                            &region,
                            &extents_view,
                            &tiers_view,
                            &fill_args,
                            &fill_list,
                        ],
                    ),
                    with_receivers(
                        "yuksel pre-pass fill",
                        &self.prepass_fill,
                        &[
                            &uniform, patches, &pre_view, &region, &fill_args, &fill_list,
                        ],
                    ),
                    self.prepass_span.bind(
                        ctx,
                        "yuksel pre-pass span",
                        &[&uniform, &pre_view, &region, &tiers_view, &extents_view],
                    ),
                ];
                let channels_view = array_view(&channels);
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
                        let bind = pipeline.bind(
                            ctx,
                            "yuksel pass 1",
                            &[&draw_uniform, &pre_view, &region, &extents_view],
                        );
                        let views = (first..first + count)
                            .map(|layer| layer_view(&channels, layer))
                            .collect();
                        draws.push((pipeline, bind, views));
                        first += count;
                    }
                    let pass2_uniform = uniform_for(0, phase);
                    let pass2 = self.pass2.bind(
                        ctx,
                        "yuksel pass 2",
                        &[&pass2_uniform, &channels_view, &region],
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
            bytes: bytes + receivers.as_ref().map_or(0, |r| r.bytes()),
            tiling,
            receivers,
        })
    }
}

/// A bind group of `resources` at bindings 0, 1, ... and the receivers' heights at binding 8
/// (`sample.wgsl`'s), for the passes that refract the water's samples.
fn bind_with_receivers(
    ctx: &GpuContext,
    label: &str,
    pipeline: &wgpu::ComputePipeline,
    resources: &[&dyn Binding],
    receivers: &wgpu::TextureView,
) -> wgpu::BindGroup {
    let numbered = resources.iter().enumerate().map(|(k, &r)| (k as u32, r));
    let entries: Vec<_> = numbered.chain([(8, receivers as &dyn Binding)]).collect();
    pipeline.bind_at(ctx, label, &entries)
}

/// The pre-pass's pixels for the largest region at any level the setup may choose (level 0 has
/// the most): the map and the region's apron.
pub(super) fn prepass_pixels(setup: &YukselSetup) -> (u32, u32) {
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
