//! The viewer's first model: the scene's technique (or `--technique`) beside the reference (or
//! `--compare`), its camera, sun and water, and defaults that keep a frame well under a second on
//! a software adapter.

use anyhow::{Context, Result};

use caustics_core::orbit::{OrbitCamera, Sun};
use caustics_core::scene::Scene;
use caustics_core::techniques::buffers::{self, Buffer, SceneHas};

use super::super::frame::{Quality, Slot, TechniqueChoice};
use super::super::ui::{Model, Shown, Stats, TextureIds};
use super::super::water::WaterState;
use super::super::{ImageOn, ViewArgs};

pub(super) fn initial_model(
    args: &ViewArgs,
    scene: &Scene,
    software: bool,
    adapter: String,
    textures: TextureIds,
    timestamps: bool,
) -> Result<Model> {
    let cells = args.cells_per_texel.max(1);
    let first = TechniqueChoice::parse(
        args.technique
            .as_deref()
            .unwrap_or(&scene.caustics.technique),
        cells,
    )
    .context("--technique")?;
    let reference = caustics_core::techniques::reference();
    let second = TechniqueChoice::parse(args.compare.as_deref().unwrap_or(reference.name()), cells)
        .context("--compare")?;
    let water = scene.water.as_ref().map(|w| {
        let mut state = WaterState::new(w, scene.time, args.ripple);
        state.amplitude = args.amplitude.max(0.0);
        state.time_scale = args.time_scale.max(0.0);
        state.paused = args.paused;
        state
    });
    let camera = OrbitCamera::from_scene(&scene.camera, scene.size);
    // Defaults that keep a frame well under a second on a software adapter or the CPU, full
    // quality on a GPU. The map's side follows the scene's (its larger side) on a GPU.
    let (scale, map_size, supersampling) = if software || args.gpu.cpu {
        (0.25, 128, 1)
    } else {
        (1.0, scene.caustics.width.max(scene.caustics.height), 2)
    };
    let available = Buffer::available(first.entry, SceneHas::of(scene));
    let buffer = match &args.buffer {
        Some(name) => Buffer::parse(name, &available).context("--buffer")?,
        None => available
            .first()
            .copied()
            .unwrap_or(Buffer::new(&buffers::HEIGHTS)),
    };
    Ok(Model {
        scene_name: scene.name.clone(),
        technique_names: caustics_core::techniques::for_scene(scene),
        has: SceneHas::of(scene),
        adapter,
        home: camera.clone(),
        camera,
        sun: Sun::from_direction(scene.light.direction),
        water,
        slots: [Slot::new(first), Slot::new(second)],
        split: args.compare.is_some(),
        quality: Quality {
            map_size: args.map_size.map_or(map_size, |[n, _]| n).clamp(8, 4096),
            supersampling: args.supersampling.unwrap_or(supersampling),
            exposure: scene.look.exposure,
            filter_water: args.filter_water,
            cpu_image: args.gpu.cpu
                || match args.final_image {
                    ImageOn::Cpu => true,
                    ImageOn::Gpu => false,
                    // The faster of the two: the GPU frame on a GPU, the CPU image on a software
                    // adapter, where lavapipe runs the GPU passes on the same cores and the CPU
                    // renderer traces the small image faster. Median frame at 640 x 360, CPU image
                    // against GPU frame (docs/benchmarks.md, the viewer's table): yuksel 87.8 / 153.9
                    // ms, procedural 90.1 / 127.8, volumes 163.9 / 179.8, cascaded 774 / 819 on
                    // Mesa 25.0.7; 31.4 / 106.7 ms (yuksel) on Mesa 22.3.6.
                    ImageOn::Auto => software,
                },
        },
        scale: args.scale.unwrap_or(scale),
        show_panel: !args.no_panel,
        show_overlay: true,
        show_map: args.show_map,
        show_buffers: args.show_buffers || args.buffer.is_some(),
        buffer,
        textures,
        maps: Default::default(),
        difference: Shown::default(),
        buffer_shown: Shown::default(),
        stats: Stats {
            timestamps,
            ..Stats::default()
        },
        view_px: args.image_size,
        view_rects: Vec::new(),
        frame_dt: 0.0,
        pending_drops: Vec::new(),
        screenshot_requested: false,
        status: None,
    })
}
