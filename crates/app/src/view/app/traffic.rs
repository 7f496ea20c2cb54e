//! What `--report-traffic` counts: egui's own uploads beside the frame's, and the per-frame
//! figures a scripted run prints.

use caustics_gpu::GpuContext;

use super::Viewer;

/// egui-wgpu 0.37's own traffic, counted into the context's app figures as its `update_texture`
/// and `update_buffers` make it (it creates through the device, out of our sight): a full
/// texture delta is a new texture and bind group, a partial one an upload; the vertex and index
/// buffers are written whole every frame and grow to twice their size (or what is needed) when
/// too small, from 1,024 vertices and 3,072 indices; its 16-byte uniform is written when the
/// screen changes.
pub(super) struct EguiTraffic {
    vertex_capacity: u64,
    index_capacity: u64,
    screen: Option<([u32; 2], u32)>,
    /// egui's own share of the app's uploaded bytes so far.
    pub(super) uploaded: u64,
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

    pub(super) fn texture(&mut self, ctx: &GpuContext, delta: &egui::epaint::ImageDelta) {
        let created = if delta.pos.is_none() { 2 } else { 0 };
        let bytes = (delta.image.width() * delta.image.height() * 4) as u64;
        self.count(ctx, created, bytes);
    }

    pub(super) fn buffers(
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

impl Viewer {
    /// With `--report-traffic` in a scripted run: the counts at the first steady frame, and at the
    /// last what each side, the frame and the viewer created, uploaded and read back per frame.
    /// `counts`: the frame's, taken before the last frame's screenshot is read back.
    pub(super) fn report_traffic(
        &mut self,
        counts: Option<caustics_gpu::TrafficCounts>,
        egui_uploaded: u64,
    ) {
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
    }
}

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
