// Technique `caustic-triangles`, photon tracing pass (paper §4.1): the light ray of each photon-image
// texel traced through the distance map, refracted (Fresnel weighted) or totally internally
// reflected up to `depth` events, then to the floor. Writes the photon hit location image:
// (x, y, power, signature), power -1 where invalid; signature = refractions + 64 * total internal
// reflections (quads whose corners took different paths are not drawn). CPU twin: `photon` in
// caustics-core/src/techniques/caustic_triangles/mod.rs.

import package::caustic_triangles::common::CausticTriangles;
import package::caustic_triangles::distance_map::{dm_info, dm_trace, dmg};
import package::shaders::optics::{fresnel_transmittance, refract_dir};

@group(0) @binding(0) var<uniform> u: CausticTriangles;
@group(0) @binding(2) var<storage, read_write> photons: array<vec4<f32>>;

const INVALID: vec4<f32> = vec4<f32>(0.0, 0.0, -1.0, 0.0);

// The light ray of texel (i, j): origin (xyz) and power (w) in `start`, direction in `dir`; power
// -1 where it carries no light into the map. CPU twin: `CausticTrianglesSetup::photon_ray`.
struct PhotonRay {
    start: vec4<f32>,
    dir: vec3<f32>,
}

fn photon_ray(i: u32, j: u32) -> PhotonRay {
    let q = u.rect.xy + u.rect.zw * vec2<f32>(f32(j) + 0.5, f32(i) + 0.5);
    let c = u.centre.xyz;
    let radius = u.centre.w;
    if u.light.w == 0.0 {
        let x = c + u.u.xyz * (q.x - dot(c, u.u.xyz)) + u.v.xyz * (q.y - dot(c, u.v.xyz)) - u.w.xyz * radius;
        return PhotonRay(vec4<f32>(x, u.v.w), u.w.xyz);
    }
    let len2 = 1.0 + dot(q, q);
    let d = (u.w.xyz + u.u.xyz * q.x + u.v.xyz * q.y) / sqrt(len2);
    let none = PhotonRay(vec4<f32>(0.0, 0.0, 0.0, -1.0), d);
    if u.spot.w > -2.0 && dot(d, u.spot.xyz) < u.spot.w {
        return none;
    }
    let oc = u.light.xyz - c;
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - radius * radius);
    if disc <= 0.0 {
        return none;
    }
    let t = max(-b - sqrt(disc), 0.0);
    return PhotonRay(vec4<f32>(u.light.xyz + d * t, u.v.w / (len2 * sqrt(len2))), d);
}

fn trace_photon(i: u32, j: u32) -> vec4<f32> {
    let ray = photon_ray(i, j);
    if ray.start.w < 0.0 {
        return INVALID;
    }
    let c = u.centre.xyz;
    let radius = u.centre.w;
    var x = ray.start.xyz;
    var r = ray.dir;
    var inside = false;
    var hit_glass = false;
    var power = ray.start.w;
    var d0 = 0.0;
    var refractions = 0u;
    var tir = 0u;
    let eps = 1e-4 * radius;
    let ior = u.u.w;
    for (var event = 0u; event <= u.depth; event++) {
        var d_floor = 3.0e38;
        if r.z < 0.0 {
            d_floor = -x.z / r.z;
        }
        let oc = x - c;
        let b = dot(oc, r);
        let disc = b * b - (dot(oc, oc) - radius * radius);
        var d_out = 0.0;
        if disc > 0.0 {
            d_out = -b + sqrt(disc);
        }
        let h = dm_trace(x, r, d0, min(d_out, d_floor), inside);
        if !h.found {
            if !hit_glass || inside || r.z >= 0.0 {
                return INVALID;
            }
            let p = x + r * d_floor;
            return vec4<f32>(p.xy, power, f32(refractions + 64u * tir));
        }
        if h.surface.w < 0.0 || event == u.depth {
            return INVALID; // a diffuse surface stops the photon, or the path is too long
        }
        hit_glass = true;
        x += r * h.d;
        var n = h.surface.xyz;
        var n1 = 1.0;
        var n2 = ior;
        if inside {
            n = -n;
            n1 = ior;
            n2 = 1.0;
        }
        let cos_i = -dot(r, n);
        let t = refract_dir(r, n, n1 / n2);
        if t.w != 0.0 {
            if u.fresnel != 0u {
                power *= fresnel_transmittance(cos_i, n1, n2);
            }
            r = normalize(t.xyz);
            inside = !inside;
            refractions += 1u;
        } else {
            r = normalize(r - 2.0 * dot(r, n) * n);
            tir += 1u;
        }
        d0 = eps;
    }
    return INVALID;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= u.p || id.y >= u.p {
        return;
    }
    dmg = dm_info(u, 0u);
    photons[id.y * u.p + id.x] = trace_photon(id.y, id.x);
}
