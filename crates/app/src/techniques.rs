//! Running any registered technique on a [`Job`]: on the GPU when there is a device and the
//! technique has a GPU implementation (`caustics_gpu::registry::REGISTRY`), on its CPU twin
//! otherwise. No technique is named here: both forms are reached from the registry's entry.

use std::collections::HashMap;

use anyhow::{Context, Result};

use caustics_core::map::CausticsMap;
pub use caustics_core::techniques::{Job, SceneCaustics, Spec};
use caustics_gpu::technique::RunOnce;
use caustics_gpu::{GpuContext, GpuTimer, PassTime};

/// What a run made, and where it ran.
pub struct Outcome {
    pub caustics: SceneCaustics,
    /// "GPU" or "CPU".
    pub backend: &'static str,
    /// The pool's walls' maps, from a technique that lights them when the scene's walls are on
    /// (`render --raw-walls`, the final image); `None` from a floor-only technique.
    pub walls: Option<caustics_core::walls::WallMaps>,
    /// The light-space deposit the floor map was looked up from, where objects are among the
    /// technique's receivers (their light in the final image); from the CPU twins.
    pub light: Option<caustics_core::receivers::LightSpace>,
}

impl Outcome {
    /// The floor map, or an error naming the technique that made an eye-space image.
    pub fn map(self, technique: &str) -> Result<CausticsMap> {
        Ok(self.caustics.into_floor(technique)?)
    }
}

/// A GPU technique's output read back (the viewer's map window, `render --raw`): a floor map of
/// the water square `size`, or an eye-space image whose texels are the CPU twin's as they are
/// (flag < 0 where a pixel has no value).
pub fn read_output(
    ctx: &GpuContext,
    output: caustics_gpu::Output,
    size: f64,
) -> Result<SceneCaustics> {
    let texture = output.texture();
    let texels = ctx.read_rgba_f32(texture)?;
    let (width, height) = (texture.width() as usize, texture.height() as usize);
    Ok(match output {
        caustics_gpu::Output::Floor(_) => SceneCaustics::Floor(CausticsMap {
            width,
            height,
            size,
            texels: texels.iter().map(|t| [t[0], t[1], t[2]]).collect(),
        }),
        caustics_gpu::Output::EyeSpace(_) => {
            SceneCaustics::EyeSpace(caustics_core::render::EyeSpaceCaustics {
                width,
                height,
                texels,
            })
        }
    })
}

/// Passes one technique run can time (procedural's texture variant has the most: a target, one
/// downsample per mip level, a resample).
const TIMED_PASSES: u32 = 32;

/// Runs techniques, keeping their GPU pipelines between runs.
pub struct Runner {
    /// The device: the techniques' unless [`twins_only`](Self::twins_only), a window's either way.
    pub gpu: Option<GpuContext>,
    /// Run every technique on its CPU twin though a device exists (`view --cpu`: the window
    /// still draws through the device).
    twins_only: bool,
    /// Timestamps of the technique passes, once [`time_passes`](Self::time_passes) turned them on.
    timer: Option<GpuTimer>,
    /// Each GPU technique's run-once form, made the first time it runs.
    once: HashMap<&'static str, Box<dyn RunOnce>>,
}

impl Runner {
    pub fn new(gpu: Option<GpuContext>) -> Self {
        Runner {
            gpu,
            twins_only: false,
            timer: None,
            once: HashMap::new(),
        }
    }

    /// The runner with every technique on its CPU twin, the device kept for whoever draws.
    pub fn twins_only(mut self) -> Self {
        self.twins_only = true;
        self
    }

    /// The device the techniques run on: none where they run on their CPU twins.
    pub fn compute(&self) -> Option<&GpuContext> {
        compute_device(&self.gpu, self.twins_only)
    }

    /// Time every GPU pass of the techniques run from now on, where the adapter has timestamp
    /// queries (the viewer's overlay); [`take_gpu_times`](Self::take_gpu_times) reads them.
    pub fn time_passes(&mut self) {
        if let Some(ctx) = self.compute().filter(|c| c.timestamps) {
            self.timer = Some(GpuTimer::new(ctx, TIMED_PASSES));
        }
    }

    /// The GPU time of each technique pass run since the last call (empty without timestamps).
    pub fn take_gpu_times(&mut self) -> Result<Vec<PassTime>> {
        match (self.timer.as_mut(), self.gpu.as_ref()) {
            (Some(t), Some(ctx)) => t.read(ctx).context("reading the technique timestamps"),
            _ => Ok(Vec::new()),
        }
    }

    /// Runs `spec` on `job`, reporting `progress(done, total)` where the technique is long (the
    /// reference).
    pub fn run(
        &mut self,
        spec: &Spec,
        job: &Job,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Outcome> {
        spec.entry.check_light(&job.scene.light)?;
        // The fields apart (not `compute()`): `once` is borrowed mutably beside the device.
        let compute = compute_device(&self.gpu, self.twins_only);
        let (made, backend) = match (compute, caustics_gpu::registry::find(spec.name())) {
            (Some(ctx), Some(entry)) => {
                let once = match self.once.entry(spec.name()) {
                    std::collections::hash_map::Entry::Occupied(o) => o.into_mut(),
                    std::collections::hash_map::Entry::Vacant(v) => v.insert(entry.once(ctx)?),
                };
                (
                    once.run(ctx, job, &spec.params, self.timer.as_mut(), progress)?,
                    "GPU",
                )
            }
            _ => (spec.run_cpu(job, progress)?, "CPU"),
        };
        Ok(Outcome {
            caustics: made.caustics,
            backend,
            walls: made.walls,
            light: made.light,
        })
    }
}

/// [`Runner::compute`]'s rule on the runner's fields.
fn compute_device(gpu: &Option<GpuContext>, twins_only: bool) -> Option<&GpuContext> {
    gpu.as_ref().filter(|_| !twins_only)
}
