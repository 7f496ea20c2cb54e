//! The registry's descriptors agree with the techniques they describe: the ranges the parser
//! enforces are the ranges each technique's own checks accept, the defaults are the techniques'
//! own, every parameter is reachable through the one spec parser, and docs/techniques.md's table
//! is the registry's.

use caustics_core::techniques::describe::{Kind, ParamDefault, check_value};
use caustics_core::techniques::{REGISTRY, Spec, find};

/// Every name once; every parameter key once within its entry; every entry found by name.
#[test]
fn names_and_keys_are_unique() {
    for (k, d) in REGISTRY.iter().enumerate() {
        assert!(
            REGISTRY[..k].iter().all(|o| o.name != d.name),
            "{} twice",
            d.name
        );
        assert_eq!(find(d.name).unwrap().name, d.name);
        for (j, p) in d.params.iter().enumerate() {
            assert!(
                d.params[..j].iter().all(|o| o.key != p.key),
                "{}.{} twice",
                d.name,
                p.key
            );
            assert!(
                !p.doc.is_empty() && !p.label.is_empty(),
                "{}.{}",
                d.name,
                p.key
            );
        }
    }
    assert_eq!(REGISTRY.iter().filter(|d| d.reference).count(), 1);
}

/// An integer's range ends are accepted by the descriptor and by the technique's own reading
/// of its table; one past each end is refused by the parser with an error naming the key and
/// the range.
#[test]
fn integer_ranges_are_the_techniques_own() {
    let mut checked = 0;
    for d in REGISTRY {
        for p in d.params {
            let Kind::Int {
                min,
                max,
                parity,
                power_of_two,
            } = p.kind
            else {
                continue;
            };
            let fit = |i: i64| {
                let mut i = i;
                if let Some(q) = parity
                    && i.rem_euclid(2) != q
                {
                    i += if i == max { -1 } else { 1 };
                }
                if power_of_two {
                    i = (i.max(1) as u64).next_power_of_two() as i64;
                    if i > max {
                        i /= 2;
                    }
                }
                i
            };
            for i in [fit(min), fit(max)] {
                let text = format!("{}:{}={i}", d.name, p.key);
                let spec: Spec = text
                    .parse()
                    .unwrap_or_else(|e| panic!("{text} refused: {e}"));
                (d.validate)(&spec.params).unwrap_or_else(|e| panic!("{text}: {e}"));
            }
            for i in [min - 1, max + 1] {
                let text = format!("{}:{}={i}", d.name, p.key);
                let e = text.parse::<Spec>().unwrap_err().to_string();
                assert!(
                    e.contains(p.key)
                        && e.contains(&min.to_string())
                        && e.contains(&max.to_string()),
                    "{text}: {e}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 40, "{checked}");
}

/// A number's range is refused past its ends; a wrong type and an unknown key are refused with
/// the key named and, for an unknown key, the parameters listed.
#[test]
fn bad_values_and_keys_are_named() {
    for d in REGISTRY {
        for p in d.params {
            if let Kind::Float { min, max } = p.kind {
                for f in [min - 1.0, max * 2.0 + 1.0] {
                    let e = format!("{}:{}={f:?}", d.name, p.key)
                        .parse::<Spec>()
                        .unwrap_err()
                        .to_string();
                    assert!(e.contains(p.key) && e.contains("between"), "{e}");
                }
            }
            let wrong = match p.kind {
                Kind::Bool | Kind::Int { .. } | Kind::Float { .. } => "\"text\"",
                Kind::Choice(_) | Kind::Path => "[1, 2]",
            };
            let e = format!("{}:{}={wrong}", d.name, p.key)
                .parse::<Spec>()
                .unwrap_err()
                .to_string();
            assert!(e.contains(p.key), "{e}");
        }
        let e = format!("{}:no_such_key=1", d.name)
            .parse::<Spec>()
            .unwrap_err()
            .to_string();
        assert!(e.contains("no_such_key"), "{e}");
        for p in d.params {
            assert!(e.contains(p.key), "{e} does not list {}", p.key);
        }
    }
    let e = "no-such-technique".parse::<Spec>().unwrap_err().to_string();
    for d in REGISTRY {
        assert!(e.contains(d.name), "{e}");
    }
}

/// The defaults each descriptor states are the technique's own (its `Default`, serialized), and
/// every choice's words are what its serde enum reads.
#[test]
fn defaults_are_the_techniques_own() {
    let mut compared = 0;
    for d in REGISTRY {
        let table = (d.own_defaults)();
        if table.is_empty() {
            assert!(d.params.is_empty(), "{} has no serde table here", d.name);
            continue;
        }
        for p in d.params {
            if d.fixed.iter().any(|(k, _)| *k == p.key) {
                continue;
            }
            match (p.default.value(), table.get(p.key)) {
                (Some(a), Some(b)) => {
                    let same = match (&a, b) {
                        (toml::Value::Float(x), toml::Value::Float(y)) => (x - y).abs() < 1e-12,
                        _ => a == *b,
                    };
                    assert!(same, "{}.{}: descriptor {a}, technique {b}", d.name, p.key);
                    compared += 1;
                }
                (None, None) => assert!(matches!(p.default, ParamDefault::Auto(_))),
                (a, b) => panic!("{}.{}: descriptor {a:?}, technique {b:?}", d.name, p.key),
            }
        }
        // Every key of the technique's table is described.
        for key in table.keys() {
            assert!(
                d.param(key).is_some(),
                "{}: `{key}` has no descriptor",
                d.table
            );
        }
        // The entry's defaults are a table the technique reads.
        let mut tables = toml::Table::new();
        tables.insert(d.table.into(), toml::Value::Table(d.defaults()));
        (d.validate)(&tables).unwrap_or_else(|e| panic!("{}: {e}", d.name));
        for p in d.params {
            if let Some(v) = p.default.value() {
                check_value(p, &v, p.key).unwrap_or_else(|e| panic!("{}: {e}", d.name));
            }
        }
    }
    assert!(compared >= 40, "{compared}");
}

/// A variant's name pins its value; a contradiction is refused, and a scene's tables are
/// checked by the same descriptors (an unknown table, key or range).
#[test]
fn variants_and_scene_tables_use_the_same_parser() {
    for d in REGISTRY {
        for (k, v) in d.fixed {
            let spec: Spec = d.name.parse().unwrap();
            assert_eq!(spec.own().get(*k).and_then(|x| x.as_str()), Some(*v));
            let other = d
                .param(k)
                .and_then(|p| match p.kind {
                    Kind::Choice(words) => words.iter().find(|w| *w != v),
                    _ => None,
                })
                .unwrap();
            assert!(
                format!("{}:{k}=\"{other}\"", d.name)
                    .parse::<Spec>()
                    .is_err()
            );
        }
    }
    let scene = |caustics: &str| {
        caustics_core::scene::Scene::from_toml(
            &format!(
                "[water]\nwaves = [{{ amplitude = 0.01, wavelength = 0.5, direction = [1.0, 0.0] }}]\ndepth = 1.0\n[light]\ndirection = [0.0, 0.0, -1.0]\n[caustics]\n{caustics}\n"
            ),
            std::path::Path::new("."),
            "t",
        )
    };
    let first = REGISTRY.iter().find(|d| !d.params.is_empty()).unwrap();
    let p = &first.params[0];
    scene(&format!("technique = \"{}\"", first.name)).unwrap();
    // The same spelling as --technique.
    let value = p.default.value().unwrap_or(toml::Value::Integer(1));
    let ok = scene(&format!("technique = '{}:{}={value}'", first.name, p.key));
    assert!(ok.is_ok(), "{:?}", ok.err());
    let e = scene(&format!(
        "technique = \"{}\"\n[caustics.{}]\nno_such_key = 1",
        first.name, first.table
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("no_such_key") && e.contains(p.key), "{e}");
    let e = scene("technique = \"no-such\"").unwrap_err().to_string();
    assert!(
        e.contains("caustics.technique") && e.contains("no-such"),
        "{e}"
    );
    let e = scene("[caustics.no-such]\nx = 1").unwrap_err().to_string();
    assert!(e.contains("caustics.no-such"), "{e}");
}

/// A fixed-length array of a scene file with another length is refused, naming the length: every
/// such field of the built-in scenes, one entry added.
#[test]
fn scene_arrays_have_their_length() {
    let mut refused = 0;
    for (name, text) in caustics_core::scene::BUILTIN_SCENES {
        for (k, line) in text.lines().enumerate() {
            let trimmed = line.trim_start();
            // A key's inline array of numbers: `key = [a, b]` (also inside inline tables).
            let Some(open) = trimmed.find("= [") else {
                continue;
            };
            let Some(close) = trimmed[open..].find(']') else {
                continue;
            };
            let inner = &trimmed[open + 3..open + close];
            if inner.is_empty() || inner.contains('{') || inner.contains('"') {
                continue;
            }
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            let at = line.len() - trimmed.len() + open + close;
            let extra = if inner.contains('.') { ", 1.0" } else { ", 1" };
            lines[k].insert_str(at, extra);
            let changed = lines.join("\n");
            match caustics_core::scene::Scene::from_toml(&changed, std::path::Path::new("."), name)
            {
                Err(e) => {
                    let e = e.to_string();
                    assert!(e.contains("exactly"), "{name} line {}: {e}", k + 1);
                    refused += 1;
                }
                Ok(_) => panic!("{name} line {}: `{}` accepted", k + 1, lines[k]),
            }
        }
    }
    assert!(refused >= 10, "{refused}");
}

/// The front door's water: `size` held once (the scene's square is the water's), the defaults a
/// user expects, and what a scene file would refuse refused by name.
#[test]
fn water_only_is_a_checked_scene_of_water_alone() {
    use caustics_core::scene::{WaterOnly, WaterSource};
    let scene = WaterOnly::new(4.0, 1.5)
        .absorption([0.3, 0.05, 0.02])
        .clamped()
        .map(128)
        .scene()
        .unwrap();
    let water = scene.water.as_ref().unwrap();
    assert_eq!((scene.size, water.size, water.depth), (4.0, 4.0, 1.5));
    assert_eq!((water.ior, water.wrap), (1.333, false));
    assert!(matches!(water.source, WaterSource::Flat));
    assert_eq!((scene.caustics.width, scene.caustics.height), (128, 128));
    assert!(scene.objects.is_empty() && !scene.floor.walls);
    assert!((scene.light.direction.length() - 1.0).abs() < 1e-12 && scene.light.direction.z < 0.0);
    for (bad, named) in [
        (WaterOnly::new(4.0, -1.0), "depth"),
        (WaterOnly::new(4.0, 1.0).sun([0.0, 0.0, 1.0]), "direction"),
        (WaterOnly::new(4.0, 1.0).ior(0.5), "ior"),
    ] {
        let err = bad.scene().expect_err("refused").to_string();
        assert!(err.contains(named), "{err}");
    }
}
