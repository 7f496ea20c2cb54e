//! Paper 3 behind [`Technique`]: its floor map (the illumination volumes cut by the floor, the
//! objects' shadows in it) and, on a scene with walls, the walls' maps; the objects' trees built
//! once in configure, the caller's heights, a new sun or camera as uniform writes.

use caustics_core::scene::Scene;
use caustics_core::techniques::volumes::{self, VolumesInput, VolumesParams, VolumesSetup};
use caustics_core::techniques::{Job, Made};
use glam::DVec3;

use super::{Frame, Volumes};
use crate::technique::{
    Fit, Output, OwnImage, Registered, RunOnce, Technique, WallsOutput, WaterTextures,
};
use crate::{GpuContext, GpuError, GpuTimer};

pub struct VolumesTechnique {
    pipelines: Volumes,
    params: VolumesParams,
    frame: Option<Configured>,
}

struct Configured {
    frame: Frame,
    water: WaterTextures,
    /// The scene as configured, objects included: a new sun or camera goes into it and the setup
    /// is derived again, without the meshes being read from the scene again.
    input: VolumesInput,
    key: SceneKey,
}

/// What the setup takes from the scene besides the objects: when it is unchanged,
/// [`update`](Technique::update) does nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SceneKey {
    width: u32,
    height: u32,
    size: f64,
    depth: f64,
    ior: f64,
    absorption: DVec3,
    wrap: bool,
    walls: bool,
    light: DVec3,
    camera: DVec3,
}

impl SceneKey {
    fn of(scene: &Scene) -> Result<SceneKey, GpuError> {
        caustics_core::techniques::volumes::DESCRIPTOR.check_floor(scene)?;
        caustics_core::techniques::volumes::DESCRIPTOR.check_light(&scene.light)?;
        let w = crate::yuksel::technique::water(scene, "volumes")?;
        Ok(SceneKey {
            width: scene.caustics.width,
            height: scene.caustics.height,
            size: w.size,
            depth: w.depth,
            ior: w.ior,
            absorption: w.absorption,
            wrap: w.wrap,
            walls: scene.floor.walls,
            light: scene.light.direction,
            camera: scene.camera.position,
        })
    }

    /// `input` with this key's water, sun, camera and map size.
    fn apply(&self, input: &mut VolumesInput) {
        input.size = self.size;
        input.depth = self.depth;
        input.ior = self.ior;
        input.absorption = self.absorption;
        input.light = self.light;
        input.camera = self.camera;
        input.width = self.width as usize;
        input.height = self.height as usize;
        input.walls = self.walls;
    }
}

pub fn create(ctx: &GpuContext, params: &toml::Table) -> Result<Box<dyn Technique>, GpuError> {
    Ok(Box::new(VolumesTechnique {
        pipelines: Volumes::new(ctx)?,
        params: VolumesParams::from_table(params)?,
        frame: None,
    }))
}

impl Technique for VolumesTechnique {
    fn name(&self) -> &str {
        "volumes"
    }

    /// The grid the application samples for the CPU twin: one height per lattice cell over the
    /// scene square (`water_cells`, or the map's width).
    fn water_resolution(&self, scene: &Scene) -> (u32, u32) {
        let n = match self.params.water_cells {
            0 => scene.caustics.width,
            n => n,
        };
        (n, n)
    }

    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError> {
        let key = SceneKey::of(scene)?;
        let input = VolumesInput::from_scene(scene)?;
        let setup = VolumesSetup::new(&self.params, &input)?;
        self.frame = None;
        let frame = self
            .pipelines
            .frame_with_water(ctx, &setup, &input, water, key.wrap, None)?;
        self.frame = Some(Configured {
            frame,
            water: water.clone(),
            input,
            key,
        });
        Ok(())
    }

    fn write_scene(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<Fit, GpuError> {
        let key = SceneKey::of(scene)?;
        let Some(c) = &mut self.frame else {
            return Err(GpuError::BadOption(
                "volumes: update before configure".into(),
            ));
        };
        if c.key == key {
            return Ok(Fit::Written);
        }
        if c.key.wrap == key.wrap {
            key.apply(&mut c.input);
            let setup = VolumesSetup::new(&self.params, &c.input)?;
            if c.frame.fits(&setup) {
                c.frame.set_setup(ctx, &setup);
                c.key = key;
                return Ok(Fit::Written);
            }
        }
        Ok(Fit::Reconfigure(c.water.clone()))
    }

    fn encode(&self, encoder: &mut wgpu::CommandEncoder, timer: Option<&mut GpuTimer>) {
        if let Some(c) = &self.frame {
            self.pipelines.encode(&c.frame, encoder, timer);
        }
    }

    fn output(&self) -> Option<Output<'_>> {
        self.frame.as_ref().map(|c| Output::Floor(&c.frame.floor))
    }

    /// The walls' maps on a scene with walls, in the floor map's format (`Rgba16Float` where the
    /// device cannot blend 32-bit floats).
    fn walls(&self) -> Option<WallsOutput<'_>> {
        self.frame
            .as_ref()?
            .frame
            .walls
            .as_ref()
            .map(|w| w.output())
    }

    fn bytes(&self) -> u64 {
        self.frame.as_ref().map_or(0, |c| c.frame.bytes())
    }

    fn set_params(&mut self, params: &toml::Table) -> Result<bool, GpuError> {
        self.params = VolumesParams::from_table(params)?;
        Ok(true)
    }
}

/// Paper 3 in the registry.
pub const REGISTERED: Registered = Registered {
    describe: &volumes::DESCRIPTOR,
    create,
    once: |ctx| Ok(Box::new(Once(Volumes::new(ctx)?))),
    image: Some(own_image),
};

/// Paper 3 ends in its refracted view (§3.3): the objects with their caustics seen through the
/// water where refraction puts them, the floor lit by its map. That view looks down through the
/// surface; a camera under the water gets the general final image of the volumes' map (`None`).
/// The floor is seen with the mean albedo of its pattern (the view pass takes one albedo).
fn own_image(
    ctx: Option<&GpuContext>,
    scene: &Scene,
    params: &toml::Table,
) -> Result<Option<OwnImage>, GpuError> {
    use caustics_core::techniques::volumes::view;
    if caustics_core::render::camera_under_water(scene, None) {
        return Ok(None);
    }
    let params = VolumesParams::from_table(params)?;
    let input = VolumesInput::from_scene(scene)?;
    let setup = VolumesSetup::new(&params, &input)?;
    let water = scene
        .water
        .as_ref()
        .expect("checked by VolumesInput::from_scene");
    let surface = water.surface_at(scene.time)?;
    let n = (input.size / setup.lattice.cell).round() as usize;
    let heights = caustics_core::water::sample_grid(surface.as_ref(), n, n, water.size);
    let samples = 64;
    let floor_albedo = (0..samples * samples)
        .map(|k| {
            let p = (glam::DVec2::new((k % samples) as f64, (k / samples) as f64) + 0.5)
                * (scene.size / samples as f64);
            scene.floor.albedo.at(p, scene.size)
        })
        .sum::<DVec3>()
        / (samples * samples) as f64;
    let camera = view::ViewCamera::new(&scene.camera);
    let (rgb, backend) = match ctx {
        Some(ctx) => {
            let v = Volumes::new(ctx)?;
            let options = super::ViewOptions {
                camera,
                floor_albedo,
            };
            let o = v.run(ctx, &setup, &input, &heights, water.wrap, Some(&options))?;
            (o.view, "GPU")
        }
        None => {
            let o = volumes::caustics(&setup, &input, &heights, water.wrap);
            let rgb = view::view_pass_with_walls(
                &setup,
                &camera,
                &heights,
                water.wrap,
                &o.objects,
                &o.floor,
                o.walls.as_ref(),
                floor_albedo,
            );
            (rgb, "CPU")
        }
    };
    Ok(Some(OwnImage {
        width: scene.camera.width,
        height: scene.camera.height,
        rgb,
        backend,
        what: "through its refracted view",
    }))
}

/// Paper 3 run once on a job: its floor map and, with walls, the walls' maps.
struct Once(Volumes);

impl RunOnce for Once {
    fn run(
        &mut self,
        ctx: &GpuContext,
        job: &Job,
        params: &toml::Table,
        _timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Made, GpuError> {
        let (setup, input, heights, wrap) = volumes::job_setup(job, params)?;
        let out = self.0.run(ctx, &setup, &input, &heights, wrap, None)?;
        progress(1, 1);
        Ok(Made::floor(out.floor, out.walls))
    }
}
