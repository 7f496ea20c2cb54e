//! One interface for every technique, in the spirit of wgpu's examples' framework: create once,
//! [`configure`](Technique::configure) when sizes or the scene change, [`update`](Technique::update)
//! every frame through small uniform writes, [`encode`](Technique::encode) into the caller's
//! command encoder. The water comes in as GPU textures the caller owns ([`WaterTextures`]: our
//! simulations' as much as an application's own), and the caustics go out as a texture the caller
//! samples ([`Output`]). Nothing is read back on the way.
//!
//! A technique describes its GPU side once, as a [`Registered`] beside its code, and is listed in
//! [`crate::registry::REGISTRY`]; the application finds it there by name and never matches names
//! itself.

use caustics_core::scene::Scene;
use caustics_core::techniques::{Descriptor, Job, JobOutput};
use caustics_core::walls::{Wall, WallMaps};

use crate::shaders::PassSource;
use crate::{GpuContext, GpuError, GpuTimer};

/// The water surface as the techniques read it: an `R32Float` texture of heights above the rest
/// level over the water square `[0, size]²`, texel `(i, j)` (row `i`) at `((j + ½) size / cols,
/// (i + ½) size / rows)`, as `caustics_core::water::sample_grid` lays a grid out. The texture
/// needs `TEXTURE_BINDING`; it is read with `textureLoad` (bicubic Catmull-Rom in `water.wgsl`'s
/// `grid_sample`), wrapped or clamped at the edges as the scene's `water.wrap` says.
///
/// The caller owns it and may rewrite it every frame (our [`crate::water::field::GpuWater`]
/// does); a technique keeps a clone of the view, so a new texture (a new size) needs a new
/// [`configure`](Technique::configure).
#[derive(Clone, Debug)]
pub struct WaterTextures {
    /// The heights above the rest level, world units: a view of the whole `R32Float` texture.
    pub heights: wgpu::TextureView,
    /// Texels along x (the texture's width).
    pub cols: u32,
    /// Texels along y (the texture's height).
    pub rows: u32,
}

impl WaterTextures {
    /// The view of a whole `R32Float` texture.
    pub fn of(texture: &wgpu::Texture) -> Self {
        WaterTextures {
            heights: texture.create_view(&Default::default()),
            cols: texture.width(),
            rows: texture.height(),
        }
    }
}

/// What a technique makes, for the caller to sample.
#[derive(Clone, Copy, Debug)]
pub enum Output<'a> {
    /// A map of the floor square: relative irradiance per channel (1 = what the sun gives through
    /// flat, clear water), texel `(i, j)` centred at `((j + ½) size / width, (i + ½) size /
    /// height)`, row 0 at y = 0; `Rgba32Float`, or `Rgba16Float` on devices that cannot blend
    /// 32-bit floats.
    Floor(&'a wgpu::Texture),
    /// An image in the scene camera's screen space (paper 5): relative irradiance of the floor
    /// point each pixel sees; alpha is the cascade the value came from (its index plus the blend
    /// towards the next, in [0, 4)) where the pixel has a value, and −1 (black) where it has none.
    EyeSpace(&'a wgpu::Texture),
}

impl<'a> Output<'a> {
    /// The texture, whichever space it is in.
    pub fn texture(&self) -> &'a wgpu::Texture {
        match self {
            Output::Floor(t) | Output::EyeSpace(t) => t,
        }
    }
}

/// A technique's maps of the pool's walls, for the final image to sample: an
/// `Rgba32Float` 2D array texture of four layers in `caustics_core::walls::Wall::ALL`'s order,
/// layer `k` holding that wall's map in its first `cols[k]` columns (`WallMap`'s layout: row 0 at
/// the floor, the rows up to the rest water level, the floor map's unit).
#[derive(Clone, Copy, Debug)]
pub struct WallsOutput<'a> {
    /// The four-layer array texture, one layer per wall in `Wall::ALL`'s order.
    pub texture: &'a wgpu::Texture,
    /// Texels across each wall's map: layer `k` holds it in its first `cols[k]` columns.
    pub cols: [u32; 4],
}

impl<'a> WallsOutput<'a> {
    /// The maps in `texture`, laid out as `layout` (one layer per wall, its first columns).
    pub fn of(texture: &'a wgpu::Texture, layout: &WallMaps) -> Self {
        WallsOutput {
            texture,
            cols: layout.maps.each_ref().map(|m| m.cols as u32),
        }
    }

    /// The four maps read back into `maps`' layout ([`WallMaps::for_floor_map`] of the floor map
    /// the technique made): a readback, for tools and the viewer's map window, never the frame.
    pub fn read(&self, ctx: &GpuContext, maps: &mut WallMaps) -> Result<(), GpuError> {
        let width = self.texture.width() as usize;
        for wall in Wall::ALL {
            let m = maps.get_mut(wall);
            if self.cols[wall.index()] as usize != m.cols
                || (self.texture.height() as usize) < m.rows
            {
                return Err(GpuError::Readback(format!(
                    "wall {} is {} x {} texels on the GPU, {} x {} expected",
                    wall.suffix(),
                    self.cols[wall.index()],
                    self.texture.height(),
                    m.cols,
                    m.rows
                )));
            }
            let texels = ctx.read_rgba_f32_layer(self.texture, wall.index() as u32)?;
            m.texels = (0..m.rows * m.cols)
                .map(|k| {
                    let t = texels[(k / m.cols) * width + k % m.cols];
                    [t[0], t[1], t[2]]
                })
                .collect();
        }
        Ok(())
    }
}

/// What [`Technique::write_scene`] did with a frame's scene.
#[derive(Debug)]
pub enum SceneWrite {
    /// The new values are in its uniforms.
    Written,
    /// A size changed: it needs [`Technique::configure`] again, on this water (the one it was
    /// configured with).
    Reconfigure(WaterTextures),
}

/// A caustics technique on the GPU. The scene gives the water's optics (`water`: size, depth,
/// index, absorption, wrap; its `source` is ignored, the heights come from [`WaterTextures`]), the
/// floor, the sun (`light`), the map size (`caustics.width`, `caustics.height`), the camera (for
/// eye-space techniques) and the objects.
///
/// Send and Sync on native targets, so that an engine can keep one in its render world (Bevy's
/// resources are both), as wgpu's own objects are there.
pub trait Technique: wgpu::WasmNotSendSync {
    /// The name it is registered under, with its variant (`yuksel-targets`, `procedural-texture`).
    fn name(&self) -> &str;

    /// The height grid (cols, rows) this technique reads the water through for `scene`: the grid
    /// its CPU twin samples, so that both see the same surface. A caller that evaluates the water
    /// itself should write it at this size.
    fn water_resolution(&self, scene: &Scene) -> (u32, u32);

    /// Build the frame's textures, buffers and bind groups for `scene` and `water`. Called once, and
    /// again when the water texture or a size changes.
    fn configure(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        water: &WaterTextures,
    ) -> Result<(), GpuError>;

    /// Take this frame's sun, camera and parameters as uniform writes where the configured
    /// resources still fit them; [`SceneWrite::Reconfigure`] (with the water it was configured
    /// with) where they do not. An error before [`configure`](Self::configure).
    fn write_scene(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<SceneWrite, GpuError>;

    /// [`write_scene`](Self::write_scene), configuring again (and saying so in the log) when
    /// the sizes changed: what a frame calls.
    fn update(&mut self, ctx: &GpuContext, scene: &Scene) -> Result<(), GpuError> {
        match self.write_scene(ctx, scene)? {
            SceneWrite::Written => Ok(()),
            SceneWrite::Reconfigure(water) => {
                tracing::debug!("{}: new sizes, configuring again", self.name());
                self.configure(ctx, scene, &water)
            }
        }
    }

    /// Record the technique's passes into the caller's encoder (after the water's own passes).
    fn encode(&self, encoder: &mut wgpu::CommandEncoder, timer: Option<&mut GpuTimer>);

    /// The texture the passes end in (`None` before [`configure`](Self::configure)).
    fn output(&self) -> Option<Output<'_>>;

    /// Its maps of the pool's walls, when the scene's walls are on and the technique lights them;
    /// `None` (the default) for a floor technique.
    fn walls(&self) -> Option<WallsOutput<'_>> {
        None
    }

    /// Where the scene has receivers (a terrain, diffuse objects): the light-space heights its
    /// rays meet and the deposit its light lands in (docs/receivers.md), for a receiver the
    /// technique's floor map does not cover (an engine's own meshes) to look its light up as a
    /// shadow map is looked up; `None` on the plane `z = 0` and for techniques that do not work
    /// in the light's space.
    fn receivers(&self) -> Option<&crate::receivers::ReceiverFrame> {
        None
    }

    /// GPU memory of the configured frame, bytes.
    fn bytes(&self) -> u64;

    /// Take new parameter tables in place, keeping the pipelines: `Ok(true)` when taken (the
    /// caller configures again before the next frame), `Ok(false)` when the technique must be
    /// created anew (its pipelines depend on them). A slider in a panel then costs a configure,
    /// no pipeline built.
    fn set_params(&mut self, params: &toml::Table) -> Result<bool, GpuError> {
        let _ = params;
        Ok(false)
    }
}

/// How a registered technique is made: its pipelines for the device, its parameters from the
/// technique tables of a scene file's `[caustics]` or the command line, keyed by technique
/// (`{ yuksel = { n = 15 } }`; a missing table means the defaults), for the entry it is
/// registered as.
pub type Make =
    fn(&'static Descriptor, &GpuContext, &toml::Table) -> Result<Box<dyn Technique>, GpuError>;

/// A technique run once on a [`Job`] and read back (the tools' path: `caustics render --raw`,
/// `compare`, the viewer's CPU-image mode), its pipelines kept between runs: the GPU twin of the
/// descriptor's [`CpuRun`](caustics_core::techniques::describe::CpuRun).
pub trait RunOnce {
    /// Run on `job` with the parameter tables `params` (keyed by technique) and read its maps
    /// back, timing the passes on `timer` and reporting `progress(done, total)` where the run is
    /// long.
    fn run(
        &mut self,
        ctx: &GpuContext,
        job: &Job,
        params: &toml::Table,
        timer: Option<&mut GpuTimer>,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput, GpuError>;
}

/// Builds a technique's [`RunOnce`] (its pipelines) for the device, for the entry it is
/// registered as.
pub type MakeOnce = fn(&'static Descriptor, &GpuContext) -> Result<Box<dyn RunOnce>, GpuError>;

/// A technique's own final image (paper 4's camera pass, §4.3; paper 3's refracted view, §3.3),
/// linear RGB at the scene camera's size.
pub struct OwnImage {
    /// Pixels across (the scene camera's width).
    pub width: u32,
    /// Pixels down (the scene camera's height).
    pub height: u32,
    /// Linear RGB before exposure and tone mapping, `width × height`, row by row, top row first.
    pub rgb: Vec<[f32; 3]>,
    /// "GPU" or "CPU".
    pub backend: &'static str,
    /// What the image is, for the log ("through its camera pass").
    pub what: &'static str,
}

/// Makes a technique's own final image of a scene on the GPU (or its CPU twin without one), with
/// the parameter tables keyed by technique; `None` where the scene is not one it has its own image
/// for (the general final image then lights the scene with its map).
pub type MakeOwnImage =
    fn(Option<&GpuContext>, &Scene, &toml::Table) -> Result<Option<OwnImage>, GpuError>;

/// One entry of the registry: the technique's description (core's, the one every front end
/// reads), its two GPU forms and its passes.
pub struct Registered {
    /// Core's description: name, paper, parameters, receivers, CPU twin.
    pub describe: &'static Descriptor,
    /// Every pass shader the technique builds (validated with naga by a test, without a GPU).
    pub passes: &'static [&'static PassSource],
    /// The GPU-resident frame's form ([`Technique`]).
    pub make: Make,
    /// The run-once form.
    pub make_once: MakeOnce,
    /// Its own final image, where the paper ends in one.
    pub image: Option<MakeOwnImage>,
}

impl Registered {
    /// As the command line spells it.
    pub fn name(&self) -> &'static str {
        self.describe.name
    }

    /// The GPU-resident technique with the parameter tables `params`, its pipelines built for
    /// `ctx`.
    /// A table named after no technique (`yuksel-targets` for `yuksel`'s) is refused by name.
    pub fn create(
        &self,
        ctx: &GpuContext,
        params: &toml::Table,
    ) -> Result<Box<dyn Technique>, GpuError> {
        caustics_core::techniques::registry::check_tables(params)?;
        (self.make)(self.describe, ctx, params)
    }

    /// The run-once form, its pipelines built for `ctx`.
    pub fn once(&self, ctx: &GpuContext) -> Result<Box<dyn RunOnce>, GpuError> {
        (self.make_once)(self.describe, ctx)
    }
}

/// The scene's water, or an error naming the technique that needs it.
pub fn scene_water<'s>(
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
