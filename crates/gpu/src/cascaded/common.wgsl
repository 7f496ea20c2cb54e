// Technique `cascaded` (paper 5): the uniform block every pass shares and the geometry they repeat.
// Mirrors `CascadedUniform` in cascaded/mod.rs and `CascadedSetup` in
// caustics-core/src/techniques/cascaded/mod.rs (its common.rs: the CPU twin of every function here).

import package::shaders::water::grid_sample;

struct Cascaded {
    light: vec4<f32>,      // xyz: unit direction the sunlight travels; w: water rest level
    e_u: vec4<f32>,        // xyz: light-view u axis; w: scene square size
    e_v: vec4<f32>,        // xyz: light-view v axis; w: T(theta0) of flat water
    view: vec4<f32>,       // this cascade: u0, v0, du, dv
    view2: vec4<f32>,      // this cascade: w0 (near plane along the light), far, photon flux, 0
    eye_pos: vec4<f32>,    // xyz; w: tan(fov_y / 2)
    eye_fwd: vec4<f32>,    // xyz; w: aspect
    eye_right: vec4<f32>,  // xyz; w: near
    eye_up: vec4<f32>,     // xyz; w: blend
    ior: vec4<f32>,        // rgb: IOR per channel; w: the scene's IOR
    absorption: vec4<f32>, // rgb: K per channel; w: C (ramps)
    ramps: vec4<f32>,      // MIN_DEPTH, MAX_DEPTH, shallow ramp width, fixed-point scale
    terrain: vec4<f32>,    // lowest, highest terrain height (padded), 1 with terrain, 0 for z = 0
    post: vec4<f32>,       // post-process dispersion shift per unit column: red xy, blue xy
    fars: vec4<f32>,       // far plane of each cascade
    fluxes: vec4<f32>,     // photon flux of each cascade
    width: u32,
    height: u32,
    res: u32,
    cascade: u32,
    flags: u32,            // bit 0: plane placement; bit 1: physical brightness; bit 2: wavelength dispersion; bit 3: footprint splat
    wrap: u32,
    walls: u32,            // 1: the pool's walls receive light (floor and walls inside [0, size]^2 x [0, level])
    _pad1: u32,
}

const MARCH_STEPS: u32 = 64u;
const BISECTION_STEPS: u32 = 20u;
const WATER_STEPS: u32 = 4u;

// Where texel (i, j)'s sun ray starts (`CascadedSetup::ray_origin`).
fn ray_origin(c: Cascaded, i: u32, j: u32) -> vec3<f32> {
    let u = c.view.x + (f32(j) + 0.5) * c.view.z;
    let v = c.view.y + (f32(i) + 0.5) * c.view.w;
    return c.e_u.xyz * u + c.e_v.xyz * v + c.light.xyz * c.view2.x;
}

// Terrain height and gradient, clamped at the square's edges; the plane z = 0 without terrain.
fn terrain_height(c: Cascaded, tex: texture_2d<f32>, p: vec2<f32>) -> vec3<f32> {
    if c.terrain.z == 0.0 {
        return vec3<f32>(0.0);
    }
    return grid_sample(tex, p, c.e_u.w, false);
}

fn terrain_gap(c: Cascaded, tex: texture_2d<f32>, o: vec3<f32>, d: vec3<f32>, s: f32) -> f32 {
    let p = o + d * s;
    return p.z - terrain_height(c, tex, p.xy).x;
}

fn in_square(c: Cascaded, q: vec3<f32>) -> bool {
    return q.x >= 0.0 && q.y >= 0.0 && q.x <= c.e_u.w && q.y <= c.e_u.w;
}

// `CascadedSetup::box_hit`: with walls, the first receiver (floor or a wall's inside) of o + s d,
// entering through the open top inside the square; -1 where there is none.
fn box_hit(c: Cascaded, o: vec3<f32>, d: vec3<f32>) -> f32 {
    if d.z >= 0.0 {
        return -1.0;
    }
    var s0 = 0.0;
    if o.z > c.light.w {
        s0 = (c.light.w - o.z) / d.z;
    }
    let p = o + d * s0;
    if !in_square(c, p) {
        return -1.0;
    }
    let s_floor = -p.z / d.z;
    if in_square(c, p + d * s_floor) {
        return s0 + s_floor;
    }
    // `Wall::exit`: the nearer of the x and y walls the horizontal direction leaves through.
    var sx = 3.0e38;
    var sy = 3.0e38;
    if d.x > 0.0 {
        sx = (c.e_u.w - p.x) / d.x;
    } else if d.x < 0.0 {
        sx = -p.x / d.x;
    }
    if d.y > 0.0 {
        sy = (c.e_u.w - p.y) / d.y;
    } else if d.y < 0.0 {
        sy = -p.y / d.y;
    }
    let s = min(sx, sy);
    if s >= 3.0e38 {
        return -1.0;
    }
    return s0 + s;
}

// `CascadedSetup::receiver_normal`: the inward normal of the receiver a box_hit point lies on.
fn receiver_normal(c: Cascaded, p: vec3<f32>) -> vec3<f32> {
    if p.z <= 1e-6 * c.light.w {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    let size = c.e_u.w;
    var best = p.x;
    var n = vec3<f32>(1.0, 0.0, 0.0);
    if size - p.x < best {
        best = size - p.x;
        n = vec3<f32>(-1.0, 0.0, 0.0);
    }
    if p.y < best {
        best = p.y;
        n = vec3<f32>(0.0, 1.0, 0.0);
    }
    if size - p.y < best {
        n = vec3<f32>(0.0, -1.0, 0.0);
    }
    return n;
}

// `terrain_march`: the first terrain hit of o + s d (d unit), -1 where there is none.
fn terrain_hit(c: Cascaded, tex: texture_2d<f32>, o: vec3<f32>, d: vec3<f32>) -> f32 {
    if c.walls != 0u && c.terrain.z == 0.0 {
        return box_hit(c, o, d);
    }
    if d.z >= 0.0 {
        return -1.0;
    }
    if c.terrain.z == 0.0 {
        let s = -o.z / d.z;
        return select(-1.0, s, s >= 0.0);
    }
    let s_a = max((c.terrain.y - o.z) / d.z, 0.0);
    let s_b = (c.terrain.x - o.z) / d.z;
    if s_b < 0.0 {
        return -1.0;
    }
    if terrain_gap(c, tex, o, d, s_a) <= 0.0 {
        return s_a;
    }
    let step = (s_b - s_a) / f32(MARCH_STEPS);
    var a = s_a;
    for (var n = 1u; n <= MARCH_STEPS; n++) {
        var b = s_a + step * f32(n);
        if terrain_gap(c, tex, o, d, b) <= 0.0 {
            for (var m = 0u; m < BISECTION_STEPS; m++) {
                let mid = 0.5 * (a + b);
                if terrain_gap(c, tex, o, d, mid) > 0.0 {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            return 0.5 * (a + b);
        }
        a = b;
    }
    return s_b;
}

// `EyeCamera::ray`: the unnormalised ray through pixel point (x, y), forward component 1.
fn eye_ray(c: Cascaded, x: f32, y: f32) -> vec3<f32> {
    let sx = (2.0 * x / f32(c.width) - 1.0) * c.eye_pos.w * c.eye_fwd.w;
    let sy = (1.0 - 2.0 * y / f32(c.height)) * c.eye_pos.w;
    return c.eye_fwd.xyz + c.eye_right.xyz * sx + c.eye_up.xyz * sy;
}

// `EyeCamera::project`: continuous pixel coordinates and view depth (z <= 0: behind the eye).
fn eye_project(c: Cascaded, p: vec3<f32>) -> vec3<f32> {
    let v = p - c.eye_pos.xyz;
    let z = dot(v, c.eye_fwd.xyz);
    if z <= 0.0 {
        return vec3<f32>(0.0, 0.0, -1.0);
    }
    let sx = dot(v, c.eye_right.xyz) / z / (c.eye_pos.w * c.eye_fwd.w);
    let sy = dot(v, c.eye_up.xyz) / z / c.eye_pos.w;
    return vec3<f32>((sx + 1.0) * 0.5 * f32(c.width), (1.0 - sy) * 0.5 * f32(c.height), z);
}
