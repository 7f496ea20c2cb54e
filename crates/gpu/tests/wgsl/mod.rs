//! naga's view of the compiled passes, for the tests that hold WGSL to its Rust twins without a GPU.

// Not every test file uses every helper.
#![allow(dead_code)]

/// naga parses and validates a compiled pass; a failure names the pass and points into its WGSL.
pub fn validated(pass: &caustics_gpu::shaders::PassSource) {
    validated_wgsl(pass.name, pass.source);
}

/// naga parses and validates `source`; a failure names `label` and points into the source.
pub fn validated_wgsl(label: &str, source: &str) {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(source)));
}

/// The size naga gives the struct `name` of a compiled pass, declared in the pass or in a module it
/// imports (build.rs's WESL compiler names those `package_<module path>_name`).
pub fn wgsl_struct_size(pass: &caustics_gpu::shaders::PassSource, name: &str) -> usize {
    let module = naga::front::wgsl::parse_str(pass.source).unwrap();
    let suffix = format!("_{name}");
    let ty = module
        .types
        .iter()
        .map(|(_, t)| t)
        .find(|t| {
            t.name
                .as_deref()
                .is_some_and(|n| n == name || n.ends_with(&suffix))
        })
        .unwrap_or_else(|| panic!("{}: no WGSL struct {name}", pass.name));
    ty.inner.size(module.to_ctx()) as usize
}
