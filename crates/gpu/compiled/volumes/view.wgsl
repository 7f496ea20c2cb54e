struct Camera {
    position: vec4<f32>,
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    floor_albedo: vec4<f32>
}

const SKY: vec3<f32> = vec3<f32>(0.55, 0.7, 0.9);

const SURFACE_STEPS: u32 = 4u;

@group(0) @binding(0)
var<uniform> c: package_volumes_common_Volumes;

@group(0) @binding(1)
var<uniform> cam: Camera;

fn deck(p: vec3<f32>) -> vec4<f32> {
    let size = c.lattice.w;
    if p.x >= 0.0 && p.y >= 0.0 && p.x <= size && p.y <= size {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    let v = (floor(p.x * 3.0) + floor(p.y * 3.0)) % 2.0;
    let albedo = 0.32 + 0.04 * select(v, v + 2.0, v < 0.0);
    return vec4<f32>(vec3<f32>(albedo * (1.0 / c.absorption.w + cam.position.w)), 1.0);
}

@group(0) @binding(4)
var depths: texture_2d_array<f32>;

@group(0) @binding(6)
var floor_map: texture_2d<f32>;

@group(0) @binding(2)
var heights: texture_2d<f32>;

@group(0) @binding(5)
var images: texture_2d_array<f32>;

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
    }
    else if d.z < 0.0 && o.z > c.params.x {
        var t = (c.params.x - o.z) / d.z;
        var hg = package_shaders_water__1grid_sample(heights, (o + d * t).xy, c.lattice.w, wrap);
        for (var k = 0u; k < SURFACE_STEPS; k++) {
            t = (c.params.x + hg.x - o.z) / d.z;
            hg = package_shaders_water__1grid_sample(heights, (o + d * t).xy, c.lattice.w, wrap);
        }
        let s = o + d * t;
        let n = package_shaders_optics__2height_field_normal(hg.yz);
        let cos_i = -dot(d, n);
        let r = package_shaders_optics__1refract_dir(d, n, c.light.w);
        let beyond = deck(s);
        if walls && beyond.w >= 0.0 {
            colour = beyond.xyz;
        }
        else if r.w != 0.0 && cos_i > 0.0 {
            let tr = package_shaders_optics__1fresnel_transmittance(cos_i, 1.0, c.params.y);
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
            }
            else if t_end < t_floor {
                path = t_end;
                under = cam.floor_albedo.xyz * (wall_light(wall, s + r.xyz * t_end) + cam.position.w);
            }
            else {
                let size = vec2<f32>(textureDimensions(floor_map));
                let px = floor((s + r.xyz * t_floor).xy / c.lattice.w * size);
                let t0 = package_shaders_optics__1refract_dir(c.light.xyz, vec3<f32>(0.0, 0.0, 1.0), c.light.w).xyz;
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

@group(0) @binding(3)
var<storage, read> objects: array<package_volumes_common_Pass>;

@group(0) @binding(7)
var out_view: texture_storage_2d<rgba32float, write>;

fn package_shaders_optics__1fresnel_transmittance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = min(abs(cos_i_in), 1.0);
    let sin_t = n1 / n2 * sqrt(max(1.0 - cos_i * cos_i, 0.0));
    if sin_t >= 1.0 {
        return 0.0;
    }
    let cos_t = sqrt(1.0 - sin_t * sin_t);
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 1.0 - 0.5 * (rs * rs + rp * rp);
}

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
}

fn package_shaders_water__1catmull_rom(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = 0.5 * vec4<f32>(-t3 + 2.0 * t2 - t, 3.0 * t3 - 5.0 * t2 + 2.0, -3.0 * t3 + 4.0 * t2 + t, t3 - t2);
    let dw = 0.5 * vec4<f32>(-3.0 * t2 + 4.0 * t - 1.0, 9.0 * t2 - 10.0 * t, -9.0 * t2 + 8.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

fn package_shaders_water__1grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

fn package_shaders_water__1grid_sample(tex: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(tex));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let wu = package_shaders_water__1catmull_rom(f.x);
    let wv = package_shaders_water__1catmull_rom(f.y);
    let n = vec2<i32>(dims);
    var first = vec2<i32>(base) - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    var h = 0.0;
    var hu = 0.0;
    var hv = 0.0;
    for (var a = 0; a < 4; a++) {
        let row = package_shaders_water__1grid_index(first.y, a, n.y, wrap);
        for (var b = 0; b < 4; b++) {
            let s = textureLoad(tex, vec2<i32>(package_shaders_water__1grid_index(first.x, b, n.x, wrap), row), 0).r;
            h += wu[0][b] * wv[0][a] * s;
            hu += wu[1][b] * wv[0][a] * s;
            hv += wu[0][b] * wv[1][a] * s;
        }
    }
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

struct package_volumes_common_Pass {
    view: package_volumes_common_View,
    cells: vec4<u32>,
    planes: u32,
    root_first: u32,
    root_count: u32,
    _pad: u32,
    albedo: vec4<f32>
}

struct package_volumes_common_View {
    a: vec4<f32>,
    b: vec4<f32>,
    v: vec4<f32>,
    lo: vec4<f32>,
    texel: vec4<f32>
}

struct package_volumes_common_Volumes {
    light: vec4<f32>,
    absorption: vec4<f32>,
    lattice: vec4<f32>,
    params: vec4<f32>,
    dims: vec4<u32>,
    flags: vec4<u32>,
    shadow: package_volumes_common_View
}

fn package_volumes_common__1to_frame(view: package_volumes_common_View, p: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(view.a.xyz, p), dot(view.b.xyz, p), dot(view.v.xyz, p)) - view.lo.xyz;
}

fn package_volumes_common_covered(t: vec4<f32>) -> bool {
    return t.y != 0.0 || t.z != 0.0 || t.w != 0.0;
}

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
            let px = floor(package_volumes_common__1to_frame(view, s + r * u).xy / view.texel.xy);
            if !(px.x >= 0.0 && px.y >= 0.0 && px.x < res && px.y < res) {
                continue;
            }
            let t = textureLoad(depths, vec2<i32>(px), i32(k), 0);
            if package_volumes_common_covered(t) && abs(t.x - zk) <= 0.5 * view.v.w {
                best = vec4<f32>(u, f32(k), px);
                break;
            }
        }
    }
    return best;
}

fn wall_exit(p: vec2<f32>, d: vec2<f32>, size: f32) -> vec2<f32> {
    var tx = -1.0;
    var wx = 0.0;
    if d.x > 0.0 {
        tx = (size - p.x) / d.x;
        wx = 1.0;
    }
    else if d.x < 0.0 {
        tx = -p.x / d.x;
    }
    var ty = -1.0;
    var wy = 2.0;
    if d.y > 0.0 {
        ty = (size - p.y) / d.y;
        wy = 3.0;
    }
    else if d.y < 0.0 {
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

fn wall_light(k: u32, q: vec3<f32>) -> vec3<f32> {
    let cols = f32(select(c.dims.z, c.dims.w, k < 2u));
    let rows = f32(c.flags.w);
    let along = select(q.x, q.y, k < 2u);
    let j = clamp(floor(along / c.lattice.w * cols), 0.0, cols - 1.0);
    let i = clamp(floor(q.z / c.params.x * rows), 0.0, rows - 1.0);
    return textureLoad(walls_map, vec2<i32>(i32(j), i32(i)), i32(k), 0).xyz;
}

@group(0) @binding(8)
var walls_map: texture_2d_array<f32>;
