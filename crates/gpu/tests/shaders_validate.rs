//! Every WGSL pass, composed with the shared math it includes, parses and validates with naga. Needs
//! no GPU, so a shader error fails CI even where no adapter exists.

use caustics_gpu::shaders::ALL_PASSES;

#[test]
fn every_pass_parses_and_validates() {
    assert!(!ALL_PASSES.is_empty());
    for pass in ALL_PASSES {
        let source = pass.composed();
        let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| {
            panic!("{}: {}", pass.name, e.emit_to_string(&source));
        });
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{}: {}", pass.name, e.emit_to_string(&source)));
    }
}

#[test]
fn uniform_structs_match_their_wgsl_size() {
    let source = caustics_gpu::shaders::PROBE.composed();
    let module = naga::front::wgsl::parse_str(&source).unwrap();
    let size_of = |name: &str| {
        let (_, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no WGSL struct {name}"));
        ty.inner.size(module.to_ctx()) as usize
    };
    use caustics_gpu::probe::{ProbeIn, ProbeOut};
    use caustics_gpu::water::{GpuProceduralWave, GpuSineWave};
    assert_eq!(size_of("SineWave"), std::mem::size_of::<GpuSineWave>());
    assert_eq!(
        size_of("ProceduralWave"),
        std::mem::size_of::<GpuProceduralWave>()
    );
    assert_eq!(size_of("ProbeIn"), std::mem::size_of::<ProbeIn>());
    assert_eq!(size_of("ProbeOut"), std::mem::size_of::<ProbeOut>());
}

/// The size naga gives the WGSL struct `name` of a pass.
fn wgsl_size(pass: &caustics_gpu::shaders::PassSource, name: &str) -> usize {
    let module = naga::front::wgsl::parse_str(&pass.composed()).unwrap();
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("{}: no WGSL struct {name}", pass.name));
    ty.inner.size(module.to_ctx()) as usize
}

#[test]
fn water_uniform_structs_match_their_wgsl_size() {
    use caustics_gpu::shaders::{OCEAN_FFT, OCEAN_SPECTRUM, RIPPLE_DROP, RIPPLE_STEP};
    use caustics_gpu::water::ocean::{FftStage, SpectrumParams};
    use caustics_gpu::water::ripple::{RippleDrop, RippleStep};
    use std::mem::size_of;
    assert_eq!(
        wgsl_size(&OCEAN_SPECTRUM, "SpectrumParams"),
        size_of::<SpectrumParams>()
    );
    assert_eq!(wgsl_size(&OCEAN_FFT, "FftStage"), size_of::<FftStage>());
    assert_eq!(
        wgsl_size(&RIPPLE_STEP, "RippleStep"),
        size_of::<RippleStep>()
    );
    assert_eq!(
        wgsl_size(&RIPPLE_DROP, "RippleDrop"),
        size_of::<RippleDrop>()
    );
}

#[test]
fn yuksel_pass1_validates_for_every_target_count() {
    for targets in 1..=8 {
        let source = caustics_gpu::yuksel::pass1_source(targets);
        let module = naga::front::wgsl::parse_str(&source)
            .unwrap_or_else(|e| panic!("{targets} targets: {}", e.emit_to_string(&source)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{targets} targets: {}", e.emit_to_string(&source)));
    }
    let source = caustics_gpu::yuksel::PASS2.composed();
    let module = naga::front::wgsl::parse_str(&source).unwrap();
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Yuksel"))
        .unwrap();
    assert_eq!(
        ty.inner.size(module.to_ctx()) as usize,
        std::mem::size_of::<caustics_gpu::yuksel::YukselUniform>()
    );
}

#[test]
fn final_image_structs_match_their_wgsl_size() {
    use caustics_gpu::final_image::{
        FINAL_IMAGE, FinalImageUniform, GpuBvhNode, GpuBvhTriangle, GpuObject,
    };
    use std::mem::size_of;
    assert_eq!(
        wgsl_size(&FINAL_IMAGE, "FinalImage"),
        size_of::<FinalImageUniform>()
    );
    assert_eq!(wgsl_size(&FINAL_IMAGE, "Object"), size_of::<GpuObject>());
    assert_eq!(wgsl_size(&FINAL_IMAGE, "BvhNode"), size_of::<GpuBvhNode>());
    assert_eq!(
        wgsl_size(&FINAL_IMAGE, "BvhTriangle"),
        size_of::<GpuBvhTriangle>()
    );
}

#[test]
fn procedural_uniform_matches_its_wgsl_size() {
    use caustics_gpu::procedural::{ProceduralUniform, RESAMPLE, SCREEN, TARGET, VERTEX};
    for pass in [&VERTEX, &SCREEN, &TARGET, &RESAMPLE] {
        assert_eq!(
            wgsl_size(pass, "Procedural"),
            std::mem::size_of::<ProceduralUniform>(),
            "{}",
            pass.name
        );
    }
}
