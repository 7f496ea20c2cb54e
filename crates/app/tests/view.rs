//! `caustics view` in a real window: under the display the environment has, else under an Xvfb
//! this test starts. Each technique renders a few frames into a screenshot that must show
//! caustics on the floor; a long scripted run switches techniques and resizes the window while its
//! resident memory must stay flat.
//!
//! Without a display and without Xvfb the tests are reported as ignored (the reason printed once),
//! unless `CAUSTICS_REQUIRE_GPU=1` (as `.ci/run` sets), when they fail: CI must not pass by
//! skipping. The file runs under libtest-mimic (`harness = false`) for that: cargo's own harness
//! can only count a test that returned early as passed.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// The viewers run one at a time: on two cores, two software-rendered windows only slow each
/// other down.
static SERIAL: Mutex<()> = Mutex::new(());

fn required() -> bool {
    std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

/// A display for the viewer: the environment's, or an Xvfb of our own (killed on drop).
struct Display {
    name: String,
    xvfb: Option<Child>,
}

impl Drop for Display {
    fn drop(&mut self) {
        if let Some(c) = self.xvfb.as_mut() {
            let _ = c.kill();
            let _ = c.wait();
        }
    }
}

fn on_path(exe: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(exe).is_file()))
}

fn display() -> Option<Display> {
    if let Some(d) = std::env::var("DISPLAY").ok().filter(|d| !d.is_empty()) {
        return Some(Display {
            name: d,
            xvfb: None,
        });
    }
    if !on_path("Xvfb") {
        let msg = "no DISPLAY and no Xvfb on PATH (apt-get install xvfb)";
        assert!(!required(), "CAUSTICS_REQUIRE_GPU=1 but {msg}");
        eprintln!("skipping the viewer test: {msg}");
        return None;
    }
    // A display number nobody holds: no lock file, no socket.
    let n = (0..200)
        .map(|k| 90 + (std::process::id() as usize + k) % 400)
        .find(|n| {
            !Path::new(&format!("/tmp/.X{n}-lock")).exists()
                && !Path::new(&format!("/tmp/.X11-unix/X{n}")).exists()
        })
        .expect("a free X display number");
    let child = Command::new("Xvfb")
        .args([
            &format!(":{n}"),
            "-screen",
            "0",
            "1024x768x24",
            "-nolisten",
            "tcp",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("Xvfb starts");
    let display = Display {
        name: format!(":{n}"),
        xvfb: Some(child),
    };
    let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
    let started = Instant::now();
    while !socket.exists() {
        assert!(
            started.elapsed() < Duration::from_secs(10),
            "Xvfb :{n} did not come up"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    Some(display)
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("caustics-view-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Run `caustics view` on `display`; `None` (the test skips) when there is no GPU adapter and
/// none is required.
fn view(display: &Display, dir: &Path, args: &[&str]) -> Option<Output> {
    let runtime = std::env::temp_dir().join(format!("caustics-xdg-{}", std::process::id()));
    std::fs::create_dir_all(&runtime).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
    }
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_caustics"));
    cmd.arg("view")
        .args(args)
        .current_dir(dir)
        .env("DISPLAY", &display.name)
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET");
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        cmd.env("XDG_RUNTIME_DIR", &runtime);
    }
    let o = cmd.output().expect("the binary runs");
    let err = String::from_utf8_lossy(&o.stderr);
    if !o.status.success() && err.contains("GPU adapter") && !required() {
        eprintln!("skipping the viewer test: {err}");
        return None;
    }
    assert!(
        o.status.success(),
        "caustics view {args:?} failed:\n{err}\n{}",
        String::from_utf8_lossy(&o.stdout)
    );
    Some(o)
}

/// The first view's rectangle (x, y, w, h) from the viewer's `screenshot:` line.
fn first_view(stdout: &str) -> [u32; 4] {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("screenshot:"))
        .expect("a screenshot line");
    let rect = line
        .split("views (x,y,w,h): ")
        .nth(1)
        .and_then(|v| v.split_whitespace().next())
        .expect("a view rectangle");
    let v: Vec<u32> = rect.split(',').map(|n| n.parse().unwrap()).collect();
    [v[0], v[1], v[2], v[3]]
}

/// Mean and standard deviation of the luminance over a box of the image.
fn luminance_stats(img: &image::RgbImage, x0: u32, y0: u32, x1: u32, y1: u32) -> (f64, f64) {
    let mut v = Vec::new();
    for y in y0..y1 {
        for x in x0..x1 {
            let p = img.get_pixel(x, y);
            v.push(0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64);
        }
    }
    let n = v.len().max(1) as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// The floor seen through the water: the lower middle of the first view.
fn floor_stats(png: &Path, view: [u32; 4]) -> (f64, f64) {
    let img = image::open(png).unwrap().to_rgb8();
    let [x, y, w, h] = view;
    luminance_stats(
        &img,
        x + w * 3 / 10,
        y + h * 55 / 100,
        x + w * 7 / 10,
        y + h * 85 / 100,
    )
}

/// The pool on a plain floor: without tiles, all the contrast on the floor is the caustics'.
fn plain_pool(dir: &Path) -> PathBuf {
    let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
        .args(["scene", "print", "pool"])
        .output()
        .unwrap();
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout)
        .unwrap()
        .replace("pattern = \"tiles\"", "pattern = \"plain\"");
    assert!(text.contains("pattern = \"plain\""));
    let path = dir.join("plain-pool.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// Every technique the registry marks implemented, and the variants the viewer offers.
fn techniques() -> Vec<String> {
    let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
        .arg("techniques")
        .output()
        .unwrap();
    let mut v: Vec<String> = String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .skip(1)
        .filter(|l| !l.contains("not yet implemented"))
        // The view shows what is made from the water: floor maps and eye-space images.
        .filter(|l| l.contains("water -> floor map") || l.contains("water -> eye space"))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .collect();
    if v.iter().any(|t| t == "yuksel") {
        v.push("yuksel-gather".into());
    }
    v
}

fn without_a_display_it_says_so_instead_of_panicking() {
    let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
        .args(["view", "--frames", "1"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("DISPLAY") && err.contains("Xvfb"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

fn every_technique_shows_caustics_in_the_window() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let Some(display) = display() else {
        return;
    };
    let dir = tmpdir("techniques");
    let scene = plain_pool(&dir);
    let scene = scene.to_str().unwrap();
    let common = [
        "--scene",
        scene,
        "--frames",
        "3",
        "--size",
        "800x480",
        "--scale",
        "0.4",
        "--map-size",
        "128",
    ];

    // Flat water: the plain floor is nearly uniform (the absorption and the Fresnel term vary a
    // little across it), which is what the caustics must beat by a wide margin.
    let flat_png = dir.join("flat.png");
    let mut args = common.to_vec();
    args.extend([
        "--amplitude",
        "0",
        "--screenshot",
        flat_png.to_str().unwrap(),
    ]);
    let Some(o) = view(&display, &dir, &args) else {
        return;
    };
    let flat = floor_stats(&flat_png, first_view(&String::from_utf8_lossy(&o.stdout)));
    eprintln!("flat water: floor luminance {:.1} ± {:.2}", flat.0, flat.1);

    for t in techniques() {
        let png = dir.join(format!("{t}.png"));
        let mut args = common.to_vec();
        // Paper 2's pattern is sparse (the 0.84° sun halo), and its default blend over the lit
        // ground halves it; the bare lookup shows whether the view draws the technique's pattern.
        let spec = if t == "procedural" {
            "procedural:ground=0".to_string()
        } else {
            t.clone()
        };
        args.extend(["--technique", &spec, "--screenshot", png.to_str().unwrap()]);
        let started = Instant::now();
        let Some(o) = view(&display, &dir, &args) else {
            return;
        };
        let stdout = String::from_utf8_lossy(&o.stdout);
        let stderr = String::from_utf8_lossy(&o.stderr);
        if let Some(e) = stderr.lines().find(|l| l.starts_with("technique `")) {
            panic!("{t}: `caustics techniques` lists it as implemented, but running it says: {e}");
        }
        let img = image::open(&png).unwrap().to_rgb8();
        assert_eq!(img.dimensions(), (800, 480), "{t}: the whole window");
        let (_, whole) = luminance_stats(&img, 0, 0, 800, 480);
        assert!(
            whole > 10.0,
            "{t}: the window is blank (luminance sd {whole:.2})"
        );
        let (mean, sd) = floor_stats(&png, first_view(&stdout));
        eprintln!(
            "{t}: floor luminance {mean:.1} ± {sd:.2} in {:.1} s; {}",
            started.elapsed().as_secs_f64(),
            stdout
                .lines()
                .find(|l| l.starts_with("frames:"))
                .unwrap_or("")
        );
        assert!(mean > 20.0, "{t}: the floor is black ({mean:.1})");
        assert!(
            sd > 10.0 && sd > 2.0 * flat.1,
            "{t}: no caustics on the floor: luminance sd {sd:.2} (flat water {:.2})",
            flat.1
        );
    }
}

/// The frame is GPU-resident: for every GPU technique, the steady frames of a run with moving
/// water create no GPU resource, read nothing back, and upload at most a few uniforms.
fn every_gpu_technique_runs_without_creating_or_reading_back() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let Some(display) = display() else {
        return;
    };
    let dir = tmpdir("traffic");
    let mut names: Vec<String> = techniques()
        .into_iter()
        .filter(|t| t != "reference")
        .collect();
    names.extend(
        [
            "procedural-vertex",
            "procedural-screen",
            "procedural-texture",
        ]
        .map(String::from),
    );
    for t in names {
        let Some(o) = view(
            &display,
            &dir,
            &[
                "--technique",
                &t,
                "--frames",
                "40",
                "--size",
                "640x360",
                "--scale",
                "0.25",
                "--map-size",
                "64",
                "--report-traffic",
            ],
        ) else {
            return;
        };
        let stdout = String::from_utf8_lossy(&o.stdout);
        let line = stdout
            .lines()
            .find(|l| l.starts_with("traffic "))
            .unwrap_or_else(|| panic!("{t}: no traffic line in\n{stdout}"));
        eprintln!("{line}");
        let number = |after: &str| -> f64 {
            line.split(after)
                .nth(1)
                .and_then(|v| v.split([' ', ',']).next())
                .and_then(|v| v.parse().ok())
                .unwrap_or_else(|| panic!("{t}: no `{after}` in {line}"))
        };
        assert!(
            line.starts_with(&format!("traffic {t}")) && line.ends_with("(frames 11 to 40)"),
            "{line}"
        );
        assert_eq!(number("created "), 0.0, "{line}");
        assert_eq!(number("readbacks "), 0.0, "{line}");
        assert!(number("uploaded ") <= 4096.0, "{line}");
    }
}

fn ripples_split_view_and_windows_run() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let Some(display) = display() else {
        return;
    };
    let dir = tmpdir("ripples");
    let png = dir.join("ripples.png");
    // The pool with its walls off: yuksel maps the floor only, so the reference's floor holds all
    // the light only when no wall takes a share.
    let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
        .args(["scene", "print", "pool"])
        .output()
        .unwrap();
    let text = String::from_utf8(o.stdout).unwrap();
    let floor_only = text.replace("walls = true", "walls = false");
    assert_ne!(text, floor_only);
    std::fs::write(dir.join("pool.toml"), floor_only).unwrap();
    let Some(o) = view(
        &display,
        &dir,
        &[
            "--scene",
            "pool.toml",
            "--frames",
            "12",
            "--size",
            "900x500",
            "--scale",
            "0.25",
            "--map-size",
            "64",
            "--technique",
            "yuksel",
            "--compare",
            "reference",
            "--ripple",
            "--drop-every",
            "4",
            "--show-map",
            "--show-buffers",
            "--screenshot",
            png.to_str().unwrap(),
        ],
    ) else {
        return;
    };
    let stdout = String::from_utf8_lossy(&o.stdout);
    // Two views side by side.
    let line = stdout
        .lines()
        .find(|l| l.starts_with("screenshot:"))
        .unwrap();
    assert_eq!(
        line.split("views (x,y,w,h): ")
            .nth(1)
            .unwrap()
            .split_whitespace()
            .count(),
        2
    );
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (900, 500));
    // Both maps are of the same rippled water (the GPU simulation, the reference reading it back):
    // the rings focus the light in both, and yuksel's flux is the reference's.
    let map = |name: &str| -> (f64, f64) {
        let line = stdout
            .lines()
            .find(|l| l.starts_with(&format!("map {name}:")))
            .unwrap_or_else(|| panic!("no map line for {name} in\n{stdout}"));
        let number = |after: &str| -> f64 {
            line.split(after)
                .nth(1)
                .and_then(|v| v.split([',', ' ']).next())
                .and_then(|v| v.parse().ok())
                .unwrap_or_else(|| panic!("no `{after}` in {line}"))
        };
        (number("mean "), number("max "))
    };
    let (yuksel, reference) = (map("yuksel"), map("reference"));
    eprintln!("maps: yuksel {yuksel:?}, reference {reference:?}");
    // Measured: peaks 1.77 (yuksel) and 1.81 (reference), against 0.91 through flat water.
    assert!(
        yuksel.1 > 1.2 && reference.1 > 1.2,
        "no ring focuses the light: {yuksel:?} {reference:?}"
    );
    // Measured: means 0.9117 and 0.9118 (1.1e-4 apart).
    assert!(
        (yuksel.0 / reference.0 - 1.0).abs() < 1.1e-3,
        "the maps' flux differs: yuksel {yuksel:?}, reference {reference:?}"
    );
}

fn switching_and_resizing_for_hundreds_of_frames_keeps_memory_flat() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let Some(display) = display() else {
        return;
    };
    let dir = tmpdir("memory");
    let frames = 300;
    let png = dir.join("last.png");
    // The water stands still: on lavapipe (Mesa 22.3) every GPU technique run grows the process
    // by 0.3 to 2 MB inside the driver's command execution, whoever calls it (`caustics bench
    // --frames 500` shows it without the viewer), and by 4.5 MB for `cascaded` (its water
    // G-buffer and photon passes; the same frame run twice grows it twice as much). With still
    // water each floor-map technique runs once and its map is reused, so what this run measures
    // is the viewer's own: technique and split switches every frame, a re-traced image every
    // frame, a new swap chain every 40 frames. An eye-space technique (`cascaded`) is made for the
    // view, so every resize and split runs it again by design: it cycles in the run after this
    // one, which checks that switching and resizing with it works, not the driver's memory.
    let floor_maps: Vec<String> = techniques()
        .into_iter()
        .filter(|t| !eye_space_techniques().contains(t))
        .collect();
    let cycle = floor_maps.join(",");
    let Some(o) = view(
        &display,
        &dir,
        &[
            "--frames",
            &frames.to_string(),
            "--size",
            "560x360",
            "--scale",
            "0.2",
            "--map-size",
            "64",
            "--paused",
            "--cycle-techniques",
            &cycle,
            "--resize-every",
            "40",
            "--report-memory",
            // The techniques' maps read back and the image traced on the CPU: the GPU frame
            // re-runs the techniques and the image pass on every switch, and Mesa 22.3's lavapipe
            // grows the process by each execution (above); this run measures the viewer's own.
            "--final-image",
            "cpu",
            "--screenshot",
            png.to_str().unwrap(),
        ],
    ) else {
        return;
    };
    let stdout = String::from_utf8_lossy(&o.stdout);
    let rss = |frame: u64| -> u64 {
        let tag = format!("memory: frame {frame} VmRSS ");
        stdout
            .lines()
            .find_map(|l| l.strip_prefix(tag.as_str()))
            .and_then(|v| v.trim_end_matches(" kB").parse().ok())
            .unwrap_or_else(|| panic!("no memory line for frame {frame} in\n{stdout}"))
    };
    let (early, late) = (rss(50), rss(frames));
    let growth = late as f64 / early as f64 - 1.0;
    eprintln!(
        "VmRSS {early} kB at frame 50, {late} kB at frame {frames} ({:+.1} %); {}",
        growth * 100.0,
        stdout
            .lines()
            .find(|l| l.starts_with("frames:"))
            .unwrap_or("")
    );
    assert!(
        growth < 0.2,
        "resident memory grew {:.1} % from frame 50 to {frames}",
        growth * 100.0
    );

    // Every technique, eye-space ones included, switched every frame and resized every 10.
    let png = dir.join("all.png");
    let Some(o) = view(
        &display,
        &dir,
        &[
            "--frames",
            "60",
            "--size",
            "560x360",
            "--scale",
            "0.2",
            "--map-size",
            "64",
            "--paused",
            "--cycle-techniques",
            "--resize-every",
            "10",
            "--screenshot",
            png.to_str().unwrap(),
        ],
    ) else {
        return;
    };
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.lines().any(|l| l.starts_with("technique `")),
        "a technique failed while cycling:\n{stderr}"
    );
    assert!(image::open(&png).is_ok());
}

/// The techniques `caustics techniques` lists as computing caustics in eye space.
fn eye_space_techniques() -> Vec<String> {
    let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
        .arg("techniques")
        .output()
        .unwrap();
    String::from_utf8(o.stdout)
        .unwrap()
        .lines()
        .filter(|l| l.contains("water -> eye space"))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .collect()
}

/// The `glass` scene has no water: the picker offers the techniques whose generators are its glass
/// objects, and `caustic-triangles` beside the glass reference runs with its buffer view open.
fn the_glass_scene_runs_caustic_triangles_beside_its_reference() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let Some(display) = display() else {
        return;
    };
    let dir = tmpdir("glass");
    let png = dir.join("glass.png");
    let Some(o) = view(
        &display,
        &dir,
        &[
            "--scene",
            "glass",
            "--technique",
            "caustic-triangles:photon_image=64,cube_resolution=64,light_cube=64",
            "--compare",
            "reference",
            "--frames",
            "3",
            "--size",
            "800x480",
            "--scale",
            "0.3",
            "--map-size",
            "96",
            "--show-map",
            "--show-buffers",
            "--screenshot",
            png.to_str().unwrap(),
        ],
    ) else {
        return;
    };
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.lines().any(|l| l.starts_with("technique `")),
        "a technique failed on the glass scene:\n{stderr}"
    );
    let img = image::open(&png).unwrap().to_rgb8();
    let (_, whole) = luminance_stats(&img, 0, 0, 800, 480);
    assert!(
        whole > 10.0,
        "the window is blank (luminance sd {whole:.2})"
    );
}

/// Whether the viewer can get a display here: the environment's, or an Xvfb this file starts.
fn display_possible() -> bool {
    std::env::var("DISPLAY").is_ok_and(|d| !d.is_empty()) || on_path("Xvfb")
}

fn main() -> std::process::ExitCode {
    use libtest_mimic::{Arguments, Trial};
    let args = Arguments::from_args();
    let ignore = !display_possible() && !required();
    if ignore {
        eprintln!("viewer tests ignored: no DISPLAY and no Xvfb on PATH (apt-get install xvfb)");
    }
    let windowed: [(&str, fn()); 5] = [
        (
            "every_technique_shows_caustics_in_the_window",
            every_technique_shows_caustics_in_the_window,
        ),
        (
            "every_gpu_technique_runs_without_creating_or_reading_back",
            every_gpu_technique_runs_without_creating_or_reading_back,
        ),
        (
            "ripples_split_view_and_windows_run",
            ripples_split_view_and_windows_run,
        ),
        (
            "switching_and_resizing_for_hundreds_of_frames_keeps_memory_flat",
            switching_and_resizing_for_hundreds_of_frames_keeps_memory_flat,
        ),
        (
            "the_glass_scene_runs_caustic_triangles_beside_its_reference",
            the_glass_scene_runs_caustic_triangles_beside_its_reference,
        ),
    ];
    let mut trials = vec![Trial::test(
        "without_a_display_it_says_so_instead_of_panicking",
        || {
            without_a_display_it_says_so_instead_of_panicking();
            Ok(())
        },
    )];
    for (name, body) in windowed {
        trials.push(
            Trial::test(name, move || {
                body();
                Ok(())
            })
            .with_ignored_flag(ignore),
        );
    }
    libtest_mimic::run(&args, trials).exit_code()
}
