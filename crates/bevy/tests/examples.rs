//! The examples as a user runs them, in a real window: under the environment's display, else under
//! an Xvfb this test starts, on whatever adapter Bevy finds (lavapipe in CI). From their
//! screenshots: caustic contrast on the pool's floor against the same pool with still water, and
//! two frames that differ; from their output: steady frames that create nothing and read nothing
//! back inside Bevy.
//!
//! Without a display and without Xvfb the windowed tests are reported as ignored (the reason
//! printed), unless `CAUSTICS_REQUIRE_GPU=1` (as `.ci/run` sets), when they fail. The file runs
//! under libtest-mimic (`harness = false`) for that: cargo's harness counts a test that returned
//! early as passed.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::Duration;

use libtest_mimic::{Arguments, Failed, Trial};

/// One example window at a time: on two cores two software-rendered windows slow each other.
static SERIAL: Mutex<()> = Mutex::new(());

fn on_path(exe: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(exe).is_file()))
}

/// The display the examples open their windows on: the environment's, or an Xvfb started once
/// (left to die with the test process's group when it ends).
fn display() -> &'static str {
    static DISPLAY: OnceLock<(String, Option<Mutex<Child>>)> = OnceLock::new();
    &DISPLAY
        .get_or_init(|| {
            if let Some(d) = std::env::var("DISPLAY").ok().filter(|d| !d.is_empty()) {
                return (d, None);
            }
            // `-displayfd 1`: Xvfb writes its display number once it accepts connections.
            let mut child = Command::new("Xvfb")
                .args([
                    "-displayfd",
                    "1",
                    "-screen",
                    "0",
                    "1280x800x24",
                    "-nolisten",
                    "tcp",
                ])
                .stdout(Stdio::piped())
                .stderr(Stdio::null())
                .spawn()
                .expect("Xvfb starts");
            let stdout = child.stdout.take().expect("piped");
            let (tx, rx) = std::sync::mpsc::channel();
            std::thread::spawn(move || {
                let mut line = String::new();
                let _ =
                    std::io::BufRead::read_line(&mut std::io::BufReader::new(stdout), &mut line);
                let _ = tx.send(line);
            });
            let line = rx
                .recv_timeout(Duration::from_secs(10))
                .expect("Xvfb did not come up within 10 s");
            let n: u32 = line
                .trim()
                .parse()
                .unwrap_or_else(|_| panic!("Xvfb wrote `{line}` for its display number"));
            (format!(":{n}"), Some(Mutex::new(child)))
        })
        .0
}

/// The examples' binaries, next to this test's (`target/<profile>/examples/`).
fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target/<profile>/deps")
        .join("examples")
        .join(name)
}

fn tmpdir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("bevy-caustics-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(name: &str, args: &[&str]) -> Output {
    let _one = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut cmd = Command::new(example(name));
    cmd.args(args)
        .env("DISPLAY", display())
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET");
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        let runtime =
            std::env::temp_dir().join(format!("bevy-caustics-xdg-{}", std::process::id()));
        std::fs::create_dir_all(&runtime).unwrap();
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
        cmd.env("XDG_RUNTIME_DIR", &runtime);
    }
    cmd.output().expect("the example runs")
}

/// Run `name` for `frames` frames into a screenshot: its pixels (RGB) and its stdout.
fn shot(name: &str, frames: u32, extra: &[&str]) -> Result<(image::RgbImage, String), Failed> {
    let path = tmpdir().join(format!("{name}-{frames}-{}.png", extra.join("")));
    let frames = frames.to_string();
    let mut args = vec!["--frames", &frames, "--screenshot", path.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = run(name, &args);
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&o.stderr);
    // A debug build's wgpu asks for the Khronos validation layer (installed in CI) and logs each
    // of its messages through wgpu_hal as `VALIDATION [id ...]`: any one fails the example, but
    // for two that say only that Debian 12's layer is older than wgpu 30 (a device feature
    // structure it does not know; naga's WGSL source-language id in the SPIR-V's debug info).
    const OLDER_LAYER: [&str; 2] = [
        "VALIDATION [VUID-VkDeviceCreateInfo-pNext-pNext ",
        "VALIDATION [UNASSIGNED-CoreValidation-Shader-InconsistentSpirv ",
    ];
    if let Some(line) = [&*stdout, &*stderr]
        .iter()
        .flat_map(|out| out.lines())
        .find(|l| l.contains("VALIDATION [") && !OLDER_LAYER.iter().any(|m| l.contains(m)))
    {
        return Err(format!("{name} {args:?}: the validation layer reported: {line}").into());
    }
    if !o.status.success() {
        return Err(format!(
            "{name} {args:?} failed ({}):\n{}\n{stdout}",
            o.status, stderr
        )
        .into());
    }
    let img = image::open(&path)
        .map_err(|e| format!("{}: {e}", path.display()))?
        .to_rgb8();
    if img.pixels().all(|p| p.0 == [0, 0, 0]) {
        return Err(format!("{name} {args:?}: the screenshot is black").into());
    }
    Ok((img, stdout))
}

/// Luminance (0-255) of the pixels in the window `[x0, x1) x [y0, y1)`, given as fractions of
/// the image's size.
fn luminance(img: &image::RgbImage, x: (f32, f32), y: (f32, f32)) -> Vec<f64> {
    let (w, h) = (img.width() as f32, img.height() as f32);
    let mut v = Vec::new();
    for j in (y.0 * h) as u32..(y.1 * h) as u32 {
        for i in (x.0 * w) as u32..(x.1 * w) as u32 {
            let p = img.get_pixel(i, j).0;
            v.push(0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64);
        }
    }
    v
}

/// Standard deviation over mean.
fn contrast(v: &[f64]) -> f64 {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
    var.sqrt() / mean.max(1e-9)
}

/// The window of the pool example's picture that shows only the pool's floor.
const FLOOR: Window = ((0.40, 0.62), (0.55, 0.75));

/// The window of the ocean example's picture that shows only the sandy bed in front of the camera.
const SAND: Window = ((0.20, 0.80), (0.62, 0.95));

/// The reef example's picture: open sand in front of the camera, the flank of the rock behind the
/// crate, and the sand under the slab's end that juts out (the overhang), in its shade.
const REEF_SAND: Window = ((0.55, 0.85), (0.75, 0.95));
const REEF_ROCK: Window = ((0.52, 0.58), (0.34, 0.42));
const REEF_SHADE: Window = ((0.335, 0.37), (0.57, 0.60));

/// An example's caustics in `window`: its luminance divided, pixel by pixel, by the same scene's
/// with still water (which takes the surfaces' own pattern out), as standard deviation over mean,
/// at least `min_contrast`; frames `at.0` and `at.1` differing by at least 1 of 255 on average; and
/// steady frames that create and read back nothing.
fn contrast_and_motion(
    name: &str,
    window: Window,
    at: (u32, u32),
    min_contrast: f64,
) -> Result<(), Failed> {
    let shots = Shots::take(name, at)?;
    shots.caustics(name, window, min_contrast)?;
    steady_traffic(&shots.out)
}

/// A window of a picture, as fractions of its width and height.
type Window = ((f32, f32), (f32, f32));

/// An example's frame `at.0` with still water and frames `at.0` and `at.1` with moving water, and
/// what it printed.
struct Shots {
    flat: image::RgbImage,
    a: image::RgbImage,
    b: image::RgbImage,
    at: (u32, u32),
    out: String,
}

impl Shots {
    fn take(name: &str, at: (u32, u32)) -> Result<Self, Failed> {
        let (flat, _) = shot(name, at.0, &["--flat"])?;
        let (a, out) = shot(name, at.0, &[])?;
        let (b, _) = shot(name, at.1, &[])?;
        Ok(Shots {
            flat,
            a,
            b,
            at,
            out,
        })
    }

    /// Window `w`'s luminance in the still frame and the two moving ones.
    fn windows(&self, w: Window) -> [Vec<f64>; 3] {
        [&self.flat, &self.a, &self.b].map(|img| luminance(img, w.0, w.1))
    }

    /// The caustic contrast (against still water) and the mean change between the two frames in
    /// `w`.
    fn measure(&self, w: Window) -> (f64, f64) {
        let [still, la, lb] = self.windows(w);
        let ratio: Vec<f64> = la.iter().zip(&still).map(|(x, s)| x / s.max(1.0)).collect();
        let moved = la.iter().zip(&lb).map(|(x, y)| (x - y).abs()).sum::<f64>() / la.len() as f64;
        (contrast(&ratio), moved)
    }

    /// Caustics in `w`: contrast at least `min_contrast`, and frames that differ by at least 1 of
    /// 255 on average.
    fn caustics(&self, name: &str, w: Window, min_contrast: f64) -> Result<(), Failed> {
        let (c, moved) = self.measure(w);
        println!(
            "{name}: caustic contrast {c:.4} (the surfaces alone: {:.4}); mean change between \
             frames {} and {}: {moved:.2} of 255",
            contrast(&self.windows(w)[0]),
            self.at.0,
            self.at.1
        );
        if c < min_contrast {
            return Err(format!("{name}: no caustics: contrast {c:.4} against still water").into());
        }
        if moved < 1.0 {
            return Err(format!(
                "{name}: the caustics did not move: mean change {moved:.3} of 255"
            )
            .into());
        }
        Ok(())
    }
}

/// Measured on lavapipe (the clock stepped 1/15 s a frame): contrast 0.039 at frame 15 (still
/// water gives 0 here); frames 15 and 25 differ by 5.3 of 255.
fn pool_contrast_and_motion() -> Result<(), Failed> {
    contrast_and_motion("pool", FLOOR, (15, 25), 0.02)
}

/// Paper 5's cascaded image from Bevy's camera on the FFT ocean's beach. Measured on lavapipe:
/// contrast 0.156 at frame 5; frames 5 and 8 differ by 25.1 of 255.
fn ocean_contrast_and_motion() -> Result<(), Failed> {
    contrast_and_motion("ocean", SAND, (5, 8), 0.05)
}

/// The application's own meshes as receivers: caustics on the sea bed and on a rock's flank, none
/// in the overhang's shade. Measured on lavapipe (yuksel, 256² maps, the clock stepped 1/15 s a
/// frame, the water's surface drawn): contrast 0.104 on the sand and 0.079 on the rock at frame 15,
/// frames 15 and 25 differing by 11.6 and 12.8 of 255 there; in the shade a luminance 0.32 of the
/// sand's, changing by 0.80 of 255 between the frames.
fn reef_receivers() -> Result<(), Failed> {
    let shots = Shots::take("reef", (15, 25))?;
    shots.caustics("reef sand", REEF_SAND, 0.05)?;
    shots.caustics("reef rock", REEF_ROCK, 0.04)?;
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let sand = mean(&shots.windows(REEF_SAND)[1]);
    let shade = mean(&shots.windows(REEF_SHADE)[1]);
    let (_, moved) = shots.measure(REEF_SHADE);
    println!(
        "reef shade: luminance {:.3} of the sand's, mean change {moved:.2} of 255",
        shade / sand
    );
    if shade > 0.45 * sand || moved > 2.0 {
        return Err(format!(
            "reef: light under the overhang: luminance {:.3} of the sand's, change {moved:.2}",
            shade / sand
        )
        .into());
    }
    steady_traffic(&shots.out)
}

/// The example's count line: steady frames must have happened, and created and read back nothing.
fn steady_traffic(out: &str) -> Result<(), Failed> {
    let line = out
        .lines()
        .find(|l| l.starts_with("bevy_caustics:"))
        .ok_or(format!("no count line in\n{out}"))?;
    println!("{line}");
    let number = |after: &str| -> Result<u64, Failed> {
        line.split(after)
            .nth(1)
            .and_then(|v| v.split([' ', ',', ';']).next())
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| format!("no `{after}` count in `{line}`").into())
    };
    let steady = number("frames, ")?;
    if steady < 1 {
        return Err(format!("only {steady} steady frames: `{line}`").into());
    }
    let (created, readbacks) = (number("created ")?, number("readbacks ")?);
    if created != 0 || readbacks != 0 {
        return Err(
            format!("steady frames created {created}, read back {readbacks}: `{line}`").into(),
        );
    }
    if line.contains("error:") {
        return Err(format!("the plugin reported an error: `{line}`").into());
    }
    Ok(())
}

fn pool_refuses_bad_input() -> Result<(), Failed> {
    for (args, expect) in [
        (&["--technique", "nope"][..], "technique `nope`"),
        (&["--frames", "0"][..], "positive count"),
        (&["--screenshot", "x.png"][..], "needs --frames"),
        (
            &["--frames", "3", "--screenshot", "x.jpg"][..],
            "writes a PNG",
        ),
    ] {
        let o = Command::new(example("pool")).args(args).output()?;
        let err = String::from_utf8_lossy(&o.stderr);
        if o.status.success() || !err.contains(expect) || err.contains("panicked") {
            return Err(format!("pool {args:?}: {} and `{err}`", o.status).into());
        }
    }
    Ok(())
}

fn main() {
    let args = Arguments::from_args();
    let windowed = std::env::var("DISPLAY").is_ok_and(|d| !d.is_empty()) || on_path("Xvfb");
    let required = std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1");
    if !windowed && !required {
        eprintln!("no DISPLAY and no Xvfb: the windowed tests are ignored");
    }
    let window = |name: &'static str, f: fn() -> Result<(), Failed>| {
        Trial::test(name, f).with_ignored_flag(!windowed && !required)
    };
    let trials = vec![
        window("pool_contrast_and_motion", pool_contrast_and_motion),
        window("ocean_contrast_and_motion", ocean_contrast_and_motion),
        window("reef_receivers", reef_receivers),
        Trial::test("pool_refuses_bad_input", pool_refuses_bad_input),
    ];
    libtest_mimic::run(&args, trials).exit();
}
