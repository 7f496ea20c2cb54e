//! Paper 1 behind [`Technique`]: both variants, the caller's heights, sun and N changes as uniform
//! writes.

use caustics_core::scene::Scene;
use caustics_core::techniques::yuksel::{self, Passes, YukselParams, YukselSetup};
use caustics_core::techniques::{Job, Made};

use super::{Frame, Variant, Yuksel};
use crate::technique::{Fit, Output, Registered, RunOnce, Technique, WaterTextures};
use crate::{GpuContext, GpuError, GpuTimer};

pub struct YukselTechnique {
    name: &'static str,
    pipelines: Yuksel,
    params: YukselParams,
    /// The passes the registered name forces (`yuksel-targets`), if any.
    fixed: Option<Variant>,
    frame: Option<(Frame, WaterTextures)>,
}

/// `yuksel`: the passes its parameters name (`passes`; the scatter by default, the paper's preset
/// its render targets).
pub fn create(ctx: &GpuContext, params: &toml::Table) -> Result<Box<dyn Technique>, GpuError> {
    YukselTechnique::new(ctx, params, None).map(|t| Box::new(t) as _)
}

/// `yuksel-targets`: the paper's render-target passes whatever the preset.
pub fn create_render_targets(
    ctx: &GpuContext,
    params: &toml::Table,
) -> Result<Box<dyn Technique>, GpuError> {
    YukselTechnique::new(ctx, params, Some(Variant::RenderTargets)).map(|t| Box::new(t) as _)
}

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
}

impl YukselTechnique {
    pub fn new(
        ctx: &GpuContext,
        params: &toml::Table,
        fixed: Option<Variant>,
    ) -> Result<Self, GpuError> {
        let params = YukselParams::from_table(params)?;
        Variant::of(&params, fixed)?;
        Ok(YukselTechnique {
            name: match fixed {
                Some(_) => yuksel::TARGETS.name,
                None => yuksel::DESCRIPTOR.name,
            },
            pipelines: Yuksel::new(ctx)?,
            params,
            fixed,
            frame: None,
        })
    }

    fn variant(&self) -> Variant {
        Variant::of(&self.params, self.fixed).expect("checked when the parameters were taken")
    }

    fn setup(&self, scene: &Scene) -> Result<YukselSetup, GpuError> {
        caustics_core::techniques::yuksel::DESCRIPTOR.check_floor(scene)?;
        let w = water(scene, "yuksel")?;
        Ok(YukselSetup::new(
            &self.params,
            scene.caustics.width as usize,
            scene.caustics.height as usize,
            w.size,
            w.depth,
            w.ior,
            w.absorption,
            w.wrap,
            scene.light.direction,
        )?)
    }
}

/// The scene's water, or an error naming the technique that needs it.
pub(crate) fn water<'s>(
    scene: &'s Scene,
    technique: &str,
) -> Result<&'s caustics_core::scene::Water, GpuError> {
    scene.water.as_ref().ok_or_else(|| {
        GpuError::BadOption(format!(
            "scene `{}` has no water: technique `{technique}` computes caustics from a water surface",
            scene.name
        ))
    })
}

impl Technique for YukselTechnique {
    fn name(&self) -> &str {
        self.name
    }

    /// The map's own lattice, as the Runner samples the surface for the CPU twin.
    fn water_resolution(&self, scene: &Scene) -> (u32, u32) {
        (scene.caustics.width, scene.caustics.height)
    }

    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError> {
        let setup = self.setup(scene)?;
        self.frame = None;
        if scene.floor.walls {
            tracing::warn!(
                "{}",
                caustics_core::techniques::floor_only_note(self.name())
            );
        }
        let frame = self
            .pipelines
            .frame_with_water(ctx, &setup, water, self.variant())?;
        self.frame = Some((frame, water.clone()));
        Ok(())
    }

    fn write_scene(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<Fit, GpuError> {
        let setup = self.setup(scene)?;
        let Some((frame, water)) = &mut self.frame else {
            return Err(GpuError::BadOption(
                "yuksel: update before configure".into(),
            ));
        };
        if *frame.setup() == setup {
            return Ok(Fit::Written);
        }
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
        self.frame.as_ref().map(|(f, _)| Output::Floor(&f.map))
    }

    fn bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |(f, _)| f.bytes())
    }

    fn set_params(&mut self, params: &toml::Table) -> Result<bool, GpuError> {
        let params = YukselParams::from_table(params)?;
        Variant::of(&params, self.fixed)?;
        self.params = params;
        Ok(true)
    }
}

/// Paper 1 in the registry: the passes its parameters name.
pub const REGISTERED: Registered = Registered {
    describe: &yuksel::DESCRIPTOR,
    create,
    once: |ctx| Ok(Box::new(Once::new(ctx, None)?)),
    image: None,
};

/// Paper 1's render-target passes in the registry (`yuksel-targets`), whatever the preset.
pub const TARGETS: Registered = Registered {
    describe: &yuksel::TARGETS,
    create: create_render_targets,
    once: |ctx| Ok(Box::new(Once::new(ctx, Some(Variant::RenderTargets))?)),
    image: None,
};

/// Paper 1 run once on a job.
struct Once {
    pipelines: Yuksel,
    fixed: Option<Variant>,
}

impl Once {
    fn new(ctx: &GpuContext, fixed: Option<Variant>) -> Result<Self, GpuError> {
        Ok(Once {
            pipelines: Yuksel::new(ctx)?,
            fixed,
        })
    }
}

impl RunOnce for Once {
    fn run(
        &mut self,
        ctx: &GpuContext,
        job: &Job,
        params: &toml::Table,
        timer: Option<&mut GpuTimer>,
        _progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Made, GpuError> {
        let (setup, heights) = yuksel::job_setup(job, params)?;
        let variant = Variant::of(&YukselParams::from_table(params)?, self.fixed)?;
        let map = self
            .pipelines
            .caustics_timed(ctx, &setup, &heights, variant, timer)?;
        Ok(Made::floor(map, None))
    }
}
