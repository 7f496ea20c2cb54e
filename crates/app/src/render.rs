//! `caustics render`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;

use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::render::{RenderOptions, render};
use caustics_core::scene::{Scene, WaterSource};
use caustics_core::techniques;

use crate::progress;

#[derive(Args)]
pub struct RenderArgs {
    /// A scene file (.toml) or a built-in scene: pool, shore, objects, glass.
    #[arg(long, default_value = "pool")]
    scene: String,
    /// The caustics technique (see `caustics techniques`); the scene's own by default.
    #[arg(long)]
    technique: Option<String>,
    /// The final image (PNG). Written to <scene>.png when neither --out nor --raw is given.
    #[arg(long)]
    out: Option<PathBuf>,
    /// The raw caustics map: float32 .npy of shape (height, width), or .exr.
    #[arg(long)]
    raw: Option<PathBuf>,
    /// Caustics map resolution WIDTHxHEIGHT, overriding the scene's.
    #[arg(long, value_parser = parse_size)]
    resolution: Option<[u32; 2]>,
    /// Final image resolution WIDTHxHEIGHT, overriding the scene camera's.
    #[arg(long, value_parser = parse_size)]
    image_size: Option<[u32; 2]>,
    /// Time at which the water is frozen, seconds (the scene's by default).
    #[arg(long)]
    time: Option<f64>,
    /// Reference quality: triangulation cells per map texel along each axis.
    #[arg(long, default_value_t = 4)]
    cells_per_texel: u32,
    /// Samples per pixel along each axis of the final image.
    #[arg(long, default_value_t = 2)]
    supersampling: u32,
}

fn parse_size(s: &str) -> Result<[u32; 2], String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, got `{s}`"))?;
    let w: u32 = w
        .trim()
        .parse()
        .map_err(|_| format!("bad width in `{s}`"))?;
    let h: u32 = h
        .trim()
        .parse()
        .map_err(|_| format!("bad height in `{s}`"))?;
    Ok([w, h])
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
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => false,
    }
}

pub fn run(args: RenderArgs) -> Result<()> {
    let mut scene = Scene::load_or_builtin(&args.scene)?;
    if let Some(t) = &args.technique {
        let info = techniques::info(t).with_context(|| {
            format!(
                "unknown technique `{t}` (known: {})",
                techniques::names().join(", ")
            )
        })?;
        scene.caustics.technique = info.name.to_string();
    }
    let info = techniques::info(&scene.caustics.technique).expect("validated");
    if !info.implemented {
        bail!(
            "technique `{}` (paper {}) is not implemented yet; `caustics techniques` lists what is",
            info.name,
            info.paper
        );
    }
    if let Some([w, h]) = args.resolution {
        check_size("--resolution", w, h)?;
        scene.caustics.width = w;
        scene.caustics.height = h;
    }
    if let Some([w, h]) = args.image_size {
        check_size("--image-size", w, h)?;
        scene.camera.width = w;
        scene.camera.height = h;
    }
    if let Some(t) = args.time {
        if !t.is_finite() {
            bail!("--time must be finite, got {t}");
        }
        scene.time = t;
    }
    let out = match (&args.out, &args.raw) {
        (None, None) => Some(crate::default_output(&args.scene)),
        (o, _) => o.clone(),
    };
    let inputs = inputs_of(&args.scene);
    for o in out.iter().chain(args.raw.iter()) {
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

    let surface = match &scene.water {
        Some(w) => {
            if matches!(w.source, WaterSource::Ripple(_)) {
                tracing::info!("running the ripple simulation");
            }
            Some(w.surface_at(scene.time)?)
        }
        None => None,
    };
    let map = match (&surface, &scene.water) {
        (Some(s), Some(_)) => {
            let started = Instant::now();
            let bar = progress::bar("caustics");
            let input = ReferenceInput::from_scene(&scene, s.as_ref())?;
            let options = ReferenceOptions {
                cells_per_texel: args.cells_per_texel,
                ..Default::default()
            };
            let map = reference(&input, &options, &progress::callback(&bar))?;
            bar.finish_and_clear();
            eprintln!(
                "caustics: reference {} x {} in {:.2} s",
                map.width,
                map.height,
                started.elapsed().as_secs_f64()
            );
            Some(map)
        }
        _ => {
            if args.raw.is_some() {
                bail!(
                    "scene `{}` has no water, so there is no caustics map to write with --raw",
                    scene.name
                );
            }
            None
        }
    };
    if let (Some(raw), Some(map)) = (&args.raw, &map) {
        map.write_raw(raw)?;
        eprintln!("wrote {}", raw.display());
    }
    if let Some(out) = &out {
        let started = Instant::now();
        let bar = progress::bar("image");
        let image = render(
            &scene,
            surface.as_deref(),
            map.as_ref(),
            &RenderOptions {
                supersampling: args.supersampling.max(1),
                ..Default::default()
            },
            &progress::callback(&bar),
        );
        bar.finish_and_clear();
        image::save_buffer(
            out,
            &image.rgb,
            image.width,
            image.height,
            image::ExtendedColorType::Rgb8,
        )
        .with_context(|| format!("cannot write {}", out.display()))?;
        eprintln!(
            "wrote {} ({} x {}, {:.2} s)",
            out.display(),
            image.width,
            image.height,
            started.elapsed().as_secs_f64()
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
