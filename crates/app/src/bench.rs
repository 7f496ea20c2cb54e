//! `caustics bench`: every registered GPU technique (`caustics_gpu::registry::REGISTRY`, no name
//! matched here) on the scenes it applies to (the pool's water for all, the glass scene's objects
//! for the techniques that take glass generators), then the whole GPU-resident frame (water,
//! technique, final image through `caustics_gpu::renderer::Renderer`) at each size. Warm-up
//! frames then timed frames; GPU time per pass from timestamp queries (median and spread), the
//! wall time per frame, the GPU memory the technique allocates, and how time grows with
//! resolution (the slope of log time over log pixels). Writes Markdown, CSV and an SVG plot.
//!
//! Each pass group is its own submission (the water's, then the technique's, untimed water
//! first), so that the technique's timestamps open their command buffer: Mesa's lavapipe reports
//! nonsense (0.05 ms for a 50 ms pass) for passes recorded after others in one command buffer.
//! The wall time of that submission (submit to idle) is the cross-check beside each GPU total.
//!
//! Without a GPU adapter (`--cpu`), the CPU twins' wall time through the same runner `caustics
//! compare` uses.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;

use caustics_core::render::RenderOptions;
use caustics_core::scene::Scene;
use caustics_core::techniques::Input;
use caustics_gpu::WaterTextures;
use caustics_gpu::registry::{self, REGISTRY};
use caustics_gpu::renderer::{FrameWater, Renderer, TechniqueSpec, WaterClock};
use caustics_gpu::water::field::GpuWater;
use caustics_gpu::{GpuContext, GpuTimer, PassTime};

use crate::progress;
use crate::techniques::{Job, Runner, Spec};

#[derive(Args)]
pub struct BenchArgs {
    /// Techniques, `name` or `name:key=value,...` as registered (`caustics techniques`); repeat
    /// the flag. Default: every registered technique.
    #[arg(long = "technique")]
    pub(crate) techniques: Vec<Spec>,
    /// Scenes to time each technique on: a scene file (.toml) or a built-in name; repeat the flag.
    /// Default: the pool, the glass scene for a technique that lights glass, the shore and the
    /// reef.
    #[arg(long = "scene")]
    scenes: Vec<String>,
    /// The whole frame's picture sizes WIDTHxHEIGHT, comma-separated (the whole-frame rows).
    /// Default 1280x720,1920x1080 (with --quick: 64x36).
    #[arg(long, value_delimiter = ',', value_parser = parse_image_size, value_name = "WxH")]
    image_size: Vec<[u32; 2]>,
    /// The caustics map's sizes, N (N x N texels) or WIDTHxHEIGHT, comma-separated (the technique
    /// rows, and the map the whole frame reads): one for every image size, or one size for all.
    /// Default: each image size's own; given alone, each is also its frame's picture size.
    #[arg(long, value_delimiter = ',', value_parser = crate::parse_map_size, value_name = "N|WxH")]
    map_size: Vec<[u32; 2]>,
    /// Timed frames per measurement (default 30; with --quick 1).
    #[arg(long)]
    frames: Option<u32>,
    /// Untimed frames first: pipeline compilation, caches (default 3; with --quick 1).
    #[arg(long)]
    warmup: Option<u32>,
    /// Shrink everything for a software adapter (lavapipe): one 64x36 size, one warm-up and
    /// one timed frame, the error-against-cost sweep on one case at a 48² map.
    #[arg(long)]
    pub(crate) quick: bool,
    /// Measure error against cost instead: each technique's main knob swept, relative L1 against
    /// the reference (as `caustics compare`) over GPU time per frame (as the bench), with the
    /// Pareto front: writes tradeoff.csv, tradeoff.md and tradeoff.svg.
    #[arg(long)]
    pub(crate) tradeoff: bool,
    /// Skip the whole-frame rows (the technique rows only).
    #[arg(long)]
    no_frame: bool,
    /// Filter the water's normals by each sample's footprint in the whole-frame rows (as
    /// `caustics render --filter-water`): the slope moments' pyramid and the filtered shading
    /// are timed with the final image.
    #[arg(long)]
    filter_water: bool,
    /// Output folder.
    #[arg(long, default_value = "bench")]
    pub(crate) out: PathBuf,
    #[command(flatten)]
    pub(crate) gpu: crate::GpuArgs,
}

#[derive(Clone, Debug)]
pub struct Measurement {
    /// The technique's label, with the scene where it is not the pool (`caustic-triangles
    /// (glass)`); `frame: <technique>` for the whole frame.
    pub technique: String,
    pub width: u32,
    pub height: u32,
    pub backend: &'static str,
    /// (pass, median ms, 10th percentile, 90th percentile), GPU timestamps.
    pub passes: Vec<(String, f64, f64, f64)>,
    /// Sum of the passes' medians (GPU) or the CPU twin's median wall time.
    pub total_ms: f64,
    /// Median wall time per frame: submit to idle for the measured submission (the technique's
    /// alone, or the whole frame's), or the CPU twin's run.
    pub wall_ms: f64,
    pub gpu_bytes: u64,
}

pub(crate) fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn parse_image_size(s: &str) -> Result<[u32; 2], String> {
    crate::parse_size_within(s, 1..=16384)
}

/// The (picture, map) sizes to time. Each image size with its map: the one map size given for all,
/// the map sizes paired in order, or the image's own size; map sizes alone each with a picture of
/// their own size; neither, 1280 x 720 and 1920 x 1080 (64 x 36 `quick`).
fn sizes(images: &[[u32; 2]], maps: &[[u32; 2]], quick: bool) -> Result<Vec<([u32; 2], [u32; 2])>> {
    if let Some([w, h]) = maps
        .iter()
        .find(|[w, h]| !(1..=16384).contains(w) || !(1..=16384).contains(h))
    {
        bail!("--map-size {w}x{h}: each side must be from 1 to 16384");
    }
    let images = match (images, maps) {
        ([], []) if quick => vec![[64, 36]],
        ([], []) => vec![[1280, 720], [1920, 1080]],
        ([], maps) => maps.to_vec(),
        (given, _) => given.to_vec(),
    };
    Ok(match maps {
        [] => images.iter().map(|&i| (i, i)).collect(),
        [m] => images.iter().map(|&i| (i, *m)).collect(),
        maps if maps.len() == images.len() => {
            images.iter().copied().zip(maps.iter().copied()).collect()
        }
        maps => bail!(
            "--map-size: {} sizes for {} image sizes; give one for all or one for each",
            maps.len(),
            images.len()
        ),
    })
}

/// Every registered technique, as specs with default parameters.
pub(crate) fn registered() -> Result<Vec<Spec>> {
    REGISTRY.iter().map(|r| Ok(r.name().parse()?)).collect()
}

/// The built-in scenes `spec` applies to: the pool (its water) for every technique, the glass
/// scene (its objects) for those that take glass generators, the shore (its beach) and the reef (its
/// sea bed and rocks).
pub(crate) fn scenes_for(spec: &Spec) -> Result<Vec<Scene>> {
    let mut out = vec![Scene::builtin("pool")?];
    if spec.entry.input == Input::GlassOrWater {
        out.push(Scene::builtin("glass")?);
    }
    out.push(Scene::builtin("shore")?);
    out.push(Scene::builtin("reef")?);
    Ok(out)
}

/// The row label of `spec` on `scene`: the scene named where it is not the pool.
fn label(spec: &Spec, scene: &Scene) -> String {
    if scene.name == "pool" {
        spec.label.clone()
    } else {
        format!("{} ({})", spec.label, scene.name)
    }
}

/// The timing table of `args`'s techniques and scenes (`--tradeoff` is [`crate::tradeoff::run`]'s,
/// which main dispatches to).
pub fn run(args: BenchArgs) -> Result<()> {
    let specs = if args.techniques.is_empty() {
        registered()?
    } else {
        args.techniques.clone()
    };
    let frames = args.frames.unwrap_or(if args.quick { 1 } else { 30 });
    let warmup = args.warmup.unwrap_or(if args.quick { 1 } else { 3 });
    if frames == 0 {
        bail!("--frames must be at least 1");
    }
    let sizes = sizes(&args.image_size, &args.map_size, args.quick)?;
    // The scenes asked for, read before any device is made so that a bad one fails at once.
    let asked = (!args.scenes.is_empty())
        .then(|| {
            args.scenes
                .iter()
                .map(|name| Scene::load_or_builtin(name))
                .collect::<Result<Vec<_>, _>>()
        })
        .transpose()?;
    let gpu = args.gpu.context()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let adapter = gpu
        .as_ref()
        .map_or("none: CPU twins (wall time)".to_string(), |c| c.describe());
    println!("adapter: {adapter}");
    let timing = Timing { warmup, frames };
    let jobs: Vec<(Spec, Scene)> = specs
        .iter()
        .map(|s| {
            let scenes = match &asked {
                Some(scenes) => scenes.clone(),
                None => scenes_for(s)?,
            };
            Ok(scenes.into_iter().map(|sc| (s.clone(), sc)))
        })
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .flatten()
        .collect();
    let bar = progress::bar("bench");
    bar.set_length((jobs.len() * sizes.len()) as u64);
    let mut results = Vec::new();
    let mut runner = None;
    let started = Instant::now();
    for (spec, base) in &jobs {
        for &([w, h], [mw, mh]) in &sizes {
            let mut scene = base.clone();
            scene.caustics.width = mw;
            scene.caustics.height = mh;
            scene.camera.width = w;
            scene.camera.height = h;
            let spec = spec.clone().over(&base.caustics.params);
            let name = label(&spec, &scene);
            let rows = match &gpu {
                Some(ctx) => {
                    let mut rows = vec![
                        time_technique(ctx, &scene, &spec, &timing)
                            .with_context(|| format!("{name} at a {mw} x {mh} map"))?,
                    ];
                    if !args.no_frame {
                        rows.push(
                            time_frame(ctx, &scene, &spec, &timing, args.filter_water)
                                .with_context(|| format!("frame of {name} at {w} x {h}"))?,
                        );
                    }
                    rows
                }
                None => {
                    let r = runner.get_or_insert_with(|| Runner::new(None));
                    vec![time_cpu(r, &scene, &spec, &timing)?]
                }
            };
            for mut m in rows {
                m.technique = format!("{}{name}", m.technique);
                report(&m);
                results.push(m);
            }
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    let elapsed = started.elapsed().as_secs_f64();
    std::fs::write(args.out.join("bench.csv"), csv(&results))?;
    std::fs::write(
        args.out.join("bench.md"),
        markdown(&results, &adapter, &timing, elapsed),
    )?;
    plot(&results, &args.out.join("bench.svg"), &adapter)?;
    eprintln!(
        "wrote {} ({elapsed:.0} s)",
        args.out.join("bench.md").display()
    );
    Ok(())
}

#[derive(Clone, Copy)]
pub(crate) struct Timing {
    pub warmup: u32,
    pub frames: u32,
}

fn report(m: &Measurement) {
    println!(
        "{:<36} {:>5} x {:<5} {} {:>9.3} ms  (wall {:.3} ms, {:.1} MiB)",
        m.technique,
        m.width,
        m.height,
        m.backend,
        m.total_ms,
        m.wall_ms,
        m.gpu_bytes as f64 / (1 << 20) as f64
    );
}

/// A 1 x 1 water texture of height 0, the water of a scene without any (glass generators read
/// none).
fn no_water(ctx: &GpuContext) -> WaterTextures {
    let t = ctx.texture_2d(
        "no water",
        (1, 1, 1),
        wgpu::TextureFormat::R32Float,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    ctx.write_texture(
        t.as_image_copy(),
        &0f32.to_ne_bytes(),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4),
            rows_per_image: Some(1),
        },
        t.size(),
    );
    WaterTextures::of(&t)
}

/// One technique through `caustics_gpu::technique`, as an application runs it: configured once
/// on the scene's GPU water, then per frame the water advanced and encoded in a submission of its
/// own (untimed), the technique updated and encoded, timed, in the next. The label of the returned
/// measurement is empty (the caller names it).
pub(crate) fn time_technique(
    ctx: &GpuContext,
    scene: &Scene,
    spec: &Spec,
    timing: &Timing,
) -> Result<Measurement> {
    let mut t = registry::create(ctx, spec.name(), &spec.params)?;
    let mut water = scene
        .water
        .as_ref()
        .map(|w| GpuWater::new(ctx, w))
        .transpose()?;
    let textures = match &mut water {
        Some(w) => {
            let (cols, rows) = t.water_resolution(scene);
            w.update(ctx, scene.time, 1.0);
            w.output(ctx, cols, rows)?
        }
        None => no_water(ctx),
    };
    t.configure(ctx, scene, &textures)?;
    let mut timer = GpuTimer::new(ctx, 64);
    let (w, h) = (scene.caustics.width, scene.caustics.height);
    let bytes = t.bytes();
    let mut clock = scene.time;
    time_frames(timing, (w, h), bytes, || {
        clock += 1.0 / 60.0;
        if let Some(water) = &mut water {
            water.update(ctx, clock, 1.0);
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            water.encode(&mut encoder, None);
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
        }
        t.update(ctx, scene)?;
        let started = Instant::now();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        t.encode(&mut encoder, Some(&mut timer));
        timer.resolve(&mut encoder);
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        Ok((started.elapsed().as_secs_f64() * 1e3, timer.read(ctx)?))
    })
}

/// The whole frame through the renderer the viewer uses: water, technique and final image at the
/// camera's size in one submission; the wall time is `render` to idle. The timestamps come from
/// the renderer's own timer (its frame-loop copy, picked up once the frame is done).
fn time_frame(
    ctx: &GpuContext,
    scene: &Scene,
    spec: &Spec,
    timing: &Timing,
    filter_water: bool,
) -> Result<Measurement> {
    let mut renderer = Renderer::new(ctx)?;
    renderer.set_water(ctx, scene.water.as_ref(), &FrameWater::Scene)?;
    renderer.set_techniques(ctx, &[Some(TechniqueSpec::from(spec))]);
    let options = RenderOptions {
        supersampling: 1,
        filter_water,
        ..Default::default()
    };
    let mut clock = scene.time;
    let mut first = true;
    let mut m = time_frames(timing, (0, 0), 0, || {
        clock += 1.0 / 60.0;
        let started = Instant::now();
        renderer.render(
            ctx,
            scene,
            WaterClock {
                time: clock,
                amplitude: 1.0,
                steps: 0,
            },
            &options,
        )?;
        ctx.wait()?;
        let wall = started.elapsed().as_secs_f64() * 1e3;
        if first {
            first = false;
            if let Some(e) = renderer.error(0) {
                bail!("{e}");
            }
        }
        let passes = (renderer.timer.as_mut()).map_or_else(Vec::new, |t| t.latest(ctx).to_vec());
        Ok((wall, passes))
    })?;
    m.width = scene.camera.width;
    m.height = scene.camera.height;
    m.gpu_bytes = renderer.technique_bytes();
    m.technique = if filter_water {
        "frame: water filtered, ".into()
    } else {
        "frame: ".into()
    };
    Ok(m)
}

/// Warm-up then timed frames of `frame`, which records, submits and waits for one frame and
/// returns its wall time and its passes' GPU times: GPU time per pass label (passes recorded more
/// than once in a frame under one label, such as one downsample per mip level, summed per frame).
fn time_frames(
    timing: &Timing,
    (width, height): (u32, u32),
    gpu_bytes: u64,
    mut frame: impl FnMut() -> Result<(f64, Vec<PassTime>)>,
) -> Result<Measurement> {
    let mut per_pass: Vec<(String, Vec<f64>)> = Vec::new();
    let mut walls = Vec::new();
    for k in 0..timing.warmup + timing.frames {
        let (wall, passes) = frame()?;
        if k < timing.warmup {
            continue;
        }
        walls.push(wall);
        let mut sums: Vec<(String, f64)> = Vec::new();
        for p in passes {
            match sums.iter_mut().find(|(l, _)| *l == p.label) {
                Some((_, ms)) => *ms += p.ms,
                None => sums.push((p.label, p.ms)),
            }
        }
        for (l, ms) in sums {
            record(&mut per_pass, l, ms);
        }
    }
    let passes = summarise(per_pass);
    walls.sort_by(f64::total_cmp);
    let wall = percentile(&walls, 0.5);
    let total = if passes.is_empty() {
        wall
    } else {
        passes.iter().map(|p| p.1).sum()
    };
    Ok(Measurement {
        technique: String::new(),
        width,
        height,
        backend: "GPU",
        passes,
        total_ms: total,
        wall_ms: wall,
        gpu_bytes,
    })
}

/// The CPU twin of `spec` on `scene` through the runner `caustics compare` uses (at most 5 frames).
fn time_cpu(
    runner: &mut Runner,
    scene: &Scene,
    spec: &Spec,
    timing: &Timing,
) -> Result<Measurement> {
    let surface = scene
        .water
        .as_ref()
        .map(|w| w.surface_at(scene.time))
        .transpose()?;
    let mut walls = Vec::new();
    for _ in 0..timing.frames.min(5) {
        let started = Instant::now();
        runner.run(spec, &Job::new(scene, surface.as_deref(), 1), &|_, _| {})?;
        walls.push(started.elapsed().as_secs_f64() * 1e3);
    }
    walls.sort_by(f64::total_cmp);
    let wall = percentile(&walls, 0.5);
    Ok(Measurement {
        technique: String::new(),
        width: scene.caustics.width,
        height: scene.caustics.height,
        backend: "CPU",
        passes: vec![(
            format!("{} (CPU twin)", spec.name()),
            wall,
            walls[0],
            walls[walls.len() - 1],
        )],
        total_ms: wall,
        wall_ms: wall,
        gpu_bytes: 0,
    })
}

/// Add a sample to the series of `label`, series kept in the order first seen.
fn record(series: &mut Vec<(String, Vec<f64>)>, label: String, ms: f64) {
    match series.iter_mut().find(|(l, _)| *l == label) {
        Some((_, v)) => v.push(ms),
        None => series.push((label, vec![ms])),
    }
}

/// Each series as (label, median, 10th percentile, 90th percentile).
fn summarise(series: Vec<(String, Vec<f64>)>) -> Vec<(String, f64, f64, f64)> {
    series
        .into_iter()
        .map(|(l, mut v)| {
            v.sort_by(f64::total_cmp);
            let at = |p| percentile(&v, p);
            (l, at(0.5), at(0.1), at(0.9))
        })
        .collect()
}

/// Least-squares slope of log(time) over log(pixels): 1 is linear in the pixel count.
pub fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x.ln(), b + y.ln()));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = points.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
        (a + (x.ln() - mx) * (y.ln() - my), b + (x.ln() - mx).powi(2))
    });
    num / den
}

fn csv(results: &[Measurement]) -> String {
    let mut s =
        "technique,width,height,backend,pass,median_ms,p10_ms,p90_ms,total_ms,wall_ms,gpu_bytes\n"
            .to_string();
    for m in results {
        let none = [(String::new(), 0.0, 0.0, 0.0)];
        let passes = if m.passes.is_empty() {
            &none[..]
        } else {
            &m.passes[..]
        };
        for (p, med, lo, hi) in passes {
            let _ = writeln!(
                s,
                "\"{}\",{},{},{},\"{p}\",{med:.4},{lo:.4},{hi:.4},{:.4},{:.4},{}",
                m.technique, m.width, m.height, m.backend, m.total_ms, m.wall_ms, m.gpu_bytes
            );
        }
    }
    s
}

fn markdown(results: &[Measurement], adapter: &str, timing: &Timing, elapsed: f64) -> String {
    let mut s = format!(
        "# caustics bench\n\nAdapter: {adapter}. {} warm-up frames, then {} timed frames per row ({elapsed:.0} s in \
         all). A technique row is the technique alone as an application runs it (configured once on the \
         pool's GPU water, or the glass scene's objects; per frame the water in a submission of its own, then \
         the technique's passes, timed, at a map of the given size); a `frame:` row is the whole GPU frame \
         through the renderer the viewer uses (water, technique, final image at a camera of the given size, \
         one submission). GPU: the sum of the passes' timestamp medians (each pass: median [10th, 90th \
         percentile]); wall: submit to idle of the timed submission, the cross-check (on a real GPU wall is \
         GPU plus a fraction of a millisecond; where GPU is far below wall, the timestamps are not to be \
         trusted: Mesa's lavapipe under-reports passes recorded after others in one command buffer); memory: \
         what the technique allocates on the GPU for that size.\n\n",
        timing.warmup, timing.frames
    );
    s += "| technique | resolution | backend | GPU total (ms) | wall (ms) | passes: median [p10, p90] ms | GPU memory (MiB) |\n|---|---|---|---|---|---|---|\n";
    for m in results {
        let passes: Vec<String> = m
            .passes
            .iter()
            .map(|(p, med, lo, hi)| format!("{p}: {med:.3} [{lo:.3}, {hi:.3}]"))
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} x {} | {} | {:.3} | {:.3} | {} | {:.2} |",
            m.technique,
            m.width,
            m.height,
            m.backend,
            m.total_ms,
            m.wall_ms,
            passes.join("; "),
            m.gpu_bytes as f64 / (1 << 20) as f64
        );
    }
    s += "\n| technique | slope of log wall time over log pixels |\n|---|---|\n";
    let mut names: Vec<&str> = results.iter().map(|m| m.technique.as_str()).collect();
    names.sort();
    names.dedup();
    for t in names {
        let pts: Vec<(f64, f64)> = results
            .iter()
            .filter(|m| m.technique == t)
            .map(|m| (m.width as f64 * m.height as f64, m.wall_ms.max(1e-6)))
            .collect();
        if pts.len() >= 2 {
            let _ = writeln!(s, "| {t} | {:.2} |", slope(&pts));
        }
    }
    s += "\n![wall time over resolution](bench.svg)\n";
    s
}

fn plot(results: &[Measurement], path: &std::path::Path, adapter: &str) -> Result<()> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let xs = results
        .iter()
        .map(|m| (m.width as f64 * m.height as f64).log10());
    let ys = results.iter().map(|m| m.wall_ms.max(1e-4).log10());
    let (x0, x1) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("wall time per frame: {adapter}"),
            ("sans-serif", 14),
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d((x0 - 0.2)..(x1 + 0.2), (y0 - 0.3)..(y1 + 0.3))?;
    chart
        .configure_mesh()
        .x_desc("log10 pixels")
        .y_desc("log10 ms")
        .draw()?;
    let mut names: Vec<&str> = results.iter().map(|m| m.technique.as_str()).collect();
    names.sort();
    names.dedup();
    for (k, t) in names.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let dashed = t.starts_with("frame: ");
        let pts: Vec<(f64, f64)> = results
            .iter()
            .filter(|m| m.technique == *t)
            .map(|m| {
                (
                    (m.width as f64 * m.height as f64).log10(),
                    m.wall_ms.max(1e-4).log10(),
                )
            })
            .collect();
        let width = if dashed { 1 } else { 2 };
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(width)))?
            .label(*t)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(width))
            });
        chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font(("sans-serif", 10))
        .border_style(BLACK)
        .background_style(WHITE.mix(0.8))
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::sizes;

    #[test]
    fn image_and_map_sizes_pair_as_documented() {
        let (hd, fhd) = ([1280, 720], [1920, 1080]);
        // Neither: the two picture sizes, each its own map; `quick`, one small size.
        assert_eq!(sizes(&[], &[], false).unwrap(), [(hd, hd), (fhd, fhd)]);
        assert_eq!(sizes(&[], &[], true).unwrap(), [([64, 36], [64, 36])]);
        // One map for every picture, or one each in order.
        let m = [1024, 1024];
        assert_eq!(sizes(&[hd, fhd], &[m], false).unwrap(), [(hd, m), (fhd, m)]);
        assert_eq!(
            sizes(&[hd, fhd], &[m, [512, 512]], false).unwrap(),
            [(hd, m), (fhd, [512, 512])]
        );
        // Maps alone: each with a picture of its own size.
        assert_eq!(sizes(&[], &[m], true).unwrap(), [(m, m)]);
        // Counts that pair no way, and a side beyond the limit, are refused by name.
        let e = sizes(&[hd], &[m, m], false).unwrap_err().to_string();
        assert!(e.contains("--map-size: 2 sizes for 1 image sizes"), "{e}");
        let e = sizes(&[hd], &[[0, 8]], false).unwrap_err().to_string();
        assert!(e.contains("--map-size 0x8"), "{e}");
    }
}
