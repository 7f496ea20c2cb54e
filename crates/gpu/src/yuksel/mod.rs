//! Technique `yuksel` on the GPU: "Fast Real-time Caustics from Height Fields" (Yuksel & Keyser).
//! The method, its passes and where it departs from the reference are documented with its CPU twin,
//! `caustics_core::techniques::yuksel`, which these passes mirror one for one:
//!
//! | pass | WGSL | CPU twin (`caustics_core::techniques::yuksel`, crates/core/src/techniques/yuksel/) |
//! |---|---|---|
//! | the heights in Hermite form (compute, one texel an invocation; [`crate::water::patches`]), which every ray reads | `water/water_patches.wgsl` | (the grid's bicubic sample) |
//! | region bound (compute, one texel an invocation) and region (one thread) | `yuksel/region_bound.wgsl`, `region.wgsl` | `region.rs`: `region_bound`, `YukselSetup::region_for` |
//! | pre-pass (compute: each pixel's tier, listing the pixels at k; their records, one listed pixel an invocation through an indirect dispatch; the spans) | `yuksel/prepass.wgsl`, `prepass_fill.wgsl`, `prepass_span.wgsl` + `sample.wgsl`, `fill.wgsl` | `prepass.rs`: `prepass` |
//! | pass 1 (fragment, multiple render targets) | `yuksel/pass1.wgsl` | `pass1.rs`: `pass1` |
//! | pass 2 (fragment) | `yuksel/pass2.wgsl` | `pass2.rs`: `pass2` (both passes: `caustics`, in `mod.rs`) |
//! | the scatter, the default `passes` (compute: each pixel's tier and records below k, listing the pixels at k; their records; the sums into the map) | `yuksel/scatter_tier.wgsl`, `scatter_fill.wgsl`, `scatter_resolve.wgsl` + `sample.wgsl`, `fill.wgsl`, `scatter.wgsl` | `scatter.rs`: `scatter_tier`, `scatter_fill`, `add_record`, `scatter_resolve` (all: `scatter`) |
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
//!
//! This file holds the passes' sources and the pipelines, and records a frame's passes
//! ([`Yuksel::encode`]); [`frame`] a frame's textures, buffers and bind groups and their sizes;
//! [`once`] the run-once path that uploads a height grid and reads the map back.

use std::collections::HashMap;
use std::sync::Mutex;

use caustics_core::techniques::yuksel::{Region, YukselSetup};

use crate::pass::{begin_compute, begin_render, compute_pipeline, pulled_pipeline, v4};
use crate::receivers::ReceiversUniform;
use crate::shaders::passes;
use crate::water::patches::WaterPatches;
use crate::{GpuContext, GpuError, GpuTimer};

pub mod frame;
pub mod once;
pub mod technique;

pub use frame::Frame;
use frame::{FramePasses, prepass_pixels};

passes! {
    PREPASS = "yuksel pre-pass", "yuksel/prepass.wgsl";
    PREPASS_FILL = "yuksel pre-pass fill", "yuksel/prepass_fill.wgsl";
    PREPASS_SPAN = "yuksel pre-pass span", "yuksel/prepass_span.wgsl";
    PASS2 = "yuksel pass 2", "yuksel/pass2.wgsl";
    REGION_BOUND = "yuksel region bound", "yuksel/region_bound.wgsl";
    REGION = "yuksel region", "yuksel/region.wgsl";
    SCATTER_TIER = "yuksel scatter tiers", "yuksel/scatter_tier.wgsl";
    SCATTER_FILL = "yuksel scatter fill", "yuksel/scatter_fill.wgsl";
    SCATTER_RESOLVE = "yuksel scatter resolve", "yuksel/scatter_resolve.wgsl";
    /// Pass 1's body: [`pass1_source`] adds the output struct and entry point for a draw's targets.
    PASS1 = "yuksel pass 1", "yuksel/pass1.wgsl";
}

/// Pass 1 for a draw that writes `targets` render targets: the static body plus the generated output
/// struct and entry point.
pub fn pass1_source(targets: u32) -> String {
    let mut s = PASS1.source.to_string();
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
    /// xyz: the unit direction the light travels, world frame; w: `η = 1 / ior`, air to water.
    pub light: [f32; 4],
    /// A map pixel's size along x and y, world units.
    pub pixel: [f32; 2],
    /// `h L'` of Eq. 1: from a floor point to its illumination centre on the rest surface, world
    /// units.
    pub centre_offset: [f32; 2],
    /// rgb: `exp(−K d0)` per channel, the absorption along the flat-water path that pass 2 applies
    /// (1 without the absorption option, or over receivers, whose lookup attenuates); w: `T(θ0)`,
    /// flat water's Fresnel transmittance for the sun (1 without the Fresnel option).
    pub attenuation: [f32; 4],
    /// Side of the floor's square `[0, size]²` the map covers, world units.
    pub size: f32,
    /// The water's rest depth above the floor, world units.
    pub depth: f32,
    /// The water's index of refraction.
    pub ior: f32,
    /// 1 with the Fresnel option: each sample's light weighted by `T(θi) / T(θ0)`; 0 without.
    pub fresnel: u32,
    /// The caustics map's width, texels.
    pub width: u32,
    /// The caustics map's height, texels.
    pub height: u32,
    /// `N`, the samples pass 1 takes along x (§4), given or the paper's 7; 0: the region pass
    /// chooses it from the water.
    pub n: u32,
    /// `M`, the neighbouring rows along y each sample's light reaches, in `M + 1` channels (§4),
    /// given or the paper's 6; `u32::MAX`: the region pass chooses it.
    pub m: u32,
    /// The heights' edge rule: 1 where they tile, 0 where they clamp.
    pub wrap: u32,
    /// Pass 1: the first of the `M + 1` channels this draw writes (four per target); 0 elsewhere.
    pub channel_base: u32,
    /// `k`, samples per map pixel along each axis.
    pub subsamples: u32,
    /// 1: each sample's light lands on its footprint; 0: on a box of the sample's size, the
    /// paper's pixel-sized square (§4).
    pub footprint: u32,
    /// Passes 1 and 2: the map's rows this draw serves, those equal to it modulo `2^level` of the
    /// frame's region (0 at level 0).
    pub phase: u32,
    /// [`YukselSetup::split`], or −1 where every pixel takes its `k × k` samples.
    pub split: f32,
    /// Tiles along x of the pre-pass texture's array ([`PrepassTiling`]); 0 where it is one.
    pub pre_tiles: u32,
    /// 1 where the pool's walls close the square ([`YukselSetup::walls`]).
    pub walls: u32,
    /// What the samples' light meets (the plane `z = 0` where `t0[3]` is 0).
    pub receivers: ReceiversUniform,
}

/// Mirrors `YukselRegion` in `yuksel/common.wgsl`: what the region pass writes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct YukselRegion {
    /// `N`: samples along x gathered per pixel, at column offsets `shift.x + [−N/2, N/2]`, in
    /// pixels of the level's map.
    pub n: u32,
    /// `M`: rows along y, at offsets `shift.y + [−M/2, M/2]`, in pixels of the level's map.
    pub m: u32,
    /// The region's shift along the refracted sun from a pixel's own sample (columns, rows), in
    /// pixels of the level's map.
    pub shift: [i32; 2],
    /// The samples are those of a map `2^level` times coarser; their light lands in the map's own
    /// pixels.
    pub level: u32,
    /// 1 where the bound asked for more than the largest `N` or `M` even at the coarsest level
    /// (light is lost), else 0.
    pub clamped: u32,
    /// Padding to the struct's 16-byte multiple.
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
            light: v4(s.light, s.eta),
            pixel: [s.pixel.x as f32, s.pixel.y as f32],
            centre_offset: [s.centre_offset.x as f32, s.centre_offset.y as f32],
            attenuation: v4(s.attenuation, s.t_flat),
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
            walls: s.walls as u32,
            receivers: ReceiversUniform::of(s.receivers.as_deref()),
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

    /// The array's layers, one per tile.
    pub fn layers(&self) -> u32 {
        self.tiles.0 * self.tiles.1
    }
}

/// The technique's pipelines, built once per device.
pub struct Yuksel {
    /// The heights in Hermite form, which every ray reads.
    patches: WaterPatches,
    /// The receivers' lookup of a frame over a terrain.
    lookup: crate::receivers::ReceiverLookup,
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
    let targets = vec![Some(MAP_FORMAT.into()); targets as usize];
    pulled_pipeline(ctx, label, module, &targets)
}

impl Yuksel {
    /// Build the compute and pass-2 pipelines, and take the render targets one pass-1 draw may
    /// write from the device's limits (at most 8); pass 1's pipelines are built per target count
    /// as they are first needed.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let limits = ctx.limits();
        let by_bytes = limits.max_color_attachment_bytes_per_sample / 16;
        let targets_per_draw = limits.max_color_attachments.min(by_bytes).clamp(1, 8);
        let pass2_module = PASS2.module(&ctx.device);
        let y = Yuksel {
            patches: WaterPatches::new(ctx),
            lookup: crate::receivers::ReceiverLookup::new(ctx),
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
                        let views: Vec<_> = views.iter().collect();
                        let mut pass =
                            begin_render(encoder, &mut timer, "yuksel pass 1", &views, true);
                        pass.set_pipeline(pipeline);
                        pass.set_bind_group(0, bind, &[]);
                        pass.draw(0..3, 0..1);
                    }
                    // Each phase writes its own rows and keeps the others'.
                    let mut pass =
                        begin_render(encoder, &mut timer, "yuksel pass 2", &[target], false);
                    pass.set_pipeline(&self.pass2);
                    pass.set_bind_group(0, &phase.pass2, &[]);
                    pass.draw(0..3, 0..1);
                }
            }
        }
        if let Some(r) = &frame.receivers {
            self.lookup.encode(r, encoder, timer);
        }
        frame.floor_map()
    }
}
