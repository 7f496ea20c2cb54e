//! The validation pass can fail: under `CAUSTICS_VALIDATION=1` (as `.ci/run`'s last step sets) an
//! invalid Vulkan call on the context's device must come back from `GpuContext::check` as a
//! `GpuError::Validation` naming the rule, and a context dropped with a message nobody reported
//! must fail its test. Without the flag the tests are reported ignored. (A shader writing past
//! its storage buffer is not reported by Debian 12's layer: see docs/maintainers/reliability.md.)
//!
//! wgpu validates everything it is given, so the invalid call is made on the raw device under it:
//! a buffer created with no usage bit, which Vulkan forbids
//! (`VUID-VkBufferCreateInfo-usage-requiredbitmask`) and drivers accept (lavapipe does).

use caustics_gpu::context::test_gpu;
use caustics_gpu::{GpuContext, GpuError, validation};
use libtest_mimic::{Arguments, Trial};
use wgpu::hal;

const RULE: &str = "VUID-VkBufferCreateInfo-usage-requiredbitmask";

/// Create (and destroy) a buffer with no usage on `ctx`'s raw Vulkan device.
fn invalid_call(ctx: &GpuContext) {
    // SAFETY: the buffer is created and destroyed here, never bound or used; lavapipe accepts
    // an empty usage (it is the layer's rule that it breaks, not the driver's).
    unsafe {
        let device = ctx
            .device
            .as_hal::<hal::api::Vulkan>()
            .expect("a Vulkan device");
        let raw = device.raw_device();
        let info = ash::vk::BufferCreateInfo::default().size(256);
        let buffer = raw.create_buffer(&info, None).expect("lavapipe makes it");
        raw.destroy_buffer(buffer, None);
    }
}

fn an_invalid_call_is_reported_by_check() {
    let ctx = test_gpu();
    ctx.wait().expect("clean before the invalid call");
    invalid_call(&ctx);
    match ctx.check() {
        Err(GpuError::Validation(text)) => assert!(text.contains(RULE), "{text}"),
        other => panic!("the layer's message did not come back: {other:?}"),
    }
    // Reported once: the context drops cleanly.
    ctx.check().expect("each message is reported once");
}

fn a_context_dropped_with_an_unreported_message_fails_its_test() {
    let dropped = std::panic::catch_unwind(|| {
        let ctx = test_gpu();
        invalid_call(&ctx);
    });
    let text = match dropped {
        Err(payload) => payload
            .downcast_ref::<String>()
            .cloned()
            .unwrap_or_default(),
        Ok(()) => panic!("the context dropped without complaint"),
    };
    assert!(text.contains(RULE), "{text}");
}

fn main() -> std::process::ExitCode {
    let args = Arguments::from_args();
    let off = !validation::requested();
    if off {
        eprintln!("validation tests ignored: {} is not 1", validation::ENV);
    }
    let trials = vec![
        Trial::test("an_invalid_call_is_reported_by_check", || {
            an_invalid_call_is_reported_by_check();
            Ok(())
        })
        .with_ignored_flag(off),
        Trial::test(
            "a_context_dropped_with_an_unreported_message_fails_its_test",
            || {
                a_context_dropped_with_an_unreported_message_fails_its_test();
                Ok(())
            },
        )
        .with_ignored_flag(off),
    ];
    libtest_mimic::run(&args, trials).exit_code()
}
