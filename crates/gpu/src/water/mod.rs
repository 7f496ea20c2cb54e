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
    /// Wave vector, radians per world unit: the height is `amplitude · sin(k · p + phase)`.
    pub k: [f32; 2],
    /// Crest height above rest, world units.
    pub amplitude: f32,
    /// Phase at the frozen time (`φ − ω t`), radians.
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
    /// Where the function's origin sits on the water, world units: paper 2's `x`, `y` are
    /// measured from it.
    pub origin: [f32; 2],
    /// Paper 2's amplitude `A` (default 0.01, as in its listing).
    pub amplitude: f32,
    /// Paper 2's spatial frequency `W` (default 10).
    pub frequency: f32,
    /// Paper 2's base octave factor `F` (default 1): octave `i` uses `f_i = F / 2^i`.
    pub octave_base: f32,
    /// Paper 2's speed `S` (default 2), radians per second.
    pub speed: f32,
    /// The instant, seconds (the `t` of `S t`).
    pub time: f32,
    /// Paper 2's octave count `O` (default 5).
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
