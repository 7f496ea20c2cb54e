//! [`crate::validation`] in a build without the `validation` feature: `CAUSTICS_VALIDATION=1` is
//! refused by name instead of running unvalidated, and a context never holds a layer's messages.

use crate::GpuError;

/// The environment variable that would turn validation on.
const ENV: &str = "CAUSTICS_VALIDATION";

pub fn requested() -> bool {
    std::env::var(ENV).is_ok_and(|v| v == "1")
}

pub fn instance(_backends: wgpu::Backends) -> Result<wgpu::Instance, GpuError> {
    Err(GpuError::RequestDevice(format!(
        "{ENV}=1 needs caustics-gpu's `validation` feature, which this build leaves out"
    )))
}

pub(crate) fn owns(_instance: &wgpu::Instance) -> bool {
    false
}

pub(crate) fn request_device(
    _adapter: &wgpu::Adapter,
    _desc: &wgpu::DeviceDescriptor<'_>,
) -> Result<(wgpu::Device, wgpu::Queue), GpuError> {
    unreachable!("no instance of this build is the validation layer's")
}

/// Never made: no instance of this build is the validation layer's.
pub(crate) enum Guard {}

impl Guard {
    pub(crate) fn of(_instance: &wgpu::Instance) -> Option<Self> {
        None
    }

    pub(crate) fn check(&self) -> Result<(), GpuError> {
        match *self {}
    }
}

pub(crate) fn panic_on_drop() {}
