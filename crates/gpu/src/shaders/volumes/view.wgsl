// Technique `volumes`, the refracted view (§3.3, Fig. 5): per camera pixel, the viewing ray meets
// the water (fixed-point steps from the rest plane to the waves), is refracted, and is traced against
// every object's reference planes and depth texture with the acceptance test of §3.1; the pixel takes
// the accepted texel of the object's final image, or the floor lit by its caustics map, attenuated
// along the view path, with the sky mixed in by the water's Fresnel reflectance. CPU twin:
// `view_pass` in caustics-core/src/techniques/volumes/view.rs.

struct Camera {
    position: vec4<f32>,      // xyz; w: ambient Ia
    forward: vec4<f32>,       // xyz; w: number of objects
    right: vec4<f32>,         // xyz, scaled by the field of view; w: image width
    up: vec4<f32>,            // xyz, scaled; w: image height
    floor_albedo: vec4<f32>,
}

const SKY: vec3<f32> = vec3<f32>(0.55, 0.7, 0.9);
const SURFACE_STEPS: u32 = 4u;

@group(0) @binding(0) var<uniform> c: Volumes;
@group(0) @binding(1) var<uniform> cam: Camera;
@group(0) @binding(2) var heights: texture_2d<f32>;
@group(0) @binding(3) var<storage, read> objects: array<Pass>;
@group(0) @binding(4) var depths: texture_2d_array<f32>;
@group(0) @binding(5) var images: texture_2d_array<f32>;
@group(0) @binding(6) var floor_map: texture_2d<f32>;
@group(0) @binding(7) var out_view: texture_storage_2d<rgba32float, write>;

// (path, object, texel x, texel y) of the nearest accepted plane point, path < 0 when none.
fn trace_objects(s: vec3<f32>, r: vec3<f32>) -> vec4<f32> {
    var best = vec4<f32>(-1.0, 0.0, 0.0, 0.0);
    let count = u32(cam.forward.w);
    for (var k = 0u; k < count; k++) {
        let view = objects[k].view;
        let vr = dot(view.v.xyz, r);
        if vr <= 1e-6 {
            continue;
        }
        let res = view.a.w;
        for (var p = 0u; p < objects[k].planes; p++) {
            let zk = (f32(p) + 0.5) * view.v.w;
            let u = (view.lo.z + zk - dot(view.v.xyz, s)) / vr;
            if u < 0.0 || (best.x >= 0.0 && best.x <= u) {
                continue;
            }
            let px = floor(to_frame(view, s + r * u).xy / view.texel.xy);
            if !(px.x >= 0.0 && px.y >= 0.0 && px.x < res && px.y < res) {
                continue;
            }
            let t = textureLoad(depths, vec2<i32>(px), i32(k), 0);
            if covered(t) && abs(t.x - zk) <= 0.5 * view.v.w {
                best = vec4<f32>(u, f32(k), px);
                break;
            }
        }
    }
    return best;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = u32(cam.right.w);
    let h = u32(cam.up.w);
    if id.x >= w || id.y >= h {
        return;
    }
    let sx = 2.0 * (f32(id.x) + 0.5) / f32(w) - 1.0;
    let sy = 1.0 - 2.0 * (f32(id.y) + 0.5) / f32(h);
    let d = normalize(cam.forward.xyz + cam.right.xyz * sx + cam.up.xyz * sy);
    let o = cam.position.xyz;
    var colour = SKY;
    let wrap = c.flags.x != 0u;
    if d.z < 0.0 && o.z > c.params.x {
        var t = (c.params.x - o.z) / d.z;
        var hg = grid_sample(heights, (o + d * t).xy, c.lattice.w, wrap);
        for (var k = 0u; k < SURFACE_STEPS; k++) {
            t = (c.params.x + hg.x - o.z) / d.z;
            hg = grid_sample(heights, (o + d * t).xy, c.lattice.w, wrap);
        }
        let s = o + d * t;
        let n = height_field_normal(hg.yz);
        let cos_i = -dot(d, n);
        let r = refract_dir(d, n, c.light.w);
        if r.w != 0.0 && cos_i > 0.0 {
            let tr = fresnel_transmittance(cos_i, 1.0, c.params.y);
            let t_floor = s.z / -r.z;
            let hit = trace_objects(s, r.xyz);
            var path = t_floor;
            var under: vec3<f32>;
            if hit.x >= 0.0 && hit.x < t_floor {
                path = hit.x;
                under = textureLoad(images, vec2<i32>(hit.zw), i32(hit.y), 0).xyz;
            } else {
                let size = vec2<f32>(textureDimensions(floor_map));
                let px = floor((s + r.xyz * t_floor).xy / c.lattice.w * size);
                // Beyond the map's square: the light of flat water (absorbed along the flat
                // refracted sun), not a wrapped copy of the objects' shadows.
                let t0 = refract_dir(c.light.xyz, vec3<f32>(0.0, 0.0, 1.0), c.light.w).xyz;
                var e = exp(-c.absorption.xyz * (c.params.x / -t0.z));
                if px.x >= 0.0 && px.y >= 0.0 && px.x < size.x && px.y < size.y {
                    e = textureLoad(floor_map, vec2<i32>(px), 0).xyz;
                }
                under = cam.floor_albedo.xyz * (e + cam.position.w);
            }
            colour = under * exp(-c.absorption.xyz * path) * tr + SKY * (1.0 - tr);
        }
    }
    textureStore(out_view, vec2<i32>(id.xy), vec4<f32>(colour, 1.0));
}
