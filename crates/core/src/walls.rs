//! The pool's four walls as receivers: in a real pool the light that the waves send
//! sideways, and all of it under a low sun, lands on the walls, which webgl-water shows as much as
//! the floor. A scene turns this on with `[floor] walls = true` ([`crate::scene::Floor::walls`]).
//!
//! Each wall's map is in the floor map's unit (relative irradiance: 1 is what the sun gives a
//! horizontal floor through flat, clear water), laid out as `--raw-walls` writes it: shape
//! `(rows, cols)`, row 0 at the floor (z = 0) and the last row ending at the rest water level
//! (z = depth), columns along the wall in increasing y (walls x = 0 and x = size) or x (walls y = 0
//! and y = size). Columns are the floor map's texels along that side; rows are as tall as the
//! floor map's finer texel side, rounded so that a whole number fills the depth.

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};

use crate::error::Result;
use crate::grid::Grid;

/// One wall of the water's square `[0, size]²`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Wall {
    /// The wall at x = 0.
    X0,
    /// The wall at x = size.
    X1,
    /// The wall at y = 0.
    Y0,
    /// The wall at y = size.
    Y1,
}

impl Wall {
    /// In the order of [`WallMaps::maps`] and of the GPU's wall-map layers.
    pub const ALL: [Wall; 4] = [Wall::X0, Wall::X1, Wall::Y0, Wall::Y1];

    /// The suffix of its `--raw-walls` file: `PREFIX-x0.npy`, ...
    pub fn suffix(self) -> &'static str {
        ["x0", "x1", "y0", "y1"][self.index()]
    }

    /// Its position in [`Wall::ALL`] (0 to 3): its map in [`WallMaps::maps`], its GPU layer.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The unit normal facing into the pool.
    pub fn normal(self) -> DVec3 {
        [DVec3::X, -DVec3::X, DVec3::Y, -DVec3::Y][self.index()]
    }

    /// The coordinate along the wall of a point on it: y for the x-walls, x for the y-walls.
    pub fn along(self, p: DVec3) -> f64 {
        match self {
            Wall::X0 | Wall::X1 => p.y,
            Wall::Y0 | Wall::Y1 => p.x,
        }
    }

    /// The point of the wall at `along` and height `z`.
    pub fn point(self, along: f64, z: f64, size: f64) -> DVec3 {
        match self {
            Wall::X0 => DVec3::new(0.0, along, z),
            Wall::X1 => DVec3::new(size, along, z),
            Wall::Y0 => DVec3::new(along, 0.0, z),
            Wall::Y1 => DVec3::new(along, size, z),
        }
    }

    /// The wall a horizontal direction `d` from `p` (inside the square) leaves the square
    /// through, and the distance to it along `d` (in `d`'s units); `None` for `d` = 0. A corner
    /// goes to the x-wall.
    pub fn exit(p: DVec2, d: DVec2, size: f64) -> Option<(Wall, f64)> {
        let axis = |p: f64, d: f64, near: Wall, far: Wall| match d {
            d if d > 0.0 => Some((far, (size - p) / d)),
            d if d < 0.0 => Some((near, -p / d)),
            _ => None,
        };
        let tx = axis(p.x, d.x, Wall::X0, Wall::X1);
        let ty = axis(p.y, d.y, Wall::Y0, Wall::Y1);
        match (tx, ty) {
            (Some(a), Some(b)) => Some(if a.1 <= b.1 { a } else { b }),
            (a, b) => a.or(b),
        }
    }
}

/// One wall's map (see the module's layout).
#[derive(Clone, Debug, PartialEq)]
pub struct WallMap {
    /// Texels along the wall: the floor map's texels along that side.
    pub cols: usize,
    /// Texels up the wall, from the floor to the rest water level.
    pub rows: usize,
    /// The wall's length (the square's side).
    pub length: f64,
    /// Its height: the rest water level above the floor.
    pub height: f64,
    /// Row-major, row 0 at the floor.
    pub texels: Vec<[f32; 3]>,
}

impl WallMap {
    /// A dark map (no light) of `cols` x `rows` texels on a wall `length` long and `height` high
    /// (world units).
    pub fn new(cols: usize, rows: usize, length: f64, height: f64) -> Self {
        WallMap {
            cols,
            rows,
            length,
            height,
            texels: vec![[0.0; 3]; cols * rows],
        }
    }

    /// A texel's area on the wall, to turn its relative irradiance into flux.
    pub fn texel_area(&self) -> f64 {
        self.length / self.cols as f64 * self.height / self.rows as f64
    }

    /// The texel holding the wall point at `along`, height `z`; `None` off the wall.
    pub fn texel(&self, along: f64, z: f64) -> Option<usize> {
        let u = along / self.length * self.cols as f64;
        let v = z / self.height * self.rows as f64;
        if !(0.0..self.cols as f64).contains(&u) || !(0.0..self.rows as f64).contains(&v) {
            return None;
        }
        Some(v as usize * self.cols + u as usize)
    }

    /// The centre of texel `(row, col)`: `(along, z)`.
    #[cfg(test)]
    pub fn texel_centre(&self, row: usize, col: usize) -> (f64, f64) {
        (
            (col as f64 + 0.5) * self.length / self.cols as f64,
            (row as f64 + 0.5) * self.height / self.rows as f64,
        )
    }

    /// Bilinear lookup at `(along, z)`, clamped at the wall's edges, as the final image reads it.
    pub fn sample(&self, along: f64, z: f64) -> [f32; 3] {
        let u = (along / self.length * self.cols as f64 - 0.5).clamp(0.0, (self.cols - 1) as f64);
        let v = (z / self.height * self.rows as f64 - 0.5).clamp(0.0, (self.rows - 1) as f64);
        let (j0, i0) = (u.floor() as usize, v.floor() as usize);
        let (j1, i1) = ((j0 + 1).min(self.cols - 1), (i0 + 1).min(self.rows - 1));
        let (fu, fv) = ((u - j0 as f64) as f32, (v - i0 as f64) as f32);
        let t = |i: usize, j: usize| self.texels[i * self.cols + j];
        std::array::from_fn(|c| {
            let a = t(i0, j0)[c] * (1.0 - fu) + t(i0, j1)[c] * fu;
            let b = t(i1, j0)[c] * (1.0 - fu) + t(i1, j1)[c] * fu;
            a * (1.0 - fv) + b * fv
        })
    }

    /// The mean of the channels, as the raw outputs hold it.
    pub fn mean_channel(&self) -> Grid {
        Grid {
            cols: self.cols,
            rows: self.rows,
            data: self
                .texels
                .iter()
                .map(|t| (t[0] + t[1] + t[2]) / 3.0)
                .collect(),
        }
    }

    /// Flux on the wall in the floor map's unit times area (channel mean).
    pub fn flux(&self) -> f64 {
        let sum: f64 = self
            .texels
            .iter()
            .map(|t| (t[0] + t[1] + t[2]) as f64 / 3.0)
            .sum();
        sum * self.texel_area()
    }
}

/// The four walls' maps, in [`Wall::ALL`]'s order.
#[derive(Clone, Debug, PartialEq)]
pub struct WallMaps {
    /// The x = 0, x = size, y = 0 and y = size walls' maps.
    pub maps: [WallMap; 4],
}

impl WallMaps {
    /// Empty maps for a floor map of `width` x `height` texels over a square of side `size`,
    /// with the rest water level `depth` above the floor.
    pub fn for_floor_map(width: usize, height: usize, size: f64, depth: f64) -> Self {
        let texel = size / width.max(height) as f64;
        let rows = ((depth / texel).round() as usize).max(1);
        let map = |w: Wall| {
            let cols = match w {
                Wall::X0 | Wall::X1 => height,
                Wall::Y0 | Wall::Y1 => width,
            };
            WallMap::new(cols, rows, size, depth)
        };
        WallMaps {
            maps: Wall::ALL.map(map),
        }
    }

    /// Wall `w`'s map.
    pub fn get(&self, w: Wall) -> &WallMap {
        &self.maps[w.index()]
    }

    /// Wall `w`'s map, to write into.
    pub fn get_mut(&mut self, w: Wall) -> &mut WallMap {
        &mut self.maps[w.index()]
    }

    /// Flux on all four walls (see [`WallMap::flux`]).
    pub fn flux(&self) -> f64 {
        self.maps.iter().map(WallMap::flux).sum()
    }

    /// The four files `--raw-walls PREFIX` writes: `PREFIX-x0.npy`, `PREFIX-x1.npy`,
    /// `PREFIX-y0.npy`, `PREFIX-y1.npy`.
    pub fn raw_paths(prefix: &Path) -> [PathBuf; 4] {
        Wall::ALL.map(|w| {
            let mut name = prefix.as_os_str().to_owned();
            name.push(format!("-{}.npy", w.suffix()));
            PathBuf::from(name)
        })
    }

    /// Writes the four maps (channel mean, float32) to [`WallMaps::raw_paths`].
    pub fn write_raw(&self, prefix: &Path) -> Result<[PathBuf; 4]> {
        let paths = Self::raw_paths(prefix);
        for (map, path) in self.maps.iter().zip(&paths) {
            map.mean_channel().write_npy(path)?;
        }
        Ok(paths)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_leaves_through_the_nearest_wall() {
        let p = DVec2::new(1.0, 3.0);
        assert_eq!(
            Wall::exit(p, DVec2::new(1.0, 0.0), 4.0),
            Some((Wall::X1, 3.0))
        );
        assert_eq!(
            Wall::exit(p, DVec2::new(-1.0, 0.0), 4.0),
            Some((Wall::X0, 1.0))
        );
        assert_eq!(
            Wall::exit(p, DVec2::new(0.0, 2.0), 4.0),
            Some((Wall::Y1, 0.5))
        );
        assert_eq!(
            Wall::exit(p, DVec2::new(-1.0, 2.0), 4.0),
            Some((Wall::Y1, 0.5))
        );
        // The corner (0, 4).
        assert_eq!(
            Wall::exit(p, DVec2::new(-1.0, 1.0), 4.0),
            Some((Wall::X0, 1.0))
        );
        assert_eq!(Wall::exit(p, DVec2::ZERO, 4.0), None);
        for w in Wall::ALL {
            let q = w.point(1.5, 0.25, 4.0);
            assert_eq!(w.along(q), 1.5);
            let inward = q + w.normal() * 0.1;
            assert!((0.0..=4.0).contains(&inward.x) && (0.0..=4.0).contains(&inward.y));
        }
    }

    #[test]
    fn wall_maps_follow_the_floor_maps_texels() {
        let maps = WallMaps::for_floor_map(256, 128, 4.0, 1.0);
        assert_eq!(
            (maps.get(Wall::X0).cols, maps.get(Wall::Y1).cols),
            (128, 256)
        );
        // Texel side 4/256 m: 64 rows fill 1 m.
        assert_eq!(maps.get(Wall::X1).rows, 64);
        let m = maps.get(Wall::Y0);
        assert_eq!(m.texel(0.0, 0.0), Some(0));
        assert_eq!(m.texel(3.99, 0.999), Some(63 * 256 + 255));
        assert_eq!(m.texel(4.0, 0.5), None);
        assert_eq!(m.texel(1.0, -0.01), None);
        let (a, z) = m.texel_centre(2, 3);
        assert_eq!(m.texel(a, z), Some(2 * 256 + 3));
        let paths = WallMaps::raw_paths(Path::new("out/w"));
        assert_eq!(paths[1], PathBuf::from("out/w-x1.npy"));
        assert_eq!(paths[2], PathBuf::from("out/w-y0.npy"));
    }

    #[test]
    fn a_uniform_wall_holds_its_area_in_flux_and_samples_flat() {
        let mut maps = WallMaps::for_floor_map(64, 64, 2.0, 0.5);
        for t in &mut maps.get_mut(Wall::X0).texels {
            *t = [2.0; 3];
        }
        // 2 x (2 m x 0.5 m).
        assert!((maps.flux() - 2.0).abs() < 1e-12);
        assert_eq!(maps.get(Wall::X0).sample(0.01, 0.49), [2.0; 3]);
        assert_eq!(maps.get(Wall::X1).sample(1.0, 0.2), [0.0; 3]);
    }
}
