//! `compiled/` holds the WGSL build.rs makes from the WESL sources of every pass (the registry's,
//! the files `passes!` embeds, each with the modules it imports inlined), for builds without the
//! `wesl` feature (an application's): this test, built with the feature, holds every copy equal to
//! what the sources compile to now. `CAUSTICS_BLESS=1` rewrites `compiled/` from them.

use std::path::{Path, PathBuf};

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

fn relative(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    if dir.exists() {
        wgsl_files(dir, &mut files);
    }
    let mut rel: Vec<PathBuf> = files
        .iter()
        .map(|f| f.strip_prefix(dir).unwrap().to_path_buf())
        .collect();
    rel.sort();
    rel
}

/// Built without the `wesl` feature the shaders came from `compiled/` itself, and the comparison
/// would hold by construction: the test is then compiled out and cannot pass.
#[cfg(feature = "wesl")]
#[test]
fn the_compiled_copies_are_the_sources_compiled() {
    let fresh = Path::new(env!("OUT_DIR")).join("wgsl");
    let kept = Path::new(env!("CARGO_MANIFEST_DIR")).join("compiled");
    let mut names: Vec<PathBuf> = caustics_gpu::registry::all_passes()
        .iter()
        .map(|p| PathBuf::from(p.file))
        .collect();
    names.sort();
    names.dedup();
    assert!(names.len() >= 55, "{} passes", names.len());
    if std::env::var("CAUSTICS_BLESS").is_ok_and(|v| v == "1") {
        if kept.exists() {
            std::fs::remove_dir_all(&kept).unwrap();
        }
        for rel in &names {
            let dest = kept.join(rel);
            std::fs::create_dir_all(dest.parent().unwrap()).unwrap();
            std::fs::copy(fresh.join(rel), dest).unwrap();
        }
        return;
    }
    let stale: Vec<String> = names
        .iter()
        .filter(|rel| {
            std::fs::read_to_string(fresh.join(rel)).ok()
                != std::fs::read_to_string(kept.join(rel)).ok()
        })
        .map(|rel| rel.display().to_string())
        .collect();
    let extra: Vec<String> = relative(&kept)
        .into_iter()
        .filter(|rel| !names.contains(rel))
        .map(|rel| rel.display().to_string())
        .collect();
    assert!(
        stale.is_empty() && extra.is_empty(),
        "crates/gpu/compiled/ is not what the WESL sources compile to (changed or new: {stale:?}; \
         no longer made: {extra:?}); rewrite it with \
         `CAUSTICS_BLESS=1 cargo test --release -p caustics-gpu --test compiled_wgsl`"
    );
}
