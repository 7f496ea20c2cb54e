// Technique `caustic-triangles` with the water surface as the caustic generator, the water photon
// pass (paper §4.1, the photon image of a height field): photon (i, j) at the lattice corner
// (j, i) * spacing of the water square, its surface point from the bicubic height interpolant, the
// sun refracted by exact Snell through its true normal, the floor z = 0 met analytically. Writes
// (x, y, power, 1) of the floor hit (power -1 where the surface faces away from the sun) and the
// refracted path length (Beer-Lambert in the triangles pass). Power: the cell's area projected
// along the light onto the horizontal, times the Fresnel transmittance relative to flat water (the
// reference's normalisation). CPU twin: `photon` in
// caustics-core/src/techniques/caustic_triangles/water.rs.

// The uniform block `WaterPhoton`: water_setup.wgsl.
@group(0) @binding(0) var<uniform> w: WaterPhoton;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> photons: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> paths: array<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = w.lattice + 1u;
    if id.x >= p || id.y >= p {
        return;
    }
    let k = id.y * p + id.x;
    let s = vec2<f32>(f32(id.x), f32(id.y)) * w.water.z;
    let hg = grid_sample(heights, s, w.water.y, w.wrap != 0u);
    let l = w.light.xyz;
    let n = height_field_normal(hg.yz);
    let cos_i = -dot(l, n);
    // The cell's area as the sun sees it, over the flat cell's.
    let seen = 1.0 + dot(l.xy, hg.yz) / -l.z;
    let t = refract_dir(l, n, 1.0 / w.light.w);
    if t.w == 0.0 || cos_i <= 0.0 || seen <= 0.0 || t.z >= 0.0 {
        photons[k] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
        paths[k] = 0.0;
        return;
    }
    let d = (w.water.x + hg.x) / -t.z;
    var fresnel = 1.0;
    if w.fresnel != 0u {
        fresnel = fresnel_transmittance(cos_i, 1.0, w.light.w) / w.water.w;
    }
    photons[k] = vec4<f32>(s + t.xy * d, w.water.z * w.water.z * seen * fresnel, 1.0);
    paths[k] = d;
}
