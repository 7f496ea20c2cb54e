//! GPU-side descriptions of the water surfaces, laid out as the structs of `shaders/water.wgsl`.

pub mod field;
pub mod ocean;
pub mod patches;
pub mod ripple;

use caustics_core::water::procedural::Procedural;
use caustics_core::water::waves::Waves;

/// Mirrors `SineWave` in `shaders/water.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuSineWave {
    pub k: [f32; 2],
    pub amplitude: f32,
    pub phase: f32,
}

impl GpuSineWave {
    /// The waves frozen at their time, one entry per component.
    pub fn from_waves(waves: &Waves) -> Vec<GpuSineWave> {
        waves
            .terms()
            .iter()
            .map(|t| GpuSineWave {
                k: [t.k.x as f32, t.k.y as f32],
                amplitude: t.amplitude as f32,
                phase: t.phase as f32,
            })
            .collect()
    }
}

/// Mirrors `ProceduralWave` in `shaders/water.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct GpuProceduralWave {
    pub origin: [f32; 2],
    pub amplitude: f32,
    pub frequency: f32,
    pub octave_base: f32,
    pub speed: f32,
    pub time: f32,
    pub octaves: u32,
}

impl From<&Procedural> for GpuProceduralWave {
    fn from(p: &Procedural) -> Self {
        GpuProceduralWave {
            origin: [p.params.origin[0] as f32, p.params.origin[1] as f32],
            amplitude: p.params.amplitude as f32,
            frequency: p.params.frequency as f32,
            octave_base: p.params.octave_base as f32,
            speed: p.params.speed as f32,
            time: p.t as f32,
            octaves: p.params.octaves,
        }
    }
}
