//! The viewer's water: the scene's own source animated in time, or the interactive ripple
//! simulation that clicks drop into, each scaled by the panel's amplitude.
//!
//! The simulation runs on the GPU ([`GpuRipples`]) when the adapter builds it, else on its CPU twin
//! ([`Ripples`]); either way the heights come back to the CPU each frame, because every technique
//! and the final image take the surface as a [`Surface`] (the techniques through `Runner`, which
//! samples it on the map's lattice).

use glam::DVec2;

use caustics_core::grid::Grid;
use caustics_core::scene::{Water, WaterSource};
use caustics_core::water::ripple::{Drop, RippleParams, Ripples};
use caustics_core::water::{GridSurface, Surface};
use caustics_gpu::GpuContext;
use caustics_gpu::water::ripple::GpuRipples;

/// Where the surface comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The scene's source (waves, procedural, ocean, height field) at the viewer's clock.
    Scene,
    /// The ripple simulation, stepped per frame; a click drops a ripple.
    Ripple,
}

/// Most simulation steps per frame: a slow frame (lavapipe) then runs the water slower than real
/// time rather than spending ever longer frames catching up.
const MAX_STEPS_PER_FRAME: u32 = 32;

enum Simulation {
    Gpu { sim: Box<GpuRipples>, heights: Grid },
    Cpu(Box<Ripples>),
}

/// A surface scaled in height: `k h(x, y)` with gradient `k ∇h`. It is how the amplitude slider
/// reaches every source alike, analytic or sampled.
struct Scaled {
    inner: Box<dyn Surface>,
    k: f64,
}

impl Surface for Scaled {
    fn height(&self, p: DVec2) -> f64 {
        self.k * self.inner.height(p)
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.k * self.inner.gradient(p)
    }
    fn height_gradient(&self, p: DVec2) -> (f64, DVec2) {
        let (h, g) = self.inner.height_gradient(p);
        (self.k * h, self.k * g)
    }
    fn lattice(&self) -> Option<(usize, usize)> {
        self.inner.lattice()
    }
}

pub struct WaterState {
    pub mode: Mode,
    /// Multiplies the heights (0: flat water).
    pub amplitude: f64,
    /// Simulated seconds per real second.
    pub time_scale: f64,
    pub paused: bool,
    /// The scene source's clock, seconds.
    pub time: f64,
    /// A click's drop: radius and height added at the centre (negative: a dent), world units.
    pub drop_radius: f64,
    pub drop_strength: f64,
    /// The scene's water.
    water: Water,
    /// The same water with its source forgotten, for the techniques whenever the surface is not
    /// the file's height field (`Runner` hands a height-field source to a technique as it is,
    /// which would ignore the amplitude and the ripples).
    sampled: Water,
    params: RippleParams,
    sim: Option<Simulation>,
    /// Fractional steps carried to the next frame.
    step_debt: f64,
    /// Steps taken since the simulation started.
    sim_steps: u64,
    /// Counts the changes of the simulation's state, for [`WaterState::key`].
    generation: u64,
    /// Why the simulation runs on the CPU, when it does.
    pub sim_note: Option<String>,
    /// Whether the simulation lives in the GPU frame (`caustics_gpu::renderer`): then this state
    /// only keeps the clock and hands the frame its steps and drops ([`take_pending`]).
    ///
    /// [`take_pending`]: Self::take_pending
    resident: bool,
    pending_steps: u32,
    pending_drops: Vec<Drop>,
    /// Counts the restarts of the simulation (a calm, a new mode), so the GPU frame knows to build it
    /// again.
    epoch: u64,
}

/// What identifies the surface of a frame: equal keys, equal surfaces, so the techniques need not
/// run again when only the camera moved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SurfaceKey {
    mode: Mode,
    amplitude: u64,
    time: u64,
    generation: u64,
}

impl WaterState {
    /// The scene's water at `time`; a scene whose source is a ripple simulation starts in
    /// [`Mode::Ripple`] with that simulation's parameters (its file source *is* the simulation).
    pub fn new(water: &Water, time: f64, ripple: bool) -> Self {
        let params = RippleParams::for_water(water);
        let is_ripple = matches!(water.source, WaterSource::Ripple(_));
        let mut sampled = water.clone();
        sampled.source = WaterSource::Flat;
        let click = Drop::click(water, [0.0, 0.0]);
        WaterState {
            mode: if ripple || is_ripple {
                Mode::Ripple
            } else {
                Mode::Scene
            },
            amplitude: 1.0,
            time_scale: 1.0,
            paused: false,
            time,
            drop_radius: click.radius,
            drop_strength: click.strength,
            water: water.clone(),
            sampled,
            params,
            sim: None,
            step_debt: 0.0,
            sim_steps: 0,
            generation: 0,
            sim_note: None,
            resident: false,
            pending_steps: 0,
            pending_drops: Vec::new(),
            epoch: 0,
        }
    }

    /// Hand the ripple simulation to the GPU frame (or take it back): from now on the steps and
    /// drops wait in [`take_pending`](Self::take_pending). Either way the simulation starts again.
    pub fn set_resident(&mut self, resident: bool) {
        if self.resident != resident {
            self.resident = resident;
            self.sim = None;
            self.sim_steps = 0;
            self.epoch += 1;
            self.generation += 1;
        }
    }

    /// The simulation's parameters and restart count, for the GPU frame's ripple source.
    pub fn ripple_spec(&self) -> (&RippleParams, u64) {
        (&self.params, self.epoch)
    }

    /// The steps and drops asked for since the last call (a resident simulation's).
    pub fn take_pending(&mut self) -> (u32, Vec<Drop>) {
        (
            std::mem::take(&mut self.pending_steps),
            std::mem::take(&mut self.pending_drops),
        )
    }

    pub fn water(&self) -> &Water {
        &self.water
    }

    /// The water as the techniques should see it (see `sampled`).
    pub fn technique_water(&self) -> &Water {
        let as_file = self.mode == Mode::Scene && self.amplitude == 1.0;
        if as_file { &self.water } else { &self.sampled }
    }

    /// Whether the scene mode has a source that changes with time (a height field or flat water
    /// does not, so a paused-or-not clock makes no difference to them).
    pub fn scene_source_moves(&self) -> bool {
        !matches!(
            self.water.source,
            WaterSource::Flat | WaterSource::HeightField(_)
        )
    }

    /// Whether frames keep changing without input.
    pub fn animating(&self) -> bool {
        !self.paused
            && match self.mode {
                Mode::Scene => self.scene_source_moves(),
                Mode::Ripple => true,
            }
    }

    pub fn key(&self) -> SurfaceKey {
        SurfaceKey {
            mode: self.mode,
            amplitude: self.amplitude.to_bits(),
            time: match self.mode {
                Mode::Scene if self.scene_source_moves() => self.time.to_bits(),
                _ => 0,
            },
            generation: match self.mode {
                Mode::Scene => 0,
                Mode::Ripple => self.generation,
            },
        }
    }

    /// Advance the clock by `dt` real seconds (nothing while paused): the scene source's time,
    /// or the simulation's steps.
    pub fn advance(&mut self, gpu: Option<&GpuContext>, dt: f64) -> anyhow::Result<()> {
        if self.paused {
            return Ok(());
        }
        let dt = dt * self.time_scale;
        match self.mode {
            Mode::Scene => self.time += dt,
            Mode::Ripple if self.resident => {
                let steps = self.steps_for(dt);
                if steps > 0 {
                    self.pending_steps += steps;
                    self.sim_steps += steps as u64;
                    self.generation += 1;
                }
            }
            Mode::Ripple => {
                self.ensure_sim(gpu)?;
                let steps = self.steps_for(dt);
                if steps > 0 {
                    self.step(gpu, steps)?;
                }
            }
        }
        Ok(())
    }

    /// The whole simulation steps `dt` simulated seconds make, with the fraction left over
    /// carried to the next frame (at most [`MAX_STEPS_PER_FRAME`]).
    fn steps_for(&mut self, dt: f64) -> u32 {
        self.step_debt += dt / self.params.time_step;
        let steps = (self.step_debt.floor().max(0.0) as u32).min(MAX_STEPS_PER_FRAME);
        self.step_debt = (self.step_debt - steps as f64).clamp(0.0, 1.0);
        steps
    }

    /// Drop a ripple at water point `p` (switching to the simulation if need be).
    pub fn drop_at(&mut self, gpu: Option<&GpuContext>, p: DVec2) -> anyhow::Result<()> {
        self.mode = Mode::Ripple;
        let d = Drop {
            position: [p.x, p.y],
            radius: self.drop_radius.max(1e-6),
            strength: self.drop_strength,
        };
        if self.resident {
            self.pending_drops.push(d);
            self.generation += 1;
            return Ok(());
        }
        self.ensure_sim(gpu)?;
        match self.sim.as_mut().expect("just made") {
            Simulation::Gpu { sim, heights } => {
                let ctx = gpu.expect("a GPU simulation has a GPU");
                GpuRipples::drop(sim, ctx, &d);
                *heights = sim.read(ctx)?;
            }
            Simulation::Cpu(r) => Ripples::drop(r, &d),
        }
        self.generation += 1;
        Ok(())
    }

    /// Calm the simulation: it restarts still, without the initial drops.
    pub fn calm(&mut self) {
        self.sim = None;
        self.sim_steps = 0;
        self.params.drops.clear();
        self.params.steps = 0;
        self.generation += 1;
        self.epoch += 1;
        self.pending_steps = 0;
        self.pending_drops.clear();
    }

    /// Simulated seconds of the ripple state, or the scene clock.
    pub fn clock(&self) -> f64 {
        match self.mode {
            Mode::Ripple => self.sim_steps as f64 * self.params.time_step,
            Mode::Scene => self.time,
        }
    }

    pub fn simulation_backend(&self) -> Option<&'static str> {
        if self.resident && self.mode == Mode::Ripple {
            return Some("GPU");
        }
        match &self.sim {
            Some(Simulation::Gpu { .. }) => Some("GPU"),
            Some(Simulation::Cpu(_)) => Some("CPU"),
            None => None,
        }
    }

    /// The surface of this frame.
    pub fn surface(&mut self, gpu: Option<&GpuContext>) -> anyhow::Result<Box<dyn Surface>> {
        let inner: Box<dyn Surface> = match self.mode {
            Mode::Scene => self.water.surface_at(self.time)?,
            Mode::Ripple => {
                self.ensure_sim(gpu)?;
                let grid = match self.sim.as_ref().expect("just made") {
                    Simulation::Gpu { heights, .. } => heights.clone(),
                    Simulation::Cpu(r) => r.current().clone(),
                };
                Box::new(GridSurface {
                    grid,
                    size: self.water.size,
                    edge: self.water.edge(),
                })
            }
        };
        Ok(if self.amplitude == 1.0 {
            inner
        } else {
            Box::new(Scaled {
                inner,
                k: self.amplitude,
            })
        })
    }

    /// Build the simulation on first use: on the GPU when there is one and it accepts the
    /// parameters, else on the CPU. The initial drops and settling steps run here.
    fn ensure_sim(&mut self, gpu: Option<&GpuContext>) -> anyhow::Result<()> {
        if self.sim.is_some() {
            return Ok(());
        }
        let (size, edge) = (self.water.size, self.water.edge());
        let gpu_sim = match gpu {
            Some(ctx) => match GpuRipples::new(ctx, &self.params, size, edge) {
                Ok(sim) => Some(sim),
                Err(e) => {
                    self.sim_note = Some(format!("ripples on the CPU: {e}"));
                    None
                }
            },
            None => None,
        };
        match gpu_sim {
            Some(mut sim) => {
                let ctx = gpu.expect("checked");
                for d in &self.params.drops {
                    sim.drop(ctx, d);
                }
                let heights = Grid::new(self.params.resolution, self.params.resolution);
                self.sim = Some(Simulation::Gpu {
                    sim: Box::new(sim),
                    heights,
                });
                // Also reads the heights back, with zero steps too.
                self.step(gpu, self.params.steps)?;
            }
            None => {
                let mut r = Ripples::new(&self.params, size, edge)?;
                r.run_initial();
                self.sim_steps = self.params.steps as u64;
                self.sim = Some(Simulation::Cpu(Box::new(r)));
            }
        }
        self.generation += 1;
        Ok(())
    }

    fn step(&mut self, gpu: Option<&GpuContext>, steps: u32) -> anyhow::Result<()> {
        match self.sim.as_mut() {
            Some(Simulation::Gpu { sim, heights }) => {
                let ctx = gpu.expect("a GPU simulation has a GPU");
                let mut encoder =
                    ctx.device
                        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                            label: Some("viewer ripple steps"),
                        });
                sim.step(ctx, &mut encoder, steps);
                ctx.queue.submit([encoder.finish()]);
                *heights = sim.read(ctx)?;
            }
            Some(Simulation::Cpu(r)) => {
                for _ in 0..steps {
                    r.step();
                }
            }
            None => return Ok(()),
        }
        if steps > 0 {
            self.sim_steps += steps as u64;
            self.generation += 1;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use caustics_core::scene::Scene;

    fn pool_water() -> Water {
        Scene::builtin("pool").unwrap().water.unwrap()
    }

    #[test]
    fn amplitude_scales_height_and_gradient() {
        let mut w = WaterState::new(&pool_water(), 0.0, false);
        let p = DVec2::new(1.3, 2.1);
        let (h1, g1) = w.surface(None).unwrap().height_gradient(p);
        w.amplitude = 2.5;
        let (h2, g2) = w.surface(None).unwrap().height_gradient(p);
        assert!((h2 - 2.5 * h1).abs() < 1e-12);
        assert!((g2 - 2.5 * g1).length() < 1e-12);
        w.amplitude = 0.0;
        assert_eq!(w.surface(None).unwrap().height(p), 0.0);
    }

    #[test]
    fn the_key_changes_with_time_only_when_animating() {
        let mut w = WaterState::new(&pool_water(), 0.0, false);
        let k0 = w.key();
        w.paused = true;
        w.advance(None, 0.1).unwrap();
        assert_eq!(w.key(), k0);
        w.paused = false;
        w.advance(None, 0.1).unwrap();
        assert_ne!(w.key(), k0);
    }

    #[test]
    fn cpu_ripples_step_and_take_drops() {
        let mut w = WaterState::new(&pool_water(), 0.0, true);
        assert_eq!(w.mode, Mode::Ripple);
        let k0 = w.key();
        w.advance(None, 1.0 / 30.0).unwrap();
        assert_eq!(w.simulation_backend(), Some("CPU"));
        assert_ne!(w.key(), k0);
        w.calm();
        let p = DVec2::new(2.0, 2.0);
        assert_eq!(w.surface(None).unwrap().height(p), 0.0);
        w.drop_at(None, p).unwrap();
        assert!(w.surface(None).unwrap().height(p) < 0.0);
    }
}
