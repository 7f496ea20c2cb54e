//! One generator's frame (a glass object's, or the water surface's for the floor or a wall): its
//! buffers, floor map and bind groups, and the passes that draw its floor map: photon tracing
//! (`photon.wgsl`), vertex irradiance (`irradiance.wgsl`) and the merge pyramid (`pyramid.wgsl`),
//! the caustic triangles (`triangles.wgsl`) or the splats (`splat.wgsl`).

use caustics_core::techniques::caustic_triangles::{CausticTrianglesSetup, DistanceMap};

use super::{CausticTriangles, CausticTrianglesUniform, CopyBandBuffer, Reconstruction};
use crate::pass::{Bind, MAP_TARGET, begin_compute, begin_render, layer_view};
use crate::{GpuContext, GpuError, GpuTimer};

/// One generator's resources (a glass object's, or the water surface's for the floor or a wall):
/// the distance map, the photon image, the vertex irradiances, the floor map, and the bind groups.
/// Built once; encode it every frame the light or object moves (the uniform and distance map can be
/// rewritten in place for the same sizes).
pub struct GeneratorFrame {
    /// The setup the uniform was written from.
    pub setup: CausticTrianglesSetup,
    /// The generator's [`CausticTrianglesUniform`], which every pass reads.
    pub uniform: wgpu::Buffer,
    /// The layered distance map's texels (§3), `[f32; 4]` each, as `DistanceMap::texels`.
    pub dm_buffer: wgpu::Buffer,
    /// The photon hit location image (§4.1), `p²` `[x, y, power, signature]` row-major: the hit in
    /// the receiver's plane (world units), power -1 where invalid, signature = refractions + 64 ×
    /// total internal reflections.
    pub photons: wgpu::Buffer,
    /// Refracted path length per photon (a water generator's; zeros for glass).
    pub paths: wgpu::Buffer,
    /// Irradiance per photon-image vertex, `p²` `f32` (power / adjacent area, floor units; -1
    /// where invalid).
    pub irradiance: wgpu::Buffer,
    /// The floor map the caustic triangles or splats add into: this frame's own, or a shared one
    /// (or a layer of it) several generators draw into.
    pub map: wgpu::Texture,
    /// The 2-D view of `map` (its layer) that the draws target.
    pub map_view: wgpu::TextureView,
    pub(crate) photon_bind: wgpu::BindGroup,
    pub(crate) irradiance_bind: wgpu::BindGroup,
    /// The merge pyramid (§5) and one bind group per level.
    pub pyramid: wgpu::Buffer,
    pub(super) pyramid_binds: Vec<wgpu::BindGroup>,
    /// The band the GPU fitted and the indirect draw of the shifted copies ([`CopyBandBuffer`]).
    pub copy_band: wgpu::Buffer,
    /// Whether the shifted copies are drawn indirectly from `copy_band` (a water frame of tiling
    /// water, whose copy band pass writes it) rather than from the setup's band.
    pub(super) gpu_band: bool,
    pub(super) triangles_bind: wgpu::BindGroup,
    pub(super) splat_bind: wgpu::BindGroup,
    pub(super) bytes: u64,
}

impl GeneratorFrame {
    /// GPU memory this frame's buffers and map take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }
}

impl CausticTriangles {
    /// A generator's frame with its own floor map, for `setup` and its distance map `dm`.
    pub fn frame(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
    ) -> Result<GeneratorFrame, GpuError> {
        self.frame_drawing_into(ctx, setup, dm, None)
    }

    /// A frame whose floor map is `map` when given (a floor map of the setup's size and this
    /// format that several generators draw into, [`draw_floor`](Self::draw_floor) with `clear`
    /// for the first only), else its own.
    pub fn frame_drawing_into(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        map: Option<&wgpu::Texture>,
    ) -> Result<GeneratorFrame, GpuError> {
        self.frame_into_layer(ctx, setup, dm, map.map(|m| (m, 0)))
    }

    /// [`frame_drawing_into`](Self::frame_drawing_into) a layer of a shared 2-D array texture at
    /// least as wide as the setup's map (the wall maps: the map in the layer's first columns).
    pub fn frame_into_layer(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        map: Option<(&wgpu::Texture, u32)>,
    ) -> Result<GeneratorFrame, GpuError> {
        use wgpu::BufferUsages as B;
        let (w, h) = (setup.floor.width as u32, setup.floor.height as u32);
        ctx.check_texture_size("caustic-triangles floor map", w, h)?;
        let p = setup.p as u64;
        let dm_bytes = dm.texels.len() as u64 * 16;
        ctx.check_buffer_size("caustic-triangles distance map", dm_bytes)?;
        ctx.check_buffer_size("caustic-triangles photon image", p * p * 16)?;
        let uniform = ctx.uniform(
            "caustic-triangles uniform",
            &CausticTrianglesUniform::new(setup, dm),
        );
        let dm_buffer = ctx.buffer_init(
            "caustic-triangles distance map",
            bytemuck::cast_slice(&dm.texels),
            B::STORAGE | B::COPY_DST,
        );
        let photons = ctx.buffer(
            "caustic-triangles photon image",
            p * p * 16,
            B::STORAGE | B::COPY_SRC | B::COPY_DST,
        );
        let paths = ctx.buffer(
            "caustic-triangles photon path lengths",
            p * p * 4,
            B::STORAGE | B::COPY_SRC,
        );
        let irradiance = ctx.buffer(
            "caustic-triangles vertex irradiance",
            p * p * 4,
            B::STORAGE | B::COPY_SRC,
        );
        let own_map = map.is_none();
        let layer = map.map_or(0, |m| m.1);
        let map = match map.map(|m| m.0) {
            Some(m) => {
                if m.width() < w
                    || (m.height(), m.format()) != (h, self.map_format)
                    || layer >= m.depth_or_array_layers()
                {
                    return Err(GpuError::Validation(format!(
                        "caustic-triangles: a shared floor map of {} x {} {:?} for a {w} x {h} {:?} frame",
                        m.width(),
                        m.height(),
                        m.format(),
                        self.map_format
                    )));
                }
                m.clone()
            }
            None => ctx.texture_2d(
                "caustic-triangles floor map",
                (w, h, 1),
                self.map_format,
                MAP_TARGET,
            ),
        };
        let map_view = layer_view(&map, layer);
        let photon_bind = self.photon.bind(
            ctx,
            "caustic-triangles photon tracing",
            &[&uniform, &dm_buffer, &photons],
        );
        let irradiance_bind = self.irradiance.bind(
            ctx,
            "caustic-triangles vertex irradiance",
            &[&uniform, &photons, &irradiance],
        );
        let (sides, offsets) = caustics_core::techniques::caustic_triangles::merge::layout(
            setup.p,
            setup.merge_levels,
        );
        let pyramid_texels = (offsets.last().unwrap() + sides.last().unwrap().pow(2)) as u64;
        ctx.check_buffer_size(
            "caustic-triangles merge pyramid",
            pyramid_texels.max(1) * 16,
        )?;
        let pyramid = ctx.buffer(
            "caustic-triangles merge pyramid",
            pyramid_texels.max(1) * 16,
            B::STORAGE | B::COPY_SRC,
        );
        let pyramid_binds = (0..=setup.merge_levels)
            .map(|k| {
                let level = ctx.buffer_init(
                    "caustic-triangles merge level",
                    bytemuck::cast_slice(&[k, 0u32, 0, 0]),
                    B::UNIFORM,
                );
                self.pyramid.bind(
                    ctx,
                    "caustic-triangles merge pyramid",
                    &[&uniform, &photons, &irradiance, &pyramid, &level],
                )
            })
            .collect();
        let copy_band = ctx.buffer_init(
            "caustic-triangles copy band",
            bytemuck::bytes_of(&CopyBandBuffer::unfitted()),
            B::STORAGE | B::INDIRECT | B::COPY_SRC,
        );
        let triangles_bind = self.triangles.bind(
            ctx,
            "caustic-triangles triangles",
            &[
                &uniform,
                &photons,
                &irradiance,
                &pyramid,
                &paths,
                &copy_band,
            ],
        );
        let splat_bind = self.splat.bind(
            ctx,
            "caustic-triangles splats",
            &[&uniform, &photons, &paths],
        );
        ctx.check()?;
        let texel = self.map_format.block_copy_size(None).unwrap_or(16) as u64;
        Ok(GeneratorFrame {
            setup: setup.clone(),
            uniform,
            dm_buffer,
            photons,
            paths,
            irradiance,
            map,
            map_view,
            photon_bind,
            irradiance_bind,
            pyramid,
            pyramid_binds,
            triangles_bind,
            splat_bind,
            copy_band,
            gpu_band: false,
            bytes: dm_bytes
                + p * p * 24
                + own_map as u64 * (w * h) as u64 * texel
                + 176
                + std::mem::size_of::<CopyBandBuffer>() as u64,
        })
    }

    /// Record the photon tracing pass, then the reconstruction into the floor map (cleared first).
    pub fn encode(
        &self,
        frame: &GeneratorFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
    ) {
        self.encode_photons(frame, encoder, timer.as_deref_mut());
        self.encode_reconstruction(frame, encoder, timer, reconstruction);
    }

    /// Record the photon tracing pass alone (§4.1) into `frame.photons`.
    pub fn encode_photons(
        &self,
        frame: &GeneratorFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let p = frame.setup.p as u32;
        let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles photon tracing");
        pass.set_pipeline(&self.photon);
        pass.set_bind_group(0, &frame.photon_bind, &[]);
        pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
    }

    /// Record the reconstruction only (vertex irradiance and triangles, or splats) from the photon
    /// image already in `frame.photons`, into the floor map (cleared first).
    pub fn encode_reconstruction(
        &self,
        frame: &GeneratorFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
    ) {
        if reconstruction == Reconstruction::Triangles {
            self.encode_irradiance(frame, encoder, timer.as_deref_mut());
        }
        self.draw_floor(frame, encoder, timer, reconstruction, &frame.map_view, true);
    }

    /// The vertex irradiance pass (§5), then, with `merge_levels`, the merge pyramid level by level.
    pub fn encode_irradiance(
        &self,
        frame: &GeneratorFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let p = frame.setup.p as u32;
        {
            let mut pass =
                begin_compute(encoder, &mut timer, "caustic-triangles vertex irradiance");
            pass.set_pipeline(&self.irradiance);
            pass.set_bind_group(0, &frame.irradiance_bind, &[]);
            pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
        }
        if frame.setup.merge_levels == 0 {
            return;
        }
        for (k, bind) in frame.pyramid_binds.iter().enumerate() {
            let n = (p - 1) >> k;
            let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles merge pyramid");
            pass.set_pipeline(&self.pyramid);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(n.div_ceil(8).max(1), n.div_ceil(8).max(1), 1);
        }
    }

    /// The floor-map render pass alone (triangles from the vertex irradiances already computed, or
    /// splats) into `target` (a floor map of this frame's size), cleared first or added to
    /// (several generators into one map).
    pub fn draw_floor(
        &self,
        frame: &GeneratorFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
        target: &wgpu::TextureView,
        clear: bool,
    ) {
        let p = frame.setup.p as u32;
        let copies = frame.setup.copies().len() as u32;
        let label = match reconstruction {
            Reconstruction::Triangles => "caustic-triangles triangles",
            Reconstruction::Splats => "caustic-triangles splats",
        };
        let mut pass = begin_render(encoder, &mut timer, label, &[target], clear);
        // The map may fill only the first columns of its target (a wall map in its layer).
        let f = &frame.setup.floor;
        pass.set_viewport(0.0, 0.0, f.width as f32, f.height as f32, 0.0, 1.0);
        match reconstruction {
            Reconstruction::Triangles => {
                pass.set_pipeline(&self.triangles);
                pass.set_bind_group(0, &frame.triangles_bind, &[]);
                let all = 6 * (p - 1) * (p - 1);
                if copies == 1 {
                    pass.draw(0..all, 0..1);
                } else {
                    // The unshifted copy (instance 8) over every quad, the eight shifted ones
                    // (instances 0..8, `copy_of_instance` in common.wgsl) over their bands only
                    // (`copy_rect`): an edge band is at most `band` quads deep. The band is the
                    // GPU's own where the copy band pass fitted it, else the setup's.
                    pass.draw(0..all, 8..9);
                    if frame.gpu_band {
                        pass.draw_indirect(
                            &frame.copy_band,
                            std::mem::offset_of!(CopyBandBuffer, draw) as u64,
                        );
                    } else {
                        let area =
                            |(i0, i1, j0, j1): (usize, usize, usize, usize)| (i1 - i0) * (j1 - j0);
                        let most = (0..9)
                            .filter(|&k| k != 4)
                            .map(|k| area(frame.setup.copy_rect(k)))
                            .max()
                            .unwrap_or(0) as u32;
                        pass.draw(0..(6 * most).min(all), 0..8);
                    }
                }
            }
            Reconstruction::Splats => {
                pass.set_pipeline(&self.splat);
                pass.set_bind_group(0, &frame.splat_bind, &[]);
                pass.draw(0..6 * p * p, 0..copies);
            }
        }
    }
}
