//! The caustics map: relative irradiance per RGB channel on the floor square, texel `(i, j)` centred
//! at `((j + 0.5) size / width, (i + 0.5) size / height)`, row 0 at y = 0. 1.0 is the irradiance that
//! the same sun gives through a flat, non-absorbing water surface onto a horizontal floor.

use std::path::Path;

use crate::error::{Error, Result};
use crate::grid::Grid;

#[derive(Clone, Debug, PartialEq)]
pub struct CausticsMap {
    pub width: usize,
    pub height: usize,
    pub size: f64,
    pub texels: Vec<[f32; 3]>,
}

impl CausticsMap {
    pub fn new(width: usize, height: usize, size: f64) -> Self {
        CausticsMap {
            width,
            height,
            size,
            texels: vec![[0.0; 3]; width * height],
        }
    }

    pub fn from_grid(g: &Grid, size: f64) -> Self {
        CausticsMap {
            width: g.cols,
            height: g.rows,
            size,
            texels: g.data.iter().map(|&v| [v; 3]).collect(),
        }
    }

    /// The single-channel map the raw outputs hold: the mean of the channels, which is the relative
    /// irradiance itself when the water absorbs nothing.
    pub fn mean_channel(&self) -> Grid {
        Grid {
            cols: self.width,
            rows: self.height,
            data: self
                .texels
                .iter()
                .map(|t| (t[0] + t[1] + t[2]) / 3.0)
                .collect(),
        }
    }

    /// This map plus `other` texel by texel (the caustics of several generators, each traced on
    /// its own, on one floor).
    pub fn added(mut self, other: &CausticsMap) -> CausticsMap {
        for (a, b) in self.texels.iter_mut().zip(&other.texels) {
            for c in 0..3 {
                a[c] += b[c];
            }
        }
        self
    }

    /// Flux on the floor square (channel mean): relative irradiance times area, the unit of
    /// [`crate::walls::WallMap::flux`], so floor and walls add up.
    pub fn flux(&self) -> f64 {
        let sum: f64 = self
            .texels
            .iter()
            .map(|t| (t[0] + t[1] + t[2]) as f64 / 3.0)
            .sum();
        sum * self.size * self.size / (self.width * self.height) as f64
    }

    pub fn channel(&self, c: usize) -> Grid {
        Grid {
            cols: self.width,
            rows: self.height,
            data: self.texels.iter().map(|t| t[c]).collect(),
        }
    }

    /// Bilinear lookup at floor point `(x, y)`, clamped at the edges (or wrapped).
    pub fn sample(&self, x: f64, y: f64, wrap: bool) -> [f32; 3] {
        let u = x / self.size * self.width as f64 - 0.5;
        let v = y / self.size * self.height as f64 - 0.5;
        let (j0, i0) = (u.floor(), v.floor());
        let (fu, fv) = ((u - j0) as f32, (v - i0) as f32);
        let fetch = |i: i64, j: i64| {
            let (i, j) = if wrap {
                (
                    i.rem_euclid(self.height as i64),
                    j.rem_euclid(self.width as i64),
                )
            } else {
                (
                    i.clamp(0, self.height as i64 - 1),
                    j.clamp(0, self.width as i64 - 1),
                )
            };
            self.texels[i as usize * self.width + j as usize]
        };
        let (i0, j0) = (i0 as i64, j0 as i64);
        let (a, b, c, d) = (
            fetch(i0, j0),
            fetch(i0, j0 + 1),
            fetch(i0 + 1, j0),
            fetch(i0 + 1, j0 + 1),
        );
        std::array::from_fn(|k| {
            (a[k] * (1.0 - fu) + b[k] * fu) * (1.0 - fv) + (c[k] * (1.0 - fu) + d[k] * fu) * fv
        })
    }

    /// Write the raw map: `.npy` (float32, shape (height, width)) or `.exr`, by extension.
    pub fn write_raw(&self, path: &Path) -> Result<()> {
        let g = self.mean_channel();
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("npy") => g.write_npy(path),
            Some("exr") => g.write_exr(path),
            _ => Err(Error::bad_file(
                path,
                "the raw caustics map is written as .npy or .exr; give one of those extensions",
            )),
        }
    }
}
