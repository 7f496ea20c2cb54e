//! Compiles each WGSL file under `src/` as the main module of a WESL program (its `import`s
//! resolved from `src/` as `package::...`) into `$OUT_DIR/wgsl/` under the same path, where
//! `passes!` includes it. Every declaration of the file itself is kept, so a pass whose entry point
//! is added at run time (yuksel's pass 1) keeps the functions it calls.

use std::path::{Path, PathBuf};

use wesl::syntax::{ModulePath, PathOrigin};
use wesl::{CompileOptions, Compiler};

fn wgsl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("src/ is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            wgsl_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            out.push(path);
        }
    }
}

fn main() {
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
        let wgsl = match compiler.compile_module(&src, &module) {
            Ok(wgsl) => wgsl,
            Err(e) => {
                eprintln!("{}: {e}", rel.display());
                std::process::exit(1);
            }
        };
        let dest = out.join(rel);
        std::fs::create_dir_all(dest.parent().expect("a file has a folder"))
            .expect("OUT_DIR is writable");
        std::fs::write(&dest, wgsl.to_string()).expect("OUT_DIR is writable");
    }
}
