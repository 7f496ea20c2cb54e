//! `caustics render`. The caustics map comes from the chosen technique (on the GPU where it has a
//! GPU path and an adapter exists, else its CPU twin), or, for `cascaded`, an image of the caustics
//! in the camera's screen space made for the final image's camera and size; the final image is rendered
//! on the GPU (`caustics_gpu::final_image`, the twin of `caustics_core::render`) when an adapter
//! can be had, else, or with `--cpu`, on the CPU.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;

use caustics_core::render::{Caustics, RenderOptions, render};
use caustics_core::scene::{Scene, WaterSource};
use caustics_core::techniques::describe::Receiver;
use caustics_core::techniques::{self, Descriptor};
use caustics_core::water::Surface;
use caustics_gpu::final_image::FinalImage;
use caustics_gpu::{GpuContext, GpuError, GpuTimer};

use crate::progress;
use crate::techniques::{Job, Runner, SceneCaustics, Spec};
use crate::view::ImageOn;

#[derive(Args)]
pub struct RenderArgs {
    /// A scene file (.toml) or a built-in scene: pool, shore, reef, objects, glass, underwater.
    #[arg(long, default_value = "pool")]
    scene: String,
    /// The caustics technique (see `caustics techniques`); the scene's own by default.
    #[arg(long)]
    technique: Option<String>,
    /// The final image (PNG). Written to <scene>.png when neither --out nor --raw is given.
    #[arg(long)]
    out: Option<PathBuf>,
    /// The raw caustics map: float32 .npy of shape (height, width), or .exr. For `cascaded`, the
    /// caustics in the final image's screen space: shape (image height, image width), row 0 at the
    /// top, NaN where the technique has none (no floor seen, beyond its last cascade).
    #[arg(long)]
    raw: Option<PathBuf>,
    /// The raw maps of the pool's walls (scenes with `[floor] walls = true`): PREFIX-x0.npy,
    /// PREFIX-x1.npy, PREFIX-y0.npy, PREFIX-y1.npy, float32 of shape (rows, cols), row 0 at the
    /// floor, in the floor map's unit. Techniques reference, caustic-triangles, volumes, cascaded.
    #[arg(long, value_name = "PREFIX")]
    raw_walls: Option<PathBuf>,
    /// The caustics map's size, N (N x N texels) or WIDTHxHEIGHT, overriding the scene's.
    #[arg(long, value_parser = crate::parse_map_size, value_name = "N|WxH")]
    map_size: Option<[u32; 2]>,
    /// The final image's size WIDTHxHEIGHT, overriding the scene camera's.
    #[arg(long, value_parser = parse_size, value_name = "WxH")]
    image_size: Option<[u32; 2]>,
    /// Time at which the water is frozen, seconds (the scene's by default; any finite time).
    #[arg(long, allow_negative_numbers = true)]
    time: Option<f64>,
    /// Reference quality: triangulation cells per map texel along each axis (1 to 16).
    #[arg(long, default_value_t = crate::CELLS_PER_TEXEL,
          value_parser = clap::value_parser!(u32).range(crate::CELLS_PER_TEXEL_RANGE))]
    cells_per_texel: u32,
    /// Samples per pixel along each axis of the final image (1 to 16).
    #[arg(long, default_value_t = 2,
          value_parser = clap::value_parser!(u32).range(crate::SUPERSAMPLING_RANGE))]
    supersampling: u32,
    /// Shade the water with normals filtered by each sample's footprint (the waves' slope
    /// moments, LEAN mapping: far water reflects a blurred sky and a glint spread by the waves it
    /// cannot resolve) instead of the exact normal where each sample meets it; both final
    /// images. docs/maintainers/look.md has what it measures against many samples.
    #[arg(long)]
    filter_water: bool,
    /// Exposure of the final image: radiance is multiplied by it before the tone curve (the
    /// scene's `[camera] exposure` by default).
    #[arg(long, allow_negative_numbers = true)]
    exposure: Option<f64>,
    /// Tone curve of the final image: aces, agx or none (the scene's `[camera] tone_map`, by
    /// default aces).
    #[arg(long)]
    tone_map: Option<caustics_core::render::ToneMap>,
    /// Where the final image is traced: `gpu`, `cpu`, or `auto`: on the GPU, except on a software
    /// adapter (lavapipe, WARP), which runs the pass on the CPU's cores more slowly than the CPU
    /// renderer does and spends tens of seconds compiling it on a fresh machine. The technique
    /// runs on the GPU either way.
    #[arg(long, value_enum, default_value_t = ImageOn::Auto)]
    final_image: ImageOn,
    #[command(flatten)]
    gpu: crate::GpuArgs,
}

fn parse_size(s: &str) -> Result<[u32; 2], String> {
    // Any size here: the ranges are checked with the scene's, naming the flag and the limit.
    crate::parse_size_within(s, 0..=u32::MAX)
}

/// Refuse an output that cannot be written, before the work rather than after it, without
/// creating or changing the file itself: an existing one must be a file opened for writing (not
/// truncated), a new one's folder must take a new file (probed with a file of another name,
/// removed at once: permissions alone do not tell, e.g. for root or a read-only mount).
fn check_writable(flag: &str, path: &Path) -> Result<()> {
    let fail = |why: String| anyhow::anyhow!("{flag} {}: cannot be written: {why}", path.display());
    if path.is_dir() {
        return Err(fail("it is a folder".into()));
    }
    if path.exists() {
        std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|e| fail(e.to_string()))?;
        return Ok(());
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return Err(fail(format!("no folder {}", parent.display())));
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let probe = parent.join(format!(".{name}.{}.caustics-probe", std::process::id()));
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map_err(|e| fail(e.to_string()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Paths the scene reads from: an output must never replace one of them.
fn inputs_of(scene_arg: &str) -> Vec<PathBuf> {
    let mut v = Vec::new();
    let path = Path::new(scene_arg);
    if path.exists() {
        v.push(path.to_path_buf());
        if let Ok(table) = std::fs::read_to_string(path)
            .map_err(|_| ())
            .and_then(|t| t.parse::<toml::Table>().map_err(|_| ()))
        {
            let base = path.parent().unwrap_or(Path::new("."));
            collect_paths(&toml::Value::Table(table), base, &mut v);
        }
    }
    v
}

fn collect_paths(v: &toml::Value, base: &Path, out: &mut Vec<PathBuf>) {
    match v {
        toml::Value::String(s) if s.contains('.') => out.push(base.join(s)),
        toml::Value::Table(t) => t.values().for_each(|x| collect_paths(x, base, out)),
        toml::Value::Array(a) => a.iter().for_each(|x| collect_paths(x, base, out)),
        _ => {}
    }
}

fn same_file(a: &Path, b: &Path) -> bool {
    matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
}

pub fn run(args: RenderArgs) -> Result<()> {
    let mut scene = Scene::load_or_builtin(&args.scene)?;
    let spec = match &args.technique {
        Some(t) => t.parse::<Spec>()?.over(&scene.caustics.params),
        None => Spec::from_scene(&scene.caustics)?,
    };
    spec.entry.check_light(&scene.light)?;
    if let Some([w, h]) = args.map_size {
        check_size("--map-size", w, h)?;
        scene.caustics.width = w;
        scene.caustics.height = h;
    }
    if let Some([w, h]) = args.image_size {
        check_size("--image-size", w, h)?;
        scene.camera.width = w;
        scene.camera.height = h;
    }
    if let Some(e) = args.exposure {
        if !(e.is_finite() && e > 0.0) {
            bail!("--exposure must be positive and finite, got {e}");
        }
        scene.look.exposure = e;
    }
    if let Some(t) = args.tone_map {
        scene.look.tone_map = t;
    }
    if let Some(t) = args.time {
        if !t.is_finite() {
            bail!("--time must be finite, got {t}");
        }
        scene.time = t;
    }
    let out = match (&args.out, &args.raw, &args.raw_walls) {
        (None, None, None) => Some(crate::default_output(&args.scene)),
        (o, _, _) => o.clone(),
    };
    let wall_paths = args
        .raw_walls
        .as_deref()
        .map(caustics_core::walls::WallMaps::raw_paths);
    if wall_paths.is_some() {
        check_walls(&scene, spec.entry)?;
    }
    let inputs = inputs_of(&args.scene);
    let outputs: Vec<(&str, &PathBuf)> = (out.iter().map(|o| ("--out", o)))
        .chain(args.raw.iter().map(|r| ("--raw", r)))
        .chain(wall_paths.iter().flatten().map(|p| ("--raw-walls", p)))
        .collect();
    for (_, o) in &outputs {
        if let Some(i) = inputs.iter().find(|i| same_file(i, o)) {
            bail!(
                "refusing to overwrite {}: the scene reads it as an input",
                i.display()
            );
        }
    }
    if let Some(raw) = &args.raw {
        match raw.extension().and_then(|e| e.to_str()) {
            Some("npy" | "exr") => {}
            _ => bail!("--raw {}: expected a .npy or .exr file name", raw.display()),
        }
    }
    if let Some(o) = &out
        && o.extension().and_then(|e| e.to_str()) != Some("png")
    {
        bail!("--out {}: expected a .png file name", o.display());
    }
    for (flag, path) in &outputs {
        check_writable(flag, path)?;
    }

    // The device, set up before the caustics so that a bad --backend fails at once and the
    // adapter is named first; the technique and the final image share it.
    let ctx = args.gpu.context()?;
    let mut runner = Runner::new(ctx);
    // A technique that ends in its own final image (paper 4's camera pass, paper 3's refracted
    // view) makes it where the scene is one it has it for.
    if let (Some(out), None, None) = (&out, &args.raw, &args.raw_walls)
        && let Some(make) = caustics_gpu::registry::find(spec.name()).and_then(|r| r.image)
    {
        let started = Instant::now();
        if let Some(image) = make(runner.gpu.as_ref(), &scene, &spec.params)? {
            caustics_core::render::write_png(
                out,
                image.width,
                image.height,
                &image.rgb,
                scene.look.exposure,
                scene.look.tone_map,
            )?;
            let what = format!("{} {}, ", spec.name(), image.what);
            say_wrote(
                out,
                (image.width, image.height),
                &what,
                started,
                image.backend,
            );
            return Ok(());
        }
    }

    // The GPU frame: water, technique and final image on the GPU, read back once as the output.
    // The walls' maps come from the technique run on its own (`Outcome::walls`).
    if let Some(ctx) = runner.gpu.as_ref()
        && scene.water.is_some()
        && args.raw_walls.is_none()
        && caustics_gpu::registry::find(spec.name()).is_some()
    {
        return render_frame(ctx, &scene, &spec, &args, out.as_deref());
    }

    let surface = scene
        .water
        .as_ref()
        .map(|w| {
            if matches!(w.source, WaterSource::Ripple(_)) {
                tracing::info!("running the ripple simulation");
            }
            w.surface_at(scene.time)
        })
        .transpose()?;
    // A map when the scene has a caustic generator the technique handles: water, or glass objects
    // (a technique that reads glass, and the reference there: paper 4's photon tracer against the
    // exact geometry, so that the glass scene's own technique draws its foci and shadows).
    let glass = scene
        .objects
        .iter()
        .any(|o| matches!(o.material, caustics_core::scene::Material::Glass { .. }));
    let has_generator = scene.water.is_some()
        || spec.entry.input == caustics_core::techniques::Input::GlassOrWater
        || (spec.entry.reference && glass);
    let mut walls = None;
    let mut light = None;
    let caustics = if has_generator {
        let started = Instant::now();
        let bar = progress::bar("caustics");
        let outcome = runner.run(
            &spec,
            &Job::new(&scene, surface.as_deref(), args.cells_per_texel),
            &progress::callback(&bar),
        )?;
        bar.finish_and_clear();
        let (w, h, what) = match &outcome.caustics {
            SceneCaustics::Floor(m) => (m.width, m.height, "map"),
            SceneCaustics::EyeSpace(e) => (e.width, e.height, "eye-space image"),
        };
        eprintln!(
            "caustics: {} {what} {w} x {h} in {:.2} s on the {}",
            spec.label,
            started.elapsed().as_secs_f64(),
            outcome.backend
        );
        walls = outcome.walls;
        light = outcome.light;
        Some(outcome.caustics)
    } else {
        if args.raw.is_some() {
            bail!(
                "scene `{}` has no water, so there is no caustics map to write with --raw (its glass \
                 objects make one with --technique caustic-triangles)",
                scene.name
            );
        }
        None
    };
    if let (Some(raw), Some(caustics)) = (&args.raw, &caustics) {
        write_raw(raw, caustics)?;
    }
    if let Some(prefix) = &args.raw_walls {
        let Some(maps) = &walls else {
            bail!(
                "technique `{}` lit no walls on scene `{}`: --raw-walls has nothing to write",
                spec.label,
                scene.name
            );
        };
        for path in maps.write_raw(prefix)? {
            eprintln!("wrote {}", path.display());
        }
    }
    // The objects among the receivers take their light from the deposit beside the floor map.
    let caustics = caustics.as_ref().map(|c| c.with_light(light.as_ref()));
    if let Some(out) = &out {
        let started = Instant::now();
        let options = args.options(&scene);
        let image_gpu = runner.gpu.as_ref().filter(|ctx| match args.final_image {
            ImageOn::Gpu => true,
            ImageOn::Cpu => false,
            ImageOn::Auto => {
                let software = FinalImage::software_adapter(ctx);
                if software {
                    eprintln!(
                        "final image on the CPU: faster there than on a software adapter \
                         (--final-image gpu to trace it on the GPU)"
                    );
                }
                !software
            }
        });
        let final_image = image_gpu
            .map(|ctx| match FinalImage::new(ctx) {
                Ok(f) => Ok(Some((ctx, f))),
                Err(e @ GpuError::DeviceLost(_)) => Err(e),
                Err(e) => {
                    eprintln!(
                        "the GPU cannot build the final-image pass ({e}): rendering on the CPU"
                    );
                    Ok(None)
                }
            })
            .transpose()?
            .flatten();
        let from_gpu = match &final_image {
            Some((ctx, final_image)) => render_on_gpu(
                ctx,
                final_image,
                &scene,
                surface.as_deref(),
                caustics,
                walls.as_ref(),
                &options,
            )?,
            None => None,
        };
        let on = if from_gpu.is_some() { "GPU" } else { "CPU" };
        let image = from_gpu.unwrap_or_else(|| {
            let bar = progress::bar("image");
            let image = render(
                &scene,
                surface.as_deref(),
                caustics,
                walls.as_ref(),
                &options,
                &progress::callback(&bar),
            );
            bar.finish_and_clear();
            image
        });
        crate::save_rgb(out, &image.rgb, image.width, image.height)?;
        say_wrote(out, (image.width, image.height), "", started, on);
    }
    Ok(())
}

/// `render` on the GPU frame (`caustics_gpu::renderer::Renderer`, as the viewer draws): the scene's
/// water written on the GPU at the scene's time, the technique, the final image; the image and
/// the raw caustics read back once at the end.
fn render_frame(
    ctx: &GpuContext,
    scene: &Scene,
    spec: &Spec,
    args: &RenderArgs,
    out: Option<&Path>,
) -> Result<()> {
    use caustics_gpu::renderer::{FrameWater, Renderer, TechniqueSpec, WaterClock};
    let started = Instant::now();
    let mut renderer = Renderer::new(ctx)?;
    renderer.set_water(ctx, scene.water.as_ref(), &FrameWater::Scene)?;
    renderer.set_techniques(ctx, &[Some(TechniqueSpec::from(spec))]);
    let options = args.options(scene);
    let clock = WaterClock {
        time: scene.time,
        amplitude: 1.0,
        steps: 0,
    };
    renderer.render(ctx, scene, clock, &options)?;
    if let Some(e) = renderer.error(0) {
        bail!("technique `{}`: {e}", spec.label);
    }
    ctx.wait()?;
    let output = renderer
        .caustics(0)
        .context("the technique made no caustics")?;
    let texture = output.texture();
    eprintln!(
        "caustics: {} {} {} x {} on the GPU ({:.2} s with the image)",
        spec.label,
        match output {
            caustics_gpu::Output::Floor(_) => "map",
            caustics_gpu::Output::EyeSpace(_) => "eye-space image",
        },
        texture.width(),
        texture.height(),
        started.elapsed().as_secs_f64()
    );
    if let Some(raw) = &args.raw {
        let size = scene.water.as_ref().map_or(1.0, |w| w.size);
        write_raw(raw, &crate::techniques::read_output(ctx, output, size)?)?;
    }
    if let Some(out) = out {
        let image = renderer.image(0).context("no final image")?;
        let texels: Vec<[u8; 4]> = ctx.read_texture(image)?;
        let rgb: Vec<u8> = texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect();
        crate::save_rgb(out, &rgb, image.width(), image.height())?;
        say_wrote(out, (image.width(), image.height()), "", started, "GPU");
    }
    Ok(())
}

impl RenderArgs {
    /// The final image's options: the scene's, with the flags' supersampling and water filter.
    fn options(&self, scene: &Scene) -> RenderOptions {
        RenderOptions {
            filter_water: self.filter_water,
            ..RenderOptions::for_scene(scene, self.supersampling.max(1))
        }
    }
}

/// The raw caustics, written to `raw` (.npy or .exr) and said so.
fn write_raw(raw: &Path, caustics: &SceneCaustics) -> Result<()> {
    match caustics {
        SceneCaustics::Floor(m) => m.write_raw(raw)?,
        SceneCaustics::EyeSpace(e) => e.write_raw(raw)?,
    }
    eprintln!("wrote {}", raw.display());
    Ok(())
}

/// The line that says the final image `out` of `size` is written: `what` made it (empty, or
/// ending in ", ") in the time since `started` on the `on` device.
fn say_wrote(out: &Path, (width, height): (u32, u32), what: &str, started: Instant, on: &str) {
    let secs = started.elapsed().as_secs_f64();
    eprintln!(
        "wrote {} ({width} x {height}, {what}{secs:.2} s on the {on})",
        out.display()
    );
}

/// The final image from the GPU twin of `caustics_core::render::render`, or `None` (after one line
/// on stderr) when the GPU fails at it, e.g. an image larger than its textures may be; a lost
/// device is an error (the CPU image would hide that the GPU went away).
fn render_on_gpu(
    ctx: &GpuContext,
    final_image: &FinalImage,
    scene: &Scene,
    surface: Option<&dyn Surface>,
    caustics: Option<Caustics>,
    walls: Option<&caustics_core::walls::WallMaps>,
    options: &RenderOptions,
) -> Result<Option<caustics_core::render::Image>, GpuError> {
    let mut timer = GpuTimer::new(ctx, 4);
    let image = final_image.render(
        ctx,
        scene,
        surface,
        caustics,
        walls,
        options,
        Some(&mut timer),
    );
    match image {
        Ok(image) => {
            if let Ok(times) = timer.read(ctx) {
                for t in times {
                    tracing::info!("GPU pass `{}`: {:.1} ms", t.label, t.ms);
                }
            }
            Ok(Some(image))
        }
        Err(e @ GpuError::DeviceLost(_)) => Err(e),
        Err(e) => {
            eprintln!("the GPU render failed ({e}): rendering on the CPU");
            Ok(None)
        }
    }
}

/// `--raw-walls` asks for light on the pool's walls: refused before any work when the scene's walls
/// are off or the technique maps the floor only.
fn check_walls(scene: &Scene, technique: &Descriptor) -> Result<()> {
    if !scene.floor.walls {
        bail!(
            "--raw-walls: the scene's walls are off: set `[floor] walls = true` in scene `{}`",
            scene.name
        );
    }
    let mapped = || {
        techniques::REGISTRY
            .iter()
            .filter(|d| d.receivers.contains(&Receiver::Walls))
            .map(|d| d.name)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let name = technique.name;
    if technique.eye_space() {
        bail!(
            "--raw-walls: {name} lights the walls in the camera's image, not in wall maps; \
             --raw-walls needs one of {}",
            mapped()
        );
    }
    if technique.floor_only() {
        bail!(
            "--raw-walls: {name} maps the floor only; --raw-walls needs one of {}",
            mapped()
        );
    }
    Ok(())
}

fn check_size(flag: &str, w: u32, h: u32) -> Result<()> {
    let max = caustics_core::scene::MAX_RESOLUTION;
    if w == 0 || h == 0 || w > max || h > max {
        bail!("{flag} {w}x{h}: each side must be between 1 and {max}");
    }
    Ok(())
}
