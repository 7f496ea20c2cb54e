struct WaterPhoton {
    light: vec4<f32>,
    water: vec4<f32>,
    lattice: u32,
    wrap: u32,
    fresnel: u32,
    receiver: u32,
    receivers: package_shaders_receivers_Receivers
}

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}
