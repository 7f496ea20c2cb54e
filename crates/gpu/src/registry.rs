//! The one place that names every GPU technique: each entry is its [`Registered`] (defined beside
//! its code, pointing at core's description), and the frame's own passes sit beside them, so the
//! list of every pass the crate builds ([`all_passes`]) is derived from here and cannot miss one.

use crate::shaders::PassSource;
use crate::technique::{Registered, Technique};
use crate::{GpuContext, GpuError};

/// Every GPU technique, in one place: one line each.
pub const REGISTRY: &[Registered] = &[
    crate::yuksel::technique::REGISTERED,
    crate::yuksel::technique::TARGETS,
    crate::procedural::technique::REGISTERED,
    crate::procedural::technique::VERTEX,
    crate::procedural::technique::SCREEN,
    crate::procedural::technique::TEXTURE,
    crate::volumes::technique::REGISTERED,
    crate::caustic_triangles::technique::REGISTERED,
    crate::cascaded::technique::REGISTERED,
];

/// The registry entry of `name`, if it has a GPU implementation.
pub fn find(name: &str) -> Option<&'static Registered> {
    let name = caustics_core::techniques::canonical(name);
    REGISTRY.iter().find(|r| r.name() == name)
}

/// The registered technique `name` with the parameter tables `params` (keyed by technique, as in a
/// scene file's `[caustics]`), its pipelines built for `ctx`.
pub fn create(
    ctx: &GpuContext,
    name: &str,
    params: &toml::Table,
) -> Result<Box<dyn Technique>, GpuError> {
    let Some(entry) = find(name) else {
        return Err(GpuError::BadOption(format!(
            "no GPU technique `{name}` (registered: {})",
            REGISTRY
                .iter()
                .map(|r| r.name())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    };
    entry.create(ctx, params)
}

/// The technique a spec string names, with its parameters: `yuksel`, `yuksel:n=15,m=14`,
/// `caustic-triangles:photon_image=256` (the command line's and a scene's spelling, parsed and
/// checked by [`caustics_core::techniques::registry::Spec`]), its pipelines built for `ctx`.
pub fn from_spec(ctx: &GpuContext, spec: &str) -> Result<Box<dyn Technique>, GpuError> {
    let spec: caustics_core::techniques::registry::Spec = spec.parse()?;
    create(ctx, spec.name(), &spec.params)
}

/// The passes of the frame around the techniques: the water, the final image, the floor map's
/// pyramid and the probe of the shared math.
pub const FRAME_PASSES: &[&[&PassSource]] = &[
    crate::water::ocean::PASSES,
    crate::water::ripple::PASSES,
    crate::water::field::PASSES,
    crate::water::patches::PASSES,
    crate::final_image::PASSES,
    crate::final_image::slopes::PASSES,
    crate::map_mips::PASSES,
    crate::receivers::PASSES,
    crate::probe::PASSES,
];

/// Every pass shader of the crate, once each: the frame's, then each technique's.
pub fn all_passes() -> Vec<&'static PassSource> {
    let mut all: Vec<&'static PassSource> = Vec::new();
    let techniques = REGISTRY.iter().map(|r| r.passes);
    for pass in FRAME_PASSES.iter().copied().chain(techniques).flatten() {
        if !all.iter().any(|p| p.name == pass.name) {
            all.push(pass);
        }
    }
    all
}
