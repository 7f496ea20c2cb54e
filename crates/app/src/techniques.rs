//! Running any technique by name, on the GPU when there is one and on its CPU twin otherwise.

use anyhow::{Context, Result, bail};
use glam::DVec3;

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference_with_walls};
use caustics_core::scene::{Floor, Water, WaterSource};
use caustics_core::techniques::{self, procedural, yuksel};
use caustics_core::walls::WallMaps;
use caustics_core::water::{Surface, sample_grid};
use caustics_gpu::procedural::ProceduralCaustics;
use caustics_gpu::yuksel::{Variant, Yuksel};
use caustics_gpu::{GpuContext, GpuTimer, PassTime};

/// A technique and its parameters, written `name` or `name:key=value,key=value` (e.g.
/// `yuksel:n=15,m=14`, `yuksel-gather`, `procedural-texture:target_resolution=512`).
#[derive(Clone, Debug)]
pub struct Spec {
    pub label: String,
    pub name: String,
    pub params: toml::Table,
    /// `yuksel-gather`: our compute variant.
    pub gather: bool,
}

impl Spec {
    /// The technique a scene file names, with its `[caustics.<name>]` table.
    pub fn from_scene(caustics: &caustics_core::scene::CausticsSettings) -> Result<Self> {
        let mut spec: Spec = caustics.technique.parse()?;
        spec.params = caustics.params.clone();
        Ok(spec)
    }

    /// The name the GPU registry (`caustics_gpu::technique::REGISTRY`) knows it by: the variant
    /// suffix kept (`yuksel-gather`); procedural's variant travels in its parameters.
    pub fn gpu_name(&self) -> String {
        if self.gather {
            format!("{}-gather", self.name)
        } else {
            self.name.clone()
        }
    }

    /// This spec's parameters laid over `base` (a scene's tables): the command line wins.
    pub fn over(mut self, base: &toml::Table) -> Self {
        let mut merged = base.clone();
        for (name, table) in &self.params {
            match (merged.get_mut(name), table) {
                (Some(toml::Value::Table(into)), toml::Value::Table(from)) => {
                    into.extend(from.iter().map(|(k, v)| (k.clone(), v.clone())));
                }
                _ => {
                    merged.insert(name.clone(), table.clone());
                }
            }
        }
        self.params = merged;
        self
    }
}

impl std::str::FromStr for Spec {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        let (name, rest) = s.split_once(':').unwrap_or((s, ""));
        let (base, gather) = match name.strip_suffix("-gather") {
            Some(b) => (b, true),
            None => (name, false),
        };
        // `procedural-vertex`, `procedural-screen`, `procedural-texture`: paper 2's three variants,
        // the `variant` parameter of `[caustics.procedural]`.
        let (base, variant) = match base.strip_prefix("procedural-") {
            Some(v) => match procedural::Variant::parse(v) {
                Some(v) => ("procedural", Some(v)),
                None => bail!(
                    "unknown variant `{v}` of `procedural` in `{name}` (known: procedural-vertex, procedural-screen, procedural-texture)"
                ),
            },
            None => (base, None),
        };
        if techniques::info(base).is_none() {
            bail!(
                "unknown technique `{name}` (known: {})",
                techniques::names().join(", ")
            );
        }
        if gather && base != "yuksel" {
            bail!("only yuksel has a `-gather` variant");
        }
        let mut table = toml::Table::new();
        for kv in rest.split(',').filter(|p| !p.is_empty()) {
            let (k, v) = kv
                .split_once('=')
                .with_context(|| format!("`{kv}` in `{s}`: expected key=value"))?;
            let value: toml::Value = format!("v = {v}")
                .parse::<toml::Table>()
                .ok()
                .and_then(|t| t.get("v").cloned())
                .unwrap_or_else(|| toml::Value::String(v.to_string()));
            table.insert(k.trim().to_string(), value);
        }
        if let Some(v) = variant {
            if let Some(given) = table.get("variant")
                && given.as_str() != Some(v.name())
            {
                bail!(
                    "`{s}`: the name says variant `{}`, the parameters {given}",
                    v.name()
                );
            }
            table.insert("variant".into(), toml::Value::String(v.name().into()));
        }
        let mut params = toml::Table::new();
        params.insert(base.to_string(), toml::Value::Table(table));
        Ok(Spec {
            label: s.to_string(),
            name: base.to_string(),
            params,
            gather,
        })
    }
}

/// The inputs every technique needs.
pub struct Job<'a> {
    pub water: &'a Water,
    pub floor: &'a Floor,
    pub surface: &'a dyn Surface,
    pub light: DVec3,
    pub width: usize,
    pub height: usize,
    pub cells_per_texel: u32,
}

impl<'a> Job<'a> {
    /// A scene's water job: its floor, sun and caustics resolution, the surface as given.
    pub fn of_scene(
        scene: &'a caustics_core::scene::Scene,
        water: &'a Water,
        surface: &'a dyn Surface,
        cells_per_texel: u32,
    ) -> Self {
        Job {
            water,
            floor: &scene.floor,
            surface,
            light: scene.light.direction,
            width: scene.caustics.width as usize,
            height: scene.caustics.height as usize,
            cells_per_texel,
        }
    }
}

pub struct Outcome {
    pub map: CausticsMap,
    /// "GPU" or "CPU".
    pub backend: &'static str,
    /// The pool's walls' maps, from a technique that lights them when the scene's walls are on
    /// (`render --raw-walls`, the final image); `None` from a floor-only technique.
    pub walls: Option<WallMaps>,
}

/// What a technique made of a whole scene: a map of the floor square, or, for `cascaded` (paper 5),
/// an image in the scene camera's screen space. Both light the final image
/// (`caustics_core::render::render_with`, `FinalImage::render_with`) through
/// [`caustics`](Self::caustics).
#[derive(Clone)]
pub enum SceneCaustics {
    Floor(CausticsMap),
    EyeSpace(caustics_core::render::EyeSpaceCaustics),
}

impl SceneCaustics {
    /// A GPU technique's output read back (the viewer's map window, `render --raw`): a floor map of
    /// the water square `size`, or an eye-space image whose texels are the CPU twin's as they are
    /// (flag < 0 where a pixel has no value).
    pub fn read(ctx: &GpuContext, output: caustics_gpu::Output, size: f64) -> Result<Self> {
        let texture = output.texture();
        let texels = ctx.read_rgba_f32(texture)?;
        let (width, height) = (texture.width() as usize, texture.height() as usize);
        Ok(match output {
            caustics_gpu::Output::Floor(_) => SceneCaustics::Floor(CausticsMap {
                width,
                height,
                size,
                texels: texels.iter().map(|t| [t[0], t[1], t[2]]).collect(),
            }),
            caustics_gpu::Output::EyeSpace(_) => {
                SceneCaustics::EyeSpace(caustics_core::render::EyeSpaceCaustics {
                    width,
                    height,
                    texels,
                })
            }
        })
    }

    pub fn caustics(&self) -> caustics_core::render::Caustics<'_> {
        match self {
            SceneCaustics::Floor(m) => caustics_core::render::Caustics::Floor(m),
            SceneCaustics::EyeSpace(e) => caustics_core::render::Caustics::EyeSpace(e),
        }
    }
}

pub struct SceneOutcome {
    pub caustics: SceneCaustics,
    /// "GPU" or "CPU".
    pub backend: &'static str,
    /// As [`Outcome::walls`].
    pub walls: Option<WallMaps>,
}

/// Passes one technique run can time (procedural's texture variant has the most: a target, one
/// downsample per mip level, a resample).
const TIMED_PASSES: u32 = 32;

/// Runs techniques, keeping their GPU pipelines between runs.
pub struct Runner {
    pub gpu: Option<GpuContext>,
    /// Timestamps of the technique passes, once [`time_passes`](Self::time_passes) turned them on.
    timer: Option<GpuTimer>,
    yuksel: Option<Yuksel>,
    procedural: Option<ProceduralCaustics>,
    caustic_triangles: Option<caustics_gpu::caustic_triangles::CausticTriangles>,
    volumes: Option<caustics_gpu::volumes::Volumes>,
    cascaded: Option<caustics_gpu::cascaded::Cascaded>,
}

impl Runner {
    pub fn new(gpu: Option<GpuContext>) -> Self {
        Runner {
            gpu,
            timer: None,
            yuksel: None,
            procedural: None,
            caustic_triangles: None,
            volumes: None,
            cascaded: None,
        }
    }

    /// Time every GPU pass of the techniques run from now on, where the adapter has timestamp
    /// queries (the viewer's overlay); [`take_gpu_times`](Self::take_gpu_times) reads them.
    pub fn time_passes(&mut self) {
        if let Some(ctx) = self.gpu.as_ref().filter(|c| c.timestamps) {
            self.timer = Some(GpuTimer::new(ctx, TIMED_PASSES));
        }
    }

    /// The GPU time of each technique pass run since the last call (empty without timestamps).
    pub fn take_gpu_times(&mut self) -> Result<Vec<PassTime>> {
        match (self.timer.as_mut(), self.gpu.as_ref()) {
            (Some(t), Some(ctx)) => t.read(ctx).context("reading the technique timestamps"),
            _ => Ok(Vec::new()),
        }
    }

    /// As [`run_scene`](Self::run_scene), for every technique, `cascaded` included: its eye-space
    /// image is made for the scene's camera at the camera's resolution.
    pub fn run_scene_caustics(
        &mut self,
        spec: &Spec,
        scene: &caustics_core::scene::Scene,
        surface: Option<&dyn Surface>,
        cells_per_texel: u32,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<SceneOutcome> {
        if spec.name != "cascaded" {
            let o = self.run_scene(spec, scene, surface, cells_per_texel, progress)?;
            return Ok(SceneOutcome {
                caustics: SceneCaustics::Floor(o.map),
                backend: o.backend,
                walls: o.walls,
            });
        }
        let water = match (&scene.water, surface) {
            (Some(w), Some(s))
                if !matches!(
                    w.source,
                    WaterSource::Ocean(_) | WaterSource::HeightField(_)
                ) =>
            {
                sample_grid(s, CASCADED_WATER_GRID, CASCADED_WATER_GRID, w.size)
            }
            _ => caustics_core::techniques::cascaded::water_grid(scene, CASCADED_WATER_GRID)?,
        };
        let outcome = self.run_cascaded(spec, scene, &water)?;
        progress(1, 1);
        Ok(outcome)
    }

    /// Technique `cascaded` (paper 5) on `scene` (its water's parameters, floor, sun and camera) with
    /// the water surface given as a height grid over the scene square: the viewer passes the
    /// surface it animates, [`run_scene_caustics`](Self::run_scene_caustics) the scene's own.
    pub fn run_cascaded(
        &mut self,
        spec: &Spec,
        scene: &caustics_core::scene::Scene,
        water: &Grid,
    ) -> Result<SceneOutcome> {
        use caustics_core::techniques::cascaded;
        let params = cascaded::CascadedParams::from_table(&spec.params)?;
        let setup = cascaded::CascadedSetup::from_scene(scene, &params)?;
        let terrain = scene.floor.terrain.as_ref();
        let (texels, backend) = match &self.gpu {
            Some(ctx) => {
                if self.cascaded.is_none() {
                    self.cascaded = Some(caustics_gpu::cascaded::Cascaded::new(ctx)?);
                }
                let gpu = self.cascaded.as_ref().expect("just made");
                (
                    gpu.caustics_timed(ctx, &setup, water, terrain, self.timer.as_mut())?
                        .image,
                    "GPU",
                )
            }
            None => (cascaded::caustics(&setup, water, terrain).image, "CPU"),
        };
        Ok(SceneOutcome {
            caustics: SceneCaustics::EyeSpace(caustics_core::render::EyeSpaceCaustics {
                width: setup.eye.width,
                height: setup.eye.height,
                texels,
            }),
            backend,
            walls: None,
        })
    }

    /// Run `spec` on a whole scene: the techniques whose generator is the scene's glass objects
    /// (caustic-triangles) as well as those of its water surface.
    pub fn run_scene(
        &mut self,
        spec: &Spec,
        scene: &caustics_core::scene::Scene,
        surface: Option<&dyn Surface>,
        cells_per_texel: u32,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Outcome> {
        use caustics_core::techniques::caustic_triangles as ct;
        techniques::check_light(&spec.name, &scene.light)?;
        match spec.name.as_str() {
            // A scene with water: its surface is the generator (the water photon pass), as on a
            // water job.
            "caustic-triangles" if scene.water.is_some() => {
                let water = scene.water.as_ref().expect("matched");
                if !scene.light.is_sun() {
                    bail!(
                        "scene `{}`: caustic-triangles lights its water surface with the directional sun only (light.position is set)",
                        scene.name
                    );
                }
                let owned;
                let surface = match surface {
                    Some(s) => s,
                    None => {
                        owned = water.surface_at(scene.time)?;
                        owned.as_ref()
                    }
                };
                let job = Job::of_scene(scene, water, surface, cells_per_texel);
                self.run_with_progress(spec, &job, progress)
            }
            "caustic-triangles" => {
                let params = ct::CausticTrianglesParams::from_table(&spec.params)?;
                let Some(ctx) = &self.gpu else {
                    return Ok(Outcome {
                        map: ct::render(scene, &params)?,
                        backend: "CPU",
                        walls: None,
                    });
                };
                if self.caustic_triangles.is_none() {
                    self.caustic_triangles =
                        Some(caustics_gpu::caustic_triangles::CausticTriangles::new(ctx)?);
                }
                let gpu = self.caustic_triangles.as_ref().expect("just made");
                let glass = scene
                    .objects
                    .iter()
                    .filter(|o| matches!(o.material, caustics_core::scene::Material::Glass { .. }))
                    .count();
                if glass == 0 {
                    bail!(
                        "scene `{}` has no glass object: caustic-triangles needs a glass caustic generator",
                        scene.name
                    );
                }
                let mut total: Option<CausticsMap> = None;
                for k in 0..glass {
                    let gs = ct::GlassScene::from_scene(scene, k)?;
                    let dm = ct::DistanceMap::build(
                        &gs,
                        params.cube_resolution as usize,
                        params.layers as usize,
                    );
                    let setup = ct::CausticTrianglesSetup::new(&params, &gs)?;
                    let frame = gpu.frame(ctx, &setup, &dm)?;
                    let mut encoder = ctx.device.create_command_encoder(&Default::default());
                    gpu.encode(
                        &frame,
                        &mut encoder,
                        self.timer.as_mut(),
                        caustics_gpu::caustic_triangles::Reconstruction::Triangles,
                    );
                    if let Some(t) = &self.timer {
                        t.resolve(&mut encoder);
                    }
                    ctx.queue.submit([encoder.finish()]);
                    let map = gpu.read_map(ctx, &frame)?;
                    total = Some(match total {
                        None => map,
                        Some(t) => add_maps(t, &map),
                    });
                    progress(k + 1, glass);
                }
                Ok(Outcome {
                    map: total.expect("one glass object at least"),
                    backend: "GPU",
                    walls: None,
                })
            }
            "reference" if scene.water.is_none() => {
                // A scene of glass objects: the reference is paper 4's photon tracer against the
                // exact geometry, one generator at a time as the technique runs.
                let generators = glass_count(scene)?;
                let options = ct::reference::ReferenceOptions {
                    photons: GLASS_REFERENCE_PHOTONS * cells_per_texel.clamp(1, 16),
                    ..Default::default()
                };
                let mut total: Option<CausticsMap> = None;
                for k in 0..generators {
                    let gs = ct::GlassScene::from_scene(scene, k)?;
                    let map = ct::reference::reference(&gs, &options).map;
                    total = Some(match total {
                        None => map,
                        Some(t) => add_maps(t, &map),
                    });
                    progress(k + 1, generators);
                }
                Ok(Outcome {
                    map: total.expect("one glass object at least"),
                    backend: "CPU",
                    walls: None,
                })
            }
            // Water with diffuse objects under it (`objects`): the truth is the photon reference with
            // mesh receivers (`volumes::reference`), so the objects' shadows are in it, as they are in
            // the floor maps of the techniques that see the objects.
            "reference" if scene.water.is_some() && !scene.objects.is_empty() => {
                use caustics_core::techniques::volumes;
                let water = scene.water.as_ref().expect("matched");
                let owned;
                let surface = match surface {
                    Some(s) => s,
                    None => {
                        owned = water.surface_at(scene.time)?;
                        owned.as_ref()
                    }
                };
                let input = volumes::VolumesInput::from_scene(scene)?;
                let setup = volumes::VolumesSetup::new(&volumes::VolumesParams::default(), &input)?;
                let options = volumes::reference::MeshReferenceOptions {
                    walls: scene.floor.walls,
                    object_maps: false,
                    ..volumes::reference::MeshReferenceOptions::per_texel(
                        &setup,
                        (MESH_REFERENCE_PHOTONS * cells_per_texel.clamp(1, 8)) as f64,
                    )
                };
                let r = volumes::reference::mesh_reference_with_progress(
                    &setup, &input, surface, &options, progress,
                );
                Ok(Outcome {
                    map: r.floor,
                    backend: "CPU",
                    walls: r.walls,
                })
            }
            // Paper 3: its floor map (the illumination volumes cut by the floor, the objects' shadows
            // in it) and, with the scene's walls, the walls' maps (the volumes cut by the walls'
            // planes); the objects' own caustics maps and the refracted view are the technique's
            // (caustics_gpu::volumes, docs/volumes.md).
            "volumes" => {
                use caustics_core::techniques::volumes;
                let (Some(water), Some(surface)) = (&scene.water, surface) else {
                    bail!(
                        "scene `{}` has no water: technique `volumes` casts caustics from a water surface",
                        scene.name
                    );
                };
                let params = volumes::VolumesParams::from_table(&spec.params)?;
                let input = volumes::VolumesInput::from_scene(scene)?;
                let setup = volumes::VolumesSetup::new(&params, &input)?;
                let n = (input.size / setup.lattice.cell).round() as usize;
                let heights = sample_grid(surface, n, n, water.size);
                let (map, walls, backend) = match &self.gpu {
                    Some(ctx) => {
                        if self.volumes.is_none() {
                            self.volumes = Some(caustics_gpu::volumes::Volumes::new(ctx)?);
                        }
                        let v = self.volumes.as_ref().expect("just made");
                        let out = v.run(ctx, &setup, &input, &heights, water.wrap, None)?;
                        (out.floor, out.walls, "GPU")
                    }
                    None => {
                        let out = volumes::caustics(&setup, &input, &heights, water.wrap);
                        (out.floor, out.walls, "CPU")
                    }
                };
                progress(1, 1);
                Ok(Outcome {
                    map,
                    backend,
                    walls,
                })
            }
            "cascaded" => bail!(
                "technique `cascaded` (paper 5) computes caustics in the eye camera's screen space, not \
                 as a map of the floor square (`Runner::run_scene_caustics` returns its image)"
            ),
            _ => {
                let (Some(water), Some(surface)) = (&scene.water, surface) else {
                    bail!(
                        "scene `{}` has no water: technique `{}` computes caustics from a water surface",
                        scene.name,
                        spec.name
                    );
                };
                let job = Job::of_scene(scene, water, surface, cells_per_texel);
                self.run_with_progress(spec, &job, progress)
            }
        }
    }

    pub fn run(&mut self, spec: &Spec, job: &Job) -> Result<Outcome> {
        self.run_with_progress(spec, job, &|_, _| {})
    }

    /// As [`run`](Self::run), reporting `progress(done, total)` where the technique is long (the
    /// reference).
    pub fn run_with_progress(
        &mut self,
        spec: &Spec,
        job: &Job,
        progress: &(dyn Fn(usize, usize) + Sync),
    ) -> Result<Outcome> {
        match spec.name.as_str() {
            "reference" => {
                let input = ReferenceInput {
                    surface: job.surface,
                    water: job.water,
                    floor: job.floor,
                    light: job.light,
                    width: job.width,
                    height: job.height,
                };
                let options = ReferenceOptions {
                    cells_per_texel: job.cells_per_texel,
                    ..Default::default()
                };
                let out = reference_with_walls(&input, &options, progress)?;
                Ok(Outcome {
                    map: out.floor,
                    backend: "CPU",
                    walls: out.walls,
                })
            }
            "yuksel" => {
                if job.floor.walls {
                    tracing::warn!("{}", techniques::floor_only_note(&spec.name));
                }
                if job.floor.terrain.is_some() {
                    bail!(
                        "technique `yuksel` computes caustics on a flat floor (paper 1, §3); this scene has a terrain"
                    );
                }
                let params = yuksel::YukselParams::from_table(&spec.params)?;
                let w = job.water;
                let setup = yuksel::YukselSetup::new(
                    &params,
                    job.width,
                    job.height,
                    w.size,
                    w.depth,
                    w.ior,
                    w.absorption,
                    w.wrap,
                    job.light,
                )?;
                let heights = lattice_heights(w, job.surface, job.width, job.height);
                match &self.gpu {
                    Some(ctx) => {
                        if self.yuksel.is_none() {
                            self.yuksel = Some(Yuksel::new(ctx)?);
                        }
                        let y = self.yuksel.as_ref().expect("just made");
                        let variant = if spec.gather {
                            Variant::Gather
                        } else {
                            Variant::RenderTargets
                        };
                        Ok(Outcome {
                            map: y.caustics_timed(
                                ctx,
                                &setup,
                                &heights,
                                variant,
                                self.timer.as_mut(),
                            )?,
                            backend: "GPU",
                            walls: None,
                        })
                    }
                    None => Ok(Outcome {
                        map: yuksel::caustics(&setup, &heights),
                        backend: "CPU",
                        walls: None,
                    }),
                }
            }
            "procedural" => {
                if job.floor.walls {
                    tracing::warn!("{}", techniques::floor_only_note(&spec.name));
                }
                if job.floor.terrain.is_some() {
                    bail!(
                        "technique `procedural` lights a flat floor at a constant depth (paper 2, \"Our Approach\"); this scene has a terrain"
                    );
                }
                let params = procedural::ProceduralCausticsParams::from_table(&spec.params)?;
                let w = job.water;
                let setup = procedural::ProceduralSetup::new(
                    &params,
                    job.width,
                    job.height,
                    w.size,
                    w.depth,
                    w.absorption,
                    w.wrap,
                    job.light,
                )?;
                let heights = procedural_heights(w, job.surface, &setup);
                let water = procedural::SurfaceInput::Grid(&heights);
                match &self.gpu {
                    Some(ctx) => {
                        if self.procedural.is_none() {
                            self.procedural = Some(ProceduralCaustics::new(ctx)?);
                        }
                        let p = self.procedural.as_ref().expect("just made");
                        Ok(Outcome {
                            map: p.caustics_timed(ctx, &setup, &water, self.timer.as_mut())?,
                            backend: "GPU",
                            walls: None,
                        })
                    }
                    None => Ok(Outcome {
                        map: procedural::caustics(&setup, &water),
                        backend: "CPU",
                        walls: None,
                    }),
                }
            }
            // Paper 4 with the water surface as the caustic generator (the water photon pass, then
            // the technique's vertex irradiance and caustic triangles; docs/caustic-triangles.md).
            "caustic-triangles" => {
                use caustics_core::techniques::caustic_triangles::{CausticTrianglesParams, water};
                if job.floor.terrain.is_some() {
                    bail!(
                        "technique `caustic-triangles` draws the water's caustic triangles on the floor plane z = 0; this scene has a terrain"
                    );
                }
                let params = CausticTrianglesParams::from_table(&spec.params)?;
                let ws =
                    water::WaterSetup::new(&params, job.water, job.light, job.width, job.height)?
                        .with_walls(job.floor.walls);
                let heights = heights_for(job.water, job.surface, job.width, job.height);
                let (map, walls, backend) = match &self.gpu {
                    Some(ctx) => {
                        if self.caustic_triangles.is_none() {
                            self.caustic_triangles =
                                Some(caustics_gpu::caustic_triangles::CausticTriangles::new(ctx)?);
                        }
                        let gpu = self.caustic_triangles.as_ref().expect("just made");
                        let (map, walls) =
                            gpu.water_caustics_walls(ctx, &ws, &heights, self.timer.as_mut())?;
                        (map, walls, "GPU")
                    }
                    None => {
                        let walls = if ws.walls {
                            Some(water::wall_caustics(&ws, &heights)?)
                        } else {
                            None
                        };
                        (water::caustics(&ws, &heights)?.map, walls, "CPU")
                    }
                };
                progress(1, 1);
                Ok(Outcome {
                    map,
                    backend,
                    walls,
                })
            }
            // Paper 3 on a water job alone (no objects to receive it: `caustics compare`, the
            // viewer's water): its floor pass, the illumination volumes cut by the floor, and with
            // the job's walls its wall pass.
            "volumes" => {
                use caustics_core::techniques::volumes;
                if job.floor.terrain.is_some() {
                    bail!(
                        "technique `volumes` draws its floor map on the plane z = 0; this scene has a terrain"
                    );
                }
                let params = volumes::VolumesParams::from_table(&spec.params)?;
                let w = job.water;
                let input = volumes::VolumesInput {
                    objects: Vec::new(),
                    size: w.size,
                    depth: w.depth,
                    ior: w.ior,
                    absorption: w.absorption,
                    light: job.light,
                    camera: DVec3::new(0.5 * w.size, 0.5 * w.size, 2.0 * w.depth + w.size),
                    width: job.width,
                    height: job.height,
                    walls: job.floor.walls,
                };
                let setup = volumes::VolumesSetup::new(&params, &input)?;
                let n = (input.size / setup.lattice.cell).round() as usize;
                let heights = sample_grid(job.surface, n, n, w.size);
                match &self.gpu {
                    Some(ctx) => {
                        if self.volumes.is_none() {
                            self.volumes = Some(caustics_gpu::volumes::Volumes::new(ctx)?);
                        }
                        let v = self.volumes.as_ref().expect("just made");
                        let out = v.run(ctx, &setup, &input, &heights, w.wrap, None)?;
                        Ok(Outcome {
                            map: out.floor,
                            backend: "GPU",
                            walls: out.walls,
                        })
                    }
                    None => {
                        let out = volumes::caustics(&setup, &input, &heights, w.wrap);
                        Ok(Outcome {
                            map: out.floor,
                            backend: "CPU",
                            walls: out.walls,
                        })
                    }
                }
            }
            other => bail!(
                "technique `{other}` is not implemented yet; `caustics techniques` lists what is"
            ),
        }
    }
}

/// Side of the height grid technique `cascaded` reads a water surface through when the scene gives
/// neither an ocean's nor a file's own grid (the shore's ocean is 128²).
const CASCADED_WATER_GRID: usize = 256;

/// The height grid technique `cascaded` reads an animated surface through (the viewer's water): a
/// height-field file's own samples, or the surface sampled `CASCADED_WATER_GRID²` over the square.
pub fn cascaded_heights(water: &Water, surface: &dyn Surface) -> Grid {
    match &water.source {
        WaterSource::HeightField(g) => g.clone(),
        _ => sample_grid(
            surface,
            CASCADED_WATER_GRID,
            CASCADED_WATER_GRID,
            water.size,
        ),
    }
}

/// Photons per texel side of the mesh-receiver reference, per cell per texel of the floor
/// reference: 4 (8² photons per texel at the viewer's 2 cells), stratified, so its noise is a few
/// per cent per texel where the floor reference's triangulation is exact.
const MESH_REFERENCE_PHOTONS: u32 = 4;

/// Photons per side of the light rectangle of one glass generator, per cell per texel, in the
/// glass reference: 128² (2 cells per texel, the viewer's default, gives 256² per glass object,
/// about two seconds for the `glass` scene on two cores).
const GLASS_REFERENCE_PHOTONS: u32 = 128;

fn glass_count(scene: &caustics_core::scene::Scene) -> Result<usize> {
    let n = scene
        .objects
        .iter()
        .filter(|o| matches!(o.material, caustics_core::scene::Material::Glass { .. }))
        .count();
    if n == 0 {
        bail!(
            "scene `{}` has neither water nor a glass object: no caustics to compute",
            scene.name
        );
    }
    Ok(n)
}

fn add_maps(mut total: CausticsMap, map: &CausticsMap) -> CausticsMap {
    for (a, b) in total.texels.iter_mut().zip(&map.texels) {
        for c in 0..3 {
            a[c] += b[c];
        }
    }
    total
}

/// The height field a grid-based technique reads: the file's own samples, or the surface sampled on
/// the map's lattice.
pub fn heights_for(water: &Water, surface: &dyn Surface, width: usize, height: usize) -> Grid {
    match &water.source {
        WaterSource::HeightField(g) => g.clone(),
        _ => sample_grid(surface, width, height, water.size),
    }
}

/// The heights `yuksel` reads: a water that is itself a grid read bicubically (the FFT ocean, the
/// ripples) sampled at its own lattice, so that yuksel's bicubic surface is the water's own;
/// others as [`heights_for`]. Sampled at the map's resolution instead, the 128² ocean is
/// re-interpolated, and its sharpest caustics move (9 % rel. L1 at 60°, deep, 256²; docs/yuksel.md).
pub fn lattice_heights(water: &Water, surface: &dyn Surface, width: usize, height: usize) -> Grid {
    let n = match &water.source {
        WaterSource::Ocean(o) => o.params().resolution,
        WaterSource::Ripple(p) => p.resolution,
        _ => return heights_for(water, surface, width, height),
    };
    sample_grid(surface, n, n, water.size)
}

/// The height grid technique `procedural` reads (the job carries the frozen surface, not its time,
/// so the paper's wave function too is read through a grid): the file's own samples, or the surface
/// sampled at least as finely as the lattice the variant evaluates on (the map, the mesh's vertices,
/// or the texture-space target).
pub fn procedural_heights(
    water: &Water,
    surface: &dyn Surface,
    setup: &procedural::ProceduralSetup,
) -> Grid {
    let n = match setup.variant {
        procedural::Variant::Vertex => setup.mesh + 1,
        procedural::Variant::Screen => 0,
        procedural::Variant::Texture => setup.target,
    };
    match &water.source {
        WaterSource::HeightField(g) => g.clone(),
        _ => sample_grid(surface, setup.width.max(n), setup.height.max(n), water.size),
    }
}
