//! The viewer's state as the user edits it ([`Model`]) and the egui code that edits it: the
//! control panel, the image views with their pointer and keyboard handling, the map and buffer
//! windows, and the timing overlay.
//!
//! Nothing here renders: the frame loop compares what the UI left in the model with what it last
//! rendered and renders again only when that differs.

use egui::{Color32, Pos2, Rect, Sense, Vec2};
use glam::DVec2;

use caustics_gpu::PassTime;

use super::frame::{Quality, Slot, TechniqueChoice};
use super::water::{Mode, WaterState};
use caustics_core::orbit::{MIN_ELEVATION, OrbitCamera, Sun, pick_water};
use caustics_core::techniques::buffers::{Buffer, SceneHas};
use caustics_core::techniques::describe::{Kind, Param, ParamDefault};

/// Texture ids of everything the UI draws, registered once and updated in place.
#[derive(Clone, Copy, Debug)]
pub struct TextureIds {
    /// The final image of each side.
    pub main: [egui::TextureId; 2],
    /// Each side's caustics map, and their difference.
    pub map: [egui::TextureId; 2],
    pub difference: egui::TextureId,
    pub buffer: egui::TextureId,
}

/// How a picture in a window is to be drawn: its size and what its colours mean, or why there
/// is none.
#[derive(Clone, Debug, Default)]
pub struct Shown {
    pub size: Option<[u32; 2]>,
    pub legend: String,
    pub error: Option<String>,
}

impl Shown {
    /// No picture, and why.
    pub fn error(why: impl Into<String>) -> Self {
        Shown {
            error: Some(why.into()),
            ..Shown::default()
        }
    }
}

/// Timings for the overlay.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Wall time between frames, smoothed.
    pub frame_ms: f64,
    pub water_ms: f64,
    /// Per side: the technique's wall time when it ran this frame.
    pub technique_ms: [Option<f64>; 2],
    pub image_ms: f64,
    /// Whether the scene was rendered this frame (else only the UI was drawn).
    pub rendered: bool,
    pub gpu: Vec<PassTime>,
    pub ui_gpu_ms: Option<f64>,
    pub timestamps: bool,
}

/// Everything the user can change, and what the views need to draw.
pub struct Model {
    pub scene_name: String,
    /// The techniques the picker offers for this scene.
    pub technique_names: Vec<String>,
    /// What the scene has that decides the buffers its techniques show.
    pub has: SceneHas,
    /// Objects in the scene (`volumes`' object maps).
    pub adapter: String,
    pub camera: OrbitCamera,
    /// The scene's own camera, for "reset view".
    pub home: OrbitCamera,
    pub sun: Sun,
    pub water: Option<WaterState>,
    /// The left side, and the right side of a split view.
    pub slots: [Slot; 2],
    pub split: bool,
    pub quality: Quality,
    /// Internal resolution as a fraction of the view's pixels.
    pub scale: f32,
    pub show_panel: bool,
    pub show_overlay: bool,
    pub show_map: bool,
    pub show_buffers: bool,
    pub buffer: Buffer,
    pub textures: TextureIds,
    pub maps: [Shown; 2],
    pub difference: Shown,
    pub buffer_shown: Shown,
    pub stats: Stats,
    /// Size of one image view on screen, physical pixels.
    pub view_px: [u32; 2],
    /// Where each image view lies in the window, physical pixels.
    pub view_rects: Vec<[u32; 4]>,
    /// Seconds since the previous frame (for flying).
    pub frame_dt: f64,
    /// Water points clicked this frame, for the frame loop to drop ripples at.
    pub pending_drops: Vec<DVec2>,
    pub screenshot_requested: bool,
    /// A line of news for the panel (a saved screenshot, an error).
    pub status: Option<String>,
}

impl Model {
    /// The internal image size of one side.
    pub fn internal_size(&self) -> (u32, u32) {
        let s = self.scale as f64;
        let px = |v: u32| ((v as f64 * s).round() as u32).max(8);
        (px(self.view_px[0]), px(self.view_px[1]))
    }

    /// The sides shown.
    pub fn sides(&self) -> usize {
        if self.split { 2 } else { 1 }
    }
}

/// The whole UI for one frame.
pub fn show(ui: &mut egui::Ui, m: &mut Model) {
    let ctx = ui.ctx().clone();
    if ctx.input(|i| i.key_pressed(egui::Key::F2)) {
        m.show_panel = !m.show_panel;
    }
    if ctx.input(|i| i.key_pressed(egui::Key::F1)) {
        m.show_overlay = !m.show_overlay;
    }
    if ctx.input(|i| i.key_pressed(egui::Key::F12)) {
        m.screenshot_requested = true;
    }
    if m.show_panel {
        egui::Panel::left("controls")
            .resizable(false)
            .exact_size(290.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| controls(ui, m));
            });
    }
    egui::CentralPanel::no_frame().show(ui, |ui| views(ui, m));
    windows(&ctx, m);
}

fn controls(ui: &mut egui::Ui, m: &mut Model) {
    ui.heading("caustics view");
    ui.label(format!("scene `{}`", m.scene_name));
    ui.small(&m.adapter);
    ui.separator();

    let names = m.technique_names.clone();
    egui::CollapsingHeader::new("Technique")
        .default_open(true)
        .show(ui, |ui| {
            technique_picker(ui, "left", &names, &mut m.slots[0]);
            ui.checkbox(&mut m.split, "split view: beside it");
            if m.split {
                technique_picker(ui, "right", &names, &mut m.slots[1]);
            }
        });

    egui::CollapsingHeader::new("Sun")
        .default_open(true)
        .show(ui, |ui| {
            ui.add(egui::Slider::new(&mut m.sun.azimuth, -180.0..=180.0).text("azimuth °"));
            ui.add(
                egui::Slider::new(&mut m.sun.elevation, MIN_ELEVATION..=90.0).text("elevation °"),
            );
            ui.small("or Ctrl+drag on the image");
        });

    if let Some(w) = m.water.as_mut() {
        egui::CollapsingHeader::new("Water")
            .default_open(true)
            .show(ui, |ui| water_controls(ui, w));
    }

    egui::CollapsingHeader::new("Quality")
        .default_open(true)
        .show(ui, |ui| {
            let (w, h) = m.internal_size();
            ui.add(
                egui::Slider::new(&mut m.scale, 0.05..=1.0)
                    .text("internal scale")
                    .fixed_decimals(2),
            );
            ui.small(format!(
                "{w} x {h} traced per side, {} x {} on screen",
                m.view_px[0], m.view_px[1]
            ));
            egui::ComboBox::from_label("map size")
                .selected_text(format!("{0} x {0}", m.quality.map_size))
                .show_ui(ui, |ui| {
                    for s in [32, 64, 128, 256, 512, 1024] {
                        ui.selectable_value(&mut m.quality.map_size, s, format!("{s} x {s}"));
                    }
                });
            ui.add(egui::Slider::new(&mut m.quality.supersampling, 1..=4).text("supersampling"));
            ui.add(egui::Slider::new(&mut m.quality.exposure, 0.2..=3.0).text("exposure"));
            ui.checkbox(
                &mut m.quality.filter_water,
                "filter the far water's normals",
            )
            .on_hover_text(
                "the waves' slopes over each sample's footprint become roughness: a blurred \
                     sky and a spread glint instead of one wave's reflection (docs/maintainers/look.md)",
            );
            ui.checkbox(&mut m.quality.cpu_image, "trace the image on the CPU")
                .on_hover_text(
                    "caustics_core::render instead of the GPU pass: faster on a software adapter",
                );
        });

    egui::CollapsingHeader::new("Views")
        .default_open(true)
        .show(ui, |ui| {
            ui.checkbox(&mut m.show_overlay, "timings overlay (F1)");
            ui.checkbox(&mut m.show_map, "caustics map");
            ui.checkbox(&mut m.show_buffers, "intermediate buffers");
            ui.horizontal(|ui| {
                if ui.button("reset view").clicked() {
                    m.camera = m.home.clone();
                }
                if ui.button("save screenshot").clicked() {
                    m.screenshot_requested = true;
                }
            });
        });
    if let Some(s) = &m.status {
        ui.label(s);
    }
    ui.separator();
    ui.small(
        "drag: orbit · right-drag or Shift+drag: pan · wheel: zoom · W A S D, Q E: fly · \
         Ctrl+drag: sun · click the water: ripple · F2: panel · F12: screenshot",
    );
}

/// A technique menu and its parameters, every widget made from the technique's descriptors.
/// Switching keeps the parameters the two entries share (`yuksel` to `yuksel-targets`), but not
/// what either name pins (from `yuksel-targets` back to `yuksel`, the passes are `yuksel`'s own).
fn technique_picker(ui: &mut egui::Ui, id: &str, names: &[String], slot: &mut Slot) {
    let mut name = slot.choice.name().to_string();
    egui::ComboBox::from_id_salt(id)
        .selected_text(&name)
        .show_ui(ui, |ui| {
            for n in names {
                ui.selectable_value(&mut name, n.clone(), n);
            }
        });
    if name != slot.choice.name()
        && let Ok(mut next) = TechniqueChoice::parse(&name, slot.choice.cells_per_texel)
    {
        if next.base() == slot.choice.base() {
            let pinned: Vec<&str> = (next.entry.fixed.iter())
                .chain(slot.choice.entry.fixed)
                .map(|(k, _)| *k)
                .collect();
            for (k, v) in &slot.choice.params {
                if next.entry.params.iter().any(|p| p.key == k) && !pinned.contains(&k.as_str()) {
                    next.params.insert(k.clone(), v.clone());
                }
            }
        }
        slot.choice = next;
    }
    for param in slot.choice.entry.params {
        param_widget(ui, id, param, &mut slot.choice.params);
    }
    if slot.choice.entry.reference {
        ui.add(egui::Slider::new(&mut slot.choice.cells_per_texel, 1..=8).text("cells per texel"));
    }
    match (&slot.error, slot.technique_ms) {
        (Some(e), _) => {
            ui.colored_label(Color32::from_rgb(230, 90, 80), e);
        }
        (None, Some(ms)) => {
            ui.small(format!("{ms:.1} ms on the {}", slot.backend));
        }
        _ => {}
    }
}

/// The widget of one parameter, as its descriptor says: a slider over an integer's range (in
/// its parity, a power of two where it must be), a number within its range, a checkbox, a menu
/// of choices, a file path. A parameter the technique chooses itself (`auto`) shows a checkbox
/// that hands it to the user.
fn param_widget(ui: &mut egui::Ui, id: &str, param: &Param, params: &mut toml::Table) {
    let hint = if param.unit.is_empty() {
        param.doc.to_string()
    } else {
        format!("{} ({})", param.doc, param.unit)
    };
    if let ParamDefault::Auto(how) = param.default {
        let mut auto = !params.contains_key(param.key);
        let r = ui.checkbox(&mut auto, format!("{}: auto", param.label));
        r.on_hover_text(format!("{hint}; auto: {how}"));
        match (auto, params.contains_key(param.key)) {
            (true, true) => {
                params.remove(param.key);
            }
            (false, false) => {
                if let Some(v) = first_value(param.kind) {
                    params.insert(param.key.to_string(), v);
                }
            }
            _ => {}
        }
        if auto {
            return;
        }
    }
    let Some(v) = params.get_mut(param.key) else {
        return;
    };
    let label = param.label;
    let response = match (param.kind, v) {
        (
            Kind::Int {
                min,
                max,
                parity,
                power_of_two,
            },
            toml::Value::Integer(i),
        ) => {
            // A slider clamps what it shows: never let its range change a value it was given.
            let (lo, hi) = (min.min(*i), max.max(*i));
            let mut slider = egui::Slider::new(i, lo..=hi).text(label);
            if hi > 64 * lo.max(1) {
                slider = slider.logarithmic(true);
            }
            let r = ui.add(slider);
            if let Some(p) = parity
                && i.rem_euclid(2) != p
            {
                // Odd N, even M: step to the nearest allowed value in range.
                *i = if *i < hi { *i + 1 } else { *i - 1 };
            }
            if power_of_two && *i > 0 && (*i & (*i - 1)) != 0 {
                let up = (*i as u64).next_power_of_two() as i64;
                *i = if up - *i < *i - up / 2 { up } else { up / 2 };
            }
            r
        }
        (Kind::Float { min, max }, value @ (toml::Value::Float(_) | toml::Value::Integer(_))) => {
            let mut f = value
                .as_float()
                .unwrap_or_else(|| value.as_integer().unwrap_or(0) as f64);
            let speed = ((max - min) / 500.0).clamp(1e-3, 1.0);
            let r = ui.add(
                egui::DragValue::new(&mut f)
                    .range(min..=max)
                    .speed(speed)
                    .prefix(format!("{label} ")),
            );
            *value = toml::Value::Float(f);
            r
        }
        (Kind::Bool, toml::Value::Boolean(b)) => ui.checkbox(b, label),
        (Kind::Choice(words), toml::Value::String(text)) => {
            egui::ComboBox::from_id_salt((id, param.key))
                .selected_text(format!("{label}: {text}"))
                .show_ui(ui, |ui| {
                    for w in words {
                        ui.selectable_value(text, w.to_string(), *w);
                    }
                })
                .response
        }
        (Kind::Path, toml::Value::String(text)) => {
            ui.horizontal(|ui| {
                ui.label(label);
                ui.text_edit_singleline(text)
            })
            .inner
        }
        (_, other) => ui.label(format!("{label} = {other}")),
    };
    response.on_hover_text(hint);
}

/// The value a parameter takes when the user takes it over from `auto`: the middle of an
/// integer's range in its parity, the low end of a number's, on, the first choice.
fn first_value(kind: Kind) -> Option<toml::Value> {
    Some(match kind {
        Kind::Int {
            min, max, parity, ..
        } => {
            let mut i = min.max(1).min(max);
            if let Some(p) = parity
                && i.rem_euclid(2) != p
            {
                i += 1;
            }
            toml::Value::Integer(i.min(max))
        }
        Kind::Float { min, .. } => toml::Value::Float(min),
        Kind::Bool => toml::Value::Boolean(true),
        Kind::Choice(words) => toml::Value::String(words.first()?.to_string()),
        Kind::Path => return None,
    })
}

fn water_controls(ui: &mut egui::Ui, w: &mut WaterState) {
    ui.horizontal(|ui| {
        ui.radio_value(&mut w.mode, Mode::Scene, "scene source");
        ui.radio_value(&mut w.mode, Mode::Ripple, "ripples");
    });
    ui.add(
        egui::Slider::new(&mut w.amplitude, 0.0..=4.0)
            .text("amplitude ×")
            .fixed_decimals(2),
    );
    ui.add(
        egui::Slider::new(&mut w.time_scale, 0.0..=4.0)
            .text("time scale")
            .fixed_decimals(2),
    );
    ui.horizontal(|ui| {
        ui.checkbox(&mut w.paused, "pause");
        ui.small(format!("t = {:.2} s", w.clock()));
    });
    if w.mode == Mode::Ripple {
        let size = w.water().size;
        ui.add(
            egui::Slider::new(&mut w.drop_radius, size * 0.01..=size * 0.3)
                .text("drop radius")
                .fixed_decimals(3),
        );
        ui.add(
            egui::Slider::new(&mut w.drop_strength, -size * 0.05..=size * 0.05)
                .text("drop height")
                .fixed_decimals(3),
        );
        ui.horizontal(|ui| {
            if ui.button("calm").clicked() {
                w.calm();
            }
            if let Some(b) = w.simulation_backend() {
                ui.small(format!("simulated on the {b}"));
            }
        });
        if let Some(n) = &w.sim_note {
            ui.small(n);
        }
    }
}

/// The image views: one, or two side by side, each taking the pointer.
fn views(ui: &mut egui::Ui, m: &mut Model) {
    let rect = ui.available_rect_before_wrap();
    let ppp = ui.ctx().pixels_per_point();
    let sides = m.sides();
    let w = rect.width() / sides as f32;
    m.view_px = [
        ((w * ppp).round() as u32).max(1),
        ((rect.height() * ppp).round() as u32).max(1),
    ];
    m.view_rects.clear();
    let full_uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
    for k in 0..sides {
        let r = Rect::from_min_size(
            rect.min + Vec2::new(k as f32 * w, 0.0),
            Vec2::new(w, rect.height()),
        );
        m.view_rects.push([
            (r.min.x * ppp).round() as u32,
            (r.min.y * ppp).round() as u32,
            (r.width() * ppp).round() as u32,
            (r.height() * ppp).round() as u32,
        ]);
        let response = ui.interact(r, ui.scope_id().with(("view", k)), Sense::click_and_drag());
        ui.painter()
            .image(m.textures.main[k], r, full_uv, Color32::WHITE);
        if sides == 2 {
            let label = m.slots[k].choice.name().to_string();
            ui.painter().text(
                r.center_top() + Vec2::new(0.0, 6.0),
                egui::Align2::CENTER_TOP,
                label,
                egui::FontId::proportional(15.0),
                Color32::WHITE,
            );
        }
        pointer(ui, m, &response, r);
    }
    keyboard(ui, m);
    if m.show_overlay {
        overlay(ui.ctx(), m, rect.min);
    }
}

/// Orbit, pan, zoom, sun and ripple drops from the pointer over a view.
fn pointer(ui: &egui::Ui, m: &mut Model, response: &egui::Response, r: Rect) {
    let modifiers = ui.input(|i| i.modifiers);
    let d = response.drag_delta();
    let (dx, dy) = (d.x as f64, d.y as f64);
    let height = m.view_px[1] as f64 / ui.ctx().pixels_per_point() as f64;
    if response.dragged_by(egui::PointerButton::Primary) {
        if modifiers.ctrl || modifiers.alt || modifiers.command {
            m.sun.drag(dx, dy);
        } else if modifiers.shift {
            m.camera.pan(dx, dy, height);
        } else {
            m.camera.orbit(dx, dy);
        }
    } else if response.dragged_by(egui::PointerButton::Secondary)
        || response.dragged_by(egui::PointerButton::Middle)
    {
        m.camera.pan(dx, dy, height);
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y) as f64;
        if scroll != 0.0 {
            m.camera.zoom(scroll / 50.0);
        }
    }
    if response.clicked()
        && let Some(p) = response.interact_pointer_pos()
    {
        let uv = (p - r.min) / r.size();
        m.pending_drops.extend(pick(m, uv.x as f64, uv.y as f64));
    }
}

/// The water point under a view's fractional position `(u, v)`, if any.
pub fn pick(m: &Model, u: f64, v: f64) -> Option<DVec2> {
    let w = m.water.as_ref()?.water();
    let [vw, vh] = m.view_px;
    let cam = m.camera.camera(vw, vh);
    pick_water(
        &cam,
        u * vw as f64 - 0.5,
        v * vh as f64 - 0.5,
        w.level(),
        w.size,
    )
}

/// WASD (and Q, E for down and up) fly while no text field has the keyboard.
fn keyboard(ui: &egui::Ui, m: &mut Model) {
    if ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    use egui::Key;
    let (f, r, u) = ui.input(|i| {
        let axis = |plus: Key, minus: Key| {
            i.key_down(plus) as i32 as f64 - i.key_down(minus) as i32 as f64
        };
        (
            axis(Key::W, Key::S),
            axis(Key::D, Key::A),
            axis(Key::E, Key::Q),
        )
    });
    if f != 0.0 || r != 0.0 || u != 0.0 {
        m.camera.fly(f, r, u, m.frame_dt.min(0.25));
        ui.ctx().request_repaint();
    }
}

fn overlay(ctx: &egui::Context, m: &Model, at: Pos2) {
    let s = &m.stats;
    egui::Area::new(egui::Id::unique("timings"))
        .fixed_pos(at + Vec2::new(8.0, 28.0))
        .interactable(false)
        .show(ctx, |ui| {
            egui::Frame::popup(ui.style())
                .fill(Color32::from_black_alpha(170))
                .show(ui, |ui| {
                    let fps = if s.frame_ms > 0.0 {
                        1e3 / s.frame_ms
                    } else {
                        0.0
                    };
                    let mono = |ui: &mut egui::Ui, t: String| {
                        ui.label(egui::RichText::new(t).monospace().color(Color32::WHITE));
                    };
                    mono(
                        ui,
                        format!("frame      {:7.1} ms  {fps:5.1} fps", s.frame_ms),
                    );
                    if s.rendered {
                        mono(ui, format!("water      {:7.1} ms", s.water_ms));
                        for k in 0..m.sides() {
                            let slot = &m.slots[k];
                            let t = match s.technique_ms[k] {
                                Some(ms) => format!("{ms:7.1} ms {}", slot.backend),
                                // In the GPU frame: its passes are timed below.
                                None if slot.backend == "GPU" && !m.quality.cpu_image => {
                                    "  (GPU frame)".into()
                                }
                                None => "  (unchanged)".into(),
                            };
                            mono(ui, format!("{:<10} {t}", short(slot.choice.name(), 14)));
                        }
                        mono(ui, format!("image      {:7.1} ms", s.image_ms));
                    } else {
                        mono(ui, "scene unchanged: not re-rendered".into());
                    }
                    if s.timestamps {
                        for p in &s.gpu {
                            let name = short(pass_name(&p.label), 16);
                            mono(ui, format!("GPU {name:<16} {:6.2} ms", p.ms));
                        }
                        if let Some(ms) = s.ui_gpu_ms {
                            mono(ui, format!("GPU {:<16} {ms:6.2} ms", "panel + blit"));
                        }
                    } else {
                        mono(ui, "GPU times: no timestamps on this adapter".into());
                    }
                    let (w, h) = m.internal_size();
                    mono(
                        ui,
                        format!("{w}x{h} per side, map {0}x{0}", m.quality.map_size),
                    );
                });
        });
}

/// A GPU pass's label without its technique's name in front (`caustic-triangles triangles` ->
/// `triangles`): the overlay's column is narrow.
fn pass_name(label: &str) -> &str {
    caustics_core::techniques::names()
        .iter()
        .find_map(|t| label.strip_prefix(t).and_then(|r| r.strip_prefix(' ')))
        .unwrap_or(label)
}

/// The first `n` characters of a label (never cutting a character in two).
fn short(s: &str, n: usize) -> &str {
    s.char_indices().nth(n).map_or(s, |(i, _)| &s[..i])
}

/// The map and buffer windows.
fn windows(ctx: &egui::Context, m: &mut Model) {
    // Down the right edge, clear of the overlay at the top left of the view.
    let right = ctx.content_rect().right();
    let mut open = m.show_map;
    egui::Window::new("Caustics map")
        .open(&mut open)
        .default_pos(Pos2::new(right - 2.0 * (WINDOW_WIDTH + 24.0), 10.0))
        .default_width(WINDOW_WIDTH)
        .show(ctx, |ui| {
            for k in 0..m.sides() {
                ui.label(format!("{} map", m.slots[k].choice.name()));
                picture(ui, m.textures.map[k], &m.maps[k]);
            }
            if m.split {
                ui.label("difference");
                picture(ui, m.textures.difference, &m.difference);
            }
        });
    m.show_map = open;

    let mut open = m.show_buffers;
    egui::Window::new("Buffers")
        .open(&mut open)
        .default_pos(Pos2::new(right - WINDOW_WIDTH - 12.0, 10.0))
        .default_width(WINDOW_WIDTH)
        .show(ctx, |ui| {
            let choice = &m.slots[0].choice;
            let available = Buffer::available(choice.entry, m.has);
            if !available.iter().any(|b| b.same_kind(&m.buffer))
                && let Some(first) = available.first()
            {
                m.buffer = *first;
            }
            egui::ComboBox::from_id_salt("buffer")
                .selected_text(m.buffer.name())
                .show_ui(ui, |ui| {
                    for b in available {
                        let selected = b.same_kind(&m.buffer);
                        if ui.selectable_label(selected, b.name()).clicked() && !selected {
                            m.buffer = b;
                        }
                    }
                });
            if let Some(index) = &m.buffer.desc.index {
                let last = m.buffer.count(&choice.params, &m.has).saturating_sub(1);
                ui.add(egui::Slider::new(&mut m.buffer.index, 0..=last).text(index.name));
            }
            ui.small(format!("of the left side's technique, `{}`", choice.name()));
            if Buffer::available(choice.entry, m.has).is_empty() {
                ui.small("it has no intermediate buffers to show");
            } else {
                picture(ui, m.textures.buffer, &m.buffer_shown);
            }
        });
    m.show_buffers = open;
}

/// Width of the map and buffer windows, points.
const WINDOW_WIDTH: f32 = 210.0;

fn picture(ui: &mut egui::Ui, id: egui::TextureId, shown: &Shown) {
    if let Some(e) = &shown.error {
        ui.colored_label(Color32::from_rgb(230, 90, 80), e);
        return;
    }
    let Some([w, h]) = shown.size else {
        ui.small("(not computed yet)");
        return;
    };
    let width = ui.available_width().clamp(120.0, 400.0);
    let size = Vec2::new(width, width * h as f32 / w.max(1) as f32);
    ui.image((id, size));
    ui.small(&shown.legend);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_are_shortened_by_characters() {
        assert_eq!(
            short("caustic-triangles water photons", 26),
            "caustic-triangles water ph"
        );
        assert_eq!(short("map 512²", 8), "map 512²");
        assert_eq!(short("map 512²", 7), "map 512");
        assert_eq!(short("", 4), "");
        assert_eq!(
            pass_name("caustic-triangles water photons"),
            "water photons"
        );
        assert_eq!(pass_name("eye depth"), "eye depth");
    }

    /// Every value a choice parameter's menu offers is one its technique accepts, and the
    /// technique accepts no value the menu leaves out: every choice of every registered entry.
    #[test]
    fn choice_menus_offer_what_the_techniques_accept() {
        let mut checked = 0;
        for d in caustics_core::techniques::REGISTRY {
            for p in d.params {
                let Kind::Choice(words) = p.kind else {
                    continue;
                };
                assert!(words.len() >= 2, "{}.{}", d.name, p.key);
                for value in words.iter().chain(&["no-such-value"]) {
                    let text = format!("{}:{}=\"{value}\"", d.name, p.key);
                    let parsed = text.parse::<crate::techniques::Spec>();
                    let pinned = d.fixed.iter().any(|(k, v)| *k == p.key && v != value);
                    // The technique's own parse of its table (serde and its checks).
                    let ok = parsed.is_ok_and(|spec| (d.validate)(&spec.params).is_ok());
                    assert_eq!(
                        ok,
                        *value != "no-such-value" && !pinned,
                        "{}.{} = {value}",
                        d.name,
                        p.key
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked >= 20, "{checked}");
    }

    /// Taking a parameter over from `auto` gives a value its descriptor accepts.
    #[test]
    fn auto_parameters_start_from_an_accepted_value() {
        for d in caustics_core::techniques::REGISTRY {
            for p in d.params {
                if let Some(v) = first_value(p.kind) {
                    caustics_core::techniques::describe::check_value(p, &v, p.key)
                        .unwrap_or_else(|e| panic!("{}.{}: {e}", d.name, p.key));
                }
            }
        }
    }

    /// The texts an egui frame drew.
    fn texts(shapes: &[egui::epaint::ClippedShape]) -> Vec<String> {
        fn walk(shape: &egui::Shape, out: &mut Vec<String>) {
            match shape {
                egui::Shape::Text(t) => out.push(t.galley.text().to_string()),
                egui::Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
                _ => {}
            }
        }
        let mut out = Vec::new();
        for s in shapes {
            walk(&s.shape, &mut out);
        }
        out
    }

    /// The panel shows every registered technique's every parameter, made from its descriptors:
    /// a label (or, for a parameter the technique chooses itself, its `auto` checkbox) per
    /// parameter, drawn by a headless egui frame.
    #[test]
    fn the_panel_shows_every_parameter_of_every_technique() {
        let ctx = egui::Context::default();
        let names: Vec<String> = caustics_core::techniques::REGISTRY
            .iter()
            .map(|d| d.name.to_string())
            .collect();
        let mut shown = 0;
        for d in caustics_core::techniques::REGISTRY {
            let mut slot = Slot::new(TechniqueChoice::parse(d.name, 2).unwrap());
            let out = ctx.run_ui(egui::RawInput::default(), |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    technique_picker(ui, "test", &names, &mut slot);
                });
            });
            let texts = texts(&out.shapes);
            for p in d.params {
                let auto = format!("{}: auto", p.label);
                assert!(
                    texts
                        .iter()
                        .any(|t| t.contains(p.label) || t.contains(&auto)),
                    "{}: no widget for `{}` among {texts:?}",
                    d.name,
                    p.key
                );
                shown += 1;
            }
            if d.reference {
                assert!(texts.iter().any(|t| t.contains("cells per texel")));
            }
        }
        let total: usize = caustics_core::techniques::REGISTRY
            .iter()
            .map(|d| d.params.len())
            .sum();
        assert_eq!(shown, total);
    }
}
