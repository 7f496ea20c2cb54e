//! The raw caustics map and the intermediate buffers as pictures: what the views beside the final
//! image show, so a technique's stages can be watched as the water moves.
//!
//! The GPU passes keep their intermediate textures to themselves, so the intermediates are
//! recomputed by the technique's CPU twin (for `yuksel`: `prepass` and `pass1`; for
//! `caustic-triangles`: the layered distance map, the photon hit location image, the vertex
//! irradiances and a point light's light cube map; for `volumes`: each object's caustics map; for
//! `cascaded`: each cascade's own screen-space caustic map; the GPU passes match them to the
//! tolerances their tests state) from the same input, only while their view is open.
//!
//! Every map is drawn as seen from above: +x to the right, +y up (row 0 of a map, at y = 0, is the
//! bottom row); eye-space images as the camera sees them.

use glam::DVec3;

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::render::EyeSpaceCaustics;
use caustics_core::scene::{Scene, Water};
use caustics_core::techniques::caustic_triangles as ct;
use caustics_core::techniques::yuksel::{self, YukselParams, YukselSetup};
use caustics_core::techniques::{cascaded, volumes};
use caustics_core::walls::{Wall, WallMaps};
use caustics_core::water::{Surface, sample_grid};

use super::frame::TechniqueChoice;
use caustics_core::techniques::{SceneCaustics, heights_for};

/// A buffer the view can show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Buffer {
    /// The water's heights on the map's lattice, as the grid-based techniques read them.
    Heights,
    /// `yuksel` pre-pass: where each sample's refracted ray lands, as offsets from its pixel.
    YukselOffset,
    /// `yuksel` pre-pass: the flux each sample carries, relative to flat water.
    YukselFlux,
    /// `yuksel` pass 1: channel `k` of the `M + 1`, what each sample row gave the row `k - M/2`
    /// away.
    YukselChannel(u32),
    /// `caustic-triangles` §3: layer `k` of the generator's layered distance map, its six cube
    /// faces side by side.
    DistanceLayer(u32),
    /// `caustic-triangles` §4.1: the photon hit location image, where each photon lands.
    PhotonHits,
    /// `caustic-triangles` §4.1: the power each photon carries to the floor.
    PhotonPower,
    /// `caustic-triangles` §5: the irradiance at each photon-image vertex (power over its area).
    VertexIrradiance,
    /// `caustic-triangles` §4.2: the light cube map a point light's caustic triangles are drawn
    /// into, its six faces side by side.
    LightCube,
    /// `volumes` §3.2: object `k`'s caustics map, as its illumination volumes light it.
    ObjectCaustics(u32),
    /// `cascaded` §3.3: cascade `k`'s own screen-space caustic map, before the cascades blend.
    CascadeMap(u32),
}

impl Buffer {
    pub fn name(&self) -> String {
        match self {
            Buffer::Heights => "water heights".into(),
            Buffer::YukselOffset => "yuksel pre-pass: hit offset".into(),
            Buffer::YukselFlux => "yuksel pre-pass: flux".into(),
            Buffer::YukselChannel(k) => format!("yuksel pass 1: channel {k}"),
            Buffer::DistanceLayer(k) => format!("distance map: layer {k}"),
            Buffer::PhotonHits => "photon hit location image".into(),
            Buffer::PhotonPower => "photon power".into(),
            Buffer::VertexIrradiance => "vertex irradiance".into(),
            Buffer::LightCube => "light cube map".into(),
            Buffer::ObjectCaustics(k) => format!("object {k}: caustics map"),
            Buffer::CascadeMap(k) => format!("cascade {k}: caustic map"),
        }
    }

    /// The short name `--buffer` takes: `heights`, `yuksel-offset`, `yuksel-flux`,
    /// `yuksel-channel:K`, `distance-layer:K`, `photon-hits`, `photon-power`, `vertex-irradiance`,
    /// `light-cube`, `object:K`, `cascade:K`.
    pub fn key(&self) -> String {
        match self {
            Buffer::Heights => "heights".into(),
            Buffer::YukselOffset => "yuksel-offset".into(),
            Buffer::YukselFlux => "yuksel-flux".into(),
            Buffer::YukselChannel(k) => format!("yuksel-channel:{k}"),
            Buffer::DistanceLayer(k) => format!("distance-layer:{k}"),
            Buffer::PhotonHits => "photon-hits".into(),
            Buffer::PhotonPower => "photon-power".into(),
            Buffer::VertexIrradiance => "vertex-irradiance".into(),
            Buffer::LightCube => "light-cube".into(),
            Buffer::ObjectCaustics(k) => format!("object:{k}"),
            Buffer::CascadeMap(k) => format!("cascade:{k}"),
        }
    }

    /// The buffer a [`key`](Self::key) names (`:K` may be left out for 0), if it is one of
    /// `available`; else an error listing those.
    pub fn parse(s: &str, available: &[Buffer]) -> anyhow::Result<Buffer> {
        let (name, k) = match s.split_once(':') {
            Some((n, k)) => (
                n,
                k.parse::<u32>()
                    .map_err(|_| anyhow::anyhow!("`{s}`: `{k}` is not an index"))?,
            ),
            None => (s, 0),
        };
        let keys: Vec<String> = available.iter().map(Buffer::key).collect();
        available
            .iter()
            .map(|b| match b {
                Buffer::YukselChannel(_) => Buffer::YukselChannel(k),
                Buffer::DistanceLayer(_) => Buffer::DistanceLayer(k),
                Buffer::ObjectCaustics(_) => Buffer::ObjectCaustics(k),
                Buffer::CascadeMap(_) => Buffer::CascadeMap(k),
                other => *other,
            })
            .find(|b| b.key().split(':').next() == Some(name))
            .ok_or_else(|| {
                anyhow::anyhow!(
                    "no buffer `{s}` for this technique here; it has: {}",
                    keys.join(", ")
                )
            })
    }

    /// The buffers a technique has in a scene with what `has` says.
    pub fn available(choice: &TechniqueChoice, has: SceneHas) -> Vec<Buffer> {
        let water = has.water;
        let mut v = Vec::new();
        if water {
            v.push(Buffer::Heights);
        }
        // Every buffer the technique's descriptor lists, where the scene has what it shows: the
        // distance map of glass (the water is traced as a height field), a point light's cube,
        // objects' maps.
        let all = [
            Buffer::YukselOffset,
            Buffer::YukselFlux,
            Buffer::YukselChannel(0),
            Buffer::PhotonHits,
            Buffer::PhotonPower,
            Buffer::VertexIrradiance,
            Buffer::DistanceLayer(0),
            Buffer::LightCube,
            Buffer::ObjectCaustics(0),
            Buffer::CascadeMap(0),
        ];
        v.extend(all.into_iter().filter(|b| {
            let key = b.key();
            let name = key.split(':').next().unwrap_or(&key);
            choice.entry.buffers.contains(&name)
                && match b {
                    Buffer::DistanceLayer(_) => !water,
                    Buffer::LightCube => has.point_light,
                    Buffer::ObjectCaustics(_) => has.objects,
                    _ => true,
                }
        }));
        v
    }
}

/// What of a scene decides which buffers a technique has there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneHas {
    pub water: bool,
    /// A point or spot light (a light cube map).
    pub point_light: bool,
    /// Objects under the water (receivers of paper 3's caustics).
    pub objects: bool,
}

impl SceneHas {
    pub fn of(scene: &Scene) -> Self {
        SceneHas {
            water: scene.water.is_some(),
            point_light: scene.light.position.is_some(),
            objects: !scene.objects.is_empty(),
        }
    }
}

/// An RGBA8 picture with a line saying how its colours read.
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
    pub legend: String,
}

/// The caustics map: relative irradiance through a heat ramp, 0 black, 1 (flat water) a dull
/// orange, the map's maximum (at least 2) white.
pub fn map_picture(map: &CausticsMap) -> Picture {
    let g = map.mean_channel();
    let (_, max) = g.min_max();
    let top = max.max(2.0);
    Picture {
        legend: format!("relative irradiance: black 0, white {top:.2} (max {max:.2})"),
        ..scalar_picture(&g, |v| heat(v / top))
    }
}

/// A technique's caustics as the map view shows them: a floor map ([`map_picture`]), with the
/// pool's walls folded out around it when the technique lit them ([`box_picture`]), or an
/// eye-space image ([`eye_picture`]).
pub fn caustics_picture(caustics: &SceneCaustics, walls: Option<&WallMaps>) -> Picture {
    match (caustics, walls) {
        (SceneCaustics::Floor(m), Some(w)) => box_picture(m, w).unwrap_or_else(|| map_picture(m)),
        (SceneCaustics::Floor(m), None) => map_picture(m),
        (SceneCaustics::EyeSpace(e), _) => eye_picture(e),
    }
}

/// The pool as an unfolded box: the floor map in the middle (y up, as [`map_picture`]), each wall
/// folded out flat beside the floor edge it stands on, its foot against that edge and its top (the
/// rest water level) outermost; dark blue in the corners. One heat ramp for all five, so light
/// the walls took from the floor reads at its true strength. `None` when the walls' maps do not
/// fit the floor map (not [`WallMaps::for_floor_map`] of it).
pub fn box_picture(floor: &CausticsMap, walls: &WallMaps) -> Option<Picture> {
    let (w, h) = (floor.width, floor.height);
    let r = walls.get(Wall::X0).rows;
    let fits = Wall::ALL.iter().all(|&k| {
        let m = walls.get(k);
        let along = match k {
            Wall::X0 | Wall::X1 => h,
            Wall::Y0 | Wall::Y1 => w,
        };
        m.rows == r && m.cols == along
    });
    if !fits {
        return None;
    }
    let (cols, rows) = (w + 2 * r, h + 2 * r);
    // Row-major with row 0 at y = 0 below the floor's first row.
    let mut values = vec![None; cols * rows];
    for i in 0..h {
        for j in 0..w {
            values[(r + i) * cols + r + j] = Some(floor.texels[i * w + j]);
        }
    }
    for k in Wall::ALL {
        let m = walls.get(k);
        for row in 0..r {
            for c in 0..m.cols {
                let (y, x) = match k {
                    Wall::X0 => (r + c, r - 1 - row),
                    Wall::X1 => (r + c, r + w + row),
                    Wall::Y0 => (r - 1 - row, r + c),
                    Wall::Y1 => (r + h + row, r + c),
                };
                values[y * cols + x] = Some(m.texels[row * m.cols + c]);
            }
        }
    }
    Some(rgb_picture(
        cols,
        rows,
        |t| values[(rows - 1 - t / cols) * cols + t % cols],
        "relative irradiance, the walls folded out around the floor",
    ))
}

/// An eye-space caustics image (`cascaded`) as the camera sees it, on the heat ramp of
/// [`map_picture`]; blue where the technique has no value (sky, water seen from above the floor's
/// reach).
pub fn eye_picture(image: &EyeSpaceCaustics) -> Picture {
    rgb_picture(
        image.width,
        image.height,
        |t| {
            let p = image.texels[t];
            (p[3] >= 0.0).then(|| [p[0], p[1], p[2]])
        },
        "relative irradiance",
    )
}

/// An RGB relative-irradiance image, row 0 at the top, on the heat ramp (0 black, the maximum,
/// at least 2, white); `None` texels drawn dark blue.
fn rgb_picture(
    width: usize,
    height: usize,
    texel: impl Fn(usize) -> Option<[f32; 3]>,
    what: &str,
) -> Picture {
    let values: Vec<Option<f32>> = (0..width * height)
        .map(|t| texel(t).map(|c| (c[0] + c[1] + c[2]) / 3.0))
        .collect();
    let max = values
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0f32, f32::max);
    let top = max.max(2.0);
    let rgba = values
        .iter()
        .flat_map(|v| match v {
            Some(v) => {
                let [r, g, b] = heat(v / top);
                [r, g, b, 255]
            }
            None => [20, 30, 70, 255],
        })
        .collect();
    Picture {
        width: width as u32,
        height: height as u32,
        rgba,
        legend: format!("{what}: black 0, white {top:.2} (max {max:.2}); dark blue: no value"),
    }
}

/// `a - b` of two maps of one size: blue where `a` is darker, red where brighter.
pub fn difference_picture(a: &CausticsMap, b: &CausticsMap) -> Option<Picture> {
    if (a.width, a.height) != (b.width, b.height) {
        return None;
    }
    let (ga, gb) = (a.mean_channel(), b.mean_channel());
    let d = Grid {
        cols: ga.cols,
        rows: ga.rows,
        data: ga.data.iter().zip(&gb.data).map(|(x, y)| x - y).collect(),
    };
    let (lo, hi) = d.min_max();
    let r = lo.abs().max(hi.abs()).max(1e-6);
    let mean_abs = d.data.iter().map(|v| v.abs() as f64).sum::<f64>() / d.data.len().max(1) as f64;
    Some(Picture {
        legend: format!("left - right: blue -{r:.2}, red +{r:.2}; mean |difference| {mean_abs:.3}"),
        ..scalar_picture(&d, |v| diverging(v / r))
    })
}

/// The inputs of a buffer computation.
pub struct BufferInput<'a> {
    pub choice: &'a TechniqueChoice,
    /// The scene with the frame's sun and map size (the glass generators' buffers read it).
    pub scene: &'a Scene,
    /// The water as the technique sees it and its surface this frame, in a scene with water.
    pub water: Option<(&'a Water, &'a dyn Surface)>,
    pub light: DVec3,
    pub map_size: usize,
}

/// Compute `buffer` for `input`; an error names what stood in the way (e.g. invalid `N`).
pub fn buffer_picture(buffer: Buffer, input: &BufferInput) -> anyhow::Result<Picture> {
    if matches!(
        buffer,
        Buffer::DistanceLayer(_)
            | Buffer::PhotonHits
            | Buffer::PhotonPower
            | Buffer::VertexIrradiance
    ) {
        return glass_picture(buffer, input);
    }
    if buffer == Buffer::LightCube {
        return light_cube_picture(input);
    }
    if let Buffer::ObjectCaustics(k) = buffer {
        return object_picture(k as usize, input);
    }
    if let Buffer::CascadeMap(k) = buffer {
        return cascade_picture(k as usize, input);
    }
    let Some((water, surface)) = input.water else {
        anyhow::bail!("the scene has no water");
    };
    let n = input.map_size;
    let heights = heights_for(water, surface, n, n);
    if buffer == Buffer::Heights {
        let (lo, hi) = heights.min_max();
        let r = lo.abs().max(hi.abs()).max(1e-9);
        return Ok(Picture {
            legend: format!("height: blue -{r:.4}, red +{r:.4} (world units)"),
            ..scalar_picture(&heights, |v| diverging(v / r))
        });
    }
    let spec = input.choice.spec()?;
    let params = YukselParams::from_table(&spec.params)?;
    let w = water;
    let mut setup = YukselSetup::new(
        &params,
        n,
        n,
        w.size,
        w.depth,
        w.ior,
        w.absorption,
        w.wrap,
        input.light,
    )?;
    setup.fit_region(&heights);
    // The samples are the region's level's (k × k per pixel of it).
    let coarse = setup.at_level(setup.region.level);
    let pre = yuksel::prepass(&coarse, &heights);
    let (pw, ph) = coarse.prepass_size();
    match buffer {
        Buffer::YukselOffset => {
            // δ in pixels: red for x, green for y, mid-grey at no offset, saturating at N/2.
            let reach = (setup.region.n / 2).max(1) as f32;
            let rgba = flip_rows(pw, ph, |t| {
                let p = pre[t];
                let c = |d: f32| ((0.5 + 0.5 * d / reach).clamp(0.0, 1.0) * 255.0) as u8;
                [c(p[0]), c(p[1]), 128, 255]
            });
            Ok(Picture {
                width: pw as u32,
                height: ph as u32,
                rgba,
                legend: format!("hit offset: red x, green y, grey 0, saturated at ±{reach} px"),
            })
        }
        Buffer::YukselFlux => {
            // Each of a pixel's k × k samples carries 1 / k² of its light: times k², 1 is what
            // flat water gives a whole pixel, whatever k.
            let k2 = (coarse.subsamples * coarse.subsamples) as f32;
            let g = Grid {
                cols: pw,
                rows: ph,
                data: pre.iter().map(|p| p[3] * k2).collect(),
            };
            let (_, max) = g.min_max();
            let top = max.max(1.5);
            Ok(Picture {
                legend: format!(
                    "sample flux x {k2} (its k x k share of a pixel; 1: flat water): black 0, white {top:.2}"
                ),
                ..scalar_picture(&g, |v| heat(v / top))
            })
        }
        Buffer::YukselChannel(k) => {
            let p1 = yuksel::pass1(&setup, &pre, 0);
            let (w1, h1) = setup.pass1_size();
            let ch = setup.region.m + 1;
            let k = (k as usize).min(setup.region.m);
            let g = Grid {
                cols: w1,
                rows: h1,
                data: (0..w1 * h1).map(|t| p1[t * ch + k]).collect(),
            };
            let (_, max) = g.min_max();
            let top = max.max(1e-6);
            Ok(Picture {
                legend: format!(
                    "channel {k} of {ch} (row offset {}): black 0, white {top:.2}",
                    k as i64 - setup.region.m as i64 / 2 - setup.region.shift[1] as i64
                ),
                ..scalar_picture(&g, |v| heat(v / top))
            })
        }
        _ => unreachable!("the water's buffers only"),
    }
}

/// The `caustic-triangles` buffers of the scene's generator, from the CPU twin's passes: its water
/// surface where it has water, else its first glass object.
fn glass_picture(buffer: Buffer, input: &BufferInput) -> anyhow::Result<Picture> {
    let spec = input.choice.spec()?;
    let params = ct::CausticTrianglesParams::from_table(&spec.params)?;
    let (setup, photons) = match input.water {
        Some((water, surface)) => {
            if let Buffer::DistanceLayer(_) = buffer {
                anyhow::bail!("the water surface is traced as a height field, not a distance map");
            }
            let n = input.map_size;
            let ws = ct::water::WaterSetup::new(&params, water, input.light, n, n)?;
            let heights = ct::water::heights(water, surface, n, n);
            let (photons, _) = ct::water::photon_pass(&ws, &heights);
            (ws.setup, photons)
        }
        None => {
            let gs = ct::GlassScene::from_scene(input.scene, 0)?;
            let dm = ct::DistanceMap::build(
                &gs,
                params.cube_resolution as usize,
                params.layers as usize,
            );
            if let Buffer::DistanceLayer(k) = buffer {
                return Ok(distance_picture(&dm, k as usize));
            }
            let setup = ct::CausticTrianglesSetup::new(&params, &gs)?;
            let photons = ct::photon_pass(&setup, &dm);
            (setup, photons)
        }
    };
    let p = setup.p;
    let valid = |t: &[f32; 4]| t[2] >= 0.0;
    match buffer {
        Buffer::PhotonHits => {
            // The floor position each photon reached, as a colour: red along x, green along y
            // over the floor square; black where the photon is invalid (missed the generator,
            // left the floor, or ran out of events).
            let size = input.scene.size as f32;
            let rgba = flip_rows(p, p, |t| {
                let h = &photons[t];
                if !valid(h) {
                    return [0, 0, 0, 255];
                }
                let c = |v: f32| ((v / size).clamp(0.0, 1.0) * 255.0) as u8;
                [c(h[0]), c(h[1]), 96, 255]
            });
            let count = photons.iter().filter(|h| valid(h)).count();
            Ok(Picture {
                width: p as u32,
                height: p as u32,
                rgba,
                legend: format!(
                    "{count} of {} photons valid: red = floor x, green = floor y, black invalid",
                    p * p
                ),
            })
        }
        Buffer::PhotonPower => {
            let g = Grid {
                cols: p,
                rows: p,
                data: photons.iter().map(|h| h[2].max(0.0)).collect(),
            };
            let (_, max) = g.min_max();
            let top = max.max(1e-12);
            Ok(Picture {
                legend: format!(
                    "photon power: black 0, white {top:.3e} floor-area units (total {:.4})",
                    ct::photon_power(&photons)
                ),
                ..scalar_picture(&g, |v| heat(v / top))
            })
        }
        Buffer::VertexIrradiance => {
            let e = ct::irradiance_pass(&setup, &photons);
            // Irradiance spans decades between the focus and the rim: a log scale.
            let g = Grid {
                cols: p,
                rows: p,
                data: e.iter().map(|v| (1.0 + v.max(0.0)).log10()).collect(),
            };
            let (_, max) = g.min_max();
            let top = max.max(1e-6);
            Ok(Picture {
                legend: format!(
                    "vertex irradiance, log scale: black 0, white {:.1} (relative to the unobstructed light)",
                    10f32.powf(top) - 1.0
                ),
                ..scalar_picture(&g, |v| heat(v / top))
            })
        }
        _ => unreachable!("the glass buffers only"),
    }
}

/// The scene as the water techniques see it this frame: the water as animated.
fn scene_with_water<'a>(input: &BufferInput<'a>) -> anyhow::Result<(Scene, &'a dyn Surface)> {
    let Some((water, surface)) = input.water else {
        anyhow::bail!("the scene has no water");
    };
    let mut scene = input.scene.clone();
    scene.water = Some(water.clone());
    scene.light.direction = input.light;
    Ok((scene, surface))
}

/// The light cube map of a point light (`caustic-triangles`, §4.2): every glass generator's caustic
/// triangles drawn onto its six faces, as the CPU twin's `render_scene` does.
fn light_cube_picture(input: &BufferInput) -> anyhow::Result<Picture> {
    let spec = input.choice.spec()?;
    let params = ct::CausticTrianglesParams::from_table(&spec.params)?;
    let gens = ct::camera::generators(input.scene, &params)?;
    let Some(light) = gens[0].setup.point else {
        anyhow::bail!(
            "the light cube map belongs to a point or spot light; this scene has the sun"
        );
    };
    let mut cube = ct::cube::LightCube::new(params.light_cube as usize, light.position);
    for g in &gens {
        let out = ct::caustics(&g.setup, &g.dm);
        ct::cube::cube_triangles_pass(&g.setup, &out.photons, &out.irradiance, &mut cube);
    }
    let c = cube.resolution;
    // Irradiance spans decades between a focus and the rest: a log scale, as for the vertices.
    let log: Vec<f32> = cube
        .caustic
        .iter()
        .map(|t| (1.0 + t[0].max(0.0)).log10())
        .collect();
    let top = log.iter().copied().fold(1e-6f32, f32::max);
    let mut rgba = Vec::with_capacity(6 * c * c * 4);
    for row in (0..c).rev() {
        for face in 0..6 {
            for col in 0..c {
                let [r, g, b] = heat(log[(face * c + row) * c + col] / top);
                rgba.extend([r, g, b, 255]);
            }
        }
    }
    Ok(Picture {
        width: 6 * c as u32,
        height: c as u32,
        rgba,
        legend: format!(
            "caustic irradiance on faces +x −x +y −y +z −z, log scale: black 0, white {:.1}",
            10f32.powf(top) - 1.0
        ),
    })
}

/// Object `k`'s caustics map (`volumes`, §3.2), in its texture's own layout (the view along the
/// refracted sun).
fn object_picture(k: usize, input: &BufferInput) -> anyhow::Result<Picture> {
    let (scene, surface) = scene_with_water(input)?;
    let spec = input.choice.spec()?;
    let params = volumes::VolumesParams::from_table(&spec.params)?;
    let vin = volumes::VolumesInput::from_scene(&scene)?;
    let count = vin.objects.len();
    if k >= count {
        anyhow::bail!(
            "the scene has {count} objects (0 to {})",
            count.saturating_sub(1)
        );
    }
    let setup = volumes::VolumesSetup::new(&params, &vin)?;
    let water = scene.water.as_ref().expect("set above");
    let n = (vin.size / setup.lattice.cell).round() as usize;
    let heights = sample_grid(surface, n, n, water.size);
    let out = volumes::caustics(&setup, &vin, &heights, water.wrap);
    let maps = &out.objects[k];
    let side = (maps.caustics.len() as f64).sqrt() as usize;
    Ok(rgb_picture(
        side,
        side,
        |t| (maps.depth[t][1..].iter().any(|v| *v != 0.0)).then(|| maps.caustics[t]),
        &format!("object {k} of {count}, relative irradiance"),
    ))
}

/// Cascade `k`'s own screen-space caustic map (`cascaded`, §3.3), before the blend between
/// cascades: where each cascade's photons land in the eye's image.
fn cascade_picture(k: usize, input: &BufferInput) -> anyhow::Result<Picture> {
    let (scene, surface) = scene_with_water(input)?;
    if k >= cascaded::CASCADES {
        anyhow::bail!(
            "there are {} cascades (0 to {})",
            cascaded::CASCADES,
            cascaded::CASCADES - 1
        );
    }
    let spec = input.choice.spec()?;
    let job = caustics_core::techniques::Job::new(&scene, Some(surface), 1);
    let (setup, grid) = cascaded::job_setup(&job, &spec.params)?;
    let frame = cascaded::caustics(&setup, &grid, scene.floor.terrain.as_ref());
    let map = frame.cascade_map(&setup, k);
    Ok(rgb_picture(
        setup.eye.width,
        setup.eye.height,
        |t| (frame.eye[t][3] != 0.0).then(|| map[t]),
        &format!("cascade {k} of {}, relative irradiance", cascaded::CASCADES),
    ))
}

/// The six faces of one layer of a layered distance map side by side (+x, −x, +y, −y, +z, −z):
/// the glass's distance through a heat ramp (white at the map's radius), diffuse occluders in
/// blue, no surface black.
fn distance_picture(dm: &ct::DistanceMap, layer: usize) -> Picture {
    let c = dm.resolution;
    let layer = layer.min(dm.layers.saturating_sub(1));
    let r = dm.radius.max(1e-9) as f32;
    let mut rgba = Vec::with_capacity(6 * c * c * 4);
    for row in (0..c).rev() {
        for face in 0..6 {
            for col in 0..c {
                let s = dm.texels[((layer * 6 + face) * c + row) * c + col][3];
                let [cr, cg, cb] = if s > 0.0 {
                    heat(0.15 + 0.85 * (s / r))
                } else if s < 0.0 {
                    let t = (-s / r).clamp(0.0, 1.0);
                    [40, (60.0 + 100.0 * t) as u8, (140.0 + 115.0 * t) as u8]
                } else {
                    [0, 0, 0]
                };
                rgba.extend([cr, cg, cb, 255]);
            }
        }
    }
    Picture {
        width: 6 * c as u32,
        height: c as u32,
        rgba,
        legend: format!(
            "layer {layer} of {}, faces +x −x +y −y +z −z: glass by distance (white {r:.3}), occluders blue, none black",
            dm.layers
        ),
    }
}

/// A grid through a colour map, drawn with y up.
fn scalar_picture(g: &Grid, colour: impl Fn(f32) -> [u8; 3]) -> Picture {
    let rgba = flip_rows(g.cols, g.rows, |t| {
        let [r, gr, b] = colour(g.data[t]);
        [r, gr, b, 255]
    });
    Picture {
        width: g.cols as u32,
        height: g.rows as u32,
        rgba,
        legend: String::new(),
    }
}

/// RGBA rows of a row-major `cols x rows` buffer (row 0 at y = 0), top row first.
fn flip_rows(cols: usize, rows: usize, texel: impl Fn(usize) -> [u8; 4]) -> Vec<u8> {
    let mut out = Vec::with_capacity(cols * rows * 4);
    for i in (0..rows).rev() {
        for j in 0..cols {
            out.extend(texel(i * cols + j));
        }
    }
    out
}

/// Black, red, orange, yellow, white over [0, 1].
fn heat(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 5] = [
        [0.0, 0.0, 0.0],
        [0.55, 0.05, 0.1],
        [0.95, 0.45, 0.05],
        [1.0, 0.85, 0.25],
        [1.0, 1.0, 1.0],
    ];
    ramp(&STOPS, t)
}

/// Blue at -1, white at 0, red at +1.
fn diverging(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 3] = [[0.15, 0.3, 0.85], [0.97, 0.97, 0.97], [0.85, 0.15, 0.1]];
    ramp(&STOPS, 0.5 + 0.5 * t)
}

fn ramp(stops: &[[f32; 3]], t: f32) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (stops.len() - 1) as f32;
    let k = (x.floor() as usize).min(stops.len() - 2);
    let f = x - k as f32;
    std::array::from_fn(|c| ((stops[k][c] * (1.0 - f) + stops[k + 1][c] * f) * 255.0).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use caustics_core::scene::Scene;

    #[test]
    fn ramps_span_their_ends() {
        assert_eq!(heat(0.0), [0, 0, 0]);
        assert_eq!(heat(1.0), [255, 255, 255]);
        assert_eq!(heat(f32::NAN), [0, 0, 0]);
        assert_eq!(diverging(0.0), [247, 247, 247]);
    }

    #[test]
    fn pictures_are_drawn_with_y_up() {
        let g = Grid::from_fn(2, 2, |i, _| i as f32);
        let p = scalar_picture(&g, |v| [(v * 255.0) as u8, 0, 0]);
        // Row 1 (y high) comes first.
        assert_eq!(&p.rgba[..4], &[255, 0, 0, 255]);
        assert_eq!(&p.rgba[8..12], &[0, 0, 0, 255]);
    }

    #[test]
    fn the_walls_fold_out_against_their_floor_edges() {
        // A 3 x 2 floor map over a 3 m square, 2 m deep: texels of 1 m, two rows on each wall.
        let mut floor = CausticsMap::new(3, 2, 3.0);
        floor.texels[0] = [1.0; 3]; // (x, y) = (0.5, 0.5)
        let mut walls = WallMaps::for_floor_map(3, 2, 3.0, 2.0);
        assert_eq!(walls.get(Wall::X1).rows, 2);
        // Wall x1, its foot, along y = 1.5 (its second column); wall y1, its top row, along x = 0.5.
        walls.get_mut(Wall::X1).texels[1] = [2.0; 3];
        walls.get_mut(Wall::Y1).texels[3] = [4.0; 3];
        let p = box_picture(&floor, &walls).unwrap();
        assert_eq!((p.width, p.height), (3 + 4, 2 + 4));
        let at = |x: usize, y: usize| {
            let k = ((p.height as usize - 1 - y) * p.width as usize + x) * 4;
            [p.rgba[k], p.rgba[k + 1], p.rgba[k + 2]]
        };
        // One ramp, white at 4.
        assert_eq!(at(2, 2 + 2 + 1), heat(1.0), "wall y1's top row, outermost");
        assert_eq!(
            at(2 + 3, 2 + 1),
            heat(0.5),
            "wall x1's foot, beside the floor's x = size edge"
        );
        assert_eq!(at(2, 2), heat(0.25), "the floor's first texel");
        assert_eq!(at(0, 0), [20, 30, 70], "a corner");
        assert_eq!(at(1, 2), heat(0.0), "wall x0, dark");
        // Walls that are not the floor map's are refused.
        let other = WallMaps::for_floor_map(4, 2, 3.0, 2.0);
        assert!(box_picture(&floor, &other).is_none());
    }

    #[test]
    fn every_yuksel_buffer_is_computed() {
        let scene = Scene::builtin("pool").unwrap();
        let water = scene.water.as_ref().unwrap();
        let surface = water.surface_at(0.0).unwrap();
        let choice = TechniqueChoice::parse("yuksel:n=5,m=4", 1).unwrap();
        for b in Buffer::available(&choice, SceneHas::of(&scene)) {
            let input = BufferInput {
                choice: &choice,
                scene: &scene,
                water: Some((water, surface.as_ref())),
                light: scene.light.direction,
                map_size: 32,
            };
            let p = buffer_picture(b, &input).unwrap();
            assert_eq!(
                p.rgba.len(),
                (p.width * p.height * 4) as usize,
                "{}",
                b.name()
            );
            assert!(p.width >= 32 && p.height >= 32);
        }
    }

    #[test]
    fn every_caustic_triangles_buffer_is_computed_on_the_glass_scene() {
        let scene = Scene::builtin("glass").unwrap();
        let choice =
            TechniqueChoice::parse("caustic-triangles:photon_image=32,cube_resolution=32", 1)
                .unwrap();
        let available = Buffer::available(&choice, SceneHas::of(&scene));
        assert!(
            !available.contains(&Buffer::Heights),
            "no water, no heights"
        );
        for b in available {
            let input = BufferInput {
                choice: &choice,
                scene: &scene,
                water: None,
                light: scene.light.direction,
                map_size: 32,
            };
            let p = buffer_picture(b, &input).unwrap();
            assert_eq!(
                p.rgba.len(),
                (p.width * p.height * 4) as usize,
                "{}",
                b.name()
            );
            // Not blank: the generator is in every buffer.
            let lit = p
                .rgba
                .chunks(4)
                .filter(|t| t[0] > 0 || t[1] > 0 || t[2] > 0)
                .count();
            assert!(lit > 0, "{} is blank", b.name());
        }
    }

    fn not_blank(p: &Picture) -> usize {
        assert_eq!(p.rgba.len(), (p.width * p.height * 4) as usize);
        p.rgba
            .chunks(4)
            .filter(|t| t[0] > 40 || t[1] > 40 || t[2] > 40)
            .count()
    }

    fn input_for<'a>(
        choice: &'a TechniqueChoice,
        scene: &'a Scene,
        surface: Option<&'a dyn Surface>,
    ) -> BufferInput<'a> {
        BufferInput {
            choice,
            scene,
            water: scene.water.as_ref().zip(surface),
            light: scene.light.direction,
            map_size: 32,
        }
    }

    #[test]
    fn buffers_are_named_on_the_command_line_by_their_keys() {
        let scene = Scene::builtin("pool").unwrap();
        let cascaded = TechniqueChoice::parse("cascaded", 1).unwrap();
        let available = Buffer::available(&cascaded, SceneHas::of(&scene));
        assert_eq!(
            Buffer::parse("cascade:2", &available).unwrap(),
            Buffer::CascadeMap(2)
        );
        assert_eq!(
            Buffer::parse("cascade", &available).unwrap(),
            Buffer::CascadeMap(0)
        );
        assert_eq!(
            Buffer::parse("heights", &available).unwrap(),
            Buffer::Heights
        );
        let err = Buffer::parse("photon-hits", &available)
            .unwrap_err()
            .to_string();
        assert!(err.contains("heights, cascade:0"), "{err}");
        assert!(Buffer::parse("cascade:x", &available).is_err());
        let yuksel = TechniqueChoice::parse("yuksel", 1).unwrap();
        for b in Buffer::available(&yuksel, SceneHas::of(&scene)) {
            let all = Buffer::available(&yuksel, SceneHas::of(&scene));
            assert_eq!(Buffer::parse(&b.key(), &all).unwrap(), b);
        }
    }

    #[test]
    fn caustic_triangles_shows_the_water_generators_photons() {
        let scene = Scene::builtin("pool").unwrap();
        let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
        let choice = TechniqueChoice::parse("caustic-triangles:photon_image=32", 1).unwrap();
        let available = Buffer::available(&choice, SceneHas::of(&scene));
        assert!(
            !available.contains(&Buffer::DistanceLayer(0)),
            "{available:?}"
        );
        let input = input_for(&choice, &scene, Some(surface.as_ref()));
        for b in available {
            let p = buffer_picture(b, &input).unwrap();
            assert!(not_blank(&p) > 0, "{} is blank", b.name());
            if b != Buffer::Heights {
                assert_eq!(
                    (p.width, p.height),
                    (33, 33),
                    "{}: the (P+1)² lattice",
                    b.name()
                );
            }
        }
    }

    #[test]
    fn cascade_maps_show_caustics_in_the_cameras_view() {
        let mut scene = Scene::builtin("pool").unwrap();
        scene.camera.width = 64;
        scene.camera.height = 36;
        let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
        let choice = TechniqueChoice::parse("cascaded:resolution=64", 1).unwrap();
        let available = Buffer::available(&choice, SceneHas::of(&scene));
        assert!(available.contains(&Buffer::CascadeMap(0)), "{available:?}");
        let input = input_for(&choice, &scene, Some(surface.as_ref()));
        // The pool is close to the camera: the nearest cascade holds it.
        let p = buffer_picture(Buffer::CascadeMap(0), &input).unwrap();
        assert_eq!((p.width, p.height), (64, 36), "the eye's image");
        assert!(not_blank(&p) > 64 * 36 / 4, "cascade 0 is nearly blank");
        let Err(err) = buffer_picture(Buffer::CascadeMap(4), &input) else {
            panic!("cascade 4 of 0..3 drawn");
        };
        assert!(err.to_string().contains("4 cascades"), "{err}");
    }

    #[test]
    fn volumes_shows_each_objects_caustics_map() {
        let scene = Scene::builtin("objects").unwrap();
        let surface = scene.water.as_ref().unwrap().surface_at(0.5).unwrap();
        let choice = TechniqueChoice::parse("volumes:planes=3,texture=32,shadow=0", 1).unwrap();
        assert!(
            Buffer::available(&choice, SceneHas::of(&scene)).contains(&Buffer::ObjectCaustics(0))
        );
        let input = input_for(&choice, &scene, Some(surface.as_ref()));
        for k in 0..scene.objects.len() as u32 {
            let p = buffer_picture(Buffer::ObjectCaustics(k), &input).unwrap();
            assert_eq!((p.width, p.height), (32, 32));
            assert!(not_blank(&p) > 16, "object {k}'s map is blank");
        }
        let k = scene.objects.len() as u32;
        assert!(buffer_picture(Buffer::ObjectCaustics(k), &input).is_err());
        // Without objects there is no object map to offer.
        let pool = Scene::builtin("pool").unwrap();
        assert!(
            !Buffer::available(&choice, SceneHas::of(&pool)).contains(&Buffer::ObjectCaustics(0))
        );
    }

    #[test]
    fn a_point_light_shows_its_light_cube_map() {
        let mut scene = Scene::builtin("glass").unwrap();
        let choice = TechniqueChoice::parse(
            "caustic-triangles:photon_image=32,cube_resolution=32,light_cube=64",
            1,
        )
        .unwrap();
        assert!(!Buffer::available(&choice, SceneHas::of(&scene)).contains(&Buffer::LightCube));
        let sun = buffer_picture(Buffer::LightCube, &input_for(&choice, &scene, None));
        assert!(sun.is_err(), "the sun has no light cube map");
        // docs/scenes/glass-lamp.toml's lamp.
        scene.light.position = Some(DVec3::new(0.15, 0.25, 0.75));
        assert!(Buffer::available(&choice, SceneHas::of(&scene)).contains(&Buffer::LightCube));
        let p = buffer_picture(Buffer::LightCube, &input_for(&choice, &scene, None)).unwrap();
        assert_eq!((p.width, p.height), (6 * 64, 64));
        assert!(not_blank(&p) > 0, "no caustic on the light cube map");
    }

    /// The value `v / top` a heat-ramp colour stands for: the nearest of 4096 points on the ramp.
    fn unheat(rgb: &[u8]) -> f32 {
        (0..=4096)
            .map(|k| k as f32 / 4096.0)
            .min_by_key(|&t| {
                heat(t)
                    .iter()
                    .zip(rgb)
                    .map(|(a, b)| a.abs_diff(*b) as u32)
                    .sum::<u32>()
            })
            .unwrap()
    }

    /// The pool with its water made flat: every buffer's value is known without a simulation.
    fn flat_pool() -> Scene {
        let mut scene = Scene::builtin("pool").unwrap();
        scene.water.as_mut().unwrap().source = caustics_core::scene::WaterSource::Flat;
        scene
    }

    /// Under flat water each yuksel sample carries its share of flat water's flux (1 once times
    /// k²: the flux picture is one colour, the ramp at 1 / 1.5), each of a pixel's k × k samples
    /// lands at its own offset, the same in every pixel (a pattern of period k), and with one sample
    /// a pixel pass 1 puts it into the one or two channels that offset straddles, the same in
    /// every texel: each channel's picture is black or uniformly white, and a wrong channel,
    /// offset or flux changes the colours.
    #[test]
    fn yuksel_buffers_under_flat_water_show_its_uniform_light() {
        let scene = flat_pool();
        let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
        let choice = TechniqueChoice::parse("yuksel:n=5,m=4", 1).unwrap();
        let input = input_for(&choice, &scene, Some(surface.as_ref()));
        let flux = buffer_picture(Buffer::YukselFlux, &input).unwrap();
        let expect = heat(1.0 / 1.5);
        let off = flux
            .rgba
            .chunks(4)
            .map(|t| (0..3).map(|c| t[c].abs_diff(expect[c])).max().unwrap())
            .max()
            .unwrap();
        eprintln!("flux picture: largest step from the ramp at 1 / 1.5: {off}");
        // measured 0 steps
        assert_eq!(off, 0, "flux picture departs from flat water's flux");
        // Each pixel's k × k samples sit at their own places in it, the same in every pixel.
        let offset = buffer_picture(Buffer::YukselOffset, &input).unwrap();
        let k = yuksel::DEFAULT_SUBSAMPLES as usize;
        let w = offset.width as usize;
        let texel = |y: usize, x: usize| &offset.rgba[(y * w + x) * 4..(y * w + x) * 4 + 4];
        for y in 0..offset.height as usize {
            for x in 0..w {
                assert_eq!(texel(y, x), texel(y % k, x % k), "offset at ({y}, {x})");
            }
        }
        assert_ne!(
            texel(0, 0),
            texel(0, 1),
            "the samples of a pixel at one place"
        );
        // One sample a pixel: it lands whole in the one or two channels its offset straddles.
        let one = TechniqueChoice::parse("yuksel:n=5,m=4,subsamples=1", 1).unwrap();
        let input = input_for(&one, &scene, Some(surface.as_ref()));
        let mut lit = Vec::new();
        for k in 0..5 {
            let p = buffer_picture(Buffer::YukselChannel(k), &input).unwrap();
            let white = p
                .rgba
                .chunks(4)
                .filter(|t| t[..3] == [255, 255, 255])
                .count();
            let black = p.rgba.chunks(4).filter(|t| t[..3] == [0, 0, 0]).count();
            let n = p.rgba.len() / 4;
            eprintln!("channel {k}: {white} white, {black} black of {n}");
            assert_eq!(white + black, n, "channel {k}: not one value");
            if white > 0 {
                lit.push(k);
            }
        }
        assert!((1..=2).contains(&lit.len()), "lit channels {lit:?}");
    }

    /// Under flat water the nearest cascade's map is the flat water's irradiance, 1 (on the ramp's
    /// middle, 1 of a top of 2), up to the splat's sampling, where that cascade lights the view:
    /// the mean value read back from the picture's colours.
    #[test]
    fn the_cascade_map_under_flat_water_reads_one() {
        let mut scene = flat_pool();
        scene.camera.width = 64;
        scene.camera.height = 36;
        scene.water.as_mut().unwrap().absorption = DVec3::ZERO;
        // The floor alone: a wall under flat water holds tan θt, not one.
        scene.floor.walls = false;
        let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
        let choice = TechniqueChoice::parse("cascaded:resolution=64", 1).unwrap();
        let input = input_for(&choice, &scene, Some(surface.as_ref()));
        let p = buffer_picture(Buffer::CascadeMap(0), &input).unwrap();
        let values: Vec<f32> = p
            .rgba
            .chunks(4)
            .filter(|t| t[..3] != [20, 30, 70])
            .map(|t| 2.0 * unheat(t))
            .collect();
        // Pixels beyond cascade 0's far plane take no light from it (black).
        let lit: Vec<f32> = values.iter().copied().filter(|&v| v > 0.5).collect();
        let mean = lit.iter().sum::<f32>() / lit.len() as f32;
        eprintln!(
            "cascade 0 under flat water: {} of {} pixels lit, mean {mean:.4}",
            lit.len(),
            values.len()
        );
        assert!(lit.len() > 64 * 36 / 2, "cascade 0 is nearly empty");
        // measured 1.0073 over 2108 of 2304 pixels
        assert!((mean - 1.0).abs() < 0.03, "mean {mean}");
    }

    /// Under flat water caustic-triangles' water photons all carry the same power (a white power
    /// picture) and land on the lattice shifted by the refracted sun: the hit picture's red and
    /// green are the floor's x and y, so they step by one lattice cell a column and a row.
    #[test]
    fn caustic_triangles_photons_under_flat_water_lie_on_the_shifted_lattice() {
        let scene = flat_pool();
        let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
        let choice = TechniqueChoice::parse("caustic-triangles:photon_image=32", 1).unwrap();
        let input = input_for(&choice, &scene, Some(surface.as_ref()));
        let power = buffer_picture(Buffer::PhotonPower, &input).unwrap();
        let white = power
            .rgba
            .chunks(4)
            .filter(|t| t[..3] == [255, 255, 255])
            .count();
        eprintln!("photon power: {white} of {} white", power.rgba.len() / 4);
        assert_eq!(white, power.rgba.len() / 4, "photon powers differ");
        let hits = buffer_picture(Buffer::PhotonHits, &input).unwrap();
        let w = hits.width as usize;
        let at = |i: usize, j: usize, c: usize| hits.rgba[(i * w + j) * 4 + c] as f64;
        // One lattice cell in colour steps: 255 / P of the square (P + 1 vertices span it).
        let cell = 255.0 / (w - 1) as f64;
        let (mut worst, mut steps) = (0.0f64, 0usize);
        for i in 0..w {
            for j in 1..w {
                let x = (at(i, j - 1, 0), at(i, j, 0));
                let y = (at(j, i, 1), at(j - 1, i, 1));
                // Where the shifted lattice wraps or leaves the square (clamped to 0 or 255), the
                // step is not a cell.
                for (a, b) in [x, y] {
                    if b > a && a > 0.0 && b < 255.0 {
                        worst = worst.max((b - a - cell).abs());
                        steps += 1;
                    }
                }
            }
        }
        eprintln!("photon hits: {steps} steps of {cell:.2}, worst departure {worst:.2}");
        assert!(steps > w * (w - 1), "too few steps on the lattice: {steps}");
        // Colours are whole steps: a cell of 7.97 steps is 7 or 8 (measured worst 0.97 over 2013
        // steps).
        assert!(worst < 1.0, "hits off the lattice by {worst} steps");
    }

    #[test]
    fn eye_space_images_mark_texels_without_a_value() {
        let image = EyeSpaceCaustics {
            width: 2,
            height: 1,
            texels: vec![[1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, -1.0]],
        };
        let p = eye_picture(&image);
        assert_eq!(&p.rgba[4..8], &[20, 30, 70, 255]);
        assert_ne!(&p.rgba[..4], &[20, 30, 70, 255]);
    }
}
