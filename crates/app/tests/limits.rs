//! Sizes beyond what the program or the device allows, asked for on the command line: one clear
//! error and a non-zero exit from `caustics render`, never a panic.

use std::process::{Command, Output};

fn render(args: &[&str]) -> Output {
    let dir = std::env::temp_dir().join(format!("caustics-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    Command::new(env!("CARGO_BIN_EXE_caustics"))
        .arg("render")
        .args(args)
        .current_dir(&dir)
        .output()
        .expect("the binary runs")
}

/// Exit status 1 (an error, not a panic's 101 or a signal), and `names` on stderr.
fn assert_refused(out: &Output, names: &[&str]) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for n in names {
        assert!(stderr.contains(n), "missing `{n}` in: {stderr}");
    }
}

#[test]
fn sizes_beyond_the_program_limit_are_refused_at_the_flag() {
    let out = render(&["--resolution", "100000x100000", "--out", "x.png"]);
    assert_refused(&out, &["--resolution 100000x100000", "between 1 and 16384"]);
    let out = render(&["--image-size", "64x100000", "--out", "x.png"]);
    assert_refused(&out, &["--image-size 64x100000", "between 1 and 16384"]);
}

/// A map the program takes but the device cannot hold: yuksel's pre-pass texture is the map plus
/// a margin on each side, so a map as wide as the device's largest texture is beyond it. Needs a
/// device whose limit the command line can reach (lavapipe's 16384: about 10 s there,
/// most of it sampling the water at the map's size before the technique is built).
#[test]
fn a_map_beyond_the_device_gives_one_error_naming_it() {
    let required = std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1");
    if !required {
        eprintln!("skipping: a 16384² map on the CPU takes too long; set CAUSTICS_REQUIRE_GPU=1");
        return;
    }
    let ctx = caustics_gpu::GpuContext::headless(&Default::default()).expect("a GPU");
    let max = ctx.limits().max_texture_dimension_2d;
    drop(ctx);
    if max > caustics_core::scene::MAX_RESOLUTION {
        eprintln!("skipping: this device's {max} texels per side are beyond what the CLI asks for");
        return;
    }
    let size = format!("{max}x{max}");
    let out = render(&[
        "--technique",
        "yuksel",
        "--resolution",
        &size,
        "--image-size",
        "64x36",
        "--out",
        "x.png",
    ]);
    assert_refused(
        &out,
        &[
            "yuksel pre-pass texture",
            "beyond what this GPU allows",
            &format!("1 .. {max} per side"),
        ],
    );
}
