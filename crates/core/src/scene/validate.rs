//! From the file schema to a [`Scene`]: every check names the field at fault.

use std::path::Path;

use glam::{DAffine3, DVec3};

use super::*;
use crate::error::{at_least, finite, non_negative, positive};
use crate::grid::MAX_RESOLUTION;
use crate::mesh;

fn resolution(field: &str, r: [u32; 2]) -> Result<()> {
    if r[0] == 0 || r[1] == 0 {
        return Err(Error::field(
            field,
            format!("must be at least 1 x 1, got {} x {}", r[0], r[1]),
        ));
    }
    if r[0] > MAX_RESOLUTION || r[1] > MAX_RESOLUTION {
        return Err(Error::field(
            field,
            format!(
                "{} x {} is beyond the largest supported size {MAX_RESOLUTION} x {MAX_RESOLUTION}",
                r[0], r[1]
            ),
        ));
    }
    Ok(())
}

fn resolve(base: &Path, p: &Path) -> PathBuf {
    if p.is_absolute() {
        p.to_path_buf()
    } else {
        base.join(p)
    }
}

pub(super) fn validate(
    file: SceneFile,
    base: &Path,
    name: &str,
    check_technique: TechniqueCheck,
) -> Result<Scene> {
    let light = validate_light(&file.light)?;
    let water = file
        .water
        .as_ref()
        .map(|w| validate_water(w, base))
        .transpose()?;
    let size = water.as_ref().map_or(1.0, |w| w.size);

    resolution("caustics.resolution", file.caustics.resolution)?;
    // The technique and its tables, by the check the loader was given (the registry's: the scene
    // model knows no technique), at this point of the file's checks.
    check_technique(&file.caustics)?;
    let technique = file.caustics.technique.clone();

    let floor = validate_floor(&file.floor, base, size)?;
    if floor.walls && water.is_none() {
        return Err(Error::field(
            "floor.walls",
            "walls receive the light the water sends down; the scene has no water",
        ));
    }
    if let (Some(w), Some(t)) = (&water, &floor.terrain) {
        let (lo, _) = t.min_max();
        if lo as f64 >= w.depth {
            return Err(Error::field(
                "floor.terrain",
                format!(
                    "lies entirely above the water level {} (its lowest point is {lo})",
                    w.depth
                ),
            ));
        }
    }

    let objects = file
        .objects
        .iter()
        .enumerate()
        .map(|(k, o)| validate_object(o, base, k, size))
        .collect::<Result<Vec<_>>>()?;
    let mut floor = floor;
    if water.is_some() {
        floor.solids = super::Solids::of(&objects);
    }

    let (camera, look) = match &file.camera {
        Some(c) => {
            positive("camera.exposure", c.exposure)?;
            finite("camera.position", &c.position)?;
            finite("camera.target", &c.target)?;
            if DVec3::from(c.position).distance(DVec3::from(c.target)) < 1e-9 {
                return Err(Error::field(
                    "camera.target",
                    "coincides with camera.position",
                ));
            }
            if !(c.fov_y > 1.0 && c.fov_y < 170.0) {
                return Err(Error::field(
                    "camera.fov_y",
                    format!("must be between 1 and 170 degrees, got {}", c.fov_y),
                ));
            }
            resolution("camera.resolution", c.resolution)?;
            // Under the water is a place to look from (the final image starts its rays there);
            // under a pool's floor is inside the ground.
            let [x, y, z] = c.position;
            let over_pool = x >= 0.0 && y >= 0.0 && x <= size && y <= size;
            if water.is_some() && floor.terrain.is_none() && over_pool && z <= 0.0 {
                return Err(Error::field(
                    "camera.position",
                    format!("{:?} is under the pool's floor (z = 0)", c.position),
                ));
            }
            let camera = Camera {
                position: c.position.into(),
                target: c.target.into(),
                fov_y: c.fov_y,
                width: c.resolution[0],
                height: c.resolution[1],
            };
            let look = Look {
                exposure: c.exposure,
                tone_map: c.tone_map,
            };
            (camera, look)
        }
        None => {
            let depth = water.as_ref().map_or(0.0, |w| w.depth);
            (default_camera(size, depth), Look::default())
        }
    };

    finite("time", &[file.time])?;
    Ok(Scene {
        name: name.to_string(),
        water,
        light,
        caustics: CausticsSettings {
            width: file.caustics.resolution[0],
            height: file.caustics.resolution[1],
            technique,
            params: file.caustics.params.clone(),
        },
        floor,
        objects,
        camera,
        look,
        time: file.time,
        size,
    })
}

/// Looking at the square's centre from above one corner, far enough to see all of it.
fn default_camera(size: f64, depth: f64) -> Camera {
    let c = DVec3::new(0.5 * size, 0.5 * size, 0.3 * depth);
    Camera {
        position: c + DVec3::new(-0.55, -0.95, 0.95) * size,
        target: c,
        fov_y: 50.0,
        width: 960,
        height: 540,
    }
}

fn validate_light(l: &LightSpec) -> Result<Light> {
    let position = match l.position {
        Some(p) => {
            finite("light.position", &p)?;
            if p[2] <= 0.0 {
                return Err(Error::field(
                    "light.position",
                    format!("{p:?} is not above the floor: a point light needs z > 0"),
                ));
            }
            Some(DVec3::from(p))
        }
        None => None,
    };
    let cone = match (l.cone, position) {
        (None, _) => None,
        (Some(_), None) => {
            return Err(Error::field(
                "light.cone",
                "makes a spot light and needs light.position (the sun has no cone)",
            ));
        }
        (Some(c), Some(_)) => {
            finite("light.cone", &[c])?;
            if !(c > 0.0 && c <= 90.0) {
                return Err(Error::field(
                    "light.cone",
                    format!("is the spot's half-angle in degrees and must be in (0, 90], got {c}"),
                ));
            }
            Some(c.to_radians())
        }
    };
    let direction = match (l.direction, position) {
        (Some(d), _) => d,
        (None, Some(_)) => [0.0, 0.0, -1.0],
        (None, None) => {
            return Err(Error::field(
                "light.direction",
                "is required for the sun (give light.position for a point light)",
            ));
        }
    };
    finite("light.direction", &direction)?;
    let d = DVec3::from(direction);
    if d.length() < 1e-12 {
        return Err(Error::field(
            "light.direction",
            "must not be the zero vector",
        ));
    }
    let d = d.normalize();
    if d.z >= -1e-6 {
        return Err(Error::field(
            "light.direction",
            format!(
                "{:?} points up or along the horizon: it is the direction the sunlight travels, so its z must be negative",
                direction
            ),
        ));
    }
    non_negative("light.color", &l.color)?;
    non_negative("light.intensity", &[l.intensity])?;
    Ok(Light {
        direction: d,
        color: l.color.into(),
        intensity: l.intensity,
        position,
        cone,
    })
}

fn validate_water(w: &WaterSpec, base: &Path) -> Result<Water> {
    positive("water.size", w.size)?;
    positive("water.depth", w.depth)?;
    at_least("water.ior", w.ior, 1.0)?;
    non_negative("water.absorption", &w.absorption)?;
    let sources = [
        w.heightfield.is_some(),
        w.waves.is_some(),
        w.procedural.is_some(),
        w.ocean.is_some(),
        w.ripple.is_some(),
    ];
    if sources.iter().filter(|&&s| s).count() > 1 {
        return Err(Error::field(
            "water",
            "has more than one surface source: give only one of heightfield, waves, procedural, ocean, ripple",
        ));
    }
    let source = if let Some(p) = &w.heightfield {
        let path = resolve(base, p);
        let grid = Grid::load(&path, w.heightfield_range.unwrap_or([-0.05, 0.05]))?;
        let (lo, _) = grid.min_max();
        if lo as f64 <= -w.depth {
            return Err(Error::bad_file(
                &path,
                format!(
                    "the surface dips to {lo}, at or below the floor (water.depth = {})",
                    w.depth
                ),
            ));
        }
        WaterSource::HeightField(grid)
    } else if let Some(waves) = &w.waves {
        for (k, wave) in waves.iter().enumerate() {
            let f = format!("water.waves[{k}]");
            finite(&format!("{f}.amplitude"), &[wave.amplitude])?;
            positive(&format!("{f}.wavelength"), wave.wavelength)?;
            finite(&format!("{f}.direction"), &wave.direction)?;
            finite(&format!("{f}.phase"), &[wave.phase])?;
        }
        let total: f64 = waves.iter().map(|w| w.amplitude.abs()).sum();
        if total >= w.depth {
            return Err(Error::field(
                "water.waves",
                format!(
                    "amplitudes add up to {total}, reaching the floor at depth {}",
                    w.depth
                ),
            ));
        }
        WaterSource::Waves(waves.clone())
    } else if let Some(p) = &w.procedural {
        finite(
            "water.procedural",
            &[p.amplitude, p.frequency, p.octave_base, p.speed],
        )?;
        positive("water.procedural.octave_base", p.octave_base)?;
        if p.octaves == 0 || p.octaves > 16 {
            return Err(Error::field(
                "water.procedural.octaves",
                format!("must be between 1 and 16, got {}", p.octaves),
            ));
        }
        WaterSource::Procedural(p.clone())
    } else if let Some(o) = &w.ocean {
        WaterSource::Ocean(Box::new(Ocean::new(o, w.size)?))
    } else if let Some(r) = &w.ripple {
        // Constructing checks the parameters (stability included).
        Ripples::new(r, w.size, if w.wrap { Edge::Wrap } else { Edge::Clamp })?;
        WaterSource::Ripple(r.clone())
    } else {
        WaterSource::Flat
    };
    Ok(Water {
        source,
        size: w.size,
        depth: w.depth,
        ior: w.ior,
        wrap: w.wrap,
        absorption: w.absorption.into(),
    })
}

fn validate_floor(f: &FloorSpec, base: &Path, size: f64) -> Result<Floor> {
    let terrain = match &f.terrain {
        None => None,
        Some(t) => Some(match (&t.heightfield, &t.beach) {
            (Some(p), None) => {
                let path = resolve(base, p);
                let g = Grid::load(&path, t.heightfield_range.unwrap_or([0.0, 1.0]))?;
                if g.min_max().0 < 0.0 {
                    return Err(Error::bad_file(
                        &path,
                        "terrain heights must not go below z = 0",
                    ));
                }
                g
            }
            (None, Some(b)) => {
                finite("floor.terrain.beach", &[b.dunes])?;
                // Heights above z = 0, as every terrain's.
                non_negative("floor.terrain.beach", &[b.deep, b.shallow])?;
                if b.resolution < 2 || b.resolution > MAX_RESOLUTION as usize {
                    return Err(Error::field(
                        "floor.terrain.beach.resolution",
                        format!(
                            "must be between 2 and {MAX_RESOLUTION}, got {}",
                            b.resolution
                        ),
                    ));
                }
                for (k, r) in b.rocks.iter().enumerate() {
                    let f = format!("floor.terrain.beach.rocks[{k}]");
                    finite(&f, &[r.position[0], r.position[1], r.radius, r.height])?;
                    positive(&format!("{f}.radius"), r.radius)?;
                    non_negative(&format!("{f}.height"), &[r.height])?;
                }
                beach(b, size)
            }
            _ => {
                return Err(Error::field(
                    "floor.terrain",
                    "needs exactly one of `heightfield` or `beach`",
                ));
            }
        }),
    };
    let albedo = match &f.albedo {
        None => Albedo::Pattern(f.pattern),
        Some(p) => read_albedo(&resolve(base, p))?,
    };
    if f.walls && terrain.is_some() {
        return Err(Error::field(
            "floor.walls",
            "walls receive light only around a flat pool floor; remove `terrain` or `walls`",
        ));
    }
    Ok(Floor {
        terrain,
        solids: None,
        albedo,
        walls: f.walls,
        deck: f.deck,
    })
}

#[cfg(feature = "formats")]
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A beach: a smooth ramp from `deep` to `shallow` across x, with gentle sand dunes across y, and
/// its rocks.
fn beach(b: &BeachSpec, size: f64) -> Grid {
    let n = b.resolution;
    Grid::from_fn(n, n, |i, j| {
        let x = (j as f64 + 0.5) / n as f64;
        let y = (i as f64 + 0.5) / n as f64;
        let ramp = b.deep + (b.shallow - b.deep) * (x * x * (3.0 - 2.0 * x));
        let dunes = b.dunes
            * ((x * 23.0 + (y * 5.0).sin()) * std::f64::consts::TAU).sin()
            * (0.5 + 0.5 * (y * 7.0 * size).cos());
        let rocks: f64 = b
            .rocks
            .iter()
            .map(|r| {
                let d = (x * size - r.position[0]).hypot(y * size - r.position[1]) / r.radius;
                r.height * (1.0 - d * d).max(0.0).powi(2)
            })
            .sum();
        (ramp + dunes + rocks).max(0.0) as f32
    })
}

fn validate_object(o: &ObjectSpec, base: &Path, k: usize, size: f64) -> Result<Object> {
    let f = format!("objects[{k}]");
    finite(&format!("{f}.position"), &o.position)?;
    positive(&format!("{f}.scale"), o.scale)?;
    finite(&format!("{f}.rotation"), &[o.rotation])?;
    let native = match &o.shape {
        ShapeSpec::Teapot => {
            let t = mesh::teapot(8);
            // Native teapot is ~3.15 units high: bring it to 1 unit.
            let (lo, hi) = t.bounds();
            t.transformed(DAffine3::from_scale(DVec3::splat(1.0 / (hi.z - lo.z))))
        }
        ShapeSpec::Sphere => {
            mesh::sphere(1.0, 64, 32).transformed(DAffine3::from_translation(DVec3::Z))
        }
        ShapeSpec::Cuboid { half_extents } => {
            finite(&format!("{f}.shape.half_extents"), half_extents)?;
            let h = DVec3::from(*half_extents);
            if h.min_element() <= 0.0 {
                return Err(Error::field(
                    format!("{f}.shape.half_extents"),
                    "must be positive",
                ));
            }
            mesh::cuboid(h).transformed(DAffine3::from_translation(DVec3::Z * h.z))
        }
        ShapeSpec::Mesh { path } => mesh::load_obj(&resolve(base, path))?,
    };
    let m = DAffine3::from_translation(o.position.into())
        * DAffine3::from_rotation_z(o.rotation.to_radians())
        * DAffine3::from_scale(DVec3::splat(o.scale));
    let mesh = native.transformed(m);
    mesh.validate(&f)?;
    let (lo, hi) = mesh.bounds();
    let extent = (hi - lo).max_element();
    if extent > 100.0 * size {
        return Err(Error::field(
            &f,
            format!("is {extent:.3} units across, far larger than the scene square of side {size}"),
        ));
    }
    let material = match &o.material {
        MaterialSpec::Diffuse { color } => {
            finite(&format!("{f}.material.color"), color)?;
            Material::Diffuse {
                color: (*color).into(),
            }
        }
        MaterialSpec::Glass { ior, tint } => {
            at_least(&format!("{f}.material.ior"), *ior, 1.0)?;
            Material::Glass {
                ior: *ior,
                tint: tint.map_or(DVec3::ONE, DVec3::from),
            }
        }
    };
    Ok(Object { mesh, material })
}

/// The floor's albedo from an image file (sRGB, any format the `image` crate reads).
#[cfg(feature = "formats")]
fn read_albedo(path: &Path) -> Result<Albedo> {
    let img = image::open(path)
        .map_err(|e| Error::bad_file(path, format!("cannot read the albedo image: {e}")))?
        .to_rgb32f();
    let (width, height) = (img.width() as usize, img.height() as usize);
    // Image rows run top down; flip so that row 0 is y = 0 like every map here.
    let mut texels = Vec::with_capacity(width * height);
    for i in (0..height).rev() {
        for j in 0..width {
            let p = img.get_pixel(j as u32, i as u32).0;
            texels.push(p.map(srgb_to_linear));
        }
    }
    Ok(Albedo::Image {
        width,
        height,
        texels,
    })
}

#[cfg(not(feature = "formats"))]
fn read_albedo(path: &Path) -> Result<Albedo> {
    Err(Error::feature_off(path, "an albedo image", "formats"))
}
