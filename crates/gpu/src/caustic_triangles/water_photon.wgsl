// Technique `caustic-triangles` with the water surface as the caustic generator, the water photon
// pass (paper §4.1, the photon image of a height field): photon (i, j) at the lattice corner
// origin + (j, i) * spacing (over the square, or reaching upwind of it where the water does not
// tile), its surface point from the bicubic height interpolant, the sun refracted by exact Snell
// through its true normal, the floor z = 0 met analytically, or, over
// a terrain, the receivers' map met by marching and the hit written at its light-space point
// (docs/receivers.md). Writes (x, y, power, 1) of the floor hit (power -1 where the surface faces away from the sun) and the
// refracted path length (Beer-Lambert in the triangles pass). Power: the cell's area projected
// along the light onto the horizontal, times the Fresnel transmittance relative to flat water (the
// reference's normalisation). With walls each receiver (the floor, one wall) has its own photon
// image: the rays extended to its plane, a wall's hits as (along, z size / depth) with the power
// stretched alike, invalid where the ray runs away from the wall or ends more than `size` below the
// floor. CPU twin: `receiver_photon` in caustics-core/src/techniques/caustic_triangles/water.rs.

import package::caustic_triangles::water_setup::WaterPhoton;
import package::shaders::optics::{fresnel_transmittance, height_field_normal, refract_dir};
import package::shaders::receivers::{light_space, meet_receivers};
import package::shaders::water::grid_sample;

// The uniform block `WaterPhoton`: water_setup.wgsl.
@group(0) @binding(0) var<uniform> w: WaterPhoton;
@group(0) @binding(1) var heights: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> photons: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> paths: array<f32>;
// The receivers' heights in the light's space (a 1 x 1 texture where the floor is the plane z = 0).
@group(0) @binding(4) var receiver_heights: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = w.lattice + 1u;
    if id.x >= p || id.y >= p {
        return;
    }
    let k = id.y * p + id.x;
    let s = w.origin.xy + vec2<f32>(f32(id.x), f32(id.y)) * w.water.z;
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
    var fresnel = 1.0;
    if w.fresnel != 0u {
        fresnel = fresnel_transmittance(cos_i, 1.0, w.light.w) / w.water.w;
    }
    let power = w.water.z * w.water.z * seen * fresnel;
    let z = w.water.x + hg.x;
    if w.receiver == 0u && w.receivers.t0.w != 0.0 {
        let start = vec3<f32>(s, z);
        let d = meet_receivers(receiver_heights, w.receivers, start, t.xyz);
        if d < 0.0 {
            photons[k] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
            paths[k] = 0.0;
            return;
        }
        photons[k] = vec4<f32>(light_space(start + t.xyz * d, w.receivers.t0.xyz), power, 1.0);
        paths[k] = d;
        return;
    }
    if w.receiver == 0u {
        let d = z / -t.z;
        photons[k] = vec4<f32>(s + t.xy * d, power, 1.0);
        paths[k] = d;
        return;
    }
    // Wall x = 0, x = size, y = 0, y = size: the axis across it, its plane, its inward normal's sign.
    let wall = w.receiver - 1u;
    let axis = wall / 2u;
    let plane = select(0.0, w.water.y, wall % 2u == 1u);
    let inward = select(1.0, -1.0, wall % 2u == 1u);
    let toward = -t[axis] * inward;
    let d = (plane - s[axis]) / t[axis];
    let hz = z + t.z * d;
    if toward <= 0.0 || hz < -w.water.y {
        photons[k] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
        paths[k] = 0.0;
        return;
    }
    let along = s[1u - axis] + t[1u - axis] * d;
    let stretch = w.water.y / w.water.x;
    photons[k] = vec4<f32>(along, hz * stretch, power * stretch, 1.0);
    paths[k] = d;
}
