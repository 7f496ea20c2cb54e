//! The page's water: the scene's own source on the page's clock until the first click, then the
//! ripple simulation resident in the GPU frame, which clicks and drags drop into (as the viewer's
//! `Mode::Ripple`). Only the clock and the pending steps and drops live here; the heights never
//! leave the GPU.

use caustics_core::scene::{Water, WaterSource};
use caustics_core::water::ripple::{Drop, RippleParams};
use caustics_gpu::renderer::{FrameWater, WaterClock};

/// Most simulation steps a frame: a slow frame (a software adapter) runs the water slower than
/// real time rather than spending ever longer frames catching up.
const MAX_STEPS_PER_FRAME: u32 = 32;

pub struct PageWater {
    water: Water,
    /// Whether the ripple simulation replaced the scene's source.
    ripples: bool,
    params: RippleParams,
    /// Restarts of the simulation, so that the frame builds it again.
    generation: u64,
    /// The scene source's clock, seconds.
    time: f64,
    step_debt: f64,
    steps: u32,
    drops: Vec<Drop>,
    /// Multiplies the heights (0: flat water).
    pub amplitude: f64,
}

impl PageWater {
    pub fn new(water: &Water, time: f64) -> Self {
        PageWater {
            water: water.clone(),
            ripples: matches!(water.source, WaterSource::Ripple(_)),
            params: RippleParams::for_water(water),
            generation: 0,
            time,
            step_debt: 0.0,
            steps: 0,
            drops: Vec::new(),
            amplitude: 1.0,
        }
    }

    pub fn water(&self) -> &Water {
        &self.water
    }

    /// Advance by `dt` seconds of page time.
    pub fn advance(&mut self, dt: f64) {
        if self.ripples {
            self.step_debt += dt / self.params.time_step;
            let steps = (self.step_debt.floor().max(0.0) as u32).min(MAX_STEPS_PER_FRAME);
            self.step_debt = (self.step_debt - steps as f64).clamp(0.0, 1.0);
            self.steps += steps;
        } else {
            self.time += dt;
        }
    }

    /// Drop a ripple at water point `p`; the first switches the water to the simulation.
    pub fn drop_at(&mut self, p: glam::DVec2) {
        self.ripples = true;
        self.drops.push(Drop::click(&self.water, [p.x, p.y]));
    }

    /// Calm the simulation: it starts again still, without its initial drops.
    pub fn calm(&mut self) {
        self.ripples = true;
        self.params.drops.clear();
        self.params.steps = 0;
        self.generation += 1;
        self.steps = 0;
        self.drops.clear();
    }

    pub fn spec(&self) -> FrameWater {
        if self.ripples {
            FrameWater::Ripples {
                params: self.params.clone(),
                generation: self.generation,
            }
        } else {
            FrameWater::Scene
        }
    }

    /// This frame's clock and its pending drops; the steps and drops are handed over once.
    pub fn take(&mut self) -> (WaterClock, Vec<Drop>) {
        let clock = WaterClock {
            time: self.time,
            amplitude: self.amplitude,
            steps: std::mem::take(&mut self.steps),
        };
        (clock, std::mem::take(&mut self.drops))
    }
}
