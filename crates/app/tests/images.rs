//! Image tests: every built-in scene's final image, as `caustics render` draws it with the scene's
//! own technique on the GPU path, against a stored reference picture, by NVIDIA's FLIP metric
//! (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images", through the
//! `nv-flip` crate: the per-pixel perceived difference in [0, 1] at 67 pixels per degree, i.e. a
//! 0.7 m wide monitor seen from 0.7 m), as wgpu's own image tests do. The scenes come from
//! `BUILTIN_SCENES`, so a new built-in scene gets its test by being added there (and failing until
//! its reference is blessed).
//!
//! Each scene is drawn small (256 x 144, one sample per pixel, a 128 x 128 caustics map from the
//! reference at 2 cells per texel) to stay fast on lavapipe.
//!
//! - The references live in `tests/images/NAME.png`. A missing one fails the test and says how to
//!   make it.
//! - `CAUSTICS_BLESS=1 cargo test --release -p caustics --test images` (re)writes every reference
//!   from this machine's render instead of comparing. Look at the pictures before committing them.
//! - On failure the test writes `tests/images/NAME-actual.png` (this run's picture) and
//!   `tests/images/NAME-difference.png` (the FLIP error map, magma colour map: black agrees,
//!   yellow differs), which git ignores.
//!
//! The bound on the mean FLIP ([`MEAN_FLIP`]) is set from the difference between the GPU's picture
//! and the CPU twin's (`--cpu`) of the same scene, the largest legitimate departure a reference
//! made elsewhere may show; the numbers are beside it.

use std::path::{Path, PathBuf};
use std::process::Command;

use caustics_core::scene::BUILTIN_SCENES;

/// Mean FLIP a picture may depart from its reference by. Measured on lavapipe (Mesa 25.0.7), the
/// CPU twins' pictures (`CAUSTICS_IMAGES_CPU=1`) against the GPU's references, with the daylight
/// sky and the caustics and floor filtered over each sample's footprint (docs/maintainers/look.md): pool
/// 0.00456, objects 0.00443, shore 0.00015, glass 0.00008 (f32 against f64 where a caustic line or
/// a grazing ray falls on one side of a pixel or the other); the GPU against itself, run to run: 0
/// (the same bytes). The bound is 2.2 times the largest, so that a reference blessed on another GPU
/// or on the CPU path passes; the reef's CPU picture departs by 0.00813 (its swell's caustic bands
/// on the rocks' flanks, 1.2 times under the bound); not the underwater scene's, whose
/// CPU picture departs by 0.0236, in the mirror of total internal reflection (the same with the
/// sun's disk taken out). A visibly wrong picture fails (`a_visibly_wrong_picture_fails`): the
/// pool 10 % brighter gives 0.109, the glass scene without its ball 0.0383.
const MEAN_FLIP: f32 = 0.01;

fn images_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/images")
}

fn required() -> bool {
    std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

/// The scene's final image as `caustics render` writes it (RGB8), and whether the GPU drew it.
fn render(scene: &str, out: &Path, extra: &[&str]) -> (image::RgbImage, bool) {
    let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
        .args([
            "render",
            "--scene",
            scene,
            "--image-size",
            "256x144",
            "--map-size",
            "128x128",
            "--cells-per-texel",
            "2",
            "--supersampling",
            "1",
            "--final-image",
            "gpu",
            "--out",
        ])
        .arg(out)
        .args(extra)
        .output()
        .expect("the binary runs");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "caustics render {scene}: {stderr}");
    let on_gpu = stderr
        .lines()
        .any(|l| l.starts_with("wrote") && l.contains("on the GPU"));
    let img = image::open(out).expect("the rendered PNG").to_rgb8();
    (img, on_gpu)
}

/// The FLIP error map of `actual` against `reference`, and its mean.
fn flip(reference: &image::RgbImage, actual: &image::RgbImage) -> (nv_flip::FlipImageFloat, f32) {
    let (w, h) = reference.dimensions();
    let r = nv_flip::FlipImageRgb8::with_data(w, h, reference.as_raw());
    let a = nv_flip::FlipImageRgb8::with_data(w, h, actual.as_raw());
    let map = nv_flip::flip(r, a, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    let mean = nv_flip::FlipPool::from_image(&map).mean();
    (map, mean)
}

fn check(scene: &str) -> Result<(), String> {
    let dir = images_dir();
    let reference_path = dir.join(format!("{scene}.png"));
    let actual_path = dir.join(format!("{scene}-actual.png"));
    let difference_path = dir.join(format!("{scene}-difference.png"));
    let tmp = std::env::temp_dir().join(format!(
        "caustics-images-{scene}-{}.png",
        std::process::id()
    ));
    let cpu = std::env::var("CAUSTICS_IMAGES_CPU").is_ok_and(|v| v == "1");
    let (actual, on_gpu) = render(scene, &tmp, if cpu { &["--cpu"] } else { &[] });
    let _ = std::fs::remove_file(&tmp);
    if required() && !on_gpu && !cpu {
        return Err(format!(
            "{scene}: CAUSTICS_REQUIRE_GPU=1 but the final image was not drawn on the GPU"
        ));
    }
    if std::env::var("CAUSTICS_BLESS").is_ok_and(|v| v == "1") {
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        actual.save(&reference_path).map_err(|e| e.to_string())?;
        eprintln!("{scene}: blessed {}", reference_path.display());
        return Ok(());
    }
    let Ok(reference) = image::open(&reference_path) else {
        actual.save(&actual_path).map_err(|e| e.to_string())?;
        return Err(format!(
            "{scene}: no reference picture at {} (this run's is at {}); look at it, then make the \
             reference with CAUSTICS_BLESS=1 cargo test --release -p caustics --test images",
            reference_path.display(),
            actual_path.display()
        ));
    };
    let reference = reference.to_rgb8();
    if reference.dimensions() != actual.dimensions() {
        actual.save(&actual_path).map_err(|e| e.to_string())?;
        return Err(format!(
            "{scene}: the reference is {:?} but the render is {:?}; bless it again \
             (CAUSTICS_BLESS=1)",
            reference.dimensions(),
            actual.dimensions()
        ));
    }
    let (map, mean) = flip(&reference, &actual);
    eprintln!(
        "{scene}: mean FLIP {mean:.5} against {} (bound {MEAN_FLIP}), on the {}",
        reference_path.display(),
        if on_gpu { "GPU" } else { "CPU" }
    );
    if mean > MEAN_FLIP {
        actual.save(&actual_path).map_err(|e| e.to_string())?;
        let colours = map.apply_color_lut(&nv_flip::magma_lut());
        image::RgbImage::from_raw(colours.width(), colours.height(), colours.to_vec())
            .expect("the error map's size")
            .save(&difference_path)
            .map_err(|e| e.to_string())?;
        return Err(format!(
            "{scene}: mean FLIP {mean:.5} above {MEAN_FLIP}; this run's picture: {}, the error \
             map: {}",
            actual_path.display(),
            difference_path.display()
        ));
    }
    let _ = std::fs::remove_file(&actual_path);
    let _ = std::fs::remove_file(&difference_path);
    Ok(())
}

/// The bound catches what a user would see as wrong: the pool 10 % brighter (its scene's exposure
/// times 1.1), and the glass scene without its ball, each against the right scene's reference.
fn a_visibly_wrong_picture_fails() -> Result<(), String> {
    let dir = images_dir();
    let tmp = std::env::temp_dir().join(format!("caustics-images-wrong-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).map_err(|e| e.to_string())?;
    let exposure = caustics_core::scene::Scene::builtin("pool")
        .map_err(|e| e.to_string())?
        .look
        .exposure;
    let brighter = format!("{}", exposure * 1.1);
    let (pool, _) = render("pool", &tmp.join("pool.png"), &["--exposure", &brighter]);
    let glass = BUILTIN_SCENES
        .iter()
        .find(|(n, _)| *n == "glass")
        .map(|(_, t)| *t)
        .ok_or("no built-in glass scene")?;
    // The first object of the glass scene is its ball.
    let start = glass.find("[[objects]]").ok_or("glass has no objects")?;
    let end = start
        + 1
        + glass[start + 1..]
            .find("[[objects]]")
            .ok_or("one object only")?;
    assert!(
        glass[start..end].contains("sphere"),
        "the first object is the ball"
    );
    let without_ball = tmp.join("glass.toml");
    std::fs::write(
        &without_ball,
        format!("{}{}", &glass[..start], &glass[end..]),
    )
    .map_err(|e| e.to_string())?;
    let (no_ball, _) = render(
        without_ball.to_str().ok_or("temp path")?,
        &tmp.join("glass.png"),
        &[],
    );
    let _ = std::fs::remove_dir_all(&tmp);
    for (scene, wrong) in [("pool", pool), ("glass", no_ball)] {
        let Ok(reference) = image::open(dir.join(format!("{scene}.png"))) else {
            return Err(format!("{scene}: no reference picture (see check)"));
        };
        let (_, mean) = flip(&reference.to_rgb8(), &wrong);
        eprintln!("{scene}, made wrong: mean FLIP {mean:.5} (bound {MEAN_FLIP})");
        if mean <= MEAN_FLIP {
            return Err(format!(
                "{scene}, made visibly wrong, passes: mean FLIP {mean:.5} <= {MEAN_FLIP}"
            ));
        }
    }
    Ok(())
}

fn main() -> std::process::ExitCode {
    use libtest_mimic::{Arguments, Trial};
    let args = Arguments::from_args();
    let trials = BUILTIN_SCENES
        .iter()
        .map(|(name, _)| {
            let name = name.to_string();
            Trial::test(format!("{name}_matches_its_reference_picture"), move || {
                check(&name).map_err(Into::into)
            })
        })
        .chain([Trial::test("a_visibly_wrong_picture_fails", || {
            a_visibly_wrong_picture_fails().map_err(Into::into)
        })])
        .collect();
    libtest_mimic::run(&args, trials).exit_code()
}
