//! The caustics techniques: the registry of names as the CLI and scene files spell them, the input
//! every technique takes, and the CPU twin of each (the oracle of its GPU implementation's tests and
//! the fallback where no GPU adapter exists).

pub mod cascaded;
pub mod caustic_triangles;
pub mod procedural;
pub mod volumes;
pub mod yuksel;

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
    pub fn describe(self) -> &'static str {
        match self {
            Input::Water => "water -> floor map",
            Input::GlassOrWater => "glass or water -> floor map",
            Input::EyeSpace => "water -> eye space",
        }
    }
}

pub struct TechniqueInfo {
    pub name: &'static str,
    pub paper: &'static str,
    pub summary: &'static str,
    /// Whether this build renders it; the others are accepted in scene files but not yet implemented.
    pub implemented: bool,
    pub input: Input,
    /// A floor technique by design (issue 18): with the scene's walls on it still maps the floor
    /// alone, and the light that would meet a wall stays on the floor map.
    pub floor_only: bool,
}

/// The line `caustics techniques` and the logs give a floor-only technique on a scene with walls.
pub fn floor_only_note(name: &str) -> String {
    format!(
        "technique `{name}` maps the floor only: the scene's walls stay lit by the ambient light, and \
         the light that would meet them stays on the floor map"
    )
}

pub const TECHNIQUES: &[TechniqueInfo] = &[
    TechniqueInfo {
        name: "reference",
        paper: "-",
        summary: "physically based forward flux tracing: exact Snell + Fresnel at a fine triangulation of the surface, exact area deposit (CPU, the ground truth)",
        implemented: true,
        input: Input::Water,
        floor_only: false,
    },
    TechniqueInfo {
        name: "yuksel",
        paper: "1",
        summary: "fast backward caustics from height fields: pre-pass, N samples along x into M+1 channels, sum along y (Yuksel & Keyser)",
        implemented: true,
        input: Input::Water,
        floor_only: true,
    },
    TechniqueInfo {
        name: "procedural",
        paper: "2",
        summary: "aesthetic procedural caustics: vertical ray to the waves, refract, look up a sun map (Sanchez-Crespo)",
        implemented: true,
        input: Input::Water,
        floor_only: true,
    },
    TechniqueInfo {
        name: "volumes",
        paper: "3",
        summary: "illumination volumes against colour + depth textures and reference planes, caustics on underwater objects",
        implemented: true,
        input: Input::Water,
        floor_only: false,
    },
    TechniqueInfo {
        name: "caustic-triangles",
        paper: "4",
        summary: "layered distance maps, photon hit image, caustic triangles into a light cube map (Umenhoffer et al.)",
        implemented: true,
        input: Input::GlassOrWater,
        floor_only: false,
    },
    TechniqueInfo {
        name: "cascaded",
        paper: "5",
        summary: "cascaded caustic maps for oceans: four light-view cascades, photons splatted in eye space, dispersion (Backlund)",
        implemented: true,
        input: Input::EyeSpace,
        floor_only: false,
    },
];

/// The checks every technique makes of its inputs, with one wording: a map of at least one texel and
/// a light that travels down. Returns the unit light direction.
pub fn check_inputs(width: usize, height: usize, light: glam::DVec3) -> crate::Result<glam::DVec3> {
    if width == 0 || height == 0 {
        return Err(crate::Error::InvalidParameter(format!(
            "caustics map resolution must be at least 1 x 1, got {width} x {height}"
        )));
    }
    if light.z >= 0.0 || !light.is_finite() {
        return Err(crate::Error::InvalidParameter(format!(
            "the light direction {light} must point down (z < 0)"
        )));
    }
    Ok(light.normalize())
}

/// Whether technique `name` can light a scene with `light`: a point or spot light (`position` in
/// `[light]`) is rendered by caustic-triangles alone (its light cube map, paper 4 §4); every other
/// technique, and the general final image, needs the directional sun.
pub fn check_light(name: &str, light: &crate::scene::Light) -> crate::Result<()> {
    if light.is_sun() || name == "caustic-triangles" {
        return Ok(());
    }
    Err(crate::Error::field(
        "light.position",
        format!(
            "technique `{name}` needs the directional sun (light.direction without light.position); \
             only caustic-triangles renders a point or spot light"
        ),
    ))
}

pub fn is_known(name: &str) -> bool {
    TECHNIQUES.iter().any(|t| t.name == name)
}

pub fn names() -> Vec<&'static str> {
    TECHNIQUES.iter().map(|t| t.name).collect()
}

pub fn info(name: &str) -> Option<&'static TechniqueInfo> {
    TECHNIQUES.iter().find(|t| t.name == name)
}
