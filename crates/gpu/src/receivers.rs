//! The receivers on the GPU (docs/receivers.md): the light-space heights a technique's rays meet,
//! uploaded from [`ReceiverHeights`] once per terrain and sun, and the lookup pass that lights the
//! floor map's texels from a technique's light-space deposit (CPU twin:
//! `caustics_core::receivers::lookup`).

use std::sync::Arc;

use caustics_core::grid::Grid;
use caustics_core::receivers::{ReceiverHeights, floor_texels};

use crate::pass::{Bind, STORAGE_OUT, begin_compute, compute_pipeline, f4, float_texture};
use crate::shaders::passes;
use crate::{GpuContext, GpuError, GpuTimer};

passes! {
    LOOKUP = "receivers lookup", "receivers_lookup.wgsl";
}

/// Mirrors `Receivers` in `shaders/receivers.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ReceiversUniform {
    /// Light-space corner of texel (0, 0), texel side, the map's steepest slope.
    pub view: [f32; 4],
    /// The flat-water refracted sun; `w`: 1 where the receivers are met, 0 for the plane `z = 0`.
    pub t0: [f32; 4],
}

impl ReceiversUniform {
    /// `r`'s view, or the plane `z = 0` where there is none.
    pub fn of(r: Option<&ReceiverHeights>) -> Self {
        let Some(r) = r else {
            return Self::default();
        };
        let t = r.t0.as_vec3();
        ReceiversUniform {
            view: f4([r.origin.x, r.origin.y, r.texel, r.max_slope]),
            t0: [t.x, t.y, t.z, 1.0],
        }
    }
}

/// Mirrors `Lookup` in `receivers_lookup.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LookupUniform {
    /// Side of the square, 1 where the light wraps.
    pub floor: [f32; 4],
    /// `K` along the flat-water path to each receiver point (zero where the deposit carries its
    /// own absorption).
    pub absorption: [f32; 4],
}

/// The receivers' heights as an `R32Float` texture (1 x 1 and zero for the plane `z = 0`).
pub fn heights_texture(
    ctx: &GpuContext,
    r: Option<&ReceiverHeights>,
) -> Result<wgpu::Texture, GpuError> {
    let grid = match r {
        Some(r) => Grid {
            cols: r.cols,
            rows: r.rows,
            data: r.heights.clone(),
        },
        None => Grid::new(1, 1),
    };
    ctx.upload_grid("receivers' heights", &grid)
}

/// The lookup pass's pipeline.
pub struct ReceiverLookup {
    pipeline: wgpu::ComputePipeline,
}

/// One technique's receivers: the heights its rays meet, and the floor map the lookup writes from
/// its deposit.
pub struct ReceiverFrame {
    /// The receivers the frame was built for (their light-space window, `t0` and terrain).
    pub receivers: Arc<ReceiverHeights>,
    /// `receivers`' heights as an `R32Float` texture over their light-space window, world units
    /// ([`heights_texture`]).
    pub heights: wgpu::Texture,
    /// The floor map: `Rgba32Float`, the floor's texels.
    pub floor: wgpu::Texture,
    /// The technique's light-space deposit the lookup reads: flux per unit area of the plane
    /// `z = 0` along `t0`, over the floor map's window and size. A receiver anywhere (an engine's
    /// own meshes) looks its light up here as [`ReceiverLookup`] does for the floor's texels.
    pub deposit: wgpu::Texture,
    /// `K` per channel along each receiver point's flat-water path, zero where the deposit
    /// carries its own paths' absorption.
    pub absorption: glam::DVec3,
    /// Whether the deposit tiles.
    pub wrap: bool,
    bind: wgpu::BindGroup,
    /// Per floor texel: light-space point, share, flat-water path
    /// (`caustics_core::receivers::floor_texels`).
    texels: wgpu::Texture,
}

/// Mirrors `LightSpace` in `final_image/final_image_inputs.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LightSpaceUniform {
    /// The receivers' window and the refracted sun.
    pub receivers: ReceiversUniform,
    /// xyz: `K` along a receiver's flat-water path; w: 1 where the deposit tiles.
    pub absorption: [f32; 4],
}

/// A technique's light-space deposit and the receivers it met, objects among them: what the
/// final image's objects look their light up in (caustics-core's `LightSpace`).
#[derive(Clone, Copy, Debug)]
pub struct LightSpaceOutput<'a> {
    /// The deposit, on the floor map's window and size.
    pub deposit: &'a wgpu::Texture,
    /// The receivers' heights ([`heights_texture`]).
    pub heights: &'a wgpu::Texture,
    /// Where the heights lie, the absorption along a receiver's path, whether the deposit tiles.
    pub uniform: LightSpaceUniform,
}

impl LightSpaceUniform {
    /// For receivers `r` whose deposit attenuates by `absorption` along a receiver's path and
    /// tiles where `wrap`.
    pub fn of(r: &ReceiverHeights, absorption: glam::DVec3, wrap: bool) -> Self {
        LightSpaceUniform {
            receivers: ReceiversUniform::of(Some(r)),
            absorption: absorption.as_vec3().extend(wrap as u32 as f32).to_array(),
        }
    }
}

impl ReceiverFrame {
    /// The deposit for the objects among the receivers to look their light up in; `None` where
    /// there are no objects among them (the floor map holds all the light).
    pub fn light_space(&self) -> Option<LightSpaceOutput<'_>> {
        self.receivers.solids.as_ref()?;
        Some(LightSpaceOutput {
            deposit: &self.deposit,
            heights: &self.heights,
            uniform: LightSpaceUniform::of(&self.receivers, self.absorption, self.wrap),
        })
    }

    /// GPU memory of the frame's textures, bytes.
    pub fn bytes(&self) -> u64 {
        let texels = |t: &wgpu::Texture| (t.width() * t.height()) as u64;
        texels(&self.heights) * 4 + texels(&self.floor) * 16 + texels(&self.texels) * 16
    }
}

impl ReceiverLookup {
    /// Build the lookup pass's pipeline for the device.
    pub fn new(ctx: &GpuContext) -> Self {
        ReceiverLookup {
            pipeline: compute_pipeline(ctx, &LOOKUP),
        }
    }

    /// The receivers `r` met by a technique whose light-space deposit is `deposit` (the floor map's
    /// size and window), looked up into a floor map of the same size, attenuated by `absorption`
    /// along the flat-water path (`caustics_core::receivers::lookup`).
    pub fn frame(
        &self,
        ctx: &GpuContext,
        r: &Arc<ReceiverHeights>,
        deposit: &wgpu::Texture,
        wrap: bool,
        absorption: glam::DVec3,
    ) -> Result<ReceiverFrame, GpuError> {
        let heights = heights_texture(ctx, Some(r))?;
        let (w, h) = (deposit.width(), deposit.height());
        let floor_texels = floor_texels(r, w as usize, h as usize);
        let texels = float_texture(
            ctx,
            "receivers' floor texels",
            wgpu::TextureFormat::Rgba32Float,
            (w, h, 1),
            bytemuck::cast_slice(&floor_texels),
        )?;
        let floor = ctx.texture_2d(
            "floor map (receivers' lookup)",
            (w, h, 1),
            wgpu::TextureFormat::Rgba32Float,
            STORAGE_OUT,
        );
        let uniform = LookupUniform {
            floor: [r.size as f32, wrap as u32 as f32, 0.0, 0.0],
            absorption: absorption.as_vec3().extend(0.0).to_array(),
        };
        let buffer = ctx.uniform(LOOKUP.name, &uniform);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (d, tv, fv) = (view(deposit), view(&texels), view(&floor));
        let bind = self
            .pipeline
            .bind(ctx, LOOKUP.name, &[&buffer, &d, &tv, &fv]);
        Ok(ReceiverFrame {
            receivers: r.clone(),
            heights,
            floor,
            deposit: deposit.clone(),
            absorption,
            wrap,
            bind,
            texels,
        })
    }

    /// Record the lookup pass, writing `f`'s floor map from the deposit it was built on; run it
    /// after the technique's passes that fill the deposit.
    pub fn encode(
        &self,
        f: &ReceiverFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let mut pass = begin_compute(encoder, &mut timer, LOOKUP.name);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &f.bind, &[]);
        pass.dispatch_workgroups(f.floor.width().div_ceil(8), f.floor.height().div_ceil(8), 1);
    }
}
