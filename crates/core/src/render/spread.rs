//! Ray differentials: how a sample's neighbours' rays differ from its own, carried along its first
//! path to give the footprint the floor's and walls' caustics and albedo are filtered over.

use glam::{DVec2, DVec3};

use crate::scene::Camera;

/// How the rays of a sample's neighbours, one sample spacing away along each image axis, differ
/// from its own: in origin and in direction (ray differentials, H. Igehy, "Tracing Ray
/// Differentials", SIGGRAPH 99), taken as secants across the sample rather than derivatives, so
/// that at the water they see how much the waves turn the refracted rays over the sample's
/// footprint, however curved the surface is within it. Carried along a sample's first path (its
/// primary ray, that ray's refraction, and the surface's mirror image of either seen from below;
/// glass, the air through Snell's window and the rays they spawn have none), they give the
/// footprint on the floor and the walls that the caustics and albedo are filtered over: the spread
/// of points that many rays of the sample would reach.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Spread {
    o: [DVec3; 2],
    d: [DVec3; 2],
}

impl Spread {
    /// The camera's: rays through image points half a sample spacing `h` (pixels) either side of
    /// `(x, y)` along each axis. GPU twin: `camera_spread` in final_image_spread.wgsl.
    pub(super) fn of_camera(cam: &Camera, x: f64, y: f64, h: f64) -> Spread {
        let dir = |dx: f64, dy: f64| cam.ray(x + dx, y + dy).1;
        Spread {
            o: [DVec3::ZERO; 2],
            d: [
                dir(0.5 * h, 0.0) - dir(-0.5 * h, 0.0),
                dir(0.0, 0.5 * h) - dir(0.0, -0.5 * h),
            ],
        }
    }

    /// The footprint's axes where the ray `o + t d` meets the plane through its end with normal
    /// `m` (Igehy's transfer: the neighbours' points on that plane, less the ray's own).
    pub(super) fn on_plane(&self, d: DVec3, t: f64, m: DVec3) -> [DVec2; 2] {
        self.on_plane3(d, t, m).map(DVec3::truncate)
    }

    /// [`on_plane`](Self::on_plane) in three dimensions (a wall's plane).
    pub(super) fn on_plane3(&self, d: DVec3, t: f64, m: DVec3) -> [DVec3; 2] {
        let cos = m.dot(d);
        std::array::from_fn(|k| {
            let v = self.o[k] + self.d[k] * t;
            if cos.abs() > 1e-9 {
                v - d * (m.dot(v) / cos)
            } else {
                v
            }
        })
    }

    /// Through the water surface met at `p` along `d` after `t`, its normal there `n`: each axis's
    /// neighbours meet the surface half a footprint either side of `p` (on the facet's plane, as
    /// Igehy's transfer has it), where the surface's own normals (`normal_at`) `bend` them: refract
    /// from above, reflect from below (the secant of the bent direction across the footprint).
    /// GPU twin: `bent_axis` in final_image_spread.wgsl.
    pub(super) fn bent(
        &self,
        normal_at: impl Fn(DVec2) -> DVec3,
        (p, d, t, n): (DVec3, DVec3, f64, DVec3),
        bend: impl Fn(DVec3, DVec3) -> Option<DVec3>,
    ) -> Spread {
        let mut out = Spread::default();
        let cos = n.dot(d);
        for k in 0..2 {
            let v = self.o[k] + self.d[k] * t;
            // A ray along the facet's plane: its neighbours' points off the ray, unprojected.
            let dp = if cos.abs() > 1e-9 {
                v - d * (n.dot(v) / cos)
            } else {
                v
            };
            let side = |sign: f64| {
                let m = normal_at((p + dp * (0.5 * sign)).truncate());
                bend((d + self.d[k] * (0.5 * sign)).normalize(), m)
            };
            out.o[k] = dp;
            if let (Some(a), Some(b)) = (side(-1.0), side(1.0)) {
                out.d[k] = b - a;
            }
        }
        out
    }
}
