//! Paper 1 behind the generic adapter: both variants, the caller's heights, sun and N changes as
//! uniform writes.

use caustics_core::scene::Scene;
use caustics_core::techniques::yuksel::{self, Passes, YukselParams, YukselSetup};
use caustics_core::techniques::{Descriptor, Job, JobOutput};

use super::{Frame, Variant, Yuksel};
use crate::adapter::Pipelines;
use crate::receivers::ReceiverFrame;
use crate::technique::{Output, Registered, WaterTextures, scene_water};
use crate::{GpuContext, GpuError, GpuTimer};

/// Paper 1 in the registry: the passes its parameters name (`passes`; the scatter by default,
/// the paper's preset its render targets).
pub const REGISTERED: Registered =
    Registered::of::<Yuksel>(&yuksel::DESCRIPTOR, super::PASSES, None);

/// Paper 1's render-target passes in the registry (`yuksel-targets`), whatever the preset.
pub const TARGETS: Registered = Registered::of::<Yuksel>(&yuksel::TARGETS, super::PASSES, None);

/// The `yuksel` technique resident on the GPU.
pub type YukselTechnique = crate::adapter::Resident<Yuksel>;

impl Variant {
    /// The passes `params` name, or the ones a registered name forces (a table naming others is
    /// refused, naming the field).
    pub fn of(params: &YukselParams, fixed: Option<Variant>) -> Result<Variant, GpuError> {
        let named = match params.passes() {
            Passes::Targets => Variant::RenderTargets,
            Passes::Scatter => Variant::Scatter,
        };
        match fixed {
            Some(v) if params.passes.is_some() && v != named => Err(GpuError::BadOption(
                "technique `yuksel-targets` runs the render-target passes; `caustics.yuksel.passes` says `scatter`".into(),
            )),
            Some(v) => Ok(v),
            None => Ok(named),
        }
    }

    /// The passes registry entry `entry` forces, if any.
    fn fixed_by(entry: &Descriptor) -> Option<Variant> {
        (entry.name == yuksel::TARGETS.name).then_some(Variant::RenderTargets)
    }
}

/// The frame's setup from the scene and the parameters, its receivers `previous` where they did
/// not change.
fn setup(
    params: &YukselParams,
    scene: &Scene,
    previous: Option<&Frame>,
) -> Result<YukselSetup, GpuError> {
    let w = scene_water(scene, "yuksel")?;
    let previous = previous.and_then(|f| f.setup().receivers.as_ref());
    Ok(YukselSetup::new(
        params,
        scene.caustics.width as usize,
        scene.caustics.height as usize,
        w.size,
        w.depth,
        w.ior,
        w.absorption,
        w.wrap,
        scene.light.direction,
    )?
    .with_floor(&scene.floor, previous))
}

impl Pipelines for Yuksel {
    type Params = (YukselParams, Variant);
    type Frame = Frame;

    fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Yuksel::new(ctx)
    }

    fn params(entry: &'static Descriptor, tables: &toml::Table) -> Result<Self::Params, GpuError> {
        let params = YukselParams::from_table(tables)?;
        let variant = Variant::of(&params, Variant::fixed_by(entry))?;
        Ok((params, variant))
    }

    /// The map's own lattice, as the Runner samples the surface for the CPU twin.
    fn water_resolution(_: &Self::Params, scene: &Scene) -> (u32, u32) {
        (scene.caustics.width, scene.caustics.height)
    }

    fn frame(
        &self,
        ctx: &GpuContext,
        (params, variant): &Self::Params,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<Frame, GpuError> {
        let setup = setup(params, scene, None)?;
        self.frame_with_water(ctx, &setup, water, *variant)
    }

    fn refit(
        &self,
        ctx: &GpuContext,
        (params, _): &Self::Params,
        frame: &mut Frame,
        scene: &Scene,
    ) -> Result<bool, GpuError> {
        let setup = setup(params, scene, Some(frame))?;
        if *frame.setup() == setup {
            return Ok(true);
        }
        if frame.fits(&setup) {
            frame.set_setup(ctx, &setup);
            return Ok(true);
        }
        Ok(false)
    }

    fn encode(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        timer: Option<&mut GpuTimer>,
    ) {
        Yuksel::encode(self, frame, encoder, timer);
    }

    fn output<'a>(&'a self, frame: &'a Frame) -> Output<'a> {
        Output::Floor(frame.floor_map())
    }

    fn receivers(frame: &Frame) -> Option<&ReceiverFrame> {
        frame.receivers.as_ref()
    }

    fn bytes(frame: &Frame) -> u64 {
        frame.bytes()
    }

    fn run_once(
        &mut self,
        ctx: &GpuContext,
        entry: &'static Descriptor,
        job: &Job,
        tables: &toml::Table,
        timer: Option<&mut GpuTimer>,
        _progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError> {
        let (setup, heights) = yuksel::job_setup(job, tables)?;
        let (_, variant) = Self::params(entry, tables)?;
        let map = self.caustics(ctx, &setup, &heights, variant, timer)?;
        Ok(JobOutput::floor(map, None))
    }
}
