//! One-off images from CPU inputs, read back (the GPU counterparts of `caustics_core::render`'s
//! entry points), and the frame's readbacks for tests and tools.

use caustics_core::render::{Caustics, Image, RenderOptions};
use caustics_core::scene::Scene;
use caustics_core::walls::WallMaps;
use caustics_core::water::Surface;

use crate::technique::{Output, WallsOutput, WaterTextures};
use crate::{GpuContext, GpuError, GpuTimer};

use super::frame::ImageInputs;
use super::resources::{upload_light_space, upload_map, upload_walls};
use super::slopes;
use super::{FinalImage, FinalImageFrame, PyramidLevel, Slab, water_grid};
use crate::pass::float_texture;
use crate::receivers::LightSpaceOutput;

impl FinalImage {
    /// Render `scene` from its camera: the GPU counterpart of
    /// `caustics_core::render::render`, with the same arguments (no progress: the image
    /// is one dispatch). `surface` is sampled on [`water_grid`]'s lattice; `caustics` comes from
    /// either source: a floor map, or an eye-space image made for the scene's camera (`cascaded`),
    /// read at the pixel each floor point projects to (none: lit as if the water were flat); the
    /// pool's walls are lit through CPU-made walls' maps (the reference's) where there are some. A
    /// one-off image from CPU inputs: the water grid, the map and the walls' maps are uploaded into
    /// textures, a [`FinalImageFrame`] is built on them, and the image is read back. With a
    /// `timer`, the passes are timed as [`encode`](FinalImageFrame::encode) says and the
    /// timestamps resolved; read them with [`GpuTimer::read`].
    #[allow(clippy::too_many_arguments)]
    pub fn render(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        surface: Option<&dyn Surface>,
        caustics: Option<Caustics>,
        walls: Option<&WallMaps>,
        options: &RenderOptions,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<Image, GpuError> {
        let grid = surface.and_then(|s| water_grid(scene, s));
        let heights = match &grid {
            Some(g) => Some(ctx.upload_grid("water height field", &g.grid)?),
            None => None,
        };
        let water = heights.as_ref().map(WaterTextures::of);
        let map = match caustics {
            Some(Caustics::Floor(m) | Caustics::Received(m, _)) => Some(upload_map(ctx, m)?),
            Some(Caustics::EyeSpace(e)) => Some(float_texture(
                ctx,
                "eye-space caustics",
                wgpu::TextureFormat::Rgba32Float,
                (e.width as u32, e.height as u32, 1),
                bytemuck::cast_slice(&e.texels),
            )?),
            None => None,
        };
        let (output, map_size) = match (caustics, &map) {
            (Some(Caustics::Floor(m) | Caustics::Received(m, _)), Some(t)) => {
                (Some(Output::Floor(t)), Some(m.size))
            }
            (Some(Caustics::EyeSpace(_)), Some(t)) => (Some(Output::EyeSpace(t)), None),
            _ => (None, None),
        };
        let walls = walls.map(|w| upload_walls(ctx, w)).transpose()?;
        let walls_output = walls.as_ref().map(|(texture, cols)| WallsOutput {
            texture,
            cols: *cols,
        });
        let light = match caustics {
            Some(Caustics::Received(_, l)) => Some(upload_light_space(ctx, l)?),
            _ => None,
        };
        let inputs = ImageInputs {
            water: water.as_ref(),
            caustics: output,
            walls: walls_output,
            light: light
                .as_ref()
                .map(|(deposit, heights, uniform)| LightSpaceOutput {
                    deposit,
                    heights,
                    uniform: *uniform,
                }),
            map_size,
        };
        let frame = self.frame(ctx, scene, inputs, options)?;

        let mut encoder = ctx.encoder("final image");
        frame.encode(&mut encoder, timer.as_deref_mut());
        ctx.submit_timed(encoder, timer.as_deref());
        ctx.check()?;
        let texels: Vec<[u8; 4]> = ctx.read_texture(frame.output())?;
        Ok(Image {
            width: frame.size.0,
            height: frame.size.1,
            rgb: texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}

impl FinalImageFrame {
    /// The levels of the water's slope moments the last submitted frame built, finest first (none
    /// without a surface; stale when the options do not filter the normals): for tests against
    /// `caustics_core::water::slopes::SlopePyramid`. A readback; not for the frame.
    pub fn read_slopes(
        &self,
        ctx: &GpuContext,
    ) -> Result<Vec<Vec<[f32; slopes::MOMENTS]>>, GpuError> {
        match &self.slopes {
            Some(s) => s.read(ctx),
            None => Ok(Vec::new()),
        }
    }

    /// The levels below level 0 of the floor map's pyramid the last submitted frame built (none
    /// without a floor map), finest first, each with its width: for tests against
    /// `CausticsMap::pyramid`. Readbacks; not for the frame.
    pub fn read_pyramid(&self, ctx: &GpuContext) -> Result<Vec<PyramidLevel>, GpuError> {
        let Some(mips) = &self.pyramid else {
            return Ok(Vec::new());
        };
        (0..mips.mip_level_count())
            .map(|k| {
                let w = mips
                    .size()
                    .mip_level_size(k, wgpu::TextureDimension::D2)
                    .width;
                Ok((w, ctx.read_texture_mip(mips, 0, k)?))
            })
            .collect()
    }

    /// The slab the last submitted frame searched for the water surface in and the slope bound
    /// of its march (zeros without a surface): for tests against
    /// [`slab_bounds`](super::slab_bounds). A readback; not for the frame.
    pub fn read_slab(&self, ctx: &GpuContext) -> Result<Slab, GpuError> {
        if self.slab_group.is_none() {
            return Ok(Slab::default());
        }
        let bits: Vec<u32> = ctx.read_buffer(&self.slab_max)?;
        let scaled = |b: u32| f32::from_bits(b) as f64 * 1.5 + 1e-6;
        Ok(Slab {
            half_height: scaled(bits[0]),
            slope: scaled(bits[1]),
        })
    }
}
