//! Device creation (headless or for a window), adapter selection, and the translation of wgpu's
//! failures into [`GpuError`]s that name the problem.

pub mod traffic;

use std::sync::{Arc, Mutex};

use crate::GpuError;

/// How to pick the adapter. Empty fields fall back to `WGPU_BACKEND` / `WGPU_ADAPTER_NAME`, then to
/// wgpu's default choice.
#[derive(Clone, Debug, Default)]
pub struct GpuOptions {
    /// `vulkan`, `metal`, `dx12` (comma-separated list allowed).
    pub backend: Option<String>,
    /// A case-insensitive substring of the adapter's name.
    pub adapter_name: Option<String>,
}

/// A device and queue with what the techniques need to know about them.
pub struct GpuContext {
    /// The instance the adapter came from; a window's surface is made from it.
    pub instance: wgpu::Instance,
    /// The chosen adapter (the physical GPU and its backend).
    pub adapter: wgpu::Adapter,
    /// The device every technique builds its resources and pipelines on.
    pub device: wgpu::Device,
    /// The device's queue: uploads, uniform writes and submissions.
    pub queue: wgpu::Queue,
    /// The adapter's name, backend, type and driver, read once (see [`describe`](Self::describe)).
    pub info: wgpu::AdapterInfo,
    /// Whether per-pass timestamps can be written.
    pub timestamps: bool,
    errors: Arc<Mutex<Vec<String>>>,
    lost: Arc<Mutex<Option<String>>>,
    pub(crate) traffic: Arc<traffic::Traffic>,
    /// The validation layer's messages, where the instance is `validation::instance`'s. Last, so
    /// that it is dropped after the device and the instance (see `validation::Guard`'s `Drop`).
    #[cfg(not(target_arch = "wasm32"))]
    validation: Option<crate::validation::Guard>,
}

/// The backends a comma-separated list names (`vulkan`, `metal`, `dx12`, `gl` and their common
/// spellings, any case), as [`GpuOptions::backend`] and `WGPU_BACKEND` are read; an unknown name is
/// a [`GpuError::BadOption`] naming it. A command line can check its option with it before any
/// device is made.
pub fn parse_backends(s: &str) -> Result<wgpu::Backends, GpuError> {
    let mut b = wgpu::Backends::empty();
    for part in s.split(',').map(|p| p.trim().to_ascii_lowercase()) {
        b |= match part.as_str() {
            "vulkan" | "vk" => wgpu::Backends::VULKAN,
            "metal" | "mtl" => wgpu::Backends::METAL,
            "dx12" | "d3d12" => wgpu::Backends::DX12,
            "gl" | "gles" | "opengl" => wgpu::Backends::GL,
            "" => continue,
            other => {
                return Err(GpuError::BadOption(format!(
                    "unknown backend `{other}` (expected vulkan, metal, dx12 or gl)"
                )));
            }
        };
    }
    Ok(b)
}

impl GpuContext {
    /// A device without a window, for rendering to textures, compute and tests. Native only: a
    /// page cannot block, so there [`create`](Self::create) is awaited.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn headless(options: &GpuOptions) -> Result<Self, GpuError> {
        pollster::block_on(Self::create(options, None))
    }

    /// Create the instance alone (the viewer needs it to make a window surface first). With
    /// `CAUSTICS_VALIDATION=1`, under the Vulkan validation layer (the `validation` module, with the `validation` feature).
    pub fn instance(options: &GpuOptions) -> Result<wgpu::Instance, GpuError> {
        #[cfg(not(target_arch = "wasm32"))]
        if crate::validation::requested() {
            let backends = match &options.backend {
                Some(b) => parse_backends(b)?,
                None => wgpu::Backends::from_env().unwrap_or(wgpu::Backends::VULKAN),
            };
            return crate::validation::instance(backends);
        }
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        if let Some(b) = &options.backend {
            desc.backends = parse_backends(b)?;
        }
        Ok(wgpu::Instance::new(desc))
    }

    /// Pick an adapter and create the device; `surface` restricts the choice to adapters that can
    /// present to it.
    pub async fn create(
        options: &GpuOptions,
        surface: Option<(&wgpu::Instance, &wgpu::Surface<'_>)>,
    ) -> Result<Self, GpuError> {
        let instance = match surface {
            Some((i, _)) => i.clone(),
            None => Self::instance(options)?,
        };
        let backends = match &options.backend {
            Some(b) => parse_backends(b)?,
            None => wgpu::Backends::from_env().unwrap_or(wgpu::Backends::all()),
        };
        let wanted = options
            .adapter_name
            .clone()
            .or_else(|| std::env::var("WGPU_ADAPTER_NAME").ok())
            .map(|s| s.to_lowercase());
        let adapters = instance.enumerate_adapters(backends).await;
        let names: Vec<String> = adapters
            .iter()
            .map(|a| format!("{} ({:?})", a.get_info().name, a.get_info().backend))
            .collect();
        let usable = |a: &wgpu::Adapter| surface.is_none_or(|(_, s)| a.is_surface_supported(s));
        let adapter = match &wanted {
            Some(w) => adapters
                .into_iter()
                .find(|a| a.get_info().name.to_lowercase().contains(w) && usable(a))
                .ok_or_else(|| GpuError::NoAdapter {
                    wanted: format!("an adapter whose name contains `{w}`"),
                    seen: names.clone(),
                })?,
            None => instance
                .request_adapter(&wgpu::RequestAdapterOptions {
                    power_preference: wgpu::PowerPreference::from_env()
                        .unwrap_or(wgpu::PowerPreference::HighPerformance),
                    compatible_surface: surface.map(|(_, s)| s),
                    force_fallback_adapter: false,
                    apply_limit_buckets: false,
                })
                .await
                .map_err(|e| GpuError::NoAdapter {
                    wanted: format!("any adapter ({e})"),
                    seen: names.clone(),
                })?,
        };
        let available = adapter.features();
        let wanted_features = wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS
            | wgpu::Features::FLOAT32_FILTERABLE
            | wgpu::Features::FLOAT32_BLENDABLE;
        let features = available & wanted_features;
        let desc = wgpu::DeviceDescriptor {
            label: Some("caustics"),
            required_features: features,
            required_limits: adapter.limits(),
            ..Default::default()
        };
        #[cfg(not(target_arch = "wasm32"))]
        if crate::validation::owns(&instance) {
            let (device, queue) = crate::validation::request_device(&adapter, &desc)?;
            return Ok(Self::from_parts(instance, adapter, device, queue));
        }
        let (device, queue) = adapter
            .request_device(&desc)
            .await
            .map_err(|e| GpuError::RequestDevice(e.to_string()))?;

        Ok(Self::from_parts(instance, adapter, device, queue))
    }

    /// Wrap a device the application already owns (an engine's, a game's), so that the techniques
    /// record into its queue and command encoders. The features and limits are the device's own:
    /// timestamps are used only where it was created with `TIMESTAMP_QUERY`, and techniques that need
    /// more than it has say so when they are built. This installs the uncaptured-error and
    /// device-lost handlers that turn wgpu's failures into [`GpuError`]s (see [`check`](Self::check)),
    /// replacing any the application had set.
    pub fn from_parts(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> Self {
        let ctx = Self::shared(instance, adapter, device, queue);
        let sink = ctx.errors.clone();
        ctx.device
            .on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
                tracing::error!("GPU error: {e}");
                sink.lock().expect("error sink").push(e.to_string());
            }));
        let lost_sink = ctx.lost.clone();
        ctx.device.set_device_lost_callback(move |reason, message| {
            *lost_sink.lock().expect("lost flag") = Some(lost_reason(reason, &message));
        });
        ctx
    }

    /// Wrap an engine's device as [`from_parts`](Self::from_parts) does, leaving its
    /// uncaptured-error and device-lost handlers in place: the engine reports wgpu's failures
    /// (Bevy's `bevy_caustics` records into Bevy's device), and [`check`](Self::check) sees only
    /// a loss it polls for and the validation layer's messages.
    pub fn shared(
        instance: wgpu::Instance,
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> Self {
        let info = adapter.get_info();
        let errors = Arc::new(Mutex::new(Vec::new()));
        let lost = Arc::new(Mutex::new(None));
        tracing::info!(
            "GPU adapter: {} ({:?}, {:?})",
            info.name,
            info.backend,
            info.device_type
        );
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        #[cfg(not(target_arch = "wasm32"))]
        let validation = crate::validation::Guard::of(&instance);
        GpuContext {
            instance,
            adapter,
            device,
            queue,
            info,
            timestamps,
            errors,
            lost,
            traffic: Default::default(),
            #[cfg(not(target_arch = "wasm32"))]
            validation,
        }
    }

    /// One line naming the adapter, for logs and benchmark tables.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {:?}, driver {} {})",
            self.info.name,
            self.info.backend,
            self.info.device_type,
            self.info.driver,
            self.info.driver_info
        )
    }

    /// The device's limits: the adapter's own for a device made here, the application's for a
    /// wrapped one.
    pub fn limits(&self) -> wgpu::Limits {
        self.device.limits()
    }

    /// Refuse a 2-D texture the device cannot hold, naming what it was for.
    pub fn check_texture_size(&self, what: &str, width: u32, height: u32) -> Result<(), GpuError> {
        let max = self.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(GpuError::TooLarge {
                what: what.to_string(),
                size: format!("{width} x {height}"),
                limit: format!("1 .. {max} per side"),
            });
        }
        Ok(())
    }

    /// Refuse a storage buffer the device cannot bind.
    pub fn check_buffer_size(&self, what: &str, bytes: u64) -> Result<(), GpuError> {
        let l = self.limits();
        let max = l.max_storage_buffer_binding_size.min(l.max_buffer_size);
        if bytes == 0 || bytes > max {
            return Err(GpuError::TooLarge {
                what: what.to_string(),
                size: format!("{bytes} bytes"),
                limit: format!("{max} bytes"),
            });
        }
        Ok(())
    }

    /// Turn any error wgpu reported since the last call, a lost device, or (with
    /// `CAUSTICS_VALIDATION=1`) a message of the validation layer, into a `GpuError`.
    pub fn check(&self) -> Result<(), GpuError> {
        self.notice_loss();
        if let Some(reason) = self.lost.lock().expect("lost flag").clone() {
            return Err(GpuError::DeviceLost(reason));
        }
        let mut errors = self.errors.lock().expect("error sink");
        if !errors.is_empty() {
            let all = errors.join("\n");
            errors.clear();
            return Err(GpuError::Validation(all));
        }
        drop(errors);
        #[cfg(not(target_arch = "wasm32"))]
        if let Some(v) = &self.validation {
            return v.check();
        }
        Ok(())
    }

    /// wgpu runs the device-lost callback only while it maintains the device (a poll): after a
    /// loss, work is dropped without an error, so without this `check` would report success on
    /// frames that never ran. A non-blocking poll costs a fence query.
    fn notice_loss(&self) {
        if let Err(e) = self.device.poll(wgpu::PollType::Poll) {
            let mut lost = self.lost.lock().expect("lost flag");
            lost.get_or_insert_with(|| e.to_string());
        }
    }

    /// Whether the device is known to be lost (after a poll to find out).
    pub(crate) fn is_lost(&self) -> bool {
        self.notice_loss();
        self.lost.lock().expect("lost flag").is_some()
    }

    /// Block until the queue is idle, then [`check`](Self::check).
    pub fn wait(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::DeviceLost(e.to_string()))?;
        self.check()
    }
}

/// What the device-lost callback says, in words: wgpu's message is empty for `destroy()`.
fn lost_reason(reason: wgpu::DeviceLostReason, message: &str) -> String {
    let why = match reason {
        wgpu::DeviceLostReason::Destroyed => "the device was destroyed",
        wgpu::DeviceLostReason::Unknown => "the driver lost it (a reset, a removed GPU, a crash)",
    };
    if message.is_empty() {
        why.to_string()
    } else {
        format!("{why}: {message}")
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn gpu_required() -> bool {
    std::env::var("CAUSTICS_REQUIRE_GPU").is_ok_and(|v| v == "1")
}

#[cfg(not(target_arch = "wasm32"))]
/// Why the GPU tests cannot run here, for a test harness to report them as ignored; `None` when a
/// device can be created, and always `None` with `CAUSTICS_REQUIRE_GPU=1` (as `.ci/run` sets), so
/// that there the tests run and fail in [`test_gpu`]: CI must not pass by skipping. With
/// `CAUSTICS_VALIDATION=1` (both helpers) a test context panics when dropped with a message of
/// the validation layer that no `check` reported, so a GPU test fails on any.
pub fn gpu_test_skip() -> Option<String> {
    crate::validation::panic_on_drop();
    if gpu_required() {
        return None;
    }
    GpuContext::headless(&GpuOptions::default())
        .err()
        .map(|e| format!("no GPU device: {e}"))
}

#[cfg(not(target_arch = "wasm32"))]
/// The device for a GPU test that its harness let run (see [`gpu_test_skip`]). Without one the
/// test fails rather than passing unrun: that happens with `CAUSTICS_REQUIRE_GPU=1` or when an
/// ignored GPU test is asked for with `--ignored` / `--include-ignored`.
pub fn test_gpu() -> GpuContext {
    crate::validation::panic_on_drop();
    GpuContext::headless(&GpuOptions::default())
        .unwrap_or_else(|e| panic!("a GPU test without a GPU device: {e}"))
}
