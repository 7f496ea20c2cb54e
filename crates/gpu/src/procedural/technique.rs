//! Paper 2 behind the generic adapter: its three variants, the caller's heights, a new sun as one
//! uniform write (the light map is the sky around the sun, the same whichever way the sun stands,
//! so it is uploaded once).

use caustics_core::receivers::Shared;
use caustics_core::scene::{Scene, WaterSource};
use caustics_core::techniques::procedural::{
    self, ProceduralCausticsParams, ProceduralSetup, SurfaceInput, Variant,
};
use caustics_core::techniques::{Descriptor, Job, JobOutput};
use glam::DVec3;

use super::ProceduralCaustics;
use crate::adapter::Pipelines;
use crate::receivers::ReceiverFrame;
use crate::technique::{Output, Registered, WaterTextures, scene_water};
use crate::{GpuContext, GpuError, GpuTimer};

/// `procedural` in the registry: the variant its table names (screen by default).
pub const REGISTERED: Registered =
    Registered::of::<ProceduralCaustics>(&procedural::DESCRIPTOR, super::PASSES, None);
/// `procedural-vertex`: paper 2 per vertex of a fine ground mesh.
pub const VERTEX: Registered =
    Registered::of::<ProceduralCaustics>(&procedural::VERTEX, super::PASSES, None);
/// `procedural-screen`: paper 2 per pixel of the map.
pub const SCREEN: Registered =
    Registered::of::<ProceduralCaustics>(&procedural::SCREEN, super::PASSES, None);
/// `procedural-texture`: paper 2 into a fixed-size texture-space target, mipmapped.
pub const TEXTURE: Registered =
    Registered::of::<ProceduralCaustics>(&procedural::TEXTURE, super::PASSES, None);

/// The `procedural` techniques resident on the GPU.
pub type ProceduralTechnique = crate::adapter::Resident<ProceduralCaustics>;

/// The parameters, and the sun's: those with the smallest generated light map, what a new sun's
/// setup is derived from, keeping the frame's own light map (which no sun changes) instead of
/// generating or loading it again.
pub struct Params {
    params: ProceduralCausticsParams,
    sun: ProceduralCausticsParams,
}

/// A [`super::ProceduralFrame`] and the scene it was configured for, which `refit` compares a new
/// scene against.
pub struct ConfiguredProcedural {
    /// The frame the passes record, with the scene's setup.
    pub frame: super::ProceduralFrame,
    key: SceneKey,
}

/// What the setup takes from the scene: when it is unchanged, a frame's update does nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SceneKey {
    width: u32,
    height: u32,
    size: f64,
    depth: f64,
    absorption: DVec3,
    wrap: bool,
    light: DVec3,
}

impl SceneKey {
    fn of(scene: &Scene) -> Result<SceneKey, GpuError> {
        procedural::DESCRIPTOR.check_light(&scene.light)?;
        let w = scene_water(scene, "procedural")?;
        Ok(SceneKey {
            width: scene.caustics.width,
            height: scene.caustics.height,
            size: w.size,
            depth: w.depth,
            absorption: w.absorption,
            wrap: w.wrap,
            light: scene.light.direction,
        })
    }

    /// The setup for this key from `params` over `scene`'s floor, as the application's Runner
    /// builds it for a water job; its receivers `previous`'s where they did not change.
    fn setup(
        &self,
        params: &ProceduralCausticsParams,
        scene: &Scene,
        previous: Option<&ProceduralSetup>,
    ) -> Result<ProceduralSetup, GpuError> {
        Ok(ProceduralSetup::new(
            params,
            self.width as usize,
            self.height as usize,
            self.size,
            self.depth,
            self.absorption,
            self.wrap,
            self.light,
        )?
        .with_floor(&scene.floor, previous.and_then(|s| s.receivers.as_ref())))
    }
}

/// The variant registry entry `entry` pins, if any.
fn fixed_by(entry: &Descriptor) -> Option<Variant> {
    [Variant::Vertex, Variant::Screen, Variant::Texture]
        .into_iter()
        .find(|v| entry.name.strip_prefix("procedural-") == Some(v.name()))
}

impl Pipelines for ProceduralCaustics {
    type Params = Params;
    type Frame = ConfiguredProcedural;

    fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        ProceduralCaustics::new(ctx)
    }

    /// The variant a registered name pins; a table naming another is refused.
    fn params(entry: &'static Descriptor, table: &toml::Table) -> Result<Params, GpuError> {
        let mut params = ProceduralCausticsParams::from_table(table)?;
        if let Some(v) = fixed_by(entry) {
            if let Some(given) = table
                .get("procedural")
                .and_then(|t| t.get("variant"))
                .filter(|given| given.as_str() != Some(v.name()))
            {
                return Err(GpuError::BadOption(format!(
                    "technique `procedural-{}`: the name says variant `{}`, the parameters {given}",
                    v.name(),
                    v.name()
                )));
            }
            params.variant = v;
        }
        let sun = ProceduralCausticsParams {
            light_map: None,
            light_map_resolution: 2,
            ..params.clone()
        };
        Ok(Params { params, sun })
    }

    fn name(_: &'static Descriptor, params: &Params) -> &'static str {
        match params.params.variant {
            Variant::Vertex => procedural::VERTEX.name,
            Variant::Screen => procedural::SCREEN.name,
            Variant::Texture => procedural::TEXTURE.name,
        }
    }

    /// In place unless the variant changes (it names the technique).
    fn params_in_place(old: &Params, new: &Params) -> bool {
        old.params.variant == new.params.variant
    }

    /// The grid the application samples for the CPU twin (`procedural_heights`): a height-field
    /// file's own samples, or the surface at least as finely as the lattice the variant evaluates
    /// on (the map, the mesh's vertices, or the texture-space target).
    fn water_resolution(params: &Params, scene: &Scene) -> (u32, u32) {
        let p = &params.params;
        let n = match p.variant {
            Variant::Vertex => p.mesh_resolution + 1,
            Variant::Screen => 0,
            Variant::Texture => p.target_resolution,
        };
        match scene.water.as_ref().map(|w| &w.source) {
            Some(WaterSource::HeightField(g)) => (g.cols as u32, g.rows as u32),
            _ => (scene.caustics.width.max(n), scene.caustics.height.max(n)),
        }
    }

    fn frame(
        &self,
        ctx: &GpuContext,
        params: &Params,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<ConfiguredProcedural, GpuError> {
        let key = SceneKey::of(scene)?;
        let setup = key.setup(&params.params, scene, None)?;
        Ok(ConfiguredProcedural {
            frame: self.frame_with_water(ctx, &setup, water)?,
            key,
        })
    }

    fn refit(
        &self,
        ctx: &GpuContext,
        params: &Params,
        frame: &mut ConfiguredProcedural,
        scene: &Scene,
    ) -> Result<bool, GpuError> {
        let key = SceneKey::of(scene)?;
        let receivers = frame.frame.setup().receivers.as_ref();
        if frame.key == key && Shared::fits(receivers, &scene.floor) {
            return Ok(true);
        }
        let mut setup = key.setup(&params.sun, scene, Some(frame.frame.setup()))?;
        setup.light = frame.frame.setup().light.clone();
        if frame.frame.fits(&setup) {
            frame.frame.set_setup(ctx, &setup);
            frame.key = key;
            return Ok(true);
        }
        Ok(false)
    }

    fn encode(
        &self,
        frame: &ConfiguredProcedural,
        encoder: &mut wgpu::CommandEncoder,
        timer: Option<&mut GpuTimer>,
    ) {
        ProceduralCaustics::encode(self, &frame.frame, encoder, timer);
    }

    fn output<'a>(&'a self, frame: &'a ConfiguredProcedural) -> Output<'a> {
        Output::Floor(frame.frame.floor_map())
    }

    fn receivers(frame: &ConfiguredProcedural) -> Option<&ReceiverFrame> {
        frame.frame.receivers.as_ref()
    }

    fn bytes(frame: &ConfiguredProcedural) -> u64 {
        frame.frame.bytes()
    }

    /// The variant from the table, which a variant's name pins.
    fn run_once(
        &mut self,
        ctx: &GpuContext,
        _: &'static Descriptor,
        job: &Job,
        tables: &toml::Table,
        timer: Option<&mut GpuTimer>,
        _progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError> {
        let (setup, heights) = procedural::job_setup(job, tables)?;
        let map = self.caustics(ctx, &setup, &SurfaceInput::Grid(&heights), timer)?;
        Ok(JobOutput::floor(map, None))
    }
}
