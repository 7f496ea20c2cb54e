//! `caustics`: render scenes, inspect scene files, list the techniques.

mod bake;
mod bench;
mod compare;
#[cfg(test)]
mod fuzz_spec;
mod progress;
mod render;
mod techniques;
mod tradeoff;
mod view;

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Args, Parser, Subcommand};

use caustics_core::scene::{BUILTIN_SCENES, Scene};
use caustics_core::techniques::REGISTRY;
use caustics_core::techniques::describe::ParamDefault;

#[derive(Parser)]
#[command(
    name = "caustics",
    version,
    about = "Real-time water caustics: five published techniques, a physically based reference, and the tools to compare them"
)]
struct Cli {
    /// More logging (-v info, -vv debug); RUST_LOG overrides.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    #[command(subcommand)]
    command: Option<Command>,
}

/// What `caustics` alone prints: where to start.
const START: &str = "\
caustics: real-time water caustics, five published techniques and a physically based reference.

Try first:
  caustics render              the pool from its camera, lit by its technique, into pool.png
  caustics view                the same in a window: move the sun, the camera and the water
  caustics techniques          the techniques, their papers and their parameters
  caustics scene list          the built-in scenes (render --scene NAME, or a .toml file)

Every command: caustics --help; one command's options: caustics help render.";

#[derive(Subcommand)]
enum Command {
    /// Render a scene: the final image from its camera and/or the raw caustics map.
    Render(render::RenderArgs),
    /// Bake a caustics texture sequence that tiles and loops, for any engine: frames, a flipbook
    /// atlas and a looping preview (docs/bake.md).
    Bake(bake::BakeArgs),
    /// List the caustics techniques.
    Techniques {
        /// Print only the names of the GPU techniques and variants as registered
        /// (`yuksel-targets`, `procedural-vertex`, ...), one a line, for scripts.
        #[arg(long)]
        gpu_names: bool,
        /// Print docs/techniques.md's table of techniques (Markdown), made from the registry.
        #[arg(long, conflicts_with = "gpu_names")]
        markdown: bool,
    },
    /// Every technique against the reference on generated surfaces: Markdown, CSV, pictures.
    Compare(compare::CompareArgs),
    /// Every technique and the whole frame timed (GPU per pass, wall, memory), or with --tradeoff
    /// error against cost with the Pareto front: Markdown, CSV, a plot.
    Bench(bench::BenchArgs),
    /// An interactive window: any scene, any technique, beside another, with the sun, the water and
    /// ripples under the mouse (needs a display; under Xvfb for headless runs).
    View(view::ViewArgs),
    /// Scene files: check one, list the built-in ones, or print one as TOML.
    #[command(subcommand)]
    Scene(SceneCommand),
    /// Print the completion script for a shell: bash, zsh, fish, elvish or powershell (e.g.
    /// `caustics completions bash > ~/.local/share/bash-completion/completions/caustics`).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
}

#[derive(Subcommand)]
enum SceneCommand {
    /// Load and validate a scene file (or a built-in scene's name) and summarise it.
    Check(SceneArg),
    /// List the built-in scenes.
    List,
    /// Print a scene as TOML (a built-in one is a starting point for your own).
    Print(SceneArg),
}

#[derive(Args)]
struct SceneArg {
    /// A scene file (.toml) or a built-in scene name.
    scene: String,
}

/// Mesa's drivers (lavapipe among them) print an `error:` line when `XDG_RUNTIME_DIR` is unset,
/// which reads like a failure of ours; give them a private one, as a desktop session would.
fn ensure_runtime_dir() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some() {
        return;
    }
    let user = std::env::var("USER").unwrap_or_else(|_| "user".into());
    let dir = std::env::temp_dir().join(format!("caustics-runtime-{user}"));
    if std::fs::create_dir_all(&dir).is_ok() {
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let _ = std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700));
        }
        // SAFETY: called first thing in `main`, before any other thread exists.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}

/// Crates that log through the `log` crate, which the `tracing-log` bridge (installed by `init`)
/// turns into tracing events. wgpu's and naga's info level is a line per resource and pass, so
/// they stay at warn under `-v`; under `-vv` they say everything.
const CHATTY: [&str; 4] = ["wgpu_core", "wgpu_hal", "wgpu", "naga"];

/// Our log: `-v` info, `-vv` debug, warnings otherwise; `rust_log` (RUST_LOG) replaces it all.
fn subscriber<W>(verbose: u8, rust_log: Option<String>, writer: W) -> impl tracing::Subscriber
where
    W: for<'w> tracing_subscriber::fmt::MakeWriter<'w> + Send + Sync + 'static,
{
    let filter = match rust_log {
        Some(directives) => tracing_subscriber::EnvFilter::new(directives),
        None => {
            let (level, chatty) = match verbose {
                0 => ("warn", "warn"),
                1 => ("info", "warn"),
                _ => ("debug", "debug"),
            };
            let quiet: Vec<String> = CHATTY.iter().map(|t| format!("{t}={chatty}")).collect();
            tracing_subscriber::EnvFilter::new(format!("{level},{}", quiet.join(",")))
        }
    };
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(writer)
        .finish()
}

/// A reader that stops early (`caustics techniques | head`) ends the output quietly, as it does
/// any Unix tool's, rather than making `println!` panic on the broken pipe (Rust ignores SIGPIPE).
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in `main`, before any other thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> ExitCode {
    restore_sigpipe();
    ensure_runtime_dir();
    let cli = Cli::parse();
    use tracing_subscriber::util::SubscriberInitExt;
    subscriber(cli.verbose, std::env::var("RUST_LOG").ok(), std::io::stderr).init();
    let result = run(cli);
    // With CAUSTICS_VALIDATION=1, any message of the Vulkan validation layer fails the command, even
    // one the command recovered from (a GPU render that fell back to the CPU) or one given when the
    // device was destroyed.
    let messages = caustics_gpu::validation::all_messages();
    if let Some(first) = messages.first() {
        // Each was logged as it came; this names the first again where the command ends.
        eprintln!(
            "error: the Vulkan validation layer reported {} message(s), the first: {first}",
            messages.len()
        );
    }
    match result {
        Ok(()) if messages.is_empty() => ExitCode::SUCCESS,
        Ok(()) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    let Some(command) = cli.command else {
        println!("{START}");
        return Ok(());
    };
    match command {
        Command::Completions { shell } => {
            use clap::CommandFactory;
            clap_complete::generate(
                shell,
                &mut Cli::command(),
                "caustics",
                &mut std::io::stdout(),
            );
            Ok(())
        }
        Command::Render(args) => render::run(args),
        Command::Bake(args) => bake::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Bench(args) if args.tradeoff => {
            tradeoff::run(&args.gpu, args.quick, &args.techniques, &args.out)
        }
        Command::Bench(args) => bench::run(args),
        Command::View(args) => view::run(args),
        Command::Techniques {
            gpu_names: true, ..
        } => {
            for r in caustics_gpu::registry::REGISTRY {
                println!("{}", r.name());
            }
            Ok(())
        }
        Command::Techniques { markdown: true, .. } => {
            print!("{}", markdown_table());
            Ok(())
        }
        Command::Techniques { .. } => {
            println!(
                "{:<20} {:<6} {:<28} description",
                "technique", "paper", "input -> output"
            );
            for t in REGISTRY {
                let status = match (caustics_gpu::registry::find(t.name), t.floor_only()) {
                    (None, _) => " [CPU only]",
                    (Some(_), true) => " [floor only: no light on a pool's walls]",
                    (Some(_), false) => "",
                };
                println!(
                    "{:<20} {:<6} {:<28} {}{}",
                    t.name,
                    t.paper,
                    t.input.describe(),
                    t.summary,
                    status
                );
                for p in t.params {
                    let unit = if p.unit.is_empty() {
                        String::new()
                    } else {
                        format!(" {}", p.unit)
                    };
                    println!("{:<20}   {} = {}{unit}: {}", "", p.key, p.default, p.doc);
                }
            }
            Ok(())
        }
        Command::Scene(SceneCommand::List) => {
            for (name, text) in BUILTIN_SCENES {
                let about = text.lines().next().unwrap_or("").trim_start_matches("# ");
                println!("{name:<10} {about}");
            }
            Ok(())
        }
        Command::Scene(SceneCommand::Print(arg)) => {
            // A built-in scene as written, comments included; a file as read, checked first so
            // that what is printed is a scene that loads.
            match BUILTIN_SCENES.iter().find(|(n, _)| *n == arg.scene) {
                Some((_, text)) => print!("{text}"),
                None => {
                    Scene::load_or_builtin(&arg.scene)?;
                    let text = std::fs::read_to_string(&arg.scene)
                        .with_context(|| format!("cannot read {}", arg.scene))?;
                    print!("{text}");
                }
            }
            Ok(())
        }
        Command::Scene(SceneCommand::Check(arg)) => {
            let scene = Scene::load_or_builtin(&arg.scene)?;
            println!("{}", summary(&scene));
            println!("ok");
            Ok(())
        }
    }
}

fn summary(scene: &Scene) -> String {
    let mut s = format!("scene `{}`\n", scene.name);
    match &scene.water {
        Some(w) => {
            use caustics_core::scene::WaterSource as W;
            let source = match &w.source {
                W::Flat => "flat".to_string(),
                W::Waves(v) => format!("{} sine waves", v.len()),
                W::Procedural(p) => format!("paper 2 wave function, {} octaves", p.octaves),
                W::Ocean(_) => "FFT ocean".to_string(),
                W::Ripple(r) => format!("ripple simulation {0} x {0}", r.resolution),
                W::HeightField(g) => format!("height field {} x {}", g.cols, g.rows),
            };
            s += &format!(
                "  water: {source}; square {} x {}, depth {}, ior {}, {}, absorption {:?}\n",
                w.size,
                w.size,
                w.depth,
                w.ior,
                if w.wrap { "periodic" } else { "clamped" },
                w.absorption.to_array()
            );
        }
        None => s += "  water: none\n",
    }
    s += &format!(
        "  floor: {}\n",
        match &scene.floor.terrain {
            Some(t) => format!("terrain {} x {}", t.cols, t.rows),
            None => "plane z = 0".into(),
        }
    );
    s += &format!("  objects: {}\n", scene.objects.len());
    let d = scene.light.direction;
    s += &format!(
        "  sun: direction ({:.3}, {:.3}, {:.3}), elevation {:.1} degrees\n",
        d.x,
        d.y,
        d.z,
        (-d.z).asin().to_degrees()
    );
    s += &format!(
        "  caustics: {} at {} x {}\n",
        scene.caustics.technique, scene.caustics.width, scene.caustics.height
    );
    s += &format!(
        "  camera: {} x {}, fov {} degrees",
        scene.camera.width, scene.camera.height, scene.camera.fov_y
    );
    s
}

/// `WIDTHxHEIGHT`, exactly two whole numbers, each within `sides`: the one spelling of a size on
/// the command line (render's, the viewer's window, bake's frames).
pub(crate) fn parse_size_within(
    s: &str,
    sides: std::ops::RangeInclusive<u32>,
) -> Result<[u32; 2], String> {
    let parts: Vec<&str> = s.split(['x', 'X']).collect();
    let [w, h] = parts[..] else {
        return Err(format!(
            "expected WIDTHxHEIGHT (two numbers), got `{s}` ({} entries)",
            parts.len()
        ));
    };
    let side = |what: &str, v: &str| match v.trim().parse::<u32>() {
        Ok(n) if sides.contains(&n) => Ok(n),
        Ok(_) => Err(format!(
            "`{s}`: each side must be a whole number from {} to {}",
            sides.start(),
            sides.end()
        )),
        Err(_) => Err(format!("bad {what} in `{s}`")),
    };
    Ok([side("width", w)?, side("height", h)?])
}

/// A caustics map's size on the command line (`--map-size`): `N` for N x N texels, or
/// `WIDTHxHEIGHT`. The ranges are checked where the size is used, naming the flag and the limit.
pub(crate) fn parse_map_size(s: &str) -> Result<[u32; 2], String> {
    match s.trim().parse::<u32>() {
        Ok(n) => Ok([n, n]),
        Err(_) if s.contains(['x', 'X']) => parse_size_within(s, 0..=u32::MAX),
        Err(_) => Err(format!(
            "expected N (N x N texels) or WIDTHxHEIGHT, got `{s}`"
        )),
    }
}

/// The reference's triangulation cells per map texel along each axis, the same default and range
/// in every command that runs it.
pub(crate) const CELLS_PER_TEXEL: u32 = 4;
pub(crate) const CELLS_PER_TEXEL_RANGE: std::ops::RangeInclusive<i64> = 1..=16;
/// Samples per pixel along each axis of a final image, in every command that traces one.
pub(crate) const SUPERSAMPLING_RANGE: std::ops::RangeInclusive<i64> = 1..=16;

/// How to choose the GPU, shared by the commands that use one.
#[derive(Args, Clone, Debug)]
pub(crate) struct GpuArgs {
    /// Run the techniques' CPU twins and the CPU final image even where a GPU adapter exists.
    #[arg(long, conflicts_with_all = ["backend", "adapter"])]
    pub(crate) cpu: bool,
    /// GPU backend: vulkan, metal, dx12 or gl (comma-separated list allowed; default:
    /// WGPU_BACKEND, else any).
    #[arg(long, value_parser = backend_arg)]
    backend: Option<String>,
    /// The GPU adapter whose name contains this (case-insensitive; default: WGPU_ADAPTER_NAME,
    /// else the high-performance one).
    #[arg(long)]
    adapter: Option<String>,
}

impl GpuArgs {
    /// The adapter asked for, as the device is made from it.
    pub(crate) fn options(&self) -> caustics_gpu::GpuOptions {
        caustics_gpu::GpuOptions {
            backend: self.backend.clone(),
            adapter_name: self.adapter.clone(),
        }
    }

    /// The GPU device, or `None` with `--cpu` or (after one line on stderr saying why) where no
    /// adapter can be had here and none was asked for: the techniques then run on their CPU twins.
    /// A `--backend` or `--adapter` that cannot be had is an error, never the CPU in its place.
    pub(crate) fn context(&self) -> Result<Option<caustics_gpu::GpuContext>> {
        use caustics_gpu::{GpuContext, GpuError};
        if self.cpu {
            return Ok(None);
        }
        let ctx = match GpuContext::headless(&self.options()) {
            Ok(ctx) => ctx,
            // A backend list `backend_arg` let through, or CAUSTICS_VALIDATION=1 without the
            // layer: the user's to mend, not a reason to fall back.
            Err(e @ GpuError::BadOption(_)) => return Err(e.into()),
            Err(e) if self.backend.is_some() || self.adapter.is_some() => {
                let asked = [("--backend", &self.backend), ("--adapter", &self.adapter)]
                    .iter()
                    .filter_map(|(flag, v)| v.as_ref().map(|v| format!("{flag} {v}")))
                    .collect::<Vec<_>>()
                    .join(" ");
                return Err(anyhow::anyhow!("{asked}: no such GPU adapter here ({e})"));
            }
            Err(e) => {
                let reason = match e {
                    GpuError::NoAdapter { wanted, seen } if seen.is_empty() => {
                        format!("wanted {wanted}; none present")
                    }
                    GpuError::NoAdapter { wanted, seen } => {
                        format!("wanted {wanted}; present: {}", seen.join(", "))
                    }
                    other => other.to_string(),
                };
                eprintln!("no GPU adapter ({reason}): using the CPU path");
                return Ok(None);
            }
        };
        // A software adapter (lavapipe, WARP) runs the passes on the CPU's cores: say so.
        let hint = if caustics_gpu::final_image::FinalImage::software_adapter(&ctx) {
            " (a software adapter)"
        } else {
            ""
        };
        eprintln!("GPU: {}{hint}", ctx.describe());
        Ok(Some(ctx))
    }
}

/// `--backend`'s value, checked as the device will read it, so that a misspelt backend is refused
/// by the parser rather than found when (or whether) a command makes its device.
pub(crate) fn backend_arg(s: &str) -> Result<String, String> {
    caustics_gpu::parse_backends(s)
        .map(|_| s.to_string())
        .map_err(|e| e.to_string())
}

/// Write 8-bit RGB pixels as the image file `path` names (PNG).
pub(crate) fn save_rgb(path: &std::path::Path, rgb: &[u8], width: u32, height: u32) -> Result<()> {
    image::save_buffer(path, rgb, width, height, image::ExtendedColorType::Rgb8)
        .with_context(|| format!("cannot write {}", path.display()))
}

/// Where outputs go unless told otherwise.
pub(crate) fn default_output(scene: &str) -> PathBuf {
    let stem = std::path::Path::new(scene)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    PathBuf::from(format!("{stem}.png"))
}

/// docs/techniques.md's table of techniques, made from the registry (`caustics techniques
/// --markdown`; a test keeps the copy current). Its links are relative to docs/.
fn markdown_table() -> String {
    let mut s = String::from(
        "| technique | paper | reads -> makes | maps | parameters (default) | documentation |\n|---|---|---|---|---|---|\n",
    );
    for d in REGISTRY {
        let params: Vec<String> = d
            .params
            .iter()
            .map(|p| match p.default {
                ParamDefault::Auto(_) => format!("`{}` (auto)", p.key),
                other => format!("`{}` ({other})", p.key),
            })
            .collect();
        let page = d.docs.strip_prefix("docs/").unwrap_or(d.docs);
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | [{}]({}) |",
            d.name,
            d.paper,
            d.input.describe(),
            d.receivers
                .iter()
                .map(|r| r.name())
                .collect::<Vec<_>>()
                .join(", "),
            if params.is_empty() {
                "-".to_string()
            } else {
                params.join(", ")
            },
            page,
            page
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use std::sync::{Arc, Mutex};

    use tracing_subscriber::util::SubscriberInitExt;

    /// What the subscriber writes, kept for the test to read.
    #[derive(Clone, Default)]
    struct Captured(Arc<Mutex<Vec<u8>>>);

    impl std::io::Write for Captured {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(buf);
            Ok(buf.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    impl<'w> tracing_subscriber::fmt::MakeWriter<'w> for Captured {
        type Writer = Captured;
        fn make_writer(&'w self) -> Captured {
            self.clone()
        }
    }

    /// The only test here that installs the process-wide subscriber (and with it the `log`
    /// bridge), as `main` does.
    #[test]
    fn log_records_reach_the_output_and_wgpu_info_stays_quiet_under_v() {
        let out = Captured::default();
        super::subscriber(1, None, out.clone())
            .try_init()
            .expect("no other test installs a subscriber");
        log::warn!(target: "wgpu_hal::vulkan::instance", "a warning from wgpu");
        log::info!(target: "wgpu_core::device::resource", "a resource from wgpu");
        log::info!(target: "naga::front::wgsl", "a parse from naga");
        tracing::info!("our own info");
        let text = String::from_utf8(out.0.lock().unwrap().clone()).unwrap();
        assert!(text.contains("a warning from wgpu"), "{text}");
        assert!(text.contains("wgpu_hal::vulkan::instance"), "{text}");
        assert!(text.contains("our own info"), "{text}");
        assert!(!text.contains("a resource from wgpu"), "{text}");
        assert!(!text.contains("a parse from naga"), "{text}");
    }
}
