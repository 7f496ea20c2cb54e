//! Paper 3 behind the generic adapter: its floor map (the illumination volumes cut by the floor,
//! the objects' shadows in it) and, on a scene with walls, the walls' maps; the objects' trees
//! built once in configure, the caller's heights, a new sun or camera as uniform writes.

use caustics_core::receivers::Shared;
use caustics_core::scene::Scene;
use caustics_core::techniques::volumes::{self, VolumesInput, VolumesParams, VolumesSetup};
use caustics_core::techniques::{Descriptor, Job, JobOutput};
use glam::DVec3;

use super::Volumes;
use crate::adapter::Pipelines;
use crate::receivers::ReceiverFrame;
use crate::technique::{Output, OwnImage, Registered, WallsOutput, WaterTextures, scene_water};
use crate::{GpuContext, GpuError, GpuTimer};

/// Paper 3 in the registry.
pub const REGISTERED: Registered =
    Registered::of::<Volumes>(&volumes::DESCRIPTOR, super::PASSES, Some(own_image));

/// The `volumes` technique resident on the GPU.
pub type VolumesTechnique = crate::adapter::Resident<Volumes>;

/// A [`super::VolumesFrame`] and the scene it was configured for, which `refit` compares a new
/// scene against.
pub struct ConfiguredVolumes {
    /// The frame the passes record, with the scene's setup.
    pub frame: super::VolumesFrame,
    /// The scene as configured, objects included: a new sun or camera goes into it and the setup
    /// is derived again, without the meshes being read from the scene again.
    input: VolumesInput,
    key: SceneKey,
}

/// What the setup takes from the scene besides the objects: when it is unchanged,
/// a frame's update does nothing.
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
        volumes::DESCRIPTOR.check_light(&scene.light)?;
        let w = scene_water(scene, "volumes")?;
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

impl Pipelines for Volumes {
    type Params = VolumesParams;
    type Frame = ConfiguredVolumes;

    fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        Volumes::new(ctx)
    }

    fn params(_: &'static Descriptor, tables: &toml::Table) -> Result<VolumesParams, GpuError> {
        Ok(VolumesParams::from_table(tables)?)
    }

    /// The grid the application samples for the CPU twin: one height per lattice cell over the
    /// scene square (`water_cells`, or the map's width).
    fn water_resolution(params: &VolumesParams, scene: &Scene) -> (u32, u32) {
        let n = match params.water_cells {
            0 => scene.caustics.width,
            n => n,
        };
        (n, n)
    }

    fn frame(
        &self,
        ctx: &GpuContext,
        params: &VolumesParams,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<ConfiguredVolumes, GpuError> {
        let key = SceneKey::of(scene)?;
        let input = VolumesInput::from_scene(scene)?;
        let setup = VolumesSetup::new(params, &input)?.with_floor(&scene.floor, None);
        let frame = self.frame_with_water(ctx, &setup, &input, water, key.wrap, None)?;
        Ok(ConfiguredVolumes { frame, input, key })
    }

    fn refit(
        &self,
        ctx: &GpuContext,
        params: &VolumesParams,
        c: &mut ConfiguredVolumes,
        scene: &Scene,
    ) -> Result<bool, GpuError> {
        let key = SceneKey::of(scene)?;
        let receivers = c.frame.setup.receivers.as_ref();
        if c.key == key && Shared::fits_terrain(receivers, &scene.floor) {
            return Ok(true);
        }
        if c.key.wrap == key.wrap {
            key.apply(&mut c.input);
            let setup = VolumesSetup::new(params, &c.input)?.with_floor(&scene.floor, receivers);
            if c.frame.fits(&setup) {
                c.frame.set_setup(ctx, &setup);
                c.key = key;
                return Ok(true);
            }
        }
        Ok(false)
    }

    fn encode(
        &self,
        c: &ConfiguredVolumes,
        encoder: &mut wgpu::CommandEncoder,
        timer: Option<&mut GpuTimer>,
    ) {
        Volumes::encode(self, &c.frame, encoder, timer);
    }

    fn output<'a>(&'a self, c: &'a ConfiguredVolumes) -> Output<'a> {
        Output::Floor(c.frame.floor_map())
    }

    /// The walls' maps on a scene with walls, in the floor map's format (`Rgba16Float` where the
    /// device cannot blend 32-bit floats).
    fn walls(c: &ConfiguredVolumes) -> Option<WallsOutput<'_>> {
        c.frame.walls.as_ref().map(|w| w.output())
    }

    fn receivers(c: &ConfiguredVolumes) -> Option<&ReceiverFrame> {
        c.frame.receivers.as_ref().map(|r| &r.frame)
    }

    fn bytes(c: &ConfiguredVolumes) -> u64 {
        c.frame.bytes()
    }

    /// Its floor map and, with walls, the walls' maps.
    fn run_once(
        &mut self,
        ctx: &GpuContext,
        _: &'static Descriptor,
        job: &Job,
        params: &toml::Table,
        _timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError> {
        let (setup, input, heights, wrap) = volumes::job_setup(job, params)?;
        let out = self.run(ctx, &setup, &input, &heights, wrap, None)?;
        progress(1, 1);
        Ok(JobOutput::floor(out.floor, out.walls))
    }
}

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
            let rgb = view::view_pass(
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
