//! Puts each pass's WGSL in `$OUT_DIR/wgsl/` under its path in `src/`, where `passes!` includes
//! it. With the `wesl` feature (on in this repository's own builds), every WGSL file under `src/`
//! is compiled as the main module of a WESL program, its `import`s resolved from `src/` as
//! `package::...`; every declaration of the file itself is kept, so a pass whose entry point is
//! added at run time (yuksel's pass 1) keeps the functions it calls, and the declarations are put
//! in the order of their names, so that the output is the same from one build to the next. Without
//! it, the copies of that output kept in `compiled/` are used, so an application builds no shader
//! compiler; a test (`tests/compiled_wgsl.rs`) holds the copies to the sources.

use std::path::{Path, PathBuf};

fn wgsl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("the folder is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            wgsl_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            out.push(path);
        }
    }
}

fn write(dest: &Path, wgsl: &str) {
    std::fs::create_dir_all(dest.parent().expect("a file has a folder"))
        .expect("OUT_DIR is writable");
    std::fs::write(dest, wgsl).expect("OUT_DIR is writable");
}

#[cfg(feature = "wesl")]
fn main() {
    use wesl::syntax::{ModulePath, PathOrigin};
    use wesl::{CompileOptions, Compiler};
    use wgsl_parse::SyntaxNode;

    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("wgsl");
    println!("cargo::rerun-if-changed=src");
    let compiler = Compiler::new(CompileOptions {
        keep_main: true,
        ..CompileOptions::default()
    });
    let mut files = Vec::new();
    wgsl_files(&src, &mut files);
    for file in files {
        let rel = file.strip_prefix(&src).expect("under src/");
        let components = rel
            .with_extension("")
            .iter()
            .map(|c| c.to_string_lossy().into_owned())
            .collect();
        let module = ModulePath::new(PathOrigin::Absolute, components);
        match compiler.compile_module(&src, &module) {
            Ok(mut wgsl) => {
                // wesl emits the imported declarations in a hash map's order, different from one
                // build to the next; WGSL takes module-scope declarations in any order, and by
                // name they come out the same every time, as `compiled/` needs.
                wgsl.syntax
                    .global_declarations
                    .sort_by_cached_key(|d| d.ident().map(|i| i.to_string()));
                write(&out.join(rel), &wgsl.to_string())
            }
            Err(e) => {
                eprintln!("{}: {e}", rel.display());
                std::process::exit(1);
            }
        }
    }
}

#[cfg(not(feature = "wesl"))]
fn main() {
    let compiled = Path::new(env!("CARGO_MANIFEST_DIR")).join("compiled");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets OUT_DIR")).join("wgsl");
    println!("cargo::rerun-if-changed=compiled");
    let mut files = Vec::new();
    wgsl_files(&compiled, &mut files);
    for file in files {
        let rel = file.strip_prefix(&compiled).expect("under compiled/");
        let wgsl = std::fs::read_to_string(&file).expect("compiled/ is readable");
        write(&out.join(rel), &wgsl);
    }
}
