// Technique `caustic-triangles` with the water surface as the generator: the uniform block of the
// water passes (the water photon pass, the copy band pass).
// Mirrors `WaterPhotonUniform` in caustic_triangles/uniforms.rs and `WaterSetup` in water.rs.

import package::shaders::receivers::Receivers;

struct WaterPhoton {
    light: vec4<f32>,   // xyz: unit direction the sunlight travels; w: index of refraction of the water
    water: vec4<f32>,   // x: depth; y: size of the square; z: lattice spacing; w: T(theta0), 1 without Fresnel
    lattice: u32,       // quads per side, P (P + 1 photons per side)
    wrap: u32,          // the surface tiles: heights sampled wrapped
    fresnel: u32,
    receiver: u32,      // 0: the floor; 1 + k: wall k of Wall::ALL (x = 0, x = size, y = 0, y = size)
    receivers: Receivers, // what the floor's photons meet (t0.w = 0: the plane z = 0)
    origin: vec4<f32>,  // xy: where photon (0, 0) lies (upwind of the square for clamped water)
}
