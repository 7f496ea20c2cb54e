//! Runs once and readbacks for tools and tests: the floor map, the photon image, the vertex
//! irradiances, the wall maps and the light cube map, read back.

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::caustic_triangles::cube::LightCube;
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_core::techniques::caustic_triangles::{CausticTrianglesSetup, DistanceMap};
use caustics_core::walls::WallMaps;

use super::{CausticTriangles, GeneratorFrame, LightCubeTarget, Reconstruction, WaterFrame};
use crate::{GpuContext, GpuError, GpuTimer};

/// What one GPU run reads back.
pub struct GpuOutput {
    /// The photon hit location image, `p²` `[x, y, power, signature]` (as
    /// [`GeneratorFrame::photons`]).
    pub photons: Vec<[f32; 4]>,
    /// Irradiance per photon-image vertex, floor units, -1 where invalid.
    pub irradiance: Vec<f32>,
    /// The floor map the caustic triangles (or splats) drew.
    pub map: CausticsMap,
}

/// What one water run reads back.
pub struct WaterGpuOutput {
    /// The photon hit location image of the water's lattice, `[x, y, power, signature]` per
    /// photon.
    pub photons: Vec<[f32; 4]>,
    /// Refracted path length per photon under water, world units (for Beer-Lambert absorption).
    pub paths: Vec<f32>,
    /// Irradiance per photon-image vertex, floor units, -1 where invalid.
    pub irradiance: Vec<f32>,
    /// The floor map: the receivers' lookup where the setup has receivers, else the triangles'.
    pub map: CausticsMap,
    /// The wall maps when the setup has walls.
    pub walls: Option<WallMaps>,
}

impl CausticTriangles {
    /// Read the floor map back (either format) as a caustics map.
    pub fn read_map(
        &self,
        ctx: &GpuContext,
        frame: &GeneratorFrame,
    ) -> Result<CausticsMap, GpuError> {
        ctx.read_map(&frame.map, frame.setup.floor.size)
    }

    /// A water frame's floor map: the receivers' lookup where it has receivers, else the
    /// triangles' map.
    pub fn read_water_map(
        &self,
        ctx: &GpuContext,
        wf: &WaterFrame,
    ) -> Result<CausticsMap, GpuError> {
        ctx.read_map(wf.floor_map(), wf.frame.setup.floor.size)
    }

    /// The frame's map, photon image and vertex irradiances, read back.
    fn read_output(&self, ctx: &GpuContext, frame: &GeneratorFrame) -> Result<GpuOutput, GpuError> {
        let map = self.read_map(ctx, frame)?;
        Ok(GpuOutput {
            photons: ctx.read_buffer(&frame.photons)?,
            irradiance: ctx.read_buffer(&frame.irradiance)?,
            map,
        })
    }

    /// Run the technique once and read everything back.
    pub fn run(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        reconstruction: Reconstruction,
    ) -> Result<GpuOutput, GpuError> {
        let frame = self.frame(ctx, setup, dm)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode(&frame, &mut encoder, None, reconstruction);
        ctx.queue.submit([encoder.finish()]);
        self.read_output(ctx, &frame)
    }

    /// The reconstruction alone from a given photon hit location image (`setup.p²` texels,
    /// `(x, y, Φ, σ)`), e.g. a synthetic one in a test; `dm` only has to fit the frame.
    pub fn reconstruct(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        photons: &[[f32; 4]],
        reconstruction: Reconstruction,
    ) -> Result<GpuOutput, GpuError> {
        assert_eq!(photons.len(), setup.p * setup.p, "photon image size");
        let frame = self.frame(ctx, setup, dm)?;
        ctx.write_buffer(&frame.photons, 0, bytemuck::cast_slice(photons));
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_reconstruction(&frame, &mut encoder, None, reconstruction);
        ctx.queue.submit([encoder.finish()]);
        self.read_output(ctx, &frame)
    }

    /// Read a water frame's wall maps back (`None` without walls).
    pub fn read_walls(
        &self,
        ctx: &GpuContext,
        wf: &WaterFrame,
    ) -> Result<Option<WallMaps>, GpuError> {
        let Some(walls) = &wf.walls else {
            return Ok(None);
        };
        let mut maps = walls.layout.clone();
        crate::technique::WallsOutput::of(&walls.texture, &walls.layout).read(ctx, &mut maps)?;
        Ok(Some(maps))
    }

    /// The water generator once, its floor map and, when `ws` has walls, the wall maps read back.
    pub fn water_caustics_walls(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &Grid,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<(CausticsMap, Option<WallMaps>), GpuError> {
        let wf = self.water_frame(ctx, ws, heights)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_water(
            &wf,
            &mut encoder,
            timer.as_deref_mut(),
            Reconstruction::Triangles,
        );
        ctx.submit_timed(encoder, timer.as_deref());
        let map = self.read_water_map(ctx, &wf)?;
        let walls = self.read_walls(ctx, &wf)?;
        ctx.check()?;
        Ok((map, walls))
    }

    /// The water generator once, everything read back.
    pub fn run_water(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &Grid,
        reconstruction: Reconstruction,
    ) -> Result<WaterGpuOutput, GpuError> {
        let wf = self.water_frame(ctx, ws, heights)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_water(&wf, &mut encoder, None, reconstruction);
        ctx.queue.submit([encoder.finish()]);
        let map = self.read_water_map(ctx, &wf)?;
        Ok(WaterGpuOutput {
            photons: ctx.read_buffer(&wf.frame.photons)?,
            paths: ctx.read_buffer(&wf.frame.paths)?,
            irradiance: ctx.read_buffer(&wf.frame.irradiance)?,
            map,
            walls: self.read_walls(ctx, &wf)?,
        })
    }

    /// Read a light cube map back as the CPU twin's [`LightCube`].
    pub fn read_cube(
        &self,
        ctx: &GpuContext,
        target: &LightCubeTarget,
        position: glam::DVec3,
    ) -> Result<LightCube, GpuError> {
        let texels = ctx.read_rgba_f32(&target.texture)?;
        Ok(LightCube {
            resolution: target.resolution as usize,
            position,
            caustic: texels.into_iter().map(|t| [t[0], t[1]]).collect(),
            shadow: ctx.read_buffer(&target.shadow)?,
        })
    }
}
