//! `docs/gpu-bench.sh --small` end to end on whatever adapter there is (lavapipe in CI): the
//! one-shot GPU run takes the built binary, and its CSV has a row for every registered technique
//! and for the whole frame of each, and the error-against-cost table a Pareto front.

#[macro_use]
#[path = "../../gpu/tests/common/mod.rs"]
mod common;

use std::path::PathBuf;
use std::process::Command;

use caustics_gpu::registry::REGISTRY;

fn gpu_bench_small_covers_every_technique_and_the_frame() {
    // A device, or the test fails: the harness has reported it ignored where none can be made.
    drop(caustics_gpu::context::test_gpu());
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = std::env::temp_dir().join(format!("caustics-gpu-bench-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let o = Command::new("bash")
        .arg(root.join("docs/gpu-bench.sh"))
        .arg(&out)
        .arg("--quick")
        .env("CAUSTICS_BIN", env!("CARGO_BIN_EXE_caustics"))
        .output()
        .expect("bash runs");
    assert!(
        o.status.success(),
        "gpu-bench.sh failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    // The technique label is the first, quoted, field.
    let labels: Vec<String> = csv
        .lines()
        .skip(1)
        .map(|l| l.split('"').nth(1).unwrap_or("").to_string())
        .collect();
    for r in REGISTRY {
        for row in [r.name().to_string(), format!("frame: {}", r.name())] {
            assert!(labels.contains(&row), "no row `{row}` in:\n{csv}");
        }
    }
    // Glass generators get their own rows.
    assert!(
        labels.iter().any(|l| l == "caustic-triangles (glass)"),
        "no glass row in:\n{csv}"
    );
    assert!(!csv.contains("no GPU path"));
    let tradeoff = std::fs::read_to_string(out.join("tradeoff.csv")).unwrap();
    let rows: Vec<&str> = tradeoff.lines().skip(1).collect();
    assert!(rows.len() >= 8, "{tradeoff}");
    // Every setting has an error in (0, 1] against the reference, and one at least is on the front.
    for r in &rows {
        let f: Vec<&str> = r.split(',').collect();
        let l1: f64 = f[f.len() - 5].parse().unwrap();
        assert!(l1 > 0.0 && l1 < 1.0, "{r}");
    }
    assert!(rows.iter().any(|r| r.ends_with(",true")), "{tradeoff}");
    let summary = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(summary.contains("## Error against cost"), "{summary}");
    let _ = std::fs::remove_dir_all(&out);
}

/// `--scene` picks the scenes the techniques are timed on; a scene that does not exist is refused
/// with its name.
fn bench_times_the_scenes_asked_for() {
    drop(caustics_gpu::context::test_gpu());
    let out = std::env::temp_dir().join(format!("caustics-bench-scene-{}", std::process::id()));
    let run = |scene: &str| {
        Command::new(env!("CARGO_BIN_EXE_caustics"))
            .args([
                "bench",
                "--quick",
                "--no-frame",
                "--technique",
                "procedural",
            ])
            .args(["--scene", scene, "--out"])
            .arg(&out)
            .output()
            .expect("caustics runs")
    };
    let o = run("reef");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    let labels: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split('"').nth(1).unwrap_or(""))
        .collect();
    assert!(!labels.is_empty(), "{csv}");
    assert!(labels.iter().all(|l| *l == "procedural (reef)"), "{csv}");
    let o = run("no-such-scene");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && stderr.contains("no-such-scene"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&out);
}

test_main! {
    gpu gpu_bench_small_covers_every_technique_and_the_frame,
    gpu bench_times_the_scenes_asked_for,
}
