//! Paper 4 behind [`Technique`], one entry for both generators the scene can have:
//!
//! - **Water** (a scene with water): the water surface is the generator ([`WaterFrame`]) and reads
//!   the caller's heights texture; the copy band pass fits the shifted copies of tiling water on
//!   the GPU, so a frame reads nothing back and uploads nothing but a changed uniform.
//! - **Glass** (a scene without water): one [`Frame`] per glass object, its distance map built on
//!   the CPU at configure (`DistanceMap::build`: it depends on the objects only, so it is rebuilt
//!   when they move, and moving them is a configure), every generator drawing additively into one
//!   floor map cleared by the first. A moving light is a uniform write per generator.
//!
//! The map is the floor square `[0, size]²` at the scene's caustics resolution, as the CPU twin's
//! (`caustics_core::techniques::caustic_triangles::render`).

use caustics_core::scene::{Light, Scene, WaterSource};
use caustics_core::techniques::caustic_triangles as ct;
use caustics_core::techniques::caustic_triangles::water::{WaterSetup, check_flat_floor};
use caustics_core::techniques::caustic_triangles::{
    CausticTrianglesParams, CausticTrianglesSetup, DistanceMap, GlassScene, PointLight,
};
use caustics_core::techniques::{Job, Made};

use super::{CausticTriangles, CausticTrianglesUniform, Frame, Reconstruction, WaterFrame};
use crate::technique::{
    Fit, Output, OwnImage, Registered, RunOnce, Technique, WallsOutput, WaterTextures,
};
use crate::{GpuContext, GpuError, GpuTimer};

pub struct CausticTrianglesTechnique {
    pipelines: CausticTriangles,
    params: CausticTrianglesParams,
    state: Option<State>,
}

enum State {
    Water {
        frame: Box<WaterFrame>,
        water: WaterTextures,
    },
    Glass {
        generators: Vec<Generator>,
        /// The floor map every generator draws into.
        map: wgpu::Texture,
        /// The light and map size the generators' uniforms hold.
        light: LightKey,
        water: WaterTextures,
    },
}

/// One glass object as a generator.
struct Generator {
    /// The object, its occluders and the light, as `GlassScene::from_scene` made them at
    /// configure (the BVHs built once).
    scene: GlassScene,
    /// Its distance map's frame (centre, radius, sizes) for the uniform; the texels are on the
    /// GPU only.
    dm: DistanceMap,
    frame: Frame,
}

/// What the glass generators' uniforms depend on in a scene, besides the objects.
#[derive(Clone, Debug, PartialEq)]
struct LightKey {
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

pub fn create(ctx: &GpuContext, params: &toml::Table) -> Result<Box<dyn Technique>, GpuError> {
    CausticTrianglesTechnique::new(ctx, params).map(|t| Box::new(t) as _)
}

impl CausticTrianglesTechnique {
    pub fn new(ctx: &GpuContext, params: &toml::Table) -> Result<Self, GpuError> {
        Ok(CausticTrianglesTechnique {
            pipelines: CausticTriangles::new(ctx)?,
            params: CausticTrianglesParams::from_table(params)?,
            state: None,
        })
    }

    /// The water generator's frame (its photon image, copy band, map), for tests and tools.
    pub fn water_frame(&self) -> Option<&WaterFrame> {
        match &self.state {
            Some(State::Water { frame, .. }) => Some(frame),
            _ => None,
        }
    }

    /// The water generator's setup for `scene` (the app's water job: the sun, the map at the
    /// scene's caustics resolution over the water square).
    fn water_setup(&self, scene: &Scene) -> Result<WaterSetup, GpuError> {
        let water = scene.water.as_ref().expect("a water scene");
        check_flat_floor(scene)?;
        if !scene.light.is_sun() {
            return Err(GpuError::BadOption(format!(
                "scene `{}`: caustic-triangles lights its water surface with the directional sun only (light.position is set)",
                scene.name
            )));
        }
        Ok(WaterSetup::new(
            &self.params,
            water,
            scene.light.direction,
            scene.caustics.width as usize,
            scene.caustics.height as usize,
        )?
        .with_walls(scene.floor.walls))
    }

    fn configure_glass(
        &self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
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
            let mut dm = DistanceMap::build(
                &gs,
                self.params.cube_resolution as usize,
                self.params.layers as usize,
            );
            let setup = CausticTrianglesSetup::new(&self.params, &gs)?;
            let shared = generators.first().map(|g| &g.frame.map);
            let frame = self
                .pipelines
                .frame_drawing_into(ctx, &setup, &dm, shared)?;
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
            water: water.clone(),
        })
    }
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

impl Technique for CausticTrianglesTechnique {
    fn name(&self) -> &str {
        "caustic-triangles"
    }

    /// The water generator reads the grid the app's water job samples (`heights_for`): a
    /// height-field file's own samples, else the map's lattice. Glass generators read no water:
    /// a 1 x 1 texture configures them.
    fn water_resolution(&self, scene: &Scene) -> (u32, u32) {
        match scene.water.as_ref().map(|w| &w.source) {
            None => (1, 1),
            Some(WaterSource::HeightField(g)) => (g.cols as u32, g.rows as u32),
            Some(_) => (scene.caustics.width, scene.caustics.height),
        }
    }

    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError> {
        self.state = None;
        let state = if scene.water.is_some() {
            let ws = self.water_setup(scene)?;
            State::Water {
                frame: Box::new(self.pipelines.water_frame_with_water(ctx, &ws, water)?),
                water: water.clone(),
            }
        } else {
            self.configure_glass(ctx, scene, water)?
        };
        self.state = Some(state);
        Ok(())
    }

    /// The sun (water) or the light (glass) as uniform writes, none when they did not change; a
    /// new map size, or water appearing or going, configures again.
    fn write_scene(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<Fit, GpuError> {
        let water_scene = scene.water.is_some();
        let ws = if water_scene {
            Some(self.water_setup(scene)?)
        } else {
            None
        };
        let again = match (&mut self.state, ws) {
            (None, _) => {
                return Err(GpuError::BadOption(
                    "caustic-triangles: update before configure".into(),
                ));
            }
            (Some(State::Water { frame, water }), Some(ws)) => {
                if frame.fits(&ws) {
                    frame.set_setup(ctx, &ws);
                    return Ok(Fit::Written);
                }
                water.clone()
            }
            (
                Some(State::Glass {
                    generators,
                    light,
                    water,
                    ..
                }),
                None,
            ) => {
                let key = LightKey::of(scene);
                if key == *light {
                    return Ok(Fit::Written);
                }
                if (key.width, key.height, key.size) == (light.width, light.height, light.size) {
                    let mut next = Vec::with_capacity(generators.len());
                    for g in generators.iter() {
                        let gs = relit(&g.scene, &scene.light)?;
                        let setup = CausticTrianglesSetup::new(&self.params, &gs)?;
                        next.push((gs, setup));
                    }
                    for (g, (gs, setup)) in generators.iter_mut().zip(next) {
                        let old = CausticTrianglesUniform::new(&g.frame.setup, &g.dm);
                        let new = CausticTrianglesUniform::new(&setup, &g.dm);
                        if bytemuck::bytes_of(&old) != bytemuck::bytes_of(&new) {
                            ctx.write_buffer(&g.frame.uniform, 0, bytemuck::bytes_of(&new));
                        }
                        g.scene = gs;
                        g.frame.setup = setup;
                    }
                    *light = key;
                    return Ok(Fit::Written);
                }
                water.clone()
            }
            (Some(State::Water { water, .. }), None)
            | (Some(State::Glass { water, .. }), Some(_)) => water.clone(),
        };
        Ok(Fit::Reconfigure(again))
    }

    fn encode(&self, encoder: &mut wgpu::CommandEncoder, mut timer: Option<&mut GpuTimer>) {
        match &self.state {
            None => {}
            Some(State::Water { frame, .. }) => {
                self.pipelines
                    .encode_water(frame, encoder, timer, Reconstruction::Triangles);
            }
            Some(State::Glass { generators, .. }) => {
                for (k, g) in generators.iter().enumerate() {
                    let f = &g.frame;
                    self.pipelines
                        .encode_photons(f, encoder, timer.as_deref_mut());
                    self.pipelines
                        .encode_irradiance(f, encoder, timer.as_deref_mut());
                    self.pipelines.draw_floor(
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

    fn output(&self) -> Option<Output<'_>> {
        match self.state.as_ref()? {
            State::Water { frame, .. } => Some(Output::Floor(&frame.frame.map)),
            State::Glass { map, .. } => Some(Output::Floor(map)),
        }
    }

    /// The water generator's wall maps on a scene with walls (glass scenes have none), in the
    /// floor map's format (`Rgba16Float` where the device cannot blend 32-bit floats).
    fn walls(&self) -> Option<WallsOutput<'_>> {
        match self.state.as_ref()? {
            State::Water { frame, .. } => frame
                .walls
                .as_ref()
                .map(|w| WallsOutput::of(&w.texture, &w.layout)),
            State::Glass { .. } => None,
        }
    }

    fn bytes(&self) -> u64 {
        match &self.state {
            None => 0,
            Some(State::Water { frame, .. }) => frame.bytes(),
            // The first generator's frame owns the shared map and counts it.
            Some(State::Glass { generators, .. }) => {
                generators.iter().map(|g| g.frame.bytes()).sum()
            }
        }
    }

    fn set_params(&mut self, params: &toml::Table) -> Result<bool, GpuError> {
        self.params = CausticTrianglesParams::from_table(params)?;
        Ok(true)
    }
}

/// Paper 4 in the registry.
pub const REGISTERED: Registered = Registered {
    describe: &ct::DESCRIPTOR,
    create,
    once: |ctx| Ok(Box::new(Once(CausticTriangles::new(ctx)?))),
    image: Some(own_image),
};

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

/// Paper 4 run once on a job: the water surface as the generator where the scene has water,
/// else each glass object in turn, their maps added.
struct Once(CausticTriangles);

impl RunOnce for Once {
    fn run(
        &mut self,
        ctx: &GpuContext,
        job: &Job,
        params: &toml::Table,
        mut timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Made, GpuError> {
        let gpu = &self.0;
        if job.scene.water.is_some() {
            let (ws, heights) = ct::water_job_setup(job, params)?;
            let (map, walls) = gpu.water_caustics_walls(ctx, &ws, &heights, timer)?;
            progress(1, 1);
            return Ok(Made::floor(map, walls));
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
            if let Some(t) = &timer {
                t.resolve(&mut encoder);
            }
            ctx.queue.submit([encoder.finish()]);
            let map = gpu.read_map(ctx, &frame)?;
            total = Some(match total {
                None => map,
                Some(t) => t.added(&map),
            });
            progress(k + 1, glass);
        }
        Ok(Made::floor(total.expect("one glass object at least"), None))
    }
}
