//! The physically based reference: forward, flux-conserving caustics from a height-field water surface
//! onto the floor (plane or terrain). Every technique is judged against it.
//!
//! # Method
//! The surface over the traced domain is cut into a fine triangulation (two triangles per cell of a
//! lattice `cells_per_texel` times finer than the map). At every vertex the sunlight (unit direction
//! `L`, `L.z < 0`) is refracted with the exact Snell law through the true normal of the surface, and
//! the ray is followed to the floor. Each triangle carries the flux that crosses it,
//!
//! `Φ = E_h · (−L · (e₁ × e₂)) / (2 |L_z|)`,
//!
//! i.e. the sun's irradiance on a horizontal plane `E_h` times the triangle's area projected along
//! `L` onto that plane, times the mean over its vertices of the Fresnel transmittance `T(θi)` and of the
//! Beer-Lambert attenuation `exp(−K d)` along the refracted path of length `d`. The floor triangle
//! spanned by the three hit points receives that flux uniformly, and it is deposited into the map's
//! texels by the exact area of overlap between the triangle and each texel (polygon clipping), so no
//! flux is lost or invented: the map integrates to the transmitted flux exactly.
//!
//! Dividing by the texel area and by `E_h T(θ₀)` (a flat surface, `cos θ₀ = −L_z`) gives the relative
//! irradiance: exactly 1 under flat water. On terrain the same flux spreads over the true, tilted area,
//! so each texel is further multiplied by `cos α = 1 / sqrt(1 + |∇f|²)` of the floor.
//!
//! As the triangulation is refined the piecewise-linear ray map converges to the true one, and so
//! does the deposited irradiance (away from the caustic singularities, where it converges in the
//! mean). Triangles facing away from the sun receive nothing (the surface shadows itself).
//!
//! # Walls
//! With the pool's walls as receivers ([`Floor::walls`]) the traced domain is the water
//! square itself (light enters the pool only through its surface, and nothing wraps), and each
//! vertex's ray stops at whichever it meets first: the floor, or a wall plane (x = 0, x = size,
//! y = 0, y = size). A triangle whose three rays meet the same receiver is deposited there as on
//! the floor, in that receiver's plane (`(along, z)` on a wall). A triangle whose rays meet
//! different receivers is split between them: for each receiver its rays met, the triangle's
//! piecewise-linear image on that receiver's plane (every vertex's ray carried to the plane) is
//! clipped to the receiver (the floor's square; a wall from the floor up), and the part inside,
//! over the whole image, is the share of the triangle's flux that meets that receiver first (for
//! straight rays from inside a convex box these parts partition the triangle; the shares are
//! normalised to sum to one, so nothing is lost to the linear approximation). Under flat water
//! every ray map is affine and the split is exact. Light meeting a wall above the rest water level
//! (a wave crest's own edge) goes to its top row. A wall texel's value is its flux over its area
//! in the floor's unit ([`crate::walls`]).

use glam::{DVec2, DVec3};

use crate::error::{Error, Result};
use crate::map::CausticsMap;
use crate::optics::{air_transmittance, height_field_normal, refract};
use crate::parallel::prelude::*;
use crate::receivers::HeightMarch;
use crate::scene::{Floor, Scene, Water};
use crate::walls::{Wall, WallMaps};
use crate::water::Surface;

use crate::techniques::describe::{Descriptor, Receiver};
use crate::techniques::{Input, Job, JobOutput};

/// The ground truth as registered: this module's flux tracing for water over the floor and
/// walls; with diffuse objects under the water, the photon reference with mesh receivers
/// (`volumes::reference`), so their shadows are in it; for glass objects without water, paper 4's
/// photon tracer against the exact geometry.
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "reference",
    table: "reference",
    paper: "-",
    summary: "physically based forward flux tracing: exact Snell + Fresnel at a fine triangulation of the surface, exact area deposit (CPU, the ground truth)",
    docs: "docs/reference.md",
    input: Input::Water,
    receivers: &[Receiver::Floor, Receiver::Walls],
    params: &[],
    fixed: &[],
    point_light: false,
    buffers: &[],
    draw_buffer: crate::techniques::buffers::no_buffers,
    reference: true,
    validate: |_| Ok(()),
    own_defaults: toml::Table::new,
    cpu: run_cpu,
};

/// Photons per texel side of the mesh-receiver reference, per cell per texel of the floor
/// reference: 4 (8² photons per texel at the viewer's 2 cells), stratified, so its noise is a few
/// per cent per texel where the floor reference's triangulation is exact.
const MESH_REFERENCE_PHOTONS: u32 = 4;

/// Photons per side of the light rectangle of one glass generator, per cell per texel, in the
/// glass reference: 128² (2 cells per texel, the viewer's default, gives 256² per glass object,
/// about two seconds for the `glass` scene on two cores).
const GLASS_REFERENCE_PHOTONS: u32 = 128;

fn run_cpu(
    job: &Job,
    _table: &toml::Table,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<JobOutput> {
    use crate::techniques::{caustic_triangles as ct, volumes};
    let scene = job.scene;
    if scene.water.is_none() {
        // A scene of glass objects: paper 4's photon tracer against the exact geometry, one
        // generator at a time as the technique runs.
        let generators = ct::glass_generators(scene)?;
        let options = ct::reference::ReferenceOptions {
            photons: GLASS_REFERENCE_PHOTONS * job.cells_per_texel.clamp(1, 16),
            ..Default::default()
        };
        let mut total: Option<CausticsMap> = None;
        for k in 0..generators {
            let gs = ct::GlassScene::from_scene(scene, k)?;
            let map = ct::reference::reference(&gs, &options).map;
            total = Some(match total {
                None => map,
                Some(t) => t.added(&map),
            });
            progress(k + 1, generators);
        }
        return Ok(JobOutput::floor(
            total.expect("one glass object at least"),
            None,
        ));
    }
    job.with_surface(DESCRIPTOR.name, |water, surface| {
        if !scene.objects.is_empty() {
            let input = volumes::VolumesInput::from_scene(scene)?;
            let setup = volumes::VolumesSetup::new(&volumes::VolumesParams::default(), &input)?;
            let options = volumes::reference::MeshReferenceOptions {
                walls: scene.floor.walls,
                object_maps: false,
                terrain: scene.floor.terrain.clone(),
                ..volumes::reference::MeshReferenceOptions::per_texel(
                    &setup,
                    (MESH_REFERENCE_PHOTONS * job.cells_per_texel.clamp(1, 8)) as f64,
                )
            };
            let r = volumes::reference::mesh_reference_with_progress(
                &setup, &input, surface, &options, progress,
            );
            return Ok(JobOutput::floor(r.floor, r.walls));
        }
        let (width, height) = job.size();
        let input = ReferenceInput {
            surface,
            water,
            floor: &scene.floor,
            light: job.light(),
            width,
            height,
        };
        let options = ReferenceOptions {
            cells_per_texel: job.cells_per_texel,
            ..Default::default()
        };
        let out = reference_with_walls(&input, &options, progress)?;
        Ok(JobOutput::floor(out.floor, out.walls))
    })
}

/// How finely, and with which physics, the reference traces (default: 4 cells per texel, Fresnel
/// and absorption on).
#[derive(Clone, Debug)]
pub struct ReferenceOptions {
    /// Triangulation cells per map texel along each axis.
    pub cells_per_texel: u32,
    /// Include the Fresnel transmittance (relative to that of flat water).
    pub fresnel: bool,
    /// Include the water's absorption `exp(−K d)`.
    pub absorption: bool,
}

impl Default for ReferenceOptions {
    fn default() -> Self {
        ReferenceOptions {
            cells_per_texel: 4,
            fresnel: true,
            absorption: true,
        }
    }
}

/// What the reference needs to know, independent of how the scene was described.
pub struct ReferenceInput<'a> {
    /// The water surface at the instant traced: heights above the rest level and their gradient.
    pub surface: &'a dyn Surface,
    /// The water's square, depth, index of refraction, wrap and absorption (its source is not read:
    /// `surface` stands for it).
    pub water: &'a Water,
    /// The receiver: flat or terrain, with or without the pool's walls.
    pub floor: &'a Floor,
    /// Unit direction the sunlight travels, `z < 0`.
    pub light: DVec3,
    /// Floor map texels along x.
    pub width: usize,
    /// Floor map texels along y.
    pub height: usize,
}

impl<'a> ReferenceInput<'a> {
    /// The scene's water, floor, sun and caustics map size, with `surface` standing for its water
    /// at the instant traced; fails for a scene without water.
    pub fn from_scene(scene: &'a Scene, surface: &'a dyn Surface) -> Result<Self> {
        let water = scene.water.as_ref().ok_or_else(|| {
            Error::InvalidParameter(format!(
                "scene `{}` has no water: the reference computes caustics from a water surface",
                scene.name
            ))
        })?;
        Ok(ReferenceInput {
            surface,
            water,
            floor: &scene.floor,
            light: scene.light.direction,
            width: scene.caustics.width as usize,
            height: scene.caustics.height as usize,
        })
    }
}

/// One refracted vertex: where its ray meets the floor, and the per-channel weight it carries
/// (Fresnel transmittance times absorption). `None` where no light reaches the floor from it.
#[derive(Clone, Copy)]
struct Hit {
    surface: DVec3,
    /// The point its receiver is met at, in that receiver's plane: `(x, y)` on the floor,
    /// `(along, z)` on a wall.
    floor: DVec2,
    weight: DVec3,
    lit: bool,
    /// The receiver met first: [`FLOOR`] or a wall's `index() + 1`; always the floor without walls.
    receiver: u8,
    /// The refracted direction, to meet the other receivers' planes (with walls only).
    dir: DVec3,
}

/// [`Hit::receiver`] of the floor.
const FLOOR: u8 = 0;

/// The most memory the reference's per-thread accumulators may take.
pub const MAX_ACCUMULATOR_BYTES: u64 = 8 << 30;

/// What the reference lights: the floor map, and the walls' maps when the floor has walls.
#[derive(Clone, Debug)]
pub struct ReferenceOutput {
    /// The floor's caustics map: relative irradiance, 1 under flat water.
    pub floor: CausticsMap,
    /// `Some` when [`Floor::walls`]: light that meets a wall is here, not on the floor.
    pub walls: Option<WallMaps>,
    /// The flux that left the water surface downwards (per channel, Fresnel and absorption
    /// included as in the maps), in the floor map's unit times area: what floor and walls hold.
    pub transmitted: DVec3,
}

/// Compute the reference caustics map of the floor (see [`reference_with_walls`] for the walls).
/// `progress(done, total)` is called as bands of the triangulation finish.
pub fn reference(
    input: &ReferenceInput,
    options: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<CausticsMap> {
    reference_with_walls(input, options, progress).map(|o| o.floor)
}

/// The reference with everything it lights: the floor map and, when [`Floor::walls`], the four
/// walls' maps (laid out as [`WallMaps::for_floor_map`] says).
pub fn reference_with_walls(
    input: &ReferenceInput,
    options: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<ReferenceOutput> {
    let ReferenceInput {
        surface,
        water,
        floor,
        light,
        width,
        height,
    } = *input;
    let light = crate::techniques::check_inputs(width, height, light)?;
    if options.cells_per_texel == 0 {
        return Err(Error::InvalidParameter(
            "reference cells_per_texel must be at least 1".into(),
        ));
    }
    let size = water.size;
    let walls = floor.walls;
    if walls && floor.terrain.is_some() {
        return Err(Error::InvalidParameter(
            "walls receive light only around a flat pool floor, not over a terrain".into(),
        ));
    }
    // Walls close the pool: no light wraps round, whatever the water's heights do.
    let wrap = water.wrap && !walls;
    let eta = 1.0 / water.ior;
    let t_flat = air_transmittance(options.fresnel, -light.z, water.ior);
    let flat_dir = refract(light, DVec3::Z, eta).expect("air to water never reflects totally");

    // The traced domain: one period when the surface wraps; otherwise the square shifted back by the
    // mean horizontal travel of the refracted light and widened by a margin for the waves' deflection.
    let cpt = options.cells_per_texel as usize;
    let texel = DVec2::new(size / width as f64, size / height as f64);
    let (origin, nx, ny) = if wrap || walls {
        (DVec2::ZERO, width * cpt, height * cpt)
    } else {
        let travel = -flat_dir.truncate() * (water.depth / -flat_dir.z);
        let margin = 0.3 * water.depth + 2.0 * texel.max_element();
        let lo = travel - DVec2::splat(margin);
        let n = |extent: f64, t: f64| ((extent + 2.0 * margin) / t * cpt as f64).ceil() as usize;
        (lo, n(size, texel.x), n(size, texel.y))
    };
    let cell = if wrap || walls {
        DVec2::new(size / nx as f64, size / ny as f64)
    } else {
        texel / cpt as f64
    };
    let terrain_march = floor.terrain.as_ref().map(|g| HeightMarch::new(g, size));
    let terrain_height = |p: DVec2| floor.height_gradient(p, size).0;

    let vertex = |a: usize, b: usize| -> Hit {
        let p = origin + DVec2::new(b as f64, a as f64) * cell;
        let (h, grad) = surface.height_gradient(p);
        let s = DVec3::new(p.x, p.y, water.depth + h);
        let n = height_field_normal(grad);
        let cos_i = -light.dot(n);
        let unlit = Hit {
            surface: s,
            floor: p,
            weight: DVec3::ZERO,
            lit: false,
            receiver: FLOOR,
            dir: DVec3::ZERO,
        };
        if cos_i <= 0.0 {
            return unlit;
        }
        let Some(t) = refract(light, n, eta) else {
            return unlit;
        };
        let mut receiver = FLOOR;
        let (floor_point, d) = match &terrain_march {
            None if walls => {
                let d_floor = if t.z < 0.0 { s.z / -t.z } else { f64::INFINITY };
                match Wall::exit(s.truncate(), t.truncate(), size) {
                    Some((w, u)) if u < d_floor => {
                        let hit = s + t * u;
                        receiver = w.index() as u8 + 1;
                        (DVec2::new(w.along(hit), hit.z), u)
                    }
                    _ if d_floor.is_finite() => ((s + t * d_floor).truncate(), d_floor),
                    _ => return unlit,
                }
            }
            None => {
                let d = s.z / -t.z;
                ((s + t * d).truncate(), d)
            }
            Some(m) => match m.intersect(s, t, &terrain_height) {
                Some(u) => ((s + t * u).truncate(), u),
                None => return unlit,
            },
        };
        let fresnel = air_transmittance(options.fresnel, cos_i, water.ior) / t_flat;
        let absorb = if options.absorption {
            (-water.absorption * d).exp()
        } else {
            DVec3::ONE
        };
        Hit {
            surface: s,
            floor: floor_point,
            weight: fresnel * absorb,
            lit: true,
            receiver,
            dir: t,
        }
    };

    // Bands of cell rows; each band recomputes its top vertex row (cheaper than sharing).
    let band = 8usize;
    let bands = ny.div_ceil(band);
    let done = std::sync::atomic::AtomicUsize::new(0);
    let deposit = Deposit {
        width,
        height,
        texel,
        wrap,
    };
    let light_z = -light.z;
    let wall_maps = walls.then(|| WallMaps::for_floor_map(width, height, size, water.depth));
    let receivers = wall_maps
        .as_ref()
        .map(|m| PoolReceivers::new(m, width, height, texel, size));
    let acc_len = width * height + receivers.as_ref().map_or(0, |n| n.wall_texels);
    // One accumulator per worker thread (bands interleaved between them) and one for the sum, fewer
    // workers where memory would not hold them, and a clear refusal where not even two fit.
    let map_bytes = acc_len as u64 * std::mem::size_of::<DVec3>() as u64;
    let by_memory = (MAX_ACCUMULATOR_BYTES / map_bytes).saturating_sub(1) as usize;
    if by_memory == 0 {
        return Err(Error::InvalidParameter(format!(
            "a {width} x {height} reference map needs {:.1} GiB for two accumulators (at most {} \
             GiB): choose a smaller resolution",
            2.0 * map_bytes as f64 / (1u64 << 30) as f64,
            MAX_ACCUMULATOR_BYTES >> 30
        )));
    }
    let workers = crate::parallel::workers()
        .min(by_memory)
        .clamp(1, bands.max(1));
    let (acc, transmitted) = (0..workers)
        .into_par_iter()
        .map(|worker| {
            let mut acc = vec![DVec3::ZERO; acc_len];
            let mut transmitted = DVec3::ZERO;
            for k in (worker..bands).step_by(workers) {
                let a0 = k * band;
                let a1 = ((k + 1) * band).min(ny);
                let mut prev: Vec<Hit> = (0..=nx).map(|b| vertex(a0, b)).collect();
                let mut next = Vec::with_capacity(nx + 1);
                for a in a0..a1 {
                    next.clear();
                    next.extend((0..=nx).map(|b| vertex(a + 1, b)));
                    for b in 0..nx {
                        let (v00, v10, v01, v11) = (prev[b], prev[b + 1], next[b], next[b + 1]);
                        // Diagonals alternate in a checkerboard ("union jack"), so the
                        // triangulation is its own mirror image in x and in y and adds no bias
                        // of its own to a symmetric surface.
                        let tris = if (a + b) % 2 == 0 {
                            [[v00, v10, v11], [v00, v11, v01]]
                        } else {
                            [[v00, v10, v01], [v10, v11, v01]]
                        };
                        for tri in tris {
                            if !(tri[0].lit && tri[1].lit && tri[2].lit) {
                                continue;
                            }
                            let e1 = tri[1].surface - tri[0].surface;
                            let e2 = tri[2].surface - tri[0].surface;
                            // Flux over E_h: the area the sun sees, projected onto the horizontal.
                            let flux = -light.dot(e1.cross(e2)) / (2.0 * light_z);
                            if flux <= 0.0 {
                                continue;
                            }
                            let w = (tri[0].weight + tri[1].weight + tri[2].weight) / 3.0;
                            transmitted += flux * w;
                            match &receivers {
                                Some(r) => r.triangle(&mut acc, &tri, flux * w),
                                None => deposit.triangle(
                                    &mut acc,
                                    [tri[0].floor, tri[1].floor, tri[2].floor],
                                    flux * w,
                                ),
                            }
                        }
                    }
                    std::mem::swap(&mut prev, &mut next);
                }
                let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(d, bands);
            }
            (acc, transmitted)
        })
        .reduce(
            || (vec![DVec3::ZERO; acc_len], DVec3::ZERO),
            |(mut a, ta), (b, tb)| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x += *y);
                (a, ta + tb)
            },
        );

    let texel_area = texel.x * texel.y;
    let mut map = CausticsMap::new(width, height, size);
    for (i, row) in map.texels.chunks_mut(width).enumerate() {
        for (j, t) in row.iter_mut().enumerate() {
            let mut e = acc[i * width + j] / texel_area;
            if floor.terrain.is_some() {
                let c = (DVec2::new(j as f64, i as f64) + 0.5) * texel;
                let g = floor.height_gradient(c, size).1;
                e /= (1.0 + g.length_squared()).sqrt();
            }
            *t = [e.x as f32, e.y as f32, e.z as f32];
        }
    }
    let walls = match (wall_maps, &receivers) {
        (Some(mut maps), Some(receivers)) => {
            for w in Wall::ALL {
                let m = maps.get_mut(w);
                let area = m.texel_area();
                let base = receivers.offsets[w.index()];
                for (k, t) in m.texels.iter_mut().enumerate() {
                    let e = acc[base + k] / area;
                    *t = [e.x as f32, e.y as f32, e.z as f32];
                }
            }
            Some(maps)
        }
        _ => None,
    };
    Ok(ReferenceOutput {
        floor: map,
        walls,
        transmitted,
    })
}

/// Exact area deposit of the triangles of the pool's receivers (floor and walls) into their
/// texels, all in one accumulator: the floor's `width x height` texels, then each wall's (in
/// [`Wall::ALL`]'s order).
struct PoolReceivers {
    width: usize,
    height: usize,
    texel: DVec2,
    size: f64,
    /// Wall texel height.
    hz: f64,
    rows: usize,
    cols: [usize; 4],
    offsets: [usize; 4],
    wall_texels: usize,
}

impl PoolReceivers {
    fn new(maps: &WallMaps, width: usize, height: usize, texel: DVec2, size: f64) -> Self {
        let mut offsets = [0; 4];
        let mut next = width * height;
        for w in Wall::ALL {
            offsets[w.index()] = next;
            next += maps.get(w).texels.len();
        }
        let m = maps.get(Wall::X0);
        PoolReceivers {
            width,
            height,
            texel,
            size,
            hz: m.height / m.rows as f64,
            rows: m.rows,
            cols: Wall::ALL.map(|w| maps.get(w).cols),
            offsets,
            wall_texels: next - width * height,
        }
    }

    fn triangle(&self, acc: &mut [DVec3], tri: &[Hit; 3], flux: DVec3) {
        let r = tri[0].receiver;
        if tri.iter().all(|h| h.receiver == r) {
            self.deposit(acc, r, &[tri[0].floor, tri[1].floor, tri[2].floor], flux);
            return;
        }
        // The receivers its rays meet, each with the triangle's image on its plane clipped to it.
        let mut parts: [(u8, [DVec2; 16], usize, f64); 3] = [(0, [DVec2::ZERO; 16], 0, 0.0); 3];
        let mut count = 0;
        let mut total = 0.0;
        let top = tri.iter().fold(0.0f64, |m, h| m.max(h.surface.z));
        for h in tri {
            let r = h.receiver;
            if parts[..count].iter().any(|p| p.0 == r) {
                continue;
            }
            let image = tri.map(|v| self.on_plane(r, &v));
            let whole = polygon_area(&image);
            // Rays from the surface meet a wall below where they started.
            let y_max = if r == FLOOR { self.size } else { top };
            let (mut poly, mut xs, mut tmp) =
                ([DVec2::ZERO; 16], [DVec2::ZERO; 16], [DVec2::ZERO; 16]);
            let n = match clip_slab(&image, &mut xs, 0, 0.0, self.size, &mut tmp) {
                m if whole > 0.0 && m >= 3 => {
                    clip_slab(&xs[..m], &mut poly, 1, 0.0, y_max, &mut tmp)
                }
                _ => 0,
            };
            let share = if n >= 3 {
                polygon_area(&poly[..n]) / whole
            } else {
                0.0
            };
            parts[count] = (r, poly, n, share);
            total += share;
            count += 1;
        }
        if total <= 0.0 {
            // Degenerate images: all of it where the first ray lands.
            let h = &tri[0];
            self.deposit(acc, h.receiver, &[h.floor; 3], flux);
            return;
        }
        for (r, poly, n, share) in &parts[..count] {
            if *share > 0.0 {
                self.deposit(acc, *r, &poly[..*n], flux * (share / total));
            }
        }
    }

    /// Where the ray of `h` meets receiver `r`'s plane, in that plane's coordinates (its own hit
    /// when `r` is the receiver it met); far away but finite for a ray parallel to the plane.
    fn on_plane(&self, r: u8, h: &Hit) -> DVec2 {
        if r == h.receiver {
            return h.floor;
        }
        let (s, t) = (h.surface, h.dir);
        let far = 1e6 * self.size;
        let param = |gap: f64, rate: f64| {
            let u = gap / rate;
            if u.is_finite() {
                u.clamp(-far, far)
            } else {
                far
            }
        };
        if r == FLOOR {
            let u = param(s.z, -t.z);
            return (s + t * u).truncate();
        }
        let w = Wall::ALL[(r - 1) as usize];
        let u = match w {
            Wall::X0 => param(-s.x, t.x),
            Wall::X1 => param(self.size - s.x, t.x),
            Wall::Y0 => param(-s.y, t.y),
            Wall::Y1 => param(self.size - s.y, t.y),
        };
        let p = s + t * u;
        DVec2::new(w.along(p), p.z)
    }

    /// Spread `flux` over `poly` (in receiver `r`'s plane) into that receiver's texels.
    fn deposit(&self, acc: &mut [DVec3], r: u8, poly: &[DVec2], flux: DVec3) {
        if r == FLOOR {
            let (w, h) = (self.width as i64, self.height as i64);
            let mut q = [DVec2::ZERO; 16];
            for (q, v) in q.iter_mut().zip(poly) {
                *q = *v / self.texel;
            }
            spread(&q[..poly.len()], flux, &mut |i, j, v| {
                acc[(i.clamp(0, h - 1) * w + j.clamp(0, w - 1)) as usize] += v;
            });
            return;
        }
        let k = (r - 1) as usize;
        let (cols, rows) = (self.cols[k] as i64, self.rows as i64);
        let along = self.size / self.cols[k] as f64;
        let base = self.offsets[k];
        let mut q = [DVec2::ZERO; 16];
        for (q, v) in q.iter_mut().zip(poly) {
            *q = DVec2::new(v.x / along, v.y / self.hz);
        }
        // Rows past the top are light meeting the wall above the rest level: its top row.
        spread(&q[..poly.len()], flux, &mut |i, j, v| {
            acc[base + (i.clamp(0, rows - 1) * cols + j.clamp(0, cols - 1)) as usize] += v;
        });
    }
}

/// Spread `flux` uniformly over the convex polygon `q` (in texel units) and hand each texel
/// `(row, col)` its share, the polygon's area inside it over the whole.
fn spread(q: &[DVec2], flux: DVec3, add: &mut dyn FnMut(i64, i64, DVec3)) {
    let lo = q.iter().fold(DVec2::INFINITY, |m, v| m.min(*v));
    let hi = q.iter().fold(DVec2::NEG_INFINITY, |m, v| m.max(*v));
    let (j0, i0) = (lo.x.floor() as i64, lo.y.floor() as i64);
    let (j1, i1) = (hi.x.floor() as i64, hi.y.floor() as i64);
    let area = polygon_area(q);
    if (j0 == j1 && i0 == i1) || area < 0.5e-12 {
        let c = q.iter().copied().sum::<DVec2>() / q.len() as f64;
        add(c.y.floor() as i64, c.x.floor() as i64, flux);
        return;
    }
    let inv = 1.0 / area;
    let mut row = [DVec2::ZERO; 16];
    let mut cellp = [DVec2::ZERO; 16];
    let mut tmp = [DVec2::ZERO; 16];
    for i in i0..=i1 {
        let n = clip_slab(q, &mut row, 1, i as f64, i as f64 + 1.0, &mut tmp);
        if n < 3 {
            continue;
        }
        let rlo = row[..n].iter().fold(f64::INFINITY, |m, v| m.min(v.x));
        let rhi = row[..n].iter().fold(f64::NEG_INFINITY, |m, v| m.max(v.x));
        for j in (rlo.floor() as i64)..=(rhi.floor() as i64).min(j1) {
            let m = clip_slab(&row[..n], &mut cellp, 0, j as f64, j as f64 + 1.0, &mut tmp);
            if m < 3 {
                continue;
            }
            let a = polygon_area(&cellp[..m]);
            if a > 0.0 {
                add(i, j, flux * (a * inv));
            }
        }
    }
}

/// Exact area deposit of floor triangles into the texel grid.
struct Deposit {
    width: usize,
    height: usize,
    texel: DVec2,
    wrap: bool,
}

impl Deposit {
    /// Spread `flux` (per channel) uniformly over the triangle `p` (world xy) and add each texel's share,
    /// the triangle's area inside the texel over its whole area.
    fn triangle(&self, acc: &mut [DVec3], p: [DVec2; 3], flux: DVec3) {
        spread(&p.map(|v| v / self.texel), flux, &mut |i, j, v| {
            self.add(acc, i, j, v)
        });
    }

    #[inline]
    fn add(&self, acc: &mut [DVec3], i: i64, j: i64, v: DVec3) {
        let (w, h) = (self.width as i64, self.height as i64);
        let (i, j) = if self.wrap {
            (i.rem_euclid(h), j.rem_euclid(w))
        } else if i < 0 || j < 0 || i >= h || j >= w {
            return;
        } else {
            (i, j)
        };
        acc[(i * w + j) as usize] += v;
    }
}

/// Sutherland-Hodgman clip of a convex polygon to `lo <= v[axis] <= hi`; returns the vertex count.
fn clip_slab(
    poly: &[DVec2],
    out: &mut [DVec2],
    axis: usize,
    lo: f64,
    hi: f64,
    tmp: &mut [DVec2],
) -> usize {
    let n = clip_half(poly, tmp, |v| v[axis] - lo);
    if n < 3 {
        return 0;
    }
    let tmp_copy: [DVec2; 16] = std::array::from_fn(|k| if k < n { tmp[k] } else { DVec2::ZERO });
    clip_half(&tmp_copy[..n], out, |v| hi - v[axis])
}

/// Keep the part of `poly` where `dist >= 0`.
fn clip_half(poly: &[DVec2], out: &mut [DVec2], dist: impl Fn(DVec2) -> f64) -> usize {
    let mut n = 0;
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        let (da, db) = (dist(a), dist(b));
        if da >= 0.0 {
            out[n] = a;
            n += 1;
        }
        if (da >= 0.0) != (db >= 0.0) {
            out[n] = a + (b - a) * (da / (da - db));
            n += 1;
        }
    }
    n
}

fn polygon_area(poly: &[DVec2]) -> f64 {
    let mut s = 0.0;
    for k in 0..poly.len() {
        s += poly[k].perp_dot(poly[(k + 1) % poly.len()]);
    }
    0.5 * s.abs()
}
