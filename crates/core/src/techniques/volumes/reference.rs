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
//! BVH) or the floor: the plane `z = 0`, or a terrain marched as [`crate::reference`] marches it
//! (`MeshReferenceOptions::terrain`), whose map is then the irradiance on the tilted surface (each
//! texel's flux over its true area).
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
//! # Walls
//! With `walls` (the scene's `[floor] walls = true`) the pool's four walls are receivers as
//! in [`crate::reference`]: only photons that enter through the water's square `[0, size]²` are
//! traced, and each ends at the first thing its straight ray meets, an object, the floor or a wall
//! plane (the wall the ray's horizontal part leaves the square through, [`Wall::exit`]). A photon on
//! a wall adds `weight / A_texel` to the wall texel at its `(along, z)`; one above the rest level (a
//! crest's own edge) goes to the top row, as the reference does. The objects shadow the walls as
//! they shadow the floor, and a wall stops light before it reaches an object behind it.
//!
//! # Convergence
//! The grid is stratified, so the noise falls faster than `1/√photons` away from the caustics'
//! singular curves; `docs/volumes.md` gives the difference between runs at `s` and `s/2`.

use crate::random::hash01;
use glam::{DVec2, DVec3};

use super::representation::covered;
use super::{CellRect, VolumesInput, VolumesSetup};
use crate::grid::{Edge, Grid};
use crate::map::CausticsMap;
use crate::mesh::MeshBvh;
use crate::optics::{air_transmittance, height_field_normal, refract};
use crate::parallel::par_sum;
use crate::receivers::HeightMarch;
use crate::walls::{Wall, WallMaps};
use crate::water::Surface;

/// How finely [`mesh_reference`] traces: photon spacings, the jitter's seed, the receivers.
#[derive(Clone, Debug)]
pub struct MeshReferenceOptions {
    /// Photon spacing on the water for the floor map, world units.
    pub floor_spacing: f64,
    /// Photon spacing on the water for the objects' maps, world units.
    pub object_spacing: f64,
    /// Seed of the photons' jitter within their squares: the same seed traces the same photons.
    pub seed: u64,
    /// The pool's walls receive light and stop it (see the module's "Walls").
    pub walls: bool,
    /// Trace the objects' own maps; off where only the floor and walls are wanted (the objects
    /// still stop light), which at the default spacing is most of the work.
    pub object_maps: bool,
    /// The floor's terrain (heights over the square, clamped beyond it) in place of the plane
    /// `z = 0`: each photon marches to it, and the floor map is the irradiance on the tilted
    /// surface, as [`crate::reference`]'s terrain maps are. Not with walls.
    pub terrain: Option<Grid>,
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
            walls: false,
            object_maps: true,
            terrain: None,
        }
    }
}

/// What [`mesh_reference`] traced: the objects', floor's and walls' maps, relative irradiance.
pub struct MeshReference {
    /// Per object, relative irradiance in the technique's texels (zero where the object is not
    /// seen); empty without [`MeshReferenceOptions::object_maps`].
    pub objects: Vec<Vec<[f32; 3]>>,
    /// The floor's map over the square `[0, size]²`, at the technique's floor map resolution.
    pub floor: CausticsMap,
    /// The walls' maps ([`WallMaps::for_floor_map`] of the floor map) with `walls`.
    pub walls: Option<WallMaps>,
    /// Photons traced in all, the floor's grid and the objects' together.
    pub photons: u64,
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
    let fresnel = air_transmittance(setup.params.fresnel, cos_i, setup.ior) / setup.t_flat;
    Some(Photon {
        start: DVec3::new(p.x, p.y, setup.depth + h),
        dir: t,
        flux: area * seen * fresnel,
    })
}

/// Where a photon's ray ends when no object stops it.
enum End {
    /// The floor point `(x, y)`.
    Floor(DVec2),
    /// A wall, at `(along, z)` on it.
    Wall(Wall, f64, f64),
}

/// The receiver a photon's ray meets first, objects aside, and its path to it: the floor, or with
/// `walls` the wall its horizontal part leaves the square through when it gets there before the
/// floor. A refracted ray always runs down, so it always ends somewhere.
fn end_of(setup: &VolumesSetup, ph: &Photon, walls: bool, terrain: Option<&Terrain>) -> (End, f64) {
    if let Some(t) = terrain {
        let height = |p: DVec2| t.grid.sample(p, setup.size, Edge::Clamp).0;
        return match t.march.intersect(ph.start, ph.dir, &height) {
            Some(d) => (End::Floor((ph.start + ph.dir * d).truncate()), d),
            None => (End::Floor(DVec2::splat(f64::NAN)), f64::INFINITY),
        };
    }
    let d_floor = ph.start.z / -ph.dir.z;
    if walls
        && let Some((wall, u)) = Wall::exit(ph.start.truncate(), ph.dir.truncate(), setup.size)
        && u < d_floor
    {
        let hit = ph.start + ph.dir * u;
        return (End::Wall(wall, wall.along(hit), hit.z), u);
    }
    (
        End::Floor((ph.start + ph.dir * d_floor).truncate()),
        d_floor,
    )
}

/// A terrain floor and the bound its march steps by.
struct Terrain<'a> {
    grid: &'a Grid,
    march: HeightMarch,
}

/// Whether a photon starting over `p` enters through the pool's square (the only way in with walls).
fn inside(p: DVec2, size: f64) -> bool {
    (0.0..size).contains(&p.x) && (0.0..size).contains(&p.y)
}

/// The texel of wall map `m` at `(along, z)`: a point above the rest level (a crest's edge) in the
/// top row, as [`crate::reference`] puts it.
fn wall_texel(m: &crate::walls::WallMap, along: f64, z: f64) -> usize {
    let col = ((along / m.length * m.cols as f64).floor().max(0.0) as usize).min(m.cols - 1);
    let row = ((z / m.height * m.rows as f64).floor().max(0.0) as usize).min(m.rows - 1);
    row * m.cols + col
}

/// The jittered photon positions over a rectangle of lattice cells, by rows of squares.
#[derive(Clone, Copy)]
struct Strata {
    origin: DVec2,
    spacing: f64,
    nx: usize,
    ny: usize,
    seed: u64,
}

impl Strata {
    /// Over the lattice cells `cells`; with `walls`, over their part inside the square (light
    /// enters the pool only through it), where a side the lattice clamped (the cells run to its
    /// edge) reaches to the square's edge: the lattice is placed for the floor, shifted back along
    /// the sun, and can stop short of the square's far side.
    fn over(setup: &VolumesSetup, cells: CellRect, spacing: f64, seed: u64, walls: bool) -> Strata {
        let lat = &setup.lattice;
        let mut lo = lat.position(cells.i0, cells.j0);
        let mut hi = lat.position(cells.i1, cells.j1);
        if walls {
            let size = DVec2::splat(setup.size);
            if cells.j0 == 0 {
                lo.x = 0.0;
            }
            if cells.i0 == 0 {
                lo.y = 0.0;
            }
            if cells.j1 == lat.nx {
                hi.x = size.x;
            }
            if cells.i1 == lat.ny {
                hi.y = size.y;
            }
            lo = lo.clamp(DVec2::ZERO, size);
            hi = hi.clamp(DVec2::ZERO, size);
        }
        let side = (hi - lo).max(DVec2::ZERO);
        Strata {
            origin: lo,
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
    mesh_reference_with_progress(setup, input, surface, options, &|_, _| {})
}

/// [`mesh_reference`], calling `progress(done, total)` as rows of photons finish (the floor's,
/// then each object's): at a 512² map it traces millions of photons through the meshes.
pub fn mesh_reference_with_progress(
    setup: &VolumesSetup,
    input: &VolumesInput,
    surface: &dyn Surface,
    options: &MeshReferenceOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> MeshReference {
    let bvhs: Vec<MeshBvh> = input.objects.iter().map(|o| o.mesh.bvh()).collect();
    let nearest = |o: DVec3, d: DVec3, t_max: f64| {
        let meshes = input.objects.iter().map(|o| &o.mesh).zip(&bvhs);
        crate::mesh::nearest(meshes, o, d, t_max)
    };
    let absorb = |d: f64| (-setup.absorption * d).exp();
    let mut photons = 0u64;
    let object_strata: Vec<Strata> = setup
        .objects
        .iter()
        .take(if options.object_maps { usize::MAX } else { 0 })
        .enumerate()
        .map(|(k, o)| {
            Strata::over(
                setup,
                o.cells,
                options.object_spacing,
                options.seed + 1 + k as u64,
                options.walls,
            )
        })
        .collect();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let terrain = options.terrain.as_ref().map(|grid| Terrain {
        grid,
        march: HeightMarch::new(grid, setup.size),
    });

    // The floor, and the walls with them.
    let (w, h) = (setup.width, setup.height);
    let texel = DVec2::new(setup.size / w as f64, setup.size / h as f64);
    let strata = Strata::over(
        setup,
        setup.all_cells(),
        options.floor_spacing,
        options.seed,
        options.walls,
    );
    let area = options.floor_spacing * options.floor_spacing;
    photons += (strata.nx * strata.ny) as u64;
    let rows = strata.ny + object_strata.iter().map(|s| s.ny).sum::<usize>();
    let row_done = || {
        let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress(d, rows);
    };
    let mut wall_maps = options
        .walls
        .then(|| WallMaps::for_floor_map(w, h, setup.size, setup.depth));
    // One accumulator for the floor's texels, then each wall's.
    let mut offsets = [w * h; 5];
    if let Some(maps) = &wall_maps {
        for (k, m) in maps.maps.iter().enumerate() {
            offsets[k + 1] = offsets[k] + m.cols * m.rows;
        }
    }
    let total = offsets[4];
    let marched = terrain.as_ref();
    // The photons of row `i` of `strata` that enter the water over the traced square, each with
    // where it ends and how far it travels before it does.
    let row = move |strata: Strata, i: usize, area: f64| {
        (0..strata.nx).filter_map(move |j| {
            let p = strata.point(i, j);
            if options.walls && !inside(p, setup.size) {
                return None;
            }
            let ph = photon(setup, surface, p, area)?;
            let (end, d) = end_of(setup, &ph, options.walls, marched);
            Some((ph, end, d))
        })
    };
    let acc = par_sum(0..strata.ny, total, |acc, i| {
        for (ph, end, d) in row(strata, i, area) {
            if nearest(ph.start, ph.dir, d).is_some() {
                continue;
            }
            let k = match end {
                End::Floor(q) => {
                    let q = q / texel;
                    let (jj, ii) = (q.x.floor(), q.y.floor());
                    if !(jj >= 0.0 && ii >= 0.0 && (jj as usize) < w && (ii as usize) < h) {
                        continue;
                    }
                    ii as usize * w + jj as usize
                }
                End::Wall(wall, along, z) => {
                    let m = wall_maps.as_ref().expect("walls on").get(wall);
                    offsets[wall.index()] + wall_texel(m, along, z)
                }
            };
            acc[k] += absorb(d) * ph.flux;
        }
        row_done();
    });
    let irradiance = |e: &DVec3, ta: f64| (*e / ta).as_vec3().to_array();
    let mut floor = CausticsMap::new(w, h, setup.size);
    let ta = texel.x * texel.y;
    for (k, (t, e)) in floor.texels.iter_mut().zip(&acc).enumerate() {
        // On a terrain the flux over a texel spreads over its tilted area.
        let tilt = terrain.as_ref().map_or(1.0, |tr| {
            let c = (DVec2::new((k % w) as f64, (k / w) as f64) + 0.5) * texel;
            let g = tr.grid.sample(c, setup.size, Edge::Clamp).1;
            (1.0 + g.length_squared()).sqrt()
        });
        *t = irradiance(e, ta * tilt);
    }
    if let Some(maps) = &mut wall_maps {
        for (k, m) in maps.maps.iter_mut().enumerate() {
            let ta = m.texel_area();
            for (t, e) in m.texels.iter_mut().zip(&acc[offsets[k]..offsets[k + 1]]) {
                *t = irradiance(e, ta);
            }
        }
    }

    // The objects, each from the photons of its own footprint.
    let mut objects = Vec::new();
    for (k, o) in setup.objects.iter().enumerate().take(object_strata.len()) {
        let view = &o.view;
        let res = view.res;
        let strata = &object_strata[k];
        let area = options.object_spacing * options.object_spacing;
        photons += (strata.nx * strata.ny) as u64;
        let mesh = &input.objects[k].mesh;
        let scale = (view.extent()).max_element();
        let acc = par_sum(0..strata.ny, res * res, |acc, i| {
            for (ph, _, limit) in row(*strata, i, area) {
                let Some((hit, t, n)) = nearest(ph.start, ph.dir, limit) else {
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
            row_done();
        });
        let tex = view.texel();
        let ta = tex.x * tex.y;
        objects.push(acc.iter().map(|e| (*e / ta).as_vec3().to_array()).collect());
    }
    MeshReference {
        objects,
        floor,
        walls: wall_maps,
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
