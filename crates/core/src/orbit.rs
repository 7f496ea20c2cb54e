//! The interactive view's camera and sun, shared by every front end (the viewer, the browser page):
//! an orbit camera around a target point (with pan, zoom and WASD flight), the sun as azimuth and
//! elevation, and the pick of a water point under the pointer.
//!
//! The world is z-up, as in the scene files; the camera is turned into a
//! [`crate::scene::Camera`] each frame so that the final image is traced exactly as
//! `caustics render` traces it, and a pick uses that camera's own [`Camera::ray`].

use glam::{DVec2, DVec3};

use crate::scene::Camera;

/// The steepest the camera looks up or down: just short of the pole, where yaw has no meaning.
const MAX_PITCH: f64 = 1.55;

/// A camera orbiting `target` at `distance`, looking at it from azimuth `yaw` and elevation
/// `pitch` (radians). Orbiting keeps the target; flying moves both.
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitCamera {
    /// The point looked at and orbited, world units.
    pub target: DVec3,
    /// Radians from +x towards +y of the direction from the target to the eye.
    pub yaw: f64,
    /// Radians of the eye above the target's horizontal plane (below it when negative), within
    /// ±1.55 once orbited.
    pub pitch: f64,
    /// From the target to the eye, world units; zoom keeps it within 0.02 to 30 times `scale`.
    pub distance: f64,
    /// Vertical field of view, degrees.
    pub fov_y: f64,
    /// The scene's size, which sets the speeds and the zoom range so that every scene, 1 unit or
    /// 32 across, handles alike.
    pub scale: f64,
}

impl OrbitCamera {
    /// The scene's own camera as an orbit around its target.
    pub fn from_scene(camera: &Camera, scene_size: f64) -> Self {
        let offset = camera.position - camera.target;
        let distance = offset.length().max(1e-6);
        OrbitCamera {
            target: camera.target,
            yaw: offset.y.atan2(offset.x),
            pitch: (offset.z / distance).clamp(-1.0, 1.0).asin(),
            distance,
            fov_y: camera.fov_y,
            scale: scene_size,
        }
    }

    /// The eye's position, world units.
    pub fn position(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        self.target + self.distance * DVec3::new(cp * cy, cp * sy, sp)
    }

    /// Forward, right and up, as [`Camera::ray`] builds them.
    pub fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let forward = (self.target - self.position()).normalize();
        let right = forward.cross(DVec3::Z).normalize_or(DVec3::X);
        (forward, right, right.cross(forward))
    }

    /// Turn by a pointer drag of `dx`, `dy` pixels: right drags the scene right (the camera left),
    /// down drags it down.
    pub fn orbit(&mut self, dx: f64, dy: f64) {
        self.yaw -= dx * 0.006;
        self.pitch = (self.pitch + dy * 0.006).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Zoom by `steps` wheel notches (positive: closer), multiplicatively so that each notch feels
    /// the same near and far.
    pub fn zoom(&mut self, steps: f64) {
        self.distance =
            (self.distance * (-steps * 0.12).exp()).clamp(0.02 * self.scale, 30.0 * self.scale);
    }

    /// Move the target with a drag of `dx`, `dy` pixels in a view `height` pixels tall, so that the
    /// point under the pointer at the target's depth follows the pointer.
    pub fn pan(&mut self, dx: f64, dy: f64, height: f64) {
        let (_, right, up) = self.basis();
        let per_pixel =
            2.0 * self.distance * (self.fov_y.to_radians() * 0.5).tan() / height.max(1.0);
        self.target += (-right * dx + up * dy) * per_pixel;
    }

    /// Fly for `dt` seconds: `forward` along the view, `right` sideways, `up` along +z (each -1, 0
    /// or 1), at a fifth of the scene per second, both the eye and the target. Nothing holds the eye
    /// above the water: flown under the surface, it sees the pool from below (the final image starts
    /// its rays in the water, `caustics_core::render::camera_under_water`).
    pub fn fly(&mut self, forward: f64, right: f64, up: f64, dt: f64) {
        let (f, r, _) = self.basis();
        let step = (f * forward + r * right + DVec3::Z * up) * (0.2 * self.scale * dt);
        self.target += step;
    }

    /// The scene camera for an image of `width` x `height` pixels.
    pub fn camera(&self, width: u32, height: u32) -> Camera {
        Camera {
            position: self.position(),
            target: self.target,
            fov_y: self.fov_y,
            width: width.max(1),
            height: height.max(1),
        }
    }
}

/// The sun as the panel shows it: where it stands in the sky, not where its light goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun {
    /// Degrees from +x towards +y of the direction towards the sun.
    pub azimuth: f64,
    /// Degrees above the horizon.
    pub elevation: f64,
}

/// The lowest sun: lower, the refracted light grazes the floor and every technique's assumptions
/// (and the scene checks, which want z < 0) strain.
pub const MIN_ELEVATION: f64 = 5.0;

impl Sun {
    /// From a scene's light direction (of travel, z < 0).
    pub fn from_direction(direction: DVec3) -> Self {
        let to_sun = -direction.normalize();
        Sun {
            azimuth: to_sun.y.atan2(to_sun.x).to_degrees(),
            elevation: to_sun.z.clamp(-1.0, 1.0).asin().to_degrees(),
        }
    }

    /// The direction the light travels, unit, pointing down.
    pub fn direction(&self) -> DVec3 {
        let (sa, ca) = self.azimuth.to_radians().sin_cos();
        let elevation = self.elevation.clamp(MIN_ELEVATION, 90.0).to_radians();
        let (se, ce) = elevation.sin_cos();
        -DVec3::new(ce * ca, ce * sa, se)
    }

    /// Move the sun by a drag of `dx`, `dy` pixels: sideways turns it, up raises it.
    pub fn drag(&mut self, dx: f64, dy: f64) {
        self.azimuth = wrap_degrees(self.azimuth - dx * 0.4);
        self.elevation = (self.elevation - dy * 0.25).clamp(MIN_ELEVATION, 90.0);
    }
}

/// An angle in (-180, 180].
fn wrap_degrees(a: f64) -> f64 {
    let w = (a + 180.0).rem_euclid(360.0) - 180.0;
    if w == -180.0 { 180.0 } else { w }
}

/// The point of the water's rest plane `z = level` seen through pixel `(x, y)` of `camera`, as
/// water coordinates in `[0, size]²`; `None` when the ray misses the plane or the square. The rest
/// plane stands in for the moving surface: waves are millimetres high, so the pick is off by less
/// than a ripple's radius.
pub fn pick_water(camera: &Camera, x: f64, y: f64, level: f64, size: f64) -> Option<DVec2> {
    let (origin, dir) = camera.ray(x, y);
    if dir.z.abs() < 1e-9 {
        return None;
    }
    let t = (level - origin.z) / dir.z;
    if t <= 0.0 {
        return None;
    }
    let p = (origin + dir * t).truncate();
    (p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size).then_some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_camera() -> Camera {
        Camera {
            position: DVec3::new(-0.3, -0.9, 2.4),
            target: DVec3::new(2.0, 2.0, 0.2),
            fov_y: 55.0,
            width: 320,
            height: 180,
        }
    }

    #[test]
    fn orbit_camera_reproduces_the_scene_camera() {
        let c = scene_camera();
        let o = OrbitCamera::from_scene(&c, 4.0);
        assert!((o.position() - c.position).length() < 1e-9);
        let back = o.camera(c.width, c.height);
        let (_, d0) = c.ray(10.0, 20.0);
        let (_, d1) = back.ray(10.0, 20.0);
        assert!((d0 - d1).length() < 1e-9);
    }

    #[test]
    fn orbit_keeps_target_and_distance_zoom_stays_in_range() {
        let mut o = OrbitCamera::from_scene(&scene_camera(), 4.0);
        let (t, d) = (o.target, o.distance);
        o.orbit(300.0, -1000.0);
        assert_eq!(o.target, t);
        assert!(((o.position() - t).length() - d).abs() < 1e-9);
        assert!(o.pitch.abs() <= MAX_PITCH);
        for _ in 0..200 {
            o.zoom(1.0);
        }
        assert!(o.distance >= 0.02 * 4.0 - 1e-12);
    }

    #[test]
    fn pan_moves_the_target_in_the_view_plane() {
        let mut o = OrbitCamera::from_scene(&scene_camera(), 4.0);
        let (f, _, _) = o.basis();
        let t = o.target;
        o.pan(40.0, -25.0, 180.0);
        assert!((o.target - t).dot(f).abs() < 1e-9);
        assert!((o.target - t).length() > 0.0);
    }

    #[test]
    fn flying_down_dives_under_the_water() {
        use crate::render::camera_under_water;
        use crate::scene::Scene;
        let mut scene = Scene::builtin("pool").unwrap();
        let level = scene.water.as_ref().unwrap().depth;
        let mut o = OrbitCamera::from_scene(&scene.camera, scene.size);
        assert!(!camera_under_water(&scene, None));
        // Forward at 0.8 m/s for 4.3 s: 3.44 m of the 4.32 m to the target on the pool's floor,
        // to (1.538, 1.417, 0.642), under the rest level 1 m.
        for _ in 0..43 {
            o.fly(1.0, 0.0, 0.0, 0.1);
        }
        let p = o.position();
        assert!((p - DVec3::new(1.538, 1.417, 0.642)).length() < 1e-3, "{p}");
        assert!(p.z < level);
        scene.camera = o.camera(320, 180);
        assert!(camera_under_water(&scene, None));
    }

    #[test]
    fn sun_round_trips_and_points_down() {
        let d = DVec3::new(0.3, 0.1, -1.0).normalize();
        let s = Sun::from_direction(d);
        assert!((s.direction() - d).length() < 1e-9);
        let mut s = s;
        s.drag(100.0, 1000.0);
        assert!(s.elevation >= MIN_ELEVATION);
        assert!(s.direction().z < 0.0);
        assert!(s.azimuth > -180.0 && s.azimuth <= 180.0);
    }

    #[test]
    fn the_centre_pixel_picks_the_target_on_the_water() {
        // A camera looking straight at a point of the rest plane picks that point at the centre.
        let c = Camera {
            position: DVec3::new(1.0, -1.0, 3.0),
            target: DVec3::new(1.5, 2.0, 1.0),
            fov_y: 50.0,
            width: 101,
            height: 101,
        };
        let p = pick_water(&c, 50.0, 50.0, 1.0, 4.0).expect("hits the water");
        assert!((p - DVec2::new(1.5, 2.0)).length() < 1e-9);
        // Looking up never hits it.
        assert!(pick_water(&c, 50.0, -5000.0, 1.0, 4.0).is_none());
    }
}
