//! Interactive ripples: the damped wave equation
//!
//! `∂²h/∂t² + d ∂h/∂t = c² ∇²h`
//!
//! (`c` the wave speed, `d` the damping rate) on an `N × N` grid over the scene square, advanced by
//! the explicit second-order leapfrog (central-difference) scheme of height-field water in games,
//! with its damping term discretised consistently. The state is a ping-pong pair of height grids,
//! `previous` (step `n − 1`) and `current` (step `n`).
//!
//! **The scheme.** Central differences in time, `h_tt ≈ (h⁺ − 2h + h⁻) / Δt²` and
//! `h_t ≈ (h⁺ − h⁻) / (2Δt)`, and the 5-point Laplacian `∇²h ≈ (h_n + h_s + h_e + h_w − 4h) / Δx²`
//! give, after multiplying by `Δt²`,
//!
//! `h⁺ − 2h + h⁻ + γ (h⁺ − h⁻) = C² (h_n + h_s + h_e + h_w − 4h)`, `γ = d Δt / 2`, `C = c Δt / Δx`,
//!
//! so `h⁺ = (2h − (1 − γ) h⁻ + C² (h_n + h_s + h_e + h_w − 4h)) / (1 + γ)` ([`update_cell`]). It is
//! second-order accurate and, for `γ ≥ 0`, stable exactly when the Courant number `C < 1/√2` (the
//! von Neumann condition of the 2-D 5-point leapfrog scheme). Without damping it conserves the
//! discrete energy of [`Ripples::energy`] exactly (up to `f32` rounding); with damping that energy never grows and decays
//! at about the continuum rate: the amplitude as `e^{−d t / 2}`, the energy as `e^{−d t}`.
//!
//! **Edges.** [`Edge::Wrap`]: periodic. [`Edge::Clamp`]: a missing neighbour reads the cell itself,
//! i.e. a zero normal derivative (Neumann): waves reflect from the walls, as in a pool. Both keep the
//! total volume `Σ h Δx²` constant.
//!
//! **Precision.** The update runs in `f32` in the order a WGSL compute shader evaluates it (one
//! invocation per cell reading the four neighbours in `current` and its own cell in `previous`), so
//! a GPU twin matches it to rounding.
//!
//! **A scene's water.** The simulation a view runs on a scene's water ([`RippleParams::for_water`])
//! and the drop a click makes on it ([`Drop::click`]) are defined in [`crate::scene`], which knows
//! the scene's water: this module knows only its own grid.

use std::f64::consts::{PI, SQRT_2};
use std::fmt;

use serde::{Deserialize, Serialize};

use super::GridSurface;
use crate::error::{Error, Result, finite, non_negative, positive};
use crate::grid::{Edge, Grid};
use crate::parallel::prelude::*;

/// Parameters of the simulation as a scene file states them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RippleParams {
    /// Cells along each side of the scene square (from 4 to 4096).
    pub resolution: usize,
    /// Wave speed `c`, world units per second.
    pub wave_speed: f64,
    /// Damping rate `d`, per second: the energy decays as `e^{−d t}`.
    pub damping: f64,
    /// Time step `Δt`, seconds. Stability needs `c Δt / Δx < 1/√2` with `Δx = size / resolution`;
    /// the default (1/240 s) keeps the default 256-cell grid on a unit square at 0.53.
    pub time_step: f64,
    /// Drops applied by [`Ripples::run_initial`], in order.
    pub drops: Vec<Drop>,
    /// Steps simulated after the initial drops, before the surface is used (default 120, i.e.
    /// 0.5 s: the rings have travelled a quarter of a unit square).
    pub steps: u32,
}

/// A drop: a smooth cosine bump `strength · ½ (1 + cos(π r / radius))` for `r < radius` added to the
/// surface at rest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Drop {
    /// Centre, world units.
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub position: [f64; 2],
    /// Radius of the bump, world units.
    pub radius: f64,
    /// Height added at the centre, world units; negative for a dent.
    pub strength: f64,
}

impl Default for RippleParams {
    fn default() -> Self {
        let drop = |x, y, radius, strength| Drop {
            position: [x, y],
            radius,
            strength,
        };
        RippleParams {
            resolution: 256,
            wave_speed: 0.5,
            damping: 0.5,
            time_step: 1.0 / 240.0,
            // Three dents of about a centimetre, spread over the unit square so that their rings
            // cross: the default scene is 1 unit across.
            drops: vec![
                drop(0.32, 0.38, 0.08, -0.012),
                drop(0.70, 0.62, 0.06, -0.010),
                drop(0.42, 0.78, 0.05, -0.008),
            ],
            steps: 120,
        }
    }
}

/// One cell's leapfrog update (see the module documentation): `prev` and `cur` are the cell's
/// heights at steps `n − 1` and `n`, `n, s, e, w` its neighbours' at step `n` (`+y`, `−y`, `+x`,
/// `−x`), `courant2 = (c Δt / Δx)²`, `gamma = d Δt / 2`. Returns the height at step `n + 1`.
///
/// The WGSL twin is, line for line,
///
/// ```wgsl
/// let laplacian = (n + s) + (e + w) - 4.0 * cur;
/// return (2.0 * cur - (1.0 - gamma) * prev + courant2 * laplacian) / (1.0 + gamma);
/// ```
///
/// Pairing `(n + s)` and `(e + w)` keeps a mirror-symmetric state exactly symmetric in `f32`.
#[allow(
    clippy::too_many_arguments,
    reason = "the eight inputs of one shader invocation, as the WGSL twin reads them"
)]
#[inline]
pub fn update_cell(
    prev: f32,
    cur: f32,
    n: f32,
    s: f32,
    e: f32,
    w: f32,
    courant2: f32,
    gamma: f32,
) -> f32 {
    let laplacian = (n + s) + (e + w) - 4.0 * cur;
    (2.0 * cur - (1.0 - gamma) * prev + courant2 * laplacian) / (1.0 + gamma)
}

/// The ripple state: two height grids over `[0, size]²` (sampled on the [`Grid`] convention) and
/// the constants of the scheme.
#[derive(Clone)]
pub struct Ripples {
    previous: Grid,
    current: Grid,
    size: f64,
    edge: Edge,
    wave_speed: f64,
    time_step: f64,
    courant2: f32,
    gamma: f32,
    drops: Vec<Drop>,
    steps: u32,
    steps_taken: u64,
}

impl fmt::Debug for Ripples {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Ripples")
            .field("resolution", &self.current.cols)
            .field("size", &self.size)
            .field("edge", &self.edge)
            .field("courant2", &self.courant2)
            .field("gamma", &self.gamma)
            .field("steps_taken", &self.steps_taken)
            .finish_non_exhaustive()
    }
}

impl Ripples {
    /// A still surface over a square of side `size`, checking every parameter (the Courant number
    /// included).
    pub fn new(params: &RippleParams, size: f64, edge: Edge) -> Result<Ripples> {
        validate(params, size)?;
        let n = params.resolution;
        let dx = size / n as f64;
        let courant = params.wave_speed * params.time_step / dx;
        Ok(Ripples {
            previous: Grid::new(n, n),
            current: Grid::new(n, n),
            size,
            edge,
            wave_speed: params.wave_speed,
            time_step: params.time_step,
            courant2: (courant * courant) as f32,
            gamma: (0.5 * params.damping * params.time_step) as f32,
            drops: params.drops.clone(),
            steps: params.steps,
            steps_taken: 0,
        })
    }

    /// The heights at the latest step.
    pub fn current(&self) -> &Grid {
        &self.current
    }

    /// The heights one step earlier.
    pub fn previous(&self) -> &Grid {
        &self.previous
    }

    /// `(c Δt / Δx)²`, as [`update_cell`] takes it (a GPU twin's uniform).
    pub fn courant2(&self) -> f32 {
        self.courant2
    }

    /// `d Δt / 2`, as [`update_cell`] takes it (a GPU twin's uniform).
    pub fn gamma(&self) -> f32 {
        self.gamma
    }

    /// Simulated time since the start, seconds.
    pub fn time(&self) -> f64 {
        self.steps_taken as f64 * self.time_step
    }

    /// Add a drop to the surface at rest: the bump goes into both grids, so it starts with zero
    /// velocity and the volume it adds stays constant. With [`Edge::Wrap`] it is measured by the
    /// nearest periodic image, so a drop near an edge reappears across it.
    pub fn drop(&mut self, d: &Drop) {
        let n = self.current.cols;
        let dx = self.size / n as f64;
        let centre = [d.position[0], d.position[1]];
        // Cells whose centre can lie within the radius, per axis; all of them if that spans the grid.
        let span = |c: f64| -> Vec<usize> {
            let lo = ((c - d.radius) / dx - 0.5).floor() as i64;
            let hi = ((c + d.radius) / dx - 0.5).ceil() as i64;
            match self.edge {
                Edge::Wrap if hi - lo + 1 >= n as i64 => (0..n).collect(),
                Edge::Wrap => (lo..=hi).map(|a| a.rem_euclid(n as i64) as usize).collect(),
                Edge::Clamp => (lo.max(0)..=hi.min(n as i64 - 1))
                    .map(|a| a as usize)
                    .collect(),
            }
        };
        let offset = |a: usize, c: f64| -> f64 {
            let o = (a as f64 + 0.5) * dx - c;
            match self.edge {
                Edge::Wrap => o - self.size * (o / self.size).round(),
                Edge::Clamp => o,
            }
        };
        let (cols, rows) = (span(centre[0]), span(centre[1]));
        for &i in &rows {
            let oy = offset(i, centre[1]);
            for &j in &cols {
                let ox = offset(j, centre[0]);
                let r = (ox * ox + oy * oy).sqrt();
                if r < d.radius {
                    let bump = (d.strength * 0.5 * (1.0 + (PI * r / d.radius).cos())) as f32;
                    self.current.data[i * n + j] += bump;
                    self.previous.data[i * n + j] += bump;
                }
            }
        }
    }

    /// Advance one time step: every cell by [`update_cell`], the new heights overwriting
    /// `previous` (each cell reads only its own previous height), then the two grids swap.
    pub fn step(&mut self) {
        let n = self.current.cols;
        let (courant2, gamma, edge) = (self.courant2, self.gamma, self.edge);
        let cur = &self.current;
        self.previous
            .data
            .par_chunks_mut(n)
            .enumerate()
            .for_each(|(i, row)| {
                let (north, south) = (neighbour(i, 1, n, edge), neighbour(i, -1, n, edge));
                for (j, prev) in row.iter_mut().enumerate() {
                    let (east, west) = (neighbour(j, 1, n, edge), neighbour(j, -1, n, edge));
                    *prev = update_cell(
                        *prev,
                        cur.at(i, j),
                        cur.at(north, j),
                        cur.at(south, j),
                        cur.at(i, east),
                        cur.at(i, west),
                        courant2,
                        gamma,
                    );
                }
            });
        std::mem::swap(&mut self.previous, &mut self.current);
        self.steps_taken += 1;
    }

    /// Apply the parameters' drops, then simulate their settling steps.
    pub fn run_initial(&mut self) {
        for d in self.drops.clone() {
            self.drop(&d);
        }
        for _ in 0..self.steps {
            self.step();
        }
    }

    /// The current heights as a surface (bicubic between samples, edges per the simulation's rule).
    pub fn surface(&self) -> GridSurface {
        GridSurface {
            grid: self.current.clone(),
            size: self.size,
            edge: self.edge,
        }
    }

    /// The discrete energy (per unit density and gravity-free: height² · area / time²) between the
    /// two stored steps,
    ///
    /// `E = ½ Δx² [ Σ_cells ((h − h⁻) / Δt)² + (c / Δx)² Σ_edges (δh)(δh⁻) ]`,
    ///
    /// kinetic plus potential, the potential term pairing the differences `δ` across each grid edge
    /// (the wrapped ones with [`Edge::Wrap`], none across the walls with [`Edge::Clamp`]) at the two
    /// steps. Taking the inner product of the scheme with `h⁺ − h⁻` shows that this is exactly
    /// conserved without damping and non-increasing with it. It is positive while the Courant
    /// condition holds.
    pub fn energy(&self) -> f64 {
        let n = self.current.cols;
        let dx = self.size / n as f64;
        let (h, hp) = (&self.current, &self.previous);
        let at = |g: &Grid, i: usize, j: usize| g.at(i, j) as f64;
        let mut kinetic = 0.0;
        let mut potential = 0.0;
        for i in 0..n {
            for j in 0..n {
                let v = (at(h, i, j) - at(hp, i, j)) / self.time_step;
                kinetic += v * v;
                // The edges to the +x and +y neighbours; at a wall the clamped neighbour is the
                // cell itself and the difference vanishes.
                for (a, b) in [
                    (i, neighbour(j, 1, n, self.edge)),
                    (neighbour(i, 1, n, self.edge), j),
                ] {
                    potential += (at(h, a, b) - at(h, i, j)) * (at(hp, a, b) - at(hp, i, j));
                }
            }
        }
        let c = self.wave_speed / dx;
        0.5 * dx * dx * (kinetic + c * c * potential)
    }
}

/// The index `d` cells from `a` along an axis of `n` cells: periodic or clamped.
#[inline]
fn neighbour(a: usize, d: isize, n: usize, edge: Edge) -> usize {
    let b = a as isize + d;
    match edge {
        Edge::Wrap => b.rem_euclid(n as isize) as usize,
        Edge::Clamp => b.clamp(0, n as isize - 1) as usize,
    }
}

fn validate(p: &RippleParams, size: f64) -> Result<()> {
    let field =
        |name: &str, problem: String| Err(Error::field(format!("water.ripple.{name}"), problem));
    positive("water.size", size)?;
    if !(4..=4096).contains(&p.resolution) {
        return field(
            "resolution",
            format!("must be between 4 and 4096, got {}", p.resolution),
        );
    }
    positive("water.ripple.wave_speed", p.wave_speed)?;
    non_negative("water.ripple.damping", &[p.damping])?;
    positive("water.ripple.time_step", p.time_step)?;
    let dx = size / p.resolution as f64;
    let courant = p.wave_speed * p.time_step / dx;
    if courant >= 1.0 / SQRT_2 {
        let largest = dx / (p.wave_speed * SQRT_2);
        return field(
            "time_step",
            format!(
                "is {} s, too long for a stable simulation: the Courant number c·dt/dx is {courant:.3} \
                 (wave_speed {} over cells of {dx:.4e} = size {size} / resolution {}) and must stay \
                 below 1/√2 ≈ 0.707; use a time step below {largest:.4e} s, a lower wave_speed or a \
                 coarser resolution",
                p.time_step, p.wave_speed, p.resolution
            ),
        );
    }
    for (k, d) in p.drops.iter().enumerate() {
        let at = |name: &str| format!("water.ripple.drops[{k}].{name}");
        finite(&at("position"), &d.position)?;
        finite(&at("strength"), &[d.strength])?;
        if !(d.radius > 0.0 && d.radius <= 0.5 * size) {
            return field(
                &format!("drops[{k}].radius"),
                format!(
                    "must be positive and at most half the scene size ({}), got {}",
                    0.5 * size,
                    d.radius
                ),
            );
        }
        if d.radius < dx {
            return field(
                &format!("drops[{k}].radius"),
                format!(
                    "is {}, smaller than one cell ({dx:.4e} = size {size} / resolution {}): the \
                     grid cannot resolve the drop",
                    d.radius, p.resolution
                ),
            );
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(resolution: usize, damping: f64, time_step: f64) -> RippleParams {
        RippleParams {
            resolution,
            wave_speed: 0.5,
            damping,
            time_step,
            drops: Vec::new(),
            steps: 0,
        }
    }

    fn central_drop(size: f64) -> Drop {
        Drop {
            position: [0.5 * size, 0.5 * size],
            radius: 0.1 * size,
            strength: -0.01,
        }
    }

    fn volume(r: &Ripples) -> f64 {
        let dx = r.size / r.current.cols as f64;
        r.current.data.iter().map(|&v| v as f64).sum::<f64>() * dx * dx
    }

    #[test]
    fn undamped_energy_is_conserved() {
        for edge in [Edge::Wrap, Edge::Clamp] {
            let mut r = Ripples::new(&params(64, 0.0, 1.0 / 120.0), 1.0, edge).unwrap();
            r.drop(&central_drop(1.0));
            r.drop(&Drop {
                position: [0.93, 0.1],
                radius: 0.07,
                strength: 0.006,
            });
            let e0 = r.energy();
            assert!(e0 > 0.0);
            for _ in 0..500 {
                r.step();
                let e = r.energy();
                assert!(
                    (e / e0 - 1.0).abs() < 0.01,
                    "{edge:?}: energy {e} from {e0}"
                );
            }
        }
    }

    #[test]
    fn damped_energy_decays_at_the_continuum_rate() {
        let (damping, dt) = (0.5, 1.0 / 120.0);
        let mut r = Ripples::new(&params(64, damping, dt), 1.0, Edge::Wrap).unwrap();
        r.drop(&central_drop(1.0));
        let e0 = r.energy();
        let mut last = e0;
        for _ in 0..500 {
            r.step();
            let e = r.energy();
            assert!(e <= last * (1.0 + 1e-6), "energy grew from {last} to {e}");
            last = e;
        }
        let expected = (-damping * r.time()).exp();
        let ratio = last / e0;
        assert!(
            (ratio / expected - 1.0).abs() < 0.05,
            "energy ratio {ratio}, e^(-d t) = {expected}"
        );
    }

    #[test]
    fn volume_is_conserved() {
        for (edge, damping) in [(Edge::Wrap, 0.0), (Edge::Wrap, 0.8), (Edge::Clamp, 0.8)] {
            let mut r = Ripples::new(&params(128, damping, 1.0 / 240.0), 1.0, edge).unwrap();
            let d = Drop {
                position: [0.3, 0.95],
                radius: 0.08,
                strength: -0.01,
            };
            r.drop(&d);
            let v0 = volume(&r);
            assert!(v0 < 0.0);
            for _ in 0..500 {
                r.step();
            }
            let v = volume(&r);
            assert!(
                (v - v0).abs() < 1e-5 * v0.abs(),
                "{edge:?}, damping {damping}: volume {v} from {v0}"
            );
        }
    }

    #[test]
    fn a_central_drop_stays_mirror_symmetric() {
        let n = 128;
        for edge in [Edge::Wrap, Edge::Clamp] {
            let mut r = Ripples::new(&params(n, 0.3, 1.0 / 240.0), 1.0, edge).unwrap();
            r.drop(&central_drop(1.0));
            for _ in 0..300 {
                r.step();
            }
            let h = r.current();
            let peak = h.data.iter().map(|v| v.abs()).fold(0.0, f32::max);
            assert!(peak > 1e-4);
            for i in 0..n {
                for j in 0..n {
                    let v = h.at(i, j);
                    assert!(
                        (v - h.at(i, n - 1 - j)).abs() < 1e-6 * peak,
                        "x mirror at ({i}, {j})"
                    );
                    assert!(
                        (v - h.at(n - 1 - i, j)).abs() < 1e-6 * peak,
                        "y mirror at ({i}, {j})"
                    );
                }
            }
        }
    }

    #[test]
    fn rings_travel_at_the_wave_speed() {
        let (n, size) = (256, 1.0);
        let p = params(n, 0.0, 1.0 / 240.0);
        let mut r = Ripples::new(&p, size, Edge::Wrap).unwrap();
        let d = Drop {
            position: [0.5, 0.5],
            radius: 0.04,
            strength: -0.01,
        };
        r.drop(&d);
        let dx = size / n as f64;
        // The crest of the ring: the largest |h| along the +x ray from the centre, beyond the drop.
        let crest = |r: &Ripples| {
            let row = n / 2;
            let y = (row as f64 + 0.5) * dx - 0.5;
            let (mut best, mut radius) = (0.0, 0.0);
            for j in n / 2..n {
                let x = (j as f64 + 0.5) * dx - 0.5;
                let v = r.current().at(row, j).abs();
                if x.hypot(y) > d.radius && v > best {
                    (best, radius) = (v, x.hypot(y));
                }
            }
            radius
        };
        let mut samples = Vec::new();
        for steps in [48, 108] {
            while r.steps_taken < steps {
                r.step();
            }
            let (t, radius) = (r.time(), crest(&r));
            let expected = p.wave_speed * t;
            assert!(
                (radius / expected - 1.0).abs() < 0.15,
                "after {t} s the ring is at {radius}, c t = {expected}"
            );
            samples.push((t, radius));
        }
        let speed = (samples[1].1 - samples[0].1) / (samples[1].0 - samples[0].0);
        assert!(
            (speed / p.wave_speed - 1.0).abs() < 0.15,
            "the ring grows at {speed}, c = {}",
            p.wave_speed
        );
    }

    #[test]
    fn a_drop_is_a_cosine_bump_that_wraps() {
        let n = 64;
        let mut r = Ripples::new(&params(n, 0.0, 1.0 / 240.0), 1.0, Edge::Wrap).unwrap();
        // Centred on the corner sample's corner: the four corner cells are equally far from it.
        r.drop(&Drop {
            position: [0.0, 0.0],
            radius: 0.1,
            strength: 0.02,
        });
        let h = r.current();
        let dx = 1.0 / n as f64;
        let expected = 0.02 * 0.5 * (1.0 + (PI * (0.5f64).sqrt() * dx / 0.1).cos());
        for (i, j) in [(0, 0), (0, n - 1), (n - 1, 0), (n - 1, n - 1)] {
            assert!((h.at(i, j) as f64 - expected).abs() < 1e-8, "({i}, {j})");
        }
        assert_eq!(r.previous(), r.current());
        assert_eq!(h.at(n / 2, n / 2), 0.0);
        let mut clamped = Ripples::new(&params(n, 0.0, 1.0 / 240.0), 1.0, Edge::Clamp).unwrap();
        clamped.drop(&Drop {
            position: [0.0, 0.0],
            radius: 0.1,
            strength: 0.02,
        });
        assert!((clamped.current().at(0, 0) as f64 - expected).abs() < 1e-8);
        assert_eq!(clamped.current().at(n - 1, n - 1), 0.0);
    }

    #[test]
    fn defaults_are_stable_on_the_unit_square() {
        let mut r = Ripples::new(&RippleParams::default(), 1.0, Edge::Clamp).unwrap();
        r.run_initial();
        assert!((r.time() - 0.5).abs() < 1e-12);
        let (lo, hi) = r.current().min_max();
        assert!(
            lo < 0.0 && hi > 0.0 && lo > -0.02 && hi < 0.02,
            "{lo}..{hi}"
        );
        r.current().check_finite("ripples").unwrap();
        let p: RippleParams = toml::from_str(
            "wave_speed = 0.3\n[[drops]]\nposition = [0.5, 0.5]\nradius = 0.1\nstrength = -0.01",
        )
        .unwrap();
        assert_eq!(p.drops.len(), 1);
        assert_eq!(p.resolution, 256);
        assert!(toml::from_str::<RippleParams>("speed = 1.0").is_err());
    }

    #[test]
    fn violating_the_courant_condition_is_an_error_naming_the_field() {
        // dx = 1/256, c = 0.5: the largest stable step is dx / (c √2) ≈ 5.524e-3 s.
        let e = Ripples::new(&params(256, 0.5, 1.0 / 120.0), 1.0, Edge::Wrap)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("water.ripple.time_step") && e.contains("5.5243e-3"),
            "{e}"
        );
        let e = Ripples::new(
            &RippleParams {
                drops: vec![Drop {
                    position: [0.5, 0.5],
                    radius: 0.001,
                    strength: 0.01,
                }],
                ..RippleParams::default()
            },
            1.0,
            Edge::Wrap,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("water.ripple.drops[0].radius"), "{e}");
        let e = Ripples::new(&params(2, 0.5, 0.01), 1.0, Edge::Wrap)
            .unwrap_err()
            .to_string();
        assert!(e.contains("water.ripple.resolution"), "{e}");
        let e = Ripples::new(&params(64, -1.0, 0.01), 1.0, Edge::Wrap)
            .unwrap_err()
            .to_string();
        assert!(e.contains("water.ripple.damping"), "{e}");
    }

    #[test]
    fn update_cell_is_the_damped_leapfrog() {
        let (prev, cur, n, s, e, w) = (0.1f32, 0.2, 0.3, -0.1, 0.25, 0.05);
        let (c2, g) = (0.25f32, 0.01);
        let lap = n as f64 + s as f64 + e as f64 + w as f64 - 4.0 * cur as f64;
        let exact = (2.0 * cur as f64 - (1.0 - g as f64) * prev as f64 + c2 as f64 * lap)
            / (1.0 + g as f64);
        assert!((update_cell(prev, cur, n, s, e, w, c2, g) as f64 - exact).abs() < 1e-6);
    }
}
