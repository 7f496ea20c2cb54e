//! The reference extended to mesh receivers: a photon tracer through the same water onto the same
//! meshes and floor, converged, to judge technique `volumes` texel for texel in its own maps.
//!
//! # Method
//! Photons start on a jittered grid over the water (one per square of side `spacing`, at a random
//! point in it), on the true surface `z = depth + h(x, y)`. Each carries the flux the sun puts through
//! the piece of tilted surface above its square, relative to the sun on a horizontal surface,
//! `spacing² (1 + L_xy · ∇h / |L_z|)` (the same measure as [`crate::reference`]), times the Fresnel
//! transmittance relative to flat water and `exp(−K d)` over its path `d` in the water. It is refracted
//! with the exact Snell law through the true normal and followed to the nearest object (every mesh's
//! BVH) or the floor `z = 0`.
//!
//! - The **floor map** is traced over the technique's whole lattice domain at `floor_spacing`: a photon
//!   that reaches the floor adds `weight / A_texel`; one stopped by an object adds nothing (the shadow).
//! - Each **object map** (the technique's texels, in the object's frame) is traced over the object's
//!   footprint cells at `object_spacing`. A photon hitting the object at `P` with normal `n` counts only
//!   if `P` is on the surface seen along the view `v` (a ray from `P` back along `−v` meets no part of
//!   the mesh, an exact visibility test), and adds `weight |n · v| / A_texel` to the texel `P` projects
//!   into: the surface behind one texel has area `A_texel / |n · v|`, so the sum is the irradiance
//!   averaged over that surface.
//!
//! # Convergence
//! The grid is stratified, so the noise falls faster than `1/√photons` away from the caustics'
//! singular curves; `docs/volumes.md` gives the difference between runs at `s` and `s/2`.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::representation::covered;
use super::{CellRect, VolumesInput, VolumesSetup};
use crate::map::CausticsMap;
use crate::mesh::MeshBvh;
use crate::optics::{fresnel_transmittance, height_field_normal, refract};
use crate::water::Surface;

#[derive(Clone, Debug)]
pub struct MeshReferenceOptions {
    /// Photon spacing on the water for the floor map, world units.
    pub floor_spacing: f64,
    /// Photon spacing on the water for the objects' maps, world units.
    pub object_spacing: f64,
    pub seed: u64,
}

impl MeshReferenceOptions {
    /// `per_texel` photons per side of a floor texel, and of an object texel.
    pub fn per_texel(setup: &VolumesSetup, per_texel: f64) -> Self {
        let floor = setup.size / setup.width as f64;
        let object = setup
            .objects
            .iter()
            .map(|o| o.view.texel().min_element())
            .fold(floor, f64::min);
        MeshReferenceOptions {
            floor_spacing: floor / per_texel,
            object_spacing: object / per_texel,
            seed: 1,
        }
    }
}

pub struct MeshReference {
    /// Per object, relative irradiance in the technique's texels (zero where the object is not seen).
    pub objects: Vec<Vec<[f32; 3]>>,
    pub floor: CausticsMap,
    pub photons: u64,
}

fn hash01(mut x: u64) -> f64 {
    x = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 31;
    (x >> 11) as f64 / (1u64 << 53) as f64
}

struct Photon {
    start: DVec3,
    dir: DVec3,
    /// Flux relative to the sun on a horizontal surface, times the Fresnel weight (per channel the
    /// absorption is applied at the hit).
    flux: f64,
}

fn photon(setup: &VolumesSetup, surface: &dyn Surface, p: DVec2, area: f64) -> Option<Photon> {
    let (h, grad) = surface.height_gradient(p);
    let l = setup.light;
    let n = height_field_normal(grad);
    let cos_i = -l.dot(n);
    let seen = 1.0 + l.truncate().dot(grad) / -l.z;
    if cos_i <= 0.0 || seen <= 0.0 {
        return None;
    }
    let t = refract(l, n, setup.eta)?;
    let fresnel = if setup.params.fresnel {
        fresnel_transmittance(cos_i, 1.0, setup.ior) / setup.t_flat
    } else {
        1.0
    };
    Some(Photon {
        start: DVec3::new(p.x, p.y, setup.depth + h),
        dir: t,
        flux: area * seen * fresnel,
    })
}

/// The jittered photon positions over a rectangle of lattice cells, by rows of squares.
struct Strata {
    origin: DVec2,
    spacing: f64,
    nx: usize,
    ny: usize,
    seed: u64,
}

impl Strata {
    fn over(setup: &VolumesSetup, cells: CellRect, spacing: f64, seed: u64) -> Strata {
        let lat = &setup.lattice;
        let origin = lat.position(cells.i0, cells.j0);
        let side =
            DVec2::new((cells.j1 - cells.j0) as f64, (cells.i1 - cells.i0) as f64) * lat.cell;
        Strata {
            origin,
            spacing,
            nx: (side.x / spacing).ceil() as usize,
            ny: (side.y / spacing).ceil() as usize,
            seed,
        }
    }

    fn point(&self, i: usize, j: usize) -> DVec2 {
        let k = ((i * self.nx + j) as u64)
            .wrapping_mul(2)
            .wrapping_add(self.seed << 40);
        self.origin + DVec2::new(j as f64 + hash01(k), i as f64 + hash01(k + 1)) * self.spacing
    }
}

/// Trace the reference. `surface` is the water (displacement from rest), as the technique's heights
/// sample it.
pub fn mesh_reference(
    setup: &VolumesSetup,
    input: &VolumesInput,
    surface: &dyn Surface,
    options: &MeshReferenceOptions,
) -> MeshReference {
    let bvhs: Vec<MeshBvh> = input.objects.iter().map(|o| o.mesh.bvh()).collect();
    let nearest = |o: DVec3, d: DVec3, t_max: f64| {
        let mut best: Option<(usize, f64, DVec3)> = None;
        for (k, (obj, bvh)) in input.objects.iter().zip(&bvhs).enumerate() {
            let limit = best.map_or(t_max, |b| b.1);
            if let Some((t, n)) = bvh.intersect(&obj.mesh, o, d, limit) {
                best = Some((k, t, n));
            }
        }
        best
    };
    let absorb = |d: f64| (-setup.absorption * d).exp();
    let mut photons = 0u64;

    // The floor.
    let (w, h) = (setup.width, setup.height);
    let texel = DVec2::new(setup.size / w as f64, setup.size / h as f64);
    let strata = Strata::over(
        setup,
        setup.all_cells(),
        options.floor_spacing,
        options.seed,
    );
    let area = options.floor_spacing * options.floor_spacing;
    photons += (strata.nx * strata.ny) as u64;
    let floor_acc = (0..strata.ny)
        .into_par_iter()
        .fold(
            || vec![DVec3::ZERO; w * h],
            |mut acc, i| {
                for j in 0..strata.nx {
                    let Some(ph) = photon(setup, surface, strata.point(i, j), area) else {
                        continue;
                    };
                    let t_floor = ph.start.z / -ph.dir.z;
                    if nearest(ph.start, ph.dir, t_floor).is_some() {
                        continue;
                    }
                    let p = (ph.start + ph.dir * t_floor).truncate() / texel;
                    let (jj, ii) = (p.x.floor(), p.y.floor());
                    if jj >= 0.0 && ii >= 0.0 && (jj as usize) < w && (ii as usize) < h {
                        acc[ii as usize * w + jj as usize] += absorb(t_floor) * ph.flux;
                    }
                }
                acc
            },
        )
        .reduce(
            || vec![DVec3::ZERO; w * h],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x += *y);
                a
            },
        );
    let mut floor = CausticsMap::new(w, h, setup.size);
    let ta = texel.x * texel.y;
    for (t, e) in floor.texels.iter_mut().zip(floor_acc) {
        *t = [(e.x / ta) as f32, (e.y / ta) as f32, (e.z / ta) as f32];
    }

    // The objects, each from the photons of its own footprint.
    let mut objects = Vec::new();
    for (k, o) in setup.objects.iter().enumerate() {
        let view = &o.view;
        let res = view.res;
        let strata = Strata::over(
            setup,
            o.cells,
            options.object_spacing,
            options.seed + 1 + k as u64,
        );
        let area = options.object_spacing * options.object_spacing;
        photons += (strata.nx * strata.ny) as u64;
        let mesh = &input.objects[k].mesh;
        let scale = (view.extent()).max_element();
        let acc = (0..strata.ny)
            .into_par_iter()
            .fold(
                || vec![DVec3::ZERO; res * res],
                |mut acc, i| {
                    for j in 0..strata.nx {
                        let Some(ph) = photon(setup, surface, strata.point(i, j), area) else {
                            continue;
                        };
                        let t_floor = ph.start.z / -ph.dir.z;
                        let Some((hit, t, n)) = nearest(ph.start, ph.dir, t_floor) else {
                            continue;
                        };
                        if hit != k {
                            continue;
                        }
                        let p = ph.start + ph.dir * t;
                        let back = p - view.v * (1e-7 * scale);
                        if bvhs[k]
                            .intersect(mesh, back, -view.v, f64::INFINITY)
                            .is_some()
                        {
                            continue; // hidden from the view by the object itself
                        }
                        let px = view.to_pixel(view.to_frame(p));
                        let (jj, ii) = (px.x.floor(), px.y.floor());
                        if jj >= 0.0 && ii >= 0.0 && (jj as usize) < res && (ii as usize) < res {
                            acc[ii as usize * res + jj as usize] +=
                                absorb(t) * ph.flux * n.dot(view.v).abs();
                        }
                    }
                    acc
                },
            )
            .reduce(
                || vec![DVec3::ZERO; res * res],
                |mut a, b| {
                    a.iter_mut().zip(&b).for_each(|(x, y)| *x += *y);
                    a
                },
            );
        let tex = view.texel();
        let ta = tex.x * tex.y;
        objects.push(
            acc.into_iter()
                .map(|e| [(e.x / ta) as f32, (e.y / ta) as f32, (e.z / ta) as f32])
                .collect(),
        );
    }
    MeshReference {
        objects,
        floor,
        photons,
    }
}

/// Texels where both the technique's depth texture and the reference see the object and the
/// comparison is meaningful: covered, and not at a grazing silhouette (`|n · v| ≥ 0.2`), where a
/// texel's surface is long and thin and both estimates are ill-conditioned.
pub fn comparable(depth: &[[f32; 4]], v: DVec3) -> Vec<bool> {
    depth
        .iter()
        .map(|t| {
            covered(t)
                && DVec3::new(t[1] as f64, t[2] as f64, t[3] as f64)
                    .dot(v)
                    .abs()
                    >= 0.2
        })
        .collect()
}
