//! The window and the frame loop: winit for the window and input, egui (through egui-winit and
//! egui-wgpu, on our own wgpu device) for the panel and for drawing the images, and the smoke
//! mode that scripts a run for tests.
//!
//! A frame: run the UI (it edits the [`Model`] and says where the views are), drop the clicked
//! ripples, advance the water, render the scene if anything it depends on changed, refresh the
//! map and buffer pictures if their windows are open, then draw egui (which draws the images) to
//! the window. The images are wgpu textures registered with egui once and rewritten in place, so
//! an image rendered in a frame is shown in that same frame.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, Result, bail};
use glam::DVec2;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

use caustics_core::render::Image;
use caustics_core::scene::Scene;
use caustics_gpu::final_image::FinalImage;
use caustics_gpu::{GpuContext, GpuOptions, GpuTimer};

use super::frame::{Quality, Rendered, SceneRenderer, Slot, TechniqueChoice};
use super::pictures;
use super::ui::{self, Model, Shown, Stats, TextureIds};
use super::water::{SurfaceKey, WaterState};
use super::{ImageOn, ViewArgs};
use crate::techniques::Runner;
use caustics_core::orbit::{OrbitCamera, Sun};
use caustics_core::techniques::buffers::{self, Buffer, BufferInput, SceneHas};

pub fn run(args: ViewArgs) -> Result<()> {
    let event_loop = EventLoop::new().context("cannot connect to the display")?;
    event_loop.set_control_flow(ControlFlow::Wait);
    let mut app = ViewApp {
        args,
        viewer: None,
        error: None,
    };
    event_loop
        .run_app(&mut app)
        .context("the window's event loop failed")?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct ViewApp {
    args: ViewArgs,
    viewer: Option<Viewer>,
    error: Option<anyhow::Error>,
}

impl ApplicationHandler for ViewApp {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.viewer.is_some() || self.error.is_some() {
            return;
        }
        match Viewer::new(event_loop, &self.args) {
            Ok(v) => {
                v.window.request_redraw();
                self.viewer = Some(v);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let Some(v) = self.viewer.as_mut() else {
            return;
        };
        let response = v.egui_state.on_window_event(&v.window, &event);
        match event {
            WindowEvent::CloseRequested => {
                self.error = v.lost.take();
                event_loop.exit();
            }
            WindowEvent::Resized(size) => v.resize(size.width, size.height),
            WindowEvent::RedrawRequested if v.lost.is_some() => {}
            WindowEvent::RedrawRequested => match v.frame() {
                Ok(Flow::Continue) => {}
                Ok(Flow::Exit) => event_loop.exit(),
                Err(e) if v.script.is_none() && device_lost(&e) => {
                    // Nothing can be drawn with a lost device: the title says it, and the window
                    // stays until closed, when the run ends with the error.
                    v.window.set_title(&format!(
                        "caustics view: {} (close the window)",
                        e.root_cause()
                    ));
                    tracing::error!("{e:#}");
                    v.lost = Some(e);
                }
                Err(e) => {
                    if device_lost(&e) {
                        v.window
                            .set_title(&format!("caustics view: {}", e.root_cause()));
                    }
                    self.error = Some(e);
                    event_loop.exit();
                }
            },
            _ => {}
        }
        if response.repaint {
            v.window.request_redraw();
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(v) = self.viewer.as_ref() else {
            return;
        };
        if v.lost.is_some() {
            event_loop.set_control_flow(ControlFlow::Wait);
        } else if v.continuous() {
            v.window.request_redraw();
            event_loop.set_control_flow(ControlFlow::Wait);
        } else if let Some(at) = v.repaint_at {
            event_loop.set_control_flow(ControlFlow::WaitUntil(at));
            if Instant::now() >= at {
                v.window.request_redraw();
            }
        } else {
            event_loop.set_control_flow(ControlFlow::Wait);
        }
    }
}

/// Whether `e` comes from a lost GPU device, which no later frame can recover from.
fn device_lost(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        matches!(
            c.downcast_ref::<caustics_gpu::GpuError>(),
            Some(caustics_gpu::GpuError::DeviceLost(_))
        )
    })
}

enum Flow {
    Continue,
    Exit,
}

/// The smoke mode's script.
struct Script {
    frames: u64,
    screenshot: Option<PathBuf>,
    /// `--cycle-techniques`: the names to cycle through, empty for all the scene offers.
    cycle: Option<Vec<String>>,
    resize_every: Option<u64>,
    drop_every: Option<u64>,
    show_map_at: Option<u64>,
    lose_device_at: Option<u64>,
    /// The window size asked for at the start, which resizes vary around.
    base_size: [u32; 2],
    /// Wall time of each frame, ms, and whether it rendered the scene.
    times: Vec<(f64, bool)>,
    /// GPU time per pass label summed over the frames after the first three, and its count.
    passes: Vec<(String, f64, u32)>,
}

/// An image egui draws from a texture of ours: registered once, rewritten in place, replaced
/// (under the same id) only when its size changes.
struct GpuImage {
    texture: wgpu::Texture,
    id: egui::TextureId,
    /// Whether `texture` is the viewer's own (written by [`set`](Self::set)) rather than the GPU
    /// frame's output ([`show`](Self::show)), which must never be written into.
    own: bool,
}

impl GpuImage {
    fn new(ctx: &GpuContext, renderer: &mut egui_wgpu::Renderer) -> Self {
        let texture = image_texture(ctx, 1, 1);
        write_rgba(ctx, &texture, &[24, 26, 30, 255]);
        // egui's bind group for it.
        ctx.count_app(1, 0);
        let id = renderer.register_native_texture(
            &ctx.device,
            &texture.create_view(&Default::default()),
            wgpu::FilterMode::Linear,
        );
        GpuImage {
            texture,
            id,
            own: true,
        }
    }

    fn set(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        width: u32,
        height: u32,
        rgba: &[u8],
    ) {
        if !self.own || (self.texture.width(), self.texture.height()) != (width, height) {
            self.texture = image_texture(ctx, width, height);
            self.own = true;
            ctx.count_app(1, 0);
            renderer.update_egui_texture_from_wgpu_texture(
                &ctx.device,
                &self.texture.create_view(&Default::default()),
                wgpu::FilterMode::Linear,
                self.id,
            );
        }
        write_rgba(ctx, &self.texture, rgba);
    }

    /// Show picture `p`, and what the panel says of it.
    fn picture(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        p: caustics_core::plot::Picture,
    ) -> Shown {
        self.set(ctx, renderer, p.width, p.height, &p.rgba);
        Shown {
            size: Some([p.width, p.height]),
            legend: p.legend,
            error: None,
        }
    }

    /// Show a texture of the GPU frame as it is: egui is told once per texture, no texel moves.
    fn show(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        texture: &wgpu::Texture,
    ) {
        if self.texture != *texture {
            self.texture = texture.clone();
            self.own = false;
            ctx.count_app(1, 0);
            renderer.update_egui_texture_from_wgpu_texture(
                &ctx.device,
                &self.texture.create_view(&Default::default()),
                wgpu::FilterMode::Linear,
                self.id,
            );
        }
    }
}

/// egui-wgpu reads a native texture as gamma-encoded `Rgba8Unorm`, which is what the final
/// image's sRGB bytes are.
fn image_texture(ctx: &GpuContext, width: u32, height: u32) -> wgpu::Texture {
    ctx.count_app(1, 0);
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("viewer image"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

fn write_rgba(ctx: &GpuContext, texture: &wgpu::Texture, rgba: &[u8]) {
    let (w, h) = (texture.width(), texture.height());
    debug_assert_eq!(rgba.len(), (w * h * 4) as usize);
    ctx.count_app(0, rgba.len() as u64);
    ctx.queue.write_texture(
        texture.as_image_copy(),
        rgba,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * w),
            rows_per_image: Some(h),
        },
        texture.size(),
    );
}

fn rgba_of(image: &Image) -> Vec<u8> {
    image
        .rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}

/// The window's surface. wgpu-hal 30 panics where the driver fails to make one (seen once under a
/// just-started Xvfb: `create_xlib_surface() failed: ERROR_OUT_OF_HOST_MEMORY`): that becomes an
/// error naming the driver's words, not a panic and its backtrace.
fn create_surface(
    instance: &wgpu::Instance,
    window: Arc<Window>,
) -> Result<Result<wgpu::Surface<'static>, wgpu::CreateSurfaceError>> {
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let made = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        instance.create_surface(window)
    }));
    std::panic::set_hook(hook);
    made.map_err(|payload| {
        let words = payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        anyhow::anyhow!("the GPU driver failed to make the window's surface: {words}")
    })
}

/// egui-wgpu 0.37's own traffic, counted into the context's app figures as its `update_texture`
/// and `update_buffers` make it (it creates through the device, out of our sight): a full
/// texture delta is a new texture and bind group, a partial one an upload; the vertex and index
/// buffers are written whole every frame and grow to twice their size (or what is needed) when
/// too small, from 1,024 vertices and 3,072 indices; its 16-byte uniform is written when the
/// screen changes.
struct EguiTraffic {
    vertex_capacity: u64,
    index_capacity: u64,
    screen: Option<([u32; 2], u32)>,
    /// egui's own share of the app's uploaded bytes so far.
    uploaded: u64,
}

impl Default for EguiTraffic {
    fn default() -> Self {
        EguiTraffic {
            vertex_capacity: VERTEX_BYTES * 1024,
            index_capacity: 4 * 1024 * 3,
            screen: None,
            uploaded: 0,
        }
    }
}

/// `egui_wgpu`'s vertex: position and uv as `f32` pairs, colour as four bytes.
const VERTEX_BYTES: u64 = 20;

impl EguiTraffic {
    fn count(&mut self, ctx: &GpuContext, created: u64, uploaded: u64) {
        self.uploaded += uploaded;
        ctx.count_app(created, uploaded);
    }

    fn texture(&mut self, ctx: &GpuContext, delta: &egui::epaint::ImageDelta) {
        let created = if delta.pos.is_none() { 2 } else { 0 };
        let bytes = (delta.image.width() * delta.image.height() * 4) as u64;
        self.count(ctx, created, bytes);
    }

    fn buffers(
        &mut self,
        ctx: &GpuContext,
        jobs: &[egui::ClippedPrimitive],
        screen: &egui_wgpu::ScreenDescriptor,
    ) {
        let (vertices, indices) =
            jobs.iter()
                .fold((0u64, 0u64), |(v, i), job| match &job.primitive {
                    egui::epaint::Primitive::Mesh(m) => {
                        (v + m.vertices.len() as u64, i + m.indices.len() as u64)
                    }
                    egui::epaint::Primitive::Callback(_) => (v, i),
                });
        let mut created = 0;
        let mut grow = |capacity: &mut u64, needed: u64| {
            if needed > 0 && *capacity < needed {
                *capacity = (*capacity * 2).max(needed);
                created += 1;
            }
        };
        grow(&mut self.index_capacity, indices * 4);
        grow(&mut self.vertex_capacity, vertices * VERTEX_BYTES);
        let key = (screen.size_in_pixels, screen.pixels_per_point.to_bits());
        let uniform = if self.screen != Some(key) {
            self.screen = Some(key);
            16
        } else {
            0
        };
        self.count(
            ctx,
            created,
            indices * 4 + vertices * VERTEX_BYTES + uniform,
        );
    }
}

/// Everything the frame compares to decide whether to render the scene again.
#[derive(Clone, Debug, PartialEq)]
struct RenderKey {
    camera: OrbitCamera,
    sun: Sun,
    size: (u32, u32),
    sides: usize,
    quality: Quality,
    choices: Vec<TechniqueChoice>,
    water: Option<SurfaceKey>,
}

/// What the buffer picture was computed from.
#[derive(Clone, Debug, PartialEq)]
struct BufferKey {
    buffer: Buffer,
    choice: TechniqueChoice,
    render: RenderKey,
}

struct Viewer {
    // Declared before the window so that they are dropped before it.
    images: [GpuImage; 2],
    map_images: [GpuImage; 2],
    difference_image: GpuImage,
    buffer_image: GpuImage,
    egui_renderer: egui_wgpu::Renderer,
    egui_traffic: EguiTraffic,
    egui_state: egui_winit::State,
    egui_ctx: egui::Context,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    renderer: SceneRenderer,
    ui_timer: Option<GpuTimer>,
    model: Model,
    script: Option<Script>,
    report_memory: bool,
    /// With --report-traffic: the counts at the start of the steady frames, and egui's share.
    report_traffic: Option<Option<(super::frame::Traffic, u64)>>,
    frame: u64,
    last_frame: Instant,
    last_render: Option<RenderKey>,
    last_buffer: Option<BufferKey>,
    /// The lost device's error, shown in the title until the window is closed.
    lost: Option<anyhow::Error>,
    /// When egui asked to be drawn again, if it did.
    repaint_at: Option<Instant>,
    window: Arc<Window>,
}

impl Viewer {
    fn new(event_loop: &ActiveEventLoop, args: &ViewArgs) -> Result<Self> {
        let scene = Scene::load_or_builtin(&args.scene)?;
        let [w, h] = args.size;
        let attributes = Window::default_attributes()
            .with_title(format!("caustics view: {}", scene.name))
            .with_inner_size(winit::dpi::PhysicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("cannot open a window")?,
        );
        let options = GpuOptions {
            backend: args.backend.clone(),
            adapter_name: args.adapter.clone(),
        };
        let instance = GpuContext::instance(&options)?;
        let surface = match create_surface(&instance, window.clone())? {
            Ok(s) => s,
            // Without a driver no backend makes a surface, and wgpu's words for it name no
            // cause: say that there is no adapter where that is why.
            Err(e) => {
                if let Err(no_gpu) = GpuContext::headless(&options) {
                    return Err(anyhow::Error::new(no_gpu)
                        .context("the viewer needs a GPU adapter that can draw to the window"));
                }
                return Err(
                    anyhow::Error::new(e).context("cannot make a wgpu surface for the window")
                );
            }
        };
        let ctx = pollster::block_on(GpuContext::create(&options, Some((&instance, &surface))))
            .context("the viewer needs a GPU adapter that can draw to the window")?;
        let software = FinalImage::software_adapter(&ctx);
        eprintln!("GPU: {}", ctx.describe());

        let size = window.inner_size();
        let caps = surface.get_capabilities(&ctx.adapter);
        // egui blends in gamma space and wants a non-sRGB target.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                )
            })
            .or_else(|| caps.formats.first().copied())
            .context("the window's surface offers no format")?;
        let present_mode = if args.frames.is_some() {
            // A scripted run measures frames, not the display's refresh.
            wgpu::PresentMode::AutoNoVsync
        } else {
            wgpu::PresentMode::AutoVsync
        };
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
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

        let egui_ctx = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(ctx.limits().max_texture_dimension_2d as usize),
        );
        let mut egui_renderer =
            egui_wgpu::Renderer::new(&ctx.device, format, egui_wgpu::RendererOptions::default());
        let images = [
            GpuImage::new(&ctx, &mut egui_renderer),
            GpuImage::new(&ctx, &mut egui_renderer),
        ];
        let map_images = [
            GpuImage::new(&ctx, &mut egui_renderer),
            GpuImage::new(&ctx, &mut egui_renderer),
        ];
        let difference_image = GpuImage::new(&ctx, &mut egui_renderer);
        let buffer_image = GpuImage::new(&ctx, &mut egui_renderer);
        let textures = TextureIds {
            main: [images[0].id, images[1].id],
            map: [map_images[0].id, map_images[1].id],
            difference: difference_image.id,
            buffer: buffer_image.id,
        };
        let ui_timer = ctx.timestamps.then(|| GpuTimer::new(&ctx, 1));
        let timestamps = ctx.timestamps;
        let adapter = format!(
            "{} ({:?}){}",
            ctx.info.name,
            ctx.info.backend,
            if software { ", software" } else { "" }
        );

        let model = initial_model(args, &scene, software, adapter, textures, timestamps)?;
        for name in args.cycle_techniques.iter().flatten() {
            TechniqueChoice::parse(name, 1)
                .with_context(|| format!("--cycle-techniques `{name}`"))?;
        }
        let renderer = SceneRenderer::new(Runner::new(Some(ctx)), scene);
        if let Some(n) = &renderer.final_note {
            eprintln!("{n}");
        }
        let script = args.frames.map(|frames| Script {
            frames,
            screenshot: args.screenshot.clone(),
            cycle: args.cycle_techniques.clone(),
            resize_every: args.resize_every,
            drop_every: args.drop_every,
            show_map_at: args.show_map_at,
            lose_device_at: args.lose_device_at,
            base_size: args.size,
            times: Vec::new(),
            passes: Vec::new(),
        });
        Ok(Viewer {
            images,
            map_images,
            difference_image,
            buffer_image,
            egui_renderer,
            egui_traffic: EguiTraffic::default(),
            egui_state,
            egui_ctx,
            surface,
            config,
            renderer,
            ui_timer,
            model,
            script,
            report_memory: args.report_memory,
            report_traffic: args.report_traffic.then_some(None),
            frame: 0,
            last_frame: Instant::now(),
            last_render: None,
            last_buffer: None,
            lost: None,
            repaint_at: None,
            window,
        })
    }

    fn ctx(&self) -> &GpuContext {
        self.renderer.gpu().expect("the viewer always has a device")
    }

    /// Whether to draw again at once: the water moves, or a script is running.
    fn continuous(&self) -> bool {
        self.script.is_some() || self.model.water.as_ref().is_some_and(|w| w.animating())
    }

    fn resize(&mut self, width: u32, height: u32) {
        if width == 0 || height == 0 {
            return;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(&self.ctx().device, &self.config);
        self.window.request_redraw();
    }

    fn frame(&mut self) -> Result<Flow> {
        let started = Instant::now();
        let dt = started.duration_since(self.last_frame).as_secs_f64();
        self.last_frame = started;
        // A script advances the water by a fixed step, so its frames are repeatable.
        let sim_dt = if self.script.is_some() {
            1.0 / 30.0
        } else {
            dt.min(0.25)
        };
        self.model.frame_dt = dt;
        self.model.stats.frame_ms = if self.model.stats.frame_ms == 0.0 {
            dt * 1e3
        } else {
            0.9 * self.model.stats.frame_ms + 0.1 * dt * 1e3
        };
        self.scripted();

        let input = self.egui_state.take_egui_input(&self.window);
        let egui_ctx = self.egui_ctx.clone();
        let mut full = egui_ctx.run_ui(input, |ui| ui::show(ui, &mut self.model));
        self.egui_state
            .handle_platform_output(&self.window, std::mem::take(&mut full.platform_output));
        self.repaint_at = full
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .and_then(|v| {
                (v.repaint_delay < Duration::from_secs(3600)).then(|| started + v.repaint_delay)
            });

        self.scripted_drops();
        let drops: Vec<DVec2> = self.model.pending_drops.drain(..).collect();
        let gpu = self.renderer.gpu();
        if let Some(w) = self.model.water.as_mut() {
            for p in drops {
                tracing::info!("ripple dropped at ({:.3}, {:.3})", p.x, p.y);
                w.drop_at(gpu, p)?;
            }
            w.advance(gpu, sim_dt)?;
        }

        let rendered = self.render_scene()?;
        self.update_pictures()?;
        let capture = match &self.script {
            Some(s) if self.frame + 1 == s.frames => s.screenshot.clone(),
            _ => None,
        }
        .or_else(|| {
            std::mem::take(&mut self.model.screenshot_requested).then(|| {
                let secs = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_secs());
                PathBuf::from(format!("caustics-view-{secs}.png"))
            })
        });
        // The last frame's counts are taken before its screenshot is read back.
        let counts = self.renderer.gpu().map(|c| c.traffic());
        let egui_uploaded = self.egui_traffic.uploaded;
        self.paint(full, capture.as_deref())?;
        self.frame += 1;

        if self.report_memory
            && (self.frame == 50
                || self.frame.is_multiple_of(100)
                || self.script.as_ref().is_some_and(|s| self.frame == s.frames))
        {
            match super::resident_kib() {
                Some(kib) => println!("memory: frame {} VmRSS {kib} kB", self.frame),
                None => println!("memory: frame {} VmRSS unknown", self.frame),
            }
            println!(
                "wgpu: frame {} {}",
                self.frame,
                super::wgpu_objects(&self.ctx().device)
            );
        }
        if let (Some(traffic), Some(s)) = (self.report_traffic.as_mut(), self.script.as_ref()) {
            let first = steady_from(s.frames);
            if self.frame + 1 == first {
                *traffic = Some((
                    self.renderer.traffic(self.model.sides()),
                    self.egui_traffic.uploaded,
                ));
            }
            if self.frame == s.frames
                && let (Some((start, egui_start)), Some(end)) = (traffic.as_ref(), counts)
            {
                let n = (s.frames + 1 - first) as f64;
                let range = format!("(frames {first} to {})", s.frames);
                let sides = self.renderer.traffic(self.model.sides());
                for k in 0..self.model.sides() {
                    let name = self
                        .renderer
                        .gpu_technique_name(k)
                        .unwrap_or(self.model.slots[k].choice.name());
                    let d = match (sides.sides.get(k), start.sides.get(k)) {
                        (Some(b), Some(a)) => b.since(a),
                        _ => Default::default(),
                    };
                    println!("traffic {name}: {} {range}", traffic_figures(&d, n));
                }
                let d = end.since(&start.total);
                println!(
                    "traffic frame: {}, timestamp reads {} per frame {range}",
                    traffic_figures(&d, n),
                    per_frame(d.timestamp_reads, n),
                );
                let egui = egui_uploaded - egui_start;
                println!(
                    "traffic viewer: created {}, uploaded {} bytes per frame (images {} bytes, egui {} bytes) {range}",
                    per_frame(d.app_created, n),
                    per_frame(d.app_uploaded_bytes, n),
                    per_frame(d.app_uploaded_bytes - egui, n),
                    per_frame(egui, n),
                );
            }
        }
        if let Some(s) = self.script.as_mut() {
            s.times.push((super::frame::ms(started), rendered));
            if self.frame > 3 {
                let ui = self.model.stats.ui_gpu_ms.map(|ms| caustics_gpu::PassTime {
                    label: "panel + blit".into(),
                    ms,
                });
                for p in self.model.stats.gpu.iter().chain(ui.as_ref()) {
                    match s.passes.iter_mut().find(|(l, _, _)| *l == p.label) {
                        Some(e) => {
                            e.1 += p.ms;
                            e.2 += 1;
                        }
                        None => s.passes.push((p.label.clone(), p.ms, 1)),
                    }
                }
            }
            if self.frame >= s.frames {
                print_summary(&s.times);
                for (label, sum, n) in &s.passes {
                    println!(
                        "gpu pass {label}: mean {:.2} ms over {n} frames",
                        sum / *n as f64
                    );
                }
                // With the map window open, what the last frame's maps held (green channel), so
                // a scripted run can judge the caustics as well as the window.
                if self.model.show_map {
                    for slot in &self.model.slots[..self.model.sides()] {
                        if let Some(m) = slot.floor_map() {
                            let g = m.texels.iter().map(|t| t[1] as f64);
                            let mean = g.clone().sum::<f64>() / m.texels.len().max(1) as f64;
                            let max = g.fold(0.0, f64::max);
                            println!(
                                "map {}: {} x {}, mean {mean:.4}, max {max:.3}",
                                slot.choice.name(),
                                m.width,
                                m.height
                            );
                        }
                    }
                }
                return Ok(Flow::Exit);
            }
        }
        Ok(Flow::Continue)
    }

    /// Render the scene if its inputs changed; returns whether it did.
    fn render_scene(&mut self) -> Result<bool> {
        let m = &mut self.model;
        let key = RenderKey {
            camera: m.camera.clone(),
            sun: m.sun,
            size: m.internal_size(),
            sides: m.sides(),
            quality: m.quality,
            choices: m.slots[..m.sides()]
                .iter()
                .map(|s| s.choice.clone())
                .collect(),
            water: m.water.as_ref().map(|w| w.key()),
        };
        if self.last_render.as_ref() == Some(&key) {
            m.stats.rendered = false;
            return Ok(false);
        }
        let sides = m.sides();
        let (images, stats) = self.renderer.render(
            m.water.as_mut(),
            &m.camera,
            m.sun.direction(),
            key.size,
            &mut m.slots[..sides],
            m.quality,
        )?;
        m.stats = Stats {
            frame_ms: m.stats.frame_ms,
            water_ms: stats.water_ms,
            technique_ms: [
                m.slots[0].technique_ms,
                if sides > 1 {
                    m.slots[1].technique_ms
                } else {
                    None
                },
            ],
            image_ms: stats.image_ms,
            rendered: true,
            gpu: stats.gpu,
            ui_gpu_ms: m.stats.ui_gpu_ms,
            timestamps: m.stats.timestamps,
        };
        let ctx = self.renderer.gpu().expect("the viewer always has a device");
        match images {
            Rendered::Cpu(images) => {
                for (k, image) in images.iter().enumerate() {
                    self.images[k].set(
                        ctx,
                        &mut self.egui_renderer,
                        image.width,
                        image.height,
                        &rgba_of(image),
                    );
                }
            }
            Rendered::Gpu => {
                for k in 0..sides {
                    if let Some(texture) = self.renderer.gpu_image(k) {
                        self.images[k].show(ctx, &mut self.egui_renderer, texture);
                    }
                }
            }
        }
        self.last_render = Some(key);
        Ok(true)
    }

    /// Refresh the map and buffer pictures whose windows are open and whose inputs changed.
    fn update_pictures(&mut self) -> Result<()> {
        let m = &mut self.model;
        // The GPU frame's maps stay on the GPU: read back for the window when they are new or
        // not yet read (the window opened on a still frame); on the CPU path the slots hold theirs.
        if m.show_map && !m.quality.cpu_image {
            let sides = m.sides();
            self.renderer
                .read_maps(&mut m.slots[..sides], m.stats.rendered)?;
        }
        let ctx = self.renderer.gpu().expect("the viewer always has a device");
        if m.show_map {
            for k in 0..m.sides() {
                let slot = &m.slots[k];
                if !slot.map_changed && m.maps[k].size.is_some() {
                    continue;
                }
                m.maps[k] = match (&slot.caustics, &slot.error) {
                    (Some(caustics), _) => self.map_images[k].picture(
                        ctx,
                        &mut self.egui_renderer,
                        pictures::caustics_picture(caustics, slot.walls.as_ref()),
                    ),
                    (None, Some(e)) => Shown {
                        error: Some(e.clone()),
                        ..Shown::default()
                    },
                    (None, None) => Shown {
                        error: Some("no water, no map".into()),
                        ..Shown::default()
                    },
                };
            }
            if m.split
                && (m.slots[0].map_changed || m.slots[1].map_changed || m.difference.size.is_none())
            {
                m.difference = match (m.slots[0].floor_map(), m.slots[1].floor_map()) {
                    (Some(a), Some(b)) => match pictures::difference_picture(a, b) {
                        Some(p) => self
                            .difference_image
                            .picture(ctx, &mut self.egui_renderer, p),
                        None => Shown {
                            error: Some("the maps differ in size".into()),
                            ..Shown::default()
                        },
                    },
                    _ => Shown {
                        error: Some("needs two floor maps".into()),
                        ..Shown::default()
                    },
                };
            }
            // Shown: a redraw without a new map (a still frame) builds and uploads nothing.
            let sides = m.sides();
            for slot in &mut m.slots[..sides] {
                slot.map_changed = false;
            }
        }
        if m.show_buffers
            && let Some(render) = self.last_render.as_ref()
        {
            let key = BufferKey {
                buffer: m.buffer,
                choice: m.slots[0].choice.clone(),
                render: render.clone(),
            };
            if self.last_buffer.as_ref() != Some(&key) {
                // The GPU frame keeps its water on the GPU: the buffer views (CPU twins) take the
                // surface of this frame when they need it.
                if self.renderer.surface.is_none()
                    && let Some(w) = m.water.as_mut()
                {
                    self.renderer.surface = Some(self.renderer.cpu_surface(w)?);
                }
                let ctx = self.renderer.gpu().expect("the viewer always has a device");
                let water = m
                    .water
                    .as_ref()
                    .zip(self.renderer.surface.as_deref())
                    .map(|(w, s)| (w.technique_water(), s));
                let choice = &m.slots[0].choice;
                let spec = choice.spec()?;
                let input = BufferInput {
                    params: &spec.params,
                    scene: &self.renderer.scene,
                    water,
                    light: m.sun.direction(),
                    map_size: m.quality.map_size as usize,
                };
                m.buffer_shown = match caustics_core::techniques::describe::picture(
                    choice.entry,
                    m.buffer,
                    &input,
                ) {
                    Ok(p) => self.buffer_image.picture(ctx, &mut self.egui_renderer, p),
                    Err(e) => Shown {
                        error: Some(format!("{e:#}")),
                        ..Shown::default()
                    },
                };
                self.last_buffer = Some(key);
            }
        }
        Ok(())
    }

    /// Draw the UI to the window, and to a texture read back into `capture` if asked.
    fn paint(&mut self, full: egui::FullOutput, capture: Option<&Path>) -> Result<()> {
        let ctx = self.renderer.gpu().expect("the viewer always has a device");
        let ppp = full.pixels_per_point;
        let jobs = self.egui_ctx.tessellate(full.shapes, ppp);
        for (id, deltas) in &full.textures_delta.set {
            for delta in deltas {
                self.egui_traffic.texture(ctx, delta);
                self.egui_renderer
                    .update_texture(&ctx.device, &ctx.queue, *id, delta);
            }
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [self.config.width, self.config.height],
            pixels_per_point: ppp,
        };
        let frame = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => Some(t),
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => None,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(&ctx.device, &self.config);
                None
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                // A lost device is the likeliest cause: say that, not the symptom.
                ctx.check()?;
                bail!("the window's surface refused a frame")
            }
        };
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("viewer panel"),
            });
        self.egui_traffic.buffers(ctx, &jobs, &screen);
        let user = self.egui_renderer.update_buffers(
            &ctx.device,
            &ctx.queue,
            &mut encoder,
            &jobs,
            &screen,
        );
        let offscreen = capture.map(|_| {
            ctx.count_app(1, 0);
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("viewer screenshot"),
                size: wgpu::Extent3d {
                    width: self.config.width,
                    height: self.config.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: self.config.format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        });
        let mut targets: Vec<wgpu::TextureView> = Vec::new();
        if let Some(f) = &frame {
            targets.push(f.texture.create_view(&Default::default()));
        }
        if let Some(t) = &offscreen {
            targets.push(t.create_view(&Default::default()));
        }
        let mut timer = self.ui_timer.as_mut();
        for (k, view) in targets.iter().enumerate() {
            let timestamp_writes = if k == 0 {
                timer
                    .as_deref_mut()
                    .and_then(|t| t.render_pass("panel + blit"))
            } else {
                None
            };
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("viewer panel"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color {
                                r: 0.09,
                                g: 0.1,
                                b: 0.12,
                                a: 1.0,
                            }),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes,
                    occlusion_query_set: None,
                    multiview_mask: None,
                })
                .forget_lifetime();
            self.egui_renderer.render(&mut pass, &jobs, &screen);
        }
        let timed = !targets.is_empty();
        if let Some(t) = self.ui_timer.as_mut() {
            t.resolve_frame(&mut encoder);
        }
        ctx.queue.submit(user.into_iter().chain([encoder.finish()]));
        if let Some(t) = self.ui_timer.as_mut() {
            t.frame_submitted();
        }
        if let Some(f) = frame {
            ctx.queue.present(f);
        }
        for id in &full.textures_delta.free {
            self.egui_renderer.free_texture(id);
        }
        if let (Some(t), true) = (self.ui_timer.as_mut(), timed) {
            // The latest the GPU has finished, a frame or two late: no stall, no readback.
            self.model.stats.ui_gpu_ms = t.latest(ctx).first().map(|p| p.ms);
        }
        if let (Some(path), Some(texture)) = (capture, &offscreen) {
            let texels: Vec<[u8; 4]> = ctx.read_texture(texture)?;
            let bgra = matches!(
                self.config.format,
                wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
            );
            let rgb: Vec<u8> = texels
                .iter()
                .flat_map(|t| {
                    if bgra {
                        [t[2], t[1], t[0]]
                    } else {
                        [t[0], t[1], t[2]]
                    }
                })
                .collect();
            image::save_buffer(
                path,
                &rgb,
                texture.width(),
                texture.height(),
                image::ExtendedColorType::Rgb8,
            )
            .with_context(|| format!("cannot write {}", path.display()))?;
            let views: Vec<String> = self
                .model
                .view_rects
                .iter()
                .map(|[x, y, w, h]| format!("{x},{y},{w},{h}"))
                .collect();
            println!(
                "screenshot: {} ({} x {}); views (x,y,w,h): {}",
                path.display(),
                texture.width(),
                texture.height(),
                views.join(" ")
            );
            self.model.status = Some(format!("saved {}", path.display()));
        }
        ctx.check()?;
        Ok(())
    }

    /// The script's technique switches and resizes, before the UI sees the frame.
    fn scripted(&mut self) {
        let Some(s) = &self.script else {
            return;
        };
        let k = self.frame;
        if s.lose_device_at == Some(k) {
            self.ctx().device.destroy();
        }
        if s.show_map_at == Some(k) {
            self.model.show_map = true;
        }
        let Some(s) = &self.script else {
            return;
        };
        if let Some(only) = &s.cycle {
            let names: Vec<String> = if only.is_empty() {
                self.model.technique_names.clone()
            } else {
                only.clone()
            };
            if names.is_empty() {
                return;
            }
            let n = names.len() as u64;
            let m = &mut self.model;
            let cells = m.slots[0].choice.cells_per_texel;
            if let Ok(c) = TechniqueChoice::parse(&names[(k % n) as usize], cells) {
                m.slots[0].choice = c;
            }
            m.split = (k / n) % 2 == 1;
            if let Ok(c) = TechniqueChoice::parse(&names[((k + 1) % n) as usize], cells) {
                m.slots[1].choice = c;
            }
        }
        if let Some(every) = s.resize_every
            && k > 0
            && k.is_multiple_of(every)
        {
            let [w, h] = s.base_size;
            // Narrower, wider, taller, each frame size a new swap chain and new image textures;
            // never narrower than the panel and a view (without the panel, than `--size` allows).
            let f = [1.0, 0.8, 1.3, 0.9][((k / every) % 4) as usize];
            let g = [1.0, 1.2, 0.85, 0.7][((k / every) % 4) as usize];
            let least = if self.model.show_panel {
                [400, 200]
            } else {
                [64, 64]
            };
            let size = winit::dpi::PhysicalSize::new(
                ((w as f64 * f) as u32).max(least[0]),
                ((h as f64 * g) as u32).max(least[1]),
            );
            if let Some(now) = self.window.request_inner_size(size) {
                self.resize(now.width, now.height);
            }
        }
    }

    /// The script's drops, as a click a little below the centre of the first view.
    fn scripted_drops(&mut self) {
        if let Some(every) = self.script.as_ref().and_then(|s| s.drop_every)
            && self.frame.is_multiple_of(every)
            && let Some(p) = ui::pick(&self.model, 0.5, 0.6)
        {
            self.model.pending_drops.push(p);
        }
    }
}

fn initial_model(
    args: &ViewArgs,
    scene: &Scene,
    software: bool,
    adapter: String,
    textures: TextureIds,
    timestamps: bool,
) -> Result<Model> {
    let cells = args.cells_per_texel.max(1);
    let first = TechniqueChoice::parse(
        args.technique
            .as_deref()
            .unwrap_or(&scene.caustics.technique),
        cells,
    )
    .context("--technique")?;
    let reference = caustics_core::techniques::reference();
    let second = TechniqueChoice::parse(args.compare.as_deref().unwrap_or(reference.name()), cells)
        .context("--compare")?;
    let water = match &scene.water {
        Some(w) => {
            let mut state = WaterState::new(w, scene.time, args.ripple);
            state.amplitude = args.amplitude.max(0.0);
            state.time_scale = args.time_scale.max(0.0);
            state.paused = args.paused;
            Some(state)
        }
        None => None,
    };
    let camera = OrbitCamera::from_scene(&scene.camera, scene.size);
    // Defaults that keep a frame well under a second on a software adapter, full quality on a
    // GPU. The map's side follows the scene's (its larger side) on a GPU.
    let (scale, map_size, supersampling) = if software {
        (0.25, 128, 1)
    } else {
        (1.0, scene.caustics.width.max(scene.caustics.height), 2)
    };
    let first_choice = first.clone();
    let available = Buffer::available(first_choice.entry, SceneHas::of(scene));
    let buffer = match &args.buffer {
        Some(name) => Buffer::parse(name, &available).context("--buffer")?,
        None => available
            .first()
            .copied()
            .unwrap_or(Buffer::new(&buffers::HEIGHTS)),
    };
    Ok(Model {
        scene_name: scene.name.clone(),
        technique_names: caustics_core::techniques::for_scene(scene),
        has: SceneHas::of(scene),
        adapter,
        home: camera.clone(),
        camera,
        sun: Sun::from_direction(scene.light.direction),
        water,
        slots: [Slot::new(first), Slot::new(second)],
        split: args.compare.is_some(),
        quality: Quality {
            map_size: args.map_size.unwrap_or(map_size).clamp(8, 4096),
            supersampling: args.supersampling.unwrap_or(supersampling).clamp(1, 8),
            exposure: scene.look.exposure,
            filter_water: args.filter_water,
            cpu_image: match args.final_image {
                ImageOn::Cpu => true,
                ImageOn::Gpu => false,
                // The faster of the two: the GPU frame on a GPU, the CPU image on a software
                // adapter, where lavapipe runs the GPU passes on the same cores and the CPU
                // renderer traces the small image faster. Median frame at 640 x 360, CPU image
                // against GPU frame (docs/benchmarks.md, the viewer's table): yuksel 87.8 / 153.9
                // ms, procedural 90.1 / 127.8, volumes 163.9 / 179.8, cascaded 774 / 819 on
                // Mesa 25.0.7; 31.4 / 106.7 ms (yuksel) on Mesa 22.3.6.
                ImageOn::Auto => software,
            },
        },
        scale: args.scale.unwrap_or(scale),
        show_panel: !args.no_panel,
        show_overlay: true,
        show_map: args.show_map,
        show_buffers: args.show_buffers || args.buffer.is_some(),
        buffer,
        textures,
        maps: Default::default(),
        difference: Shown::default(),
        buffer_shown: Shown::default(),
        stats: Stats {
            timestamps,
            ..Stats::default()
        },
        view_px: [args.size[0], args.size[1]],
        view_rects: Vec::new(),
        frame_dt: 0.0,
        pending_drops: Vec::new(),
        screenshot_requested: false,
        status: None,
    })
}

/// One line of frame times for a scripted run: the first frames compile shaders and build
/// pipelines, so the statistics skip them.
/// The first frame whose traffic `--report-traffic` counts: the first ones build the pipelines
/// and the frames (and a technique's first run configures it), so a run of N frames counts from
/// frame 11 on, or from its second half when shorter.
fn steady_from(frames: u64) -> u64 {
    (frames / 2).min(10) + 1
}

/// What a side (or the frame) created, uploaded and read back, per frame over `frames` frames.
fn traffic_figures(d: &caustics_gpu::TrafficCounts, frames: f64) -> String {
    format!(
        "created {}, uploaded {} bytes, readbacks {} per frame",
        per_frame(d.created(), frames),
        per_frame(d.uploaded_bytes, frames),
        per_frame(d.readbacks, frames),
    )
}

/// `total / frames`, as a whole number when it is one.
fn per_frame(total: u64, frames: f64) -> String {
    let v = total as f64 / frames;
    if v.fract() == 0.0 {
        format!("{v}")
    } else {
        format!("{v:.1}")
    }
}

fn print_summary(times: &[(f64, bool)]) {
    let warm = 3.min(times.len().saturating_sub(1));
    let mut ms: Vec<f64> = times[warm..].iter().map(|t| t.0).collect();
    let rendered = times[warm..].iter().filter(|t| t.1).count();
    if ms.is_empty() {
        return;
    }
    ms.sort_by(|a, b| a.total_cmp(b));
    let mean = ms.iter().sum::<f64>() / ms.len() as f64;
    println!(
        "frames: {} (first {warm} skipped): mean {mean:.1} ms, median {:.1} ms, max {:.1} ms; \
         first frame {:.1} ms; scene rendered in {rendered} of {}",
        times.len(),
        ms[ms.len() / 2],
        ms[ms.len() - 1],
        times[0].0,
        ms.len()
    );
}
