//! The caustics map as a picture: what the map window beside the final image shows (a floor map,
//! the pool's walls folded out around it, an eye-space image, the difference of two maps). The
//! techniques' intermediate buffers are drawn by the techniques themselves
//! (`caustics_core::techniques::buffers`).
//!
//! Every map is drawn as seen from above: +x to the right, +y up (row 0 of a map, at y = 0, is the
//! bottom row); eye-space images as the camera sees them.

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::plot::{Picture, diverging, heat, rgb_picture, scalar_picture};
use caustics_core::render::EyeSpaceCaustics;
use caustics_core::techniques::SceneCaustics;
use caustics_core::walls::{Wall, WallMaps};

/// The caustics map: relative irradiance through a heat ramp, 0 black, 1 (flat water) a dull
/// orange, the map's maximum (at least 2) white.
pub fn map_picture(map: &CausticsMap) -> Picture {
    let g = map.mean_channel();
    let (_, max) = g.min_max();
    let top = max.max(2.0);
    Picture {
        legend: format!("relative irradiance: black 0, white {top:.2} (max {max:.2})"),
        ..scalar_picture(&g, |v| heat(v / top))
    }
}

/// A technique's caustics as the map view shows them: a floor map ([`map_picture`]), with the
/// pool's walls folded out around it when the technique lit them ([`box_picture`]), or an
/// eye-space image ([`eye_picture`]).
pub fn caustics_picture(caustics: &SceneCaustics, walls: Option<&WallMaps>) -> Picture {
    match (caustics, walls) {
        (SceneCaustics::Floor(m), Some(w)) => box_picture(m, w).unwrap_or_else(|| map_picture(m)),
        (SceneCaustics::Floor(m), None) => map_picture(m),
        (SceneCaustics::EyeSpace(e), _) => eye_picture(e),
    }
}

/// The pool as an unfolded box: the floor map in the middle (y up, as [`map_picture`]), each wall
/// folded out flat beside the floor edge it stands on, its foot against that edge and its top (the
/// rest water level) outermost; dark blue in the corners. One heat ramp for all five, so light
/// the walls took from the floor reads at its true strength. `None` when the walls' maps do not
/// fit the floor map (not [`WallMaps::for_floor_map`] of it).
pub fn box_picture(floor: &CausticsMap, walls: &WallMaps) -> Option<Picture> {
    let (w, h) = (floor.width, floor.height);
    let r = walls.get(Wall::X0).rows;
    let fits = Wall::ALL.iter().all(|&k| {
        let m = walls.get(k);
        let along = match k {
            Wall::X0 | Wall::X1 => h,
            Wall::Y0 | Wall::Y1 => w,
        };
        m.rows == r && m.cols == along
    });
    if !fits {
        return None;
    }
    let (cols, rows) = (w + 2 * r, h + 2 * r);
    // Row-major with row 0 at y = 0 below the floor's first row.
    let mut values = vec![None; cols * rows];
    for i in 0..h {
        for j in 0..w {
            values[(r + i) * cols + r + j] = Some(floor.texels[i * w + j]);
        }
    }
    for k in Wall::ALL {
        let m = walls.get(k);
        for row in 0..r {
            for c in 0..m.cols {
                let (y, x) = match k {
                    Wall::X0 => (r + c, r - 1 - row),
                    Wall::X1 => (r + c, r + w + row),
                    Wall::Y0 => (r - 1 - row, r + c),
                    Wall::Y1 => (r + h + row, r + c),
                };
                values[y * cols + x] = Some(m.texels[row * m.cols + c]);
            }
        }
    }
    Some(rgb_picture(
        cols,
        rows,
        |t| values[(rows - 1 - t / cols) * cols + t % cols],
        "relative irradiance, the walls folded out around the floor",
    ))
}

/// An eye-space caustics image (`cascaded`) as the camera sees it, on the heat ramp of
/// [`map_picture`]; blue where the technique has no value (sky, water seen from above the floor's
/// reach).
pub fn eye_picture(image: &EyeSpaceCaustics) -> Picture {
    rgb_picture(
        image.width,
        image.height,
        |t| {
            let p = image.texels[t];
            (p[3] >= 0.0).then(|| [p[0], p[1], p[2]])
        },
        "relative irradiance",
    )
}

/// `a - b` of two maps of one size: blue where `a` is darker, red where brighter.
pub fn difference_picture(a: &CausticsMap, b: &CausticsMap) -> Option<Picture> {
    if (a.width, a.height) != (b.width, b.height) {
        return None;
    }
    let (ga, gb) = (a.mean_channel(), b.mean_channel());
    let d = Grid {
        cols: ga.cols,
        rows: ga.rows,
        data: ga.data.iter().zip(&gb.data).map(|(x, y)| x - y).collect(),
    };
    let (lo, hi) = d.min_max();
    let r = lo.abs().max(hi.abs()).max(1e-6);
    let mean_abs = d.data.iter().map(|v| v.abs() as f64).sum::<f64>() / d.data.len().max(1) as f64;
    Some(Picture {
        legend: format!("left - right: blue -{r:.2}, red +{r:.2}; mean |difference| {mean_abs:.3}"),
        ..scalar_picture(&d, |v| diverging(v / r))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_walls_fold_out_against_their_floor_edges() {
        // A 3 x 2 floor map over a 3 m square, 2 m deep: texels of 1 m, two rows on each wall.
        let mut floor = CausticsMap::new(3, 2, 3.0);
        floor.texels[0] = [1.0; 3]; // (x, y) = (0.5, 0.5)
        let mut walls = WallMaps::for_floor_map(3, 2, 3.0, 2.0);
        assert_eq!(walls.get(Wall::X1).rows, 2);
        // Wall x1, its foot, along y = 1.5 (its second column); wall y1, its top row, along x = 0.5.
        walls.get_mut(Wall::X1).texels[1] = [2.0; 3];
        walls.get_mut(Wall::Y1).texels[3] = [4.0; 3];
        let p = box_picture(&floor, &walls).unwrap();
        assert_eq!((p.width, p.height), (3 + 4, 2 + 4));
        let at = |x: usize, y: usize| {
            let k = ((p.height as usize - 1 - y) * p.width as usize + x) * 4;
            [p.rgba[k], p.rgba[k + 1], p.rgba[k + 2]]
        };
        // One ramp, white at 4.
        assert_eq!(at(2, 2 + 2 + 1), heat(1.0), "wall y1's top row, outermost");
        assert_eq!(
            at(2 + 3, 2 + 1),
            heat(0.5),
            "wall x1's foot, beside the floor's x = size edge"
        );
        assert_eq!(at(2, 2), heat(0.25), "the floor's first texel");
        assert_eq!(at(0, 0), [20, 30, 70], "a corner");
        assert_eq!(at(1, 2), heat(0.0), "wall x0, dark");
        // Walls that are not the floor map's are refused.
        let other = WallMaps::for_floor_map(4, 2, 3.0, 2.0);
        assert!(box_picture(&floor, &other).is_none());
    }

    #[test]
    fn eye_space_images_mark_texels_without_a_value() {
        let image = EyeSpaceCaustics {
            width: 2,
            height: 1,
            texels: vec![[1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, -1.0]],
        };
        let p = eye_picture(&image);
        assert_eq!(&p.rgba[4..8], &[20, 30, 70, 255]);
        assert_ne!(&p.rgba[..4], &[20, 30, 70, 255]);
    }
}
