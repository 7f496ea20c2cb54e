//! Paper 5 behind the generic adapter: the caller's heights, the terrain uploaded once per configure, a
//! moving camera or sun as uniform writes while the eye image keeps the camera's size.
//!
//! The output is [`Output::EyeSpace`]: the composed image (`Rgba32Float`, the camera's `width x
//! height`, row 0 at the top of the image), relative irradiance in red, green and blue, and in
//! alpha the cascade the pixel's value came from (`k + b`, `b` the blend into cascade `k + 1`, in
//! `[0, 4)`). A pixel with no value (its ray meets no floor within the cascades' reach) has alpha
//! `−1` and black colour; no pixel is NaN. This is the CPU twin's `CascadedFrame::image` as is, so
//! "has a value" is `alpha >= 0`, not the `alpha == 1` of [`Output::EyeSpace`]'s general note.

use caustics_core::scene::{Scene, WaterSource};
use caustics_core::techniques::cascaded::{self, CascadedParams, CascadedSetup};
use caustics_core::techniques::{Descriptor, Job, JobOutput, SceneCaustics};

use super::{Cascaded, CascadedResources};
use crate::adapter::Pipelines;
use crate::technique::{Output, Registered, WaterTextures};
use crate::{GpuContext, GpuError, GpuTimer};

/// Side of the height grid the technique reads a surface through when the scene gives neither an
/// ocean's nor a file's own grid: the application's (`CASCADED_WATER_GRID` in the app's
/// techniques, `cascaded::water_grid`'s caller).
pub const WATER_GRID: u32 = 256;

/// Paper 5 in the registry.
pub const REGISTERED: Registered =
    Registered::of::<Cascaded>(&cascaded::DESCRIPTOR, super::PASSES, None);

/// The `cascaded` technique resident on the GPU.
pub type CascadedTechnique = crate::adapter::Resident<Cascaded>;

impl Pipelines for Cascaded {
    type Params = CascadedParams;
    type Frame = CascadedResources;

    fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Cascaded::new(ctx)
    }

    fn params(_: &'static Descriptor, tables: &toml::Table) -> Result<CascadedParams, GpuError> {
        Ok(CascadedParams::from_table(tables)?)
    }

    /// As `caustics_core::techniques::cascaded::water_grid` reads a scene: an ocean's own grid, a
    /// height-field file's own samples, else [`WATER_GRID`]² over the square.
    fn water_resolution(_: &CascadedParams, scene: &Scene) -> (u32, u32) {
        match scene.water.as_ref().map(|w| &w.source) {
            Some(WaterSource::Ocean(o)) => {
                let n = o.params().resolution as u32;
                (n, n)
            }
            Some(WaterSource::HeightField(g)) => (g.cols as u32, g.rows as u32),
            _ => (WATER_GRID, WATER_GRID),
        }
    }

    /// The frame for the scene's camera size and G-buffer resolution; the floor's terrain (if
    /// any) is uploaded here and only here.
    fn frame(
        &self,
        ctx: &GpuContext,
        params: &CascadedParams,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<CascadedResources, GpuError> {
        let setup = CascadedSetup::from_scene(scene, params)?;
        Cascaded::frame(
            self,
            ctx,
            &setup,
            &water.heights,
            scene.floor.terrain.as_ref(),
        )
    }

    /// The cascades refitted to the camera and sun: uniform writes while the camera's size, the
    /// resolution, the terrain's presence and the dispersion mode hold. A new terrain is a new
    /// configure (the caller's: the terrain is not compared here).
    fn refit(
        &self,
        ctx: &GpuContext,
        params: &CascadedParams,
        frame: &mut CascadedResources,
        scene: &Scene,
    ) -> Result<bool, GpuError> {
        let setup = CascadedSetup::from_scene(scene, params)?;
        if frame.fits(&setup) {
            frame.set_setup(ctx, &setup);
            return Ok(true);
        }
        Ok(false)
    }

    fn encode(
        &self,
        frame: &CascadedResources,
        encoder: &mut wgpu::CommandEncoder,
        timer: Option<&mut GpuTimer>,
    ) {
        Cascaded::encode(self, frame, encoder, timer);
    }

    fn output<'a>(&'a self, frame: &'a CascadedResources) -> Output<'a> {
        Output::EyeSpace(Cascaded::output(self, frame))
    }

    fn bytes(frame: &CascadedResources) -> u64 {
        frame.bytes()
    }

    /// Its eye-space image for the scene's camera.
    fn run_once(
        &mut self,
        ctx: &GpuContext,
        _: &'static Descriptor,
        job: &Job,
        params: &toml::Table,
        timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError> {
        let (setup, water) = cascaded::job_setup(job, params)?;
        let terrain = job.scene.floor.terrain.as_ref();
        let image = self.caustics(ctx, &setup, &water, terrain, timer)?.image;
        progress(1, 1);
        Ok(JobOutput {
            caustics: SceneCaustics::EyeSpace(caustics_core::render::EyeSpaceCaustics {
                width: setup.eye.width,
                height: setup.eye.height,
                texels: image,
            }),
            light: None,
            walls: None,
        })
    }
}
