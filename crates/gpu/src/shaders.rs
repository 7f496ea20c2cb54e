//! How the passes' WGSL is built. Each pass is a WESL main module beside the Rust that runs it,
//! importing what it shares by path (`import package::shaders::optics::refract_dir;`): the
//! modules under `shaders/` (the optics, the water surface, the reductions, the shading, the
//! caustics maps' sampling, the BVH) and its technique's own (`package::yuksel::common`).
//! build.rs compiles each into one WGSL string (names of imported items mangled as
//! `package_<module path>_<name>`), which `passes!` embeds.
//!
//! A technique's registry entry lists its passes, and the frame lists its own
//! ([`crate::registry::all_passes`]): a test validates every one with naga without a GPU, and
//! another that every `.wgsl` file of the crate is one of them or a module they import.

/// The optics every technique shares: Fresnel, refraction, the height field's normal. bevy_caustics'
/// material imports it as the WESL module `caustics_gpu::optics`.
pub const OPTICS: &str = include_str!("shaders/optics.wgsl");
/// How a surface reads the floor map's pyramid and the walls' maps: the final image's and
/// bevy_caustics' material's one copy, functions of their arguments alone (textures included),
/// imported here as `package::shaders::caustics_sampling` and there as
/// `caustics_gpu::caustics_sampling`.
pub const CAUSTICS_SAMPLING: &str = include_str!("shaders/caustics_sampling.wgsl");

/// The receivers' heights in the light's space (docs/receivers.md): the light-space point, the
/// map's bilinear height, a ray's meeting with it and a receiver point's share of the light there
/// (`receiver_share`, a shadow map's depth test). Functions of their arguments alone with no import:
/// `package::shaders::receivers` here, `caustics_gpu::receivers` in bevy_caustics' material.
pub const RECEIVERS: &str = include_str!("shaders/receivers.wgsl");

/// The shading rule: how a surface under the water turns a caustics map into the sun's light
/// (flat water's refracted sun, its absorbed light on any surface, the transmitted irradiance, the
/// pool's walls). The final image's and bevy_caustics' material's one copy, and an application's:
/// functions of their arguments alone with no import, so the text can be pasted ahead of any WGSL
/// (`format!("{CAUSTICS_LIGHT}{CAUSTICS_SAMPLING}{your_shader}")`) or imported as a WESL module
/// (`package::shaders::caustics_light` here, `caustics_gpu::caustics_light` in Bevy).
pub const CAUSTICS_LIGHT: &str = include_str!("shaders/caustics_light.wgsl");

/// The passes a module declares: each `NAME = "label", "file";` (the file under
/// `crates/gpu/src/`, the pass's WESL main module) becomes `pub const NAME: PassSource` holding
/// the WGSL build.rs compiled from it, and all of them the module's `PASSES`, so a pass is listed
/// where it is declared.
macro_rules! passes {
    ($($(#[$attr:meta])* $id:ident = $name:literal, $file:literal;)+) => {
        $(
            #[doc = concat!("The `", $name, "` pass: the WGSL compiled from `", $file, "`.")]
            #[doc = ""]
            $(#[$attr])*
            pub const $id: $crate::shaders::PassSource = $crate::shaders::PassSource {
                name: $name,
                file: $file,
                source: include_str!(concat!(env!("OUT_DIR"), "/wgsl/", $file)),
            };
        )+
        /// Every pass this module declares, for the registry.
        pub const PASSES: &[&$crate::shaders::PassSource] = &[$(&$id),+];
    };
}
pub(crate) use passes;

/// A pass shader: its name (for messages), its main module's file under `crates/gpu/src/` (for
/// tools and messages) and the WGSL compiled from it with everything it imports.
pub struct PassSource {
    /// The pass's label, e.g. "yuksel pass 2": the shader module's and the messages' name.
    pub name: &'static str,
    /// Its main WESL module, relative to `crates/gpu/src/`, e.g. "yuksel/pass2.wgsl".
    pub file: &'static str,
    /// The complete WGSL build.rs compiled from it, imports included.
    pub source: &'static str,
}

impl PassSource {
    /// The pass's shader module on `device`, labelled with its name.
    pub fn module(&self, device: &wgpu::Device) -> wgpu::ShaderModule {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(self.name),
            source: wgpu::ShaderSource::Wgsl(self.source.into()),
        })
    }
}
