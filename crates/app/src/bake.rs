//! `caustics bake`: a caustics map sequence of water that tiles and loops, for engines that project
//! an animated caustic texture (a light cookie, a decal, a projector) instead of computing caustics.
//! The water is made to loop by `caustics_core::bake`; each frame is one technique run on it, on
//! the GPU kept resident (the water source, the technique and a read-back buffer made once; a frame
//! is a few uniform writes, one submission and one readback), or through the CPU twins where there
//! is no adapter.
//!
//! Outputs in the folder (docs/bake.md): `frame-NNNN.png` (16-bit; flat water's level is
//! [`FLAT_LEVEL`] of full scale) or `.exr` (linear), `atlas.png` (the flipbook), `preview.apng`
//! (the loop tiled 2 x 2), `bake.toml` (how to bake it again), and with `--npy` `frame-NNNN.npy`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use glam::DVec3;

use caustics_core::bake::{Frame, bake_scene, colour_scenes, cpu_frame, frame_time};
use caustics_core::scene::Scene;
use caustics_core::techniques::Spec;
use caustics_gpu::bake::BakeFrames;

use crate::progress;

/// Where flat water's relative irradiance of 1 sits in a 16-bit PNG frame: a quarter of full
/// scale, so that foci up to four times flat water's light are kept (brighter ones clip; the EXR
/// and `--npy` outputs keep every value).
pub const FLAT_LEVEL: f64 = 0.25;

#[derive(Args)]
pub struct BakeArgs {
    /// The folder to write into (made if missing).
    #[arg(long, default_value = "caustics-bake")]
    out: PathBuf,
    /// The water to bake: a scene file (.toml) or a built-in scene whose waves or FFT ocean loop
    /// (pool, shore, objects, underwater). Ripples and paper 2's wave cannot loop and are refused.
    #[arg(long, default_value = "pool")]
    scene: String,
    /// The technique (see `caustics techniques`). Default `reference`: the most accurate, and fast
    /// enough for a bake (its time and error: docs/bake.md).
    #[arg(long, default_value = caustics_core::bake::DEFAULT_TECHNIQUE)]
    technique: String,
    /// Frames in one loop.
    #[arg(long, default_value_t = 64)]
    frames: u32,
    /// Each frame's caustics map, N (N x N texels) or WIDTHxHEIGHT, over one tile of the water.
    #[arg(long, value_parser = crate::parse_map_size, value_name = "N|WxH", default_value = "512")]
    map_size: [u32; 2],
    /// The loop's length, seconds of the water's time: frame k is at k / frames of it.
    #[arg(long, default_value_t = 4.0)]
    period: f64,
    /// The sun's elevation above the horizon, degrees (the scene's by default).
    #[arg(long, allow_negative_numbers = true)]
    sun_elevation: Option<f64>,
    /// The sun's azimuth, degrees from +x towards +y (the scene's by default).
    #[arg(long, allow_negative_numbers = true)]
    sun_azimuth: Option<f64>,
    /// The water's depth over the floor the texture lies on, world units (the scene's by default).
    #[arg(long, allow_negative_numbers = true)]
    depth: Option<f64>,
    /// Refract red, green and blue with water's own index each (1.3311, 1.3330, 1.3371 about the
    /// scene's, as paper 5's ray-based dispersion): colour frames, three technique runs a frame.
    #[arg(long)]
    dispersion: bool,
    /// Frame format: png (16-bit, flat water at a quarter of full scale) or exr (linear).
    #[arg(long, value_enum, default_value_t = Format::Png)]
    format: Format,
    /// Also write each frame's relative irradiance as float32 frame-NNNN.npy, shape (height,
    /// width), or (height, width, 3) with --dispersion; row 0 at y = 0.
    #[arg(long)]
    npy: bool,
    /// Bake frames A up to (not including) B only, so that a job array can split a long bake;
    /// `caustics bake --assemble DIR` then writes the atlas and the preview from the pieces.
    #[arg(long, value_parser = parse_range, value_name = "A..B")]
    range: Option<(u32, u32)>,
    /// Write the atlas and the preview of the bake in DIR from its frames (after --range pieces).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["range", "out"])]
    assemble: Option<PathBuf>,
    /// Replace the files of an earlier bake in the folder.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    gpu: crate::GpuArgs,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
enum Format {
    Png,
    Exr,
}

impl Format {
    fn extension(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Exr => "exr",
        }
    }
}

/// A frame's sides, texels.
const MAP_SIDES: std::ops::RangeInclusive<u32> = 8..=8192;

fn parse_range(s: &str) -> Result<(u32, u32), String> {
    let (a, b) = s
        .split_once("..")
        .ok_or_else(|| format!("expected A..B (frames A up to B), got `{s}`"))?;
    let n = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{s}`: `{v}` is not a frame number"))
    };
    let (a, b) = (n(a)?, n(b)?);
    if a >= b {
        return Err(format!("`{s}`: the range is empty (A must be below B)"));
    }
    Ok((a, b))
}

/// What `bake.toml` records: everything needed to bake the same frames again.
#[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
struct Record {
    scene: String,
    technique: String,
    frames: u32,
    /// The frames' size, texels (read from `resolution` too, the key of older records).
    #[serde(alias = "resolution")]
    map_size: [u32; 2],
    period: f64,
    /// The sun's direction of travel.
    sun: [f64; 3],
    depth: f64,
    dispersion: bool,
    format: Format,
    flat_level: f64,
    /// What was changed to make the water tile and loop.
    notes: Vec<String>,
}

pub fn run(args: BakeArgs) -> Result<()> {
    if let Some(dir) = &args.assemble {
        return assemble(dir, args.force);
    }
    if args.frames == 0 {
        bail!("--frames 0: a loop needs at least one frame");
    }
    if let Some((_, b)) = args.range
        && b > args.frames
    {
        bail!(
            "--range ..{b}: the bake has {} frames (0 to {})",
            args.frames,
            args.frames - 1
        );
    }
    let spec: Spec = args.technique.parse().context("--technique")?;
    if spec.entry.eye_space() {
        bail!(
            "--technique {}: it makes caustics in the camera's screen space, not a map of the floor to tile",
            spec.name()
        );
    }
    let mut scene = Scene::load_or_builtin(&args.scene)?;
    if let Some(depth) = args.depth {
        if !(depth.is_finite() && depth > 0.0) {
            bail!("--depth {depth}: expected a positive depth");
        }
        if let Some(w) = scene.water.as_mut() {
            w.depth = depth;
        }
    }
    if args.sun_elevation.is_some() || args.sun_azimuth.is_some() {
        scene.light.direction = sun_direction(&scene, args.sun_elevation, args.sun_azimuth)?;
    }
    let [w, h] = args.map_size;
    if !(MAP_SIDES.contains(&w) && MAP_SIDES.contains(&h)) {
        bail!(
            "--map-size {w}x{h}: each side must be from {} to {}",
            MAP_SIDES.start(),
            MAP_SIDES.end()
        );
    }
    let (scene, notes) = bake_scene(&scene, args.period, w, h)?;
    let water = scene.water.as_ref().expect("bake_scene keeps the water");
    let record = Record {
        scene: args.scene.clone(),
        technique: spec.label.clone(),
        frames: args.frames,
        map_size: args.map_size,
        period: args.period,
        sun: scene.light.direction.to_array(),
        depth: water.depth,
        dispersion: args.dispersion,
        format: args.format,
        flat_level: FLAT_LEVEL,
        notes: notes.clone(),
    };
    for n in &notes {
        eprintln!("note: {n}");
    }
    let range = args.range.unwrap_or((0, args.frames));
    // A technique without a GPU implementation (the reference) bakes through its CPU twin: no
    // device then.
    let ctx = match caustics_gpu::registry::find(spec.name()) {
        Some(_) => args.gpu.context()?,
        None => None,
    };
    prepare_folder(&args.out, &record, range, args.npy, args.force)?;
    let scenes = colour_scenes(&scene, args.dispersion);
    let mut gpu = (ctx.as_ref())
        .map(|ctx| BakeFrames::new(ctx, spec.name(), &spec.params, &scenes))
        .transpose()?;
    let bar = progress::bar("baking");
    bar.set_length((range.1 - range.0) as u64);
    let started = Instant::now();
    let mut steady = None;
    for k in range.0..range.1 {
        if k == range.0 + 1 {
            steady = ctx.as_ref().map(|c| c.traffic());
        }
        let t = frame_time(k, args.frames, args.period);
        let frame = match (&ctx, gpu.as_mut()) {
            (Some(ctx), Some(g)) => g.frame(ctx, t).map_err(anyhow::Error::from),
            _ => cpu_frame(&spec, &scenes, t).map_err(anyhow::Error::from),
        }
        .with_context(|| format!("frame {k}"))?;
        write_frame(&args.out, k, &frame, args.format, args.npy)?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    let secs = started.elapsed().as_secs_f64();
    let n = range.1 - range.0;
    let mut line = format!(
        "baked {n} frames of {w} x {h} in {secs:.1} s ({:.2} frames/s) with {} on the {}",
        n as f64 / secs,
        spec.label,
        if gpu.is_some() { "GPU" } else { "CPU" }
    );
    if let (Some(ctx), Some(start), Some(_)) = (&ctx, steady, &gpu) {
        let d = ctx.traffic().since(&start);
        let per = |v: u64| v as f64 / (n - 1) as f64;
        line += &format!(
            "; per frame after the first: created {}, uploaded {} bytes, readbacks {}",
            per(d.created()),
            per(d.uploaded_bytes),
            per(d.readbacks)
        );
    }
    eprintln!("{line}");
    if range == (0, args.frames) {
        assemble(&args.out, true)?;
    } else {
        eprintln!(
            "frames {} to {} written; when every piece is in, `caustics bake --assemble {}` writes the atlas and the preview",
            range.0,
            range.1 - 1,
            args.out.display()
        );
    }
    Ok(())
}

/// The sun's direction of travel from an elevation and azimuth in degrees, each the scene's sun's
/// where not given.
fn sun_direction(scene: &Scene, elevation: Option<f64>, azimuth: Option<f64>) -> Result<DVec3> {
    let d = -scene.light.direction;
    let el = elevation.unwrap_or_else(|| d.z.clamp(-1.0, 1.0).asin().to_degrees());
    let az = azimuth.unwrap_or_else(|| d.y.atan2(d.x).to_degrees());
    if !(el > 0.0 && el <= 90.0) {
        bail!("--sun-elevation {el}: expected degrees above the horizon, in (0, 90]");
    }
    if !az.is_finite() {
        bail!("--sun-azimuth {az}: expected degrees");
    }
    let (se, ce) = el.to_radians().sin_cos();
    let (sa, ca) = az.to_radians().sin_cos();
    Ok(-DVec3::new(ce * ca, ce * sa, se))
}

fn frame_path(dir: &Path, k: u32, extension: &str) -> PathBuf {
    dir.join(format!("frame-{k:04}.{extension}"))
}

/// Make the folder, and refuse (without `force`) to replace anything an earlier bake wrote there:
/// the frames in `range`, the atlas, the preview, or a `bake.toml` of other settings.
fn prepare_folder(
    dir: &Path,
    record: &Record,
    range: (u32, u32),
    raw: bool,
    force: bool,
) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        bail!("--out {}: not a folder", dir.display());
    }
    std::fs::create_dir_all(dir).with_context(|| format!("--out {}", dir.display()))?;
    let toml_path = dir.join("bake.toml");
    let text = toml::to_string(record)?;
    let mut existing: Vec<PathBuf> = Vec::new();
    if let Ok(old) = std::fs::read_to_string(&toml_path) {
        let same = toml::from_str::<Record>(&old).is_ok_and(|o| o == *record);
        if !same {
            existing.push(toml_path.clone());
        }
    }
    for k in range.0..range.1 {
        for ext in [record.format.extension(), "npy"] {
            let p = frame_path(dir, k, ext);
            if p.exists() && (ext != "npy" || raw) {
                existing.push(p);
            }
        }
    }
    if range == (0, record.frames) {
        existing.extend(
            ["atlas.png", "preview.apng"]
                .map(|n| dir.join(n))
                .into_iter()
                .filter(|p| p.exists()),
        );
    }
    if !existing.is_empty() && !force {
        let shown: Vec<String> = existing
            .iter()
            .take(4)
            .map(|p| p.display().to_string())
            .collect();
        bail!(
            "--out {}: {} file(s) of an earlier bake would be replaced ({}{}); bake into another folder or add --force",
            dir.display(),
            existing.len(),
            shown.join(", "),
            if existing.len() > 4 { ", ..." } else { "" }
        );
    }
    std::fs::write(&toml_path, text).with_context(|| format!("{}", toml_path.display()))?;
    Ok(())
}

/// A relative irradiance as a 16-bit code: flat water at [`FLAT_LEVEL`] of full scale.
fn code(v: f32) -> u16 {
    (v as f64 * FLAT_LEVEL * 65535.0)
        .round()
        .clamp(0.0, 65535.0) as u16
}

/// Texel (row `i` from the top of the picture, column `j`) of `frame`: the map seen from above, +y
/// up, so picture row 0 is the map's last row.
fn at(frame: &Frame, c: usize, i: usize, j: usize) -> f32 {
    frame.channels[c][(frame.height - 1 - i) * frame.width + j]
}

fn write_frame(dir: &Path, k: u32, frame: &Frame, format: Format, raw: bool) -> Result<()> {
    let (w, h) = (frame.width, frame.height);
    let colours = frame.channels.len();
    let path = frame_path(dir, k, format.extension());
    match format {
        Format::Png => {
            let data: Vec<u16> = (0..h)
                .flat_map(|i| (0..w).flat_map(move |j| (0..colours).map(move |c| (i, j, c))))
                .map(|(i, j, c)| code(at(frame, c, i, j)))
                .collect();
            save_png16(&path, w as u32, h as u32, colours, data)?;
        }
        Format::Exr => {
            use exr::prelude::*;
            let names: &[&str] = if colours == 3 {
                &["R", "G", "B"]
            } else {
                &["Y"]
            };
            let channels = names
                .iter()
                .enumerate()
                .map(|(c, n)| {
                    let samples = (0..h)
                        .flat_map(|i| (0..w).map(move |j| (i, j)))
                        .map(|(i, j)| at(frame, c, i, j))
                        .collect();
                    AnyChannel::new(*n, FlatSamples::F32(samples))
                })
                .collect();
            let layer = Layer::new(
                (w, h),
                LayerAttributes::named("caustics"),
                Encoding::FAST_LOSSLESS,
                AnyChannels::sort(channels),
            );
            Image::from_layer(layer)
                .write()
                .to_file(&path)
                .with_context(|| format!("{}", path.display()))?;
        }
    }
    if raw {
        use npyz::WriterBuilder;
        let path = frame_path(dir, k, "npy");
        let file = std::fs::File::create(&path).with_context(|| format!("{}", path.display()))?;
        let mut shape = vec![h as u64, w as u64];
        if colours == 3 {
            shape.push(3);
        }
        let mut writer = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&shape)
            .writer(std::io::BufWriter::new(file))
            .begin_nd()?;
        writer.extend((0..w * h).flat_map(|t| (0..colours).map(move |c| frame.channels[c][t])))?;
        writer.finish()?;
    }
    Ok(())
}

fn save_png16(path: &Path, w: u32, h: u32, colours: usize, data: Vec<u16>) -> Result<()> {
    let result = if colours == 3 {
        image::ImageBuffer::<image::Rgb<u16>, _>::from_raw(w, h, data)
            .context("frame size")?
            .save(path)
    } else {
        image::ImageBuffer::<image::Luma<u16>, _>::from_raw(w, h, data)
            .context("frame size")?
            .save(path)
    };
    result.with_context(|| format!("{}", path.display()))
}

/// The atlas (every frame in a grid, row by row from the top left) and the preview (the loop
/// tiled 2 x 2, an animated PNG) of the bake in `dir`, from its frames and `bake.toml`.
fn assemble(dir: &Path, force: bool) -> Result<()> {
    let toml_path = dir.join("bake.toml");
    let text = std::fs::read_to_string(&toml_path)
        .with_context(|| format!("{}: no bake here", toml_path.display()))?;
    let record: Record =
        toml::from_str(&text).with_context(|| format!("{}", toml_path.display()))?;
    let missing: Vec<u32> = (0..record.frames)
        .filter(|&k| !frame_path(dir, k, record.format.extension()).exists())
        .collect();
    if let Some(first) = missing.first() {
        bail!(
            "{}: {} of {} frames missing (frame {first} first); bake them with --range",
            dir.display(),
            missing.len(),
            record.frames
        );
    }
    let [w, h] = record.map_size;
    let cols = (record.frames as f64).sqrt().ceil() as u32;
    let rows = record.frames.div_ceil(cols);
    let outputs = [dir.join("atlas.png"), dir.join("preview.apng")];
    if !force && let Some(p) = outputs.iter().find(|p| p.exists()) {
        bail!(
            "{}: already assembled; add --force to write it again",
            p.display()
        );
    }
    // The preview's frames: each frame as 8-bit grey or colour, at most 256 texels a side, 2 x 2.
    let step = (w.max(h) as f64 / 256.0).ceil().max(1.0) as u32;
    let (pw, ph) = (w / step, h / step);
    let colour = record.dispersion;
    let mut atlas = image::ImageBuffer::<image::Rgb<u16>, Vec<u16>>::new(cols * w, rows * h);
    let mut preview: Vec<Vec<u8>> = Vec::new();
    for k in 0..record.frames {
        let frame: image::ImageBuffer<image::Rgb<u16>, Vec<u16>> = match record.format {
            // The PNG (16-bit grey or RGB) as written.
            Format::Png => {
                let path = frame_path(dir, k, "png");
                image::open(&path)
                    .with_context(|| format!("{}", path.display()))?
                    .to_rgb16()
            }
            Format::Exr => exr_as_png16(&frame_path(dir, k, "exr"), w, h)?,
        };
        if frame.dimensions() != (w, h) {
            bail!(
                "frame {k} is {:?}, the bake's frames are {w} x {h}",
                frame.dimensions()
            );
        }
        image::imageops::replace(
            &mut atlas,
            &frame,
            ((k % cols) * w) as i64,
            ((k / cols) * h) as i64,
        );
        let mut tile = Vec::with_capacity((4 * pw * ph * 3) as usize);
        for i in 0..2 * ph {
            for j in 0..2 * pw {
                let p = frame.get_pixel((j % pw) * step, (i % ph) * step);
                // Flat water at a quarter of the 16-bit scale: shown at mid-grey in 8 bits.
                let b =
                    |v: u16| ((v as f64 / 65535.0 * 2.0).min(1.0).powf(1.0 / 2.2) * 255.0) as u8;
                if colour {
                    tile.extend(p.0.map(b));
                } else {
                    tile.push(b(p.0[1]));
                }
            }
        }
        preview.push(tile);
    }
    if colour {
        atlas.save(&outputs[0])?;
    } else {
        let grey: Vec<u16> = atlas.pixels().map(|p| p.0[1]).collect();
        save_png16(&outputs[0], cols * w, rows * h, 1, grey)?;
    }
    write_apng(&outputs[1], 2 * pw, 2 * ph, colour, &preview, &record)?;
    eprintln!(
        "wrote {} ({cols} x {rows} frames, row by row from the top left) and {}",
        outputs[0].display(),
        outputs[1].display()
    );
    Ok(())
}

fn exr_as_png16(
    path: &Path,
    w: u32,
    h: u32,
) -> Result<image::ImageBuffer<image::Rgb<u16>, Vec<u16>>> {
    use exr::prelude::*;
    let image =
        read_all_flat_layers_from_file(path).with_context(|| format!("{}", path.display()))?;
    let layer = image.layer_data.first().context("an EXR with no layer")?;
    let channel = |name: &str| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .map(|c| c.sample_data.values_as_f32().collect::<Vec<f32>>())
    };
    let planes: Vec<Vec<f32>> = match channel("Y") {
        Some(y) => vec![y.clone(), y.clone(), y],
        None => ["R", "G", "B"]
            .iter()
            .map(|n| channel(n).with_context(|| format!("{}: no channel {n}", path.display())))
            .collect::<anyhow::Result<_>>()?,
    };
    let data = (0..(w * h) as usize)
        .flat_map(|t| planes.iter().map(move |p| code(p[t])))
        .collect();
    image::ImageBuffer::from_raw(w, h, data).context("EXR size")
}

/// The loop as an animated PNG at the bake's frame rate, looping forever.
fn write_apng(
    path: &Path,
    w: u32,
    h: u32,
    colour: bool,
    frames: &[Vec<u8>],
    record: &Record,
) -> Result<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, w, h);
    encoder.set_color(if colour {
        png::ColorType::Rgb
    } else {
        png::ColorType::Grayscale
    });
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_animated(frames.len() as u32, 0)?;
    // Frame delay in seconds as a fraction: the loop's period over its frames.
    let ms = (record.period * 1000.0 / record.frames as f64)
        .round()
        .clamp(1.0, 65535.0) as u16;
    encoder.set_frame_delay(ms, 1000)?;
    let mut writer = encoder.write_header()?;
    for f in frames {
        writer.write_image_data(f)?;
    }
    writer.finish()?;
    Ok(())
}
