//! The registry: every technique in one table ([`REGISTRY`]), and everything that walks it.
//! Looking an entry up by name, the spec parser ([`Spec`], `name:key=value`) and the checks of a
//! technique's tables, docs/techniques.md's table, the techniques a scene offers, and the check of
//! a scene file's `technique` and `[caustics.<name>]` tables while it is read. The one place in
//! the crate that names every technique: the techniques and the reference below it know only the
//! description ([`super::describe`]) they are written against; the renderer and the front ends
//! above it find them here.

use std::path::Path;

use super::describe::{Descriptor, Input, Param, check_value};
use super::job::{Job, JobOutput};
use super::{cascaded, caustic_triangles, procedural, volumes, yuksel};
use crate::scene::{CausticsSettings, CausticsSpec, Light, Material, Scene, WaterOnly};
use crate::{Error, Result};

/// Former names still read, each with the entry it now names: `yuksel-gather` is `yuksel`, whose
/// default passes are the scatter that name ran (docs/yuksel.md).
pub const ALIASES: &[(&str, &str)] = &[("yuksel-gather", "yuksel")];

/// Every technique, in one place: the ground truth first, then the papers in order. A new
/// technique adds its entry here (and its GPU implementation one line in `caustics_gpu`'s).
pub const REGISTRY: &[&Descriptor] = &[
    &crate::reference::DESCRIPTOR,
    &yuksel::DESCRIPTOR,
    &yuksel::TARGETS,
    &procedural::DESCRIPTOR,
    &procedural::VERTEX,
    &procedural::SCREEN,
    &procedural::TEXTURE,
    &volumes::DESCRIPTOR,
    &caustic_triangles::DESCRIPTOR,
    &cascaded::DESCRIPTOR,
];

/// The techniques a front end offers for `scene`: every registered technique that computes
/// caustics from what the scene has (its water: floor maps, a technique whose generator may be
/// the water surface, and eye-space images; else its glass objects), the reference always (for
/// glass, paper 4's photon tracer), after the others.
pub fn for_scene(scene: &Scene) -> Vec<String> {
    let inputs: &[Input] = if scene.water.is_some() {
        &[Input::Water, Input::GlassOrWater, Input::EyeSpace]
    } else if scene
        .objects
        .iter()
        .any(|o| matches!(o.material, Material::Glass { .. }))
    {
        &[Input::GlassOrWater]
    } else {
        return Vec::new();
    };
    let mut entries: Vec<&Descriptor> = REGISTRY
        .iter()
        .copied()
        .filter(|d| inputs.contains(&d.input) || d.reference)
        .collect();
    // The techniques first, the reference they are judged against after.
    entries.sort_by_key(|d| d.reference);
    entries.iter().map(|d| d.name.to_string()).collect()
}

/// Every parameter a table accepts: those of all the entries sharing it, each once.
pub fn table_params(table: &str) -> impl Iterator<Item = &'static Param> + '_ {
    let mut seen: Vec<&'static str> = Vec::new();
    REGISTRY
        .iter()
        .filter(move |d| d.table == table)
        .flat_map(|d| d.params.iter())
        .filter(move |p| {
            if seen.contains(&p.key) {
                false
            } else {
                seen.push(p.key);
                true
            }
        })
}

/// The registered entry `name`.
pub fn find(name: &str) -> Option<&'static Descriptor> {
    let name = canonical(name);
    REGISTRY.iter().copied().find(|d| d.name == name)
}

/// The registered name `name` stands for: itself, or the entry a former name
/// ([`ALIASES`]) now names.
pub fn canonical(name: &str) -> &str {
    ALIASES
        .iter()
        .find(|(old, _)| *old == name)
        .map_or(name, |(_, new)| new)
}

/// The names of every entry, for error messages.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|d| d.name).collect()
}

// What an entry knows only from the other entries: the parameters its table accepts (its
// variants' too) and the techniques that render a point light.
impl Descriptor {
    /// The parameter `key` of its table: its own, or one of the entries sharing the table.
    pub fn param(&self, key: &str) -> Option<&'static Param> {
        table_params(self.table).find(|p| p.key == key)
    }

    /// Refuses a point or spot light where the technique needs the sun.
    pub fn check_light(&self, light: &Light) -> Result<()> {
        if light.is_sun() || self.point_light {
            return Ok(());
        }
        Err(Error::field(
            "light.position",
            format!(
                "technique `{}` needs the directional sun (light.direction without light.position); \
                 only {} render a point or spot light",
                self.name,
                REGISTRY
                    .iter()
                    .filter(|d| d.point_light)
                    .map(|d| d.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ))
    }
}

/// Checks one technique's table (`[caustics.<table>]`): every key a parameter of it, every value
/// of its type and in its range.
pub fn check_table(table: &str, values: &toml::Table) -> Result<()> {
    for (key, value) in values {
        let Some(param) = table_params(table).find(|p| p.key == key) else {
            let known: Vec<&str> = table_params(table).map(|p| p.key).collect();
            return Err(Error::field(
                format!("caustics.{table}.{key}"),
                format!(
                    "is not a parameter of `{table}` (its parameters: {})",
                    if known.is_empty() {
                        "none".to_string()
                    } else {
                        known.join(", ")
                    }
                ),
            ));
        };
        check_value(param, value, &format!("caustics.{table}.{key}"))?;
    }
    Ok(())
}

/// Checks a scene's `[caustics]` technique tables (keyed by technique).
pub fn check_tables(tables: &toml::Table) -> Result<()> {
    for (key, value) in tables {
        let toml::Value::Table(t) = value else {
            return Err(Error::field(
                format!("caustics.{key}"),
                "is not a known setting: expected `resolution`, `technique`, or a table named after a technique",
            ));
        };
        if !REGISTRY.iter().any(|d| d.table == key) {
            return Err(Error::field(
                format!("caustics.{key}"),
                format!(
                    "is not a technique's table (tables: {})",
                    tables_known().join(", ")
                ),
            ));
        }
        check_table(key, t)?;
    }
    Ok(())
}

fn tables_known() -> Vec<&'static str> {
    let mut v: Vec<&str> = REGISTRY.iter().map(|d| d.table).collect();
    v.dedup();
    v
}

/// A technique and its parameters, written `name` or `name:key=value,key=value` (e.g.
/// `yuksel:n=15,m=14`, `yuksel-targets`, `procedural-texture:target_resolution=512`): the one
/// spelling of the command line, a scene's `technique`, and the viewer's panel.
#[derive(Clone, Debug)]
pub struct Spec {
    /// As given.
    pub label: String,
    /// The registered entry the name picks.
    pub entry: &'static Descriptor,
    /// Its parameter tables keyed by table (`{ yuksel = { n = 15 } }`), as a scene's `[caustics]`.
    pub params: toml::Table,
}

impl Spec {
    /// The registered name (`yuksel-targets`).
    pub fn name(&self) -> &'static str {
        self.entry.name
    }

    /// Its own table (the keys given for its technique), empty when none was given.
    pub fn own(&self) -> toml::Table {
        match self.params.get(self.entry.table) {
            Some(toml::Value::Table(t)) => t.clone(),
            _ => toml::Table::new(),
        }
    }

    /// The technique a scene names, with its `[caustics.<name>]` tables under what the
    /// `technique` string gives.
    pub fn from_scene(caustics: &CausticsSettings) -> Result<Self> {
        let spec: Spec = caustics.technique.parse()?;
        Ok(spec.over(&caustics.params))
    }

    /// This spec's parameters laid over `base` (a scene's tables): the spec wins.
    pub fn over(mut self, base: &toml::Table) -> Self {
        let mut merged = base.clone();
        for (name, table) in &self.params {
            match (merged.get_mut(name), table) {
                (Some(toml::Value::Table(into)), toml::Value::Table(from)) => {
                    into.extend(from.iter().map(|(k, v)| (k.clone(), v.clone())));
                }
                _ => {
                    merged.insert(name.clone(), table.clone());
                }
            }
        }
        self.params = merged;
        self
    }

    /// Runs the CPU twin.
    pub fn run_cpu(
        &self,
        job: &Job,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<JobOutput> {
        self.entry.check_light(&job.scene.light)?;
        (self.entry.cpu)(job, &self.params, progress)
    }
}

impl std::str::FromStr for Spec {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        let (name, rest) = s.split_once(':').unwrap_or((s, ""));
        let name = name.trim();
        let entry = find(name).ok_or_else(|| {
            Error::InvalidParameter(format!(
                "unknown technique `{name}` (known: {})",
                names().join(", ")
            ))
        })?;
        if entry.name != name {
            tracing::warn!(
                "technique `{name}` is now called `{}`: read as that",
                entry.name
            );
        }
        let mut table = toml::Table::new();
        for kv in rest.split(',').filter(|p| !p.trim().is_empty()) {
            let (k, v) = kv.split_once('=').ok_or_else(|| {
                Error::InvalidParameter(format!("`{kv}` in `{s}`: expected key=value"))
            })?;
            let k = k.trim();
            let value: toml::Value = format!("v = {v}")
                .parse::<toml::Table>()
                .ok()
                .and_then(|t| t.get("v").cloned())
                .unwrap_or_else(|| toml::Value::String(v.trim().to_string()));
            table.insert(k.to_string(), value);
        }
        for (k, pinned) in entry.fixed {
            if let Some(given) = table.get(*k)
                && given.as_str() != Some(pinned)
            {
                return Err(Error::InvalidParameter(format!(
                    "`{s}`: the name says {k} `{pinned}`, the parameters {given}"
                )));
            }
            table.insert((*k).into(), toml::Value::String((*pinned).into()));
        }
        // A field's error names the key as the spec spells it.
        let named = |e: Error| match e {
            Error::InvalidField { field, problem } => Error::InvalidParameter(format!(
                "`{s}`: `{}` {problem}",
                field.rsplit('.').next().unwrap_or(&field)
            )),
            other => other,
        };
        check_table(entry.table, &table).map_err(named)?;
        let mut params = toml::Table::new();
        params.insert(entry.table.to_string(), toml::Value::Table(table));
        (entry.validate)(&params).map_err(named)?;
        Ok(Spec {
            label: s.to_string(),
            entry,
            params,
        })
    }
}

/// The ground truth's spec, at its defaults: what `caustics compare` and the sweep measure
/// against.
pub fn reference() -> Spec {
    let entry = REGISTRY
        .iter()
        .copied()
        .find(|d| d.reference)
        .expect("the registry has a reference");
    entry.name.parse().expect("a bare name parses")
}

/// Checks a scene file's `technique` (`name` or `name:key=value,...`, as `--technique` takes it)
/// and its `[caustics.<name>]` tables with the one parser, the registry's descriptors: what the
/// scene loaders below pass the scene model's reader, which knows no technique.
pub fn check_scene_technique(caustics: &CausticsSpec) -> Result<()> {
    let spec = caustics.technique.parse::<Spec>().map_err(|e| match e {
        Error::InvalidParameter(problem) => Error::field("caustics.technique", problem),
        other => other,
    })?;
    check_tables(&caustics.params)?;
    // A name that pins a parameter (`yuksel-targets`: `passes = "targets"`) wins over the
    // scene's table, so a table that says otherwise would be dropped without a word.
    let table = caustics.params.get(spec.entry.table);
    for (key, pinned) in spec.entry.fixed {
        if let Some(given) = table.and_then(|t| t.get(*key))
            && given.as_str() != Some(pinned)
        {
            return Err(Error::field(
                format!("caustics.{}.{key}", spec.entry.table),
                format!(
                    "is {given}, but the scene's technique `{}` always runs with {key} \
                     `{pinned}`: drop the key, or choose another technique",
                    spec.entry.name
                ),
            ));
        }
    }
    Ok(())
}

// The scene loaders every front end calls, each refusing a technique or table the registry does
// not know: the scene model reads and checks the rest of the file (`Scene::from_toml_with` and its
// kin), and is handed the registry's check because it sits below the techniques.
impl Scene {
    /// Read and check a scene file; relative paths inside it are relative to the file.
    pub fn load(path: &Path) -> Result<Scene> {
        Scene::load_with(path, check_scene_technique)
    }

    /// A built-in scene by name (`pool`, `shore`, `objects`, `glass`).
    pub fn builtin(name: &str) -> Result<Scene> {
        Scene::builtin_with(name, check_scene_technique)
    }

    /// A scene file path, or a built-in scene's name.
    pub fn load_or_builtin(arg: &str) -> Result<Scene> {
        let path = Path::new(arg);
        if path.exists() || arg.ends_with(".toml") {
            Scene::load(path)
        } else {
            Scene::builtin(arg)
        }
    }

    /// A scene from a file's `text` (relative paths in it relative to `base`; `name` names it and
    /// its errors), its technique checked against the registry.
    pub fn from_toml(text: &str, base: &Path, name: &str) -> Result<Scene> {
        Scene::from_toml_with(text, base, name, check_scene_technique)
    }
}

impl WaterOnly {
    /// The scene: flat water (the application's heights replace it), a flat floor, the sun;
    /// checked as a scene file is, so a depth or index out of range is refused by name.
    pub fn scene(&self) -> Result<Scene> {
        Scene::from_file_with(self.file(), Path::new("."), "water", check_scene_technique)
    }
}

#[cfg(test)]
mod for_scene_tests {
    use super::for_scene;
    use crate::scene::Scene;

    #[test]
    fn a_scene_offers_the_techniques_that_run_on_it() {
        let names = for_scene(&Scene::builtin("pool").unwrap());
        for n in [
            "reference",
            "yuksel",
            "yuksel-targets",
            "procedural",
            "volumes",
            "cascaded",
        ] {
            assert!(names.iter().any(|x| x == n), "{n} missing from {names:?}");
        }
        assert_eq!(names.last().map(String::as_str), Some("reference"));
        // The water surface is a caustic generator of paper 4 too.
        assert!(names.iter().any(|x| x == "caustic-triangles"));
        // A scene of glass objects offers the techniques whose generators they are.
        let glass = for_scene(&Scene::builtin("glass").unwrap());
        assert_eq!(glass, ["caustic-triangles", "reference"]);
        // Over a terrain, every technique of the water.
        let shore = for_scene(&Scene::builtin("shore").unwrap());
        assert_eq!(
            shore,
            [
                "yuksel",
                "yuksel-targets",
                "procedural",
                "procedural-vertex",
                "procedural-screen",
                "procedural-texture",
                "volumes",
                "caustic-triangles",
                "cascaded",
                "reference"
            ]
        );
        assert_eq!(for_scene(&Scene::builtin("reef").unwrap()), shore);
    }
}
