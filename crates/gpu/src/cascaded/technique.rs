//! Paper 5 behind [`Technique`]: the caller's heights, the terrain uploaded once per configure, a
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
use caustics_core::techniques::{Job, Made, SceneCaustics};

use super::{Cascaded, Frame};
use crate::technique::{Fit, Output, Registered, RunOnce, Technique, WaterTextures};
use crate::{GpuContext, GpuError, GpuTimer};

/// Side of the height grid the technique reads a surface through when the scene gives neither an
/// ocean's nor a file's own grid: the application's (`CASCADED_WATER_GRID` in the app's
/// techniques, `cascaded::water_grid`'s caller).
pub const WATER_GRID: u32 = 256;

pub struct CascadedTechnique {
    pipelines: Cascaded,
    params: CascadedParams,
    frame: Option<(Frame, WaterTextures)>,
}

pub fn create(ctx: &GpuContext, params: &toml::Table) -> Result<Box<dyn Technique>, GpuError> {
    CascadedTechnique::new(ctx, params).map(|t| Box::new(t) as _)
}

impl CascadedTechnique {
    pub fn new(ctx: &GpuContext, params: &toml::Table) -> Result<Self, GpuError> {
        Ok(CascadedTechnique {
            pipelines: Cascaded::new(ctx)?,
            params: CascadedParams::from_table(params)?,
            frame: None,
        })
    }

    /// The configured frame (its setup, G-buffers and screen-space maps), for tests and tools.
    pub fn frame(&self) -> Option<&Frame> {
        self.frame.as_ref().map(|(f, _)| f)
    }
}

impl Technique for CascadedTechnique {
    fn name(&self) -> &str {
        "cascaded"
    }

    /// As `caustics_core::techniques::cascaded::water_grid` reads a scene: an ocean's own grid, a
    /// height-field file's own samples, else [`WATER_GRID`]² over the square.
    fn water_resolution(&self, scene: &Scene) -> (u32, u32) {
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
    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError> {
        let setup = CascadedSetup::from_scene(scene, &self.params)?;
        self.frame = None;
        let frame =
            self.pipelines
                .frame(ctx, &setup, &water.heights, scene.floor.terrain.as_ref())?;
        self.frame = Some((frame, water.clone()));
        Ok(())
    }

    /// The cascades refitted to the camera and sun: uniform writes while the camera's size, the
    /// resolution, the terrain's presence and the dispersion mode hold. A new terrain is a new
    /// configure (the caller's: the terrain is not compared here).
    fn write_scene(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<Fit, GpuError> {
        let setup = CascadedSetup::from_scene(scene, &self.params)?;
        let Some((frame, water)) = &mut self.frame else {
            return Err(GpuError::BadOption(
                "cascaded: update before configure".into(),
            ));
        };
        if frame.fits(&setup) {
            frame.set_setup(ctx, &setup);
            return Ok(Fit::Written);
        }
        Ok(Fit::Reconfigure(water.clone()))
    }

    fn encode(&self, encoder: &mut wgpu::CommandEncoder, timer: Option<&mut GpuTimer>) {
        if let Some((frame, _)) = &self.frame {
            self.pipelines.encode(frame, encoder, timer);
        }
    }

    fn output(&self) -> Option<Output<'_>> {
        self.frame
            .as_ref()
            .map(|(f, _)| Output::EyeSpace(self.pipelines.output(f)))
    }

    fn bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |(f, _)| f.bytes())
    }

    fn set_params(&mut self, params: &toml::Table) -> Result<bool, GpuError> {
        self.params = CascadedParams::from_table(params)?;
        Ok(true)
    }
}

/// Paper 5 in the registry.
pub const REGISTERED: Registered = Registered {
    describe: &cascaded::DESCRIPTOR,
    create,
    once: |ctx| Ok(Box::new(Once(Cascaded::new(ctx)?))),
    image: None,
};

/// Paper 5 run once on a job: its eye-space image for the scene's camera.
struct Once(Cascaded);

impl RunOnce for Once {
    fn run(
        &mut self,
        ctx: &GpuContext,
        job: &Job,
        params: &toml::Table,
        timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Made, GpuError> {
        let (setup, water) = cascaded::job_setup(job, params)?;
        let terrain = job.scene.floor.terrain.as_ref();
        let image = self
            .0
            .caustics_timed(ctx, &setup, &water, terrain, timer)?
            .image;
        progress(1, 1);
        Ok(Made {
            caustics: SceneCaustics::EyeSpace(caustics_core::render::EyeSpaceCaustics {
                width: setup.eye.width,
                height: setup.eye.height,
                texels: image,
            }),
            walls: None,
        })
    }
}
