//! The `caustics` binary as a user meets it: the scene contract, outputs, and clear errors for bad
//! input with a non-zero exit.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use caustics_core::grid::Grid;

fn caustics(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_caustics"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("caustics-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const CONTRACT: &str = r#"
[water]
heightfield = "surface.npy"
size = 1.0
depth = 0.4
ior = 1.333
wrap = true

[light]
direction = [0.3, 0.1, -1.0]

[caustics]
resolution = [48, 32]
technique = "reference"
"#;

fn contract_dir(name: &str, surface: &Grid, toml: &str) -> PathBuf {
    let d = tmpdir(name);
    surface.write_npy(&d.join("surface.npy")).unwrap();
    std::fs::write(d.join("scene.toml"), toml).unwrap();
    d
}

/// The built-in scene `name` (`pool` or `objects`) written to `dir` with gentle ripples (21 cm to
/// 1 m long) in place of its waves: the tests that use it measure a technique's flux and shadows
/// at map sizes that resolve those ripples, not the built-in's 11 cm wavelets.
/// Returns the file's name in `dir`.
fn with_gentle_ripples(dir: &Path, name: &str) -> String {
    let text = caustics_core::scene::BUILTIN_SCENES
        .iter()
        .find(|(n, _)| *n == name)
        .expect("built-in scene")
        .1;
    let start = text.find("waves = [").expect("waves");
    let end = start + text[start..].find("\n]\n").expect("end of waves") + 3;
    let waves = match name {
        "pool" => {
            "waves = [
  { amplitude = 0.0040, wavelength = 0.50, direction = [1.0, 0.25] },
  { amplitude = 0.0032, wavelength = 0.36, direction = [-0.4, 1.0], phase = 1.3 },
  { amplitude = 0.0025, wavelength = 0.27, direction = [0.8, -0.7], phase = 2.1 },
  { amplitude = 0.0020, wavelength = 0.21, direction = [0.1, 1.0], phase = 0.4 },
  { amplitude = 0.0050, wavelength = 1.00, direction = [1.0, 0.9], phase = 4.0 },
]
"
        }
        "objects" => {
            "waves = [
  { amplitude = 0.0045, wavelength = 0.55, direction = [1.0, 0.2] },
  { amplitude = 0.0035, wavelength = 0.38, direction = [-0.3, 1.0], phase = 0.7 },
  { amplitude = 0.0025, wavelength = 0.26, direction = [0.7, -0.8], phase = 2.5 },
]
"
        }
        _ => panic!("no gentle ripples for {name}"),
    };
    let file = format!("{name}-gentle.toml");
    std::fs::write(
        dir.join(&file),
        format!("{}{waves}{}", &text[..start], &text[end..]),
    )
    .unwrap();
    file
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn the_minimum_contract_renders_a_raw_map_of_the_stated_shape() {
    // A gentle periodic swell sampled on the contract's lattice.
    let n = 64;
    let g = Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64;
        let y = (i as f64 + 0.5) / n as f64;
        (0.004 * (std::f64::consts::TAU * (3.0 * x + y)).sin()) as f32
    });
    let d = contract_dir("contract", &g, CONTRACT);
    let o = caustics(&["render", "--scene", "scene.toml", "--raw", "map.npy"], &d);
    assert!(o.status.success(), "{}", stderr(&o));
    let map = Grid::load(&d.join("map.npy"), [0.0, 1.0]).unwrap();
    assert_eq!((map.rows, map.cols), (32, 48), "shape is (height, width)");
    // Flux is conserved: the mean is the mean Fresnel ratio, within a percent of 1 for a gentle swell.
    assert!((map.mean() - 1.0).abs() < 0.01, "mean {}", map.mean());
    let (lo, hi) = map.min_max();
    assert!(lo < 0.9 && hi > 1.1, "caustics present: {lo} .. {hi}");
    // The same map as EXR.
    let o = caustics(&["render", "--scene", "scene.toml", "--raw", "map.exr"], &d);
    assert!(o.status.success(), "{}", stderr(&o));
    let exr = Grid::load(&d.join("map.exr"), [0.0, 1.0]).unwrap();
    assert_eq!(exr, map);
}

#[test]
fn a_flat_height_field_gives_one() {
    let d = contract_dir("flat", &Grid::new(16, 16), CONTRACT);
    let o = caustics(
        &["render", "--scene", "scene.toml", "--raw", "flat.npy"],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let map = Grid::load(&d.join("flat.npy"), [0.0, 1.0]).unwrap();
    for v in &map.data {
        assert!((v - 1.0).abs() < 1e-4, "{v}");
    }
}

#[test]
fn the_default_scene_renders_an_image() {
    let d = tmpdir("default");
    let o = caustics(
        &[
            "render",
            "--map-size",
            "64x64",
            "--image-size",
            "96x54",
            "--supersampling",
            "1",
            "--final-image",
            "gpu",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(d.join("pool.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (96, 54));
    // The same picture from the CPU's final image (and, where a GPU made the first, its map): the
    // two implementations agree, so a wrong picture from either fails here.
    let o = caustics(
        &[
            "render",
            "--map-size",
            "64x64",
            "--image-size",
            "96x54",
            "--supersampling",
            "1",
            "--cpu",
            "--out",
            "cpu.png",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let cpu = image::open(d.join("cpu.png")).unwrap().to_rgb8();
    let n = img.as_raw().len() as f64;
    let diff: f64 = img
        .as_raw()
        .iter()
        .zip(cpu.as_raw())
        .map(|(a, b)| (*a as f64 - *b as f64).abs())
        .sum::<f64>()
        / n;
    let mean = cpu.as_raw().iter().map(|&v| v as f64).sum::<f64>() / n;
    // The caustics show: the pool's floor is not one flat colour. Luminance spread of the CPU image.
    let lum: Vec<f64> = cpu
        .pixels()
        .map(|p| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64)
        .collect();
    let lmean = lum.iter().sum::<f64>() / lum.len() as f64;
    let spread = (lum.iter().map(|l| (l - lmean).powi(2)).sum::<f64>() / lum.len() as f64).sqrt();
    eprintln!(
        "default scene: mean |GPU - CPU| {diff:.3} of 255, mean {mean:.1}, luminance spread {spread:.1}"
    );
    assert!(diff < DEFAULT_SCENE_DIFF, "{diff}");
    assert!(
        (mean - DEFAULT_SCENE_MEAN).abs() < 0.02 * DEFAULT_SCENE_MEAN,
        "{mean}"
    );
    assert!(spread > 0.5 * DEFAULT_SCENE_SPREAD, "{spread}");
}

/// Mean |GPU - CPU| per channel, 0..255: measured 0.115 on lavapipe with the caustics and the
/// tiles filtered over each sample's footprint; 5.5x.
const DEFAULT_SCENE_DIFF: f64 = 0.63;
/// The CPU picture's mean channel value (measured 184.5 with the daylight sky, its ambient light,
/// the stone deck and the footprint-filtered caustics and tiles, docs/maintainers/look.md; held to 2 %) and
/// luminance spread (measured 23.2, a flat floor without caustics has far less): the scene's look.
const DEFAULT_SCENE_MEAN: f64 = 184.5;
const DEFAULT_SCENE_SPREAD: f64 = 23.2;

#[test]
fn outputs_that_cannot_be_written_fail_before_the_work() {
    let d = tmpdir("unwritable");
    std::fs::create_dir_all(d.join("folder.png")).unwrap();
    for (flag, path, needle) in [
        ("--out", "nowhere/out.png", "no folder nowhere"),
        ("--out", "folder.png", "it is a folder"),
        ("--raw", "nowhere/out.npy", "no folder nowhere"),
    ] {
        let start = std::time::Instant::now();
        // A map large enough that the work would take long: the check comes first.
        let o = caustics(&["render", "--map-size", "2048x2048", flag, path], &d);
        let e = stderr(&o);
        assert!(!o.status.success(), "{flag} {path}: must fail");
        assert!(
            e.contains("cannot be written") && e.contains(needle),
            "{flag} {path}: {e}"
        );
        assert!(
            start.elapsed().as_secs_f64() < 20.0,
            "{flag} {path}: checked after the work"
        );
    }
    // Nothing left beside the outputs: no probe file, and the folder is as it was.
    let mut left: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, ["folder.png"]);
}

#[test]
fn a_size_takes_its_entries_whole() {
    let d = tmpdir("resolution");
    let bad = [
        ("--map-size", ["64x64x64", "64x", "sixty"]),
        ("--image-size", ["64x64x64", "64", "64x"]),
    ];
    for (flag, values) in bad {
        for bad in values {
            let o = caustics(&["render", flag, bad, "--out", "x.png"], &d);
            let e = stderr(&o);
            assert!(!o.status.success(), "{flag} {bad}: must fail");
            assert!(e.contains(flag) && e.contains(bad), "{flag} {bad}: {e}");
        }
    }
    assert!(!d.join("x.png").exists());
}

fn expect_error(name: &str, toml: &str, surface: &Grid, needle: &[&str]) {
    let d = contract_dir(name, surface, toml);
    let o = caustics(&["render", "--scene", "scene.toml", "--raw", "out.npy"], &d);
    let e = stderr(&o);
    assert!(!o.status.success(), "{name}: must fail");
    for n in needle {
        assert!(e.contains(n), "{name}: `{n}` not in: {e}");
    }
    assert!(!e.contains("panicked"), "{name}: {e}");
    assert!(!d.join("out.npy").exists(), "{name}: no output on error");
}

#[test]
fn bad_input_gets_a_clear_error() {
    let ok = Grid::new(16, 16);
    expect_error(
        "up",
        &CONTRACT.replace("[0.3, 0.1, -1.0]", "[0.3, 0.1, 0.5]"),
        &ok,
        &["light.direction", "points up"],
    );
    expect_error(
        "depth",
        &CONTRACT.replace("depth = 0.4", "depth = -0.4"),
        &ok,
        &["water.depth", "positive"],
    );
    expect_error(
        "ior",
        &CONTRACT.replace("ior = 1.333", "ior = 0.8"),
        &ok,
        &["water.ior", "at least 1"],
    );
    expect_error(
        "zero",
        &CONTRACT.replace("[48, 32]", "[0, 32]"),
        &ok,
        &["caustics.resolution"],
    );
    expect_error(
        "absurd",
        &CONTRACT.replace("[48, 32]", "[100000, 32]"),
        &ok,
        &["caustics.resolution", "beyond"],
    );
    expect_error(
        "syntax",
        &CONTRACT.replace("depth = 0.4", "depth = "),
        &ok,
        &["scene.toml", "malformed"],
    );
    expect_error(
        "typo",
        &CONTRACT.replace("depth = 0.4", "depht = 0.4"),
        &ok,
        &["depht"],
    );
    expect_error(
        "technique",
        &CONTRACT.replace("\"reference\"", "\"nope\""),
        &ok,
        &["nope"],
    );
    let mut nan = Grid::new(8, 8);
    nan.data[9] = f32::NAN;
    expect_error(
        "nan",
        CONTRACT,
        &nan,
        &["surface.npy", "row 1, column 1", "NaN"],
    );
    expect_error(
        "missing",
        &CONTRACT.replace("surface.npy", "nowhere.npy"),
        &ok,
        &["nowhere.npy"],
    );
    let deep = Grid::from_fn(8, 8, |_, _| -0.5);
    expect_error(
        "below floor",
        CONTRACT,
        &deep,
        &["surface.npy", "below the floor"],
    );
}

#[test]
fn a_height_field_of_the_wrong_shape_is_refused() {
    let d = contract_dir("shape", &Grid::new(4, 4), CONTRACT);
    // A 1-D array written by hand: magic, version 1.0, header, 4 float32 samples.
    let header = "{'descr': '<f4', 'fortran_order': False, 'shape': (4,), }";
    let mut h = header.to_string();
    while !(10 + h.len() + 1).is_multiple_of(64) {
        h.push(' ');
    }
    h.push('\n');
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend((h.len() as u16).to_le_bytes());
    bytes.extend(h.as_bytes());
    bytes.extend([0u8; 16]);
    std::fs::write(d.join("surface.npy"), bytes).unwrap();
    let o = caustics(&["render", "--scene", "scene.toml", "--raw", "out.npy"], &d);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("2-D"), "{}", stderr(&o));
}

#[test]
fn numbers_out_of_range_are_refused_by_name() {
    let d = tmpdir("ranges");
    for (args, range) in [
        (&["render", "--supersampling", "0"][..], "1..=16"),
        (&["render", "--supersampling", "17"][..], "1..=16"),
        (&["view", "--supersampling", "0"][..], "1..=16"),
        (&["view", "--cells-per-texel", "0"][..], "1..=16"),
    ] {
        let o = caustics(args, &d);
        assert!(!o.status.success(), "{args:?}");
        let e = stderr(&o);
        assert!(e.contains(args[1]) && e.contains(range), "{args:?}: {e}");
    }
    // Negative numbers are values, not flags: a negative exposure is refused by name, and a
    // negative time gets past the parser to the scene's checks (here: a scene that is not there).
    let o = caustics(&["render", "--exposure", "-1"], &d);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("--exposure must be positive"),
        "{}",
        stderr(&o)
    );
    let o = caustics(&["render", "--time", "-1.5", "--scene", "absent.toml"], &d);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        !e.contains("unexpected argument") && e.contains("absent.toml"),
        "{e}"
    );
    assert!(
        std::fs::read_dir(&d).unwrap().next().is_none(),
        "nothing written"
    );
}

#[test]
/// Every command that takes a GPU refuses a backend that does not exist, naming `--backend`,
/// before it writes anything (the CPU reference's bake included, which makes no device): a
/// misspelt backend is not a reason to fall back to the CPU.
fn a_backend_that_does_not_exist_is_refused_by_every_command() {
    let d = tmpdir("backend");
    for command in ["render", "compare", "bench", "bake", "view"] {
        let o = caustics(&[command, "--backend", "vulcan"], &d);
        assert!(!o.status.success(), "{command}");
        let e = stderr(&o);
        assert!(
            e.contains("--backend") && e.contains("vulcan"),
            "{command}: {e}"
        );
    }
    assert!(
        std::fs::read_dir(&d).unwrap().next().is_none(),
        "nothing written"
    );
}

#[test]
fn inputs_are_never_overwritten() {
    let g = Grid::from_fn(8, 8, |i, j| 0.001 * (i + j) as f32);
    let d = contract_dir("overwrite", &g, CONTRACT);
    let before = std::fs::read(d.join("surface.npy")).unwrap();
    let o = caustics(
        &["render", "--scene", "scene.toml", "--raw", "surface.npy"],
        &d,
    );
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("refusing to overwrite"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(d.join("surface.npy")).unwrap(), before);
}

#[test]
fn scene_check_and_techniques() {
    let d = tmpdir("check");
    for (name, _) in caustics_core::scene::BUILTIN_SCENES {
        let o = caustics(&["scene", "check", name], &d);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
    }
    let o = caustics(&["scene", "check", "missing.toml"], &d);
    assert!(!o.status.success() && stderr(&o).contains("missing.toml"));
    // `scene print` takes what `scene check` takes: a built-in scene printed and written to a
    // file prints the same again; a file that is no scene is refused by name.
    let pool = caustics(&["scene", "print", "pool"], &d);
    assert!(pool.status.success(), "{}", stderr(&pool));
    std::fs::write(d.join("mine.toml"), &pool.stdout).unwrap();
    let again = caustics(&["scene", "print", "mine.toml"], &d);
    assert!(again.status.success(), "{}", stderr(&again));
    assert_eq!(again.stdout, pool.stdout);
    std::fs::write(d.join("bad.toml"), "[water\n").unwrap();
    let o = caustics(&["scene", "print", "bad.toml"], &d);
    assert!(
        !o.status.success() && stderr(&o).contains("bad.toml"),
        "{}",
        stderr(&o)
    );
    // Every registered technique, and every parameter of each under it, from the registry.
    let o = caustics(&["techniques"], &d);
    let out = String::from_utf8_lossy(&o.stdout);
    for t in caustics_core::techniques::REGISTRY {
        let at = out
            .lines()
            .position(|l| l.split_whitespace().next() == Some(t.name))
            .unwrap_or_else(|| panic!("{} missing from:\n{out}", t.name));
        let below: Vec<&str> = out.lines().skip(at + 1).take(t.params.len()).collect();
        for (p, line) in t.params.iter().zip(&below) {
            assert!(
                line.trim_start().starts_with(&format!("{} = ", p.key)),
                "{}: `{}` missing: {line}",
                t.name,
                p.key
            );
        }
    }
    // docs/techniques.md's table is the one the registry makes.
    let o = caustics(&["techniques", "--markdown"], &d);
    let readme = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/techniques.md"
    ))
    .unwrap();
    let begin = "<!-- techniques: made by `caustics techniques --markdown` -->\n";
    let a = readme
        .find(begin)
        .expect("docs/techniques.md marks its table")
        + begin.len();
    let b = a + readme[a..]
        .find("<!-- techniques end -->")
        .expect("the table's end marker");
    assert_eq!(
        &readme[a..b],
        String::from_utf8_lossy(&o.stdout),
        "docs/techniques.md's table is stale: paste `caustics techniques --markdown` between its markers"
    );
    for t in caustics_core::techniques::REGISTRY {
        assert!(
            readme[a..b].contains(&format!("| `{}` |", t.name)),
            "{} missing",
            t.name
        );
    }
    // The GPU registry's names, one a line, each one `render --technique` accepts (CI's
    // validation pass renders every one of them).
    let o = caustics(&["techniques", "--gpu-names"], &d);
    let names: Vec<String> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(str::to_string)
        .collect();
    let registry: Vec<&str> = caustics_gpu::registry::REGISTRY
        .iter()
        .map(|r| r.name())
        .collect();
    assert_eq!(names, registry);
    assert!(names.contains(&"yuksel-targets".to_string()), "{names:?}");
}

/// A small `caustics compare`: the files appear, the reference against itself scores exactly zero
/// error and SSIM 1 (a known difference, none, gives the known numbers), and yuksel on the smooth
/// lens bump is close to the reference with its flux conserved.
#[test]
fn a_small_compare_writes_its_tables_and_scores_correctly() {
    let d = tmpdir("compare");
    let o = caustics(
        &[
            "compare",
            "--quick",
            "--cpu",
            "--map-size",
            "48",
            "--cells-per-texel",
            "2",
            "--technique",
            "reference",
            "--technique",
            "yuksel:n=15,m=14",
            "--out",
            "cmp",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(d.join("cmp/compare.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 4 * 2, "4 quick cases x 2 techniques:\n{csv}");
    // The technique label may hold commas (quoted): read the four metrics from the end.
    let num = |r: &Vec<&str>, k: usize| r[r.len() - 8 + k].parse::<f64>().unwrap();
    for r in &rows {
        if r[1] == "\"reference\"" {
            assert_eq!(
                (num(r, 4), num(r, 5), num(r, 6), num(r, 7)),
                (0.0, 0.0, 0.0, 1.0),
                "{r:?}"
            );
        }
    }
    let lens = rows
        .iter()
        .find(|r| r[0].starts_with("lens") && r[1].contains("yuksel"))
        .unwrap();
    assert!(num(lens, 4) < 0.05 && num(lens, 6).abs() < 0.01, "{lens:?}");
    assert!(d.join("cmp/compare.md").exists());
    assert!(
        std::fs::read_dir(d.join("cmp")).unwrap().any(|e| e
            .unwrap()
            .path()
            .extension()
            .is_some_and(|x| x == "png"))
    );
}

/// `caustics compare --receivers`: the table technique x receiver, each receiver a column, the
/// walls where the technique lights them; the reference against itself scores zero everywhere.
#[test]
fn compare_receivers_writes_the_technique_by_receiver_table() {
    let d = tmpdir("compare-receivers");
    let o = caustics(
        &[
            "compare",
            "--receivers",
            "--cpu",
            "--map-size",
            "48",
            "--cells-per-texel",
            "2",
            "--technique",
            "reference",
            "--technique",
            "yuksel",
            "--out",
            "cmp",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(d.join("cmp/compare.md")).unwrap();
    let table: Vec<&str> = md
        .lines()
        .skip_while(|l| !l.starts_with("## Technique x receiver"))
        .filter(|l| l.starts_with('|'))
        .take(4)
        .collect();
    assert!(
        table[0].contains("sand-bar")
            && table[0].contains("rocks")
            && table[0].contains("walls")
            && table[0].contains("objects"),
        "{md}"
    );
    assert_eq!(
        table[2], "| reference | 0.00 % | 0.00 % | 0.00 % | 0.00 % | 0.00 % | 0.00 % |",
        "{md}"
    );
    // yuksel maps the floor only: no walls.
    assert!(
        table[3].starts_with("| yuksel |") && table[3].ends_with(" - |"),
        "{md}"
    );
}

/// `--technique` runs the technique on the scene: yuksel's map of a gentle swell is close to the
/// reference's.
#[test]
fn render_uses_the_chosen_technique() {
    let n = 64;
    let g = Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64;
        let y = (i as f64 + 0.5) / n as f64;
        (0.002 * (std::f64::consts::TAU * (2.0 * x + y)).sin()) as f32
    });
    let d = contract_dir("chosen-technique", &g, CONTRACT);
    for (args, name) in [
        (vec!["--raw", "ref.npy"], "ref.npy"),
        (
            vec!["--technique", "yuksel:n=15,m=14", "--raw", "yuk.npy"],
            "yuk.npy",
        ),
    ] {
        let mut all = vec!["render", "--scene", "scene.toml", "--cpu"];
        all.extend(args);
        let o = caustics(&all, &d);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(d.join(name).exists());
    }
    let r = Grid::load(&d.join("ref.npy"), [0.0, 1.0]).unwrap();
    let y = Grid::load(&d.join("yuk.npy"), [0.0, 1.0]).unwrap();
    let l1: f32 = r
        .data
        .iter()
        .zip(&y.data)
        .map(|(a, b)| (a - b).abs())
        .sum::<f32>()
        / r.data.iter().sum::<f32>();
    assert!(l1 < 0.05, "yuksel against the reference: relative L1 {l1}");
    assert!(r != y, "a different technique gives a different map");
}

/// `caustics bench` writes its table, CSV and plot, and reports one row per technique and size.
#[test]
fn a_small_bench_writes_its_outputs() {
    let d = tmpdir("bench");
    let o = caustics(
        &[
            "bench",
            "--cpu",
            "--frames",
            "1",
            "--warmup",
            "0",
            "--map-size",
            "40x30,80x60",
            "--out",
            "b",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let md = std::fs::read_to_string(d.join("b/bench.md")).unwrap();
    for t in [
        "| yuksel | 40 x 30 |",
        "| yuksel | 80 x 60 |",
        "| yuksel-targets | 80 x 60 |",
    ] {
        assert!(md.contains(t), "{t} missing from:\n{md}");
    }
    assert!(
        std::fs::read_to_string(d.join("b/bench.svg"))
            .unwrap()
            .contains("<svg")
    );
    assert!(
        std::fs::read_to_string(d.join("b/bench.csv"))
            .unwrap()
            .lines()
            .count()
            > 4
    );
}

/// The glass scene through `render`: caustic-triangles makes a floor map with a focus brighter than
/// the unobstructed sun, and a water technique explains that the scene has no water.
#[test]
fn render_maps_glass_caustics() {
    let d = tmpdir("glass");
    let o = caustics(
        &[
            "render",
            "--scene",
            "glass",
            "--cpu",
            "--map-size",
            "64x64",
            "--technique",
            "caustic-triangles:photon_image=32,cube_resolution=64",
            "--raw",
            "g.npy",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let map = Grid::load(&d.join("g.npy"), [0.0, 1.0]).unwrap();
    assert!(map.min_max().1 > 2.0, "a focus: max {}", map.min_max().1);
    let o = caustics(
        &[
            "render",
            "--scene",
            "glass",
            "--cpu",
            "--technique",
            "yuksel",
            "--raw",
            "y.npy",
        ],
        &d,
    );
    assert!(
        !o.status.success() && stderr(&o).contains("no water"),
        "{}",
        stderr(&o)
    );
}

/// The raw `.npy` a render wrote: its shape and its samples (NaN kept: `Grid::load` refuses them).
fn read_npy_f32(path: &Path) -> ((usize, usize), Vec<f32>) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..6], b"\x93NUMPY", "{}", path.display());
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = String::from_utf8_lossy(&bytes[10..10 + len]).into_owned();
    assert!(header.contains("'<f4'"), "{header}");
    let shape = header.split("'shape': (").nth(1).unwrap();
    let dims: Vec<usize> = shape
        .split(')')
        .next()
        .unwrap()
        .split(',')
        .filter_map(|v| v.trim().parse().ok())
        .collect();
    let data = bytes[10 + len..]
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    ((dims[0], dims[1]), data)
}

/// Technique `cascaded` through `render`: its caustics live in the camera's screen space, so the
/// raw output is an image of the final image's size (NaN where it has none: the sky), and the
/// final image reads it on the sand, which shows the caustics' bright lines.
#[test]
fn render_shows_cascaded_caustics() {
    let d = tmpdir("cascaded");
    let o = caustics(
        &[
            "render",
            "--scene",
            "shore",
            "--cpu",
            "--technique",
            "cascaded:resolution=256",
            "--image-size",
            "160x90",
            "--supersampling",
            "1",
            "--out",
            "c.png",
            "--raw",
            "c.npy",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("eye-space image 160 x 90"),
        "{}",
        stderr(&o)
    );
    let ((rows, cols), raw) = read_npy_f32(&d.join("c.npy"));
    assert_eq!((rows, cols), (90, 160));
    // The top rows see the sky. Rows 36-55 see the floor 15-45 m out under 1-3 m of water, where
    // the waves focus the sun into bright lines with dark gaps (nearer, the beach is too shallow).
    assert!(raw[..160].iter().all(|v| v.is_nan()));
    let band: Vec<f32> = raw[36 * 160..56 * 160].to_vec();
    assert!(band.iter().all(|v| v.is_finite()));
    let mean = band.iter().sum::<f32>() / band.len() as f32;
    let bright = band.iter().filter(|&&v| v > 1.5 * mean).count() as f32 / band.len() as f32;
    let dark = band.iter().filter(|&&v| v < 0.6 * mean).count() as f32 / band.len() as f32;
    // Measured: mean 0.86, 2.3 % bright, 1.1 % dark (flat-water light: none of either).
    assert!(mean > 0.5 && mean < 1.5, "mean {mean}");
    assert!(
        bright > 0.01 && dark > 0.005,
        "bright {bright}, dark {dark}"
    );
    // In the image the same rows vary along each row: 4.8 steps of green (measured), 2.5 where
    // the floor is lit as under flat water (a 4 x 4 reference map), from the sand and the view.
    let img = image::open(d.join("c.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (160, 90));
    let mut spread = 0.0;
    for y in 36..56 {
        let row: Vec<f64> = (0..160).map(|x| img.get_pixel(x, y)[1] as f64).collect();
        let m = row.iter().sum::<f64>() / 160.0;
        spread += (row.iter().map(|v| (v - m).powi(2)).sum::<f64>() / 160.0).sqrt() / 20.0;
    }
    assert!(
        spread > 3.5,
        "the floor shows no caustics: row spread {spread:.1} steps"
    );
}

/// The glass scene under a lamp (docs/scenes/glass-lamp.toml, a spot light): caustic-triangles
/// renders it through its own camera pass (light cube map, shadows), and a technique that needs
/// the sun refuses it, naming the field.
#[test]
fn render_lights_glass_with_a_lamp() {
    let d = tmpdir("glass-lamp");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/scenes/glass-lamp.toml"
    );
    let o = caustics(
        &[
            "render",
            "--scene",
            scene,
            "--cpu",
            "--image-size",
            "48x32",
            "--technique",
            "caustic-triangles:photon_image=24,cube_resolution=48,light_cube=64",
            "--out",
            "lamp.png",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(d.join("lamp.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (48, 32));
    let lum: Vec<u32> = img
        .pixels()
        .map(|p| p.0.iter().map(|&c| c as u32).sum())
        .collect();
    let (lo, hi) = (lum.iter().min().unwrap(), lum.iter().max().unwrap());
    assert!(hi - lo > 150, "lit and unlit parts: {lo} .. {hi}");
    let o = caustics(
        &["render", "--scene", scene, "--cpu", "--technique", "yuksel"],
        &d,
    );
    assert!(
        !o.status.success() && stderr(&o).contains("light.position"),
        "{}",
        stderr(&o)
    );
}

/// Technique volumes (paper 3) through `render` on the objects scene, on its CPU twin: the floor map
/// holds the three objects' shadows (about 6 % of the pool: their projections along the refracted
/// sun), the walls' shadows, and the light the waves focus elsewhere.
#[test]
fn volumes_renders_the_objects_scene_with_their_shadows() {
    let d = tmpdir("volumes");
    let o = caustics(
        &[
            "render",
            "--cpu",
            "--scene",
            "objects",
            "--technique",
            "volumes:planes=3,texture=32",
            "--map-size",
            "96x96",
            "--image-size",
            "64x36",
            "--out",
            "objects.png",
            "--raw",
            "objects.npy",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(d.join("objects.png").exists());
    let g = Grid::load(&d.join("objects.npy"), [0.0, 1.0]).unwrap();
    let dark = g.data.iter().filter(|&&v| v < 0.05).count() as f64 / g.data.len() as f64;
    // The pool's walls (on in the scene) shade the floor strips along the two walls the sun comes
    // over, `depth tan θt` wide along each axis (8.7 % of the pool here; measured 14.9 % dark in
    // all): the objects' shadows are the rest.
    let scene = caustics_core::scene::Scene::builtin("objects").unwrap();
    let w = scene.water.as_ref().unwrap();
    assert!(scene.floor.walls);
    let t = caustics_core::optics::refract(
        scene.light.direction.normalize(),
        glam::DVec3::Z,
        1.0 / w.ior,
    )
    .unwrap();
    let (sx, sy) = (
        (w.depth * t.x / t.z).abs() / w.size,
        (w.depth * t.y / t.z).abs() / w.size,
    );
    let objects = dark - (sx + sy - sx * sy);
    assert!(
        objects > 0.03 && objects < 0.1,
        "shadowed share {dark}, objects' {objects}"
    );
    let max = g.data.iter().cloned().fold(0.0, f32::max);
    assert!(max > 1.5, "the waves focus the light: {max}");
}

/// Without `--raw`, technique volumes writes its own picture, the refracted view of §3.3 (the objects
/// with their caustics seen through the water), at the camera's size.
#[test]
fn volumes_writes_its_refracted_view() {
    let d = tmpdir("volumes-view");
    let o = caustics(
        &[
            "render",
            "--cpu",
            "--scene",
            "objects",
            "--technique",
            "volumes:planes=3,texture=32",
            "--map-size",
            "64x64",
            "--image-size",
            "80x60",
            "--out",
            "view.png",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("refracted view"), "{}", stderr(&o));
    let img = image::open(d.join("view.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (80, 60));
    // The red ball and the blue block are in the picture, among the water's cyan.
    let reddish = img
        .pixels()
        .filter(|p| p[0] as u32 > p[2] as u32 + 30)
        .count();
    assert!(reddish > 5, "{reddish}");
}

/// The pool through `render` with caustic-triangles: its water surface is the generator (the water
/// photon pass), the map averages the flat-water light the pool's absorption leaves, and the final
/// image is written.
#[test]
fn render_pool_with_caustic_triangles_uses_the_water_as_generator() {
    let d = tmpdir("pool-caustic-triangles");
    let scene = with_gentle_ripples(&d, "pool");
    // The floor map alone, wrapping round the square (the pool's walls, on in the built-in scene,
    // would take the light that leaves it).
    let text = std::fs::read_to_string(d.join(&scene)).unwrap();
    std::fs::write(
        d.join(&scene),
        text.replace("walls = true", "walls = false"),
    )
    .unwrap();
    let o = caustics(
        &[
            "render",
            "--scene",
            &scene,
            "--cpu",
            "--map-size",
            "64x64",
            "--image-size",
            "48x32",
            "--technique",
            "caustic-triangles:photon_image=64",
            "--raw",
            "p.npy",
            "--out",
            "p.png",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let map = Grid::load(&d.join("p.npy"), [0.0, 1.0]).unwrap();
    assert_eq!((map.cols, map.rows), (64, 64));
    // Flat water 1 m deep under the pool's sun: the refracted path is 1.027 m, and the channels
    // keep exp(−K d) of K = (0.45, 0.09, 0.05): 0.831 on average. The waves redistribute the light
    // and the wrapped copies keep all of it.
    let mean = map.mean();
    assert!((mean / 0.831 - 1.0).abs() < 0.01, "mean {mean}");
    let (lo, hi) = map.min_max();
    let (lo, hi) = (lo as f64, hi as f64);
    assert!(hi > 1.1 * mean && lo < 0.9 * mean, "caustics: {lo} .. {hi}");
    let img = image::open(d.join("p.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (48, 32));
}

/// `render --scene glass` with the scene's own technique, `reference`: paper 4's photon tracer
/// against the exact geometry makes the floor map, so the image shows the glass objects' foci and
/// shadows.
#[test]
fn the_glass_reference_renders_foci_and_shadows() {
    let d = tmpdir("glass-reference");
    let o = caustics(
        &[
            "render",
            "--scene",
            "glass",
            "--map-size",
            "128x128",
            "--image-size",
            "320x180",
            "--cells-per-texel",
            "1",
            "--out",
            "g.png",
            "--raw",
            "g.npy",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("reference map 128 x 128"),
        "{}",
        stderr(&o)
    );
    let ((rows, cols), map) = read_npy_f32(&d.join("g.npy"));
    assert_eq!((rows, cols), (128, 128));
    // Measured: the sphere's focus peaks at 137 times the unobstructed sun.
    let peak = map.iter().cloned().fold(0.0f32, f32::max);
    assert!(peak > 20.0, "no focus: the map peaks at {peak}");
    // Measured: 2.9 % of the image darker than 0.6 times its median (the shadows, lit by the
    // daylight sky's ambient light alone); 0.5 % darker than a fixed 100 of 255.
    let img = image::open(d.join("g.png")).unwrap().to_luma8();
    let mut lum: Vec<u8> = img.pixels().map(|p| p[0]).collect();
    lum.sort_unstable();
    let median = lum[lum.len() / 2] as f64;
    let dark = lum.iter().filter(|&&l| (l as f64) < 0.6 * median).count() as f64 / lum.len() as f64;
    assert!(dark > 0.01, "no shadows: {:.2} % dark", dark * 100.0);
}

/// On a scene with diffuse objects under the water (`objects`), the reference is the photon tracer
/// with mesh receivers: its floor map holds the objects' shadows, as `volumes`' does, so that a
/// technique's shadows are not counted as its error.
#[test]
fn the_reference_sees_the_objects() {
    let d = tmpdir("objects-reference");
    // Under the gentle ripples the dark texels are the objects' shadows, not the gaps between
    // sharp caustic lines.
    let scene = with_gentle_ripples(&d, "objects");
    let raw = |technique: &str, out: &str| {
        let o = caustics(
            &[
                "render",
                "--scene",
                &scene,
                "--technique",
                technique,
                "--map-size",
                "64x64",
                "--cells-per-texel",
                "1",
                "--raw",
                out,
            ],
            &d,
        );
        assert!(o.status.success(), "{technique}: {}", stderr(&o));
        read_npy_f32(&d.join(out)).1
    };
    let reference = raw("reference", "r.npy");
    let volumes = raw("volumes", "v.npy");
    let dark = |m: &[f32]| m.iter().filter(|&&v| v < 0.3).count() as f64 / m.len() as f64;
    // Measured: 6.35 % of the floor in the objects' shadows in both maps.
    assert!(
        dark(&reference) > 0.03,
        "no shadows: {:.3}",
        dark(&reference)
    );
    assert!(
        (dark(&reference) - dark(&volumes)).abs() < 0.01,
        "shadows {:.4} against volumes' {:.4}",
        dark(&reference),
        dark(&volumes)
    );
    // Measured: volumes' flux 0.31 % below the reference's.
    let sum = |m: &[f32]| m.iter().map(|&v| v as f64).sum::<f64>();
    let flux = sum(&volumes) / sum(&reference) - 1.0;
    assert!(flux.abs() < 0.03, "flux {flux}");
}

/// `--raw-walls PREFIX` writes the four walls' maps of the pool in the floor map's unit,
/// shape (rows, cols): a sun travelling towards +x lights x = size most; and it is refused before
/// the work where there are no walls to write or the technique maps the floor only.
#[test]
fn render_writes_the_pools_walls() {
    let d = tmpdir("walls");
    // The pool under a low sun (63° from the zenith) travelling towards +x, a little +y.
    let (_, pool) = caustics_core::scene::BUILTIN_SCENES
        .iter()
        .find(|(n, _)| *n == "pool")
        .expect("built-in pool");
    std::fs::write(
        d.join("low.toml"),
        pool.replace(
            "direction = [0.3, 0.1, -1.0]",
            "direction = [1.0, 0.2, -0.5]",
        ),
    )
    .unwrap();
    let o = caustics(
        &[
            "render",
            "--scene",
            "low.toml",
            "--map-size",
            "64x64",
            "--cells-per-texel",
            "2",
            "--raw-walls",
            "w",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // 4 m at 64 texels: 1 m deep is 16 rows.
    let mean = |s: &str| {
        let (shape, v) = read_npy_f32(&d.join(format!("w-{s}.npy")));
        assert_eq!(shape, (16, 64), "{s}");
        v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64
    };
    let (x0, x1, y0, y1) = (mean("x0"), mean("x1"), mean("y0"), mean("y1"));
    eprintln!("walls' mean: x0 {x0:.4} x1 {x1:.4} y0 {y0:.4} y1 {y1:.4}");
    assert_eq!(x0, 0.0);
    assert!(x1 > 0.5 && x1 > 3.0 * y1, "{x1} {y1}");
    assert_eq!(y0, 0.0);
    assert!(
        !d.join("low.png").exists(),
        "--raw-walls alone writes no image"
    );

    for (args, needle) in [
        (
            vec!["--scene", "shore", "--raw-walls", "w"],
            "the scene's walls are off: set `[floor] walls = true`",
        ),
        (
            vec![
                "--scene",
                "low.toml",
                "--technique",
                "yuksel",
                "--raw-walls",
                "w",
            ],
            "yuksel maps the floor only; --raw-walls needs one of reference, ",
        ),
        (
            vec![
                "--scene",
                "low.toml",
                "--technique",
                "cascaded",
                "--raw-walls",
                "w",
            ],
            "cascaded lights the walls in the camera's image, not in wall maps",
        ),
        (
            vec!["--scene", "low.toml", "--raw-walls", "nowhere/w"],
            "--raw-walls nowhere/w-x0.npy: cannot be written",
        ),
    ] {
        let o = caustics(&[&["render"], &args[..]].concat(), &d);
        assert!(!o.status.success());
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("caustics:"), "refused after the work");
    }
}

/// The app reaches techniques through the registry alone: outside comments and test modules its
/// source names no registered technique in a string and reaches into no technique's module (a
/// technique added to the registry appears in every front end without an edit here).
#[test]
fn the_app_source_names_no_technique() {
    use caustics_core::techniques::REGISTRY;
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = vec![];
    let mut dirs = vec![src];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                files.push(p);
            }
        }
    }
    assert!(files.len() > 10, "{files:?}");
    let mut modules: Vec<String> = REGISTRY
        .iter()
        .map(|d| format!("techniques::{}", d.table.replace('-', "_")))
        .collect();
    modules.dedup();
    let mut found = vec![];
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        for (n, line) in code.lines().enumerate() {
            let line = line.trim_start();
            if line.starts_with("//") {
                continue;
            }
            let quoted = REGISTRY
                .iter()
                .any(|d| line.contains(&format!("\"{}", d.name)));
            // `techniques::reference()` is the registry's accessor, not the module.
            let reached = modules
                .iter()
                .any(|m| line.contains(m.as_str()) && !line.contains(&format!("{m}(")));
            if quoted || reached {
                found.push(format!("{}:{}: {line}", f.display(), n + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "technique names in the app:\n{}",
        found.join("\n")
    );
}

/// `--final-image auto` (the default) traces the image where it is faster: on the CPU beside a
/// software adapter (whose pass costs tens of seconds to compile on a fresh machine: 43.9 s against
/// 8.1 s for the README's first command with Mesa's shader cache off), on the GPU beside a real one;
/// `--final-image gpu` and `cpu` choose.
#[test]
fn the_final_image_goes_where_it_is_faster() {
    let d = tmpdir("final-image");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "render",
            "--map-size",
            "32x32",
            "--image-size",
            "48x27",
            "--supersampling",
            "1",
        ];
        args.extend(extra);
        let o = caustics(&args, &d);
        assert!(o.status.success(), "{}", stderr(&o));
        let err = stderr(&o);
        let wrote = err
            .lines()
            .find(|l| l.starts_with("wrote"))
            .unwrap_or_else(|| panic!("{err}"))
            .to_string();
        (err, wrote)
    };
    let (err, wrote) = run(&[]);
    let Some(gpu) = err.lines().find(|l| l.starts_with("GPU: ")) else {
        assert!(wrote.contains("on the CPU"), "{err}");
        return;
    };
    if gpu.contains("a software adapter") {
        assert!(
            wrote.contains("on the CPU") && err.contains("--final-image gpu"),
            "{err}"
        );
    } else {
        assert!(wrote.contains("on the GPU"), "{err}");
    }
    assert!(run(&["--final-image", "gpu"]).1.contains("on the GPU"));
    assert!(run(&["--final-image", "cpu"]).1.contains("on the CPU"));
}

/// `--filter-water` on either final image: the shore's far water differs from the unfiltered
/// picture while the near water, which the samples resolve, does not.
#[test]
fn filter_water_changes_only_the_far_water_on_both_final_images() {
    let d = tmpdir("filter-water");
    let common = [
        "render",
        "--scene",
        "shore",
        "--image-size",
        "160x90",
        "--map-size",
        "64x64",
    ];
    for on in ["cpu", "gpu"] {
        let plain = format!("plain-{on}.png");
        let filtered = format!("filtered-{on}.png");
        for (out, extra) in [(&plain, None), (&filtered, Some("--filter-water"))] {
            let mut args = common.to_vec();
            args.extend(["--final-image", on, "--out", out]);
            args.extend(extra);
            let o = caustics(&args, &d);
            let err = stderr(&o);
            assert!(o.status.success(), "{err}");
            // Where there is an adapter (always, with CAUSTICS_REQUIRE_GPU=1), `gpu` traced the
            // image there: no quiet fallback to the CPU counts as the GPU's.
            let required = std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1");
            if on == "gpu" && (required || err.lines().any(|l| l.starts_with("GPU: "))) {
                assert!(
                    err.lines()
                        .any(|l| l.starts_with("wrote") && l.contains("on the GPU")),
                    "{err}"
                );
            }
        }
        let plain = image::open(d.join(plain)).unwrap().to_rgb8();
        let filtered = image::open(d.join(filtered)).unwrap().to_rgb8();
        let band = |y0: u32, y1: u32| {
            let mut sum = 0u64;
            for y in y0..y1 {
                for x in 0..160 {
                    let (a, b) = (plain.get_pixel(x, y), filtered.get_pixel(x, y));
                    sum += (0..3).map(|c| a[c].abs_diff(b[c]) as u64).sum::<u64>();
                }
            }
            sum as f64 / ((y1 - y0) * 160 * 3) as f64
        };
        let (far, near) = (band(26, 34), band(70, 90));
        eprintln!("--filter-water, {on}: far rows move {far:.2} steps, near rows {near:.2}");
        // Measured: the far rows move 4.49 steps on average on both, the near ones not at all.
        assert!(far > 1.0, "{on}: {far}");
        assert_eq!(near, 0.0, "{on}");
    }
}

/// The options of one command's `--help`: every `--name` at the start of an option's line.
fn options_of(command: &str) -> Vec<String> {
    let d = std::env::temp_dir();
    let o = caustics(&[command, "--help"], &d);
    assert!(o.status.success(), "{command} --help: {}", stderr(&o));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let l = l
                .strip_prefix("-v, ")
                .or(l.strip_prefix("-h, "))
                .unwrap_or(l);
            l.strip_prefix("--")
                .map(|rest| rest.split([' ', '<', '=']).next().unwrap_or("").to_string())
        })
        .collect()
}

/// `command --help`'s text for the option `--name`: its line and its description, up to the next
/// option.
fn option_help(command: &str, name: &str) -> Option<String> {
    let d = std::env::temp_dir();
    let o = caustics(&[command, "--help"], &d);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| {
        l.trim_start()
            .strip_prefix(&format!("--{name}"))
            .is_some_and(|rest| rest.is_empty() || rest.starts_with([' ', '<']))
    })?;
    let end = lines[start + 1..]
        .iter()
        .position(|l| l.trim_start().starts_with('-'))
        .map_or(lines.len(), |k| start + 1 + k);
    Some(lines[start..end].join(" "))
}

#[test]
/// One vocabulary: every command that runs techniques on a device takes the same GPU options, the
/// scene, the caustics map's size and the picture's size by the same flags, with the same defaults
/// and ranges; `--help` shows none of the smoke tests' drivers.
fn the_commands_speak_one_vocabulary() {
    let commands = ["render", "bake", "compare", "bench", "view"];
    for command in commands {
        let options = options_of(command);
        let has = |o: &str| options.iter().any(|x| x == o);
        for gpu in ["cpu", "backend", "adapter"] {
            assert!(has(gpu), "{command} lacks --{gpu}: {options:?}");
        }
        // Every command here sizes a caustics map, and by one flag taking one spelling.
        let map = option_help(command, "map-size").unwrap_or_default();
        assert!(map.contains("<N"), "{command}: --map-size <N|WxH>: {map:?}");
        for dialect in ["resolution", "size", "small"] {
            assert!(!has(dialect), "{command} still says --{dialect}");
        }
    }
    for command in ["render", "bake", "bench", "view"] {
        assert!(
            options_of(command).iter().any(|o| o == "scene"),
            "{command} lacks --scene"
        );
    }
    for command in ["render", "bench", "view"] {
        let image = option_help(command, "image-size").unwrap_or_default();
        assert!(
            image.contains("WIDTHxHEIGHT"),
            "{command}: --image-size: {image:?}"
        );
    }
    for command in ["compare", "bench"] {
        assert!(
            options_of(command).iter().any(|o| o == "quick"),
            "{command} lacks --quick"
        );
    }
    // `--raw` names a file wherever it is taken (render's map); bake's extra frames are `--npy`.
    assert!(!options_of("bake").iter().any(|o| o == "raw"));
    // The same default and range wherever a setting is taken.
    let d = std::env::temp_dir();
    for (flag, commands, default) in [
        (
            "cells-per-texel",
            &["render", "compare", "view"][..],
            Some("[default: 4]"),
        ),
        ("supersampling", &["render", "view"][..], None),
    ] {
        for command in commands {
            let help = option_help(command, flag).unwrap_or_default();
            if let Some(default) = default {
                assert!(help.contains(default), "{command} --{flag}: {help}");
            }
            let o = caustics(&[command, &format!("--{flag}"), "17"], &d);
            assert!(
                !o.status.success() && stderr(&o).contains("1..=16"),
                "{command} --{flag} 17: {}",
                stderr(&o)
            );
        }
    }
    let view = options_of("view");
    for hidden in [
        "cycle-techniques",
        "resize-every",
        "drop-every",
        "show-map-at",
        "lose-device-at",
        "report-memory",
    ] {
        assert!(
            !view.iter().any(|o| o == hidden),
            "view --help shows --{hidden}"
        );
    }
}

#[test]
/// The commands whose maps are square refuse a map that is not, by name, before any work (the
/// viewer before it looks for a display).
fn a_square_map_is_asked_for_where_maps_are_square() {
    let d = tmpdir("square");
    for args in [&["compare", "--out", "x"][..], &["view"][..]] {
        let command = args[0];
        let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
            .args(args)
            .args(["--map-size", "32x16"])
            .current_dir(&d)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        let e = stderr(&o);
        assert!(
            !o.status.success() && e.contains("--map-size 32x16") && e.contains("square"),
            "{command}: {e}"
        );
    }
    assert!(!d.join("x").exists());
}

#[test]
/// `--map-size N` is the square N x N, as `WIDTHxHEIGHT` would say it.
fn a_map_size_of_one_number_is_square() {
    let d = tmpdir("map-size-n");
    let o = caustics(
        &[
            "render",
            "--cpu",
            "--technique",
            "procedural",
            "--map-size",
            "24",
            "--raw",
            "n.npy",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let o = caustics(
        &[
            "render",
            "--cpu",
            "--technique",
            "procedural",
            "--map-size",
            "24x24",
            "--raw",
            "wxh.npy",
        ],
        &d,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let n = std::fs::read(d.join("n.npy")).unwrap();
    assert_eq!(n, std::fs::read(d.join("wxh.npy")).unwrap());
    assert!(String::from_utf8_lossy(&n[..128]).contains("(24, 24"));
}

#[test]
/// `caustics` alone says what to try first; `caustics completions SHELL` prints a script that
/// completes the subcommands.
fn a_newcomer_is_told_where_to_start_and_shells_complete_the_commands() {
    let d = std::env::temp_dir();
    let o = caustics(&[], &d);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        out.contains("Try first") && out.contains("caustics render"),
        "{out}"
    );
    for shell in ["bash", "zsh", "fish"] {
        let o = caustics(&["completions", shell], &d);
        assert!(o.status.success(), "{shell}: {}", stderr(&o));
        let script = String::from_utf8_lossy(&o.stdout);
        for command in ["render", "bake", "compare", "bench", "view", "techniques"] {
            assert!(script.contains(command), "{shell}'s script lacks {command}");
        }
    }
    let o = caustics(&["completions", "tcsh"], &d);
    assert!(
        !o.status.success() && stderr(&o).contains("tcsh"),
        "{}",
        stderr(&o)
    );
}

#[test]
/// A `--backend` or `--adapter` that names no adapter here is an error naming it, not the CPU in
/// its place.
fn an_adapter_asked_for_and_absent_is_an_error() {
    let d = tmpdir("adapter");
    let o = caustics(
        &[
            "render",
            "--adapter",
            "no-such-gpu-anywhere",
            "--out",
            "x.png",
        ],
        &d,
    );
    let e = stderr(&o);
    assert!(!o.status.success(), "{e}");
    assert!(e.contains("--adapter no-such-gpu-anywhere"), "{e}");
    assert!(!d.join("x.png").exists());
}

/// The `caustics` command lines of a Markdown file's `sh` blocks, one a line (continued lines
/// joined, a `&&` chain split, comments dropped).
fn commands_in(markdown: &str) -> Vec<Vec<String>> {
    let mut lines = Vec::new();
    let mut in_sh = false;
    let mut pending = String::new();
    for line in markdown.lines() {
        match line.trim() {
            "```sh" => in_sh = true,
            l if l.starts_with("```") => in_sh = false,
            l if in_sh => {
                let l = l.find(" #").map_or(l, |k| &l[..k]);
                match l.strip_suffix('\\') {
                    Some(head) => pending += &format!("{head} "),
                    None => lines.push(std::mem::take(&mut pending) + l),
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for line in lines {
        for part in line.split("&&") {
            let words: Vec<String> = part.split_whitespace().map(String::from).collect();
            if words.first().is_some_and(|w| w == "caustics") {
                out.push(words[1..].to_vec());
            }
        }
    }
    out
}

/// `args` with `flag` set to `value`, in place of the value it had.
fn set(args: &mut Vec<String>, flag: &str, value: &str) {
    match args.iter().position(|a| a == flag) {
        Some(k) => args[k + 1] = value.to_string(),
        None => args.extend([flag.to_string(), value.to_string()]),
    }
}

#[test]
/// Every `caustics` command of the README runs as written, in order in one folder (so that a file
/// one writes is there for the next), with small sizes where the size only sets the time: renders
/// at a 32² map and a 96 x 54 picture, bakes of 2 frames of 16². `view` opens a window, which the
/// viewer's tests do: here its command line must get past the parser to the display check.
fn every_command_in_the_readme_runs() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../README.md")).unwrap();
    let commands = commands_in(&readme);
    assert!(commands.len() >= 8, "{commands:?}");
    let d = tmpdir("readme");
    for mut args in commands {
        let written = args.join(" ");
        let redirect = args.iter().position(|a| a == ">").map(|k| {
            let file = args[k + 1].clone();
            args.truncate(k);
            file
        });
        match args.first().map(String::as_str) {
            Some("render") => {
                set(&mut args, "--map-size", "32");
                set(&mut args, "--image-size", "96x54");
            }
            Some("bake") => {
                set(&mut args, "--map-size", "16");
                set(&mut args, "--frames", "2");
            }
            _ => {}
        }
        let mut command = Command::new(env!("CARGO_BIN_EXE_caustics"));
        command.args(&args).current_dir(&d);
        if args.first().is_some_and(|a| a == "view") {
            command.env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY");
        }
        let o = command.output().unwrap();
        if args.first().is_some_and(|a| a == "view") {
            assert!(
                stderr(&o).contains("opens a window"),
                "`caustics {written}`: {}",
                stderr(&o)
            );
            continue;
        }
        assert!(o.status.success(), "`caustics {written}`: {}", stderr(&o));
        if let Some(file) = redirect {
            std::fs::write(d.join(file), &o.stdout).unwrap();
        }
    }
}

/// Markdown files under `dir`, recursively.
fn markdown_under(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            markdown_under(&path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            out.push(path);
        }
    }
}

#[test]
/// The README and the guides describe the project as it is: no session, issue or stop numbers of
/// the work that made it, no names of the tools it was made with. History is the commit log's.
fn the_docs_tell_no_history_of_their_making() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = vec![root.join("README.md")];
    markdown_under(&root.join("docs"), &mut files);
    assert!(files.len() > 15, "{files:?}");
    let numbered = |text: &str, word: &str| {
        text.match_indices(word).any(|(k, _)| {
            let rest = text[k + word.len()..].trim_start_matches('#');
            rest.starts_with(|c: char| c.is_ascii_digit())
        })
    };
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap().to_lowercase();
        for word in ["session ", "issue ", "issues ", "stop "] {
            assert!(
                !numbered(&text, word),
                "{}: `{word}` with a number",
                file.display()
            );
        }
        for phrase in ["`device` tool", "the draw did", "helper agent"] {
            assert!(!text.contains(phrase), "{}: `{phrase}`", file.display());
        }
    }
}

#[test]
/// Every `caustics` command of the guides (docs/) names flags, values and subcommands the tool
/// takes: each is given to the parser as written with `--help` after it, which clap reaches only
/// when every word before it parsed. (The README's commands run whole, above.)
fn every_command_in_the_guides_parses() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = Vec::new();
    markdown_under(&root.join("docs"), &mut files);
    let mut checked = 0;
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for mut args in commands_in(&text) {
            if let Some(k) = args.iter().position(|a| a == ">" || a == "|") {
                args.truncate(k);
            }
            let written = args.join(" ");
            args.push("--help".into());
            let o = Command::new(env!("CARGO_BIN_EXE_caustics"))
                .args(&args)
                .output()
                .unwrap();
            assert!(
                o.status.success(),
                "{}: `caustics {written}`: {}",
                file.display(),
                stderr(&o)
            );
            checked += 1;
        }
    }
    assert!(checked >= 20, "{checked} commands in the guides");
}

/// GitHub's anchor of a Markdown heading: lower case, punctuation dropped, spaces to hyphens.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a Markdown file's headings (outside code blocks).
fn anchors_of(text: &str) -> Vec<String> {
    let mut fenced = false;
    text.lines()
        .filter(|l| {
            if l.trim_start().starts_with("```") {
                fenced = !fenced;
            }
            !fenced && l.starts_with('#')
        })
        .map(|l| anchor(l.trim_start_matches('#')))
        .collect()
}

#[test]
/// Every relative link of the README and the guides reaches a file of the repository, and a link
/// to a heading (`file.md#heading`, `#heading`) reaches a heading of that file.
fn the_docs_links_resolve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut files = vec![root.join("README.md")];
    markdown_under(&root.join("docs"), &mut files);
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (k, _) in text.match_indices("](") {
            let Some(end) = text[k + 2..].find(')') else {
                continue;
            };
            let link = &text[k + 2..k + 2 + end];
            if link.contains("://") || link.starts_with("mailto:") || link.contains(' ') {
                continue;
            }
            let (path, heading) = link.split_once('#').unwrap_or((link, ""));
            let target = if path.is_empty() {
                file.clone()
            } else {
                file.parent().unwrap().join(path)
            };
            assert!(
                target.exists(),
                "{}: the link `{link}` reaches no file",
                file.display()
            );
            if !heading.is_empty() && target.extension().is_some_and(|e| e == "md") {
                let anchors = anchors_of(&std::fs::read_to_string(&target).unwrap());
                assert!(
                    anchors.iter().any(|a| a == heading),
                    "{}: the link `{link}` reaches no heading of {}",
                    file.display(),
                    target.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked} links");
}
