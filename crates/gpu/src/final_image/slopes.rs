//! The pyramid of the water's slope moments on the GPU, which the final image reads when it
//! filters the waves' normals by each sample's footprint (`RenderOptions::filter_water`): the twin
//! of caustics-core's `SlopePyramid` (`water/slopes.rs`, where the filter is written down). Level 0
//! holds, per texel of the heights' lattice, the moments of the surface's slope over the texel
//! (`final_image/water_slopes_base.wgsl`); each level above averages 2 x 2 of the one below
//! (`final_image/water_slopes_halve.wgsl`), up to one texel. All levels lie in one storage buffer, five
//! floats a texel, level after level; the final image finds a level's place from the lattice
//! alone (`slope_level` in `final_image_rough_water.wgsl`).

use crate::pass::{Bind, compute_pipeline};
use crate::shaders::passes;
use crate::{GpuContext, GpuError};
use wgpu::BufferUsages as B;

passes! {
    WATER_SLOPES_BASE = "water slopes base", "final_image/water_slopes_base.wgsl";
    WATER_SLOPES_HALVE = "water slopes halve", "final_image/water_slopes_halve.wgsl";
}

/// The moments a texel holds: `E[h_x]`, `E[h_y]`, `E[h_x²]`, `E[h_y²]`, `E[h_x h_y]`.
pub const MOMENTS: usize = 5;

/// `@workgroup_size(8, 8)` of both passes.
const TILE: u32 = 8;

/// Mirrors `SlopeLevel` in `final_image/water_slopes.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct SlopeLevelUniform {
    size: f32,
    wrap: u32,
    offset: u32,
    cols: u32,
    rows: u32,
    below_offset: u32,
    below_cols: u32,
    below_rows: u32,
}

/// The columns and rows of each level of a `cols x rows` lattice's pyramid, finest first: each
/// level halves the one below, rounding up, down to one texel (`SlopePyramid::new`).
pub fn level_sizes(cols: u32, rows: u32) -> Vec<(u32, u32)> {
    let mut sizes = vec![(cols.max(1), rows.max(1))];
    while let Some(&(c, r)) = sizes.last().filter(|&&(c, r)| c > 1 || r > 1) {
        sizes.push((c.div_ceil(2), r.div_ceil(2)));
    }
    sizes
}

/// The two pipelines, built once per device.
#[derive(Clone)]
pub struct SlopePipelines {
    base: wgpu::ComputePipeline,
    halve: wgpu::ComputePipeline,
}

/// One heights texture's pyramid: the buffer and one dispatch a level, made once; recording them
/// creates nothing.
pub struct SlopePyramid {
    pipelines: SlopePipelines,
    pub(super) moments: wgpu::Buffer,
    levels: Vec<(wgpu::BindGroup, (u32, u32))>,
    /// Each level's uniform; level 0's holds the edge rule.
    uniforms: Vec<wgpu::Buffer>,
    base: SlopeLevelUniform,
}

impl SlopePipelines {
    /// Build the base and halving pipelines.
    pub fn new(ctx: &GpuContext) -> Self {
        SlopePipelines {
            base: compute_pipeline(ctx, &WATER_SLOPES_BASE),
            halve: compute_pipeline(ctx, &WATER_SLOPES_HALVE),
        }
    }

    /// The pyramid of the surface whose Hermite patches are `patches` (`cols x rows` texels over
    /// the water's square `size`, periodic when `wrap`).
    pub fn pyramid(
        &self,
        ctx: &GpuContext,
        patches: &wgpu::TextureView,
        (cols, rows): (u32, u32),
        size: f64,
        wrap: bool,
    ) -> Result<SlopePyramid, GpuError> {
        let sizes = level_sizes(cols, rows);
        let texels: u64 = sizes.iter().map(|&(c, r)| c as u64 * r as u64).sum();
        let bytes = texels * (MOMENTS * 4) as u64;
        ctx.check_buffer_size("water slope moments", bytes)?;
        let moments = ctx.buffer("water slope moments", bytes, B::STORAGE | B::COPY_SRC);
        let mut uniforms = Vec::with_capacity(sizes.len());
        let mut levels = Vec::with_capacity(sizes.len());
        let (mut offset, mut below) = (0u32, (0u32, 0u32, 0u32));
        let mut base = SlopeLevelUniform::default();
        for (k, &(c, r)) in sizes.iter().enumerate() {
            let level = SlopeLevelUniform {
                size: size as f32,
                wrap: wrap as u32,
                offset,
                cols: c,
                rows: r,
                below_offset: below.0,
                below_cols: below.1,
                below_rows: below.2,
            };
            let uniform = ctx.uniform("water slope level", &level);
            let group = if k == 0 {
                self.base
                    .bind(ctx, WATER_SLOPES_BASE.name, &[&uniform, patches, &moments])
            } else {
                self.halve
                    .bind(ctx, WATER_SLOPES_HALVE.name, &[&uniform, &moments])
            };
            if k == 0 {
                base = level;
            }
            uniforms.push(uniform);
            levels.push((group, (c, r)));
            below = (offset, c, r);
            offset += c * r;
        }
        Ok(SlopePyramid {
            pipelines: self.clone(),
            moments,
            levels,
            uniforms,
            base,
        })
    }
}

impl SlopePyramid {
    /// Record the levels, finest first, into `pass`; each dispatch reads the one before.
    pub fn encode(&self, pass: &mut wgpu::ComputePass) {
        for (k, (group, (c, r))) in self.levels.iter().enumerate() {
            let pipeline = if k == 0 {
                &self.pipelines.base
            } else {
                &self.pipelines.halve
            };
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(c.div_ceil(TILE), r.div_ceil(TILE), 1);
        }
    }

    /// Take a new edge rule (a uniform write, only when it changes), as the patches do.
    pub fn set_wrap(&mut self, ctx: &GpuContext, wrap: bool) {
        if (self.base.wrap != 0) != wrap {
            self.base.wrap = wrap as u32;
            ctx.write_pod(&self.uniforms[0], &self.base);
        }
    }

    /// The lattice of level 0.
    pub fn lattice(&self) -> (u32, u32) {
        self.levels[0].1
    }

    /// Every level's texels, finest first: for tests against `SlopePyramid`. A readback.
    pub fn read(&self, ctx: &GpuContext) -> Result<Vec<Vec<[f32; MOMENTS]>>, GpuError> {
        let all: Vec<f32> = ctx.read_buffer(&self.moments)?;
        let mut rest = &all[..];
        Ok(self
            .levels
            .iter()
            .map(|(_, (c, r))| {
                let (level, tail) = rest.split_at((c * r) as usize * MOMENTS);
                rest = tail;
                level
                    .chunks_exact(MOMENTS)
                    .map(|m| std::array::from_fn(|k| m[k]))
                    .collect()
            })
            .collect())
    }
}
