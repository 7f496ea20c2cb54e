//! Every WGSL pass, compiled by build.rs with the modules it imports, parses and validates with naga.
//! Needs no GPU, so a shader error fails CI even where no adapter exists. The passes are the
//! registry's (`caustics_gpu::registry::all_passes`), and every `.wgsl` file of the crate must be
//! one of them or a module they import, so a pass left out of its technique's list fails here.

mod wgsl;

use std::path::{Path, PathBuf};

use caustics_gpu::registry::all_passes;
use wgsl::{validated, validated_wgsl, wgsl_struct_size};

#[test]
fn every_pass_parses_and_validates() {
    let passes = all_passes();
    assert!(passes.len() >= 55, "{}", passes.len());
    for pass in passes {
        validated(pass);
    }
}

/// The modules an application's material takes (the shading rule and the maps' sampling) work
/// pasted ahead of its own WGSL, as `caustics_gpu::shaders` documents: no import, no binding, and
/// their functions callable from a fragment shader of its own.
#[test]
fn the_shading_modules_paste_ahead_of_an_applications_shader() {
    use caustics_gpu::shaders::{CAUSTICS_LIGHT, CAUSTICS_SAMPLING};
    for module in [CAUSTICS_LIGHT, CAUSTICS_SAMPLING] {
        assert!(
            !module
                .lines()
                .any(|l| l.starts_with("import ") || l.starts_with("@group")),
            "{module}"
        );
    }
    let material = r#"
@group(0) @binding(0) var map: texture_2d<f32>;
@fragment fn fs(@location(0) p: vec3<f32>, @location(1) n: vec3<f32>) -> @location(0) vec4<f32> {
    let toward_sun = sun_under_water(normalize(vec3<f32>(0.3, 0.2, 0.9)), 1.333);
    let flat = flat_water_light(vec3<f32>(0.45, 0.09, 0.05), 1.0 - p.z, toward_sun, n);
    let c = caustics_filtered(map, map, 0u, p.xy, dpdx(p.xy), dpdy(p.xy), 4.0, true, flat, true);
    return vec4<f32>(sun_through_water(c, 0.9, 0.97, 1.0), 1.0);
}"#;
    validated_wgsl(
        "an application's material",
        &format!("{CAUSTICS_LIGHT}{CAUSTICS_SAMPLING}{material}"),
    );
}

fn wgsl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            wgsl_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            out.push(path);
        }
    }
}

/// The files under `src/` a pass's main module reaches through its `import package::...` lines,
/// itself included.
fn reached(src: &Path, file: &str, out: &mut Vec<String>) {
    if out.iter().any(|f| f == file) {
        return;
    }
    out.push(file.to_string());
    let text = std::fs::read_to_string(src.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    for import in text.split("import package::").skip(1) {
        let path = import.split(';').next().unwrap();
        let module = match path.split_once("::{") {
            Some((module, _)) => module,
            None => path.rsplit_once("::").map_or(path, |(module, _)| module),
        };
        reached(src, &format!("{}.wgsl", module.replace("::", "/")), out);
    }
}

/// The files every registered pass reaches.
fn registered_files(src: &Path) -> Vec<String> {
    let mut files = Vec::new();
    for pass in all_passes() {
        reached(src, pass.file, &mut files);
    }
    files
}

/// Every `.wgsl` file under `src/` is a registered pass's main module or a module one imports.
#[test]
fn every_wgsl_file_is_a_registered_pass_or_a_module_it_imports() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let registered = registered_files(&src);
    let mut files = Vec::new();
    wgsl_files(&src, &mut files);
    assert!(files.len() >= 60, "{}", files.len());
    for file in files {
        let rel = file
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        assert!(
            registered.contains(&rel),
            "{rel} is in no registered pass: list it in its technique's PASSES (or the frame's)"
        );
    }
}

#[test]
fn uniform_structs_match_their_wgsl_struct_size() {
    let size_of = |name: &str| wgsl_struct_size(&caustics_gpu::probe::PROBE, name);
    use caustics_gpu::probe::{ProbeIn, ProbeOut};
    use caustics_gpu::water::{GpuProceduralWave, GpuSineWave};
    assert_eq!(size_of("SineWave"), std::mem::size_of::<GpuSineWave>());
    assert_eq!(
        size_of("ProceduralWave"),
        std::mem::size_of::<GpuProceduralWave>()
    );
    assert_eq!(size_of("ProbeIn"), std::mem::size_of::<ProbeIn>());
    assert_eq!(size_of("ProbeOut"), std::mem::size_of::<ProbeOut>());
}

#[test]
fn water_uniform_structs_match_their_wgsl_struct_size() {
    use caustics_gpu::water::ocean::{FftStage, OCEAN_FFT, OCEAN_SPECTRUM, SpectrumParams};
    use caustics_gpu::water::ripple::{RIPPLE_DROP, RIPPLE_STEP, RippleDrop, RippleStep};
    use std::mem::size_of;
    assert_eq!(
        wgsl_struct_size(&OCEAN_SPECTRUM, "SpectrumParams"),
        size_of::<SpectrumParams>()
    );
    assert_eq!(
        wgsl_struct_size(&OCEAN_FFT, "FftStage"),
        size_of::<FftStage>()
    );
    assert_eq!(
        wgsl_struct_size(&RIPPLE_STEP, "RippleStep"),
        size_of::<RippleStep>()
    );
    assert_eq!(
        wgsl_struct_size(&RIPPLE_DROP, "RippleDrop"),
        size_of::<RippleDrop>()
    );
}

#[test]
fn yuksel_pass1_validates_for_every_target_count() {
    for targets in 1..=8 {
        let source = caustics_gpu::yuksel::pass1_source(targets);
        validated_wgsl(&format!("{targets} targets"), &source);
    }
    assert_eq!(
        wgsl_struct_size(&caustics_gpu::yuksel::PASS2, "Yuksel"),
        std::mem::size_of::<caustics_gpu::yuksel::YukselUniform>()
    );
}

#[test]
fn final_image_structs_match_their_wgsl_struct_size() {
    use caustics_gpu::bvh::{GpuBvhNode, GpuBvhTriangle};
    use caustics_gpu::final_image::{FINAL_IMAGE, FinalImageUniform, GpuObject};
    use std::mem::size_of;
    assert_eq!(
        wgsl_struct_size(&FINAL_IMAGE, "FinalImage"),
        size_of::<FinalImageUniform>()
    );
    assert_eq!(
        wgsl_struct_size(&FINAL_IMAGE, "Object"),
        size_of::<GpuObject>()
    );
    assert_eq!(
        wgsl_struct_size(&FINAL_IMAGE, "BvhNode"),
        size_of::<GpuBvhNode>()
    );
    assert_eq!(
        wgsl_struct_size(&FINAL_IMAGE, "BvhTriangle"),
        size_of::<GpuBvhTriangle>()
    );
}

#[test]
fn procedural_uniform_matches_its_wgsl_struct_size() {
    use caustics_gpu::procedural::{ProceduralUniform, RESAMPLE, SCREEN, TARGET, VERTEX};
    for pass in [&VERTEX, &SCREEN, &TARGET, &RESAMPLE] {
        assert_eq!(
            wgsl_struct_size(pass, "Procedural"),
            std::mem::size_of::<ProceduralUniform>(),
            "{}",
            pass.name
        );
    }
}

/// `scripts/mutate-passes.sh`'s table follows the code: each mutation names a registered pass's
/// file (or a module the passes import) and the exact text it changes is still there, so no line of
/// the table goes stale unseen.
#[test]
fn the_mutation_table_names_registered_passes_and_their_text() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let script = std::fs::read_to_string(root.join("scripts/mutate-passes.sh")).unwrap();
    let registered = registered_files(&root.join("crates/gpu/src"));
    let (mut lines, mut stale) = (0, Vec::new());
    let table = script
        .split_once("MUTATIONS=$(cat <<EOF\n")
        .and_then(|(_, rest)| rest.split_once("\nEOF\n"))
        .expect("the script's MUTATIONS table")
        .0;
    for line in table.lines().filter(|l| !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split(" @@ ").collect();
        let [name, file, old, _new, _tests] = fields[..] else {
            panic!("a mutation line has five fields: {line}");
        };
        let rel = file
            .strip_prefix("$S/")
            .unwrap_or_else(|| panic!("{name}: {file} is not under $S"));
        let text = std::fs::read_to_string(root.join("crates/gpu/src").join(rel))
            .unwrap_or_else(|e| panic!("{name}: {rel}: {e}"));
        if !text.contains(old) {
            stale.push(format!("{name}: `{old}` is not in {rel}"));
        }
        if !registered.iter().any(|f| f == rel) {
            stale.push(format!("{name}: {rel} is no registered pass's"));
        }
        lines += 1;
    }
    assert!(
        stale.is_empty(),
        "stale mutation lines:\n{}",
        stale.join("\n")
    );
    assert!(lines >= 60, "{lines} mutation lines");
}
