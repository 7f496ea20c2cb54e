//! The WGSL shared by the passes, once: the optics (`shaders/optics.wgsl`), the water surface
//! (`shaders/water.wgsl`), the reductions, the shading, the caustics maps' sampling and the BVH.
//! Each pass is a file of its own beside the Rust that runs it, composed with the shared files it
//! needs by [`compose`].
//!
//! A technique's registry entry lists its passes, and the frame lists its own
//! ([`crate::registry::all_passes`]): a test validates every one with naga without a GPU, and
//! another that every `.wgsl` file of the crate is one of them or a part they share.

pub const OPTICS: &str = include_str!("shaders/optics.wgsl");
pub const WATER: &str = include_str!("shaders/water.wgsl");
/// Min and max across workgroups through order-preserving u32 atomics.
pub const REDUCE: &str = include_str!("shaders/reduce.wgsl");
/// The final image's shading of a surface point: sky, sun, walls, objects.
pub const SHADING: &str = include_str!("shaders/shading.wgsl");
/// How a surface reads the floor map's pyramid and the walls' maps: the final image's and
/// bevy_caustics' material's one copy, a module of functions of their arguments alone (textures
/// included), so it composes here as WGSL and imports there as WESL.
pub const CAUSTICS_SAMPLING: &str = include_str!("shaders/caustics_sampling.wgsl");
/// Rays against the objects' bounding-volume hierarchies, in buffers of [`crate::bvh`]'s layout.
pub const BVH: &str = include_str!("shaders/bvh.wgsl");

/// Shared files followed by a pass's own source.
pub fn compose(shared: &[&str], pass: &str) -> String {
    let mut s = String::new();
    for part in shared {
        s.push_str(part);
        s.push('\n');
    }
    s.push_str(pass);
    s
}

/// The passes a module declares: each `NAME = "label", [shared parts], "file";` (the file under
/// `crates/gpu/src/`, whose text is the pass's own source) becomes `pub const NAME: PassSource`,
/// and all of them the module's `PASSES`, so a pass is listed where it is declared.
macro_rules! passes {
    ($($(#[$attr:meta])* $id:ident = $name:literal, [$($shared:expr),* $(,)?], $file:literal;)+) => {
        $(
            $(#[$attr])*
            pub const $id: $crate::shaders::PassSource = $crate::shaders::PassSource {
                name: $name,
                shared: &[$($shared),*],
                file: $file,
                source: include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/", $file)),
            };
        )+
        /// Every pass this module declares, for the registry.
        pub const PASSES: &[&$crate::shaders::PassSource] = &[$(&$id),+];
    };
}
pub(crate) use passes;

/// A pass shader: its name (for messages), its file under `crates/gpu/src/` (for tools and
/// messages; a test holds it to `source`), the shared files it includes, and its own source.
pub struct PassSource {
    pub name: &'static str,
    pub file: &'static str,
    pub shared: &'static [&'static str],
    pub source: &'static str,
}

impl PassSource {
    pub fn composed(&self) -> String {
        compose(self.shared, self.source)
    }

    pub fn module(&self, device: &wgpu::Device) -> wgpu::ShaderModule {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(self.name),
            source: wgpu::ShaderSource::Wgsl(self.composed().into()),
        })
    }
}
