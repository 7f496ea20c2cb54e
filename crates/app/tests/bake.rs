//! `caustics bake` as a user runs it: the files it writes and their encoding, the loop's last step
//! like any other, pieces of a bake assembled as a whole one, water that cannot loop refused, bad
//! arguments named, and nothing of an earlier bake replaced without `--force`. (The frames'
//! physics, tiling, loop and flux are tested on the CPU twin in `caustics_core::bake` and on the GPU
//! in `caustics-gpu`'s `bake_gpu`.)

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn caustics(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_caustics"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("caustics-bake-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `caustics bake` into `out`: 4 frames of 32², a 2 s loop, unless `extra` says otherwise.
fn bake(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["bake", "--out", out.to_str().unwrap()];
    for (flag, value) in [
        ("--frames", "4"),
        ("--map-size", "32x32"),
        ("--period", "2"),
    ] {
        if !extra.contains(&flag) {
            args.extend([flag, value]);
        }
    }
    args.extend(extra);
    caustics(&args)
}

fn read_npy(path: &Path) -> (Vec<u64>, Vec<f32>) {
    let bytes = std::fs::read(path).unwrap();
    let npy = npyz::NpyFile::new(&bytes[..]).unwrap();
    let shape = npy.shape().to_vec();
    (shape, npy.into_vec::<f32>().unwrap())
}

#[test]
fn a_bake_writes_its_frames_atlas_preview_and_record() {
    let dir = tmpdir("files");
    let o = bake(&dir, &["--npy"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("baked 4 frames of 32 x 32"), "{err}");
    for k in 0..4 {
        let png = image::open(dir.join(format!("frame-{k:04}.png"))).unwrap();
        assert_eq!(png.color(), image::ColorType::L16, "16-bit grey");
        assert_eq!((png.width(), png.height()), (32, 32));
    }
    let atlas = image::open(dir.join("atlas.png")).unwrap();
    assert_eq!((atlas.width(), atlas.height()), (64, 64), "2 x 2 frames");
    assert_eq!(atlas.color(), image::ColorType::L16);
    // An animated PNG: its `acTL` chunk says 4 frames, played forever.
    let apng = std::fs::read(dir.join("preview.apng")).unwrap();
    let at = apng
        .windows(4)
        .position(|w| w == b"acTL")
        .expect("an acTL chunk");
    assert_eq!(&apng[at + 4..at + 12], &[0, 0, 0, 4, 0, 0, 0, 0]);
    let record: toml::Table = std::fs::read_to_string(dir.join("bake.toml"))
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(record["technique"].as_str(), Some("reference"));
    assert_eq!(record["frames"].as_integer(), Some(4));
    // The frames as PNG codes: flat water's 1 at a quarter of full scale.
    let (shape, first) = read_npy(&dir.join("frame-0000.npy"));
    assert_eq!(shape, [32, 32]);
    let png = image::open(dir.join("frame-0000.png")).unwrap().to_luma16();
    // PNG row 0 is the map's top row (y high); the .npy's row 0 is y = 0.
    let (v, c) = (first[31 * 32 + 5], png.get_pixel(5, 0).0[0]);
    assert_eq!(c, (v as f64 * 0.25 * 65535.0).round().min(65535.0) as u16);
    // The loop's last step (frame 3 to frame 0) is like its other steps.
    let frames: Vec<Vec<f32>> = (0..4)
        .map(|k| read_npy(&dir.join(format!("frame-{k:04}.npy"))).1)
        .collect();
    let step = |a: &[f32], b: &[f32]| {
        a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f32>() / a.len() as f32
    };
    let steps: Vec<f32> = (0..4)
        .map(|k| step(&frames[k], &frames[(k + 1) % 4]))
        .collect();
    eprintln!("steps between frames, the last back to the first: {steps:?}");
    let mean = steps[..3].iter().sum::<f32>() / 3.0;
    // measured: the last step 0.8 % from the others' mean (the reference, 32², 4 frames)
    assert!((steps[3] / mean - 1.0).abs() < 0.04, "{steps:?}");
    for (k, f) in frames.iter().enumerate() {
        let flux = f.iter().sum::<f32>() / f.len() as f32;
        eprintln!("frame {k}: flux {flux:.6}");
        // measured 6.4e-5 from flat water's
        assert!((flux - 1.0).abs() < 3.6e-4, "frame {k}: flux {flux}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn nothing_is_replaced_without_force() {
    let dir = tmpdir("force");
    assert!(bake(&dir, &[]).status.success());
    let before = std::fs::read(dir.join("frame-0001.png")).unwrap();
    std::fs::write(dir.join("frame-0001.png"), b"mine").unwrap();
    let o = bake(&dir, &[]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("--force") && err.contains("would be replaced"),
        "{err}"
    );
    assert_eq!(std::fs::read(dir.join("frame-0001.png")).unwrap(), b"mine");
    // Other settings in the same folder: the record would change, refused as well.
    let o = bake(&dir, &["--period", "3"]);
    assert!(stderr(&o).contains("bake.toml"), "{}", stderr(&o));
    let o = bake(&dir, &["--force"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(dir.join("frame-0001.png")).unwrap(), before);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pieces_assemble_into_the_whole_bake() {
    let whole = tmpdir("whole");
    assert!(bake(&whole, &[]).status.success());
    let pieces = tmpdir("pieces");
    for range in ["0..1", "1..4"] {
        let o = bake(&pieces, &["--range", range]);
        assert!(o.status.success(), "{range}: {}", stderr(&o));
        assert!(stderr(&o).contains("--assemble"), "{}", stderr(&o));
    }
    assert!(!pieces.join("atlas.png").exists());
    let o = caustics(&["bake", "--assemble", pieces.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in ["atlas.png", "frame-0002.png"] {
        assert_eq!(
            std::fs::read(whole.join(name)).unwrap(),
            std::fs::read(pieces.join(name)).unwrap(),
            "{name}"
        );
    }
    // A missing piece is named.
    std::fs::remove_file(pieces.join("frame-0003.png")).unwrap();
    let o = caustics(&["bake", "--assemble", pieces.to_str().unwrap(), "--force"]);
    assert!(stderr(&o).contains("frame 3"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&whole);
    let _ = std::fs::remove_dir_all(&pieces);
}

#[test]
fn dispersion_bakes_colour_frames() {
    let dir = tmpdir("dispersion");
    let o = bake(&dir, &["--dispersion", "--npy", "--format", "exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (shape, data) = read_npy(&dir.join("frame-0000.npy"));
    assert_eq!(shape, [32, 32, 3]);
    let split = data
        .chunks(3)
        .map(|c| (c[0] - c[2]).abs())
        .fold(0.0f32, f32::max);
    eprintln!("largest red-blue split: {split:.4}");
    // measured 0.0536 (the reference, 32², frame 0)
    assert!(split > 0.01, "red and blue alike: {split}");
    assert!(dir.join("frame-0000.exr").exists());
    let atlas = image::open(dir.join("atlas.png")).unwrap();
    assert_eq!(atlas.color(), image::ColorType::Rgb16);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn water_that_cannot_loop_is_refused() {
    let dir = tmpdir("refused");
    let pool = String::from_utf8(caustics(&["scene", "print", "pool"]).stdout).unwrap();
    let start = pool.find("waves = [").unwrap();
    let end = start + pool[start..].find("\n]\n").unwrap() + 3;
    for (source, says) in [
        ("ripple = {}\n", "ripple simulation cannot loop"),
        ("procedural = {}\n", "procedural wave cannot loop"),
    ] {
        let scene = dir.join("scene.toml");
        std::fs::write(
            &scene,
            format!("{}{source}{}", &pool[..start], &pool[end..]),
        )
        .unwrap();
        let out = dir.join("out");
        let o = bake(&out, &["--scene", scene.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(stderr(&o).contains(says), "{}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"));
        assert!(!out.exists(), "a refused bake left a folder");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_arguments_get_clear_errors() {
    let dir = tmpdir("bad");
    let cases: [(&[&str], &str); 9] = [
        (&["--frames", "0"], "--frames 0"),
        (&["--map-size", "4x4"], "from 8 to 8192"),
        (&["--map-size", "32x32x2"], "WIDTHxHEIGHT"),
        (&["--period", "0"], "--period 0"),
        (&["--range", "3..2"], "empty"),
        (&["--range", "0..9"], "the bake has 4 frames"),
        (&["--technique", "cascaded"], "screen space"),
        (&["--sun-elevation", "-5"], "--sun-elevation -5"),
        (&["--depth", "0"], "--depth 0"),
    ];
    for (extra, says) in cases {
        let out = dir.join("out");
        let o = bake(&out, extra);
        let err = stderr(&o);
        // 2: refused by the argument parser; 1: by the bake.
        assert!(matches!(o.status.code(), Some(1 | 2)), "{extra:?}: {err}");
        assert!(err.contains(says), "{extra:?}: {err}");
        assert!(!err.contains("panicked"), "{extra:?}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
