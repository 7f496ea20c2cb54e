//! The eye camera's screen space: its pinhole projection ([`EyeCamera`]) and the caustics an
//! eye-space technique (`cascaded`, paper 5) makes in it ([`EyeSpaceCaustics`]). Both the
//! technique that makes such an image and the final image that reads it use these, so they sit
//! below the techniques and the renderer, above the scene model whose camera they project through.

use glam::{DVec2, DVec3};

use crate::error::Result;
use crate::grid::Grid;
use crate::scene::Camera;

/// The eye camera as a pinhole: `Camera::ray`'s basis with the field of view folded in.
#[derive(Clone, Copy, Debug)]
pub struct EyeCamera {
    /// The eye's position, world units.
    pub position: DVec3,
    /// Unit view direction, from the eye towards the camera's target.
    pub forward: DVec3,
    /// Unit screen x axis: horizontal (perpendicular to `forward` and world z), to the right.
    pub right: DVec3,
    /// Unit screen up axis, perpendicular to `forward` and `right` (pixel y grows the other way).
    pub up: DVec3,
    /// `tan(fov_y / 2)`.
    pub half: f64,
    /// Image width over height.
    pub aspect: f64,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
}

impl EyeCamera {
    /// The pinhole of the scene's camera, at the camera's own image size.
    pub fn new(c: &Camera) -> Self {
        let forward = (c.target - c.position).normalize();
        let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
        let up = right.cross(forward);
        EyeCamera {
            position: c.position,
            forward,
            right,
            up,
            half: (c.fov_y.to_radians() * 0.5).tan(),
            aspect: c.width as f64 / c.height as f64,
            width: c.width as usize,
            height: c.height as usize,
        }
    }

    /// The unnormalised ray through pixel point `(x, y)` (pixel centres at `+ ½`), forward component 1.
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        let sx = (2.0 * x / self.width as f64 - 1.0) * self.half * self.aspect;
        let sy = (1.0 - 2.0 * y / self.height as f64) * self.half;
        self.forward + self.right * sx + self.up * sy
    }

    /// Continuous pixel coordinates and view depth of world point `p` (`None` behind the eye).
    pub fn project(&self, p: DVec3) -> Option<(DVec2, f64)> {
        let v = p - self.position;
        let z = v.dot(self.forward);
        if z <= 0.0 {
            return None;
        }
        let sx = v.dot(self.right) / z / (self.half * self.aspect);
        let sy = v.dot(self.up) / z / self.half;
        Some((
            DVec2::new(
                (sx + 1.0) * 0.5 * self.width as f64,
                (1.0 - sy) * 0.5 * self.height as f64,
            ),
            z,
        ))
    }
}

/// Caustics computed in the eye camera's screen space (technique `cascaded`): per pixel of an image
/// made for the scene's camera, `[r, g, b, flag]` of relative irradiance (as a caustics map's texels)
/// at the floor point the pixel's straight ray meets; `flag < 0` where the technique has none.
#[derive(Clone, Debug)]
pub struct EyeSpaceCaustics {
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// `width · height` texels `[r, g, b, flag]`, row by row, row 0 at the top of the image.
    pub texels: Vec<[f32; 4]>,
}

/// Smallest total weight of the valid texels around a lookup for [`EyeSpaceCaustics::sample`] to
/// answer (below it the point lies off the image's valid part).
pub const EYE_SPACE_MIN_WEIGHT: f64 = 1e-3;

impl EyeSpaceCaustics {
    /// The camera's projection onto this image (its own size, the camera's aspect ratio).
    pub fn eye(&self, camera: &Camera) -> EyeCamera {
        let mut e = EyeCamera::new(camera);
        e.width = self.width;
        e.height = self.height;
        e
    }

    /// Write the image raw, as `CausticsMap::write_raw` writes a map: the mean of the channels as
    /// float32 `.npy` of shape (height, width) or single-channel `.exr`, by extension, row 0 at the
    /// top of the image; NaN where the technique has no value.
    pub fn write_raw(&self, path: &std::path::Path) -> Result<()> {
        let grid = Grid::from_fn(self.width, self.height, |i, j| {
            let t = self.texels[i * self.width + j];
            if t[3] < 0.0 {
                f32::NAN
            } else {
                (t[0] + t[1] + t[2]) / 3.0
            }
        });
        grid.write_raw(path, "the raw eye-space caustics")
    }

    /// Relative irradiance at floor point `p`: bilinear between the centres of the valid texels
    /// around the pixel point `p` projects to, their weights renormalised; `None` where `p` is
    /// behind the eye or has (next to) no valid texel around it.
    pub fn sample(&self, eye: &EyeCamera, p: DVec3) -> Option<DVec3> {
        let (q, _) = eye.project(p)?;
        let (u, v) = (q.x - 0.5, q.y - 0.5);
        let (x0, y0) = (u.floor(), v.floor());
        let (fu, fv) = (u - x0, v - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for (dy, wy) in [(0, 1.0 - fv), (1, fv)] {
            for (dx, wx) in [(0, 1.0 - fu), (1, fu)] {
                let (x, y) = (x0 + dx, y0 + dy);
                if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
                    continue;
                }
                let t = self.texels[y as usize * self.width + x as usize];
                if t[3] < 0.0 {
                    continue;
                }
                sum += DVec3::new(t[0] as f64, t[1] as f64, t[2] as f64) * (wx * wy);
                weight += wx * wy;
            }
        }
        (weight >= EYE_SPACE_MIN_WEIGHT).then(|| sum / weight)
    }
}
