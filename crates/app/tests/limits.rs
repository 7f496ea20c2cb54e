//! Sizes beyond what the program or the device allows, asked for on the command line: one clear
//! error and a non-zero exit from `caustics render`, never a panic.
//!
//! Run by libtest-mimic (`harness = false`): the device test is reported as ignored, with the
//! reason, where it cannot run (no `CAUSTICS_REQUIRE_GPU=1`: a 16384² map on the CPU path takes too
//! long; a device whose limit the command line cannot reach), never as passed unrun.

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

fn sizes_beyond_the_program_limit_are_refused_at_the_flag() {
    let out = render(&["--map-size", "100000x100000", "--out", "x.png"]);
    assert_refused(&out, &["--map-size 100000x100000", "between 1 and 16384"]);
    let out = render(&["--image-size", "64x100000", "--out", "x.png"]);
    assert_refused(&out, &["--image-size 64x100000", "between 1 and 16384"]);
}

/// A map the program takes but the device cannot hold: the render targets' pass-1 targets
/// (`yuksel-targets`) are the map plus M rows (its pre-pass texture, larger still, is cut into
/// layers that fit), so a map as tall as the device's largest texture is beyond it; yuksel's
/// default (the scatter) is refused too, by its sums' binding size or the device's memory. Needs a
/// device whose limit the command line can reach (lavapipe's 16384: about 10 s there,
/// most of it sampling the water at the map's size before the technique is built).
fn a_map_beyond_the_device_gives_one_error_naming_it(max: u32) {
    let size = format!("{max}x{max}");
    let map = |technique| {
        render(&[
            "--technique",
            technique,
            "--map-size",
            &size,
            "--image-size",
            "64x36",
            "--out",
            "x.png",
        ])
    };
    let scatter = map("yuksel");
    assert_refused(&scatter, &[]);
    // lavapipe: "yuksel scatter sums of 1073741824 bytes is beyond what this GPU allows (134217728
    // bytes)"; a device with a larger binding size runs out of memory instead.
    let said = String::from_utf8_lossy(&scatter.stderr);
    assert!(
        said.contains("yuksel scatter sums") || said.contains("Out of Memory"),
        "{said}"
    );
    let out = map("yuksel-targets");
    assert_refused(
        &out,
        &[
            // The pre-pass texture is cut into tiles that fit; the pass-1 targets (the map's
            // height plus M rows) are what the map's side runs into.
            "yuksel pass-1 targets",
            "beyond what this GPU allows",
            &format!("1 .. {max} per side"),
        ],
    );
}

/// The device's largest texture side, or why the device test cannot run here.
fn device_limit() -> Result<u32, String> {
    let required = std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1");
    if !required {
        return Err("a 16384² map on the CPU takes too long; set CAUSTICS_REQUIRE_GPU=1".into());
    }
    let ctx = caustics_gpu::GpuContext::headless(&Default::default())
        .map_err(|e| format!("CAUSTICS_REQUIRE_GPU=1 but no GPU device: {e}"))?;
    let max = ctx.limits().max_texture_dimension_2d;
    if max > caustics_core::scene::MAX_RESOLUTION {
        return Err(format!(
            "this device's {max} texels per side are beyond what the CLI asks for"
        ));
    }
    Ok(max)
}

fn main() -> std::process::ExitCode {
    use libtest_mimic::{Arguments, Trial};
    let args = Arguments::from_args();
    let limit = device_limit();
    // Required without a device: the test runs, and fails naming why; otherwise it is ignored.
    let missing = limit
        .as_ref()
        .is_err_and(|why| why.starts_with("CAUSTICS_REQUIRE_GPU=1 but"));
    if let (Err(why), false) = (&limit, missing) {
        eprintln!("the device test is ignored: {why}");
    }
    let trials = vec![
        Trial::test(
            "sizes_beyond_the_program_limit_are_refused_at_the_flag",
            || {
                sizes_beyond_the_program_limit_are_refused_at_the_flag();
                Ok(())
            },
        ),
        Trial::test("a_map_beyond_the_device_gives_one_error_naming_it", {
            let limit = limit.clone();
            move || {
                let max = limit.clone()?;
                a_map_beyond_the_device_gives_one_error_naming_it(max);
                Ok(())
            }
        })
        .with_ignored_flag(limit.is_err() && !missing),
    ];
    libtest_mimic::run(&args, trials).exit_code()
}
