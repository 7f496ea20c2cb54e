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

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::map::CausticsMap;
use crate::optics::{fresnel_transmittance, height_field_normal, refract};
use crate::scene::{Floor, Scene, Water};
use crate::water::Surface;

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
    pub surface: &'a dyn Surface,
    pub water: &'a Water,
    pub floor: &'a Floor,
    /// Unit direction the sunlight travels, `z < 0`.
    pub light: DVec3,
    pub width: usize,
    pub height: usize,
}

impl<'a> ReferenceInput<'a> {
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
    floor: DVec2,
    weight: DVec3,
    lit: bool,
}

/// The most memory the reference's per-thread accumulators may take.
pub const MAX_ACCUMULATOR_BYTES: u64 = 8 << 30;

/// Compute the reference caustics map. `progress(done, total)` is called as bands of the
/// triangulation finish.
pub fn reference(
    input: &ReferenceInput,
    options: &ReferenceOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<CausticsMap> {
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
    let wrap = water.wrap;
    let eta = 1.0 / water.ior;
    let t_flat = if options.fresnel {
        fresnel_transmittance(-light.z, 1.0, water.ior)
    } else {
        1.0
    };
    let flat_dir = refract(light, DVec3::Z, eta).expect("air to water never reflects totally");

    // The traced domain: one period when the surface wraps; otherwise the square shifted back by the
    // mean horizontal travel of the refracted light and widened by a margin for the waves' deflection.
    let cpt = options.cells_per_texel as usize;
    let texel = DVec2::new(size / width as f64, size / height as f64);
    let (origin, nx, ny) = if wrap {
        (DVec2::ZERO, width * cpt, height * cpt)
    } else {
        let travel = -flat_dir.truncate() * (water.depth / -flat_dir.z);
        let margin = 0.3 * water.depth + 2.0 * texel.max_element();
        let lo = travel - DVec2::splat(margin);
        let n = |extent: f64, t: f64| ((extent + 2.0 * margin) / t * cpt as f64).ceil() as usize;
        (lo, n(size, texel.x), n(size, texel.y))
    };
    let cell = if wrap {
        DVec2::new(size / nx as f64, size / ny as f64)
    } else {
        texel / cpt as f64
    };
    let terrain_march = floor
        .terrain
        .as_ref()
        .map(|g| TerrainMarch::new(floor, g, size));

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
        };
        if cos_i <= 0.0 {
            return unlit;
        }
        let Some(t) = refract(light, n, eta) else {
            return unlit;
        };
        let (floor_point, d) = match &terrain_march {
            None => {
                let d = s.z / -t.z;
                ((s + t * d).truncate(), d)
            }
            Some(m) => match m.intersect(s, t) {
                Some(hit) => hit,
                None => return unlit,
            },
        };
        let fresnel = if options.fresnel {
            fresnel_transmittance(cos_i, 1.0, water.ior) / t_flat
        } else {
            1.0
        };
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
    // One accumulator per worker thread (bands interleaved between them) and one for the sum, fewer
    // workers where memory would not hold them, and a clear refusal where not even two fit.
    let map_bytes = (width * height) as u64 * std::mem::size_of::<DVec3>() as u64;
    let by_memory = (MAX_ACCUMULATOR_BYTES / map_bytes).saturating_sub(1) as usize;
    if by_memory == 0 {
        return Err(Error::InvalidParameter(format!(
            "a {width} x {height} reference map needs {:.1} GiB for two accumulators (at most {} \
             GiB): choose a smaller resolution",
            2.0 * map_bytes as f64 / (1u64 << 30) as f64,
            MAX_ACCUMULATOR_BYTES >> 30
        )));
    }
    let workers = rayon::current_num_threads()
        .min(by_memory)
        .clamp(1, bands.max(1));
    let acc = (0..workers)
        .into_par_iter()
        .map(|worker| {
            let mut acc = vec![DVec3::ZERO; width * height];
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
                            deposit.triangle(
                                &mut acc,
                                [tri[0].floor, tri[1].floor, tri[2].floor],
                                flux * w,
                            );
                        }
                    }
                    std::mem::swap(&mut prev, &mut next);
                }
                let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(d, bands);
            }
            acc
        })
        .reduce(
            || vec![DVec3::ZERO; width * height],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x += *y);
                a
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
    Ok(map)
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
        let q = p.map(|v| v / self.texel);
        let area2 = (q[1] - q[0]).perp_dot(q[2] - q[0]).abs();
        let lo = q[0].min(q[1]).min(q[2]);
        let hi = q[0].max(q[1]).max(q[2]);
        let (j0, i0) = (lo.x.floor() as i64, lo.y.floor() as i64);
        let (j1, i1) = (hi.x.floor() as i64, hi.y.floor() as i64);
        // Inside one texel, or so thin that its area is lost in rounding: all of it goes to one texel.
        if (j0 == j1 && i0 == i1) || area2 < 1e-12 {
            let c = (q[0] + q[1] + q[2]) / 3.0;
            self.add(acc, c.y.floor() as i64, c.x.floor() as i64, flux);
            return;
        }
        let inv = 1.0 / (0.5 * area2);
        let mut row = [DVec2::ZERO; 8];
        let mut cellp = [DVec2::ZERO; 10];
        let mut tmp = [DVec2::ZERO; 10];
        for i in i0..=i1 {
            let n = clip_slab(&q, &mut row, 1, i as f64, i as f64 + 1.0, &mut tmp);
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
                    self.add(acc, i, j, flux * (a * inv));
                }
            }
        }
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
    let tmp_copy: [DVec2; 10] = std::array::from_fn(|k| if k < n { tmp[k] } else { DVec2::ZERO });
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

/// Ray against the terrain height field: conservative steps bounded by the terrain's steepest slope,
/// then bisection on the sign change.
struct TerrainMarch<'a> {
    floor: &'a Floor,
    size: f64,
    max_slope: f64,
}

impl<'a> TerrainMarch<'a> {
    fn new(floor: &'a Floor, g: &crate::grid::Grid, size: f64) -> Self {
        let (dx, dy) = (size / g.cols as f64, size / g.rows as f64);
        let mut max_slope: f64 = 0.0;
        for i in 0..g.rows {
            for j in 0..g.cols {
                let v = g.at(i, j) as f64;
                if j + 1 < g.cols {
                    max_slope = max_slope.max((g.at(i, j + 1) as f64 - v).abs() / dx);
                }
                if i + 1 < g.rows {
                    max_slope = max_slope.max((g.at(i + 1, j) as f64 - v).abs() / dy);
                }
            }
        }
        // The bicubic interpolant overshoots the samples' slopes by at most 25 % (Catmull-Rom).
        TerrainMarch {
            floor,
            size,
            max_slope: max_slope * 1.25 * std::f64::consts::SQRT_2,
        }
    }

    /// Where the ray `s + u t` (t going down) first meets the terrain, and the path length `u`.
    fn intersect(&self, s: DVec3, t: DVec3) -> Option<(DVec2, f64)> {
        let gap = |u: f64| {
            let p = s + t * u;
            p.z - self.floor.height_gradient(p.truncate(), self.size).0
        };
        let rate = -t.z + self.max_slope * t.truncate().length();
        let mut u = 0.0;
        let mut g = gap(0.0);
        if g <= 0.0 {
            return None; // the floor rises above the water here: dry land
        }
        let tol = 1e-7 * self.size;
        for _ in 0..256 {
            let step = (g / rate).max(tol);
            let g_next = gap(u + step);
            if g_next <= 0.0 {
                let (mut a, mut b) = (u, u + step);
                for _ in 0..48 {
                    let m = 0.5 * (a + b);
                    if gap(m) > 0.0 {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                let u = 0.5 * (a + b);
                return Some(((s + t * u).truncate(), u));
            }
            u += step;
            g = g_next;
            if g < tol {
                return Some(((s + t * u).truncate(), u));
            }
        }
        Some(((s + t * u).truncate(), u))
    }
}
