// Technique `volumes`, the refracted view (§3.3, Fig. 5): per camera pixel, the viewing ray meets
// the water (fixed-point steps from the rest plane to the waves), is refracted, and is traced against
// every object's reference planes and depth texture with the acceptance test of §3.1; the pixel takes
// the accepted texel of the object's final image, or the floor lit by its caustics map, attenuated
// along the view path, with the sky mixed in by the water's Fresnel reflectance; with the pool's
// walls (flags.z), a ray from the surface inside the square that leaves it through a wall before the
// floor sees that wall lit by its map, and the pool is sunk into a deck. CPU twin:
// `view_pass_with_walls` in
// caustics-core/src/techniques/volumes/view.rs.

import package::shaders::optics::{fresnel_transmittance, height_field_normal, refract_dir};
import package::shaders::water::grid_sample;
import package::volumes::common::{Pass, Volumes, covered, to_frame};

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
// The walls' maps, one layer per wall in `Wall::ALL`'s order (a stand-in without walls).
@group(0) @binding(8) var walls_map: texture_2d_array<f32>;

// (t, wall) of the wall the ray s + t d (horizontal part) leaves the square through, as
// `Wall::exit` (a corner goes to the x-wall); t < 0 for a vertical ray.
fn wall_exit(p: vec2<f32>, d: vec2<f32>, size: f32) -> vec2<f32> {
    var tx = -1.0;
    var wx = 0.0;
    if d.x > 0.0 {
        tx = (size - p.x) / d.x;
        wx = 1.0;
    } else if d.x < 0.0 {
        tx = -p.x / d.x;
    }
    var ty = -1.0;
    var wy = 2.0;
    if d.y > 0.0 {
        ty = (size - p.y) / d.y;
        wy = 3.0;
    } else if d.y < 0.0 {
        ty = -p.y / d.y;
    }
    if tx >= 0.0 && (ty < 0.0 || tx <= ty) {
        return vec2<f32>(tx, wx);
    }
    if ty >= 0.0 {
        return vec2<f32>(ty, wy);
    }
    return vec2<f32>(-1.0, 0.0);
}

// The deck at p beyond the pool's square (`deck` in the CPU twin); w < 0 over the pool.
fn deck(p: vec3<f32>) -> vec4<f32> {
    let size = c.lattice.w;
    if p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    let v = (floor(p.x * 3.0) + floor(p.y * 3.0)) % 2.0;
    let albedo = 0.32 + 0.04 * select(v, v + 2.0, v < 0.0);
    return vec4<f32>(vec3<f32>(albedo * (1.0 / c.absorption.w + cam.position.w)), 1.0);
}

// Wall k's map's nearest texel at the wall point q (the top row above the rest level).
fn wall_light(k: u32, q: vec3<f32>) -> vec3<f32> {
    let cols = f32(select(c.dims.z, c.dims.w, k < 2u));
    let rows = f32(c.flags.w);
    let along = select(q.x, q.y, k < 2u);
    let j = clamp(floor(along / c.lattice.w * cols), 0.0, cols - 1.0);
    let i = clamp(floor(q.z / c.params.x * rows), 0.0, rows - 1.0);
    return textureLoad(walls_map, vec2<i32>(i32(j), i32(i)), i32(k), 0).xyz;
}

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
    let walls = c.flags.z != 0u;
    var on_deck = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    if walls && d.z < 0.0 && o.z > c.params.x {
        let deck_height = c.params.x + 0.1 * min(c.lattice.w, 1.0);
        on_deck = deck(o + d * max((deck_height - o.z) / d.z, 0.0));
    }
    if on_deck.w >= 0.0 {
        colour = on_deck.xyz;
    } else if d.z < 0.0 && o.z > c.params.x {
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
        let beyond = deck(s);
        if walls && beyond.w >= 0.0 {
            colour = beyond.xyz;
        } else if r.w != 0.0 && cos_i > 0.0 {
            let tr = fresnel_transmittance(cos_i, 1.0, c.params.y);
            let t_floor = s.z / -r.z;
            var t_end = t_floor;
            var wall = 0u;
            let size = c.lattice.w;
            if c.flags.z != 0u && s.x >= 0.0 && s.y >= 0.0 && s.x <= size && s.y <= size {
                let exit = wall_exit(s.xy, r.xy, size);
                if exit.x >= 0.0 && exit.x < t_floor {
                    t_end = exit.x;
                    wall = u32(exit.y);
                }
            }
            let hit = trace_objects(s, r.xyz);
            var path = t_floor;
            var under: vec3<f32>;
            if hit.x >= 0.0 && hit.x < t_end {
                path = hit.x;
                under = textureLoad(images, vec2<i32>(hit.zw), i32(hit.y), 0).xyz;
            } else if t_end < t_floor {
                path = t_end;
                under = cam.floor_albedo.xyz * (wall_light(wall, s + r.xyz * t_end) + cam.position.w);
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
