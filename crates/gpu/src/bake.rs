//! `caustics bake`'s frames on the GPU, kept resident: the water source, one technique a colour
//! (`caustics_core::bake::colour_scenes`) and one read-back buffer are made once; a frame writes
//! the clock and the uniforms, records the water's passes, the techniques' and the copies into one
//! submission, and maps the buffer once. Nothing is created per frame (the traffic counters show
//! it), and the frames are the CPU twin's (`caustics_core::bake::cpu_frame`) to the techniques'
//! tolerances.

use caustics_core::Error::Unavailable;
use caustics_core::bake::Frame;
use caustics_core::scene::Scene;

use crate::registry;
use crate::technique::{Output, Technique};
use crate::water::field::GpuWater;
use crate::{GpuContext, GpuError, Readback};

/// The resident state of a `caustics bake` on the GPU: one water simulation, one configured
/// technique per colour scene, and the read-back buffer with one layer per colour.
pub struct BakeFrames {
    water: GpuWater,
    techniques: Vec<(Box<dyn Technique>, Scene)>,
    readback: Readback,
}

impl BakeFrames {
    /// Technique `name` with its parameter tables `params` on each of `scenes` (one a colour, of
    /// one water).
    pub fn new(
        ctx: &GpuContext,
        name: &str,
        params: &toml::Table,
        scenes: &[Scene],
    ) -> Result<Self, GpuError> {
        let no_water = || GpuError::Core(Unavailable("a bake needs water".into()));
        let water = scenes
            .first()
            .and_then(|s| s.water.as_ref())
            .ok_or_else(no_water)?;
        let mut source = GpuWater::new(ctx, water)?;
        source.update(ctx, 0.0, 1.0);
        let mut techniques = Vec::new();
        for scene in scenes {
            let mut t = registry::create(ctx, name, params)?;
            let (cols, rows) = t.water_resolution(scene);
            let heights = source.output(ctx, cols, rows)?;
            t.configure(ctx, scene, &heights)?;
            t.update(ctx, scene)?;
            techniques.push((t, scene.clone()));
        }
        let Some(Output::Floor(first)) = techniques[0].0.output() else {
            return Err(GpuError::Core(Unavailable(format!(
                "{name} makes no floor map to bake"
            ))));
        };
        let readback = Readback::new(ctx, first, techniques.len() as u32);
        Ok(BakeFrames {
            water: source,
            techniques,
            readback,
        })
    }

    /// The frame at `time` seconds of the water's clock.
    pub fn frame(&mut self, ctx: &GpuContext, time: f64) -> Result<Frame, GpuError> {
        self.water.update(ctx, time, 1.0);
        for (t, scene) in &mut self.techniques {
            t.update(ctx, scene)?;
        }
        let mut encoder = ctx.encoder("bake frame");
        self.water.encode(&mut encoder, None);
        for (layer, (t, _)) in self.techniques.iter().enumerate() {
            t.encode(&mut encoder, None);
            if let Some(Output::Floor(texture)) = t.output() {
                self.readback.record(&mut encoder, texture, layer as u32);
            }
        }
        ctx.queue.submit([encoder.finish()]);
        ctx.check()?;
        let texels = self.readback.read_rgba_f32(ctx)?;
        let (width, height) = self.readback.size();
        let maps: Vec<Vec<[f32; 3]>> = texels
            .chunks(width * height)
            .map(|layer| layer.iter().map(|t| [t[0], t[1], t[2]]).collect())
            .collect();
        Ok(Frame::from_maps(width, height, &maps))
    }
}
