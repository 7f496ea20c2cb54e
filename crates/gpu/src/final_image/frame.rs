//! Building a [`FinalImageFrame`]: every resource of one scene at one image size, made once.

use caustics_core::map::pyramid_levels;
use caustics_core::render::RenderOptions;
use caustics_core::scene::{Albedo, Scene};

use crate::map_mips::{MapMips, mip_chain};
use crate::pass::{Bind, STORAGE_OUT, bind_group};
use crate::receivers::{LightSpaceOutput, LightSpaceUniform};
use crate::technique::{Output, WallsOutput, WaterTextures};
use crate::water::patches::Patches;
use crate::{GpuContext, GpuError};

use super::resources::rgba32;
use super::upload::Lighting;
use super::{
    FINAL_IMAGE_SURFACE, FinalImage, FinalImageFrame, FinalImageUniform, SLAB_LATTICE,
    SURFACE_CELLS, SURFACE_DEPTH, SURFACE_HITS, SlabUniform, SurfaceRaster, meshes,
};
use crate::pass::{array_view, float_texture, storage_buffer};
use wgpu::BufferUsages as B;

/// What a final image is made from besides the scene; `Default` is none of it (flat, still
/// water's light).
#[derive(Clone, Copy, Default)]
pub struct ImageInputs<'a> {
    /// The heights as the techniques read them, bound as they are (the caller may rewrite the
    /// texture every frame); `None` without water.
    pub water: Option<&'a WaterTextures>,
    /// The technique's output texture, bound as it is: a floor map over the water square (over
    /// the scene square without water), or an eye-space image of the scene's camera; `None`
    /// lights the floor as under flat water.
    pub caustics: Option<Output<'a>>,
    /// The walls' maps of a technique that lit the pool's walls (bound as they are; ignored when
    /// the scene's walls are off).
    pub walls: Option<WallsOutput<'a>>,
    /// Its light-space deposit beside a floor map, where objects are among its receivers: their
    /// light ([`crate::receivers::ReceiverFrame::light_space`]); `None` lights the objects as
    /// under flat water.
    pub light: Option<LightSpaceOutput<'a>>,
    /// The square a floor map covers, where it is not the water's.
    pub map_size: Option<f64>,
}

impl FinalImage {
    /// The final image of `scene` at its camera's size, every resource built here once: the
    /// objects' trees (a scene whose objects change needs a new frame), the terrain and albedo
    /// textures, the `Rgba8Unorm` output, the uniform and the bind groups.
    /// What lights it is in `inputs` ([`ImageInputs`]). [`update`](FinalImageFrame::update) takes
    /// the first frame's camera and sun before [`encode`](FinalImageFrame::encode).
    pub fn frame(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        inputs: ImageInputs,
        options: &RenderOptions,
    ) -> Result<FinalImageFrame, GpuError> {
        self.build(ctx, scene, inputs, options)
    }

    /// [`frame`](Self::frame), a floor map's square given (`map_size`) or
    /// the scene's.
    #[allow(clippy::too_many_arguments)]
    fn build(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        inputs: ImageInputs,
        options: &RenderOptions,
    ) -> Result<FinalImageFrame, GpuError> {
        let ImageInputs {
            water,
            caustics,
            walls,
            light,
            map_size,
        } = inputs;
        // The deposit lights objects under water, beside a floor map.
        let light = light.filter(|_| matches!(caustics, Some(Output::Floor(_))));
        let (width, height) = (scene.camera.width, scene.camera.height);
        ctx.check_texture_size("final image", width, height)?;
        // Heights without water in the scene have no square to cover: the frame has no surface.
        let water = water.filter(|_| scene.water.is_some());
        let lighting = match caustics {
            Some(Output::Floor(_)) => Lighting::Floor {
                size: map_size.unwrap_or(scene.water.as_ref().map_or(scene.size, |w| w.size)),
                light_space: light.is_some(),
            },
            Some(Output::EyeSpace(_)) => Lighting::EyeSpace,
            None => Lighting::Flat,
        };

        let meshes = meshes(scene);
        let terrain = match &scene.floor.terrain {
            Some(t) => Some(ctx.upload_grid("terrain height field", t)?),
            None => None,
        };
        let terrain_patches = terrain.as_ref().map(|t| self.terrain_patches(ctx, t));
        let albedo_image = match &scene.floor.albedo {
            Albedo::Image {
                width,
                height,
                texels,
            } => Some(float_texture(
                ctx,
                "floor albedo image",
                wgpu::TextureFormat::Rgba32Float,
                (*width as u32, *height as u32, 1),
                bytemuck::cast_slice(&rgba32(texels)),
            )?),
            Albedo::Pattern(_) => None,
        };
        let walls = walls.filter(|_| scene.floor.walls && scene.water.is_some());
        let wall_cols =
            storage_buffer(ctx, "walls' columns", &walls.map_or([0u32; 4], |w| w.cols))?;
        let objects = storage_buffer(ctx, "scene objects", &meshes.objects)?;
        let nodes = storage_buffer(ctx, "object BVH nodes", &meshes.trees.nodes)?;
        let triangles = storage_buffer(ctx, "object BVH triangles", &meshes.trees.triangles)?;
        let uniform = ctx.uniform_buffer::<FinalImageUniform>("final image uniform");
        let slab_max = ctx.buffer(
            "final image slab bounds",
            8,
            B::STORAGE | B::COPY_DST | B::COPY_SRC,
        );
        let output = ctx.texture_2d(
            "final image",
            (width, height, 1),
            wgpu::TextureFormat::Rgba8Unorm,
            STORAGE_OUT,
        );

        let (mips, mips_groups) = match caustics {
            Some(Output::Floor(map)) => self.pyramid(ctx, map).unzip(),
            _ => (None, None),
        };
        let view = |t: Option<&wgpu::Texture>, empty: &wgpu::Texture| {
            t.unwrap_or(empty).create_view(&Default::default())
        };
        let patches = water.map(|w| {
            let wrap = scene.water.as_ref().is_some_and(|sw| sw.wrap);
            self.patches.frame(ctx, &w.heights, wrap)
        });
        let water_view = match &patches {
            Some(p) => p.view.clone(),
            None => view(None, &self.empty_rgba32),
        };
        // The surface rasterised for the camera, where there is one to search for.
        let surface = patches
            .as_ref()
            .map(|p| self.surface_raster(ctx, [&uniform, &slab_max], p, (width, height)));
        let no_slopes = storage_buffer(ctx, "no water slope moments", &[0f32; 5])?;
        // The slope moments' pyramid is made by `update` (the first below, when the options filter
        // the water), which leaves the water unfiltered where it cannot be made.
        let slopes_group = bind_group(
            ctx,
            "water slope moments",
            &self.slopes_layout,
            &[&no_slopes],
        );
        let views = [
            terrain_patches.unwrap_or_else(|| view(None, &self.empty_r32)),
            view(caustics.map(|c| c.texture()), &self.empty_rgba32),
            view(albedo_image.as_ref(), &self.empty_rgba32),
            output.create_view(&Default::default()),
            array_view(walls.map_or(&self.empty_walls, |w| w.texture)),
            view(mips.as_ref(), &self.empty_rgba32),
            view(light.map(|l| l.deposit), &self.empty_rgba32),
            view(light.map(|l| l.heights), &self.empty_r32),
        ];
        let surface_hits = match &surface {
            Some(s) => s.hits.clone(),
            None => view(None, &self.empty_r32),
        };
        let light_uniform = ctx.uniform(
            "final image light space",
            &light.map_or(LightSpaceUniform::default(), |l| l.uniform),
        );
        let scene_group = bind_group(
            ctx,
            "final image scene",
            &self.scene_layout,
            &[
                &uniform,
                &water_view,
                &views[0],
                &views[1],
                &views[2],
                &objects,
                &views[3],
                &slab_max,
                &views[4],
                &wall_cols,
                &views[5],
                &light_uniform,
                &views[6],
                &views[7],
                &surface_hits,
            ],
        );
        let mesh_group = bind_group(
            ctx,
            "scene meshes",
            &self.mesh_layout,
            &[&nodes, &triangles],
        );
        let mut resources = vec![
            objects,
            nodes,
            triangles,
            wall_cols,
            no_slopes,
            light_uniform,
        ];
        let slab_group = match (water, &scene.water) {
            (Some(w), Some(sw)) => {
                // The water's square and edge rule are the scene's: a new frame when they change.
                let slab = SlabUniform {
                    size: sw.size as f32,
                    wrap: sw.wrap as u32,
                    lattice: SLAB_LATTICE,
                    _pad: 0,
                };
                let slab_uniform = ctx.uniform("final image slab uniform", &slab);
                let group = self.slab_pipeline.bind(
                    ctx,
                    "final image slab",
                    &[&slab_uniform, &w.heights, &slab_max],
                );
                resources.push(slab_uniform);
                Some(group)
            }
            _ => None,
        };

        let mut frame = FinalImageFrame {
            pipelines: self.pipelines.clone(),
            pipeline: None,
            slab_pipeline: self.slab_pipeline.clone(),
            surface_pipeline: self.surface_pipeline.clone(),
            surface,
            patches_pipeline: self.patches.clone(),
            patches,
            mips_groups,
            scene_group,
            mesh_group,
            slab_group,
            uniform,
            slab_max,
            output,
            lighting,
            map_size,
            object_count: meshes.objects.len() as u32,
            size: (width, height),
            written: None,
            _resources: resources,
            pyramid: mips,
            slopes: None,
            slope_pipelines: self.slopes.clone(),
            slopes_layout: self.slopes_layout.clone(),
            slopes_group,
            slopes_failed: false,
            _textures: albedo_image.into_iter().collect(),
        };
        frame.update(ctx, scene, options);
        ctx.check()?;
        Ok(frame)
    }

    /// The terrain's heights in Hermite form, clamped at its edges, as the image reads them: made
    /// once, since a frame's terrain does not change.
    fn terrain_patches(&self, ctx: &GpuContext, heights: &wgpu::Texture) -> wgpu::TextureView {
        let patches = self
            .patches
            .frame(ctx, &heights.create_view(&Default::default()), false);
        let mut encoder = ctx.encoder("terrain patches");
        self.patches.encode(&patches, &mut encoder, &mut None);
        ctx.queue.submit([encoder.finish()]);
        patches.view
    }

    /// The surface's grid for an image of `size` pixels over the heights in Hermite form
    /// (`patches`), raised by the slab's slope bound (`slab_max`): its bind group and its targets,
    /// the distances and a depth.
    fn surface_raster(
        &self,
        ctx: &GpuContext,
        [uniform, slab_max]: [&wgpu::Buffer; 2],
        patches: &Patches,
        (width, height): (u32, u32),
    ) -> SurfaceRaster {
        let group = self.surface_pipeline.bind_at(
            ctx,
            FINAL_IMAGE_SURFACE.name,
            &[(0, uniform), (1, &patches.view), (7, slab_max)],
        );
        let target = |label, format| {
            ctx.texture_2d(
                label,
                (width, height, 1),
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            )
            .create_view(&Default::default())
        };
        let (cols, rows) = patches.size();
        SurfaceRaster {
            group,
            hits: target("final image surface distances", SURFACE_HITS),
            depth: target("final image surface depth", SURFACE_DEPTH),
            cells: (cols.min(SURFACE_CELLS), rows.min(SURFACE_CELLS)),
        }
    }

    /// The levels of `map`'s pyramid below level 0 (`CausticsMap::pyramid`: level `L` is
    /// `max(1, size >> L)`), as the mips of one `Rgba32Float` texture whose level `L - 1` is the
    /// pyramid's level `L`, and the dispatches that fill it; none for a map of one texel.
    fn pyramid(&self, ctx: &GpuContext, map: &wgpu::Texture) -> Option<(wgpu::Texture, MapMips)> {
        let levels = pyramid_levels(map.width() as usize, map.height() as usize) as u32 - 1;
        if levels == 0 {
            return None;
        }
        let mips = mip_chain(
            ctx,
            "caustics map pyramid",
            ((map.width() / 2).max(1), (map.height() / 2).max(1)),
            levels,
            wgpu::TextureUsages::COPY_SRC,
        );
        let groups = MapMips::beside(ctx, &self.mips_pipeline, map, &mips);
        Some((mips, groups))
    }
}
