//! The one adapter between a technique's own code and the two interfaces every front end uses, in
//! the spirit of wgpu's examples' small framework trait: a technique writes its pipelines and how
//! they build, refit and record a frame ([`Pipelines`]); [`Resident`] makes that the frame's
//! [`Technique`] and [`Once`] the tools' [`RunOnce`], and [`Registered::of`] its registry entry.

use caustics_core::scene::Scene;
use caustics_core::techniques::{Descriptor, Job, JobOutput};

use crate::receivers::ReceiverFrame;
use crate::shaders::PassSource;
use crate::technique::{
    MakeOwnImage, Output, Registered, RunOnce, Technique, WallsOutput, WaterTextures,
};
use crate::{GpuContext, GpuError, GpuTimer};

/// A technique's pipelines, built once per device, and what they do with a frame.
pub trait Pipelines: Sized + wgpu::WasmNotSendSync + 'static {
    /// The technique's reading of its parameter table.
    type Params: wgpu::WasmNotSendSync;
    /// The resources of one configured frame: textures, buffers, bind groups, and whatever of the
    /// scene [`refit`](Self::refit) compares against.
    type Frame: wgpu::WasmNotSendSync;

    /// Build the technique's pipelines (shader modules, layouts, samplers) for the device: once
    /// per device, whatever the parameters that do not change them.
    fn new(ctx: &GpuContext) -> Result<Self, GpuError>;

    /// The parameters of registry entry `entry` from the tables keyed by technique (a variant's
    /// name pins some of them: a table that says otherwise is refused by name).
    fn params(entry: &'static Descriptor, tables: &toml::Table) -> Result<Self::Params, GpuError>;

    /// The name a frame goes by (the entry's, unless the parameters choose a variant).
    fn name(entry: &'static Descriptor, params: &Self::Params) -> &'static str {
        let _ = params;
        entry.name
    }

    /// Whether `new` can replace `old` without building the pipelines again.
    fn params_in_place(old: &Self::Params, new: &Self::Params) -> bool {
        let _ = (old, new);
        true
    }

    /// The height grid (cols, rows) the technique reads the water through ([`Technique::water_resolution`]).
    fn water_resolution(params: &Self::Params, scene: &Scene) -> (u32, u32);

    /// Build a frame's resources for `scene` and `water` ([`Technique::configure`]).
    fn frame(
        &self,
        ctx: &GpuContext,
        params: &Self::Params,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<Self::Frame, GpuError>;

    /// Take `scene`'s sun, camera and parameters as uniform writes where `frame` still fits them:
    /// `Ok(true)` when it does (nothing written when nothing changed), `Ok(false)` when the sizes
    /// changed and the frame must be built again.
    fn refit(
        &self,
        ctx: &GpuContext,
        params: &Self::Params,
        frame: &mut Self::Frame,
        scene: &Scene,
    ) -> Result<bool, GpuError>;

    /// Record the frame's passes into the caller's encoder, timing each one on `timer`
    /// ([`Technique::encode`]).
    fn encode(
        &self,
        frame: &Self::Frame,
        encoder: &mut wgpu::CommandEncoder,
        timer: Option<&mut GpuTimer>,
    );

    /// The texture `frame`'s passes end in ([`Technique::output`]).
    fn output<'a>(&'a self, frame: &'a Self::Frame) -> Output<'a>;

    /// The walls' maps, where the technique lights them.
    fn walls(frame: &Self::Frame) -> Option<WallsOutput<'_>> {
        let _ = frame;
        None
    }

    /// The receivers the frame's light meets and its light-space deposit, where it has them
    /// ([`Technique::receivers`]).
    fn receivers(frame: &Self::Frame) -> Option<&ReceiverFrame> {
        let _ = frame;
        None
    }

    /// GPU memory of the frame, bytes.
    fn bytes(frame: &Self::Frame) -> u64;

    /// Run the technique once on a job and read its maps back ([`RunOnce::run`]).
    fn run_once(
        &mut self,
        ctx: &GpuContext,
        entry: &'static Descriptor,
        job: &Job,
        tables: &toml::Table,
        timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError>;
}

/// A technique resident on the GPU: its pipelines, its parameters and its configured frame.
pub struct Resident<P: Pipelines> {
    entry: &'static Descriptor,
    pipelines: P,
    params: P::Params,
    frame: Option<(P::Frame, WaterTextures)>,
}

impl<P: Pipelines> Resident<P> {
    /// Build the pipelines and read the parameters of registry entry `entry` from `tables`
    /// (keyed by technique); no frame until [`Technique::configure`].
    pub fn new(
        entry: &'static Descriptor,
        ctx: &GpuContext,
        tables: &toml::Table,
    ) -> Result<Self, GpuError> {
        let params = P::params(entry, tables)?;
        Ok(Resident {
            entry,
            pipelines: P::new(ctx)?,
            params,
            frame: None,
        })
    }

    fn create(
        entry: &'static Descriptor,
        ctx: &GpuContext,
        tables: &toml::Table,
    ) -> Result<Box<dyn Technique>, GpuError> {
        Ok(Box::new(Self::new(entry, ctx, tables)?))
    }

    /// The configured frame, for tests and tools.
    pub fn frame(&self) -> Option<&P::Frame> {
        self.frame.as_ref().map(|(f, _)| f)
    }
}

impl<P: Pipelines> Technique for Resident<P> {
    fn name(&self) -> &str {
        P::name(self.entry, &self.params)
    }

    fn water_resolution(&self, scene: &Scene) -> (u32, u32) {
        P::water_resolution(&self.params, scene)
    }

    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError> {
        self.frame = None;
        let frame = self.pipelines.frame(ctx, &self.params, scene, water)?;
        if scene.floor.walls && self.entry.floor_only() {
            tracing::warn!(
                "{}",
                caustics_core::techniques::floor_only_note(self.name())
            );
        }
        self.frame = Some((frame, water.clone()));
        Ok(())
    }

    fn write_scene(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
    ) -> Result<crate::technique::SceneWrite, GpuError> {
        let name = P::name(self.entry, &self.params);
        let Some((frame, water)) = &mut self.frame else {
            return Err(GpuError::BadOption(format!(
                "{name}: update before configure"
            )));
        };
        if self.pipelines.refit(ctx, &self.params, frame, scene)? {
            Ok(crate::technique::SceneWrite::Written)
        } else {
            Ok(crate::technique::SceneWrite::Reconfigure(water.clone()))
        }
    }

    fn encode(&self, encoder: &mut wgpu::CommandEncoder, timer: Option<&mut GpuTimer>) {
        if let Some((frame, _)) = &self.frame {
            self.pipelines.encode(frame, encoder, timer);
        }
    }

    fn output(&self) -> Option<Output<'_>> {
        let (frame, _) = self.frame.as_ref()?;
        Some(self.pipelines.output(frame))
    }

    fn walls(&self) -> Option<WallsOutput<'_>> {
        P::walls(&self.frame.as_ref()?.0)
    }

    fn receivers(&self) -> Option<&ReceiverFrame> {
        P::receivers(&self.frame.as_ref()?.0)
    }

    fn bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |(f, _)| P::bytes(f))
    }

    fn set_params(&mut self, tables: &toml::Table) -> Result<bool, GpuError> {
        let params = P::params(self.entry, tables)?;
        if !P::params_in_place(&self.params, &params) {
            return Ok(false);
        }
        self.params = params;
        Ok(true)
    }
}

/// A technique's pipelines kept between runs on jobs.
pub struct Once<P: Pipelines> {
    entry: &'static Descriptor,
    pipelines: P,
}

impl<P: Pipelines> Once<P> {
    fn create(entry: &'static Descriptor, ctx: &GpuContext) -> Result<Box<dyn RunOnce>, GpuError> {
        Ok(Box::new(Once::<P> {
            entry,
            pipelines: P::new(ctx)?,
        }))
    }
}

impl<P: Pipelines> RunOnce for Once<P> {
    fn run(
        &mut self,
        ctx: &GpuContext,
        job: &Job,
        params: &toml::Table,
        timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError> {
        self.pipelines
            .run_once(ctx, self.entry, job, params, timer, progress)
    }
}

impl Registered {
    /// The registry entry of a technique whose pipelines are `P`: `describe` its description,
    /// `passes` every pass it builds, `image` its own final image where its paper ends in one.
    pub const fn of<P: Pipelines>(
        describe: &'static Descriptor,
        passes: &'static [&'static PassSource],
        image: Option<MakeOwnImage>,
    ) -> Registered {
        Registered {
            describe,
            passes,
            make: Resident::<P>::create,
            make_once: Once::<P>::create,
            image,
        }
    }
}
