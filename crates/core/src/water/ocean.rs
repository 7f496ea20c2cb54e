//! A Tessendorf FFT ocean (J. Tessendorf, "Simulating Ocean Water", SIGGRAPH 2001 course notes):
//! a Gaussian random sea with the Phillips spectrum, animated by deep-water dispersion and summed on
//! an `N × N` grid by an inverse FFT.
//!
//! The surface is the trigonometric polynomial over the tile `[0, size]²`
//!
//! `h(x, t) = Σ_k h̃(k, t) e^{i k·x}`, `k = 2π (n, m) / size`, `n, m ∈ [−N/2, N/2)`
//!
//! (§4.3), where, from independent complex Gaussians drawn once,
//!
//! - `h̃0(k) = (ξ_r + i ξ_i) sqrt(P_h(k) / 2)` (§4.3),
//! - `P_h(k) = A exp(−1 / (k L)²) / k⁴ · |k̂·ŵ|^p · exp(−k² l²)` with `L = V² / g`: Phillips' spectrum
//!   (§4.3; the paper's `p` is 2, and the last factor is its small-wave suppression),
//! - `h̃(k, t) = h̃0(k) e^{iωt} + conj(h̃0(−k)) e^{−iωt}` (§4.3), Hermitian in `k` so `h` is real,
//! - `ω(k) = sqrt(g |k|)` (deep water, §4.2), optionally quantised to `⌊ω / ω0⌋ ω0` with
//!   `ω0 = 2π / T` so that the animation repeats exactly after `T` seconds (§4.2, "repeat time").
//!
//! Choices beyond the paper, all so the series is exact and easy to use:
//!
//! - **Amplitude.** Phillips' `A` has no useful unit: the realised height depends on the tile size
//!   and on how much of the spectrum the lattice resolves (a 1 m pool under a 6 m/s wind sees only
//!   the `k⁻⁴` tail past the peak at `1/L ≈ 0.27 m⁻¹`). So `A` is not a parameter: the spectrum is
//!   scaled so that the time-averaged root-mean-square height of this realisation equals
//!   [`OceanParams::rms_height`] (by default 1% of the tile size). The wind then sets the shape of
//!   the spectrum (its peak, its axis), `rms_height` its size.
//! - **Zero modes.** `h̃0 = 0` at `k = 0` (the mean level stays at rest) and on the Nyquist row and
//!   column (`n = −N/2` or `m = −N/2`), whose partner `−k` lies outside the lattice: without them the
//!   series is Hermitian term by term, hence real everywhere, not only at the samples, and its
//!   derivative is well defined.
//! - **Seeding.** Each mode draws its Gaussians from its own splitmix64 stream keyed by the seed and
//!   `(n, m)`, so the same seed at a finer resolution keeps the same long waves and only adds short
//!   ones (before the normalisation to `rms_height`, which shifts the overall scale slightly).
//! - **Direction.** `|k̂·ŵ|^p` is even in `k`, so Phillips' spectrum alone makes a sea of waves
//!   running both ways along the wind, whose pairs `k`, `−k` interfere into standing waves: crests
//!   that bob in place and an rms height that swells and fades by tens of percent as the few
//!   longest waves beat. Real wind waves run downwind, so by default the spectrum is kept only for
//!   waves running downwind and scaled by [`OceanParams::against_wind`] (default 0) for the others.
//!   With Tessendorf's sign convention the `h̃0(k)` term, `e^{i(k·x + ωt)}`, runs along `−k`: the
//!   downwind waves are those with `k·ŵ < 0`. With no wave running against the wind, each pair
//!   `k`, `−k` holds one travelling wave and, by Parseval, the rms height is the same at every
//!   time.

use crate::random::SplitMix64;
use std::f64::consts::{PI, TAU};
use std::fmt;

use glam::DVec2;
use num_complex::Complex;
use serde::{Deserialize, Serialize};

use super::GridSurface;
use super::waves::GRAVITY;
use crate::error::{Error, Result, between, non_negative, positive};
use crate::grid::{Edge, Grid};

/// The root-mean-square height, as a fraction of the tile size, used when
/// [`OceanParams::rms_height`] is not given. With the other defaults it gives rms slopes of about
/// 0.2 on tiles of 1 to 10 units (0.35 on 50): a chop whose crests focus light into sharp caustics.
/// Scenes with shallow water should set a smaller `rms_height`, or the troughs reach the floor.
pub const DEFAULT_RMS_FRACTION: f64 = 0.01;

/// Parameters of the ocean, with Tessendorf's names where he names them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OceanParams {
    /// Grid size `N` (the grid is `N × N` over the tile); a power of two from 4 to 4096.
    pub resolution: usize,
    /// Wind speed `V`, m/s (world units are metres); sets the spectrum's peak at `k = 1/L`,
    /// `L = V² / g`.
    pub wind_speed: f64,
    /// Wind direction `ŵ` in the xy plane (need not be normalised).
    #[serde(deserialize_with = "crate::scene::exact::array")]
    pub wind_direction: [f64; 2],
    /// Time-averaged root-mean-square height of the surface, world units. The Phillips amplitude
    /// `A` is solved for it (see the module documentation). `None`: [`DEFAULT_RMS_FRACTION`] of the
    /// tile size, 1 cm on a 1 m pool, 0.5 m on a 50 m tile.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_height: Option<f64>,
    /// Seed of the random sea; the same seed gives the same sea.
    pub seed: u64,
    /// Small-wave suppression length `l` of the factor `exp(−k² l²)` (§4.3), world units; 0 turns
    /// it off. The grid already stops at the Nyquist wave number `π N / size`; a value near
    /// `size / N` quiets the shortest waves, which the bicubic interpolant between samples renders
    /// least faithfully.
    pub small_wave_cutoff: f64,
    /// Exponent `p` of the directional factor `|k̂·ŵ|^p` (2 in the paper; larger aligns the waves
    /// more closely with the wind, 0 makes the sea isotropic).
    pub directional_exponent: f64,
    /// The Phillips spectrum's weight for waves running against the wind, from 0 (all waves run
    /// downwind, the default) to 1 (the paper's symmetric sea of standing waves).
    pub against_wind: f64,
    /// Repeat time `T`, seconds: the frequencies are quantised so that the surface at `t + T` equals
    /// the surface at `t` (§4.2). Waves slower than `2π / T` then stand still. `None`: exact
    /// dispersion, no loop.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repeat_period: Option<f64>,
}

impl Default for OceanParams {
    fn default() -> Self {
        OceanParams {
            resolution: 128,
            wind_speed: 6.0,
            wind_direction: [1.0, 0.3],
            rms_height: None,
            seed: 0,
            small_wave_cutoff: 0.0,
            directional_exponent: 2.0,
            against_wind: 0.0,
            repeat_period: None,
        }
    }
}

/// The precomputed ocean: `h̃0(k)`, `conj(h̃0(−k))` and `ω(k)` on the `N × N` lattice, ready to be
/// evaluated at any time.
///
/// Spectral arrays are in FFT order, row-major like [`Grid`]: entry `i N + j` holds the wave vector
/// [`Ocean::wave_vector`]`(i, j) = 2π (n, m) / size` with `n = j`, `m = i` for indices below `N/2`
/// and `j − N`, `i − N` from `N/2` on.
#[derive(Clone)]
pub struct Ocean {
    params: OceanParams,
    size: f64,
    rms_height: f64,
    h0: Vec<Complex<f64>>,
    h0_minus_conj: Vec<Complex<f64>>,
    omega: Vec<f64>,
}

impl fmt::Debug for Ocean {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Ocean")
            .field("params", &self.params)
            .field("size", &self.size)
            .field("rms_height", &self.rms_height)
            .finish_non_exhaustive()
    }
}

impl Ocean {
    /// Draw the random sea for a tile of side `size` (world units), checking every parameter.
    pub fn new(params: &OceanParams, size: f64) -> Result<Ocean> {
        validate(params, size)?;
        let n = params.resolution;
        let wind = DVec2::from(params.wind_direction).normalize();
        let peak = params.wind_speed * params.wind_speed / GRAVITY;
        let omega0 = params.repeat_period.map(|period| TAU / period);
        let mut ocean = Ocean {
            params: params.clone(),
            size,
            rms_height: params.rms_height.unwrap_or(DEFAULT_RMS_FRACTION * size),
            h0: vec![Complex::new(0.0, 0.0); n * n],
            h0_minus_conj: Vec::new(),
            omega: vec![0.0; n * n],
        };
        for i in 0..n {
            for j in 0..n {
                let k = ocean.wave_vector(i, j);
                let index = i * n + j;
                let omega = (GRAVITY * k.length()).sqrt();
                ocean.omega[index] = match omega0 {
                    Some(w0) => (omega / w0).floor() * w0,
                    None => omega,
                };
                let (fx, fy) = (frequency(j, n), frequency(i, n));
                let nyquist = -((n / 2) as i64);
                if (fx, fy) == (0, 0) || fx == nyquist || fy == nyquist {
                    continue;
                }
                let mut spectrum = phillips(
                    k,
                    wind,
                    peak,
                    params.small_wave_cutoff,
                    params.directional_exponent,
                );
                // h̃0(k) drives e^{i(k·x + ωt)}, which runs along −k.
                if k.dot(wind) > 0.0 {
                    spectrum *= params.against_wind;
                }
                let (xi_r, xi_i) = gaussian_pair(params.seed, fx, fy);
                ocean.h0[index] = Complex::new(xi_r, xi_i) * (0.5 * spectrum).sqrt();
            }
        }
        ocean.h0_minus_conj = (0..n * n)
            .map(|index| {
                let (i, j) = (index / n, index % n);
                ocean.h0[((n - i) % n) * n + (n - j) % n].conj()
            })
            .collect();

        // By Parseval, the mean square of h over the tile at time t is Σ |h̃(k, t)|². Averaged over
        // time the cross term 2 Re(h̃0(k) h̃0(−k) e^{2iωt}) vanishes, except where ω = 0 (the modes
        // a repeat time freezes), which keep it.
        let mean_square: f64 = (0..n * n)
            .map(|index| {
                let (a, b) = (ocean.h0[index], ocean.h0_minus_conj[index]);
                if ocean.omega[index] == 0.0 {
                    (a + b).norm_sqr()
                } else {
                    a.norm_sqr() + b.norm_sqr()
                }
            })
            .sum();
        if !(mean_square > 0.0 && mean_square.is_finite()) {
            return Err(Error::field(
                "water.ocean.wind_speed",
                format!(
                    "leaves no wave on the lattice: the Phillips spectrum for a {} m/s wind \
                     vanishes on a {n}×{n} grid over {size} units (raise the wind speed or the \
                     tile size)",
                    params.wind_speed
                ),
            ));
        }
        let scale = ocean.rms_height / mean_square.sqrt();
        for v in ocean.h0.iter_mut().chain(ocean.h0_minus_conj.iter_mut()) {
            *v *= scale;
        }
        Ok(ocean)
    }

    /// The parameters the ocean was built from, as the scene gave them.
    pub fn params(&self) -> &OceanParams {
        &self.params
    }

    /// Side of the tile, world units; the surface is periodic with this period in x and y.
    pub fn size(&self) -> f64 {
        self.size
    }

    /// The time-averaged root-mean-square height the spectrum is scaled to, world units.
    pub fn rms_height(&self) -> f64 {
        self.rms_height
    }

    /// Wave vector of spectral entry `(i, j)` (row `i`, column `j`, FFT order), per world unit.
    pub fn wave_vector(&self, i: usize, j: usize) -> DVec2 {
        let n = self.params.resolution;
        DVec2::new(frequency(j, n) as f64, frequency(i, n) as f64) * (TAU / self.size)
    }

    /// `h̃0(k)`, FFT order: with [`Ocean::h0_minus_conj`] and [`Ocean::omega`], what a GPU twin
    /// uploads once.
    pub fn h0(&self) -> &[Complex<f64>] {
        &self.h0
    }

    /// `conj(h̃0(−k))`, FFT order.
    pub fn h0_minus_conj(&self) -> &[Complex<f64>] {
        &self.h0_minus_conj
    }

    /// `ω(k)`, rad/s, FFT order (quantised when a repeat period is set).
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }

    /// `h̃(k, t) = h̃0(k) e^{iωt} + conj(h̃0(−k)) e^{−iωt}` (§4.3), FFT order. Hermitian:
    /// `h̃(−k, t) = conj(h̃(k, t))`, exactly, also in floating point.
    pub fn spectrum_at(&self, t: f64) -> Vec<Complex<f64>> {
        self.h0
            .iter()
            .zip(&self.h0_minus_conj)
            .zip(&self.omega)
            .map(|((&a, &b), &omega)| {
                let (s, c) = (omega * t).sin_cos();
                a * Complex::new(c, s) + b * Complex::new(c, -s)
            })
            .collect()
    }

    /// The heights at time `t` on the grid convention of [`Grid`]: sample `(i, j)` is
    /// `h(((j + 0.5) dx, (i + 0.5) dx))`, `dx = size / N`, exactly (to rounding) the series' value.
    pub fn height_grid(&self, t: f64) -> Grid {
        self.to_grid(self.heights(t).iter().map(|v| v.re))
    }

    /// `(∂h/∂x, ∂h/∂y)` at time `t` on the same samples as [`Ocean::height_grid`], by spectral
    /// differentiation `∇h = Σ i k h̃(k, t) e^{i k·x}` (§4.3): the exact gradient of the series, not
    /// a finite difference. Both come from one complex FFT: the two spectra are Hermitian, so the
    /// transform of `i k_x h̃ + i (i k_y h̃)` has `∂h/∂x` as its real part and `∂h/∂y` as its
    /// imaginary part.
    pub fn slope_grids(&self, t: f64) -> (Grid, Grid) {
        let slopes = self.slopes(t);
        (
            self.to_grid(slopes.iter().map(|v| v.re)),
            self.to_grid(slopes.iter().map(|v| v.im)),
        )
    }

    /// The surface at time `t`: the height grid read through the bicubic interpolant, periodic.
    pub fn surface(&self, t: f64) -> GridSurface {
        GridSurface {
            grid: self.height_grid(t),
            size: self.size,
            edge: Edge::Wrap,
        }
    }

    /// The series summed term by term at any point: `O(N²)` per point, the reference the FFT is
    /// tested against.
    #[cfg(test)]
    fn exact_height(&self, t: f64, p: DVec2) -> f64 {
        let n = self.params.resolution;
        self.spectrum_at(t)
            .iter()
            .enumerate()
            .map(|(index, h)| {
                let phase = self.wave_vector(index / n, index % n).dot(p);
                (h * Complex::from_polar(1.0, phase)).re
            })
            .sum()
    }

    /// The complex inverse transform of `h̃(k, t)` on the samples: real part the heights, imaginary
    /// part rounding noise.
    fn heights(&self, t: f64) -> Vec<Complex<f64>> {
        self.synthesize(self.spectrum_at(t))
    }

    /// `∂h/∂x + i ∂h/∂y` on the samples.
    fn slopes(&self, t: f64) -> Vec<Complex<f64>> {
        let n = self.params.resolution;
        let mut spectrum = self.spectrum_at(t);
        for (index, h) in spectrum.iter_mut().enumerate() {
            let k = self.wave_vector(index / n, index % n);
            let i_h = Complex::new(-h.im, h.re);
            // i k_x h̃ + i (i k_y h̃) = i k_x h̃ − k_y h̃.
            *h = i_h * k.x - *h * k.y;
        }
        self.synthesize(spectrum)
    }

    /// `f(x_ij) = Σ_k F(k) e^{i k·x_ij}` at the sample points by a 2-D inverse FFT, rows then
    /// columns. The DFT sums `e^{2πi (n j + m i) / N}`, i.e. evaluates at `x = (j, i) dx`; our samples
    /// sit half a texel further on, at `((j + 0.5) dx, (i + 0.5) dx)`, so each coefficient first
    /// takes the shift `e^{i k·(dx/2, dx/2)} = e^{iπ (n + m) / N}` (with the signed `n, m`: the
    /// shift, unlike the DFT kernel, tells `n` from `n − N`).
    fn synthesize(&self, mut spectrum: Vec<Complex<f64>>) -> Vec<Complex<f64>> {
        let n = self.params.resolution;
        let shift: Vec<Complex<f64>> = (0..n)
            .map(|a| Complex::from_polar(1.0, PI * frequency(a, n) as f64 / n as f64))
            .collect();
        for (index, v) in spectrum.iter_mut().enumerate() {
            *v *= shift[index / n] * shift[index % n];
        }
        inverse_dft_rows(&mut spectrum, n); // every row: the sum over n
        let mut columns = transpose(&spectrum, n);
        inverse_dft_rows(&mut columns, n); // every column: the sum over m
        transpose(&columns, n)
    }

    fn to_grid(&self, values: impl Iterator<Item = f64>) -> Grid {
        let n = self.params.resolution;
        Grid {
            cols: n,
            rows: n,
            data: values.map(|v| v as f32).collect(),
        }
    }
}

fn validate(p: &OceanParams, size: f64) -> Result<()> {
    let at = |name: &str| format!("water.ocean.{name}");
    positive("water.size", size)?;
    if !(p.resolution.is_power_of_two() && (4..=4096).contains(&p.resolution)) {
        return Err(Error::field(
            at("resolution"),
            format!(
                "must be a power of two between 4 and 4096, got {}",
                p.resolution
            ),
        ));
    }
    positive(&at("wind_speed"), p.wind_speed)?;
    let wind = DVec2::from(p.wind_direction);
    if !(wind.is_finite() && wind != DVec2::ZERO) {
        return Err(Error::field(
            at("wind_direction"),
            format!(
                "must be a finite non-zero vector, got {:?}",
                p.wind_direction
            ),
        ));
    }
    if let Some(rms) = p.rms_height {
        positive(&at("rms_height"), rms)?;
    }
    non_negative(&at("small_wave_cutoff"), &[p.small_wave_cutoff])?;
    non_negative(&at("directional_exponent"), &[p.directional_exponent])?;
    between(&at("against_wind"), p.against_wind, 0.0, 1.0)?;
    if let Some(period) = p.repeat_period {
        positive(&at("repeat_period"), period)?;
    }
    Ok(())
}

/// The signed frequency of FFT index `a` of `n`: `a` below `n/2`, `a − n` from `n/2` on.
fn frequency(a: usize, n: usize) -> i64 {
    if a < n / 2 {
        a as i64
    } else {
        a as i64 - n as i64
    }
}

/// Phillips' spectrum with `A = 1` (§4.3): `exp(−1/(kL)²) / k⁴ · |k̂·ŵ|^p · exp(−k² l²)`.
fn phillips(k: DVec2, wind: DVec2, peak: f64, cutoff: f64, exponent: f64) -> f64 {
    let k2 = k.length_squared();
    let align = (k.dot(wind).abs() / k2.sqrt()).powf(exponent);
    (-1.0 / (k2 * peak * peak)).exp() / (k2 * k2) * align * (-k2 * cutoff * cutoff).exp()
}

/// Two independent standard normal numbers for mode `(n, m)`, from a splitmix64 stream keyed by
/// the seed and the mode, by the Box-Muller transform.
fn gaussian_pair(seed: u64, n: i64, m: i64) -> (f64, f64) {
    let key = ((n as u32 as u64) << 32) | m as u32 as u64;
    let mut rng = SplitMix64(seed ^ SplitMix64(key).next());
    // Uniforms in (0, 1): 53 random bits, centred in their bin so that ln never sees 0.
    let mut uniform = || ((rng.next() >> 11) as f64 + 0.5) * (1.0 / (1u64 << 53) as f64);
    let (u1, u2) = (uniform(), uniform());
    let r = (-2.0 * u1.ln()).sqrt();
    let (s, c) = (TAU * u2).sin_cos();
    (r * c, r * s)
}

/// Each run of `n` values replaced by its unnormalised inverse DFT, `x_j = Σ_k X_k e^{2πi jk/n}`:
/// rustfft's FFT with the `fft` feature.
#[cfg(feature = "fft")]
fn inverse_dft_rows(data: &mut [Complex<f64>], n: usize) {
    rustfft::FftPlanner::new().plan_fft_inverse(n).process(data);
}

#[cfg(not(feature = "fft"))]
fn inverse_dft_rows(data: &mut [Complex<f64>], n: usize) {
    direct_inverse_dft_rows(data, n);
}

/// The same sums taken directly, `O(n²)` a row, for a build without the `fft` feature.
#[cfg(any(test, not(feature = "fft")))]
fn direct_inverse_dft_rows(data: &mut [Complex<f64>], n: usize) {
    let twiddle: Vec<Complex<f64>> = (0..n)
        .map(|k| Complex::from_polar(1.0, TAU * k as f64 / n as f64))
        .collect();
    let mut row = vec![Complex::new(0.0, 0.0); n];
    for values in data.chunks_exact_mut(n) {
        for (j, out) in row.iter_mut().enumerate() {
            *out = values
                .iter()
                .enumerate()
                .map(|(k, v)| v * twiddle[(j * k) % n])
                .sum();
        }
        values.copy_from_slice(&row);
    }
}

fn transpose(a: &[Complex<f64>], n: usize) -> Vec<Complex<f64>> {
    let mut out = vec![Complex::new(0.0, 0.0); n * n];
    for i in 0..n {
        for j in 0..n {
            out[j * n + i] = a[i * n + j];
        }
    }
    out
}

#[cfg(test)]
mod tests {

    /// The direct transform a build without `fft` uses gives rustfft's sums.
    #[cfg(feature = "fft")]
    #[test]
    fn the_direct_transform_matches_the_fft() {
        let n = 16;
        let data: Vec<Complex<f64>> = (0..3 * n as i64)
            .map(|k| {
                let (a, b) = gaussian_pair(7, k, 0);
                Complex::new(a, b)
            })
            .collect();
        let (mut fast, mut direct) = (data.clone(), data);
        inverse_dft_rows(&mut fast, n);
        direct_inverse_dft_rows(&mut direct, n);
        let worst = fast
            .iter()
            .zip(&direct)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        // Measured 3.7e-15.
        assert!(worst < 3e-14, "direct DFT off the FFT by {worst:e}");
    }
    use super::*;

    fn ocean(resolution: usize, size: f64) -> Ocean {
        let params = OceanParams {
            resolution,
            ..OceanParams::default()
        };
        Ocean::new(&params, size).unwrap()
    }

    fn sample_point(i: usize, j: usize, n: usize, size: f64) -> DVec2 {
        DVec2::new(j as f64 + 0.5, i as f64 + 0.5) * (size / n as f64)
    }

    fn rms(values: impl Iterator<Item = f64>) -> f64 {
        let (sum, count) = values.fold((0.0, 0usize), |(s, c), v| (s + v * v, c + 1));
        (sum / count as f64).sqrt()
    }

    #[test]
    fn grid_equals_the_direct_fourier_sum_at_the_samples() {
        let (n, size, t) = (16, 3.0, 1.3);
        let o = ocean(n, size);
        let heights = o.heights(t);
        let grid = o.height_grid(t);
        let scale = o.rms_height();
        for i in 0..n {
            for j in 0..n {
                let exact = o.exact_height(t, sample_point(i, j, n, size));
                let fft = heights[i * n + j].re;
                assert!(
                    (fft - exact).abs() < 1e-9 * scale,
                    "({i}, {j}): FFT {fft}, direct sum {exact}"
                );
                // The f32 grid holds the same values to single precision.
                assert!((grid.at(i, j) as f64 - exact).abs() < 1e-6 * scale);
            }
        }
    }

    #[test]
    fn spectral_slopes_are_the_derivative_of_the_series() {
        let (n, size, t) = (32, 2.0, 0.4);
        let o = ocean(n, size);
        let slopes = o.slopes(t);
        let (gx, gy) = o.slope_grids(t);
        let scale = slopes.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let e = 1e-5 * size;
        for (i, j) in [(0, 0), (3, 17), (16, 16), (31, 5), (22, 31)] {
            let p = sample_point(i, j, n, size);
            let fx = (o.exact_height(t, p + DVec2::X * e) - o.exact_height(t, p - DVec2::X * e))
                / (2.0 * e);
            let fy = (o.exact_height(t, p + DVec2::Y * e) - o.exact_height(t, p - DVec2::Y * e))
                / (2.0 * e);
            let s = slopes[i * n + j];
            assert!(
                (s.re - fx).abs() < 1e-6 * scale && (s.im - fy).abs() < 1e-6 * scale,
                "({i}, {j}): spectral ({}, {}), finite differences ({fx}, {fy})",
                s.re,
                s.im
            );
            assert!((gx.at(i, j) as f64 - s.re).abs() < 1e-6 * scale);
            assert!((gy.at(i, j) as f64 - s.im).abs() < 1e-6 * scale);
        }
    }

    #[test]
    fn the_field_tiles() {
        let (size, t) = (4.0, 2.5);
        let o = ocean(16, size);
        for p in [
            DVec2::new(0.3, 1.7),
            DVec2::new(3.9, 0.01),
            DVec2::new(-1.2, 2.2),
        ] {
            let h = o.exact_height(t, p);
            for offset in [
                DVec2::new(size, 0.0),
                DVec2::new(0.0, -size),
                DVec2::splat(size),
            ] {
                let shifted = o.exact_height(t, p + offset);
                assert!(
                    (h - shifted).abs() < 1e-9 * o.rms_height(),
                    "{h} vs {shifted} at {p}"
                );
            }
        }
    }

    #[test]
    fn spectrum_is_hermitian_and_heights_are_real_with_zero_mean() {
        let (n, t) = (64, 3.7);
        let o = ocean(n, 10.0);
        let spectrum = o.spectrum_at(t);
        for i in 0..n {
            for j in 0..n {
                let minus = spectrum[((n - i) % n) * n + (n - j) % n];
                assert_eq!(spectrum[i * n + j], minus.conj());
            }
        }
        let heights = o.heights(t);
        let rms_re = rms(heights.iter().map(|v| v.re));
        let max_im = heights.iter().map(|v| v.im.abs()).fold(0.0, f64::max);
        assert!(
            max_im < 1e-9 * rms_re,
            "imaginary part {max_im}, rms {rms_re}"
        );
        let mean = heights.iter().map(|v| v.re).sum::<f64>() / heights.len() as f64;
        assert!(mean.abs() < 1e-12 * rms_re, "mean {mean}");
        assert!(o.height_grid(t).mean().abs() < 1e-6 * rms_re);
    }

    #[test]
    fn default_rms_height_is_one_percent_of_the_tile() {
        for size in [1.0, 5.0, 20.0, 50.0] {
            let o = Ocean::new(&OceanParams::default(), size).unwrap();
            assert_eq!(o.rms_height(), 0.01 * size);
            for t in [0.0, 1.7, 10.0, 100.0] {
                let measured = rms(o.height_grid(t).data.iter().map(|&v| v as f64));
                // Travelling waves only: the rms is the target at every instant, not just on average.
                let ratio = measured / (0.01 * size);
                assert!(
                    (ratio - 1.0).abs() < 1e-3,
                    "size {size}, t {t}: rms {measured} is {ratio} of the target"
                );
            }
        }
        let explicit = OceanParams {
            rms_height: Some(0.05),
            ..OceanParams::default()
        };
        let o = Ocean::new(&explicit, 3.0).unwrap();
        let measured = rms(o.height_grid(0.0).data.iter().map(|&v| v as f64));
        assert!((measured / 0.05 - 1.0).abs() < 1e-3, "rms {measured}");
    }

    #[test]
    fn the_symmetric_sea_has_the_target_rms_on_average() {
        let params = OceanParams {
            resolution: 64,
            against_wind: 1.0,
            ..OceanParams::default()
        };
        for size in [1.0, 20.0] {
            let o = Ocean::new(&params, size).unwrap();
            let times: Vec<f64> = (0..200).map(|k| 0.37 * k as f64).collect();
            let mean_square = times
                .iter()
                .map(|&t| rms(o.heights(t).iter().map(|v| v.re)).powi(2))
                .sum::<f64>()
                / times.len() as f64;
            let ratio = mean_square.sqrt() / o.rms_height();
            assert!((ratio - 1.0).abs() < 0.2, "size {size}: {ratio}");
        }
    }

    #[test]
    fn waves_run_downwind() {
        // For a wave running along ŵ, ∂h/∂t and ŵ·∇h have opposite signs wherever it is not flat.
        let correlation = |against_wind: f64| {
            let params = OceanParams {
                resolution: 64,
                against_wind,
                ..OceanParams::default()
            };
            let o = Ocean::new(&params, 10.0).unwrap();
            let wind = DVec2::from(params.wind_direction).normalize();
            let (t, dt) = (2.0, 1e-4);
            let (before, after) = (o.heights(t - dt), o.heights(t + dt));
            let slopes = o.slopes(t);
            let (mut dot, mut a2, mut b2) = (0.0, 0.0, 0.0);
            for ((b, a), s) in before.iter().zip(&after).zip(&slopes) {
                let ht = (a.re - b.re) / (2.0 * dt);
                let along = wind.x * s.re + wind.y * s.im;
                dot += ht * along;
                a2 += ht * ht;
                b2 += along * along;
            }
            dot / (a2 * b2).sqrt()
        };
        let downwind = correlation(0.0);
        assert!(downwind < -0.5, "correlation {downwind}");
        let symmetric = correlation(1.0);
        assert!(
            symmetric.abs() < downwind.abs() / 2.0,
            "{symmetric} vs {downwind}"
        );
    }

    #[test]
    fn time_moves_the_field_and_the_seed_fixes_it() {
        let o = ocean(32, 1.0);
        let a = o.height_grid(0.0);
        assert_ne!(a, o.height_grid(0.5));
        assert_eq!(a, ocean(32, 1.0).height_grid(0.0));
        let other = Ocean::new(
            &OceanParams {
                resolution: 32,
                seed: 7,
                ..OceanParams::default()
            },
            1.0,
        )
        .unwrap();
        assert_ne!(a, other.height_grid(0.0));
    }

    #[test]
    fn repeat_period_makes_the_animation_loop() {
        let params = OceanParams {
            resolution: 32,
            repeat_period: Some(4.0),
            ..OceanParams::default()
        };
        let o = Ocean::new(&params, 2.0).unwrap();
        let (a, b) = (o.heights(1.1), o.heights(5.1));
        let err = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (x.re - y.re).abs())
            .fold(0.0, f64::max);
        assert!(err < 1e-9 * o.rms_height(), "{err}");
        assert_ne!(o.height_grid(1.1), o.height_grid(2.1));
    }

    #[test]
    fn bad_params_name_the_field() {
        let check = |params: OceanParams, size: f64, field: &str, detail: &str| {
            let e = Ocean::new(&params, size).unwrap_err().to_string();
            assert!(e.contains(field) && e.contains(detail), "{e}");
        };
        let d = OceanParams::default;
        check(
            OceanParams {
                resolution: 100,
                ..d()
            },
            1.0,
            "water.ocean.resolution",
            "power of two between 4 and 4096, got 100",
        );
        check(
            OceanParams {
                resolution: 8192,
                ..d()
            },
            1.0,
            "water.ocean.resolution",
            "8192",
        );
        check(
            OceanParams {
                wind_speed: 0.0,
                ..d()
            },
            1.0,
            "water.ocean.wind_speed",
            "got 0",
        );
        check(
            OceanParams {
                wind_direction: [0.0, 0.0],
                ..d()
            },
            1.0,
            "water.ocean.wind_direction",
            "non-zero",
        );
        check(
            OceanParams {
                wind_direction: [f64::NAN, 1.0],
                ..d()
            },
            1.0,
            "water.ocean.wind_direction",
            "NaN",
        );
        check(
            OceanParams {
                rms_height: Some(-1.0),
                ..d()
            },
            1.0,
            "water.ocean.rms_height",
            "-1",
        );
        check(
            OceanParams {
                small_wave_cutoff: f64::INFINITY,
                ..d()
            },
            1.0,
            "water.ocean.small_wave_cutoff",
            "inf",
        );
        check(
            OceanParams {
                directional_exponent: -2.0,
                ..d()
            },
            1.0,
            "water.ocean.directional_exponent",
            "-2",
        );
        check(
            OceanParams {
                against_wind: 1.5,
                ..d()
            },
            1.0,
            "water.ocean.against_wind",
            "1.5",
        );
        check(
            OceanParams {
                repeat_period: Some(0.0),
                ..d()
            },
            1.0,
            "water.ocean.repeat_period",
            "got 0",
        );
        check(d(), 0.0, "water.size", "got 0");
    }

    #[test]
    fn params_read_from_toml_with_defaults() {
        let p: OceanParams = toml::from_str("resolution = 64\nrms_height = 0.02").unwrap();
        assert_eq!(
            p,
            OceanParams {
                resolution: 64,
                rms_height: Some(0.02),
                ..OceanParams::default()
            }
        );
        assert!(toml::from_str::<OceanParams>("amplitude = 1.0").is_err());
        let round_trip: OceanParams =
            toml::from_str(&toml::to_string(&OceanParams::default()).unwrap()).unwrap();
        assert_eq!(round_trip, OceanParams::default());
    }
}
