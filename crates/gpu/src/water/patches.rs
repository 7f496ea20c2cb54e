//! The water's heights in Hermite form for the passes that sample the surface many times a pixel:
//! each texel's height and its central differences along u, v and across
//! (`water/water_patches.wgsl`), written once a frame, so that `grid_sample_hermite` reads the 4
//! texels around a point where `grid_sample`'s bicubic reads 16. Catmull-Rom is the cubic Hermite
//! spline on central differences, so the surface is the same (the CPU twins keep sampling their
//! grids bicubically). What it saves the passes that sample the water: docs/benchmarks.md.

use crate::pass::{Bind, STORAGE_OUT, begin_compute, compute_pipeline};
use crate::shaders::passes;
use crate::{GpuContext, GpuTimer};

passes! {
    WATER_PATCHES = "water patches", "water/water_patches.wgsl";
}

/// Mirrors `Patches` in `water/water_patches.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
struct PatchesUniform {
    wrap: u32,
    _pad: [u32; 3],
}

impl PatchesUniform {
    fn new(wrap: bool) -> Self {
        PatchesUniform {
            wrap: wrap as u32,
            _pad: [0; 3],
        }
    }
}

/// The pass's pipeline, built once per device.
#[derive(Clone)]
pub struct WaterPatches {
    pipeline: wgpu::ComputePipeline,
}

/// One heights texture's patches: an `Rgba32Float` texture of its size and the pass that fills it.
pub struct Patches {
    /// The `Rgba32Float` patches, one texel per height texel: the height, and its central
    /// differences (per texel) along u, along v and across; what `grid_sample_hermite` reads.
    pub view: wgpu::TextureView,
    uniform: wgpu::Buffer,
    wrap: bool,
    bind: wgpu::BindGroup,
    size: (u32, u32),
}

impl WaterPatches {
    /// Build the pass's pipeline for the device.
    pub fn new(ctx: &GpuContext) -> Self {
        WaterPatches {
            pipeline: compute_pipeline(ctx, &WATER_PATCHES),
        }
    }

    /// The patches of `heights` (periodic where `wrap`), filled by each [`encode`](Self::encode).
    pub fn frame(&self, ctx: &GpuContext, heights: &wgpu::TextureView, wrap: bool) -> Patches {
        let size = heights.texture().size();
        let view = ctx
            .texture_2d(
                "water patches",
                (size.width, size.height, 1),
                wgpu::TextureFormat::Rgba32Float,
                STORAGE_OUT,
            )
            .create_view(&Default::default());
        let uniform = ctx.uniform("water patches", &PatchesUniform::new(wrap));
        let bind = self
            .pipeline
            .bind(ctx, "water patches", &[&uniform, heights, &view]);
        Patches {
            view,
            uniform,
            wrap,
            bind,
            size: (size.width, size.height),
        }
    }

    /// Record the pass filling `patches` from its heights as they are now.
    pub fn encode(
        &self,
        patches: &Patches,
        encoder: &mut wgpu::CommandEncoder,
        timer: &mut Option<&mut GpuTimer>,
    ) {
        let mut pass = begin_compute(encoder, timer, WATER_PATCHES.name);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &patches.bind, &[]);
        pass.dispatch_workgroups(patches.size.0.div_ceil(8), patches.size.1.div_ceil(8), 1);
    }
}

impl Patches {
    /// The texels along each side: the heights texture's.
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// GPU memory, bytes: 16 a height texel.
    pub fn bytes(&self) -> u64 {
        self.size.0 as u64 * self.size.1 as u64 * 16
    }

    /// Take a new edge rule (a uniform write, only when it changes).
    pub fn set_wrap(&mut self, ctx: &GpuContext, wrap: bool) {
        if wrap != self.wrap {
            ctx.write_pod(&self.uniform, &PatchesUniform::new(wrap));
            self.wrap = wrap;
        }
    }
}
