//! A floor map's box-filter pyramid on the GPU (`map_mips.wgsl`, one dispatch a
//! level), the twin of caustics-core's `CausticsMap::pyramid`: level `L` is `max(1, size >> L)`
//! texels a side, each the mean of the 2 x 2 under it, so that a reader can take the map's mean
//! over a footprint of any size in a few taps (`MapPyramid::filtered`). The final image builds one
//! beside its floor map every frame; an application whose map texture has its own mip chain (the
//! Bevy plugin's material) fills that chain in place.

use caustics_core::map::pyramid_levels;

use crate::GpuContext;
use crate::pass::{Bind, begin_compute, compute_pipeline, mip_view};
use crate::shaders::passes;

passes! {
    /// One level of the caustics map's pyramid (caustics-core's `CausticsMap::pyramid`), which the
    /// final image reads over each sample's footprint on the floor.
    CAUSTICS_MIPS = "caustics mips", "map_mips.wgsl";
}

/// `map_mips.wgsl`'s workgroup side.
const TILE: u32 = 8;

/// The bind groups that write one map's pyramid, finest level first, each with the size of the
/// level it writes. Made once per map texture; recording them creates nothing.
pub struct MapMips {
    pipeline: wgpu::ComputePipeline,
    levels: Vec<(wgpu::BindGroup, (u32, u32))>,
    /// The texture the levels are written into (one for all of them).
    written: Option<wgpu::Texture>,
}

/// The compute pipeline every [`MapMips`] records: one per device is enough.
pub fn mips_pipeline(ctx: &GpuContext) -> wgpu::ComputePipeline {
    compute_pipeline(ctx, &CAUSTICS_MIPS)
}

/// An `Rgba32Float` texture of `levels` mips from `size`, which [`MapMips`] can write
/// (`STORAGE_BINDING` and `TEXTURE_BINDING`, and `usage`).
pub fn mip_chain(
    ctx: &GpuContext,
    label: &str,
    (width, height): (u32, u32),
    levels: u32,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING | usage;
    let format = wgpu::TextureFormat::Rgba32Float;
    ctx.texture_mips(label, (width, height), levels, format, usage)
}

impl MapMips {
    /// Levels 1 and above of the pyramid of `map` (`Rgba32Float`, level 0) into `mips`, whose mip
    /// `L − 1` is the pyramid's level `L` (`pyramid_levels(map) − 1` mips, `STORAGE_BINDING`).
    pub fn beside(
        ctx: &GpuContext,
        pipeline: &wgpu::ComputePipeline,
        map: &wgpu::Texture,
        mips: &wgpu::Texture,
    ) -> MapMips {
        let levels = (0..mips.mip_level_count())
            .map(|k| {
                let fine = if k == 0 {
                    mip_view(map, 0)
                } else {
                    mip_view(mips, k - 1)
                };
                (fine, mip_view(mips, k), mips, k)
            })
            .collect::<Vec<_>>();
        Self::from_views(ctx, pipeline, &levels)
    }

    /// Mips 1 and above of `map` (`Rgba32Float`, `STORAGE_BINDING` and `TEXTURE_BINDING`, as
    /// many mips as [`pyramid_levels`] or fewer) from its own mip 0: mip `L` becomes the
    /// pyramid's level `L`. For a map an application samples with `textureLoad` at a level.
    pub fn in_place(
        ctx: &GpuContext,
        pipeline: &wgpu::ComputePipeline,
        map: &wgpu::Texture,
    ) -> MapMips {
        let count = map
            .mip_level_count()
            .min(pyramid_levels(map.width() as usize, map.height() as usize) as u32);
        let levels = (1..count)
            .map(|k| (mip_view(map, k - 1), mip_view(map, k), map, k))
            .collect::<Vec<_>>();
        Self::from_views(ctx, pipeline, &levels)
    }

    fn from_views(
        ctx: &GpuContext,
        pipeline: &wgpu::ComputePipeline,
        levels: &[(wgpu::TextureView, wgpu::TextureView, &wgpu::Texture, u32)],
    ) -> MapMips {
        let written = levels.first().map(|&(_, _, texture, _)| texture.clone());
        let levels = levels
            .iter()
            .map(|(fine, coarse, texture, k)| {
                let group = pipeline.bind(ctx, CAUSTICS_MIPS.name, &[fine, coarse]);
                let size = texture
                    .size()
                    .mip_level_size(*k, wgpu::TextureDimension::D2);
                (group, (size.width, size.height))
            })
            .collect();
        MapMips {
            pipeline: pipeline.clone(),
            levels,
            written,
        }
    }

    /// Levels written: the pyramid's below level 0.
    pub fn len(&self) -> usize {
        self.levels.len()
    }

    /// Whether there is no level to write (a 1 x 1 map, or one made with a single mip):
    /// [`encode`](Self::encode) then records nothing.
    pub fn is_empty(&self) -> bool {
        self.levels.is_empty()
    }

    /// [`encode`](Self::encode) in a compute pass of its own, for a map whose level 0 was written
    /// earlier in `encoder` (a copy of a technique's map). The written texture is declared a
    /// storage target first: wgpu 30 records the first state of a subresource that a pass meets
    /// for the first time in its command buffer as the pass's last use (gfx-rs/wgpu#10199), so a
    /// level written and then read by the next dispatch would be left in the sampled layout.
    pub fn encode_pass(&self, encoder: &mut wgpu::CommandEncoder, label: &str) {
        if let Some(texture) = &self.written {
            encoder.transition_resources(
                std::iter::empty(),
                std::iter::once(wgpu::TextureTransition {
                    texture,
                    selector: None,
                    state: wgpu::TextureUses::STORAGE_WRITE_ONLY,
                }),
            );
        }
        let mut pass = begin_compute(encoder, &mut None, label);
        self.encode(&mut pass);
    }

    /// The dispatches into `pass`, finest first: each reads the level the one before it wrote.
    /// Leaves `pass`'s pipeline set to the mips' own.
    pub fn encode(&self, pass: &mut wgpu::ComputePass) {
        if self.levels.is_empty() {
            return;
        }
        pass.set_pipeline(&self.pipeline);
        for (group, (w, h)) in &self.levels {
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(w.div_ceil(TILE), h.div_ceil(TILE), 1);
        }
    }
}
