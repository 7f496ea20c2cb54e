//! WGSL sources. The math shared by all passes lives in `shaders/optics.wgsl` and
//! `shaders/water.wgsl`, once; each pass is its own file and is composed with the shared files it
//! needs by [`compose`] (plain concatenation: WGSL has no include, and a build-time preprocessor is
//! more machinery than two files need).
//!
//! Every composed pass is listed in [`ALL_PASSES`], which a test parses and validates with naga
//! without a GPU.

pub const OPTICS: &str = include_str!("shaders/optics.wgsl");
pub const WATER: &str = include_str!("shaders/water.wgsl");
/// Min and max across workgroups through order-preserving u32 atomics.
pub const REDUCE: &str = include_str!("shaders/reduce.wgsl");

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

/// A pass shader: its name (for messages), the shared files it includes, and its own source.
pub struct PassSource {
    pub name: &'static str,
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

pub const PROBE: PassSource = PassSource {
    name: "probe",
    shared: &[OPTICS, WATER],
    source: include_str!("shaders/probe.wgsl"),
};

pub const OCEAN_SPECTRUM: PassSource = PassSource {
    name: "ocean_spectrum",
    shared: &[],
    source: include_str!("shaders/ocean_spectrum.wgsl"),
};

pub const OCEAN_FFT: PassSource = PassSource {
    name: "ocean_fft",
    shared: &[],
    source: include_str!("shaders/ocean_fft.wgsl"),
};

pub const OCEAN_OUTPUT: PassSource = PassSource {
    name: "ocean_output",
    shared: &[],
    source: include_str!("shaders/ocean_output.wgsl"),
};

pub const RIPPLE_STEP: PassSource = PassSource {
    name: "ripple_step",
    shared: &[],
    source: include_str!("shaders/ripple_step.wgsl"),
};

pub const RIPPLE_DROP: PassSource = PassSource {
    name: "ripple_drop",
    shared: &[],
    source: include_str!("shaders/ripple_drop.wgsl"),
};

/// Every pass shader of the crate.
pub const ALL_PASSES: &[&PassSource] = &[
    &PROBE,
    &crate::yuksel::PREPASS,
    &crate::yuksel::PREPASS_FILL,
    &crate::yuksel::PREPASS_SPAN,
    &crate::yuksel::PASS2,
    &crate::yuksel::SCATTER_TIER,
    &crate::yuksel::SCATTER_FILL,
    &crate::yuksel::SCATTER_RESOLVE,
    &crate::yuksel::REGION,
    &crate::yuksel::REGION_BOUND,
    &crate::cascaded::EYE,
    &crate::cascaded::WATER_GBUFFER,
    &crate::cascaded::TERRAIN_GBUFFER,
    &crate::cascaded::PHOTONS,
    &crate::cascaded::COMPOSE,
    &crate::cascaded::DISPERSE,
    &crate::procedural::VERTEX,
    &crate::procedural::SCREEN,
    &crate::procedural::TARGET,
    &crate::procedural::DOWNSAMPLE,
    &crate::procedural::RESAMPLE,
    &OCEAN_SPECTRUM,
    &OCEAN_FFT,
    &OCEAN_OUTPUT,
    &RIPPLE_STEP,
    &RIPPLE_DROP,
    &crate::water::patches::WATER_PATCHES,
    &crate::water::field::WAVES,
    &crate::water::field::PROCEDURAL,
    &crate::water::field::GRID,
    &crate::water::field::RIPPLE_CLEAR,
    &crate::final_image::FINAL_IMAGE,
    &crate::final_image::FINAL_IMAGE_SLAB,
    &crate::final_image::slopes::WATER_SLOPES_BASE,
    &crate::final_image::slopes::WATER_SLOPES_HALVE,
    &crate::final_image::CAUSTICS_MIPS,
    &crate::caustic_triangles::PHOTON,
    &crate::caustic_triangles::IRRADIANCE,
    &crate::caustic_triangles::TRIANGLES,
    &crate::caustic_triangles::BAND_BOUND,
    &crate::caustic_triangles::SPLAT,
    &crate::caustic_triangles::PYRAMID,
    &crate::caustic_triangles::CUBE,
    &crate::caustic_triangles::SHADOW,
    &crate::caustic_triangles::WATER_PHOTON,
    &crate::caustic_triangles::COPY_BAND,
    &crate::caustic_triangles::camera::CAMERA,
    &crate::volumes::DEPTH,
    &crate::volumes::WATER_PASS,
    &crate::volumes::SLICES,
    &crate::volumes::FLOOR,
    &crate::volumes::SHADE,
    &crate::volumes::VIEW,
];
