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

use caustics_core::scene::Scene;
use caustics_gpu::final_image::FinalImage;
use caustics_gpu::{GpuContext, GpuTimer};

use super::ViewArgs;
use super::frame::{Quality, Rendered, SceneRenderer, TechniqueChoice};
use super::ui::{self, Model, Stats, TextureIds};
use super::water::SurfaceKey;
use crate::techniques::Runner;
use caustics_core::orbit::{OrbitCamera, Sun};
use caustics_core::techniques::buffers::Buffer;

mod gpu_image;
mod model;
mod picture_windows;
mod script;
mod traffic;

use gpu_image::{GpuImage, app_texture, rgba_of};
use model::initial_model;
use script::Script;
use traffic::EguiTraffic;

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
        let [w, h] = args.image_size;
        let attributes = Window::default_attributes()
            .with_title(format!("caustics view: {}", scene.name))
            .with_inner_size(winit::dpi::PhysicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .context("cannot open a window")?,
        );
        let options = args.gpu.options();
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
        let images: [GpuImage; 2] =
            std::array::from_fn(|_| GpuImage::new(&ctx, &mut egui_renderer));
        let map_images: [GpuImage; 2] =
            std::array::from_fn(|_| GpuImage::new(&ctx, &mut egui_renderer));
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
        let runner = Runner::new(Some(ctx));
        let runner = if args.gpu.cpu {
            runner.twins_only()
        } else {
            runner
        };
        let renderer = SceneRenderer::new(runner, scene);
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
            base_size: args.image_size,
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
        self.report_traffic(counts, egui_uploaded);
        if self.record_frame(super::frame::ms(started), rendered) {
            return Ok(Flow::Exit);
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
            technique_ms: std::array::from_fn(|k| m.slots[k].technique_ms.filter(|_| k < sides)),
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
            let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
            let size = (self.config.width, self.config.height);
            app_texture(ctx, "viewer screenshot", size, self.config.format, usage)
        });
        let targets: Vec<wgpu::TextureView> = (frame.iter().map(|f| &f.texture))
            .chain(&offscreen)
            .map(|t| t.create_view(&Default::default()))
            .collect();
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
            let (r, b) = if bgra { (2, 0) } else { (0, 2) };
            let rgb: Vec<u8> = texels.iter().flat_map(|t| [t[r], t[1], t[b]]).collect();
            crate::save_rgb(path, &rgb, texture.width(), texture.height())?;
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
}
