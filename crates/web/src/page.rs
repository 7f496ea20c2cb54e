//! The page's state and what its script calls: start on a canvas, one frame per animation frame,
//! the pointer, the technique menu, and a status for the page's overlay and its tests.

use caustics_core::orbit::{OrbitCamera, Sun, pick_water};
use caustics_core::render::RenderOptions;
use caustics_core::scene::Scene;
use caustics_core::techniques::{self, Spec, describe};
use caustics_gpu::renderer::{Renderer, TechniqueSpec};
use caustics_gpu::{GpuContext, GpuOptions, TrafficCounts};
use glam::DVec2;
use serde::Serialize;
use wasm_bindgen::prelude::*;

use crate::blit::Blit;
use crate::water::PageWater;

/// A side without a technique: its floor lit as through flat water, its view through the same
/// waves (what the page's test compares a technique's floor with).
const NONE: &str = "none";

/// Pixels between the two halves of a split view.
const GAP: u32 = 2;

/// What a pointer drag does, chosen where it starts.
#[derive(Clone, Copy, PartialEq)]
enum Drag {
    /// Drops ripples along the way (it started on the water).
    Water {
        last: DVec2,
    },
    Orbit,
    Sun,
}

/// Sizes for the adapter: a software one (SwiftShader, a fallback adapter) renders a sixteenth of
/// the canvas's pixels and a small map (a frame of 200 x 77 pixels costs 250 to 500 ms in headless
/// Chromium on SwiftShader, docs/web.md); a GPU renders the canvas's pixels and the scene's own
/// map, two samples per pixel side (the viewer's defaults).
#[derive(Clone, Copy, Debug, Serialize)]
struct Quality {
    /// The image's pixels per canvas pixel, along each axis.
    scale: f64,
    map: u32,
    supersampling: u32,
    /// The water's normals filtered by each sample's footprint (`RenderOptions::filter_water`).
    filter_water: bool,
}

#[wasm_bindgen]
pub struct Page {
    ctx: GpuContext,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    blit: Blit,
    renderer: Renderer,
    scene: Scene,
    orbit: OrbitCamera,
    sun: Sun,
    water: PageWater,
    sides: Vec<Option<TechniqueSpec>>,
    labels: Vec<String>,
    quality: Quality,
    software: bool,
    drag: Option<(Drag, f64, f64)>,
    last_ms: Option<f64>,
    /// Seconds of water time a frame, where fixed (the tests' repeatable water).
    fixed_step: Option<f64>,
    /// Smoothed time between frames, milliseconds.
    frame_ms: f64,
    /// Frames in a row the canvas gave no texture for (its surface lost or outdated).
    lost: u32,
    /// Set by the queue once the work submitted before [`Page::settle`] is done.
    settled: std::sync::Arc<std::sync::atomic::AtomicBool>,
    frames: u64,
    /// What the page renders (water source, techniques, sizes), and the frame it last changed.
    rendering: (String, u64),
    /// The frame and the traffic from which frames count as steady: a few frames after the last
    /// change, once its resources (pipelines, textures, bind groups) are made.
    steady_from: Option<(u64, TrafficCounts)>,
}

fn js(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A parameter as the page's menu builds its control.
#[derive(Serialize)]
struct ParamJs {
    key: &'static str,
    label: &'static str,
    /// `int`, `float`, `bool`, `choice`.
    kind: &'static str,
    min: Option<f64>,
    max: Option<f64>,
    step: Option<f64>,
    choices: Vec<&'static str>,
    /// The value when not given; `None` when the technique chooses (`auto`).
    default: Option<toml::Value>,
    auto: Option<&'static str>,
    unit: &'static str,
    doc: &'static str,
}

#[derive(Serialize)]
struct TechniqueJs {
    name: &'static str,
    paper: &'static str,
    summary: &'static str,
    params: Vec<ParamJs>,
}

fn param_js(p: &describe::Param) -> Option<ParamJs> {
    let (kind, min, max, step, choices) = match p.kind {
        describe::Kind::Int {
            min,
            max,
            parity,
            power_of_two: _,
        } => (
            "int",
            Some(min as f64),
            Some(max as f64),
            Some(if parity.is_some() { 2.0 } else { 1.0 }),
            Vec::new(),
        ),
        describe::Kind::Float { min, max } => ("float", Some(min), Some(max), None, Vec::new()),
        describe::Kind::Bool => ("bool", None, None, None, Vec::new()),
        describe::Kind::Choice(c) => ("choice", None, None, None, c.to_vec()),
        // A file's path means nothing on a page.
        describe::Kind::Path => return None,
    };
    Some(ParamJs {
        key: p.key,
        label: p.label,
        kind,
        min,
        max,
        step,
        choices,
        default: p.default.value(),
        auto: match p.default {
            describe::ParamDefault::Auto(how) => Some(how),
            _ => None,
        },
        unit: p.unit,
        doc: p.doc,
    })
}

#[wasm_bindgen]
impl Page {
    /// The built-in scene `scene` (pool, shore, reef, underwater) on `canvas`, with technique `technique`
    /// (`name` or `name:key=value,...`; empty: the first the page offers) alone. Fails, naming why, where WebGPU or an adapter is
    /// missing or the scene has no water.
    pub async fn start(
        canvas: web_sys::HtmlCanvasElement,
        scene: String,
        technique: String,
    ) -> Result<Page, JsError> {
        console_error_panic_hook::set_once();
        let scene = Scene::builtin(&scene).map_err(js)?;
        let Some(water) = &scene.water else {
            return Err(js(format!(
                "scene `{}` has no water: the page shows the water scenes (pool, shore, reef, underwater)",
                scene.name
            )));
        };
        let water = PageWater::new(water, scene.time);
        let (width, height) = (canvas.width().max(1), canvas.height().max(1));
        let options = GpuOptions::default();
        let instance = GpuContext::instance(&options).map_err(js)?;
        let surface = instance
            .create_surface(wgpu::SurfaceTarget::Canvas(canvas))
            .map_err(|e| js(format!("the canvas cannot show WebGPU: {e}")))?;
        let ctx = GpuContext::create(&options, Some((&instance, &surface)))
            .await
            .map_err(|e| match e {
                caustics_gpu::GpuError::NoAdapter { .. } => js(
                    "this browser has WebGPU but gave the page no GPU adapter (a blocklisted or \
                     disabled GPU: chrome://gpu or about:support says why)",
                ),
                e => js(e),
            })?;
        let caps = surface.get_capabilities(&ctx.adapter);
        // The final image holds sRGB-encoded values: a format that does not encode them again.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or(caps.formats.first().copied())
            .ok_or_else(|| js("the canvas offers no texture format"))?;
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width,
            height,
            present_mode: wgpu::PresentMode::Fifo,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        surface.configure(&ctx.device, &config);
        let software = ctx.info.device_type == wgpu::DeviceType::Cpu
            || ctx.info.name.to_lowercase().contains("swiftshader");
        let quality = if software {
            Quality {
                scale: 0.25,
                map: 128,
                supersampling: 1,
                filter_water: false,
            }
        } else {
            Quality {
                scale: 1.0,
                map: scene.caustics.width.max(scene.caustics.height),
                supersampling: 2,
                filter_water: false,
            }
        };
        let blit = Blit::new(&ctx, format);
        let renderer = Renderer::new(&ctx).map_err(js)?;
        let mut page = Page {
            orbit: OrbitCamera::from_scene(&scene.camera, scene.size),
            sun: Sun::from_direction(scene.light.direction),
            rendering: (String::new(), 0),
            steady_from: None,
            ctx,
            surface,
            config,
            blit,
            renderer,
            scene,
            water,
            sides: Vec::new(),
            labels: Vec::new(),
            quality,
            software,
            drag: None,
            last_ms: None,
            fixed_step: None,
            lost: 0,
            settled: Default::default(),
            frame_ms: 0.0,
            frames: 0,
        };
        // By default the first technique the page offers on the scene (the scenes name the CPU
        // reference as theirs).
        let technique = match technique.is_empty() {
            true => page
                .offered()
                .first()
                .map(|r| r.describe.name.to_string())
                .ok_or_else(|| js("no GPU technique runs on this scene"))?,
            false => technique,
        };
        page.set_sides(&technique, None)?;
        Ok(page)
    }

    /// The techniques the page offers (those with a GPU implementation that run on this scene),
    /// with their parameters, as JSON for the menu.
    pub fn techniques(&self) -> String {
        let list: Vec<TechniqueJs> = self
            .offered()
            .into_iter()
            .map(|r| TechniqueJs {
                name: r.describe.name,
                paper: r.describe.paper,
                summary: r.describe.summary,
                params: r.describe.params.iter().filter_map(param_js).collect(),
            })
            .collect();
        serde_json::to_string(&list).expect("plain data")
    }

    /// Show `left` alone, or `left` and `right` side by side (`name` or `name:key=value,...`
    /// each, or `none`: lit as through flat water, over the same moving surface). A spelling the registry does not know, or a technique without a GPU implementation,
    /// is refused with the reason and nothing changes.
    pub fn set_sides(&mut self, left: &str, right: Option<String>) -> Result<(), JsError> {
        let mut sides = Vec::new();
        let mut labels = Vec::new();
        for s in std::iter::once(left).chain(right.as_deref()) {
            if s == NONE {
                labels.push(NONE.to_string());
                sides.push(None);
                continue;
            }
            let spec: Spec = s.parse().map_err(js)?;
            if caustics_gpu::registry::find(spec.name()).is_none() {
                return Err(js(format!(
                    "`{}` has no GPU implementation; the page runs the GPU techniques",
                    spec.name()
                )));
            }
            labels.push(s.to_string());
            sides.push(Some(TechniqueSpec::from(&spec)));
        }
        self.sides = sides;
        self.labels = labels;
        Ok(())
    }

    /// The canvas's new size in pixels (at most the adapter's largest texture a side).
    pub fn resize(&mut self, width: u32, height: u32) {
        let max = self.ctx.limits().max_texture_dimension_2d;
        let (width, height) = (width.clamp(1, max), height.clamp(1, max));
        if (self.config.width, self.config.height) != (width, height) {
            self.config.width = width;
            self.config.height = height;
            self.surface.configure(&self.ctx.device, &self.config);
        }
    }

    /// Override the adapter's sizes: the image's pixels per canvas pixel, the map's side and the
    /// samples per pixel side (each ignored when 0).
    pub fn set_quality(&mut self, scale: f64, map: u32, supersampling: u32) {
        if scale > 0.0 {
            self.quality.scale = scale.clamp(0.05, 2.0);
        }
        if map > 0 {
            self.quality.map = map.clamp(8, 4096);
        }
        if supersampling > 0 {
            self.quality.supersampling = supersampling.clamp(1, 8);
        }
    }

    /// Shade the far water with its normals filtered by each sample's footprint: steadier in
    /// motion under the horizon, off by default (docs/maintainers/look.md).
    pub fn set_filter_water(&mut self, on: bool) {
        self.quality.filter_water = on;
    }

    /// Multiply the water's heights (0: flat water, the page's control for caustics' contrast).
    pub fn set_amplitude(&mut self, amplitude: f64) {
        self.water.amplitude = amplitude.max(0.0);
    }

    /// Advance the water by `seconds` a frame whatever the frame's time (0: real time), so that
    /// two pages show the same water at the same frame.
    pub fn set_fixed_step(&mut self, seconds: f64) {
        self.fixed_step = (seconds > 0.0).then_some(seconds);
    }

    /// Calm the ripples: the water stands still until the next click.
    pub fn calm(&mut self) {
        self.water.calm();
    }

    /// Render one frame at page time `now_ms` (`requestAnimationFrame`'s clock) and show it.
    /// Returns whether the canvas showed it (it skips a frame whose surface was outdated; a
    /// surface lost three frames in a row is an error).
    pub fn frame(&mut self, now_ms: f64) -> Result<bool, JsError> {
        let dt = match (self.fixed_step, self.last_ms) {
            (Some(step), _) => step,
            (None, Some(t)) => ((now_ms - t) / 1000.0).clamp(0.0, 0.1),
            (None, None) => 0.0,
        };
        if let Some(t) = self.last_ms {
            let ms = now_ms - t;
            self.frame_ms = if self.frames < 2 {
                ms
            } else {
                0.9 * self.frame_ms + 0.1 * ms
            };
        }
        self.last_ms = Some(now_ms);
        self.water.advance(dt);

        let (iw, ih) = self.image_size();
        self.scene.camera = self.orbit.camera(iw, ih);
        self.scene.light.direction = self.sun.direction();
        self.scene.caustics.width = self.quality.map;
        self.scene.caustics.height = self.quality.map;
        let options = RenderOptions {
            supersampling: self.quality.supersampling,
            exposure: self.scene.look.exposure,
            tone_map: self.scene.look.tone_map,
            filter_water: self.quality.filter_water,
        };
        let ctx = &self.ctx;
        self.renderer
            .set_water(ctx, Some(self.water.water()), &self.water.spec())
            .map_err(js)?;
        let (clock, drops) = self.water.take();
        for d in &drops {
            self.renderer.drop_ripple(ctx, d);
        }
        self.renderer.set_techniques(ctx, &self.sides);
        self.renderer
            .render(ctx, &self.scene, clock, &options)
            .map_err(js)?;

        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.lost += 1;
                if self.lost >= 3 {
                    ctx.check().map_err(js)?;
                    return Err(js(
                        "the canvas lost its WebGPU surface three frames in a row (its format or \
                         size refused)",
                    ));
                }
                self.surface.configure(&ctx.device, &self.config);
                return Ok(false);
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                return Ok(false);
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                ctx.check().map_err(js)?;
                return Err(js("the canvas refused a frame"));
            }
        };
        let view = frame.texture.create_view(&Default::default());
        let images: Vec<Option<&wgpu::Texture>> = (0..self.sides.len())
            .map(|k| self.renderer.image(k))
            .collect();
        self.blit.draw(
            ctx,
            &view,
            (self.config.width, self.config.height),
            &images,
            GAP,
        );
        ctx.queue.present(frame);
        self.lost = 0;
        self.frames += 1;
        self.note_steady();
        self.ctx.check().map_err(js)?;
        Ok(true)
    }

    /// Any error the browser reported since the last frame (WebGPU reports them asynchronously,
    /// so the page asks again once the last frame's work is done: [`settle`](Self::settle)).
    pub fn check(&self) -> Result<(), JsError> {
        self.ctx.check().map_err(js)
    }

    /// Ask the queue to say when the work submitted so far is done ([`settled`](Self::settled)).
    pub fn settle(&self) {
        let done = self.settled.clone();
        done.store(false, std::sync::atomic::Ordering::Release);
        self.ctx.queue.on_submitted_work_done(move || {
            done.store(true, std::sync::atomic::Ordering::Release);
        });
    }

    /// Whether the work submitted before the last [`settle`](Self::settle) is done.
    pub fn settled(&self) -> bool {
        self.settled.load(std::sync::atomic::Ordering::Acquire)
    }

    /// A pointer pressed at canvas pixel `(x, y)`: on the water it drops a ripple (and a drag
    /// draws more), elsewhere it orbits; with `sun` (the right button, or shift) it moves the sun.
    /// Returns what the drag does: `water`, `orbit` or `sun`.
    pub fn pointer_down(&mut self, x: f64, y: f64, sun: bool) -> String {
        let drag = if sun {
            Drag::Sun
        } else if let Some(p) = self.pick(x, y) {
            self.water.drop_at(p);
            Drag::Water { last: p }
        } else {
            Drag::Orbit
        };
        self.drag = Some((drag, x, y));
        match drag {
            Drag::Water { .. } => "water",
            Drag::Orbit => "orbit",
            Drag::Sun => "sun",
        }
        .to_string()
    }

    pub fn pointer_move(&mut self, x: f64, y: f64) {
        let Some((drag, x0, y0)) = self.drag else {
            return;
        };
        let (dx, dy) = (x - x0, y - y0);
        let drag = match drag {
            Drag::Orbit => {
                self.orbit.orbit(dx, dy);
                drag
            }
            Drag::Sun => {
                self.sun.drag(dx, dy);
                drag
            }
            // A drop each time the pointer has moved half a drop's radius over the water, so a
            // drag draws a wake rather than a pile of drops in one place.
            Drag::Water { last } => match self.pick(x, y) {
                Some(p) if (p - last).length() > self.water.water().size / 32.0 => {
                    self.water.drop_at(p);
                    Drag::Water { last: p }
                }
                _ => drag,
            },
        };
        self.drag = Some((drag, x, y));
    }

    pub fn pointer_up(&mut self) {
        self.drag = None;
    }

    /// A wheel turn: positive `notches` come closer.
    pub fn zoom(&mut self, notches: f64) {
        self.orbit.zoom(notches);
    }

    /// The page's state as JSON: the adapter, the sizes, the frame time, each pass's GPU time
    /// (where the browser gives timestamps), each side's technique and error, and what the steady
    /// frames created and uploaded.
    pub fn status(&mut self) -> String {
        #[derive(Serialize)]
        struct SideJs<'a> {
            technique: &'a str,
            error: Option<&'a str>,
        }
        #[derive(Serialize)]
        struct StatusJs<'a> {
            adapter: &'a str,
            software: bool,
            timestamps: bool,
            quality: Quality,
            image: (u32, u32),
            /// The orbit camera: yaw and pitch (radians), distance.
            camera: (f64, f64, f64),
            frames: u64,
            frame_ms: f64,
            passes: Vec<(String, f64)>,
            sides: Vec<SideJs<'a>>,
            water: &'static str,
            /// Since the last change of what the page renders: frames, resources created, bytes
            /// uploaded, blocking readbacks.
            steady: (u64, u64, u64, u64),
        }
        let passes = match self.renderer.timer.as_mut() {
            Some(t) => t
                .latest(&self.ctx)
                .iter()
                .map(|p| (p.label.clone(), p.ms))
                .collect(),
            None => Vec::new(),
        };
        let (from, since) = match &self.steady_from {
            Some((frame, t)) => (*frame, self.ctx.traffic().since(t)),
            None => (self.frames, TrafficCounts::default()),
        };
        let status = StatusJs {
            adapter: &self.ctx.info.name,
            software: self.software,
            timestamps: self.ctx.timestamps,
            quality: self.quality,
            image: self.image_size(),
            camera: (self.orbit.yaw, self.orbit.pitch, self.orbit.distance),
            frames: self.frames,
            frame_ms: self.frame_ms,
            passes,
            sides: (0..self.sides.len())
                .map(|k| SideJs {
                    technique: &self.labels[k],
                    error: self.renderer.error(k),
                })
                .collect(),
            water: match self.water.spec() {
                caustics_gpu::renderer::FrameWater::Scene => "scene",
                caustics_gpu::renderer::FrameWater::Ripples { .. } => "ripples",
            },
            steady: (
                self.frames - from,
                since.created() + since.app_created,
                since.uploaded_bytes + since.app_uploaded_bytes,
                since.readbacks,
            ),
        };
        serde_json::to_string(&status).expect("plain data")
    }
}

impl Page {
    /// The registered GPU techniques that run on the scene.
    fn offered(&self) -> Vec<&'static caustics_gpu::technique::Registered> {
        techniques::for_scene(&self.scene)
            .iter()
            .filter_map(|n| caustics_gpu::registry::find(n))
            .collect()
    }

    /// Each side's image size: its share of the canvas at the quality's scale.
    fn image_size(&self) -> (u32, u32) {
        let n = self.sides.len().max(1) as u32;
        let width = self.config.width.saturating_sub(GAP * (n - 1)) / n;
        let s = self.quality.scale;
        (
            ((width as f64 * s).round() as u32).max(16),
            ((self.config.height as f64 * s).round() as u32).max(16),
        )
    }

    /// The water point under canvas pixel `(x, y)`, in whichever side it falls.
    fn pick(&self, x: f64, y: f64) -> Option<DVec2> {
        let n = self.sides.len().max(1) as u32;
        let side_w = (self.config.width.saturating_sub(GAP * (n - 1)) / n).max(1) as f64;
        let k = (x / (side_w + GAP as f64))
            .floor()
            .clamp(0.0, (n - 1) as f64);
        let u = (x - k * (side_w + GAP as f64)) / side_w;
        let v = y / self.config.height.max(1) as f64;
        let (iw, ih) = self.image_size();
        let camera = self.orbit.camera(iw, ih);
        let water = self.water.water();
        pick_water(
            &camera,
            u * iw as f64 - 0.5,
            v * ih as f64 - 0.5,
            water.level(),
            water.size,
        )
    }

    /// Frames count as steady from the third after the last change of what the page renders.
    fn note_steady(&mut self) {
        let key = format!(
            "{:?} {:?} {:?} {:?}",
            self.water.spec(),
            self.labels,
            (self.config.width, self.config.height),
            self.quality
        );
        if key != self.rendering.0 {
            self.rendering = (key, self.frames);
            self.steady_from = None;
        } else if self.steady_from.is_none() && self.frames >= self.rendering.1 + 3 {
            self.steady_from = Some((self.frames, self.ctx.traffic()));
        }
    }
}
