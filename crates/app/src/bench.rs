//! `caustics bench`: for each technique and resolution, warm-up frames then timed frames; GPU time
//! per pass from timestamp queries (median and spread), CPU time per frame, the GPU memory the
//! technique allocates, and how time grows with resolution (the slope of log time over log pixels).
//! Writes Markdown, CSV and an SVG plot.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;

use caustics_core::cases::cases;
use caustics_core::techniques::procedural::{self, ProceduralCausticsParams, ProceduralSetup};
use caustics_core::techniques::yuksel::{self, YukselParams, YukselSetup};
use caustics_gpu::procedural::ProceduralCaustics;
use caustics_gpu::yuksel::{Variant, Yuksel};
use caustics_gpu::{GpuContext, GpuTimer};

use crate::progress;
use crate::techniques::{Spec, heights_for, procedural_heights};

#[derive(Args)]
pub struct BenchArgs {
    /// Techniques, `name` or `name:key=value,...` (yuksel, yuksel-gather, procedural,
    /// procedural-vertex, procedural-screen, procedural-texture); repeat the flag. Default: yuksel
    /// and yuksel-gather.
    #[arg(long = "technique")]
    techniques: Vec<Spec>,
    /// Map resolutions WIDTHxHEIGHT, comma-separated (the paper's sizes first).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "400x300,800x600,1920x1080,4096x4096"
    )]
    resolution: Vec<String>,
    /// Timed frames per measurement.
    #[arg(long, default_value_t = 50)]
    frames: u32,
    /// Untimed frames first (pipeline compilation, caches).
    #[arg(long, default_value_t = 5)]
    warmup: u32,
    /// Output folder.
    #[arg(long, default_value = "bench")]
    out: PathBuf,
    #[command(flatten)]
    gpu: crate::GpuArgs,
}

#[derive(Clone, Debug)]
pub struct Measurement {
    pub technique: String,
    pub width: u32,
    pub height: u32,
    pub backend: &'static str,
    /// (pass, median ms, 10th percentile, 90th percentile), GPU timestamps.
    pub passes: Vec<(String, f64, f64, f64)>,
    /// Sum of the passes' medians (GPU) or the CPU twin's median wall time.
    pub total_ms: f64,
    /// Wall time per frame on the CPU side: encode + submit + wait.
    pub cpu_ms: f64,
    pub gpu_bytes: u64,
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

fn parse_res(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .with_context(|| format!("`{s}`: expected WIDTHxHEIGHT"))?;
    let (w, h): (u32, u32) = (w.trim().parse()?, h.trim().parse()?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        bail!("resolution {s}: each side must be between 1 and 16384");
    }
    Ok((w, h))
}

pub fn run(args: BenchArgs) -> Result<()> {
    let specs = if args.techniques.is_empty() {
        vec!["yuksel".parse()?, "yuksel-gather".parse()?]
    } else {
        args.techniques.clone()
    };
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    let sizes = args
        .resolution
        .iter()
        .map(|s| parse_res(s))
        .collect::<Result<Vec<_>>>()?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let gpu = args.gpu.context();
    let adapter = gpu
        .as_ref()
        .map_or("none: CPU twins (wall time)".to_string(), |c| c.describe());
    println!("adapter: {adapter}");
    // The measured water: smooth periodic waves, the sun 30 degrees from the zenith, deep water.
    let case = cases(true).into_iter().next().expect("a case");
    let surface = case.water.surface_at(0.0)?;
    let bar = progress::bar("bench");
    bar.set_length((specs.len() * sizes.len()) as u64);
    let mut results = Vec::new();
    for spec in &specs {
        if spec.name == "procedural" {
            let params = ProceduralCausticsParams::from_table(&spec.params)?;
            let pipelines = gpu.as_ref().map(ProceduralCaustics::new).transpose()?;
            for &(w, h) in &sizes {
                let wt = &case.water;
                let setup = ProceduralSetup::new(
                    &params,
                    w as usize,
                    h as usize,
                    wt.size,
                    wt.depth,
                    wt.absorption,
                    wt.wrap,
                    case.light,
                )?;
                let heights = procedural_heights(wt, surface.as_ref(), &setup);
                let water = procedural::SurfaceInput::Grid(&heights);
                let m = match (&gpu, &pipelines) {
                    (Some(ctx), Some(p)) => {
                        let frame = p.frame(ctx, &setup, &water)?;
                        time_frames(ctx, &args, &spec.label, (w, h), frame.bytes(), |timer| {
                            let mut encoder =
                                ctx.device.create_command_encoder(&Default::default());
                            p.encode(&frame, &mut encoder, Some(timer));
                            timer.resolve(&mut encoder);
                            ctx.queue.submit([encoder.finish()]);
                        })?
                    }
                    _ => bench_cpu_procedural(&setup, &water, &args, &spec.label),
                };
                report(&m);
                results.push(m);
                bar.inc(1);
            }
            continue;
        }
        if spec.name != "yuksel" {
            bail!(
                "`caustics bench` measures yuksel and procedural so far; `{}` has no GPU path yet",
                spec.label
            );
        }
        let params = YukselParams::from_table(&spec.params)?;
        let variant = if spec.gather {
            Variant::Gather
        } else {
            Variant::RenderTargets
        };
        let pipelines = gpu.as_ref().map(Yuksel::new).transpose()?;
        for &(w, h) in &sizes {
            let wt = &case.water;
            let setup = YukselSetup::new(
                &params,
                w as usize,
                h as usize,
                wt.size,
                wt.depth,
                wt.ior,
                wt.absorption,
                wt.wrap,
                case.light,
            )?;
            let heights = heights_for(wt, surface.as_ref(), w as usize, h as usize);
            let m = match (&gpu, &pipelines) {
                (Some(ctx), Some(y)) => {
                    bench_gpu(ctx, y, &setup, &heights, variant, &args, &spec.label)?
                }
                _ => bench_cpu(&setup, &heights, &args, &spec.label),
            };
            report(&m);
            results.push(m);
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    std::fs::write(args.out.join("bench.csv"), csv(&results))?;
    std::fs::write(
        args.out.join("bench.md"),
        markdown(&results, &adapter, &args),
    )?;
    plot(&results, &args.out.join("bench.svg"), &adapter)?;
    eprintln!("wrote {}", args.out.join("bench.md").display());
    Ok(())
}

fn report(m: &Measurement) {
    println!(
        "{:<24} {:>5} x {:<5} {} {:>9.3} ms  (CPU {:.3} ms, {:.1} MiB)",
        m.technique,
        m.width,
        m.height,
        m.backend,
        m.total_ms,
        m.cpu_ms,
        m.gpu_bytes as f64 / (1 << 20) as f64
    );
}

fn bench_gpu(
    ctx: &GpuContext,
    y: &Yuksel,
    setup: &YukselSetup,
    heights: &caustics_core::grid::Grid,
    variant: Variant,
    args: &BenchArgs,
    label: &str,
) -> Result<Measurement> {
    let frame = y.frame(ctx, setup, heights, variant)?;
    time_frames(
        ctx,
        args,
        label,
        (setup.width as u32, setup.height as u32),
        frame.bytes(),
        |timer| {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            y.encode(&frame, &mut encoder, Some(timer));
            timer.resolve(&mut encoder);
            ctx.queue.submit([encoder.finish()]);
        },
    )
}

/// Warm-up then timed frames of whatever `submit` encodes (with the timer's timestamps, resolved)
/// and submits: GPU time per pass label (passes recorded more than once in a frame under one label,
/// such as one downsample per mip level, are summed per frame), and the CPU wall time of encoding,
/// submitting and waiting.
fn time_frames(
    ctx: &GpuContext,
    args: &BenchArgs,
    label: &str,
    (width, height): (u32, u32),
    gpu_bytes: u64,
    mut submit: impl FnMut(&mut GpuTimer),
) -> Result<Measurement> {
    let mut timer = GpuTimer::new(ctx, 32);
    let mut per_pass: Vec<(String, Vec<f64>)> = Vec::new();
    let mut cpu = Vec::new();
    for k in 0..args.warmup + args.frames {
        let started = Instant::now();
        submit(&mut timer);
        ctx.wait()?;
        let wall = started.elapsed().as_secs_f64() * 1e3;
        let passes = timer.read(ctx)?;
        if k < args.warmup {
            continue;
        }
        cpu.push(wall);
        let mut frame: Vec<(String, f64)> = Vec::new();
        for p in passes {
            match frame.iter_mut().find(|(l, _)| *l == p.label) {
                Some((_, ms)) => *ms += p.ms,
                None => frame.push((p.label, p.ms)),
            }
        }
        for (l, ms) in frame {
            record(&mut per_pass, l, ms);
        }
    }
    let passes = summarise(per_pass);
    cpu.sort_by(f64::total_cmp);
    let total = if passes.is_empty() {
        percentile(&cpu, 0.5)
    } else {
        passes.iter().map(|p| p.1).sum()
    };
    Ok(Measurement {
        technique: label.to_string(),
        width,
        height,
        backend: "GPU",
        passes,
        total_ms: total,
        cpu_ms: percentile(&cpu, 0.5),
        gpu_bytes,
    })
}

/// The procedural CPU twin, stage by stage (wall time, at most 5 frames).
fn bench_cpu_procedural(
    setup: &ProceduralSetup,
    water: &procedural::SurfaceInput,
    args: &BenchArgs,
    label: &str,
) -> Measurement {
    let frames = args.frames.min(5);
    let mut stages: Vec<(String, Vec<f64>)> = Vec::new();
    let mut total = Vec::new();
    for _ in 0..frames {
        let mut times: Vec<(&str, f64)> = Vec::new();
        let mut lap = Instant::now();
        let mut mark = |name: &'static str, times: &mut Vec<(&str, f64)>| {
            times.push((name, lap.elapsed().as_secs_f64() * 1e3));
            lap = Instant::now();
        };
        match setup.variant {
            procedural::Variant::Vertex => {
                let values = procedural::vertex_values(setup, water);
                mark("vertex values", &mut times);
                let _ = procedural::rasterise(setup, &values);
                mark("rasterise", &mut times);
            }
            procedural::Variant::Screen => {
                let _ = procedural::per_pixel(setup, water, setup.width, setup.height);
                mark("per pixel", &mut times);
            }
            procedural::Variant::Texture => {
                let level0 = procedural::per_pixel(setup, water, setup.target, setup.target);
                mark("target", &mut times);
                let levels = procedural::mip_chain(level0, setup.target);
                mark("mips", &mut times);
                let _ = procedural::resample(setup, &levels);
                mark("resample", &mut times);
            }
        }
        total.push(times.iter().map(|t| t.1).sum::<f64>());
        for (name, ms) in times {
            let name = format!("procedural {name} (CPU twin)");
            record(&mut stages, name, ms);
        }
    }
    total.sort_by(f64::total_cmp);
    Measurement {
        technique: label.to_string(),
        width: setup.width as u32,
        height: setup.height as u32,
        backend: "CPU",
        passes: summarise(stages),
        total_ms: percentile(&total, 0.5),
        cpu_ms: percentile(&total, 0.5),
        gpu_bytes: 0,
    }
}

fn bench_cpu(
    setup: &YukselSetup,
    heights: &caustics_core::grid::Grid,
    args: &BenchArgs,
    label: &str,
) -> Measurement {
    let frames = args.frames.min(5);
    let mut names = ["pre-pass", "pass 1", "pass 2"].map(|n| (n.to_string(), Vec::new()));
    let mut total = Vec::new();
    for _ in 0..frames {
        let t0 = Instant::now();
        let pre = yuksel::prepass(setup, heights);
        let t1 = Instant::now();
        let p1 = yuksel::pass1(setup, &pre);
        let t2 = Instant::now();
        let _ = yuksel::pass2(setup, &p1);
        let t3 = Instant::now();
        for (k, d) in [t1 - t0, t2 - t1, t3 - t2].iter().enumerate() {
            names[k].1.push(d.as_secs_f64() * 1e3);
        }
        total.push((t3 - t0).as_secs_f64() * 1e3);
    }
    total.sort_by(f64::total_cmp);
    Measurement {
        technique: label.to_string(),
        width: setup.width as u32,
        height: setup.height as u32,
        backend: "CPU",
        passes: summarise(
            names
                .into_iter()
                .map(|(l, v)| (format!("yuksel {l} (CPU twin)"), v))
                .collect(),
        ),
        total_ms: percentile(&total, 0.5),
        cpu_ms: percentile(&total, 0.5),
        gpu_bytes: 0,
    }
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
            let (median, lo, hi) = (
                percentile(&v, 0.5),
                percentile(&v, 0.1),
                percentile(&v, 0.9),
            );
            (l, median, lo, hi)
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
        "technique,width,height,backend,pass,median_ms,p10_ms,p90_ms,total_ms,cpu_ms,gpu_bytes\n"
            .to_string();
    for m in results {
        for (p, med, lo, hi) in &m.passes {
            let _ = writeln!(
                s,
                "\"{}\",{},{},{},\"{p}\",{med:.4},{lo:.4},{hi:.4},{:.4},{:.4},{}",
                m.technique, m.width, m.height, m.backend, m.total_ms, m.cpu_ms, m.gpu_bytes
            );
        }
    }
    s
}

fn markdown(results: &[Measurement], adapter: &str, args: &BenchArgs) -> String {
    let mut s = format!(
        "# caustics bench\n\nAdapter: {adapter}. {} warm-up frames, then {} timed frames per row; GPU times are \
         timestamp queries around each pass (median, with the 10th-90th percentile spread); CPU is the wall \
         time of encoding, submitting and waiting for one frame; memory is what the technique allocates on \
         the GPU for that size.\n\n",
        args.warmup, args.frames
    );
    s += "| technique | resolution | backend | total (ms) | passes: median [p10, p90] ms | CPU (ms) | GPU memory (MiB) |\n|---|---|---|---|---|---|---|\n";
    for m in results {
        let passes: Vec<String> = m
            .passes
            .iter()
            .map(|(p, med, lo, hi)| format!("{p}: {med:.3} [{lo:.3}, {hi:.3}]"))
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} x {} | {} | {:.3} | {} | {:.3} | {:.2} |",
            m.technique,
            m.width,
            m.height,
            m.backend,
            m.total_ms,
            passes.join("; "),
            m.cpu_ms,
            m.gpu_bytes as f64 / (1 << 20) as f64
        );
    }
    s += "\n| technique | slope of log time over log pixels |\n|---|---|\n";
    let mut names: Vec<&str> = results.iter().map(|m| m.technique.as_str()).collect();
    names.dedup();
    for t in names {
        let pts: Vec<(f64, f64)> = results
            .iter()
            .filter(|m| m.technique == t)
            .map(|m| (m.width as f64 * m.height as f64, m.total_ms))
            .collect();
        if pts.len() >= 2 {
            let _ = writeln!(s, "| {t} | {:.2} |", slope(&pts));
        }
    }
    s += "\n![time over resolution](bench.svg)\n";
    s
}

fn plot(results: &[Measurement], path: &std::path::Path, adapter: &str) -> Result<()> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (720, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let xs = results
        .iter()
        .map(|m| (m.width as f64 * m.height as f64).log10());
    let ys = results.iter().map(|m| m.total_ms.max(1e-4).log10());
    let (x0, x1) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys.fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("time per frame: {adapter}"), ("sans-serif", 14))
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
    names.dedup();
    for (k, t) in names.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let pts: Vec<(f64, f64)> = results
            .iter()
            .filter(|m| m.technique == *t)
            .map(|m| {
                (
                    (m.width as f64 * m.height as f64).log10(),
                    m.total_ms.max(1e-4).log10(),
                )
            })
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))?
            .label(*t)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 16, y)], color.stroke_width(2))
            });
        chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()?;
    root.present()?;
    Ok(())
}
