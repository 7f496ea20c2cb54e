//! The per-object representation of §3.1-3.2: an orthographic frame aligned with a direction (the
//! refracted viewing ray for an object, the refracted sun for the shadow map), the depth texture
//! rendered along it, and the diffuse map. GPU twin: `volumes/depth.wgsl`.

use glam::{DVec2, DVec3};

use crate::mesh::{MeshBvh, TriangleMesh};

/// An orthographic view: the box `lo..hi` in the frame `(a, b, v)` (`v` the direction of projection,
/// depth growing along it), seen by `res x res` texels. Frame coordinates are measured from `lo`:
/// `(u, w, depth) = (a · p, b · p, v · p) − lo`.
#[derive(Clone, Debug, PartialEq)]
pub struct OrthoView {
    /// The texture's `u` axis, unit, world frame: horizontal, `v × z` (x where `v` is vertical).
    pub a: DVec3,
    /// The texture's `w` axis, unit, world frame: `v × a`.
    pub b: DVec3,
    /// The unit direction of projection, world frame; depth grows along it.
    pub v: DVec3,
    /// The box's near corner as `(a · p, b · p, v · p)`, world units: the frame's origin.
    pub lo: DVec3,
    /// The box's far corner as `(a · p, b · p, v · p)`, world units.
    pub hi: DVec3,
    /// Texels per side of its square textures.
    pub res: usize,
}

impl OrthoView {
    /// The box around `meshes` with its front face perpendicular to `v` (Fig. 3), padded by a
    /// thousandth of its size so that no surface lies on its faces.
    pub fn around(meshes: &[&TriangleMesh], v: DVec3, res: usize) -> OrthoView {
        let v = v.normalize();
        let a = v.cross(DVec3::Z).try_normalize().unwrap_or(DVec3::X);
        let b = v.cross(a);
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for m in meshes {
            for p in &m.positions {
                let q = DVec3::new(a.dot(*p), b.dot(*p), v.dot(*p));
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
        let pad = DVec3::splat(1e-3 * (hi - lo).max_element());
        OrthoView {
            a,
            b,
            v,
            lo: lo - pad,
            hi: hi + pad,
            res,
        }
    }

    /// The box's size along `(a, b, v)`, world units.
    pub fn extent(&self) -> DVec3 {
        self.hi - self.lo
    }

    /// A texel's size in `(u, w)`.
    pub fn texel(&self) -> DVec2 {
        self.extent().truncate() / self.res as f64
    }

    /// `(u, w, depth)` of world point `p`.
    pub fn to_frame(&self, p: DVec3) -> DVec3 {
        DVec3::new(self.a.dot(p), self.b.dot(p), self.v.dot(p)) - self.lo
    }

    /// Texture pixel coordinates (texel `(i, j)` spans `[j, j + 1] x [i, i + 1]`) of frame point `q`.
    pub fn to_pixel(&self, q: DVec3) -> DVec2 {
        q.truncate() / self.texel()
    }

    /// The world point at the centre of texel `(i, j)` at `depth`.
    pub fn texel_point(&self, i: usize, j: usize, depth: f64) -> DVec3 {
        let t = self.texel();
        let u = self.lo.x + (j as f64 + 0.5) * t.x;
        let w = self.lo.y + (i as f64 + 0.5) * t.y;
        self.a * u + self.b * w + self.v * (self.lo.z + depth)
    }

    /// The nearest texel's entry of `texture` at frame point `q`, if `q` is inside the view and the
    /// texel is covered.
    pub fn lookup(&self, texture: &[[f32; 4]], q: DVec3) -> Option<[f32; 4]> {
        let px = self.to_pixel(q);
        let (j, i) = (px.x.floor(), px.y.floor());
        let r = self.res as f64;
        if !(j >= 0.0 && i >= 0.0 && j < r && i < r) {
            return None;
        }
        let t = texture[i as usize * self.res + j as usize];
        covered(&t).then_some(t)
    }
}

/// Whether a depth-texture entry holds a surface (its normal is not zero).
pub fn covered(t: &[f32; 4]) -> bool {
    t[1] != 0.0 || t[2] != 0.0 || t[3] != 0.0
}

/// The depth texture (§3.2, "rendering diffuse object using orthographic projection"): per texel, the
/// depth of the nearest surface of `meshes` along `v` and its outward normal, `[depth, nx, ny, nz]`;
/// zero where no surface is. Cast as one ray per texel centre, which gives what a rasteriser with a
/// depth buffer gives at the same centres.
pub fn depth_pass(view: &OrthoView, meshes: &[(&TriangleMesh, &MeshBvh)]) -> Vec<[f32; 4]> {
    let m = ray_margin(view);
    let t_max = view.extent().z + 2.0 * m;
    let mut out = vec![[0.0f32; 4]; view.res * view.res];
    for i in 0..view.res {
        for j in 0..view.res {
            let o = view.texel_point(i, j, -m);
            if let Some((_, t, n)) = crate::mesh::nearest(meshes.iter().copied(), o, view.v, t_max)
            {
                out[i * view.res + j] = [(t - m) as f32, n.x as f32, n.y as f32, n.z as f32];
            }
        }
    }
    out
}

/// How far before the box's front face the depth rays start.
pub fn ray_margin(view: &OrthoView) -> f64 {
    0.01 * view.extent().z
}

/// The diffuse map (§3.2): the object's colour where the depth texture is covered, with the
/// coverage in alpha.
pub fn diffuse_map(depth: &[[f32; 4]], albedo: DVec3) -> Vec<[f32; 4]> {
    depth
        .iter()
        .map(|t| {
            if covered(t) {
                [albedo.x as f32, albedo.y as f32, albedo.z as f32, 1.0]
            } else {
                [0.0; 4]
            }
        })
        .collect()
}
