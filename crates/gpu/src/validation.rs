//! The Khronos validation layer with GPU-assisted validation, on request (`CAUSTICS_VALIDATION=1`).
//!
//! wgpu's own way (`InstanceFlags::VALIDATION | GPU_BASED_VALIDATION`) does not work with the layer
//! Debian 12 ships (1.3.239): wgpu relays the layer's messages only when `InstanceFlags::DEBUG` is
//! set, and with `DEBUG` wgpu-core hands naga the WGSL source as debug info, so every module starts
//! with `OpSource WGSL` (source language 10), which that layer's SPIR-V parser refuses: every shader
//! is reported invalid and GPU-assisted validation instruments none of them. So the Vulkan instance
//! is made here, with `ash`: the layer, `VK_EXT_debug_utils` with a messenger of our own that keeps
//! every message it is given, and `VkValidationFeaturesEXT` asking for GPU-assisted validation; it
//! is handed to wgpu with `wgpu_hal::vulkan::Instance::from_raw` without `DEBUG`, so naga writes no
//! `OpSource` and the layer can instrument each module. The device is made without robust buffer
//! access (`request_device`), under which the layer would not look for out-of-bounds accesses.
//!
//! A [`GpuContext`](crate::GpuContext) on such an instance reports the messages as a
//! [`GpuError::Validation`] from `check()`; one made by the test helpers
//! (`context::test_gpu`) panics when it is dropped with messages it never reported, so a GPU
//! test fails on any; and [`all_messages`] lists every message of the process, for a program to
//! refuse to exit cleanly after one (the `caustics` binary does).

use std::ffi::{CStr, c_void};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use ash::vk::Handle;
use ash::{ext, vk};
use wgpu::hal;

use crate::GpuError;

/// The environment variable that turns validation on (value `1`).
pub const ENV: &str = "CAUSTICS_VALIDATION";

const LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";

/// Whether `CAUSTICS_VALIDATION=1`.
pub fn requested() -> bool {
    std::env::var(ENV).is_ok_and(|v| v == "1")
}

/// The messages one instance's messenger was given, in order, and how many of them `check()` has
/// already reported.
struct Sink {
    /// The `VkInstance` while it lives (0 before and after), to find the sink from a wgpu instance.
    instance: AtomicU64,
    messages: Mutex<(Vec<String>, usize)>,
}

impl Sink {
    fn lock(&self) -> std::sync::MutexGuard<'_, (Vec<String>, usize)> {
        // A poisoned lock still holds every message; the callback must not panic across the FFI.
        self.messages.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Every sink of the process. They are never freed: the messenger's user data points at one, and
/// the layer may call it until the instance is destroyed, which happens inside wgpu.
static SINKS: Mutex<Vec<Arc<Sink>>> = Mutex::new(Vec::new());

/// Set by the test helpers: a dropped context with unreported messages then panics.
static PANIC_ON_DROP: AtomicBool = AtomicBool::new(false);

fn sinks() -> std::sync::MutexGuard<'static, Vec<Arc<Sink>>> {
    SINKS.lock().unwrap_or_else(|e| e.into_inner())
}

unsafe extern "system" fn on_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    kind: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: `user` is the `Sink` this messenger was made with, kept alive in `SINKS` for the
    // life of the process; `data` is valid for this call (Vulkan spec, PFN_vkDebugUtilsMessengerCallbackEXT).
    let (sink, data) = unsafe { (&*(user as *const Sink), &*data) };
    let text = |p: *const std::ffi::c_char| {
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: a non-null string of the callback data is NUL-terminated.
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    let line = format!(
        "{severity:?} {kind:?} [{} {:#x}] {}",
        text(data.p_message_id_name),
        data.message_id_number as u32,
        text(data.p_message)
    );
    tracing::error!("Vulkan validation layer: {line}");
    sink.lock().0.push(line);
    vk::FALSE
}

fn messenger_info(sink: &Sink) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
    vk::DebugUtilsMessengerCreateInfoEXT::default()
        // Not INFO or VERBOSE: there the loader lists the manifests it read and the layer says
        // which checks it runs, on every instance.
        .message_severity(
            vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
        )
        .message_type(
            vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
        )
        .pfn_user_callback(Some(on_message))
        .user_data(sink as *const Sink as *mut c_void)
}

fn refuse(why: impl std::fmt::Display) -> GpuError {
    GpuError::BadOption(format!("{ENV}=1: {why}"))
}

/// A Vulkan instance under the validation layer with GPU-assisted validation, wrapped for wgpu.
/// Fails (rather than running unvalidated) when the layer or its validation-features extension is
/// missing, or when `backends` leaves Vulkan out.
pub fn instance(backends: wgpu::Backends) -> Result<wgpu::Instance, GpuError> {
    if !backends.contains(wgpu::Backends::VULKAN) {
        return Err(refuse(format!(
            "the validation layer is Vulkan's, and the backends asked for are {backends:?}"
        )));
    }
    // SAFETY: loading the system's Vulkan loader, as wgpu-hal does.
    let entry =
        unsafe { ash::Entry::load() }.map_err(|e| refuse(format!("no Vulkan loader: {e}")))?;
    // SAFETY: plain queries of the loader (this and the calls below up to `create_instance`).
    let version = unsafe { entry.try_enumerate_instance_version() }
        .map_err(refuse)?
        .unwrap_or(vk::API_VERSION_1_0);
    let layers = unsafe { entry.enumerate_instance_layer_properties() }.map_err(refuse)?;
    if !layers.iter().any(|l| l.layer_name_as_c_str() == Ok(LAYER)) {
        return Err(refuse(
            "the Khronos validation layer is not installed (Debian: vulkan-validationlayers)",
        ));
    }
    let layer_extensions =
        unsafe { entry.enumerate_instance_extension_properties(Some(LAYER)) }.map_err(refuse)?;
    if !layer_extensions
        .iter()
        .any(|e| e.extension_name_as_c_str() == Ok(ext::validation_features::NAME))
    {
        return Err(refuse(
            "the validation layer lacks VK_EXT_validation_features (needed for GPU-assisted validation)",
        ));
    }

    // No `DEBUG`: it is what makes naga write `OpSource WGSL` (see the module's comment).
    let flags = wgpu::InstanceFlags::VALIDATION | wgpu::InstanceFlags::GPU_BASED_VALIDATION;
    let mut extensions =
        hal::vulkan::Instance::desired_extensions(&entry, version, flags).map_err(refuse)?;
    // Provided by the layer (and the loader), so present whatever `desired_extensions` found.
    for name in [ext::debug_utils::NAME, ext::validation_features::NAME] {
        if !extensions.contains(&name) {
            extensions.push(name);
        }
    }

    let sink = Arc::new(Sink {
        instance: AtomicU64::new(0),
        messages: Mutex::new((Vec::new(), 0)),
    });
    sinks().push(sink.clone());
    let app_info = vk::ApplicationInfo::default()
        .application_name(c"caustics")
        .engine_name(c"wgpu-hal")
        // The newest version wgpu-hal 30 is written for (as its own `init` asks).
        .api_version(version.min(vk::API_VERSION_1_3));
    let names: Vec<*const std::ffi::c_char> = extensions.iter().map(|e| e.as_ptr()).collect();
    let layer_names = [LAYER.as_ptr()];
    // GPU-assisted validation instruments every shader to check, at run time, descriptor and
    // buffer accesses; the reserved binding slot is where it binds its own output buffer (the
    // layer lowers `maxBoundDescriptorSets` by one to keep it free).
    let enables = [
        vk::ValidationFeatureEnableEXT::GPU_ASSISTED,
        vk::ValidationFeatureEnableEXT::GPU_ASSISTED_RESERVE_BINDING_SLOT,
    ];
    let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(&enables);
    // Also chained here so that vkCreateInstance and vkDestroyInstance report to the sink.
    let mut during_creation = messenger_info(&sink);
    let create = vk::InstanceCreateInfo::default()
        .application_info(&app_info)
        .enabled_layer_names(&layer_names)
        .enabled_extension_names(&names)
        .push_next(&mut features)
        .push_next(&mut during_creation);
    // SAFETY: every pointer in `create` outlives the call.
    let raw = unsafe { entry.create_instance(&create, None) }
        .map_err(|e| refuse(format!("vkCreateInstance under the layer failed: {e}")))?;
    sink.instance.store(raw.handle().as_raw(), Ordering::SeqCst);
    let debug_utils = ext::debug_utils::Instance::new(&entry, &raw);
    // SAFETY: `raw` is a live instance with VK_EXT_debug_utils enabled.
    let messenger =
        match unsafe { debug_utils.create_debug_utils_messenger(&messenger_info(&sink), None) } {
            Ok(m) => m,
            Err(e) => {
                // SAFETY: nothing else has the instance yet.
                unsafe { raw.destroy_instance(None) };
                return Err(refuse(format!(
                    "vkCreateDebugUtilsMessengerEXT failed: {e}"
                )));
            }
        };
    let owned = raw.clone();
    let dropped = sink.clone();
    // wgpu-hal drops its `Entry` (which unloads the Vulkan loader once the last clone goes) before
    // it calls this; the clone keeps the loader's functions callable here.
    let loader = entry.clone();
    let drop_callback: hal::DropCallback = Box::new(move || {
        // SAFETY: called once, when wgpu-hal drops the instance, which it no longer uses.
        unsafe {
            debug_utils.destroy_debug_utils_messenger(messenger, None);
            owned.destroy_instance(None);
        }
        // A later instance may get the same handle.
        dropped.instance.store(0, Ordering::SeqCst);
        drop(loader);
    });
    // SAFETY: `raw` was made from `entry` with `version`, `extensions` (a superset of
    // `desired_extensions`, from the same entry) and `flags`; with a drop callback, wgpu-hal
    // leaves destroying it to us, after its last use.
    let hal_instance = unsafe {
        hal::vulkan::Instance::from_raw(
            entry,
            raw,
            version,
            0,
            None,
            extensions,
            flags,
            wgpu::MemoryBudgetThresholds::default(),
            false,
            Some(drop_callback),
        )
    }
    .map_err(refuse)?;
    // SAFETY: a valid Vulkan instance, owned by wgpu from here on.
    Ok(unsafe { wgpu::Instance::from_hal::<hal::api::Vulkan>(hal_instance) })
}

/// Whether `instance` was made by [`instance`].
pub(crate) fn owns(instance: &wgpu::Instance) -> bool {
    sink_of(instance).is_some()
}

/// The device wgpu's `Adapter::request_device` would make, but without robust buffer access
/// (`robustBufferAccess`, `robustBufferAccess2`): with it, an out-of-bounds buffer access is
/// defined (clamped or dropped) and GPU-assisted validation does not look for one. wgpu still
/// compiles its shaders for the adapter, whose `robustBufferAccess2` lets naga leave buffer
/// accesses unchecked, so every access past a binding our WGSL makes reaches the layer.
pub(crate) fn request_device(
    adapter: &wgpu::Adapter,
    desc: &wgpu::DeviceDescriptor<'_>,
) -> Result<(wgpu::Device, wgpu::Queue), GpuError> {
    let failed = |e: &dyn std::fmt::Display| GpuError::RequestDevice(format!("{ENV}=1: {e}"));
    // SAFETY: the adapter is only queried and its device made as wgpu-hal's `open` makes it.
    let open = unsafe {
        let hal_adapter = adapter
            .as_hal::<hal::api::Vulkan>()
            .ok_or_else(|| failed(&"not a Vulkan adapter"))?;
        let features = desc.required_features;
        let extensions = hal_adapter.required_device_extensions(features);
        let mut enabled = hal_adapter.physical_device_features(&extensions, features);
        let mut core = enabled.get_core();
        core.robust_buffer_access = vk::FALSE;
        let names: Vec<*const std::ffi::c_char> = extensions.iter().map(|e| e.as_ptr()).collect();
        // Queue family 0, as wgpu-hal 30's `open_with_callback` takes.
        let families = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(0)
            .queue_priorities(&[1.0])];
        let mut info = enabled.add_to_device_create(
            vk::DeviceCreateInfo::default()
                .queue_create_infos(&families)
                .enabled_extension_names(&names),
        );
        info.p_enabled_features = &core;
        // The chain points into `enabled`, which `info` borrows mutably.
        let mut next = info.p_next as *mut vk::BaseOutStructure<'_>;
        while !next.is_null() {
            if (*next).s_type == vk::StructureType::PHYSICAL_DEVICE_ROBUSTNESS_2_FEATURES_EXT {
                (*(next as *mut vk::PhysicalDeviceRobustness2FeaturesEXT<'_>))
                    .robust_buffer_access2 = vk::FALSE;
            }
            next = (*next).p_next;
        }
        let raw = hal_adapter
            .shared_instance()
            .raw_instance()
            .create_device(hal_adapter.raw_physical_device(), &info, None)
            .map_err(|e| failed(&e))?;
        hal_adapter
            .device_from_raw(
                raw,
                None,
                &extensions,
                features,
                &desc.required_limits,
                &desc.memory_hints,
                0,
                0,
            )
            .map_err(|e| failed(&e))?
    };
    // SAFETY: `open` was made from this adapter with `desc`'s features and limits.
    unsafe { adapter.create_device_from_hal::<hal::api::Vulkan>(open, desc) }
        .map_err(|e| failed(&e))
}

/// The sink of an instance made by [`instance`], if `instance` is one.
fn sink_of(instance: &wgpu::Instance) -> Option<Arc<Sink>> {
    // SAFETY: only the handle is read.
    let hal_instance = unsafe { instance.as_hal::<hal::api::Vulkan>() }?;
    let raw = hal_instance
        .shared_instance()
        .raw_instance()
        .handle()
        .as_raw();
    sinks()
        .iter()
        .find(|s| s.instance.load(Ordering::SeqCst) == raw)
        .cloned()
}

fn report(messages: &[String]) -> String {
    format!(
        "the Vulkan validation layer reported {} message(s):\n{}",
        messages.len(),
        messages.join("\n")
    )
}

/// What a [`GpuContext`](crate::GpuContext) on a validation instance keeps: the instance's
/// messages, reported by `check()`, and a last look when the context is dropped.
pub(crate) struct Guard {
    sink: Arc<Sink>,
}

impl Guard {
    /// `Some` when `instance` was made by [`instance`].
    pub(crate) fn of(instance: &wgpu::Instance) -> Option<Self> {
        sink_of(instance).map(|sink| Guard { sink })
    }

    /// The messages not yet reported, as an error.
    pub(crate) fn check(&self) -> Result<(), GpuError> {
        let mut guard = self.sink.lock();
        let (messages, reported) = &mut *guard;
        if *reported == messages.len() {
            return Ok(());
        }
        let new = &messages[*reported..];
        *reported = messages.len();
        Err(GpuError::Validation(report(new)))
    }
}

impl Drop for Guard {
    /// In tests, messages no `check()` reported fail the test here (a context is dropped after
    /// its device, so messages about leaked objects count too).
    fn drop(&mut self) {
        if !PANIC_ON_DROP.load(Ordering::SeqCst) || std::thread::panicking() {
            return;
        }
        let guard = self.sink.lock();
        let (messages, reported) = &*guard;
        if *reported < messages.len() {
            let text = report(&messages[*reported..]);
            drop(guard);
            panic!("{text}");
        }
    }
}

/// Make contexts panic when dropped with unreported messages (the test helpers call it).
pub(crate) fn panic_on_drop() {
    PANIC_ON_DROP.store(true, Ordering::SeqCst);
}

/// Every message the layer gave this process, reported or not, in order per instance.
pub fn all_messages() -> Vec<String> {
    sinks().iter().flat_map(|s| s.lock().0.clone()).collect()
}
