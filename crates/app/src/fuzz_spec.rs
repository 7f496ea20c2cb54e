//! The technique spec parser (`--technique name[:key=value,...]`, [`Spec`]'s `FromStr`) fed
//! arbitrary text: mutated valid specs, with the parser's own punctuation and TOML's nesting
//! spliced in. A case passes when parsing returns, `Ok` or `Err`, without a panic and quickly, and
//! an accepted spec goes on through `over` as `caustics render` takes it.
//!
//! CI runs `CASES` cases from a fixed seed; a long run:
//! `CAUSTICS_FUZZ_SECS=600 cargo test --release -p caustics --bin caustics fuzz_spec -- --nocapture`
//! (`CAUSTICS_FUZZ_SEED` picks the stream). The core crate's loaders have the same kind of fuzzer,
//! `crates/core/tests/fuzz_loaders.rs`; docs/maintainers/reliability.md lists what both found.

use std::time::{Duration, Instant};

use crate::techniques::Spec;

const CASES: u64 = 5000;
/// One parse longer than this is a hang. A parse takes microseconds, 100 000-deep TOML nesting
/// milliseconds; the slowest of 7.3 million cases on a loaded machine under `nice` took 1.05 s.
const SLOW: Duration = Duration::from_secs(10);

/// The seeds, from the registry: every entry bare, every entry with every parameter at a value
/// its descriptor accepts, and each entry's first parameter given a table and an array.
fn seeds() -> Vec<String> {
    use caustics_core::techniques::REGISTRY;
    let mut out = Vec::new();
    for d in REGISTRY {
        out.push(d.name.to_string());
        let kv: Vec<String> = d
            .params
            .iter()
            .filter_map(|p| {
                let v = p.default.value().or_else(|| match p.kind {
                    caustics_core::techniques::describe::Kind::Int { max, .. } => {
                        Some(toml::Value::Integer(max))
                    }
                    caustics_core::techniques::describe::Kind::Path => {
                        Some(toml::Value::String("map.png".into()))
                    }
                    _ => None,
                })?;
                Some(format!("{}={v}", p.key))
            })
            .collect();
        if !kv.is_empty() {
            out.push(format!("{}:{}", d.name, kv.join(",")));
        }
        if let Some(p) = d.params.first() {
            out.push(format!("{}:{}=[1,2,3],{}={{a=1}}", d.name, p.key, p.key));
        }
    }
    out
}

static SEEDS: std::sync::LazyLock<Vec<String>> = std::sync::LazyLock::new(seeds);

/// Fragments the parser splits on or hands to TOML, and the pieces of the registry's names (a
/// variant's suffix, a table's name with the dash a variant adds).
static TOKENS: std::sync::LazyLock<Vec<String>> = std::sync::LazyLock::new(|| {
    let mut t: Vec<String> = FIXED_TOKENS.iter().map(|s| s.to_string()).collect();
    for d in caustics_core::techniques::REGISTRY {
        if let Some(suffix) = d.name.strip_prefix(d.table).filter(|s| !s.is_empty()) {
            t.push(suffix.to_string());
            t.push(format!("{}-", d.table));
        }
    }
    t.sort();
    t.dedup();
    t
});

const FIXED_TOKENS: [&str; 18] = [
    ":",
    ",",
    "=",
    "\"",
    "'''",
    "[",
    "]",
    "{",
    "}",
    "\n",
    "variant",
    "1e999",
    "-9223372036854775809",
    "nan",
    "inf",
    "\u{0}",
    "é",
    "\\u0000",
];

/// xorshift64*, as in `crates/core/tests/fuzz_loaders.rs`.
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
}

fn mutate(rng: &mut Rng, data: &mut Vec<u8>) {
    let len = data.len();
    match rng.below(7) {
        0 if len > 0 => {
            let k = rng.below(len);
            data[k] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let a = rng.below(len);
            let b = (a + 1 + rng.below(8)).min(len);
            data.drain(a..b);
        }
        2 if len > 0 => {
            let a = rng.below(len);
            let b = (a + 1 + rng.below(16)).min(len);
            let chunk = data[a..b].to_vec();
            let at = rng.below(len + 1);
            data.splice(at..at, chunk);
        }
        3 => {
            // Nesting, deep enough to find a recursive descent without a depth limit.
            let deepest = if rng.below(8) == 0 { 100_000 } else { 64 };
            let depth = 1 + rng.below(deepest);
            let (open, close) = if rng.below(2) == 0 {
                ("[", "]")
            } else {
                ("{a=", "}")
            };
            let at = rng.below(len + 1);
            let mut nest = open.repeat(depth);
            if rng.below(2) == 0 {
                nest.push_str(&close.repeat(depth));
            }
            data.splice(at..at, nest.into_bytes());
        }
        4 => {
            let other = SEEDS[rng.below(SEEDS.len())].as_bytes();
            let a = rng.below(len + 1);
            let b = rng.below(other.len());
            data.truncate(a);
            data.extend_from_slice(&other[b..]);
        }
        _ => {
            let t = &TOKENS[rng.below(TOKENS.len())];
            let at = rng.below(len + 1);
            data.splice(at..at, t.bytes());
        }
    }
}

/// Parse `text` as `caustics render --technique` does, and use what it accepts; whether it did.
fn exercise(text: &str) -> bool {
    let Ok(spec) = text.parse::<Spec>() else {
        return false;
    };
    let _ = spec.own();
    let mut base = toml::Table::new();
    for d in caustics_core::techniques::REGISTRY {
        base.insert(d.table.to_string(), toml::Value::Table(d.defaults()));
    }
    let merged = spec.over(&base);
    assert!(merged.params.contains_key(merged.entry.table), "{text:?}");
    true
}

#[test]
fn fuzz_spec_parser_never_panics_or_hangs() {
    let secs: Option<u64> = std::env::var("CAUSTICS_FUZZ_SECS")
        .ok()
        .and_then(|s| s.parse().ok());
    let seed: u64 = match std::env::var("CAUSTICS_FUZZ_SEED") {
        Ok(s) => s.parse().expect("CAUSTICS_FUZZ_SEED is a u64"),
        Err(_) if secs.is_some() => std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos() as u64,
        Err(_) => 0x5eed_5bec,
    };
    eprintln!("spec: seed {seed}");
    let mut rng = Rng(seed | 1);
    let deadline = secs.map(|s| Instant::now() + Duration::from_secs(s));
    let (mut cases, mut accepted, mut slowest) = (0u64, 0u64, Duration::ZERO);
    let mut findings = Vec::new();
    let quiet = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    while deadline.map_or(cases < CASES, |d| Instant::now() < d) {
        let mut data = SEEDS[rng.below(SEEDS.len())].as_bytes().to_vec();
        for _ in 0..1 + rng.below(5) {
            mutate(&mut rng, &mut data);
        }
        let text = String::from_utf8_lossy(&data).into_owned();
        let t = Instant::now();
        let result = std::panic::catch_unwind(|| exercise(&text));
        let elapsed = t.elapsed();
        slowest = slowest.max(elapsed);
        if result.is_err() || elapsed > SLOW {
            let shown: String = text.chars().take(200).collect();
            findings.push(format!(
                "{}: {shown:?} ({} chars)",
                if result.is_err() { "panicked" } else { "slow" },
                text.len()
            ));
        }
        accepted += u64::from(matches!(result, Ok(true)));
        cases += 1;
    }
    std::panic::set_hook(quiet);
    eprintln!(
        "spec: {cases} cases, {accepted} accepted, {} findings, slowest {slowest:?}",
        findings.len()
    );
    assert!(findings.is_empty(), "{}", findings.join("\n"));
}
