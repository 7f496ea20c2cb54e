//! Per-pass GPU time from timestamp queries written at the start and end of each pass (needs only
//! `TIMESTAMP_QUERY`). Where the adapter lacks it the timer records nothing and says so.

use crate::{GpuContext, GpuError};

pub struct GpuTimer {
    query_set: Option<wgpu::QuerySet>,
    resolve: Option<wgpu::Buffer>,
    capacity: u32,
    labels: Vec<String>,
    period_ns: f64,
}

/// One pass's GPU time.
#[derive(Clone, Debug)]
pub struct PassTime {
    pub label: String,
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
                Some(ctx.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamp resolve"),
                    size: capacity as u64 * 8,
                    usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                })),
            )
        } else {
            (None, None)
        };
        GpuTimer {
            query_set,
            resolve,
            capacity,
            labels: Vec::new(),
            period_ns: ctx.queue.get_timestamp_period() as f64,
        }
    }

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
        let stamps: Vec<u64> = ctx.read_buffer(buf)?;
        let times = self
            .labels
            .drain(..)
            .enumerate()
            .map(|(k, label)| PassTime {
                label,
                ms: stamps[2 * k + 1].saturating_sub(stamps[2 * k]) as f64 * self.period_ns * 1e-6,
            })
            .collect();
        Ok(times)
    }
}
