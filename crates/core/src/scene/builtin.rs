//! The built-in scenes, usable by name; each is an ordinary scene file.

/// The built-in scenes as (name, scene file text) pairs;
/// [`Scene::builtin`](crate::scene::Scene::builtin) reads one by name.
pub const BUILTIN_SCENES: &[(&str, &str)] = &[
    ("pool", include_str!("scenes/pool.toml")),
    ("shore", include_str!("scenes/shore.toml")),
    ("reef", include_str!("scenes/reef.toml")),
    ("objects", include_str!("scenes/objects.toml")),
    ("glass", include_str!("scenes/glass.toml")),
    ("underwater", include_str!("scenes/underwater.toml")),
];
