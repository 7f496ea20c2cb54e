//! The file loaders fed arbitrary bytes: the scene TOML (`Scene::load`), the height fields
//! (`Grid::load`: `.npy`, `.exr`, 16-bit `.png`) and meshes (`load_obj`).
//!
//! A mutation fuzzer on stable Rust, so that CI runs it: each case is a valid seed file with a stack
//! of random edits (bit flips, bytes and words set to boundary values, cut, repeated or spliced
//! ranges, numbers in text swapped for extreme ones). It is not coverage-guided (cargo-fuzz needs
//! nightly), so the seeds carry it past the formats' magic numbers and headers. A loader passes a
//! case when it returns, `Ok` or `Err`, without a panic, within `HANG` and without asking for a
//! single block larger than `HUGE`: a tiny file must not make a loader reserve gigabytes.
//!
//! CI runs `CASES` cases per loader from a fixed seed. A long run:
//! `CAUSTICS_FUZZ_SECS=600 cargo test --release -p caustics-core --test fuzz_loaders -- --nocapture`
//! (`CAUSTICS_FUZZ_SEED` picks the random stream; a long run without it seeds from the clock and
//! prints the seed). A failing case is saved under `target/fuzz-findings/` and named in the
//! failure; the fixed ones live on in `regressions` below with their bytes.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use caustics_core::grid::Grid;
use caustics_core::mesh::load_obj;
use caustics_core::scene::{BUILTIN_SCENES, Scene};

/// Cases per loader in a CI run (about a second each on two cores).
const CASES: u64 = 400;
/// A single allocation above this from an input of a few kilobytes is a finding. The largest
/// legitimate one is a 16384 x 16384 float32 grid (a beach terrain at `MAX_RESOLUTION`), 1 GiB.
const HUGE: usize = (1 << 30) + (1 << 28);
/// Refused outright (the allocation fails and the process aborts, naming the size), so that a
/// finding cannot take the machine's memory with it.
const REFUSED: usize = 8 << 30;
/// A case that runs longer than this is a hang.
const HANG: Duration = Duration::from_secs(30);

/// The system allocator, watching for single blocks above `HUGE`.
struct Watch;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Watch {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if layout.size() > REFUSED {
            return std::ptr::null_mut();
        }
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if layout.size() > REFUSED {
            return std::ptr::null_mut();
        }
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > REFUSED {
            return std::ptr::null_mut();
        }
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOC: Watch = Watch;

/// The allocation watch and the silenced panic hook are process-wide, so the loaders take turns;
/// each test holds its turn from its first line.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn turn() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

/// xorshift64*: a small deterministic stream, so that a CI failure replays from its seed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn chance(&mut self, one_in: u64) -> bool {
        self.next().is_multiple_of(one_in)
    }
}

/// Values at the edges of integer ranges, where size and offset arithmetic goes wrong.
const WORDS: [u64; 14] = [
    0,
    1,
    2,
    0x7f,
    0xff,
    0x7fff,
    0xffff,
    0x1_0000,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_ffff,
    0x1_0000_0000,
    0x7fff_ffff_ffff_ffff,
    u64::MAX,
];

/// Numbers for text formats: extremes, non-finite spellings, indices past the end, sizes.
const NUMBERS: [&str; 24] = [
    "0",
    "-0",
    "1",
    "-1",
    "2",
    "3",
    "16384",
    "16385",
    "65536",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551616",
    "1e308",
    "1e39",
    "-1e308",
    "1e-320",
    "nan",
    "inf",
    "-inf",
    "0.5",
    "-2147483648",
    "1e999",
    "99999999999999999999999999",
];

fn is_number_byte(b: u8) -> bool {
    b.is_ascii_digit() || matches!(b, b'.' | b'-' | b'+' | b'e' | b'E')
}

/// One random edit of `data`; `other` is another seed to splice from.
fn mutate(rng: &mut Rng, data: &mut Vec<u8>, other: &[u8], text: bool) {
    let len = data.len();
    match rng.below(if text { 12 } else { 10 }) {
        0 if len > 0 => {
            let k = rng.below(len);
            data[k] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let k = rng.below(len);
            data[k] = rng.next() as u8;
        }
        2 if len > 0 => {
            // A boundary word, little or big endian, 1 to 8 bytes wide.
            let width = [1, 2, 4, 8][rng.below(4)].min(len);
            let k = rng.below(len - width + 1);
            let w = WORDS[rng.below(WORDS.len())];
            let bytes = if rng.chance(2) {
                w.to_le_bytes()
            } else {
                w.to_be_bytes()
            };
            data[k..k + width].copy_from_slice(&bytes[..width]);
        }
        3 if len > 0 => {
            let at = rng.below(len);
            data.truncate(at);
        }
        4 if len > 1 => {
            let a = rng.below(len);
            let b = (a + 1 + rng.below(64)).min(len);
            data.drain(a..b);
        }
        5 if len > 0 => {
            // Repeat a range, as a format's repeated records would.
            let a = rng.below(len);
            let b = (a + 1 + rng.below(256)).min(len);
            let chunk = data[a..b].to_vec();
            let at = rng.below(len + 1);
            for _ in 0..1 + rng.below(4) {
                data.splice(at..at, chunk.iter().copied());
            }
        }
        6 => {
            let at = rng.below(len + 1);
            let n = 1 + rng.below(32);
            let bytes: Vec<u8> = (0..n).map(|_| rng.next() as u8).collect();
            data.splice(at..at, bytes);
        }
        7 if !other.is_empty() => {
            // The head of one seed with the tail of another.
            let a = rng.below(len + 1);
            let b = rng.below(other.len());
            data.truncate(a);
            data.extend_from_slice(&other[b..]);
        }
        8 if len > 0 => {
            let a = rng.below(len);
            let b = (a + 1 + rng.below(16)).min(len);
            data[a..b].reverse();
        }
        10 | 11 if text => {
            // Swap a number in the text for an extreme one.
            let starts: Vec<usize> = (0..len)
                .filter(|&k| is_number_byte(data[k]) && (k == 0 || !is_number_byte(data[k - 1])))
                .collect();
            if let Some(&a) = starts.get(rng.below(starts.len())) {
                let b = (a..len).find(|&k| !is_number_byte(data[k])).unwrap_or(len);
                let n = NUMBERS[rng.below(NUMBERS.len())];
                data.splice(a..b, n.bytes());
            }
        }
        _ => {
            // A whole line repeated or dropped, for line-based and TOML text.
            let lines: Vec<usize> = std::iter::once(0)
                .chain((0..len).filter(|&k| data[k] == b'\n').map(|k| k + 1))
                .filter(|&k| k < len)
                .collect();
            if let Some(&a) = lines.get(rng.below(lines.len())) {
                let b = (a..len).find(|&k| data[k] == b'\n').map_or(len, |k| k + 1);
                if rng.chance(2) {
                    data.drain(a..b);
                } else {
                    let line = data[a..b].to_vec();
                    let at = lines[rng.below(lines.len())];
                    data.splice(at..at, line);
                }
            }
        }
    }
}

/// Where a failing case is kept: `target/fuzz-findings/<loader>/`.
fn findings_dir(loader: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../target/fuzz-findings")
        .join(loader)
}

/// Runs `load` on mutated copies of `seeds`, written to `<dir>/case.<ext>`; `dir` may hold files
/// the cases refer to (a scene's height field). Panics, naming the saved cases, if any case
/// panicked, hung or asked for a huge block.
fn fuzz<T, E: std::fmt::Display>(
    loader: &str,
    ext: &str,
    text: bool,
    seeds: &[Vec<u8>],
    dir: &Path,
    load: impl Fn(&Path) -> Result<T, E>,
) {
    let secs: Option<u64> = std::env::var("CAUSTICS_FUZZ_SECS")
        .ok()
        .and_then(|s| s.parse().ok());
    let seed: u64 = match std::env::var("CAUSTICS_FUZZ_SEED") {
        Ok(s) => s.parse().expect("CAUSTICS_FUZZ_SEED is a u64"),
        Err(_) if secs.is_some() => std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos() as u64,
        Err(_) => loader.bytes().fold(0x5eed, |h, b| h * 31 + u64::from(b)),
    };
    let mut rng = Rng(seed | 1);
    let path = dir.join(format!("case.{ext}"));
    let out = findings_dir(loader);

    // A hang cannot be interrupted from here: a watchdog keeps the case and ends the process.
    let started = std::sync::Arc::new(Mutex::new(None::<Instant>));
    let done = std::sync::Arc::new(AtomicBool::new(false));
    {
        let (started, done, path, out) = (started.clone(), done.clone(), path.clone(), out.clone());
        let loader = loader.to_string();
        std::thread::spawn(move || {
            while !done.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(500));
                let since = *started.lock().unwrap();
                if since.is_some_and(|t| t.elapsed() > HANG) {
                    let _ = std::fs::create_dir_all(&out);
                    let kept = out.join(format!(
                        "hang.{}",
                        path.display().to_string().rsplit('.').next().unwrap()
                    ));
                    let _ = std::fs::copy(&path, &kept);
                    eprintln!(
                        "{loader}: a case ran past {HANG:?}; kept as {}",
                        kept.display()
                    );
                    std::process::abort();
                }
            }
        });
    }

    eprintln!(
        "{loader}: seed {seed}; {}; a case that aborts the process is left at {}",
        secs.map_or(format!("{CASES} cases"), |s| format!("{s} s")),
        path.display()
    );
    let deadline = secs.map(|s| Instant::now() + Duration::from_secs(s));
    let mut findings = Vec::new();
    let (mut cases, mut refused, mut slowest) = (0u64, 0u64, Duration::ZERO);
    let quiet = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    loop {
        let more = match deadline {
            Some(d) => Instant::now() < d,
            None => cases < CASES,
        };
        if !more {
            break;
        }
        let mut data = seeds[rng.below(seeds.len())].clone();
        let other = &seeds[rng.below(seeds.len())];
        for _ in 0..1 + rng.below(6) {
            mutate(&mut rng, &mut data, other, text);
        }
        std::fs::write(&path, &data).unwrap();
        LARGEST.store(0, Ordering::Relaxed);
        let t = Instant::now();
        *started.lock().unwrap() = Some(t);
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| load(&path)));
        *started.lock().unwrap() = None;
        let elapsed = t.elapsed();
        slowest = slowest.max(elapsed);
        let largest = LARGEST.load(Ordering::Relaxed);
        let problem = match &result {
            Err(panic) => Some(format!(
                "panicked: {}",
                panic
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| panic.downcast_ref::<&str>().copied())
                    .unwrap_or("?")
            )),
            Ok(_) if largest > HUGE => Some(format!(
                "allocated a block of {largest} bytes from a {}-byte file",
                data.len()
            )),
            Ok(Err(_)) => {
                refused += 1;
                None
            }
            Ok(Ok(_)) => None,
        };
        if let Some(problem) = problem {
            std::fs::create_dir_all(&out).unwrap();
            let kept = out.join(format!("case-{seed}-{cases}.{ext}"));
            std::fs::write(&kept, &data).unwrap();
            findings.push(format!("{}: {problem}", kept.display()));
        }
        cases += 1;
    }
    std::panic::set_hook(quiet);
    done.store(true, Ordering::Relaxed);
    eprintln!(
        "{loader}: {cases} cases, {refused} refused with an error, {} findings, slowest {slowest:?}",
        findings.len()
    );
    assert!(findings.is_empty(), "{loader}:\n{}", findings.join("\n"));
}

/// A fresh directory for one loader's cases.
fn case_dir(loader: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("caustics-fuzz-{loader}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn small_grid() -> Grid {
    Grid::from_fn(5, 3, |i, j| 0.01 * (i as f32 - 0.5 * j as f32))
}

fn grid_seed(ext: &str) -> Vec<u8> {
    let dir = case_dir("seeds");
    let path = dir.join(format!("seed.{ext}"));
    match ext {
        "npy" => small_grid().write_npy(&path).unwrap(),
        "exr" => small_grid().write_exr(&path).unwrap(),
        _ => unreachable!(),
    }
    std::fs::read(path).unwrap()
}

/// A hand-written float64 `.npy` (the writer only writes float32).
fn npy_f64() -> Vec<u8> {
    npy_f64_claiming("(2, 2)")
}

/// A float64 `.npy` of four samples whose header claims `shape`.
fn npy_f64_claiming(shape: &str) -> Vec<u8> {
    let header = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    let mut h = header.as_bytes().to_vec();
    while !(10 + h.len() + 1).is_multiple_of(64) {
        h.push(b' ');
    }
    h.push(b'\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(h.len() as u16).to_le_bytes());
    out.extend_from_slice(&h);
    for v in [0.0f64, 0.01, -0.01, 0.02] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

fn png16(width: u32, height: u32) -> Vec<u8> {
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(width, height, |x, y| {
        image::Luma([(x * 9000 + y * 3000) as u16])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}

const OBJ_SEEDS: [&str; 3] = [
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\n\
     o b\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf -4 -3 -2 -1\n",
    "g quad\nv -1 -1 0.5\nv 1 -1 0.5\nv 1 1 0.5\nv -1 1 0.5\nvn 0 0 -1\nf 1//1 2//1 3//1 4//1\nl 1 2\np 3\n",
];

#[test]
fn npy_height_fields() {
    let _turn = turn();
    let dir = case_dir("npy");
    let seeds = vec![grid_seed("npy"), npy_f64()];
    fuzz("npy", "npy", false, &seeds, &dir, |p| {
        Grid::load(p, [0.0, 1.0])
    });
}

#[test]
fn exr_height_fields() {
    let _turn = turn();
    let dir = case_dir("exr");
    fuzz("exr", "exr", false, &[grid_seed("exr")], &dir, |p| {
        Grid::load(p, [0.0, 1.0])
    });
}

#[test]
fn png16_height_fields() {
    let _turn = turn();
    let dir = case_dir("png");
    let seeds = vec![png16(5, 3), png16(1, 1), png16(17, 2)];
    fuzz("png", "png", false, &seeds, &dir, |p| {
        Grid::load(p, [-0.05, 0.05])
    });
}

#[test]
fn obj_meshes() {
    let _turn = turn();
    let dir = case_dir("obj");
    let seeds: Vec<Vec<u8>> = OBJ_SEEDS.iter().map(|s| s.as_bytes().to_vec()).collect();
    fuzz("obj", "obj", true, &seeds, &dir, load_obj);
}

#[test]
fn scene_files() {
    let _turn = turn();
    // Scenes that name a height field and a mesh beside them, so that cases reach those paths too.
    let dir = case_dir("scene");
    small_grid().write_npy(&dir.join("h.npy")).unwrap();
    Grid::from_fn(4, 4, |i, j| 0.1 * (i + j) as f32)
        .write_npy(&dir.join("t.npy"))
        .unwrap();
    std::fs::write(dir.join("a.png"), png16(4, 4)).unwrap();
    std::fs::write(dir.join("m.obj"), OBJ_SEEDS[0]).unwrap();
    let mut seeds: Vec<Vec<u8>> = BUILTIN_SCENES
        .iter()
        .map(|(_, text)| text.as_bytes().to_vec())
        .collect();
    seeds.push(
        b"[water]\nsize = 2.0\ndepth = 1.0\nheightfield = \"h.npy\"\nheightfield_range = [-0.05, 0.05]\n\n\
          [floor]\nterrain = { heightfield = \"t.npy\" }\nalbedo = \"a.png\"\n\n\
          [[objects]]\nshape = { kind = \"mesh\", path = \"m.obj\" }\nposition = [1.0, 1.0, 0.0]\nscale = 0.5\n\n\
          [light]\ndirection = [0.2, 0.1, -1.0]\n\n\
          [caustics]\nresolution = [64, 64]\ntechnique = \"yuksel\"\n"
            .to_vec(),
    );
    for seed in &seeds[4..] {
        std::fs::write(dir.join("check.toml"), seed).unwrap();
        Scene::load(&dir.join("check.toml")).expect("the seed scene is valid");
    }
    fuzz("scene", "toml", true, &seeds, &dir, Scene::load);
}

/// Every case the fuzzer found, with its bytes (`tests/fuzz_regressions/`), refused with an error
/// that names the problem, without a panic or a huge allocation.
#[test]
fn regressions() {
    let _turn = turn();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz_regressions");
    let cases = [
        (
            // A 475-byte EXR whose data window is 65 535 x ~10¹²: exr 1.74 reserved its samples first.
            "exr-huge-data-window.exr",
            "is larger than the largest height field taken",
        ),
        // 466 bytes, a data window of 134 217 725 x 3: the same, one long row.
        (
            "exr-long-data-window.exr",
            "is larger than the largest height field taken",
        ),
        // Version-2 .npy headers whose 4-byte header length reads as 1.7 to 2.1 GB (a mutated
        // length field, or a version-1 file's header text read as one): npyz reserved it.
        ("npy-header-1.npy", "the header claims 1937440886 bytes"),
        ("npy-header-2.npy", "the header claims"),
        ("npy-header-3.npy", "the header claims"),
    ];
    // Not a finding, a guard beside the header's: a shape the samples cannot fill.
    let crafted = case_dir("regressions").join("npy-shape-beyond-the-file.npy");
    std::fs::write(&crafted, npy_f64_claiming("(1048576, 1048576)")).unwrap();
    let crafted = crafted.to_str().unwrap();
    let cases = cases.into_iter().chain([(
        crafted,
        "needs more than the 32 bytes of samples the file holds",
    )]);
    for (file, problem) in cases {
        let path = dir.join(file);
        LARGEST.store(0, Ordering::Relaxed);
        let result = match path.extension().and_then(|e| e.to_str()) {
            Some("toml") => Scene::load(&path).map(|_| ()),
            Some("obj") => load_obj(&path).map(|_| ()),
            _ => Grid::load(&path, [0.0, 1.0]).map(|_| ()),
        };
        let e = result.expect_err(file).to_string();

        assert!(e.contains(problem) && e.contains(file), "{file}: {e}");
        eprintln!("{file}: {e}");
        let largest = LARGEST.load(Ordering::Relaxed);
        assert!(largest < 1 << 20, "{file}: a block of {largest} bytes");
    }
}
