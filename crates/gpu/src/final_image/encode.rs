//! A frame's per-frame work: the uniform write when the camera, sun or options moved, and the
//! passes recorded into the caller's encoder.

use caustics_core::render::RenderOptions;
use caustics_core::scene::Scene;

use crate::pass::{begin_compute, bind_group};
use crate::{GpuContext, GpuTimer};

use super::upload::{self, Lighting};
use super::{
    FINAL_IMAGE, FINAL_IMAGE_SLAB, FINAL_IMAGE_SURFACE, FinalImageFrame, SLAB_LATTICE,
    SurfaceRaster, TILE, flags,
};

impl FinalImageFrame {
    /// Take this frame's camera, sun, exposure and supersampling from `scene` and `options`: one
    /// uniform write (and the slope moments' pyramid made, the first time the options filter the
    /// water). What the frame was built with stays: the image size (the aspect ratio is the
    /// frame's), the textures, the objects; a change to those needs a new frame.
    pub fn update(&mut self, ctx: &GpuContext, scene: &Scene, options: &RenderOptions) {
        let wrap = scene.water.as_ref().is_some_and(|w| w.wrap);
        if let Some(patches) = &mut self.patches {
            patches.set_wrap(ctx, wrap);
        }
        if options.filter_water && self.slopes.is_none() && !self.slopes_failed {
            self.make_slopes(ctx, scene);
        }
        if let Some(slopes) = &mut self.slopes {
            slopes.set_wrap(ctx, wrap);
        }
        let lighting = match self.lighting {
            // A floor map covers the water square (the scene's without water), as the techniques
            // lay their maps out, unless the caller said otherwise.
            Lighting::Floor { light_space, .. } => Lighting::Floor {
                size: self
                    .map_size
                    .unwrap_or(scene.water.as_ref().map_or(scene.size, |w| w.size)),
                light_space,
            },
            other => other,
        };
        let params = upload::uniform(
            scene,
            self.slab_group.is_some(),
            self.slopes.as_ref().map(|s| s.lattice()),
            lighting,
            options,
            self.object_count,
            self.size,
        );
        if self
            .pipeline
            .as_ref()
            .is_none_or(|(f, _)| *f != params.flags & super::SPECIALISED)
        {
            let pipeline = self.pipelines.get(ctx, params.flags);
            self.pipeline = Some((params.flags & super::SPECIALISED, pipeline));
        }
        if self
            .written
            .is_some_and(|w| bytemuck::bytes_of(&w) == bytemuck::bytes_of(&params))
        {
            return;
        }
        ctx.write_pod(&self.uniform, &params);
        self.written = Some(params);
    }

    /// Record the water's patches, slab bound and surface from the camera (when there is water)
    /// and the image into `encoder`. With a `timer`, every pass is timed: the patches as "water
    /// patches", the slab pass (128² bicubic samples) as "final image slab", the surface's grid
    /// as "final image surface", the image as "final image"; a timer needs room for four passes
    /// per image.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, mut timer: Option<&mut GpuTimer>) {
        if let Some(patches) = &self.patches {
            self.patches_pipeline.encode(patches, encoder, &mut timer);
        }
        if let Some(group) = &self.slab_group {
            encoder.clear_buffer(&self.slab_max, 0, None);
            let mut pass = begin_compute(encoder, &mut timer, FINAL_IMAGE_SLAB.name);
            pass.set_pipeline(&self.slab_pipeline);
            pass.set_bind_group(0, group, &[]);
            let groups = SLAB_LATTICE.div_ceil(TILE);
            pass.dispatch_workgroups(groups, groups, 1);
        }
        let Some((_, pipeline)) = &self.pipeline else {
            return;
        };
        if let Some(surface) = &self.surface {
            self.rasterise_surface(surface, encoder, &mut timer);
        }
        let mut pass = begin_compute(encoder, &mut timer, FINAL_IMAGE.name);
        // The floor map's pyramid, finest level first; the image's dispatch reads it all.
        if let Some(mips) = &self.mips_groups {
            mips.encode(&mut pass);
        }
        if let Some(slopes) = self.slopes.as_ref().filter(|_| self.filters_water()) {
            slopes.encode(&mut pass);
        }
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &self.scene_group, &[]);
        pass.set_bind_group(1, &self.mesh_group, &[]);
        pass.set_bind_group(2, &self.slopes_group, &[]);
        let (width, height) = self.size;
        pass.dispatch_workgroups(width.div_ceil(TILE), height.div_ceil(TILE), 1);
    }

    /// The water's surface as a grid of triangles from the camera: each pixel's distance to it
    /// along its central ray (negative where none), where the image's search starts.
    fn rasterise_surface(
        &self,
        surface: &SurfaceRaster,
        encoder: &mut wgpu::CommandEncoder,
        timer: &mut Option<&mut GpuTimer>,
    ) {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(FINAL_IMAGE_SURFACE.name),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &surface.hits,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: -1.0,
                        g: 0.0,
                        b: 0.0,
                        a: 1.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &surface.depth,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: timer
                .as_deref_mut()
                .and_then(|t| t.render_pass(FINAL_IMAGE_SURFACE.name)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.surface_pipeline);
        pass.set_bind_group(0, &surface.group, &[]);
        let (cols, rows) = surface.cells;
        pass.draw(0..6 * (cols + 1) * (rows + 1), 0..1);
    }

    /// The slope moments' pyramid, for options that filter the water's normals in a frame built
    /// without them: made once, on the frame's heights. Where it cannot be made (a lattice whose
    /// pyramid exceeds the adapter's buffers), the water stays unfiltered, said in the log.
    fn make_slopes(&mut self, ctx: &GpuContext, scene: &Scene) {
        let (Some(patches), Some(water)) = (&self.patches, &scene.water) else {
            return;
        };
        match self.slope_pipelines.pyramid(
            ctx,
            &patches.view,
            patches.size(),
            water.size,
            water.wrap,
        ) {
            Ok(pyramid) => {
                self.slopes_group = bind_group(
                    ctx,
                    "water slope moments",
                    &self.slopes_layout,
                    &[&pyramid.moments],
                );
                self.slopes = Some(pyramid);
            }
            Err(e) => {
                tracing::warn!("the water's normals stay unfiltered: {e}");
                self.slopes_failed = true;
            }
        }
    }

    /// Whether the uniform last written filters the waves' normals by the samples' footprints.
    fn filters_water(&self) -> bool {
        self.written
            .is_some_and(|w| w.flags & flags::FILTER_WATER != 0)
    }

    /// The image: `Rgba8Unorm`, tone-mapped and sRGB-encoded (the 8-bit codes of
    /// `caustics_core::render`'s image), usable as a storage, sampled or copied texture.
    pub fn output(&self) -> &wgpu::Texture {
        &self.output
    }
}
