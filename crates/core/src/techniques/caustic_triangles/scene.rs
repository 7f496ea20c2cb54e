//! What technique `caustic-triangles` and its reference see of a scene: one glass caustic generator
//! (an exact sphere or any closed mesh), diffuse occluders (walls) that stop light, the floor plane
//! `z = 0` as the receiver, and the scene's directional sun. The floor map covers the square
//! `[origin, origin + size]²` of the floor (the whole scene square when made from a [`Scene`]).

use glam::{DVec2, DVec3};

use crate::error::{Error, Result};
use crate::map::CausticsMap;
use crate::mesh::{MeshBvh, TriangleMesh, cuboid};
use crate::scene::{Material, Scene};

/// The generator's geometry: exact where it can be.
#[derive(Clone, Debug)]
pub enum Shape {
    /// An exact sphere.
    Sphere {
        /// Its centre, world coordinates.
        centre: DVec3,
        /// Its radius, world units.
        radius: f64,
    },
    /// A closed triangle mesh.
    Mesh {
        /// The triangles, world coordinates.
        mesh: TriangleMesh,
        /// The mesh's bounding-volume hierarchy for ray hits.
        bvh: MeshBvh,
    },
}

impl Shape {
    /// A mesh shape, its BVH built here.
    pub fn mesh(mesh: TriangleMesh) -> Shape {
        let bvh = mesh.bvh();
        Shape::Mesh { mesh, bvh }
    }

    /// Nearest hit of `origin + t dir` (unit `dir`) with `0 < t < t_max`: `t` and the outward normal.
    pub fn intersect(&self, origin: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, DVec3)> {
        match self {
            Shape::Sphere { centre, radius } => {
                let oc = origin - *centre;
                let b = oc.dot(dir);
                let c = oc.length_squared() - radius * radius;
                let disc = b * b - c;
                if disc < 0.0 {
                    return None;
                }
                let s = disc.sqrt();
                // A relative epsilon keeps a ray that starts on the surface from hitting it again.
                let eps = 1e-9 * radius;
                [-b - s, -b + s]
                    .into_iter()
                    .find(|&t| t > eps && t < t_max)
                    .map(|t| (t, (origin + t * dir - *centre) / *radius))
            }
            Shape::Mesh { mesh, bvh } => {
                let eps = 1e-9 * (mesh.bounds().1 - mesh.bounds().0).length();
                bvh.intersect(mesh, origin + eps * dir, dir, t_max - eps)
                    .map(|(t, n)| (t + eps, n))
            }
        }
    }

    /// The axis-aligned bounding box `(min, max)`, world coordinates.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        match self {
            Shape::Sphere { centre, radius } => (*centre - *radius, *centre + *radius),
            Shape::Mesh { mesh, .. } => mesh.bounds(),
        }
    }

    /// The rectangle `[min, max]` the shape covers in the light-space coordinates `(p·u, p·v)`.
    pub fn light_rect(&self, u: DVec3, v: DVec3) -> (DVec2, DVec2) {
        match self {
            Shape::Sphere { centre, radius } => {
                let c = DVec2::new(centre.dot(u), centre.dot(v));
                (c - *radius, c + *radius)
            }
            Shape::Mesh { mesh, .. } => {
                mesh.positions
                    .iter()
                    .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                        let q = DVec2::new(p.dot(u), p.dot(v));
                        (lo.min(q), hi.max(q))
                    })
            }
        }
    }
}

/// A diffuse object that stops light (a wall): a mesh and its BVH.
#[derive(Clone, Debug)]
pub struct Occluder {
    /// The occluder's triangles, world coordinates.
    pub mesh: TriangleMesh,
    /// The mesh's bounding-volume hierarchy for ray hits.
    pub bvh: MeshBvh,
}

impl Occluder {
    /// An occluder of `mesh`, its BVH built here.
    pub fn new(mesh: TriangleMesh) -> Self {
        let bvh = mesh.bvh();
        Occluder { mesh, bvh }
    }

    /// An axis-aligned box wall from `min` to `max`.
    pub fn wall(min: DVec3, max: DVec3) -> Self {
        let m = cuboid(0.5 * (max - min))
            .transformed(glam::DAffine3::from_translation(0.5 * (min + max)));
        Occluder::new(m)
    }
}

/// The floor square the map covers and its resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorWindow {
    /// The square's corner of least x and y on the floor, world units.
    pub origin: DVec2,
    /// Side of the square, world units.
    pub size: f64,
    /// Map texels along x.
    pub width: usize,
    /// Map texels along y.
    pub height: usize,
}

impl FloorWindow {
    /// Floor area of one map texel, world units².
    pub fn texel_area(&self) -> f64 {
        (self.size / self.width as f64) * (self.size / self.height as f64)
    }

    /// Floor point to map pixel coordinates (texel `(i, j)` spans `[j, j+1) x [i, i+1)`).
    pub fn to_pixel(&self, p: DVec2) -> DVec2 {
        (p - self.origin) / self.size * DVec2::new(self.width as f64, self.height as f64)
    }

    /// A `width x height` map of the square, all zero.
    pub fn empty_map(&self) -> CausticsMap {
        CausticsMap::new(self.width, self.height, self.size)
    }
}

/// A point light (paper 4, §4: the light the light cube map is centred at), optionally a spot.
///
/// Its radiant intensity is `position.z²` in the technique's floor units, so that it puts
/// irradiance 1 on the floor straight below it, as the sun puts 1 on the floor anywhere: the maps
/// and images of both lights read the same.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    /// Where the light is, world coordinates, above the floor (`z > 0`).
    pub position: DVec3,
    /// Unit axis of the spot's cone.
    pub axis: DVec3,
    /// The spot's half-angle, radians; `None` lights every direction.
    pub cone: Option<f64>,
}

impl PointLight {
    /// Radiant intensity, floor units (irradiance 1 on the floor straight below the light).
    pub fn intensity(&self) -> f64 {
        self.position.z * self.position.z
    }

    /// Whether the unit direction `d` from the light lies in the spot's cone.
    pub fn lights(&self, d: DVec3) -> bool {
        self.cone.is_none_or(|c| d.dot(self.axis) >= c.cos())
    }
}

/// Everything the technique and the reference need.
#[derive(Clone, Debug)]
pub struct GlassScene {
    /// The caustic generator's geometry (one glass object).
    pub generator: Shape,
    /// The generator's index of refraction, in air (> 1).
    pub ior: f64,
    /// Diffuse objects (walls) that stop light.
    pub occluders: Vec<Occluder>,
    /// Unit direction the sunlight travels, `z < 0`; for a point light, the direction from the
    /// light to the generator's bounding-sphere centre (the axis of its photon image).
    pub light: DVec3,
    /// A point light instead of the sun.
    pub point: Option<PointLight>,
    /// The floor square the caustics map covers and its resolution.
    pub floor: FloorWindow,
}

/// The generator's bounding sphere: the centre of its bounding box and the farthest vertex.
pub fn bounding_sphere(shape: &Shape) -> (DVec3, f64) {
    match shape {
        Shape::Sphere { centre, radius } => (*centre, *radius),
        Shape::Mesh { mesh, .. } => {
            let (lo, hi) = mesh.bounds();
            let c = 0.5 * (lo + hi);
            let r = mesh
                .positions
                .iter()
                .map(|p| (*p - c).length())
                .fold(0.0, f64::max);
            (c, r)
        }
    }
}

/// The light's frame: `w` the direction of travel, `u`, `v` spanning the plane across it.
pub fn light_frame(light: DVec3) -> (DVec3, DVec3, DVec3) {
    let w = light.normalize();
    let u = w.cross(DVec3::Y).try_normalize().unwrap_or(DVec3::X);
    let v = w.cross(u);
    (u, v, w)
}

impl GlassScene {
    /// The light-space rectangle the photons start over: the generator's under the sun; under a
    /// point light, the tangent plane (at distance 1 along `w`) of the cone of directions from the
    /// light to the generator's bounding sphere.
    pub fn light_rect(&self, u: DVec3, v: DVec3) -> (DVec2, DVec2) {
        let Some(pl) = self.point else {
            return self.generator.light_rect(u, v);
        };
        let (c, r) = bounding_sphere(&self.generator);
        let tan = r
            / ((c - pl.position).length_squared() - r * r)
                .max(1e-30)
                .sqrt();
        (DVec2::splat(-tan), DVec2::splat(tan))
    }

    /// A scene lit by the sun travelling along `light` (normalised here; it must point down). Errors
    /// where the IOR is not above 1 or the floor window is empty.
    pub fn new(
        generator: Shape,
        ior: f64,
        light: DVec3,
        floor: FloorWindow,
        occluders: Vec<Occluder>,
    ) -> Result<Self> {
        if light.z >= 0.0 || !light.is_finite() {
            return Err(Error::InvalidParameter(format!(
                "the light direction {light} must point down (z < 0)"
            )));
        }
        if ior.is_nan() || ior <= 1.0 {
            return Err(Error::InvalidParameter(format!(
                "the generator's index of refraction must exceed 1, got {ior}"
            )));
        }
        if floor.width == 0 || floor.height == 0 || floor.size.is_nan() || floor.size <= 0.0 {
            return Err(Error::InvalidParameter(format!(
                "the floor map must be at least 1 x 1 over a positive size, got {} x {} over {}",
                floor.width, floor.height, floor.size
            )));
        }
        Ok(GlassScene {
            generator,
            ior,
            occluders,
            light: light.normalize(),
            point: None,
            floor,
        })
    }

    /// The same scene lit by the point (or spot) light `point` instead of the sun. The light must be
    /// outside the generator's bounding sphere (its photon image spans the sphere's cone).
    pub fn with_point_light(mut self, point: PointLight) -> Result<Self> {
        let (c, r) = bounding_sphere(&self.generator);
        let to = c - point.position;
        if !point.position.is_finite() || point.position.z <= 0.0 {
            return Err(Error::InvalidParameter(format!(
                "the point light at {} must be above the floor (z > 0)",
                point.position
            )));
        }
        if to.length() <= r * 1.01 {
            return Err(Error::InvalidParameter(format!(
                "the point light at {} is inside the caustic generator's bounding sphere (centre {c}, \
                 radius {r:.4}): caustic-triangles needs it outside",
                point.position
            )));
        }
        let axis = point.axis.try_normalize().ok_or_else(|| {
            Error::InvalidParameter("the spot light's axis must not be the zero vector".into())
        })?;
        if let Some(cone) = point.cone
            && !(cone > 0.0 && cone <= std::f64::consts::FRAC_PI_2)
        {
            return Err(Error::InvalidParameter(format!(
                "the spot light's half-angle must be in (0, 90] degrees, got {}",
                cone.to_degrees()
            )));
        }
        self.light = to.normalize();
        self.point = Some(PointLight { axis, ..point });
        Ok(self)
    }

    /// The scene's `index`-th glass object as the generator (its mesh), its diffuse objects as
    /// occluders, the caustics resolution over the scene square.
    pub fn from_scene(scene: &Scene, index: usize) -> Result<Self> {
        if scene.floor.terrain.is_some() {
            return Err(Error::InvalidParameter(format!(
                "scene `{}`: caustic-triangles draws glass objects' caustics on the floor plane z = 0 \
                 only, and the scene has a terrain",
                scene.name
            )));
        }
        let glass: Vec<_> = scene
            .objects
            .iter()
            .filter(|o| matches!(o.material, Material::Glass { .. }))
            .collect();
        let obj = glass.get(index).ok_or_else(|| {
            Error::InvalidParameter(format!(
                "scene `{}` has {} glass objects; caustic-triangles needs glass object {index}",
                scene.name,
                glass.len()
            ))
        })?;
        let Material::Glass { ior, .. } = obj.material else {
            unreachable!()
        };
        let occluders = scene
            .objects
            .iter()
            .filter(|o| matches!(o.material, Material::Diffuse { .. }))
            .map(|o| Occluder::new(o.mesh.clone()))
            .collect();
        let gs = GlassScene::new(
            Shape::mesh(obj.mesh.clone()),
            ior,
            scene.light.direction,
            FloorWindow {
                origin: DVec2::ZERO,
                size: scene.size,
                width: scene.caustics.width as usize,
                height: scene.caustics.height as usize,
            },
            occluders,
        )?;
        match scene.light.position {
            None => Ok(gs),
            Some(position) => gs.with_point_light(PointLight {
                position,
                axis: scene.light.direction,
                cone: scene.light.cone,
            }),
        }
    }

    /// Nearest occluder hit before `t_max`.
    pub fn occluder_hit(&self, origin: DVec3, dir: DVec3, t_max: f64) -> Option<f64> {
        self.occluders
            .iter()
            .filter_map(|o| o.bvh.intersect(&o.mesh, origin, dir, t_max).map(|h| h.0))
            .fold(None, |best: Option<f64>, t| {
                Some(best.map_or(t, |b| b.min(t)))
            })
    }
}
