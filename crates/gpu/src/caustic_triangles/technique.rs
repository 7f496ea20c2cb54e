//! Paper 4 behind the generic adapter, one entry for both generators the scene can have:
//!
//! - **Water** (a scene with water): the water surface is the generator ([`WaterFrame`]) and reads
//!   the caller's heights texture; the copy band pass fits the shifted copies of tiling water on
//!   the GPU, so a frame reads nothing back and uploads nothing but a changed uniform.
//! - **Glass** (a scene without water): one [`GeneratorFrame`] per glass object, its distance map
//!   built on the CPU at configure (`DistanceMap::build`: it depends on the objects only, so it is
//!   rebuilt when they move, and moving them is a configure), every generator drawing additively
//!   into one floor map cleared by the first. A moving light is a uniform write per generator.
//!
//! The map is the floor square `[0, size]²` at the scene's caustics resolution, as the CPU twin's
//! (`caustics_core::techniques::caustic_triangles::render`).

use caustics_core::receivers::ReceiverHeights;
use caustics_core::scene::{Light, Scene, WaterSource};
use caustics_core::techniques::caustic_triangles as ct;
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_core::techniques::caustic_triangles::{
    CausticTrianglesParams, CausticTrianglesSetup, DistanceMap, GlassScene, PointLight,
};
use caustics_core::techniques::{Descriptor, Job, JobOutput};

use super::{
    CausticTriangles, CausticTrianglesUniform, GeneratorFrame, Reconstruction, WaterFrame,
};
use crate::adapter::Pipelines;
use crate::receivers::ReceiverFrame;
use crate::technique::{Output, OwnImage, Registered, WallsOutput, WaterTextures};
use crate::{GpuContext, GpuError, GpuTimer};

/// Paper 4 in the registry.
pub const REGISTERED: Registered =
    Registered::of::<CausticTriangles>(&ct::DESCRIPTOR, super::PASSES, Some(own_image));

/// The `caustic-triangles` technique resident on the GPU.
pub type CausticTrianglesTechnique = crate::adapter::Resident<CausticTriangles>;

/// A configured frame: the water surface as the generator, or the scene's glass objects.
pub enum State {
    /// The water surface as the one generator, lighting the floor (and walls).
    Water(Box<WaterFrame>),
    /// The scene's glass objects, one generator each, drawing into one shared floor map.
    Glass {
        /// One per glass object, in the scene's order.
        generators: Vec<Generator>,
        /// The floor map every generator draws into.
        map: wgpu::Texture,
        /// The light and map size the generators' uniforms hold.
        light: LightKey,
    },
}

/// One glass object as a generator.
pub struct Generator {
    /// The object, its occluders and the light, as `GlassScene::from_scene` made them at
    /// configure (the BVHs built once).
    scene: GlassScene,
    /// Its distance map's frame (centre, radius, sizes) for the uniform; the texels are on the
    /// GPU only.
    dm: DistanceMap,
    frame: GeneratorFrame,
}

/// What the glass generators' uniforms depend on in a scene, besides the objects.
#[derive(Clone, Debug, PartialEq)]
pub struct LightKey {
    direction: glam::DVec3,
    position: Option<glam::DVec3>,
    cone: Option<f64>,
    width: u32,
    height: u32,
    size: f64,
}

impl LightKey {
    fn of(scene: &Scene) -> Self {
        let Light {
            direction,
            position,
            cone,
            ..
        } = scene.light;
        LightKey {
            direction,
            position,
            cone,
            width: scene.caustics.width,
            height: scene.caustics.height,
            size: scene.size,
        }
    }
}

impl CausticTrianglesTechnique {
    /// The water generator's frame (its photon image, copy band, map), for tests and tools.
    pub fn water_frame(&self) -> Option<&WaterFrame> {
        match self.frame()? {
            State::Water(frame) => Some(frame),
            State::Glass { .. } => None,
        }
    }
}

/// The water generator's setup for `scene` (the app's water job: the sun, the map at the scene's
/// caustics resolution over the water square, the terrain's receivers, `previous` where they did
/// not change).
fn water_setup(
    params: &CausticTrianglesParams,
    scene: &Scene,
    previous: Option<&std::sync::Arc<ReceiverHeights>>,
) -> Result<WaterSetup, GpuError> {
    let water = scene.water.as_ref().expect("a water scene");
    if !scene.light.is_sun() {
        return Err(GpuError::BadOption(format!(
            "scene `{}`: caustic-triangles lights its water surface with the directional sun only (light.position is set)",
            scene.name
        )));
    }
    Ok(WaterSetup::new(
        params,
        water,
        scene.light.direction,
        scene.caustics.width as usize,
        scene.caustics.height as usize,
    )?
    .with_walls(scene.floor.walls)
    .with_floor(&scene.floor, previous))
}

/// A generator per glass object, drawing into one floor map.
fn configure_glass(
    pipelines: &CausticTriangles,
    ctx: &GpuContext,
    params: &CausticTrianglesParams,
    scene: &Scene,
) -> Result<State, GpuError> {
    let count = scene
        .objects
        .iter()
        .filter(|o| matches!(o.material, caustics_core::scene::Material::Glass { .. }))
        .count();
    if count == 0 {
        return Err(GpuError::BadOption(format!(
            "scene `{}` has neither water nor a glass object: caustic-triangles needs a caustic generator",
            scene.name
        )));
    }
    let mut generators: Vec<Generator> = Vec::with_capacity(count);
    for k in 0..count {
        let gs = GlassScene::from_scene(scene, k)?;
        let mut dm =
            DistanceMap::build(&gs, params.cube_resolution as usize, params.layers as usize);
        let setup = CausticTrianglesSetup::new(params, &gs)?;
        let shared = generators.first().map(|g| &g.frame.map);
        let frame = pipelines.frame_drawing_into(ctx, &setup, &dm, shared)?;
        dm.texels = Vec::new();
        generators.push(Generator {
            scene: gs,
            dm,
            frame,
        });
    }
    let map = generators[0].frame.map.clone();
    Ok(State::Glass {
        generators,
        map,
        light: LightKey::of(scene),
    })
}

/// `gs` under `light` (same generator, occluders and floor).
fn relit(gs: &GlassScene, light: &Light) -> Result<GlassScene, GpuError> {
    let sun = GlassScene::new(
        gs.generator.clone(),
        gs.ior,
        light.direction,
        gs.floor,
        gs.occluders.clone(),
    )?;
    Ok(match light.position {
        None => sun,
        Some(position) => sun.with_point_light(PointLight {
            position,
            axis: light.direction,
            cone: light.cone,
        })?,
    })
}

/// Paper 4 ends in its own camera pass (§4.3) on a scene of glass objects: lit through the light
/// cube map of a point light or the floor map of the sun. With water, the water surface is its
/// generator and its floor map lights the general final image (`None`).
fn own_image(
    ctx: Option<&GpuContext>,
    scene: &Scene,
    params: &toml::Table,
) -> Result<Option<OwnImage>, GpuError> {
    if scene.water.is_some() {
        return Ok(None);
    }
    let params = CausticTrianglesParams::from_table(params)?;
    let (image, backend) = super::camera::scene_image(
        ctx,
        scene,
        &params,
        &ct::camera::CameraParams::from_scene(scene),
    )?;
    Ok(Some(OwnImage {
        width: image.width,
        height: image.height,
        rgb: image.rgb,
        backend,
        what: "through its camera pass",
    }))
}

impl Pipelines for CausticTriangles {
    type Params = CausticTrianglesParams;
    type Frame = State;

    fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        CausticTriangles::new(ctx)
    }

    fn params(_: &'static Descriptor, tables: &toml::Table) -> Result<Self::Params, GpuError> {
        Ok(CausticTrianglesParams::from_table(tables)?)
    }

    /// The water generator reads the grid the app's water job samples (`heights_for`): a
    /// height-field file's own samples, else the map's lattice. Glass generators read no water:
    /// a 1 x 1 texture configures them.
    fn water_resolution(_: &Self::Params, scene: &Scene) -> (u32, u32) {
        match scene.water.as_ref().map(|w| &w.source) {
            None => (1, 1),
            Some(WaterSource::HeightField(g)) => (g.cols as u32, g.rows as u32),
            Some(_) => (scene.caustics.width, scene.caustics.height),
        }
    }

    fn frame(
        &self,
        ctx: &GpuContext,
        params: &Self::Params,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<State, GpuError> {
        if scene.water.is_some() {
            let ws = water_setup(params, scene, None)?;
            Ok(State::Water(Box::new(
                self.water_frame_with_water(ctx, &ws, water)?,
            )))
        } else {
            configure_glass(self, ctx, params, scene)
        }
    }

    /// The sun (water) or the light (glass) as uniform writes, none when they did not change; a
    /// new map size, or water appearing or going, configures again.
    fn refit(
        &self,
        ctx: &GpuContext,
        params: &Self::Params,
        state: &mut State,
        scene: &Scene,
    ) -> Result<bool, GpuError> {
        let previous = match &*state {
            State::Water(frame) => frame.setup.receivers.clone(),
            State::Glass { .. } => None,
        };
        let ws = match scene.water {
            Some(_) => Some(water_setup(params, scene, previous.as_ref())?),
            None => None,
        };
        match (state, ws) {
            (State::Water(frame), Some(ws)) => {
                if frame.fits(&ws) {
                    frame.set_setup(ctx, &ws);
                    return Ok(true);
                }
                Ok(false)
            }
            (
                State::Glass {
                    generators, light, ..
                },
                None,
            ) => {
                let key = LightKey::of(scene);
                if key == *light {
                    return Ok(true);
                }
                if (key.width, key.height, key.size) != (light.width, light.height, light.size) {
                    return Ok(false);
                }
                let mut next = Vec::with_capacity(generators.len());
                for g in generators.iter() {
                    let gs = relit(&g.scene, &scene.light)?;
                    let setup = CausticTrianglesSetup::new(params, &gs)?;
                    next.push((gs, setup));
                }
                for (g, (gs, setup)) in generators.iter_mut().zip(next) {
                    let old = CausticTrianglesUniform::new(&g.frame.setup, &g.dm);
                    let new = CausticTrianglesUniform::new(&setup, &g.dm);
                    if bytemuck::bytes_of(&old) != bytemuck::bytes_of(&new) {
                        ctx.write_pod(&g.frame.uniform, &new);
                    }
                    g.scene = gs;
                    g.frame.setup = setup;
                }
                *light = key;
                Ok(true)
            }
            (State::Water(_), None) | (State::Glass { .. }, Some(_)) => Ok(false),
        }
    }

    fn encode(
        &self,
        state: &State,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        match state {
            State::Water(frame) => {
                self.encode_water(frame, encoder, timer, Reconstruction::Triangles);
            }
            State::Glass { generators, .. } => {
                for (k, g) in generators.iter().enumerate() {
                    let f = &g.frame;
                    self.encode_photons(f, encoder, timer.as_deref_mut());
                    self.encode_irradiance(f, encoder, timer.as_deref_mut());
                    self.draw_floor(
                        f,
                        encoder,
                        timer.as_deref_mut(),
                        Reconstruction::Triangles,
                        &f.map_view,
                        k == 0,
                    );
                }
            }
        }
    }

    fn output<'a>(&'a self, state: &'a State) -> Output<'a> {
        match state {
            State::Water(frame) => Output::Floor(frame.floor_map()),
            State::Glass { map, .. } => Output::Floor(map),
        }
    }

    /// The water generator's wall maps on a scene with walls (glass scenes have none), in the
    /// floor map's format (`Rgba16Float` where the device cannot blend 32-bit floats).
    fn walls(state: &State) -> Option<WallsOutput<'_>> {
        match state {
            State::Water(frame) => frame
                .walls
                .as_ref()
                .map(|w| WallsOutput::of(&w.texture, &w.layout)),
            State::Glass { .. } => None,
        }
    }

    fn receivers(state: &State) -> Option<&ReceiverFrame> {
        match state {
            State::Water(frame) => frame.receivers.as_ref(),
            State::Glass { .. } => None,
        }
    }

    fn bytes(state: &State) -> u64 {
        match state {
            State::Water(frame) => frame.bytes(),
            // The first generator's frame owns the shared map and counts it.
            State::Glass { generators, .. } => generators.iter().map(|g| g.frame.bytes()).sum(),
        }
    }

    /// The water surface as the generator where the scene has water, else each glass object in
    /// turn, their maps added.
    fn run_once(
        &mut self,
        ctx: &GpuContext,
        _: &'static Descriptor,
        job: &Job,
        params: &toml::Table,
        mut timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError> {
        let gpu = &*self;
        if job.scene.water.is_some() {
            let (ws, heights) = ct::water_job_setup(job, params)?;
            let (map, walls) = gpu.water_caustics_walls(ctx, &ws, &heights, timer)?;
            progress(1, 1);
            return Ok(JobOutput::floor(map, walls));
        }
        let params = CausticTrianglesParams::from_table(params)?;
        let glass = ct::glass_generators(job.scene)?;
        let mut total: Option<caustics_core::map::CausticsMap> = None;
        for k in 0..glass {
            let gs = GlassScene::from_scene(job.scene, k)?;
            let dm =
                DistanceMap::build(&gs, params.cube_resolution as usize, params.layers as usize);
            let setup = CausticTrianglesSetup::new(&params, &gs)?;
            let frame = gpu.frame(ctx, &setup, &dm)?;
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            gpu.encode(
                &frame,
                &mut encoder,
                timer.as_deref_mut(),
                Reconstruction::Triangles,
            );
            ctx.submit_timed(encoder, timer.as_deref());
            let map = gpu.read_map(ctx, &frame)?;
            total = Some(match total {
                None => map,
                Some(t) => t.added(&map),
            });
            progress(k + 1, glass);
        }
        Ok(JobOutput::floor(
            total.expect("one glass object at least"),
            None,
        ))
    }
}
