//! Numbers as pictures: RGBA8 images with a line saying how their colours read, on the ramps every
//! front end shares (the viewer's map and buffer windows, and any page or plugin that shows a
//! technique's stages). Maps are drawn as seen from above: +x to the right, +y up (row 0 of a map,
//! at y = 0, is the bottom row).

use crate::grid::Grid;

/// An RGBA8 picture, top row first, with a line saying how its colours read.
#[derive(Clone, Debug)]
pub struct Picture {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Display colours, four bytes (red, green, blue, alpha) a pixel, row by row, top row first.
    pub rgba: Vec<u8>,
    /// How the colours read, for the user (`black 0, white 2.00 ...`); may be empty.
    pub legend: String,
}

/// The colour of a texel that has no value (sky, a corner outside the pool's box).
pub const NO_VALUE: [u8; 3] = [20, 30, 70];

/// A grid through a colour map, drawn with y up.
pub fn scalar_picture(g: &Grid, colour: impl Fn(f32) -> [u8; 3]) -> Picture {
    let rgba = flip_rows(g.cols, g.rows, |t| {
        let [r, gr, b] = colour(g.data[t]);
        [r, gr, b, 255]
    });
    Picture {
        width: g.cols as u32,
        height: g.rows as u32,
        rgba,
        legend: String::new(),
    }
}

/// `g` on the heat ramp, black at 0 and white at its maximum (at least `floor`), with the legend
/// `legend(white)`.
pub fn heat_picture(g: &Grid, floor: f32, legend: impl FnOnce(f32) -> String) -> Picture {
    let top = g.min_max().1.max(floor);
    Picture {
        legend: legend(top),
        ..scalar_picture(g, |v| heat(v / top))
    }
}

/// An RGB relative-irradiance image, row 0 at the top, on the heat ramp (0 black, the maximum,
/// at least 2, white); `None` texels drawn in [`NO_VALUE`].
pub fn rgb_picture(
    width: usize,
    height: usize,
    texel: impl Fn(usize) -> Option<[f32; 3]>,
    what: &str,
) -> Picture {
    let values: Vec<Option<f32>> = (0..width * height)
        .map(|t| texel(t).map(|c| (c[0] + c[1] + c[2]) / 3.0))
        .collect();
    let max = values
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0f32, f32::max);
    let top = max.max(2.0);
    let rgba = values
        .iter()
        .flat_map(|v| match v {
            Some(v) => {
                let [r, g, b] = heat(v / top);
                [r, g, b, 255]
            }
            None => [NO_VALUE[0], NO_VALUE[1], NO_VALUE[2], 255],
        })
        .collect();
    Picture {
        width: width as u32,
        height: height as u32,
        rgba,
        legend: format!("{what}: black 0, white {top:.2} (max {max:.2}); dark blue: no value"),
    }
}

/// RGBA rows of a row-major `cols x rows` buffer (row 0 at y = 0), top row first.
pub fn flip_rows(cols: usize, rows: usize, texel: impl Fn(usize) -> [u8; 4]) -> Vec<u8> {
    let mut out = Vec::with_capacity(cols * rows * 4);
    for i in (0..rows).rev() {
        for j in 0..cols {
            out.extend(texel(i * cols + j));
        }
    }
    out
}

/// Black, red, orange, yellow, white over [0, 1].
pub fn heat(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 5] = [
        [0.0, 0.0, 0.0],
        [0.55, 0.05, 0.1],
        [0.95, 0.45, 0.05],
        [1.0, 0.85, 0.25],
        [1.0, 1.0, 1.0],
    ];
    ramp(&STOPS, t)
}

/// Blue at -1, white at 0, red at +1.
pub fn diverging(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 3] = [[0.15, 0.3, 0.85], [0.97, 0.97, 0.97], [0.85, 0.15, 0.1]];
    ramp(&STOPS, 0.5 + 0.5 * t)
}

fn ramp(stops: &[[f32; 3]], t: f32) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (stops.len() - 1) as f32;
    let k = (x.floor() as usize).min(stops.len() - 2);
    let f = x - k as f32;
    std::array::from_fn(|c| ((stops[k][c] * (1.0 - f) + stops[k + 1][c] * f) * 255.0).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramps_span_their_ends() {
        assert_eq!(heat(0.0), [0, 0, 0]);
        assert_eq!(heat(1.0), [255, 255, 255]);
        assert_eq!(heat(f32::NAN), [0, 0, 0]);
        assert_eq!(diverging(0.0), [247, 247, 247]);
    }

    #[test]
    fn pictures_are_drawn_with_y_up() {
        let g = Grid::from_fn(2, 2, |i, _| i as f32);
        let p = scalar_picture(&g, |v| [(v * 255.0) as u8, 0, 0]);
        // Row 1 (y high) comes first.
        assert_eq!(&p.rgba[..4], &[255, 0, 0, 255]);
        assert_eq!(&p.rgba[8..12], &[0, 0, 0, 255]);
    }
}
