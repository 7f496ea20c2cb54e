//! The smoke mode: a scripted run for tests (`--frames` and the options beside it) that switches
//! techniques, resizes the window, drops ripples, loses the device, and prints what it measured.

use std::path::PathBuf;

use super::super::frame::TechniqueChoice;
use super::super::ui;
use super::Viewer;

/// The smoke mode's script.
pub(super) struct Script {
    pub(super) frames: u64,
    pub(super) screenshot: Option<PathBuf>,
    /// `--cycle-techniques`: the names to cycle through, empty for all the scene offers.
    pub(super) cycle: Option<Vec<String>>,
    pub(super) resize_every: Option<u64>,
    pub(super) drop_every: Option<u64>,
    pub(super) show_map_at: Option<u64>,
    pub(super) lose_device_at: Option<u64>,
    /// The window size asked for at the start, which resizes vary around.
    pub(super) base_size: [u32; 2],
    /// Wall time of each frame, ms, and whether it rendered the scene.
    pub(super) times: Vec<(f64, bool)>,
    /// GPU time per pass label summed over the frames after the first three, and its count.
    pub(super) passes: Vec<(String, f64, u32)>,
}

impl Viewer {
    /// The script's technique switches and resizes, before the UI sees the frame.
    pub(super) fn scripted(&mut self) {
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
    pub(super) fn scripted_drops(&mut self) {
        if let Some(every) = self.script.as_ref().and_then(|s| s.drop_every)
            && self.frame.is_multiple_of(every)
            && let Some(p) = ui::pick(&self.model, 0.5, 0.6)
        {
            self.model.pending_drops.push(p);
        }
    }

    /// Record the frame's wall time (`frame_ms`) and GPU passes; at the script's last frame print the
    /// summary and say to exit.
    pub(super) fn record_frame(&mut self, frame_ms: f64, rendered: bool) -> bool {
        if let Some(s) = self.script.as_mut() {
            s.times.push((frame_ms, rendered));
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
                return true;
            }
        }
        false
    }
}

/// One line of frame times for a scripted run: the first frames compile shaders and build
/// pipelines, so the statistics skip them.
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
