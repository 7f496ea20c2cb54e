//! Per-pass GPU time from timestamp queries written at the start and end of each pass (needs only
//! `TIMESTAMP_QUERY`). Where the adapter lacks it the timer records nothing and says so.
//!
//! Two ways to read them: [`GpuTimer::read`] waits for the GPU (benchmarks, tests: one run, its own
//! times), and the frame loop's [`GpuTimer::resolve_frame`] + [`GpuTimer::frame_submitted`] +
//! [`GpuTimer::latest`], which copy each frame's stamps into a buffer of the timer's own and pick
//! them up whenever the GPU has finished with them, a frame or two late, without stalling the queue
//! or creating anything. [`crate::traffic`] counts the first as a readback (it waits) and the
//! second as a timestamp read of its own (one per frame it maps), apart from the frame's data.

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

use crate::{GpuContext, GpuError};

/// Timestamp queries for up to a fixed number of passes, labelled as they are recorded, and the
/// buffers their stamps are resolved into and read back from.
pub struct GpuTimer {
    query_set: Option<wgpu::QuerySet>,
    resolve: Option<wgpu::Buffer>,
    capacity: u32,
    labels: Vec<String>,
    period_ns: f64,
    /// The frame loop's mappable copy of the stamps, and its state.
    staging: Option<wgpu::Buffer>,
    staged: Staged,
    latest: Vec<PassTime>,
    traffic: Arc<crate::context::traffic::Traffic>,
}

const MAPPING: u8 = 0;
const MAPPED: u8 = 1;
const MAP_FAILED: u8 = 2;

/// Where the frame loop's copy of the stamps is.
enum Staged {
    /// Free: the next `resolve_frame` may copy into it.
    Idle,
    /// A copy of these passes was recorded; `frame_submitted` maps it.
    Recorded(Vec<String>),
    /// Mapping; the state turns [`MAPPED`] or [`MAP_FAILED`] when the GPU is done with it.
    Mapping(Vec<String>, Arc<AtomicU8>),
}

/// One pass's GPU time.
#[derive(Clone, Debug)]
pub struct PassTime {
    /// The pass's name, as given to [`GpuTimer::compute_pass`] or [`GpuTimer::render_pass`].
    pub label: String,
    /// GPU time between the pass's start and end stamps, milliseconds.
    pub ms: f64,
}

impl GpuTimer {
    /// Room for `passes` timed passes between resets.
    pub fn new(ctx: &GpuContext, passes: u32) -> Self {
        let capacity = passes * 2;
        let (query_set, resolve) = if ctx.timestamps {
            (
                Some(ctx.create_query_set(&wgpu::QuerySetDescriptor {
                    label: Some("pass timestamps"),
                    ty: wgpu::QueryType::Timestamp,
                    count: capacity,
                })),
                Some(ctx.buffer(
                    "timestamp resolve",
                    capacity as u64 * 8,
                    wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                )),
            )
        } else {
            (None, None)
        };
        let staging = query_set.as_ref().map(|_| {
            ctx.buffer(
                "timestamp staging",
                capacity as u64 * 8,
                wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            )
        });
        GpuTimer {
            query_set,
            resolve,
            capacity,
            labels: Vec::new(),
            period_ns: ctx.queue.get_timestamp_period() as f64,
            staging,
            staged: Staged::Idle,
            latest: Vec::new(),
            traffic: ctx.traffic.clone(),
        }
    }

    /// The frame loop's resolve: record the copy of this frame's stamps into the timer's staging
    /// buffer if the previous copy has been picked up (else this frame goes untimed), and forget
    /// the labels either way, ready for the next frame.
    pub fn resolve_frame(&mut self, encoder: &mut wgpu::CommandEncoder) {
        let labels = std::mem::take(&mut self.labels);
        if let (Some(qs), Some(buf), Some(staging), Staged::Idle) =
            (&self.query_set, &self.resolve, &self.staging, &self.staged)
            && !labels.is_empty()
        {
            let n = labels.len() as u32 * 2;
            encoder.resolve_query_set(qs, 0..n, buf, 0);
            encoder.copy_buffer_to_buffer(buf, 0, staging, 0, n as u64 * 8);
            self.staged = Staged::Recorded(labels);
        }
    }

    /// After the submission holding [`resolve_frame`](Self::resolve_frame)'s copy: start mapping it.
    pub fn frame_submitted(&mut self) {
        let Some(staging) = &self.staging else { return };
        if let Staged::Recorded(_) = &self.staged {
            let Staged::Recorded(labels) = std::mem::replace(&mut self.staged, Staged::Idle) else {
                unreachable!("matched above")
            };
            self.traffic.timestamp_read();
            let done = Arc::new(AtomicU8::new(MAPPING));
            let flag = done.clone();
            staging.slice(..).map_async(wgpu::MapMode::Read, move |r| {
                flag.store(
                    if r.is_ok() { MAPPED } else { MAP_FAILED },
                    Ordering::Release,
                );
            });
            self.staged = Staged::Mapping(labels, done);
        }
    }

    /// The pass times of the latest frame the GPU has finished, without waiting for it.
    pub fn latest(&mut self, ctx: &GpuContext) -> &[PassTime] {
        let _ = ctx.device.poll(wgpu::PollType::Poll);
        if let (Some(staging), Staged::Mapping(labels, done)) = (&self.staging, &self.staged) {
            match done.load(Ordering::Acquire) {
                MAPPED => {
                    if let Ok(view) = staging.slice(..).get_mapped_range() {
                        let stamps: &[u64] = bytemuck::cast_slice(&view);
                        self.latest = self.times(labels.iter().cloned(), stamps);
                    }
                    staging.unmap();
                    self.staged = Staged::Idle;
                }
                // A failed map leaves the buffer unmapped: free it for the next frame's copy.
                MAP_FAILED => self.staged = Staged::Idle,
                _ => {}
            }
        }
        &self.latest
    }

    fn times(&self, labels: impl Iterator<Item = String>, stamps: &[u64]) -> Vec<PassTime> {
        labels
            .enumerate()
            .map(|(k, label)| PassTime {
                label,
                ms: stamps[2 * k + 1].saturating_sub(stamps[2 * k]) as f64 * self.period_ns * 1e-6,
            })
            .collect()
    }

    /// Whether the device writes timestamps; a timer without them times nothing and reads back no
    /// pass.
    pub fn enabled(&self) -> bool {
        self.query_set.is_some()
    }

    fn next(&mut self, label: &str) -> Option<(&wgpu::QuerySet, u32)> {
        let qs = self.query_set.as_ref()?;
        let k = self.labels.len() as u32;
        if 2 * k + 2 > self.capacity {
            tracing::warn!("GPU timer full: pass `{label}` is not timed");
            return None;
        }
        self.labels.push(label.to_string());
        Some((qs, 2 * k))
    }

    /// Timestamp writes for a compute pass named `label`.
    pub fn compute_pass(&mut self, label: &str) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        self.next(label)
            .map(|(qs, k)| wgpu::ComputePassTimestampWrites {
                query_set: qs,
                beginning_of_pass_write_index: Some(k),
                end_of_pass_write_index: Some(k + 1),
            })
    }

    /// Timestamp writes for a render pass named `label`.
    pub fn render_pass(&mut self, label: &str) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        self.next(label)
            .map(|(qs, k)| wgpu::RenderPassTimestampWrites {
                query_set: qs,
                beginning_of_pass_write_index: Some(k),
                end_of_pass_write_index: Some(k + 1),
            })
    }

    /// Record the copy of this frame's timestamps; call once after the timed passes.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        if let (Some(qs), Some(buf)) = (&self.query_set, &self.resolve) {
            let n = self.labels.len() as u32 * 2;
            if n > 0 {
                encoder.resolve_query_set(qs, 0..n, buf, 0);
            }
        }
    }

    /// The times of the passes recorded since the last reset (after the resolving submission), and
    /// forget them.
    pub fn read(&mut self, ctx: &GpuContext) -> Result<Vec<PassTime>, GpuError> {
        let Some(buf) = &self.resolve else {
            return Ok(Vec::new());
        };
        if self.labels.is_empty() {
            return Ok(Vec::new());
        }
        let stamps: Vec<u64> = ctx.read_buffer(buf)?;
        let labels = std::mem::take(&mut self.labels);
        Ok(self.times(labels.into_iter(), &stamps))
    }
}

/// What [`median_runs`] measured, milliseconds: each pass's median GPU time, in the order the
/// passes ran, and the submissions' median wall-clock time.
pub struct Medians {
    /// Each pass's label and median GPU time, milliseconds.
    pub passes: Vec<(String, f64)>,
    /// Median wall-clock time from a submission to the end of the wait for it, milliseconds.
    pub wall_ms: f64,
}

/// `runs` submissions of what `encode` records, after one more left out (pipeline compilation,
/// caches), each waited for: the median of each pass's GPU time and of the submission's
/// wall-clock time. For measuring one piece of a frame on its own (`caustics bench` times whole
/// techniques and frames).
#[cfg(not(target_arch = "wasm32"))]
pub fn median_runs(
    ctx: &GpuContext,
    passes: u32,
    runs: usize,
    mut encode: impl FnMut(&mut wgpu::CommandEncoder, &mut GpuTimer),
) -> Result<Medians, GpuError> {
    let mut samples: Vec<Vec<PassTime>> = Vec::new();
    let mut walls = Vec::new();
    for run in 0..=runs {
        let mut timer = GpuTimer::new(ctx, passes);
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encode(&mut encoder, &mut timer);
        timer.resolve(&mut encoder);
        let t0 = std::time::Instant::now();
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        let wall = t0.elapsed().as_secs_f64() * 1e3;
        let times = timer.read(ctx)?;
        if run > 0 {
            samples.push(times);
            walls.push(wall);
        }
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    };
    let passes = samples.first().map_or(Vec::new(), |first| {
        (0..first.len())
            .map(|k| {
                let ms = samples.iter().filter_map(|s| s.get(k)).map(|t| t.ms);
                (first[k].label.clone(), median(ms.collect()))
            })
            .collect()
    });
    Ok(Medians {
        passes,
        wall_ms: median(walls),
    })
}
