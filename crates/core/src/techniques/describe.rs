//! How a technique describes itself, once, beside its code: its name, paper, what it reads and
//! lights, and its parameters as typed descriptors. Every front end reads these and nothing else:
//! the spec parser (`name:key=value`, a scene's `technique` and its `[caustics.<name>]` tables),
//! `caustics techniques`, the viewer's panel, bench and the error-against-cost sweep, the fuzzed
//! specs and docs/techniques.md's table. The CPU twin is reached from the entry
//! ([`Descriptor::cpu`]); the GPU crate's registry points at the same entry.
//!
//! This is what every technique is written against, so it knows no technique: what needs the
//! list of them (looking a name up, the spec parser, the checks of a scene's tables, naming the
//! techniques that render a point light) is the registry's ([`super::registry`]).

use super::buffers::{Buffer, BufferDesc, BufferInput, DrawBuffer, HEIGHTS, Needs, SceneHas};
use super::job::{Job, JobOutput, heights_for};
use crate::plot::{Picture, diverging, scalar_picture};
use crate::{Error, Result};

/// What a parameter holds and the values it may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// An integer in `[min, max]`; `parity` 1 wants it odd, 0 even; `power_of_two` a power of two.
    Int {
        /// The least value allowed (inclusive).
        min: i64,
        /// The greatest value allowed (inclusive).
        max: i64,
        /// The remainder modulo 2 the value must have (1: odd, 0: even); `None`: either.
        parity: Option<i64>,
        /// The value must be a power of two.
        power_of_two: bool,
    },
    /// A finite number in `[min, max]`.
    Float {
        /// The least value allowed (inclusive).
        min: f64,
        /// The greatest value allowed (inclusive).
        max: f64,
    },
    /// A flag: `true` or `false`.
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

    /// A number in `[min, max]`, both inclusive.
    pub const fn float(min: f64, max: f64) -> Kind {
        Kind::Float { min, max }
    }
}

/// A parameter's value when it is not given (not `Default`: that name is the prelude's trait).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ParamDefault {
    /// This integer.
    Int(i64),
    /// This number, in the parameter's unit.
    Float(f64),
    /// This flag.
    Bool(bool),
    /// This word or path, as the table writes it (a [`Kind::Choice`]'s word, a [`Kind::Path`]).
    Text(&'static str),
    /// Chosen by the technique from the scene or another parameter, as this says.
    Auto(&'static str),
}

impl ParamDefault {
    /// The value as a scene file writes it; `None` for [`ParamDefault::Auto`].
    pub fn value(self) -> Option<toml::Value> {
        Some(match self {
            ParamDefault::Int(i) => toml::Value::Integer(i),
            ParamDefault::Float(f) => toml::Value::Float(f),
            ParamDefault::Bool(b) => toml::Value::Boolean(b),
            ParamDefault::Text(t) => toml::Value::String(t.into()),
            ParamDefault::Auto(_) => return None,
        })
    }
}

impl std::fmt::Display for ParamDefault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ParamDefault::Auto(how) => write!(f, "auto ({how})"),
            other => write!(f, "{}", other.value().expect("not auto")),
        }
    }
}

/// One parameter of a technique's table.
#[derive(Clone, Copy, Debug)]
pub struct Param {
    /// As the table and the command line spell it.
    pub key: &'static str,
    /// The panel's label (the paper's symbol where it has one).
    pub label: &'static str,
    /// Its type and the values it may take.
    pub kind: Kind,
    /// Its value when the table does not give it.
    pub default: ParamDefault,
    /// Unit of the value ("texels", "degrees"); empty for a count or a flag.
    pub unit: &'static str,
    /// One line on what it does (the paper's section where it has one).
    pub doc: &'static str,
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
        default: ParamDefault,
        unit: &'static str,
        doc: &'static str,
    ) -> Param {
        Param {
            key,
            label,
            kind,
            default,
            unit,
            doc,
            sweep: &[],
        }
    }
}

impl Param {
    /// An option on by default (a technique's Fresnel weight, its absorption).
    pub const fn on(key: &'static str, label: &'static str, doc: &'static str) -> Param {
        Param::new(key, label, Kind::Bool, ParamDefault::Bool(true), "", doc)
    }
}

/// What a technique lights.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Receiver {
    /// The pool's floor, in the floor caustics map.
    Floor,
    /// The pool's side walls, in maps of their own when the scene's walls are on.
    Walls,
    /// Objects under the water (paper 3's receivers), in a map per object.
    Objects,
    /// The floor as the eye camera sees it (paper 5), not a map.
    EyeSpace,
}

impl Receiver {
    /// Its name in docs/techniques.md's table (`floor`, `eye space`).
    pub fn name(self) -> &'static str {
        ["floor", "walls", "objects", "eye space"][self as usize]
    }
}

/// What a technique reads and what it makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// A map of the floor square from the water surface (the minimum scene contract's case).
    Water,
    /// A map of the floor square from the scene's glass objects, or from its water surface where
    /// it has water (caustic-triangles: paper 4's generator is any refracting surface).
    GlassOrWater,
    /// Caustics from the water in the eye camera's screen space, not a floor map.
    EyeSpace,
}

impl Input {
    /// Its `input -> output` column in `caustics techniques` and docs/techniques.md's table
    /// (`water -> floor map`).
    pub fn describe(self) -> &'static str {
        let names = [
            "water -> floor map",
            "glass or water -> floor map",
            "water -> eye space",
        ];
        names[self as usize]
    }
}

/// The checks every technique makes of its inputs, with one wording: a map of at least one texel and
/// a light that travels down. Returns the unit light direction.
pub fn check_inputs(width: usize, height: usize, light: glam::DVec3) -> Result<glam::DVec3> {
    if width == 0 || height == 0 {
        return Err(Error::InvalidParameter(format!(
            "caustics map resolution must be at least 1 x 1, got {width} x {height}"
        )));
    }
    if light.z >= 0.0 || !light.is_finite() {
        return Err(Error::InvalidParameter(format!(
            "the light direction {light} must point down (z < 0)"
        )));
    }
    Ok(light.normalize())
}

/// The CPU twin of an entry: the job, the parameter tables keyed by table (a scene file's
/// `[caustics]`), progress `(done, total)`.
pub type CpuRun = fn(&Job, &toml::Table, &(dyn Fn(usize, usize) + Sync)) -> Result<JobOutput>;

/// One registered technique, as the command line spells it: a variant (`yuksel-targets`,
/// `procedural-texture`) is an entry of its own sharing its technique's parameter table.
#[derive(Clone, Copy, Debug)]
pub struct Descriptor {
    /// As the command line and a scene's `technique` spell it (`yuksel-targets`).
    pub name: &'static str,
    /// The key of its parameter table (`yuksel` for `yuksel-targets`).
    pub table: &'static str,
    /// The paper in `shared/papers` (1 to 5), `-` for ours.
    pub paper: &'static str,
    /// One line on what it does, for `caustics techniques` and the web page.
    pub summary: &'static str,
    /// Its documentation, relative to the repository's root.
    pub docs: &'static str,
    /// What it reads and what it makes.
    pub input: Input,
    /// What it lights.
    pub receivers: &'static [Receiver],
    /// Its parameters, in the panel's order: those a variant does not read are left out of its
    /// entry (the table accepts every key of its technique's entries).
    pub params: &'static [Param],
    /// What the name pins in the table (`procedural-texture`: `variant = "texture"`).
    pub fixed: &'static [(&'static str, &'static str)],
    /// Whether a point or spot light is rendered (paper 4's light cube map); the others need the
    /// directional sun.
    pub point_light: bool,
    /// The intermediate buffers a view can show, beyond the water's heights.
    pub buffers: &'static [BufferDesc],
    /// Draws them, with the CPU twin's passes.
    pub draw_buffer: DrawBuffer,
    /// The ground truth others are measured against (not a technique to pick for speed).
    pub reference: bool,
    /// The technique's own reading of the tables (its serde struct and its checks across
    /// parameters), which the parser runs after the descriptors' checks.
    pub validate: fn(&toml::Table) -> Result<()>,
    /// The technique's own defaults: its parameters' serde `Default`, serialized as its table
    /// (empty for an entry without parameters), against which the descriptors' defaults are
    /// checked.
    pub own_defaults: fn() -> toml::Table,
    /// The CPU twin.
    pub cpu: CpuRun,
}

impl PartialEq for Descriptor {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl Descriptor {
    /// A floor technique by design: with the scene's walls on it still maps the floor alone (the
    /// light that meets a wall leaves its map, as in `yuksel`, or stays on the floor, as in
    /// `procedural`'s gathering).
    pub fn floor_only(&self) -> bool {
        !self.receivers.contains(&Receiver::Walls) && !self.receivers.contains(&Receiver::EyeSpace)
    }

    /// It makes the eye camera's image of the caustics (paper 5), not a floor map.
    pub fn eye_space(&self) -> bool {
        self.receivers.contains(&Receiver::EyeSpace)
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
}

/// The line `caustics techniques` and the logs give a floor-only technique on a scene with walls.
pub fn floor_only_note(name: &str) -> String {
    format!(
        "technique `{name}` maps the floor only: the scene's walls stay lit by the ambient light"
    )
}

/// A technique's parameters checked against its entry's kinds and ranges, as a table read from a
/// scene is: one rule for parameters built in code and for those read from a file.
pub fn check_params<T: serde::Serialize>(entry: &Descriptor, params: &T) -> Result<()> {
    let table = entry.table;
    let values = toml::Table::try_from(params)
        .map_err(|e| Error::field(format!("caustics.{table}"), e.to_string()))?;
    for (key, value) in &values {
        if let Some(param) = entry.params.iter().find(|p| p.key == key) {
            check_value(param, value, &format!("caustics.{table}.{key}"))?;
        }
    }
    Ok(())
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

/// [`Descriptor::own_defaults`] of a technique whose parameters are the serde struct `T`.
pub fn serde_defaults<T: Default + serde::Serialize>() -> toml::Table {
    toml::Table::try_from(T::default()).expect("a technique's parameters serialize as a table")
}

/// A technique's parameters from the tables keyed by technique: its entry's table where there is
/// one (a malformed one refused naming `caustics.<table>`), else the defaults; checked by
/// `validate`.
pub fn read_params<T: Default + serde::de::DeserializeOwned>(
    tables: &toml::Table,
    entry: &Descriptor,
    validate: impl Fn(&T) -> Result<()>,
) -> Result<T> {
    let key = entry.table;
    let params = match tables.get(key) {
        Some(v) => (v.clone().try_into())
            .map_err(|e| Error::field(format!("caustics.{key}"), e.to_string()))?,
        None => T::default(),
    };
    validate(&params)?;
    Ok(params)
}

// What a job and a buffer know of the technique they are for: here, so that the job and the
// buffers, which the descriptor is made of, stay below it.

impl Job<'_> {
    /// Says once in the log that a floor technique leaves the scene's walls unlit.
    pub fn note_floor_only(&self, technique: &Descriptor) {
        if self.scene.floor.walls && technique.floor_only() {
            tracing::warn!("{}", floor_only_note(technique.name));
        }
    }
}

impl Buffer {
    /// The buffers `entry` shows in a scene with what `has` says: the heights where there is
    /// water, then the technique's own where the scene has what they show; none where the
    /// technique does not run (a water technique in a scene of glass).
    pub fn available(entry: &Descriptor, has: SceneHas) -> Vec<Buffer> {
        if !has.water && entry.input != Input::GlassOrWater {
            return Vec::new();
        }
        let heights = has.water.then_some(&HEIGHTS);
        heights
            .into_iter()
            .chain(entry.buffers.iter().filter(|b| match b.needs {
                Needs::Anything => true,
                Needs::NoWater => !has.water,
                Needs::PointLight => has.point_light,
                Needs::Objects => has.objects > 0,
            }))
            .map(Buffer::new)
            .collect()
    }
}

/// Compute `buffer` of `entry` for `input`; an error names what stood in the way (e.g. an invalid
/// `N`, an object the scene does not have).
pub fn picture(entry: &Descriptor, buffer: Buffer, input: &BufferInput) -> Result<Picture> {
    if buffer.desc.key == HEIGHTS.key {
        let (water, surface) = input.water()?;
        let n = input.map_size;
        let heights = heights_for(water, surface, n, n);
        let (lo, hi) = heights.min_max();
        let r = lo.abs().max(hi.abs()).max(1e-9);
        return Ok(Picture {
            legend: format!("height: blue -{r:.4}, red +{r:.4} (world units)"),
            ..scalar_picture(&heights, |v| diverging(v / r))
        });
    }
    (entry.draw_buffer)(input, buffer)
}
