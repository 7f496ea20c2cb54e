//! `caustics compare`: every technique against the reference on the generated cases of
//! `caustics_core::cases`, with the metrics of `caustics_core::metrics`; writes Markdown, CSV and
//! pictures (technique | reference | difference, with a colour bar).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use image::{Rgb, RgbImage};

use caustics_core::cases::{Case, RECEIVERS, cases, receiver_cases};
use caustics_core::map::CausticsMap;
use caustics_core::metrics::{Metrics, compare, compare_grids};
use caustics_core::walls::WallMaps;

use crate::progress;
use caustics_core::glam::DVec3;
use caustics_core::scene::{Camera, CausticsSettings, Light, Look, Scene};

use crate::techniques::{Job, Runner, Spec};

#[derive(Args)]
pub struct CompareArgs {
    /// Techniques to measure, `name` or `name:key=value,...` (e.g. `yuksel:n=15,m=14`,
    /// `yuksel-targets`); repeat the flag. Default: every registered technique that makes a floor
    /// map (`caustics bench --tradeoff` scores the eye-space `cascaded`).
    #[arg(long = "technique")]
    techniques: Vec<Spec>,
    /// The caustics map's sizes, N (N x N texels; the cases' maps are square), comma-separated.
    /// Default 256 (with --quick 64).
    #[arg(long, value_delimiter = ',', value_parser = crate::parse_map_size, value_name = "N")]
    map_size: Vec<[u32; 2]>,
    /// Small: only the mid sun over deep water, a 64² map unless --map-size says otherwise.
    #[arg(long)]
    quick: bool,
    /// Output folder.
    #[arg(long, default_value = "compare")]
    out: PathBuf,
    /// Reference quality: triangulation cells per map texel along each axis (1 to 16).
    #[arg(long, default_value_t = crate::CELLS_PER_TEXEL,
          value_parser = clap::value_parser!(u32).range(crate::CELLS_PER_TEXEL_RANGE))]
    cells_per_texel: u32,
    /// Write a picture for every row (by default only for the first map size).
    #[arg(long)]
    all_pictures: bool,
    /// Only these cases (comma-separated names, e.g. `waves-mid-deep`) get pictures; default: all.
    #[arg(long, value_delimiter = ',')]
    picture_cases: Vec<String>,
    /// The receivers instead of the surfaces: one water over a flat floor, a sand bar, rocks and
    /// the pool's walls, and a table technique x receiver.
    #[arg(long)]
    receivers: bool,
    #[command(flatten)]
    gpu: crate::GpuArgs,
}

pub struct Row {
    pub case: String,
    pub technique: String,
    pub resolution: u32,
    pub backend: &'static str,
    pub metrics: Metrics,
    pub picture: Option<String>,
    pub diff_range: f32,
}

pub fn run(mut args: CompareArgs) -> Result<()> {
    if args.map_size.is_empty() {
        let n = if args.quick { 64 } else { 256 };
        args.map_size = vec![[n, n]];
    }
    let specs = if args.techniques.is_empty() {
        default_specs()?
    } else {
        args.techniques.clone()
    };
    for &[w, h] in &args.map_size {
        if w != h {
            anyhow::bail!("--map-size {w}x{h}: the cases' maps are square; give one side");
        }
        if w == 0 || w > 8192 {
            anyhow::bail!("--map-size {w}: must be between 1 and 8192");
        }
    }
    let map_sides: Vec<u32> = args.map_size.iter().map(|[n, _]| *n).collect();
    let mut runner = Runner::new(args.gpu.context()?);
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let adapter = runner
        .gpu
        .as_ref()
        .map_or("none (CPU twins)".to_string(), |c| c.describe());
    let cases = if args.receivers {
        receiver_cases()
    } else {
        cases(args.quick)
    };
    let bar = progress::bar("compare");
    bar.set_length((cases.len() * map_sides.len()) as u64);
    let mut rows = Vec::new();
    for case in &cases {
        let surface = case.water.surface_at(case.time)?;
        for (k, &res) in map_sides.iter().enumerate() {
            let mut scene = case_scene(case, res);
            scene.objects = case.objects.clone();
            let job = Job::new(&scene, Some(surface.as_ref()), args.cells_per_texel);
            let truth = runner.run(&caustics_core::techniques::reference(), &job, &|_, _| {})?;
            let truth_walls = truth.walls.as_ref().map(stacked);
            let truth = truth.map(caustics_core::techniques::reference().name())?;
            for spec in &specs {
                let out = runner
                    .run(spec, &job, &|_, _| {})
                    .with_context(|| format!("{} on {}", spec.label, case.name))?;
                let backend = out.backend;
                let row = |case: String, metrics, picture, diff_range| Row {
                    case,
                    technique: spec.label.clone(),
                    resolution: res,
                    backend,
                    metrics,
                    picture,
                    diff_range,
                };
                if let (Some(walls), Some(truth)) = (&out.walls, &truth_walls) {
                    let metrics = compare_grids(&stacked(walls), truth);
                    rows.push(row(format!("{}:walls", case.name), metrics, None, 0.0));
                }
                let map = out.map(spec.name())?;
                let metrics = compare(&map, &truth);
                let wanted =
                    args.picture_cases.is_empty() || args.picture_cases.contains(&case.name);
                let (picture, diff_range) = if wanted && (k == 0 || args.all_pictures) {
                    let name = format!("{}-{}-{}.png", case.name, file_safe(&spec.label), res);
                    let range = write_triptych(&args.out.join(&name), &map, &truth)?;
                    (Some(name), range)
                } else {
                    (None, 0.0)
                };
                rows.push(row(case.name.clone(), metrics, picture, diff_range));
            }
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    std::fs::write(args.out.join("compare.csv"), csv(&rows))?;
    std::fs::write(
        args.out.join("compare.md"),
        markdown(&rows, &cases, &adapter, &args),
    )?;
    eprintln!(
        "wrote {} ({} rows)",
        args.out.join("compare.md").display(),
        rows.len()
    );
    Ok(())
}

/// A case as a scene of water alone over its floor under its sun, with a square map of side
/// `res`: no objects, a camera looking down at the square.
pub(crate) fn case_scene(case: &Case, res: u32) -> Scene {
    let size = case.water.size;
    Scene {
        name: case.name.clone(),
        water: Some(case.water.clone()),
        light: Light {
            direction: case.light.normalize(),
            color: DVec3::ONE,
            intensity: 1.0,
            position: None,
            cone: None,
        },
        caustics: CausticsSettings {
            width: res,
            height: res,
            technique: caustics_core::techniques::reference().name().to_string(),
            params: toml::Table::new(),
        },
        floor: case.floor.clone(),
        objects: Vec::new(),
        camera: Camera {
            position: DVec3::new(0.5 * size, -0.6 * size, case.water.depth + 1.2 * size),
            target: DVec3::new(0.5 * size, 0.5 * size, 0.0),
            fov_y: 45.0,
            width: 640,
            height: 360,
        },
        look: Look::default(),
        time: case.time,
        size,
    }
}

/// Every registered GPU technique that makes a floor map from the water, in the registry's order
/// (on its CPU twin where no adapter exists). `cascaded` makes an eye-space
/// image, which these floor cases cannot score: `caustics bench --tradeoff` measures it through
/// the pool's camera.
fn default_specs() -> Result<Vec<Spec>> {
    caustics_gpu::registry::REGISTRY
        .iter()
        .filter(|r| !r.describe.eye_space())
        .map(|r| Ok(r.name().parse()?))
        .collect()
}

/// The walls' maps one above the other (mean channel), to be measured as one map.
fn stacked(walls: &WallMaps) -> caustics_core::grid::Grid {
    let cols = walls.maps[0].cols;
    let data = walls
        .maps
        .iter()
        .flat_map(|m| {
            assert_eq!(m.cols, cols, "square floor maps give walls of one width");
            m.texels.iter().map(|t| (t[0] + t[1] + t[2]) / 3.0)
        })
        .collect::<Vec<f32>>();
    caustics_core::grid::Grid {
        cols,
        rows: data.len() / cols,
        data,
    }
}

/// Relative L1 per technique (rows) and receiver (columns) of the receivers' cases.
fn receivers_table(rows: &[Row]) -> String {
    let mut s = String::from("## Technique x receiver (relative L1)\n\n| technique |");
    let mut columns: Vec<String> = RECEIVERS.iter().map(|r| format!("receivers-{r}")).collect();
    columns.push("receivers-walls:walls".into());
    for c in &columns {
        let label = match c.trim_start_matches("receivers-") {
            "walls" => "floor (walls on)",
            label => label,
        };
        let _ = write!(s, " {label} |");
    }
    s += "\n|---|";
    s += &"---|".repeat(columns.len());
    s += "\n";
    let mut techniques: Vec<&str> = Vec::new();
    for r in rows {
        if !techniques.contains(&r.technique.as_str()) {
            techniques.push(&r.technique);
        }
    }
    for t in techniques {
        let _ = write!(s, "| {t} |");
        for c in &columns {
            match rows.iter().find(|r| r.technique == t && &r.case == c) {
                Some(r) => {
                    let _ = write!(s, " {:.2} % |", 100.0 * r.metrics.relative_l1);
                }
                None => s += " - |",
            }
        }
        s += "\n";
    }
    s += "\nThe same water (`waves-mid-deep`) over each receiver; `walls:walls` is the four walls' maps \
          measured as one, `-` where a technique lights no walls.\n\n";
    s
}

fn file_safe(s: &str) -> String {
    s.replace(|c: char| !(c.is_ascii_alphanumeric() || c == '-'), "_")
}

pub fn csv(rows: &[Row]) -> String {
    let mut s =
        "case,technique,resolution,backend,relative_l1,relative_rmse,flux_error,ssim\n".to_string();
    for r in rows {
        let m = &r.metrics;
        let _ = writeln!(
            s,
            "{},\"{}\",{},{},{:.6},{:.6},{:.6},{:.6}",
            r.case,
            r.technique,
            r.resolution,
            r.backend,
            m.relative_l1,
            m.relative_rmse,
            m.flux_error,
            m.ssim
        );
    }
    s
}

fn markdown(rows: &[Row], cases: &[Case], adapter: &str, args: &CompareArgs) -> String {
    let mut s = String::from("# Techniques against the reference\n\n");
    let join = |v: Vec<String>| v.join(", ");
    let what = if args.receivers {
        format!(
            "one water over each receiver ({})",
            join(RECEIVERS.iter().map(|r| r.to_string()).collect())
        )
    } else {
        format!(
            "water kinds x suns (zenith angle {} degrees) x depths ({} on the unit square)",
            join(
                caustics_core::cases::SUNS
                    .iter()
                    .map(|(_, z)| format!("{z}"))
                    .collect()
            ),
            join(
                caustics_core::cases::DEPTHS
                    .iter()
                    .map(|(_, d)| format!("{d}"))
                    .collect()
            ),
        )
    };
    let flag = match (args.quick, args.receivers) {
        (_, true) => " --receivers",
        (true, false) => " --quick",
        (false, false) => "",
    };
    let _ = writeln!(
        s,
        "Generated by `caustics compare{flag}` on adapter: {adapter}. The reference uses {} \
         triangulation cells per texel. {} cases: {what}.\n",
        args.cells_per_texel,
        cases.len(),
    );
    s += "- **rel. L1**: sum |technique - reference| / sum reference: the share of the light misplaced or lost.\n";
    s += "- **rel. RMSE**: root mean square difference over the mean irradiance.\n";
    s += "- **flux**: total light of the map over the reference's, minus 1 (negative: light lost).\n";
    s += "- **SSIM**: structural similarity of the tone-mapped maps (1 = identical).\n\n";
    if args.receivers {
        s += &receivers_table(rows);
    }
    // Means per technique and resolution.
    s += "## Summary (mean over cases)\n\n| technique | resolution | rel. L1 | rel. RMSE | flux | SSIM |\n|---|---|---|---|---|---|\n";
    let mut keys: Vec<(String, u32)> = rows
        .iter()
        .map(|r| (r.technique.clone(), r.resolution))
        .collect();
    keys.sort();
    keys.dedup();
    for (t, res) in keys {
        let sel: Vec<&Row> = rows
            .iter()
            .filter(|r| r.technique == t && r.resolution == res)
            .collect();
        let n = sel.len() as f64;
        let mean = |f: fn(&Metrics) -> f64| sel.iter().map(|r| f(&r.metrics)).sum::<f64>() / n;
        let _ = writeln!(
            s,
            "| {t} | {res} | {:.2} % | {:.2} % | {:+.2} % | {:.3} |",
            100.0 * mean(|m| m.relative_l1),
            100.0 * mean(|m| m.relative_rmse),
            100.0 * mean(|m| m.flux_error),
            mean(|m| m.ssim)
        );
    }
    s += "\n## Every case\n\n| case | technique | resolution | backend | rel. L1 | rel. RMSE | flux | SSIM | picture |\n|---|---|---|---|---|---|---|---|---|\n";
    for r in rows {
        let m = &r.metrics;
        let pic = r.picture.as_ref().map_or(String::new(), |p| {
            format!("[png]({p}) (difference ±{:.2})", r.diff_range)
        });
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.2} % | {:.2} % | {:+.2} % | {:.3} | {pic} |",
            r.case,
            r.technique,
            r.resolution,
            r.backend,
            100.0 * m.relative_l1,
            100.0 * m.relative_rmse,
            100.0 * m.flux_error,
            m.ssim
        );
    }
    s += "\nPictures: technique | reference | difference (blue: technique darker, red: brighter, scaled to \
          the 99th percentile of |difference|, given beside each link), with the colour bar at the right. \
          Maps are tone-mapped as E / (1 + E): flat water is mid-grey.\n";
    s
}

/// Technique | reference | difference, and a colour bar. Returns the difference range shown.
pub fn write_triptych(
    path: &Path,
    technique: &CausticsMap,
    reference: &CausticsMap,
) -> Result<f32> {
    let a = technique.mean_channel();
    let r = reference.mean_channel();
    let (w, h) = (a.cols as u32, a.rows as u32);
    let gap = 4;
    let bar = 12;
    let mut img = RgbImage::from_pixel(3 * w + 3 * gap + bar, h, Rgb([255, 255, 255]));
    let mut diffs: Vec<f32> = a
        .data
        .iter()
        .zip(&r.data)
        .map(|(x, y)| (x - y).abs())
        .collect();
    diffs.sort_by(f32::total_cmp);
    let range = diffs[((diffs.len() - 1) as f32 * 0.99) as usize].max(1e-6);
    let grey = |e: f32| {
        let v = (e.max(0.0) / (1.0 + e.max(0.0)) * 255.0) as u8;
        Rgb([v, v, v])
    };
    for i in 0..h {
        for j in 0..w {
            // Row 0 of a map is y = 0: draw it at the bottom, as seen from above.
            let y = h - 1 - i;
            let k = (i * w + j) as usize;
            img.put_pixel(j, y, grey(a.data[k]));
            img.put_pixel(w + gap + j, y, grey(r.data[k]));
            img.put_pixel(
                2 * (w + gap) + j,
                y,
                diverging((a.data[k] - r.data[k]) / range),
            );
        }
    }
    for y in 0..h {
        let v = 1.0 - 2.0 * y as f32 / (h - 1).max(1) as f32;
        for x in 0..bar {
            img.put_pixel(3 * (w + gap) + x, y, diverging(v));
        }
    }
    img.save(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(range)
}

/// Blue (−1) through white (0) to red (+1).
fn diverging(v: f32) -> Rgb<u8> {
    let v = v.clamp(-1.0, 1.0);
    let t = 1.0 - v.abs();
    let strong = 255.0 * t;
    if v >= 0.0 {
        Rgb([255, strong as u8, strong as u8])
    } else {
        Rgb([strong as u8, strong as u8, 255])
    }
}
