//! The post-process dispersion pass (`disperse.wgsl`, once per frame, under
//! [`Dispersion::Post`]).

use super::CascadedSetup;
#[cfg(doc)]
use super::Dispersion;

/// Post-process dispersion pass ([`Dispersion::Post`]): channel `c` of pixel `(x, y)`, whose floor
/// point is `F`, is the composed channel `c` read bilinearly at the projection of
/// `F − d · post_shift[c]`, `d` the water column over `F`.
pub fn disperse(setup: &CascadedSetup, eye: &[[f32; 4]], composed: &[[f32; 4]]) -> Vec<[f32; 4]> {
    let e = &setup.eye;
    let (w, h) = (e.width, e.height);
    let fetch = |x: i64, y: i64, c: usize| -> f64 {
        let x = x.clamp(0, w as i64 - 1) as usize;
        let y = y.clamp(0, h as i64 - 1) as usize;
        composed[y * w + x][c] as f64
    };
    let mut out = composed.to_vec();
    for y in 0..h {
        for x in 0..w {
            let ev = eye[y * w + x];
            if ev[3] == 0.0 {
                continue;
            }
            let f = e.position + e.ray(x as f64 + 0.5, y as f64 + 0.5) * ev[0] as f64;
            let column = (setup.level - f.z).max(0.0);
            for c in [0usize, 2] {
                let q = f - (setup.post_shift[c] * column).extend(0.0);
                let Some((p, _)) = e.project(q) else {
                    continue;
                };
                let (u, v) = (p.x - 0.5, p.y - 0.5);
                let (x0, y0) = (u.floor(), v.floor());
                let (fu, fv) = (u - x0, v - y0);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let val = (fetch(x0, y0, c) * (1.0 - fu) + fetch(x0 + 1, y0, c) * fu) * (1.0 - fv)
                    + (fetch(x0, y0 + 1, c) * (1.0 - fu) + fetch(x0 + 1, y0 + 1, c) * fu) * fv;
                out[y * w + x][c] = val as f32;
            }
        }
    }
    out
}
