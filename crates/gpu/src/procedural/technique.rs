//! Paper 2 behind [`Technique`]: its three variants, the caller's heights, a new sun as one uniform
//! write (the light map is the sky around the sun, the same whichever way the sun stands, so it is
//! uploaded once).

use caustics_core::scene::{Scene, WaterSource};
use caustics_core::techniques::procedural::{
    self, ProceduralCausticsParams, ProceduralSetup, SurfaceInput, Variant,
};
use caustics_core::techniques::{Job, Made};
use glam::DVec3;

use super::{Frame, ProceduralCaustics};
use crate::technique::{Fit, Output, Registered, RunOnce, Technique, WaterTextures};
use crate::yuksel::technique::water;
use crate::{GpuContext, GpuError, GpuTimer};

pub struct ProceduralTechnique {
    name: String,
    pipelines: ProceduralCaustics,
    params: ProceduralCausticsParams,
    /// The parameters with the smallest generated light map: what [`update`](Technique::update)
    /// derives a new sun's setup from, keeping the frame's own light map (which no sun changes)
    /// instead of generating or loading it again.
    sun_params: ProceduralCausticsParams,
    /// The variant the registered name forces, if any.
    fixed: Option<Variant>,
    frame: Option<(Frame, WaterTextures, SceneKey)>,
}

/// What the setup takes from the scene: when it is unchanged, [`update`](Technique::update) does
/// nothing.
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

/// `procedural`: the variant its parameters name (`variant`, screen by default).
pub fn create(ctx: &GpuContext, params: &toml::Table) -> Result<Box<dyn Technique>, GpuError> {
    ProceduralTechnique::new(ctx, params, None).map(|t| Box::new(t) as _)
}

pub fn create_vertex(
    ctx: &GpuContext,
    params: &toml::Table,
) -> Result<Box<dyn Technique>, GpuError> {
    ProceduralTechnique::new(ctx, params, Some(Variant::Vertex)).map(|t| Box::new(t) as _)
}

pub fn create_screen(
    ctx: &GpuContext,
    params: &toml::Table,
) -> Result<Box<dyn Technique>, GpuError> {
    ProceduralTechnique::new(ctx, params, Some(Variant::Screen)).map(|t| Box::new(t) as _)
}

pub fn create_texture(
    ctx: &GpuContext,
    params: &toml::Table,
) -> Result<Box<dyn Technique>, GpuError> {
    ProceduralTechnique::new(ctx, params, Some(Variant::Texture)).map(|t| Box::new(t) as _)
}

impl ProceduralTechnique {
    /// `variant`: the one a registered name forces; a table naming another is refused.
    pub fn new(
        ctx: &GpuContext,
        params: &toml::Table,
        variant: Option<Variant>,
    ) -> Result<Self, GpuError> {
        let (params, sun_params) = Self::read(params, variant)?;
        Ok(ProceduralTechnique {
            name: format!("procedural-{}", params.variant.name()),
            pipelines: ProceduralCaustics::new(ctx)?,
            params,
            sun_params,
            fixed: variant,
            frame: None,
        })
    }

    /// The parameters from the tables, and the sun's (no light map), with the variant `fixed`
    /// forces.
    fn read(
        table: &toml::Table,
        fixed: Option<Variant>,
    ) -> Result<(ProceduralCausticsParams, ProceduralCausticsParams), GpuError> {
        let mut params = ProceduralCausticsParams::from_table(table)?;
        if let Some(v) = fixed {
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
        let sun_params = ProceduralCausticsParams {
            light_map: None,
            light_map_resolution: 2,
            ..params.clone()
        };
        Ok((params, sun_params))
    }

    fn key(scene: &Scene) -> Result<SceneKey, GpuError> {
        caustics_core::techniques::procedural::DESCRIPTOR.check_floor(scene)?;
        caustics_core::techniques::procedural::DESCRIPTOR.check_light(&scene.light)?;
        let w = water(scene, "procedural")?;
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

    /// The setup for `key` from `params`, as the application's Runner builds it for a water job.
    fn setup(
        params: &ProceduralCausticsParams,
        key: &SceneKey,
    ) -> Result<ProceduralSetup, GpuError> {
        Ok(ProceduralSetup::new(
            params,
            key.width as usize,
            key.height as usize,
            key.size,
            key.depth,
            key.absorption,
            key.wrap,
            key.light,
        )?)
    }
}

impl Technique for ProceduralTechnique {
    fn name(&self) -> &str {
        &self.name
    }

    /// The grid the application samples for the CPU twin (`procedural_heights`): a height-field
    /// file's own samples, or the surface at least as finely as the lattice the variant evaluates
    /// on (the map, the mesh's vertices, or the texture-space target).
    fn water_resolution(&self, scene: &Scene) -> (u32, u32) {
        let n = match self.params.variant {
            Variant::Vertex => self.params.mesh_resolution + 1,
            Variant::Screen => 0,
            Variant::Texture => self.params.target_resolution,
        };
        match scene.water.as_ref().map(|w| &w.source) {
            Some(WaterSource::HeightField(g)) => (g.cols as u32, g.rows as u32),
            _ => (scene.caustics.width.max(n), scene.caustics.height.max(n)),
        }
    }

    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError> {
        let key = Self::key(scene)?;
        let setup = Self::setup(&self.params, &key)?;
        self.frame = None;
        if scene.floor.walls {
            tracing::warn!(
                "{}",
                caustics_core::techniques::floor_only_note(self.name())
            );
        }
        let frame = self.pipelines.frame_with_water(ctx, &setup, water)?;
        self.frame = Some((frame, water.clone(), key));
        Ok(())
    }

    fn write_scene(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<Fit, GpuError> {
        let key = Self::key(scene)?;
        let Some((frame, water, old)) = &mut self.frame else {
            return Err(GpuError::BadOption(
                "procedural: update before configure".into(),
            ));
        };
        if *old == key {
            return Ok(Fit::Written);
        }
        let mut setup = Self::setup(&self.sun_params, &key)?;
        setup.light = frame.setup().light.clone();
        if frame.fits(&setup) {
            frame.set_setup(ctx, &setup);
            *old = key;
            return Ok(Fit::Written);
        }
        Ok(Fit::Reconfigure(water.clone()))
    }

    fn encode(&self, encoder: &mut wgpu::CommandEncoder, timer: Option<&mut GpuTimer>) {
        if let Some((frame, _, _)) = &self.frame {
            self.pipelines.encode(frame, encoder, timer);
        }
    }

    fn output(&self) -> Option<Output<'_>> {
        self.frame.as_ref().map(|(f, _, _)| Output::Floor(&f.map))
    }

    fn bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |(f, _, _)| f.bytes())
    }

    /// In place unless the variant changes (it names the technique).
    fn set_params(&mut self, params: &toml::Table) -> Result<bool, GpuError> {
        let (params, sun_params) = Self::read(params, self.fixed)?;
        if params.variant != self.params.variant {
            return Ok(false);
        }
        (self.params, self.sun_params) = (params, sun_params);
        Ok(true)
    }
}

/// `procedural` in the registry: the variant its table names.
pub const REGISTERED: Registered = Registered {
    describe: &procedural::DESCRIPTOR,
    create,
    once: Once::create,
    image: None,
};

pub const VERTEX: Registered = Registered {
    describe: &procedural::VERTEX,
    create: create_vertex,
    once: Once::create,
    image: None,
};

pub const SCREEN: Registered = Registered {
    describe: &procedural::SCREEN,
    create: create_screen,
    once: Once::create,
    image: None,
};

pub const TEXTURE: Registered = Registered {
    describe: &procedural::TEXTURE,
    create: create_texture,
    once: Once::create,
    image: None,
};

/// Paper 2 run once on a job (the variant from the table, which a variant's name pins).
struct Once(ProceduralCaustics);

impl Once {
    fn create(ctx: &GpuContext) -> Result<Box<dyn RunOnce>, GpuError> {
        Ok(Box::new(Once(ProceduralCaustics::new(ctx)?)))
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
        let (setup, heights) = procedural::job_setup(job, params)?;
        let map = self
            .0
            .caustics_timed(ctx, &setup, &SurfaceInput::Grid(&heights), timer)?;
        Ok(Made::floor(map, None))
    }
}
