//! How a technique describes itself, once, beside its code: its name, paper, what it reads and
//! lights, and its parameters as typed descriptors. Every front end reads these and nothing else:
//! the spec parser (`name:key=value`, a scene's `technique` and its `[caustics.<name>]` tables),
//! `caustics techniques`, the viewer's panel, bench and the error-against-cost sweep, the fuzzed
//! specs and the README's table. The CPU twin is reached from the entry ([`Descriptor::cpu`]); the
//! GPU crate's registry points at the same entry.

use std::fmt::Write as _;

use crate::{Error, Result};

use super::{Input, Job, Made};

/// What a parameter holds and the values it may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// An integer in `[min, max]`; `parity` 1 wants it odd, 0 even; `power_of_two` a power of two.
    Int {
        min: i64,
        max: i64,
        parity: Option<i64>,
        power_of_two: bool,
    },
    /// A finite number in `[min, max]`.
    Float {
        min: f64,
        max: f64,
    },
    Bool,
    /// One of these words (the serde names of the technique's enum).
    Choice(&'static [&'static str]),
    /// A file's path (text).
    Path,
}

impl Kind {
    /// An integer range without a parity.
    pub const fn int(min: i64, max: i64) -> Kind {
        Kind::Int {
            min,
            max,
            parity: None,
            power_of_two: false,
        }
    }

    pub const fn float(min: f64, max: f64) -> Kind {
        Kind::Float { min, max }
    }
}

/// A parameter's value when it is not given.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Default {
    Int(i64),
    Float(f64),
    Bool(bool),
    Text(&'static str),
    /// Chosen by the technique from the scene or another parameter, as this says.
    Auto(&'static str),
}

impl Default {
    /// The value as a scene file writes it; `None` for [`Default::Auto`].
    pub fn value(self) -> Option<toml::Value> {
        Some(match self {
            Default::Int(i) => toml::Value::Integer(i),
            Default::Float(f) => toml::Value::Float(f),
            Default::Bool(b) => toml::Value::Boolean(b),
            Default::Text(t) => toml::Value::String(t.into()),
            Default::Auto(_) => return None,
        })
    }
}

impl std::fmt::Display for Default {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Default::Auto(how) => write!(f, "auto ({how})"),
            other => write!(f, "{}", other.value().expect("not auto")),
        }
    }
}

/// What a change of the parameter costs a running GPU frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// A uniform write: the next frame takes it.
    Uniform,
    /// New resources or pipelines: the renderer configures the technique again.
    Reconfigure,
}

/// One parameter of a technique's table.
#[derive(Clone, Copy, Debug)]
pub struct Param {
    /// As the table and the command line spell it.
    pub key: &'static str,
    /// The panel's label (the paper's symbol where it has one).
    pub label: &'static str,
    pub kind: Kind,
    pub default: Default,
    /// Unit of the value ("texels", "degrees"); empty for a count or a flag.
    pub unit: &'static str,
    /// One line on what it does (the paper's section where it has one).
    pub doc: &'static str,
    pub change: Change,
    /// The settings `caustics bench --tradeoff` sweeps this knob over (empty: not swept); the
    /// first two make its quick run.
    pub sweep: &'static [&'static str],
}

impl Param {
    /// A parameter that is not swept (`Param { sweep: &[..], ..Param::new(..) }` for one that is).
    pub const fn new(
        key: &'static str,
        label: &'static str,
        kind: Kind,
        default: Default,
        unit: &'static str,
        doc: &'static str,
        change: Change,
    ) -> Param {
        Param {
            key,
            label,
            kind,
            default,
            unit,
            doc,
            change,
            sweep: &[],
        }
    }
}

/// What a technique lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Receiver {
    Floor,
    Walls,
    Objects,
    /// The floor as the eye camera sees it (paper 5), not a map.
    EyeSpace,
}

impl Receiver {
    pub fn name(self) -> &'static str {
        match self {
            Receiver::Floor => "floor",
            Receiver::Walls => "walls",
            Receiver::Objects => "objects",
            Receiver::EyeSpace => "eye space",
        }
    }
}

/// The CPU twin of an entry: the job, the parameter tables keyed by table (a scene file's
/// `[caustics]`), progress `(done, total)`.
pub type CpuRun = fn(&Job, &toml::Table, &(dyn Fn(usize, usize) + Sync)) -> Result<Made>;

/// One registered technique, as the command line spells it: a variant (`yuksel-targets`,
/// `procedural-texture`) is an entry of its own sharing its technique's parameter table.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    pub name: &'static str,
    /// The key of its parameter table (`yuksel` for `yuksel-targets`).
    pub table: &'static str,
    /// The paper in `shared/papers` (1 to 5), `-` for ours.
    pub paper: &'static str,
    pub summary: &'static str,
    /// Its documentation, relative to the repository's root.
    pub docs: &'static str,
    pub input: Input,
    pub receivers: &'static [Receiver],
    /// Its parameters, in the panel's order: those a variant does not read are left out of its
    /// entry (the table accepts every key of its technique's entries).
    pub params: &'static [Param],
    /// What the name pins in the table (`procedural-texture`: `variant = "texture"`).
    pub fixed: &'static [(&'static str, &'static str)],
    /// Whether a point or spot light is rendered (paper 4's light cube map); the others need the
    /// directional sun.
    pub point_light: bool,
    /// Why it draws on the plane z = 0 only (it then refuses a scene with a terrain, and the
    /// front ends do not offer it there); `None` where it follows a terrain.
    pub flat_floor: Option<&'static str>,
    /// The intermediate buffers a view can show, beyond the water's heights.
    pub buffers: &'static [super::buffers::BufferDesc],
    /// Draws them, with the CPU twin's passes.
    pub draw_buffer: super::buffers::DrawBuffer,
    /// The ground truth others are measured against (not a technique to pick for speed).
    pub reference: bool,
    /// The technique's own reading of the tables (its serde struct and its checks across
    /// parameters), which the parser runs after the descriptors' checks.
    pub validate: fn(&toml::Table) -> Result<()>,
    /// The CPU twin.
    pub cpu: CpuRun,
}

impl PartialEq for Descriptor {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Descriptor {
    /// A floor technique by design (issue 18): with the scene's walls on it still maps the floor
    /// alone, and the light that would meet a wall stays on the floor map.
    pub fn floor_only(&self) -> bool {
        !self.receivers.contains(&Receiver::Walls) && !self.receivers.contains(&Receiver::EyeSpace)
    }

    pub fn eye_space(&self) -> bool {
        self.receivers.contains(&Receiver::EyeSpace)
    }

    pub fn param(&self, key: &str) -> Option<&'static Param> {
        table_params(self.table).find(|p| p.key == key)
    }

    /// Its parameters with their defaults, as the panel starts them: every non-auto default, then
    /// what the name pins.
    pub fn defaults(&self) -> toml::Table {
        let mut t: toml::Table = self
            .params
            .iter()
            .filter_map(|p| Some((p.key.to_string(), p.default.value()?)))
            .collect();
        for (k, v) in self.fixed {
            t.insert((*k).into(), toml::Value::String((*v).into()));
        }
        t
    }

    /// The line `caustics techniques` and the logs give a floor-only technique on a scene with
    /// walls.
    pub fn floor_only_note(&self) -> String {
        floor_only_note(self.name)
    }

    /// Refuses a scene with a terrain where the technique draws on the plane z = 0
    /// ([`flat_floor`](Self::flat_floor)): one wording for both twins.
    pub fn check_floor(&self, scene: &crate::scene::Scene) -> Result<()> {
        if let (Some(why), Some(_)) = (self.flat_floor, &scene.floor.terrain) {
            return Err(Error::InvalidParameter(format!(
                "technique `{}` {why}; scene `{}` has a terrain",
                self.name, scene.name
            )));
        }
        Ok(())
    }

    /// Refuses a point or spot light where the technique needs the sun.
    pub fn check_light(&self, light: &crate::scene::Light) -> Result<()> {
        if light.is_sun() || self.point_light {
            return Ok(());
        }
        Err(Error::field(
            "light.position",
            format!(
                "technique `{}` needs the directional sun (light.direction without light.position); \
                 only {} render a point or spot light",
                self.name,
                super::REGISTRY
                    .iter()
                    .filter(|d| d.point_light)
                    .map(|d| d.name)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ))
    }
}

/// The line `caustics techniques` and the logs give a floor-only technique on a scene with walls.
pub fn floor_only_note(name: &str) -> String {
    format!(
        "technique `{name}` maps the floor only: the scene's walls stay lit by the ambient light, and \
         the light that would meet them stays on the floor map"
    )
}

/// Every parameter a table accepts: those of all the entries sharing it, each once.
pub fn table_params(table: &str) -> impl Iterator<Item = &'static Param> + '_ {
    let mut seen: Vec<&'static str> = Vec::new();
    super::REGISTRY
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
    super::REGISTRY.iter().copied().find(|d| d.name == name)
}

/// The registered name `name` stands for: itself, or the entry a former name
/// ([`ALIASES`](super::ALIASES)) now names.
pub fn canonical(name: &str) -> &str {
    super::ALIASES
        .iter()
        .find(|(old, _)| *old == name)
        .map_or(name, |(_, new)| new)
}

/// The names of every entry, for error messages.
pub fn names() -> Vec<&'static str> {
    super::REGISTRY.iter().map(|d| d.name).collect()
}

/// `value` checked against `param`'s type and range; `at` names where it was given.
pub fn check_value(param: &Param, value: &toml::Value, at: &str) -> Result<()> {
    let bad = |problem: String| Err(Error::field(at, problem));
    let unit = if param.unit.is_empty() {
        String::new()
    } else {
        format!(" {}", param.unit)
    };
    match (param.kind, value) {
        (
            Kind::Int {
                min,
                max,
                parity,
                power_of_two,
            },
            toml::Value::Integer(i),
        ) => {
            if !(min..=max).contains(i) {
                return bad(format!(
                    "must be between {min} and {max}{unit}, got {i} ({})",
                    param.doc
                ));
            }
            if let Some(p) = parity
                && i.rem_euclid(2) != p
            {
                let want = if p == 1 { "odd" } else { "even" };
                return bad(format!("must be {want}, got {i} ({})", param.doc));
            }
            if power_of_two && (*i <= 0 || (*i & (*i - 1)) != 0) {
                return bad(format!("must be a power of two, got {i} ({})", param.doc));
            }
            Ok(())
        }
        (Kind::Float { min, max }, toml::Value::Float(_) | toml::Value::Integer(_)) => {
            let f = value
                .as_float()
                .unwrap_or_else(|| value.as_integer().unwrap_or(0) as f64);
            if !f.is_finite() || f < min || f > max {
                return bad(format!(
                    "must be a number between {min} and {max}{unit}, got {f} ({})",
                    param.doc
                ));
            }
            Ok(())
        }
        (Kind::Bool, toml::Value::Boolean(_)) | (Kind::Path, toml::Value::String(_)) => Ok(()),
        (Kind::Choice(words), toml::Value::String(s)) => {
            if words.contains(&s.as_str()) {
                Ok(())
            } else {
                bad(format!(
                    "must be one of {}, got \"{s}\" ({})",
                    quoted(words),
                    param.doc
                ))
            }
        }
        (kind, other) => bad(format!(
            "must be {}, got {other} ({})",
            kind_name(kind),
            param.doc
        )),
    }
}

fn kind_name(kind: Kind) -> String {
    match kind {
        Kind::Int { .. } => "an integer".into(),
        Kind::Float { .. } => "a number".into(),
        Kind::Bool => "true or false".into(),
        Kind::Choice(words) => format!("one of {}", quoted(words)),
        Kind::Path => "a file path in quotes".into(),
    }
}

fn quoted(words: &[&str]) -> String {
    words
        .iter()
        .map(|w| format!("\"{w}\""))
        .collect::<Vec<_>>()
        .join(", ")
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
        if !super::REGISTRY.iter().any(|d| d.table == key) {
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
    let mut v: Vec<&str> = super::REGISTRY.iter().map(|d| d.table).collect();
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
    pub fn from_scene(caustics: &crate::scene::CausticsSettings) -> Result<Self> {
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
    pub fn run_cpu(&self, job: &Job, progress: &(dyn Fn(usize, usize) + Sync)) -> Result<Made> {
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
        check_table(entry.table, &table).map_err(|e| match e {
            Error::InvalidField { field, problem } => Error::InvalidParameter(format!(
                "`{s}`: `{}` {problem}",
                field.rsplit('.').next().unwrap_or(&field)
            )),
            other => other,
        })?;
        let mut params = toml::Table::new();
        params.insert(entry.table.to_string(), toml::Value::Table(table));
        (entry.validate)(&params).map_err(|e| match e {
            Error::InvalidField { field, problem } => Error::InvalidParameter(format!(
                "`{s}`: `{}` {problem}",
                field.rsplit('.').next().unwrap_or(&field)
            )),
            other => other,
        })?;
        Ok(Spec {
            label: s.to_string(),
            entry,
            params,
        })
    }
}

/// The README's table of techniques, made from the registry (`caustics techniques --markdown`; a
/// test keeps the README's copy current).
pub fn markdown_table() -> String {
    let mut s = String::from(
        "| technique | paper | reads -> makes | lights | parameters (default) | documentation |\n|---|---|---|---|---|---|\n",
    );
    for d in super::REGISTRY {
        let params: Vec<String> = d
            .params
            .iter()
            .map(|p| match p.default {
                Default::Auto(_) => format!("`{}` (auto)", p.key),
                other => format!("`{}` ({other})", p.key),
            })
            .collect();
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | [{}]({}) |",
            d.name,
            d.paper,
            d.input.describe(),
            d.receivers
                .iter()
                .map(|r| r.name())
                .collect::<Vec<_>>()
                .join(", "),
            if params.is_empty() {
                "-".to_string()
            } else {
                params.join(", ")
            },
            d.docs,
            d.docs
        );
    }
    s
}

/// The ground truth's spec, at its defaults: what `caustics compare` and the sweep measure
/// against.
pub fn reference() -> Spec {
    let entry = super::REGISTRY
        .iter()
        .copied()
        .find(|d| d.reference)
        .expect("the registry has a reference");
    entry.name.parse().expect("a bare name parses")
}
