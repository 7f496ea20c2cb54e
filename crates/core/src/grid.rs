//! Regularly sampled scalar fields over the square `[0, size]²`: height fields of water and terrain,
//! and caustics maps. Sample `(i, j)` (row `i`, column `j`) sits at
//! `((j + 0.5) size / cols, (i + 0.5) size / rows)`, the same centring as the texels of a map, so a
//! height field and a caustics map of the same resolution line up texel for texel.
//!
//! Between samples the field is the Catmull-Rom bicubic interpolant: C¹, so a height field read from a
//! file has a continuous normal, and its gradient is the exact derivative of the interpolated height
//! (at the samples it reduces to the central difference).

#[cfg(feature = "formats")]
use std::io::{BufReader, BufWriter};
use std::path::Path;

use glam::DVec2;

use crate::error::{Error, Result};

/// The largest caustics map or image side we accept: far beyond any GPU's 2-D texture limit is a
/// typo. It lives with the grids because a height field file is refused past it before its samples
/// are read; the scene's checks take it from here (`crate::scene::MAX_RESOLUTION`).
pub const MAX_RESOLUTION: u32 = 16384;

/// What happens outside `[0, size]²`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edge {
    /// The field is periodic with period `size` (a tileable surface).
    Wrap,
    /// The field keeps its edge value.
    Clamp,
}

/// A scalar field sampled on a `cols × rows` lattice over `[0, size]²` (the size is given at each
/// lookup): a height field in world units above its rest level, or a map's values.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Samples along x.
    pub cols: usize,
    /// Samples along y.
    pub rows: usize,
    /// Row-major, row 0 at y = 0.
    pub data: Vec<f32>,
}

impl Grid {
    /// A grid of zeros.
    pub fn new(cols: usize, rows: usize) -> Self {
        Grid {
            cols,
            rows,
            data: vec![0.0; cols * rows],
        }
    }

    /// A grid whose sample at row `i`, column `j` is `f(i, j)`.
    pub fn from_fn(cols: usize, rows: usize, mut f: impl FnMut(usize, usize) -> f32) -> Self {
        let mut data = Vec::with_capacity(cols * rows);
        for i in 0..rows {
            for j in 0..cols {
                data.push(f(i, j));
            }
        }
        Grid { cols, rows, data }
    }

    /// The sample at row `i` (along y), column `j` (along x); panics outside the grid.
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> f32 {
        self.data[i * self.cols + j]
    }

    /// The four rows (as offsets into `data`) and four columns of the bicubic taps around
    /// `(i0, j0)`, `i0 − 1 ..= i0 + 2`, by the edge rule: 8 index wraps where 16 fetches would do
    /// 32.
    #[inline]
    fn taps(&self, i0: i64, j0: i64, edge: Edge) -> ([usize; 4], [usize; 4]) {
        let (r, c) = (self.rows as i64, self.cols as i64);
        let wrap = |k: i64, n: i64| match edge {
            Edge::Wrap => k.rem_euclid(n),
            Edge::Clamp => k.clamp(0, n - 1),
        } as usize;
        (
            std::array::from_fn(|a| wrap(i0 - 1 + a as i64, r) * self.cols),
            std::array::from_fn(|b| wrap(j0 - 1 + b as i64, c)),
        )
    }

    /// Value and gradient of the bicubic interpolant at `p` (world units, the grid covering
    /// `[0, size]²`).
    pub fn sample(&self, p: DVec2, size: f64, edge: Edge) -> (f64, DVec2) {
        let dx = size / self.cols as f64;
        let dy = size / self.rows as f64;
        let u = p.x / dx - 0.5;
        let v = p.y / dy - 0.5;
        let (j0, i0) = (u.floor(), v.floor());
        let (fu, fv) = (u - j0, v - i0);
        let (j0, i0) = (j0 as i64, i0 as i64);
        let (wu, dwu) = catmull_rom(fu);
        let (wv, dwv) = catmull_rom(fv);
        let (rows, cols) = self.taps(i0, j0, edge);
        let (mut h, mut hu, mut hv) = (0.0, 0.0, 0.0);
        for (&row, (&wy, &dwy)) in rows.iter().zip(wv.iter().zip(&dwv)) {
            for (&col, (&wx, &dwx)) in cols.iter().zip(wu.iter().zip(&dwu)) {
                let s = self.data[row + col] as f64;
                h += wx * wy * s;
                hu += dwx * wy * s;
                hv += wx * dwy * s;
            }
        }
        (h, DVec2::new(hu / dx, hv / dy))
    }

    /// The value alone of [`sample`](Self::sample), the same sum in the same order (so the same
    /// bits), without the gradient's: the view rays' march through the water evaluates only
    /// heights, hundreds of times for a grazing ray.
    pub fn height(&self, p: DVec2, size: f64, edge: Edge) -> f64 {
        let u = p.x / (size / self.cols as f64) - 0.5;
        let v = p.y / (size / self.rows as f64) - 0.5;
        let (j0, i0) = (u.floor(), v.floor());
        let (wu, _) = catmull_rom(u - j0);
        let (wv, _) = catmull_rom(v - i0);
        let (rows, cols) = self.taps(i0 as i64, j0 as i64, edge);
        let mut h = 0.0;
        for (&row, &wy) in rows.iter().zip(&wv) {
            for (&col, &wx) in cols.iter().zip(&wu) {
                h += wx * wy * self.data[row + col] as f64;
            }
        }
        h
    }

    /// The smallest and largest samples (`(+∞, −∞)` for an empty grid).
    pub fn min_max(&self) -> (f32, f32) {
        self.data
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// The mean of the samples (NaN for an empty grid).
    pub fn mean(&self) -> f64 {
        self.data.iter().map(|&v| v as f64).sum::<f64>() / self.data.len() as f64
    }

    /// Reject NaN and infinite samples, naming the first.
    pub fn check_finite(&self, what: &str) -> Result<()> {
        if let Some(k) = self.data.iter().position(|v| !v.is_finite()) {
            return Err(Error::InvalidParameter(format!(
                "{what}: sample (row {}, column {}) is {}",
                k / self.cols,
                k % self.cols,
                self.data[k]
            )));
        }
        Ok(())
    }

    /// Load a height field: `.npy` (float32 or float64, shape (rows, cols), C order), `.exr` (the first
    /// channel of the first layer) or 16-bit greyscale `.png` (0..65535 mapped linearly onto `png_range`).
    pub fn load(path: &Path, png_range: [f32; 2]) -> Result<Grid> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .unwrap_or("")
            .to_ascii_lowercase();
        let grid = match ext.as_str() {
            "npy" => read_npy(path)?,
            "exr" => read_exr(path)?,
            "png" => read_png16(path, png_range)?,
            _ => {
                return Err(Error::bad_file(
                    path,
                    "unsupported height-field format (expected .npy, .exr or 16-bit .png)",
                ));
            }
        };
        if grid.cols == 0 || grid.rows == 0 {
            return Err(Error::bad_file(path, "the height field is empty"));
        }
        if let Some(k) = grid.data.iter().position(|v| !v.is_finite()) {
            return Err(Error::bad_file(
                path,
                format!(
                    "sample (row {}, column {}) is {} (height fields must be finite)",
                    k / grid.cols,
                    k % grid.cols,
                    grid.data[k]
                ),
            ));
        }
        Ok(grid)
    }

    /// Write `what` (its name in the error) as `.npy` or `.exr`, by the path's extension.
    pub fn write_raw(&self, path: &Path, what: &str) -> Result<()> {
        let extension = path.extension().and_then(|e| e.to_str());
        match extension.map(|e| e.to_ascii_lowercase()).as_deref() {
            Some("npy") => self.write_npy(path),
            Some("exr") => self.write_exr(path),
            _ => Err(Error::bad_file(
                path,
                format!("{what} are written as .npy or .exr; give one of those extensions"),
            )),
        }
    }

    /// Write as float32 `.npy` of shape (rows, cols), row 0 first.
    pub fn write_npy(&self, path: &Path) -> Result<()> {
        #[cfg(not(feature = "formats"))]
        return Err(Error::feature_off(path, "writing .npy", "formats"));
        #[cfg(feature = "formats")]
        {
            use npyz::WriterBuilder;
            let file = std::fs::File::create(path).map_err(|e| Error::io(path, e))?;
            let mut writer = npyz::WriteOptions::new()
                .default_dtype()
                .shape(&[self.rows as u64, self.cols as u64])
                .writer(BufWriter::new(file))
                .begin_nd()
                .map_err(|e| Error::io(path, e))?;
            writer
                .extend(self.data.iter().copied())
                .map_err(|e| Error::io(path, e))?;
            writer.finish().map_err(|e| Error::io(path, e))
        }
    }

    /// Write as a single-channel (`Y`) float32 OpenEXR image, row 0 first.
    pub fn write_exr(&self, path: &Path) -> Result<()> {
        #[cfg(not(feature = "formats"))]
        return Err(Error::feature_off(path, "writing .exr", "formats"));
        #[cfg(feature = "formats")]
        {
            use exr::prelude::*;
            let channel = AnyChannel::new("Y", FlatSamples::F32(self.data.clone()));
            let layer = Layer::new(
                (self.cols, self.rows),
                LayerAttributes::named("caustics"),
                Encoding::FAST_LOSSLESS,
                AnyChannels::sort(SmallVec::from_vec(vec![channel])),
            );
            Image::from_layer(layer)
                .write()
                .to_file(path)
                .map_err(|e| crate::Error::bad_file(path, e.to_string()))
        }
    }
}

/// Catmull-Rom weights of the four taps at offsets -1, 0, 1, 2 and their derivatives with respect to t.
fn catmull_rom(t: f64) -> ([f64; 4], [f64; 4]) {
    let t2 = t * t;
    let t3 = t2 * t;
    (
        [
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ],
        [
            0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
            0.5 * (9.0 * t2 - 10.0 * t),
            0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
            0.5 * (3.0 * t2 - 2.0 * t),
        ],
    )
}

#[cfg(feature = "formats")]
/// The byte offset of a `.npy` file's samples, from its preamble: the magic string, the version,
/// and the header's length (2 bytes in version 1, 4 in versions 2 and 3).
///
/// npyz reserves the header's claimed length before reading it, so a 100-byte file claiming a
/// 2 GB header made it reserve 2 GB (found by fuzzing, `fuzz_regressions/npy-header-*.npy`);
/// the claim is checked against the file's length first.
fn npy_data_offset(path: &Path, file: &mut std::fs::File, len: u64) -> Result<u64> {
    use std::io::Read;
    let mut pre = [0u8; 12];
    let got = file.read(&mut pre).map_err(|e| Error::io(path, e))?;
    if got < 10 || &pre[..6] != b"\x93NUMPY" {
        return Err(Error::bad_file(
            path,
            "not a valid .npy file: no NUMPY preamble",
        ));
    }
    let (start, header) = match pre[6] {
        1 => (10, u64::from(u16::from_le_bytes([pre[8], pre[9]]))),
        2 | 3 if got == 12 => (
            12,
            u64::from(u32::from_le_bytes([pre[8], pre[9], pre[10], pre[11]])),
        ),
        v => {
            return Err(Error::bad_file(
                path,
                format!("not a valid .npy file: unknown format version {v}"),
            ));
        }
    };
    if start + header > len {
        return Err(Error::bad_file(
            path,
            format!(
                "not a valid .npy file: the header claims {header} bytes, the file has {len} in all"
            ),
        ));
    }
    Ok(start + header)
}

#[cfg(feature = "formats")]
fn read_npy(path: &Path) -> Result<Grid> {
    use std::io::{Seek, SeekFrom};
    let mut file = std::fs::File::open(path).map_err(|e| Error::io(path, e))?;
    let len = file.metadata().map_err(|e| Error::io(path, e))?.len();
    let offset = npy_data_offset(path, &mut file, len)?;
    file.seek(SeekFrom::Start(0))
        .map_err(|e| Error::io(path, e))?;
    let npy = npyz::NpyFile::new(BufReader::new(file))
        .map_err(|e| Error::bad_file(path, format!("not a valid .npy file: {e}")))?;
    let shape = npy.shape().to_vec();
    if shape.len() != 2 {
        return Err(Error::bad_file(
            path,
            format!("expected a 2-D array (rows, cols), found shape {shape:?}"),
        ));
    }
    if npy.order() == npyz::Order::Fortran {
        return Err(Error::bad_file(
            path,
            "Fortran-ordered arrays are not supported; save with C order",
        ));
    }
    let dtype = npy.dtype();
    // Likewise the samples: the shape must fit in the file before any is read.
    if let npyz::DType::Plain(t) = &dtype {
        let needed = (shape[0].checked_mul(shape[1])).and_then(|n| n.checked_mul(t.size_field()));
        if needed.is_none_or(|n| n > len - offset) {
            return Err(Error::bad_file(
                path,
                format!(
                    "the header's shape ({}, {}) of {}-byte samples needs more than the {} bytes \
                     of samples the file holds",
                    shape[0],
                    shape[1],
                    t.size_field(),
                    len - offset
                ),
            ));
        }
    }
    let data: Vec<f32> = match &dtype {
        npyz::DType::Plain(t) if t.type_char() == npyz::TypeChar::Float && t.size_field() == 4 => {
            npy.into_vec::<f32>()
                .map_err(|e| Error::bad_file(path, e.to_string()))?
        }
        npyz::DType::Plain(t) if t.type_char() == npyz::TypeChar::Float && t.size_field() == 8 => {
            npy.into_vec::<f64>()
                .map_err(|e| Error::bad_file(path, e.to_string()))?
                .into_iter()
                .map(|v| v as f32)
                .collect()
        }
        other => {
            return Err(Error::bad_file(
                path,
                format!("expected float32 samples, found dtype {}", other.descr()),
            ));
        }
    };
    let (rows, cols) = (shape[0] as usize, shape[1] as usize);
    Ok(Grid { cols, rows, data })
}

#[cfg(feature = "formats")]
fn read_exr(path: &Path) -> Result<Grid> {
    use exr::prelude::*;
    // exr sizes its sample buffers from the header's data window before it reads a pixel, so a
    // few hundred bytes naming a 10⁸ x 10⁸ window asked for petabytes (found by fuzzing,
    // crates/core/tests/fuzz_regressions/exr-huge-data-window.exr). The headers alone are read
    // first, and a layer larger than the largest grid the program takes is refused.
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| crate::Error::bad_file(path, format!("not a readable OpenEXR image: {e}")))?;
    let max = MAX_RESOLUTION as usize;
    for header in meta.headers.iter() {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        let channels = header.channels.list.len();
        if w > max || h > max || (w * h).saturating_mul(channels) > max * max {
            return Err(crate::Error::bad_file(
                path,
                format!(
                    "a layer of {w} x {h} samples in {channels} channel(s) is larger than the largest \
                     height field taken ({max} x {max} samples in one channel)"
                ),
            ));
        }
    }
    let image = read_first_flat_layer_from_file(path)
        .map_err(|e| crate::Error::bad_file(path, format!("not a readable OpenEXR image: {e}")))?;
    let layer = &image.layer_data;
    let (cols, rows) = (layer.size.width(), layer.size.height());
    let channel = layer
        .channel_data
        .list
        .first()
        .ok_or_else(|| crate::Error::bad_file(path, "the image has no channel"))?;
    let data: Vec<f32> = channel.sample_data.values_as_f32().collect();
    Ok(Grid { cols, rows, data })
}

#[cfg(feature = "formats")]
fn read_png16(path: &Path, range: [f32; 2]) -> Result<Grid> {
    let img = image::open(path).map_err(|e| Error::bad_file(path, e.to_string()))?;
    let image::DynamicImage::ImageLuma16(img) = img else {
        return Err(Error::bad_file(
            path,
            format!("expected a 16-bit greyscale PNG, found {:?}", img.color()),
        ));
    };
    let (cols, rows) = (img.width() as usize, img.height() as usize);
    // PNG rows run top to bottom; row 0 of the file is the row at y = 0, as in .npy.
    let data = img
        .into_raw()
        .into_iter()
        .map(|v| range[0] + (range[1] - range[0]) * v as f32 / 65535.0)
        .collect();
    Ok(Grid { cols, rows, data })
}

#[cfg(not(feature = "formats"))]
fn read_npy(path: &Path) -> Result<Grid> {
    Err(Error::feature_off(path, "a .npy height field", "formats"))
}

#[cfg(not(feature = "formats"))]
fn read_exr(path: &Path) -> Result<Grid> {
    Err(Error::feature_off(path, "an .exr height field", "formats"))
}

#[cfg(not(feature = "formats"))]
fn read_png16(path: &Path, _range: [f32; 2]) -> Result<Grid> {
    Err(Error::feature_off(path, "a PNG height field", "formats"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolant_passes_through_samples_and_gradient_is_exact() {
        let g = Grid::from_fn(16, 12, |i, j| ((i * 7 + j * 3) % 5) as f32 * 0.1);
        let size = 2.0;
        for (i, j) in [(0usize, 0usize), (3, 5), (11, 15)] {
            let p = DVec2::new(
                (j as f64 + 0.5) * size / 16.0,
                (i as f64 + 0.5) * size / 12.0,
            );
            let (h, _) = g.sample(p, size, Edge::Wrap);
            assert!((h - g.at(i, j) as f64).abs() < 1e-6);
        }
        let e = 1e-6;
        for p in [
            DVec2::new(0.31, 0.77),
            DVec2::new(1.9, 0.02),
            DVec2::new(-0.3, 2.4),
        ] {
            let (_, grad) = g.sample(p, size, Edge::Wrap);
            let fx = (g.sample(p + DVec2::X * e, size, Edge::Wrap).0
                - g.sample(p - DVec2::X * e, size, Edge::Wrap).0)
                / (2.0 * e);
            let fy = (g.sample(p + DVec2::Y * e, size, Edge::Wrap).0
                - g.sample(p - DVec2::Y * e, size, Edge::Wrap).0)
                / (2.0 * e);
            assert!((grad.x - fx).abs() < 1e-5 && (grad.y - fy).abs() < 1e-5);
        }
    }

    #[test]
    fn npy_and_exr_round_trip() {
        let dir = std::env::temp_dir().join(format!("caustics-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let g = Grid::from_fn(5, 3, |i, j| i as f32 - 0.25 * j as f32);
        let npy = dir.join("g.npy");
        g.write_npy(&npy).unwrap();
        assert_eq!(Grid::load(&npy, [0.0, 1.0]).unwrap(), g);
        let exr = dir.join("g.exr");
        g.write_exr(&exr).unwrap();
        assert_eq!(Grid::load(&exr, [0.0, 1.0]).unwrap(), g);
    }

    #[test]
    fn sixteen_bit_png_maps_onto_its_range() {
        let dir = std::env::temp_dir().join(format!("caustics-grid-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("h.png");
        let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(4, 3, |x, y| {
            image::Luma([(x * 20000 + y * 1000) as u16])
        });
        img.save(&p).unwrap();
        let g = Grid::load(&p, [-0.1, 0.1]).unwrap();
        assert_eq!((g.cols, g.rows), (4, 3));
        let expected = |x: u32, y: u32| -0.1 + 0.2 * (x * 20000 + y * 1000) as f32 / 65535.0;
        assert!((g.at(2, 3) - expected(3, 2)).abs() < 1e-6);
        assert!((g.at(0, 0) + 0.1).abs() < 1e-6);
        // An 8-bit PNG is refused: it cannot hold a height field's precision.
        let p8 = dir.join("h8.png");
        image::GrayImage::new(2, 2).save(&p8).unwrap();
        let e = Grid::load(&p8, [0.0, 1.0]).unwrap_err().to_string();
        assert!(e.contains("16-bit"), "{e}");
    }

    #[test]
    fn bad_files_are_named() {
        let dir = std::env::temp_dir().join(format!("caustics-grid-bad-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("junk.npy");
        std::fs::write(&p, b"not numpy").unwrap();
        let e = Grid::load(&p, [0.0, 1.0]).unwrap_err().to_string();
        assert!(e.contains("junk.npy") && e.contains(".npy"), "{e}");
        let nan = dir.join("nan.npy");
        let mut g = Grid::new(4, 4);
        g.data[6] = f32::NAN;
        g.write_npy(&nan).unwrap();
        let e = Grid::load(&nan, [0.0, 1.0]).unwrap_err().to_string();
        assert!(e.contains("row 1, column 2") && e.contains("NaN"), "{e}");
    }
}
