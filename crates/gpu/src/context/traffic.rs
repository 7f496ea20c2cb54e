//! Counting what crosses the bus: every GPU resource this crate creates (textures, buffers, bind
//! groups, pipelines, samplers, query sets), every byte it uploads through the queue, and every
//! readback. A real-time frame should create nothing, upload a few uniforms and read nothing back;
//! these counters are how the viewer (`caustics view --report-traffic`) and the tests show it.
//!
//! Every creation in `caustics-gpu` goes through the [`GpuContext`] methods below rather than
//! `ctx.device` directly, so the counts are complete for this crate. Two more kinds are kept apart
//! from the frame's: the timestamp copies a frame loop maps to show pass times without waiting
//! ([`crate::GpuTimer::frame_submitted`]), and what the application reports of its own
//! ([`GpuContext::count_app`]: the viewer's images, egui's buffers and textures), so that a
//! traffic line sees everything that crosses the bus, and says whose it was.

use std::sync::atomic::{AtomicU64, Ordering};

use wgpu::util::DeviceExt;

use crate::GpuContext;

/// The running totals, shared by every clone of a context's handle.
#[derive(Debug, Default)]
pub struct Traffic {
    textures: AtomicU64,
    buffers: AtomicU64,
    bind_groups: AtomicU64,
    pipelines: AtomicU64,
    samplers: AtomicU64,
    query_sets: AtomicU64,
    uploaded_bytes: AtomicU64,
    readbacks: AtomicU64,
    timestamp_reads: AtomicU64,
    app_created: AtomicU64,
    app_uploaded_bytes: AtomicU64,
}

/// A snapshot of [`Traffic`]; subtract two with [`since`](Self::since) for what a span of frames
/// did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TrafficCounts {
    /// Textures this crate created.
    pub textures: u64,
    /// Buffers this crate created (with or without contents).
    pub buffers: u64,
    /// Bind groups this crate created.
    pub bind_groups: u64,
    /// Compute and render pipelines this crate created.
    pub pipelines: u64,
    /// Samplers this crate created.
    pub samplers: u64,
    /// Query sets (timestamps) this crate created.
    pub query_sets: u64,
    /// Bytes this crate sent to the GPU: buffer and texture writes and the contents of buffers and
    /// textures created with data.
    pub uploaded_bytes: u64,
    /// Blocking reads of GPU data into the CPU (a map, a timer's [`read`](crate::GpuTimer::read)).
    pub readbacks: u64,
    /// Timestamp copies mapped by a frame loop (a frame or two late, never waited on).
    pub timestamp_reads: u64,
    /// Resources the application says it created (not this crate's).
    pub app_created: u64,
    /// Bytes the application says it uploaded (not this crate's).
    pub app_uploaded_bytes: u64,
}

impl TrafficCounts {
    /// GPU resources created, of every kind.
    pub fn created(&self) -> u64 {
        self.textures
            + self.buffers
            + self.bind_groups
            + self.pipelines
            + self.samplers
            + self.query_sets
    }

    /// What happened between `earlier` and `self`.
    pub fn since(&self, earlier: &TrafficCounts) -> TrafficCounts {
        self.zip(earlier, |a, b| a - b)
    }

    fn zip(&self, other: &TrafficCounts, f: impl Fn(u64, u64) -> u64) -> TrafficCounts {
        TrafficCounts {
            textures: f(self.textures, other.textures),
            buffers: f(self.buffers, other.buffers),
            bind_groups: f(self.bind_groups, other.bind_groups),
            pipelines: f(self.pipelines, other.pipelines),
            samplers: f(self.samplers, other.samplers),
            query_sets: f(self.query_sets, other.query_sets),
            uploaded_bytes: f(self.uploaded_bytes, other.uploaded_bytes),
            readbacks: f(self.readbacks, other.readbacks),
            timestamp_reads: f(self.timestamp_reads, other.timestamp_reads),
            app_created: f(self.app_created, other.app_created),
            app_uploaded_bytes: f(self.app_uploaded_bytes, other.app_uploaded_bytes),
        }
    }
}

impl std::ops::AddAssign for TrafficCounts {
    fn add_assign(&mut self, other: TrafficCounts) {
        *self = self.zip(&other, |a, b| a + b);
    }
}

impl Traffic {
    fn add(counter: &AtomicU64, n: u64) {
        counter.fetch_add(n, Ordering::Relaxed);
    }

    /// The totals as they stand.
    pub fn snapshot(&self) -> TrafficCounts {
        let l = |c: &AtomicU64| c.load(Ordering::Relaxed);
        TrafficCounts {
            textures: l(&self.textures),
            buffers: l(&self.buffers),
            bind_groups: l(&self.bind_groups),
            pipelines: l(&self.pipelines),
            samplers: l(&self.samplers),
            query_sets: l(&self.query_sets),
            uploaded_bytes: l(&self.uploaded_bytes),
            readbacks: l(&self.readbacks),
            timestamp_reads: l(&self.timestamp_reads),
            app_created: l(&self.app_created),
            app_uploaded_bytes: l(&self.app_uploaded_bytes),
        }
    }

    pub(crate) fn readback(&self) {
        Self::add(&self.readbacks, 1);
    }

    pub(crate) fn timestamp_read(&self) {
        Self::add(&self.timestamp_reads, 1);
    }
}

/// The counted ways to create resources and upload data; same arguments as `wgpu::Device`'s and
/// `wgpu::Queue`'s own.
impl GpuContext {
    /// Everything counted since the context was made.
    pub fn traffic(&self) -> TrafficCounts {
        self.traffic.snapshot()
    }

    /// The application's own traffic on this device, to be counted beside this crate's:
    /// `created` resources and `uploaded` bytes (the viewer's images, egui's buffers and
    /// textures).
    pub fn count_app(&self, created: u64, uploaded: u64) {
        Traffic::add(&self.traffic.app_created, created);
        Traffic::add(&self.traffic.app_uploaded_bytes, uploaded);
    }

    /// `wgpu::Device::create_buffer`, counted.
    pub fn create_buffer(&self, desc: &wgpu::BufferDescriptor) -> wgpu::Buffer {
        Traffic::add(&self.traffic.buffers, 1);
        self.device.create_buffer(desc)
    }

    /// A buffer of `size` bytes, not mapped, counted.
    pub fn buffer(&self, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
        self.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage,
            mapped_at_creation: false,
        })
    }

    /// A buffer holding `contents`, counted as [`create_buffer_init`](Self::create_buffer_init).
    pub fn buffer_init(
        &self,
        label: &str,
        contents: &[u8],
        usage: wgpu::BufferUsages,
    ) -> wgpu::Buffer {
        self.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage,
        })
    }

    /// A uniform buffer (also a copy destination, to be rewritten) holding `value`.
    pub fn uniform<T: bytemuck::Pod>(&self, label: &str, value: &T) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        self.buffer_init(label, bytemuck::bytes_of(value), usage)
    }

    /// A uniform buffer (a copy destination) the size of one `T`, to be written before use.
    pub fn uniform_buffer<T>(&self, label: &str) -> wgpu::Buffer {
        let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
        self.buffer(label, std::mem::size_of::<T>() as u64, usage)
    }

    /// A buffer created with its contents (counted as uploaded bytes).
    pub fn create_buffer_init(&self, desc: &wgpu::util::BufferInitDescriptor) -> wgpu::Buffer {
        Traffic::add(&self.traffic.buffers, 1);
        Traffic::add(&self.traffic.uploaded_bytes, desc.contents.len() as u64);
        if self.is_lost() {
            // wgpu's `create_buffer_init` panics when a lost device cannot map the new buffer; the
            // buffer is invalid either way, and the caller's next `check` reports the loss.
            let size = (desc.contents.len() as u64).next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT);
            return self.device.create_buffer(&wgpu::BufferDescriptor {
                label: desc.label,
                size: size.max(wgpu::COPY_BUFFER_ALIGNMENT),
                usage: desc.usage,
                mapped_at_creation: false,
            });
        }
        self.device.create_buffer_init(desc)
    }

    /// `wgpu::Device::create_texture`, counted.
    pub fn create_texture(&self, desc: &wgpu::TextureDescriptor) -> wgpu::Texture {
        Traffic::add(&self.traffic.textures, 1);
        self.device.create_texture(desc)
    }

    /// A texture created with its texels (counted as uploaded bytes).
    pub fn create_texture_with_data(
        &self,
        desc: &wgpu::TextureDescriptor,
        order: wgpu::util::TextureDataOrder,
        data: &[u8],
    ) -> wgpu::Texture {
        Traffic::add(&self.traffic.textures, 1);
        Traffic::add(&self.traffic.uploaded_bytes, data.len() as u64);
        self.device
            .create_texture_with_data(&self.queue, desc, order, data)
    }

    /// `wgpu::Device::create_bind_group`, counted.
    pub fn create_bind_group(&self, desc: &wgpu::BindGroupDescriptor) -> wgpu::BindGroup {
        Traffic::add(&self.traffic.bind_groups, 1);
        self.device.create_bind_group(desc)
    }

    /// `wgpu::Device::create_compute_pipeline`, counted.
    pub fn create_compute_pipeline(
        &self,
        desc: &wgpu::ComputePipelineDescriptor,
    ) -> wgpu::ComputePipeline {
        Traffic::add(&self.traffic.pipelines, 1);
        self.device.create_compute_pipeline(desc)
    }

    /// `wgpu::Device::create_render_pipeline`, counted.
    pub fn create_render_pipeline(
        &self,
        desc: &wgpu::RenderPipelineDescriptor,
    ) -> wgpu::RenderPipeline {
        Traffic::add(&self.traffic.pipelines, 1);
        self.device.create_render_pipeline(desc)
    }

    /// `wgpu::Device::create_sampler`, counted.
    pub fn create_sampler(&self, desc: &wgpu::SamplerDescriptor) -> wgpu::Sampler {
        Traffic::add(&self.traffic.samplers, 1);
        self.device.create_sampler(desc)
    }

    /// `wgpu::Device::create_query_set`, counted.
    pub fn create_query_set(&self, desc: &wgpu::QuerySetDescriptor) -> wgpu::QuerySet {
        Traffic::add(&self.traffic.query_sets, 1);
        self.device.create_query_set(desc)
    }

    /// `wgpu::Queue::write_buffer`, its bytes counted as uploaded.
    pub fn write_buffer(&self, buffer: &wgpu::Buffer, offset: u64, data: &[u8]) {
        Traffic::add(&self.traffic.uploaded_bytes, data.len() as u64);
        self.queue.write_buffer(buffer, offset, data);
    }

    /// Write `value`'s bytes at the start of `buffer`, counted as uploaded.
    pub fn write_pod<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer, value: &T) {
        self.write_buffer(buffer, 0, bytemuck::bytes_of(value));
    }

    /// `wgpu::Queue::write_texture`, its bytes counted as uploaded.
    pub fn write_texture(
        &self,
        texture: wgpu::TexelCopyTextureInfo,
        data: &[u8],
        layout: wgpu::TexelCopyBufferLayout,
        size: wgpu::Extent3d,
    ) {
        Traffic::add(&self.traffic.uploaded_bytes, data.len() as u64);
        self.queue.write_texture(texture, data, layout, size);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_subtract_per_kind() {
        let a = TrafficCounts {
            textures: 2,
            buffers: 3,
            uploaded_bytes: 100,
            readbacks: 1,
            ..Default::default()
        };
        let b = TrafficCounts {
            textures: 5,
            buffers: 3,
            bind_groups: 4,
            uploaded_bytes: 164,
            readbacks: 1,
            ..Default::default()
        };
        let d = b.since(&a);
        assert_eq!(d.created(), 7);
        assert_eq!(d.uploaded_bytes, 64);
        assert_eq!(d.readbacks, 0);
    }
}
