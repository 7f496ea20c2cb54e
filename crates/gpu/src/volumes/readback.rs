//! Runs once and readbacks for tools and tests: every map a frame made, read back.

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::volumes::illumination::WaterVertex;
use caustics_core::techniques::volumes::{ObjectMaps, VolumesInput, VolumesSetup};
use caustics_core::walls::WallMaps;

use super::{ViewOptions, Volumes, VolumesFrame, WallsFrame};
use crate::{GpuContext, GpuError};

/// What one GPU run reads back.
pub struct GpuOutput {
    /// Each object's depth texture, diffuse map, caustics map and final image (Eq. 4), in the
    /// setup's order.
    pub objects: Vec<ObjectMaps>,
    /// The floor's caustics map over the scene square, relative to flat water.
    pub floor: CausticsMap,
    /// The walls' maps, `None` without walls.
    pub walls: Option<WallMaps>,
    /// The shadow map's texels, `[depth, nx, ny, nz]` as an object's depth texture (empty without
    /// shadows).
    pub shadow: Vec<[f32; 4]>,
    /// The water pass's refracted lattice vertices.
    pub water: Vec<WaterVertex>,
    /// The refracted view, row 0 at the top (empty without one).
    pub view: Vec<[f32; 3]>,
}

impl Volumes {
    fn read_map(
        &self,
        ctx: &GpuContext,
        texture: &wgpu::Texture,
    ) -> Result<Vec<[f32; 3]>, GpuError> {
        let texels = ctx.read_rgba_f32(texture)?;
        Ok(texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect())
    }

    /// Read everything a frame made back.
    pub fn read(&self, ctx: &GpuContext, frame: &VolumesFrame) -> Result<GpuOutput, GpuError> {
        let mut objects = Vec::new();
        for o in &frame.objects {
            let image: Vec<[f32; 4]> = ctx.read_texture_layer(&frame.images, o.layer)?;
            objects.push(ObjectMaps {
                depth: ctx.read_texture_layer(&frame.depths, o.layer)?,
                diffuse: ctx.read_texture(&o.diffuse)?,
                caustics: self.read_map(ctx, &o.caustics)?,
                image: image.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
            });
        }
        let s = &frame.setup;
        Ok(GpuOutput {
            objects,
            floor: CausticsMap {
                width: s.width,
                height: s.height,
                size: s.size,
                texels: self.read_map(ctx, frame.floor_map())?,
            },
            walls: match &frame.walls {
                Some(w) => Some(read_walls(ctx, w)?),
                None => None,
            },
            shadow: match &frame.shadow {
                Some((tex, _, _)) => ctx.read_texture(tex)?,
                None => Vec::new(),
            },
            water: ctx.read_buffer(&frame.water)?,
            view: match &frame.view {
                Some((tex, _, _)) => {
                    let texels: Vec<[f32; 4]> = ctx.read_texture(tex)?;
                    texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect()
                }
                None => Vec::new(),
            },
        })
    }

    /// Run the technique once and read everything back.
    pub fn run(
        &self,
        ctx: &GpuContext,
        setup: &VolumesSetup,
        input: &VolumesInput,
        heights: &Grid,
        wrap: bool,
        view: Option<&ViewOptions>,
    ) -> Result<GpuOutput, GpuError> {
        let frame = self.frame(ctx, setup, input, heights, wrap, view)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode(&frame, &mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        self.read(ctx, &frame)
    }
}

/// The walls' maps of a frame, read back.
fn read_walls(ctx: &GpuContext, walls: &WallsFrame) -> Result<WallMaps, GpuError> {
    let mut maps = walls.layout.clone();
    walls.output().read(ctx, &mut maps)?;
    Ok(maps)
}
