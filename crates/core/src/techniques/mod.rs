//! The caustics techniques: the registry of names as the CLI and scene files spell them, the input
//! every technique takes, and the CPU twin of each (the oracle of its GPU implementation's tests and
//! the fallback where no GPU adapter exists).

pub mod cascaded;
pub mod caustic_triangles;
pub mod procedural;
pub mod yuksel;

pub struct TechniqueInfo {
    pub name: &'static str,
    pub paper: &'static str,
    pub summary: &'static str,
    /// Whether this build renders it; the others are accepted in scene files but not yet implemented.
    pub implemented: bool,
}

pub const TECHNIQUES: &[TechniqueInfo] = &[
    TechniqueInfo {
        name: "reference",
        paper: "-",
        summary: "physically based forward flux tracing: exact Snell + Fresnel at a fine triangulation of the surface, exact area deposit (CPU, the ground truth)",
        implemented: true,
    },
    TechniqueInfo {
        name: "yuksel",
        paper: "1",
        summary: "fast backward caustics from height fields: pre-pass, N samples along x into M+1 channels, sum along y (Yuksel & Keyser)",
        implemented: true,
    },
    TechniqueInfo {
        name: "procedural",
        paper: "2",
        summary: "aesthetic procedural caustics: vertical ray to the waves, refract, look up a sun map (Sanchez-Crespo)",
        implemented: true,
    },
    TechniqueInfo {
        name: "volumes",
        paper: "3",
        summary: "illumination volumes against colour + depth textures and reference planes, caustics on underwater objects",
        implemented: false,
    },
    TechniqueInfo {
        name: "caustic-triangles",
        paper: "4",
        summary: "layered distance maps, photon hit image, caustic triangles into a light cube map (Umenhoffer et al.)",
        implemented: true,
    },
    TechniqueInfo {
        name: "cascaded",
        paper: "5",
        summary: "cascaded caustic maps for oceans: four light-view cascades, photons splatted in eye space, dispersion (Backlund)",
        implemented: true,
    },
];

pub fn is_known(name: &str) -> bool {
    TECHNIQUES.iter().any(|t| t.name == name)
}

pub fn names() -> Vec<&'static str> {
    TECHNIQUES.iter().map(|t| t.name).collect()
}

pub fn info(name: &str) -> Option<&'static TechniqueInfo> {
    TECHNIQUES.iter().find(|t| t.name == name)
}
