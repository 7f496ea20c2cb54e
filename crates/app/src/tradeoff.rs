//! `caustics bench --tradeoff`: which technique for which budget. Each technique's main knob is
//! swept (paper 1's region N = M, paper 2's variant and its mesh or target resolution, paper 3's
//! reference planes, paper 4's photon image, paper 5's cascade resolution); each setting gets its
//! error, the relative L1 against the reference exactly as `caustics compare` measures it (the
//! same runner, the same cases of `caustics_core::cases`, the mean over them), and its cost, the
//! GPU time per frame exactly as `caustics bench` measures it (the technique alone through
//! `caustics_gpu::technique`, at the same map size, on the first case's water). The Pareto front
//! is every setting that no other beats on both at once.
//!
//! `cascaded` (paper 5) makes an eye-space image, not a floor map, so it is measured on the pool
//! scene through its camera: the reference floor map projected to the eye (each pixel reads the
//! map bilinearly at the floor point its eye ray meets, as `caustics_core::render`'s test of
//! eye-space caustics does), and the relative L1 taken over the pixels that have a value and see
//! the floor square. Its cost is timed on that scene at that camera size.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, bail};

use caustics_core::cases::cases;
use caustics_core::metrics::compare;
use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::scene::Scene;

use crate::bench::{Timing, time_technique};
use crate::compare::case_scene;
use crate::techniques::{Job, Runner, SceneCaustics, Spec};

/// One setting of one technique.
pub struct Point {
    pub technique: String,
    pub setting: String,
    /// Map side (floor techniques) or the camera's width x height (cascaded).
    pub size: String,
    /// Mean relative L1 against the reference.
    pub error: f64,
    /// The cost charted: the GPU time, or the wall time where the timestamps are not to be
    /// trusted ([`cost`]).
    pub cost_ms: f64,
    /// GPU time per frame: the sum of the technique's passes' timestamp medians.
    pub gpu_ms: f64,
    /// Wall time of the technique's submission, the cross-check.
    pub wall_ms: f64,
    pub pareto: bool,
}

/// The sweep: every registered GPU technique but the reference, each over the settings of the
/// parameters its descriptor flags for sweeping (each one's `sweep` values in turn, the others at
/// their defaults; the first two of each for the quick run), or once at its defaults where none
/// is flagged. An entry whose every variant is an entry of its own (`procedural`) is swept
/// through them; one with a variant of its own beside them (`yuksel`'s scatter beside
/// `yuksel-targets`) is swept too.
fn sweep(quick: bool) -> Vec<(&'static str, Vec<String>)> {
    caustics_gpu::registry::REGISTRY
        .iter()
        .map(|r| r.describe)
        .filter(|d| !d.reference)
        .filter(|d| !(d.fixed.is_empty() && variants_cover(d)))
        .map(|d| {
            let mut settings: Vec<String> = d
                .params
                .iter()
                .flat_map(|p| {
                    let n = if quick { 2 } else { p.sweep.len() };
                    p.sweep.iter().take(n).map(|v| format!("{}={v}", p.key))
                })
                .collect();
            if settings.is_empty() {
                settings.push(String::new());
            }
            (d.name, settings)
        })
        .collect()
}

/// Whether the entries that pin a parameter of `d`'s table pin every value it may take.
fn variants_cover(d: &caustics_core::techniques::Descriptor) -> bool {
    use caustics_core::techniques::REGISTRY as DESCRIBED;
    use caustics_core::techniques::describe::Kind;
    let pins: Vec<(&str, &str)> = DESCRIBED
        .iter()
        .filter(|o| o.table == d.table)
        .flat_map(|o| o.fixed.iter().copied())
        .collect();
    let Some((key, _)) = pins.first() else {
        return false;
    };
    match d.param(key).map(|p| p.kind) {
        Some(Kind::Choice(values)) => values
            .iter()
            .all(|v| pins.iter().any(|(k, pinned)| k == key && pinned == v)),
        _ => false,
    }
}

struct Sizes {
    /// Floor map side for the water techniques.
    map: u32,
    cells_per_texel: u32,
    /// How many of the quick cases.
    cases: usize,
    /// Cascaded: the camera, and the reference map side of the pool floor.
    eye: (u32, u32),
    eye_reference: u32,
    timing: Timing,
}

/// `only`: the techniques `--technique` names (a family's name takes its variants); empty, all.
pub fn run(gpu: &crate::GpuArgs, quick: bool, only: &[Spec], out: &Path) -> Result<()> {
    let s = if quick {
        Sizes {
            map: 48,
            cells_per_texel: 2,
            cases: 1,
            eye: (80, 45),
            eye_reference: 64,
            timing: Timing {
                warmup: 1,
                frames: 2,
            },
        }
    } else {
        Sizes {
            map: 256,
            cells_per_texel: 4,
            cases: 4,
            eye: (640, 360),
            eye_reference: 512,
            timing: Timing {
                warmup: 3,
                frames: 20,
            },
        }
    };
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let Some(ctx) = gpu.context()? else {
        bail!("`caustics bench --tradeoff` times techniques on the GPU: no GPU adapter");
    };
    let adapter = ctx.describe();
    let started = Instant::now();
    let mut runner = Runner::new(Some(ctx));
    let all = cases(true);
    let cases = &all[..s.cases.min(all.len())];
    // The references, once per case.
    let mut truths = Vec::new();
    let truth_spec = caustics_core::techniques::reference();
    for case in cases {
        let surface = case.water.surface_at(case.time)?;
        let scene = case_scene(case, s.map);
        let job = Job::new(&scene, Some(surface.as_ref()), s.cells_per_texel);
        truths.push(
            runner
                .run(&truth_spec, &job, &|_, _| {})?
                .map(truth_spec.name())?,
        );
    }
    let pool = pool_scene(&s);
    let mut points = Vec::new();
    let named = |name: &str| {
        only.is_empty()
            || only.iter().any(|o| {
                let family = name.strip_prefix(o.entry.name);
                family.is_some_and(|rest| rest.is_empty() || rest.starts_with('-'))
            })
    };
    for (name, settings) in sweep(quick).into_iter().filter(|(n, _)| named(n)) {
        for setting in settings {
            let text = if setting.is_empty() {
                name.to_string()
            } else {
                format!("{name}:{setting}")
            };
            let spec: Spec = text.parse()?;
            let p = if spec.entry.eye_space() {
                eye_space_point(&mut runner, &spec, &pool, &s)
            } else {
                floor_point(&mut runner, &spec, cases, &truths, &s)
            }
            .with_context(|| format!("error against cost of {text}"))?;
            println!(
                "{:<44} {:>9} rel. L1 {:6.2} %  GPU {:9.3} ms  (wall {:.3} ms)",
                text,
                p.size,
                100.0 * p.error,
                p.gpu_ms,
                p.wall_ms
            );
            points.push(p);
        }
    }
    mark_pareto(&mut points);
    let elapsed = started.elapsed().as_secs_f64();
    std::fs::write(out.join("tradeoff.csv"), csv(&points))?;
    std::fs::write(
        out.join("tradeoff.md"),
        markdown(&points, &adapter, &s, quick, elapsed),
    )?;
    plot(&points, &out.join("tradeoff.svg"), &adapter)?;
    eprintln!(
        "wrote {} ({elapsed:.0} s)",
        out.join("tradeoff.md").display()
    );
    Ok(())
}

/// The pool with the eye-space sizes of the sweep and no parameters of its own.
fn pool_scene(s: &Sizes) -> Scene {
    let mut pool = Scene::builtin("pool").expect("the built-in pool parses");
    pool.camera.width = s.eye.0;
    pool.camera.height = s.eye.1;
    pool.caustics.width = s.eye_reference;
    pool.caustics.height = s.eye_reference;
    pool.caustics.params = toml::Table::new();
    pool
}

/// A floor technique: mean relative L1 over the cases, GPU time on the first case's water.
fn floor_point(
    runner: &mut Runner,
    spec: &Spec,
    cases: &[caustics_core::cases::Case],
    truths: &[caustics_core::map::CausticsMap],
    s: &Sizes,
) -> Result<Point> {
    let mut error = 0.0;
    for (case, truth) in cases.iter().zip(truths) {
        let surface = case.water.surface_at(case.time)?;
        let scene = case_scene(case, s.map);
        let job = Job::new(&scene, Some(surface.as_ref()), s.cells_per_texel);
        let map = runner.run(spec, &job, &|_, _| {})?.map(spec.name())?;
        error += compare(&map, truth).relative_l1;
    }
    error /= cases.len() as f64;
    // The first case's scene: its water, floor and sun.
    let scene = case_scene(&cases[0], s.map);
    point(runner, spec, &scene, s, format!("{0}²", s.map), error)
}

/// An eye-space technique on the pool through its camera against the reference map read where
/// each pixel sees the floor.
fn eye_space_point(runner: &mut Runner, spec: &Spec, pool: &Scene, s: &Sizes) -> Result<Point> {
    let water = pool.water.as_ref().expect("the pool has water");
    let surface = water.surface_at(pool.time)?;
    let input = ReferenceInput::from_scene(pool, surface.as_ref())?;
    let options = ReferenceOptions {
        cells_per_texel: s.cells_per_texel.min(2),
        ..Default::default()
    };
    let map = reference(&input, &options, &|_, _| {})?;
    let out = runner.run(spec, &Job::new(pool, Some(surface.as_ref()), 1), &|_, _| {})?;
    let SceneCaustics::EyeSpace(image) = out.caustics else {
        bail!("{} made a floor map, not an eye-space image", spec.name());
    };
    let floor = caustics_core::render::eye_floor_points(pool)?;
    let (mut diff, mut total) = (0.0f64, 0.0f64);
    for (t, f) in image.texels.iter().zip(&floor) {
        let Some(f) = f else { continue };
        if t[3] < 0.0 || !t[0].is_finite() {
            continue;
        }
        if f.x < 0.0 || f.y < 0.0 || f.x > pool.size || f.y > pool.size {
            continue;
        }
        let r = map.sample(f.x, f.y, water.wrap);
        let (ours, theirs) = (
            (t[0] + t[1] + t[2]) as f64 / 3.0,
            (r[0] + r[1] + r[2]) as f64 / 3.0,
        );
        diff += (ours - theirs).abs();
        total += theirs;
    }
    if total <= 0.0 {
        bail!(
            "no pixel of the {} x {} image sees the lit floor",
            image.width,
            image.height
        );
    }
    let size = format!("{} x {}", pool.camera.width, pool.camera.height);
    point(runner, spec, pool, s, size, diff / total)
}

/// The cost of a frame: its GPU time, unless the wall time of the same submission is more than
/// twice that plus a millisecond. A real GPU's wall time is its GPU time plus a fraction of a
/// millisecond of submission and wake-up; Mesa's lavapipe under-reports passes recorded after
/// others in one command buffer (0.05 ms for a 50 ms pass), and there the wall time is the truer
/// cost.
pub fn cost(gpu_ms: f64, wall_ms: f64) -> f64 {
    if wall_ms > 2.0 * gpu_ms + 1.0 {
        wall_ms
    } else {
        gpu_ms
    }
}

/// The point of `spec` at `error`, its cost timed on `scene`.
fn point(
    runner: &Runner,
    spec: &Spec,
    scene: &Scene,
    s: &Sizes,
    size: String,
    error: f64,
) -> Result<Point> {
    let ctx = runner.gpu.as_ref().expect("a GPU runner");
    let m = time_technique(ctx, scene, spec, &s.timing)?;
    let setting = spec
        .label
        .split_once(':')
        .map_or("default".to_string(), |(_, p)| p.to_string());
    Ok(Point {
        technique: spec.name().to_string(),
        setting,
        size,
        error,
        cost_ms: cost(m.total_ms, m.wall_ms),
        gpu_ms: m.total_ms,
        wall_ms: m.wall_ms,
        pareto: false,
    })
}

/// Mark every point that no other point beats on both cost and error (at least as good on both,
/// better on one).
pub fn mark_pareto(points: &mut [Point]) {
    let flags: Vec<bool> = points
        .iter()
        .map(|p| {
            !points.iter().any(|q| {
                q.cost_ms <= p.cost_ms
                    && q.error <= p.error
                    && (q.cost_ms < p.cost_ms || q.error < p.error)
            })
        })
        .collect();
    for (p, f) in points.iter_mut().zip(flags) {
        p.pareto = f;
    }
}

fn csv(points: &[Point]) -> String {
    let mut s = "technique,setting,size,relative_l1,cost_ms,gpu_ms,wall_ms,pareto\n".to_string();
    for p in points {
        let _ = writeln!(
            s,
            "{},\"{}\",{},{:.6},{:.4},{:.4},{:.4},{}",
            p.technique, p.setting, p.size, p.error, p.cost_ms, p.gpu_ms, p.wall_ms, p.pareto
        );
    }
    s
}

fn markdown(points: &[Point], adapter: &str, s: &Sizes, quick: bool, elapsed: f64) -> String {
    let mut out = format!(
        "Generated by `caustics bench --tradeoff{}` on adapter: {adapter} ({elapsed:.0} s). Error: the \
         relative L1 against the reference (sum |technique - reference| / sum reference), the mean over \
         {} of `caustics compare --quick`'s cases at a {}² map ({} reference cells per texel). Cost: the \
         GPU time per frame of the technique alone, as `caustics bench` times it (the sum of its passes' \
         timestamp medians over {} frames, on the first case's water at the same map size); wall: submit \
         to idle of its submission, the cross-check; the cost charted is the GPU time, or the wall time \
         (in italics) where it exceeds twice the GPU time plus 1 ms: a real GPU's wall time is its GPU \
         time plus a fraction of a millisecond, while Mesa's lavapipe under-reports the timestamps of \
         passes recorded after others in one command buffer. `cascaded` makes an eye-space image: its error is \
         taken on the pool scene through a {} x {} camera, against the reference map of the pool floor \
         ({}²) read where each pixel sees the floor, over the pixels that have a value; its cost at that \
         camera size. **Pareto** (★): no other setting is both cheaper and closer to the reference.\n\n",
        if quick { " --quick" } else { "" },
        s.cases,
        s.map,
        s.cells_per_texel,
        s.timing.frames,
        s.eye.0,
        s.eye.1,
        s.eye_reference,
    );
    out += "| technique | setting | size | rel. L1 | cost (ms) | GPU (ms) | wall (ms) | Pareto |\n|---|---|---|---|---|---|---|---|\n";
    let mut sorted: Vec<&Point> = points.iter().collect();
    sorted.sort_by(|a, b| a.cost_ms.total_cmp(&b.cost_ms));
    for p in sorted {
        let cost = if p.cost_ms == p.gpu_ms {
            format!("{:.3}", p.cost_ms)
        } else {
            format!("*{:.3}*", p.cost_ms)
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.2} % | {cost} | {:.3} | {:.3} | {} |",
            p.technique,
            p.setting,
            p.size,
            100.0 * p.error,
            p.gpu_ms,
            p.wall_ms,
            if p.pareto { "★" } else { "" }
        );
    }
    out
}

fn plot(points: &[Point], path: &Path, adapter: &str) -> Result<()> {
    use plotters::prelude::*;
    let root = SVGBackend::new(path, (900, 560)).into_drawing_area();
    root.fill(&WHITE)?;
    let x = |p: &Point| p.cost_ms.max(1e-4).log10();
    let y = |p: &Point| (100.0 * p.error).max(1e-3).log10();
    let (x0, x1) = points
        .iter()
        .map(x)
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    let (y0, y1) = points
        .iter()
        .map(y)
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(v), b.max(v)));
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("error against cost: {adapter}"), ("sans-serif", 14))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d((x0 - 0.2)..(x1 + 0.2), (y0 - 0.2)..(y1 + 0.2))?;
    chart
        .configure_mesh()
        .x_desc("log10 ms per frame (GPU, or wall where timestamps fail)")
        .y_desc("log10 relative L1 (%)")
        .draw()?;
    let mut names: Vec<&str> = points.iter().map(|p| p.technique.as_str()).collect();
    names.dedup();
    for (k, t) in names.iter().enumerate() {
        let color = Palette99::pick(k).to_rgba();
        let pts: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.technique == *t)
            .map(|p| (x(p), y(p)))
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(1)))?
            .label(*t)
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, color.filled()));
        chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 4, color.filled())))?;
    }
    // The front: a staircase through the Pareto points, cheapest first, each ringed.
    let mut front: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.pareto)
        .map(|p| (x(p), y(p)))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut stairs = Vec::new();
    for (k, &(fx, fy)) in front.iter().enumerate() {
        if k > 0 {
            stairs.push((fx, front[k - 1].1));
        }
        stairs.push((fx, fy));
    }
    chart
        .draw_series(LineSeries::new(stairs, BLACK.stroke_width(2)))?
        .label("Pareto front")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], BLACK.stroke_width(2)));
    chart.draw_series(
        front
            .into_iter()
            .map(|p| Circle::new(p, 7, BLACK.stroke_width(2))),
    )?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 10))
        .border_style(BLACK)
        .background_style(WHITE.mix(0.8))
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(gpu_ms: f64, error: f64) -> Point {
        Point {
            technique: String::new(),
            setting: String::new(),
            size: String::new(),
            error,
            cost_ms: gpu_ms,
            gpu_ms,
            wall_ms: gpu_ms,
            pareto: false,
        }
    }

    /// Each parameter a descriptor flags is swept in turn (yuksel: its samples, its split and the
    /// paper's preset), the quick run taking the first two values of each.
    #[test]
    fn every_flagged_parameter_is_swept() {
        let of = |quick| {
            sweep(quick)
                .into_iter()
                .find(|(name, _)| *name == "yuksel")
                .expect("yuksel is swept")
                .1
        };
        let full = of(false);
        for s in [
            "preset=paper",
            "subsamples=1",
            "subsamples=4",
            "split=0",
            "split=0.3",
        ] {
            assert!(full.iter().any(|v| v == s), "{s} in {full:?}");
        }
        let quick = of(true);
        assert_eq!(
            quick,
            [
                "preset=paper",
                "subsamples=1",
                "subsamples=2",
                "split=0",
                "split=0.3"
            ]
        );
        // `yuksel`'s scatter and its render-target entry both; `procedural` through its variants.
        let names: Vec<&str> = sweep(false).into_iter().map(|(n, _)| n).collect();
        for n in [
            "yuksel",
            "yuksel-targets",
            "procedural-vertex",
            "procedural-texture",
        ] {
            assert!(names.contains(&n), "{n} in {names:?}");
        }
        assert!(!names.contains(&"procedural"), "{names:?}");
    }

    /// A point beaten on both counts leaves the front; a tie on one count, better on the other, too.
    #[test]
    fn the_front_keeps_only_the_unbeaten() {
        let mut pts = vec![
            p(1.0, 0.5),
            p(2.0, 0.2),
            p(3.0, 0.3),
            p(2.0, 0.25),
            p(4.0, 0.1),
        ];
        mark_pareto(&mut pts);
        let flags: Vec<bool> = pts.iter().map(|p| p.pareto).collect();
        assert_eq!(flags, [true, true, false, false, true]);
    }
}
