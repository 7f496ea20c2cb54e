// The receivers' heights in the light's space: what lies under the water as the sun sees it through
// flat water (caustics mapping's receiver model; docs/receivers.md). CPU twin:
// caustics-core/src/receivers.rs, `ReceiverHeights`.

// Mirrors `ReceiversUniform` in crates/gpu/src/receivers.rs.
struct Receivers {
    view: vec4<f32>,   // xy: light-space corner of texel (0, 0); z: texel side; w: the map's steepest slope
    t0: vec4<f32>,     // xyz: the flat-water refracted sun; w: 1 where the receivers are met, 0: the plane z = 0
}

// Where the line through p along t0 meets the plane z = 0.
fn light_space(p: vec3<f32>, t0: vec3<f32>) -> vec2<f32> {
    return p.xy + t0.xy * (p.z / -t0.z);
}

// The map's height at light-space point q, bilinear between texel centres, clamped at the edges.
fn receiver_height(map: texture_2d<f32>, r: Receivers, q: vec2<f32>) -> f32 {
    let dims = vec2<i32>(textureDimensions(map));
    let u = (q - r.view.xy) / r.view.z - 0.5;
    let c = floor(u);
    let f = u - c;
    let i = vec2<i32>(c);
    let a = textureLoad(map, clamp(i, vec2<i32>(0), dims - 1), 0).x;
    let b = textureLoad(map, clamp(i + vec2<i32>(1, 0), vec2<i32>(0), dims - 1), 0).x;
    let d = textureLoad(map, clamp(i + vec2<i32>(0, 1), vec2<i32>(0), dims - 1), 0).x;
    let e = textureLoad(map, clamp(i + vec2<i32>(1, 1), vec2<i32>(0), dims - 1), 0).x;
    return mix(mix(a, b, f.x), mix(d, e, f.x), f.y);
}

// A sign change of a gap being closed by regula falsi in its Illinois form (caustics-core's
// `receivers::regula_falsi`): `a` where the gap is `ga` > 0, `b` where it is `gb` ≤ 0, and which
// end the last guess replaced (1: a, -1: b, 0: none yet).
struct Bracket {
    a: f32,
    ga: f32,
    b: f32,
    gb: f32,
    kept: i32,
}

// The next guess: where the chord between the bracket's ends crosses zero.
fn chord(br: Bracket) -> f32 {
    return (br.a * br.gb - br.b * br.ga) / (br.gb - br.ga);
}

// The bracket after the guess `m` found the gap `gm` there: the end on its side replaced, and the
// other end's gap halved where that end was kept twice running, so the bracket closes from both
// sides.
fn narrowed(br: Bracket, m: f32, gm: f32) -> Bracket {
    var out = br;
    if gm > 0.0 {
        out.a = m;
        out.ga = gm;
        if br.kept == 1 {
            out.gb *= 0.5;
        }
        out.kept = 1;
    } else {
        out.b = m;
        out.gb = gm;
        if br.kept == -1 {
            out.ga *= 0.5;
        }
        out.kept = -1;
    }
    return out;
}

// The length d along s + d t (t unit, going down) to where the ray first meets the receivers, or
// -1 where it starts below them or never comes down: steps bounded by the map's slope times the
// ray's drift from t0, then regula falsi in its Illinois form on the sign change (the CPU twin's
// `ReceiverHeights::meet` and `regula_falsi`, in f32: steps and tolerance 1e-4 texel).
fn meet_receivers(map: texture_2d<f32>, r: Receivers, s: vec3<f32>, t: vec3<f32>) -> f32 {
    if t.z >= 0.0 {
        return -1.0;
    }
    let t0 = r.t0.xyz;
    let drift = length(t.xy - t0.xy * (t.z / t0.z));
    let rate = -t.z + r.view.w * drift;
    var g = s.z - receiver_height(map, r, light_space(s, t0));
    if g <= 0.0 {
        return -1.0;
    }
    let tol = 1e-4 * r.view.z;
    var d = 0.0;
    for (var k = 0; k < 256; k++) {
        let step = max(g / rate, tol);
        let p = s + t * (d + step);
        let g_next = p.z - receiver_height(map, r, light_space(p, t0));
        if g_next <= 0.0 {
            var br = Bracket(d, g, d + step, g_next, 0);
            var m = br.b;
            for (var n = 0; n < 24; n++) {
                m = chord(br);
                let pm = s + t * m;
                let gm = pm.z - receiver_height(map, r, light_space(pm, t0));
                br = narrowed(br, m, gm);
                if abs(gm) < tol || br.b - br.a < tol {
                    break;
                }
            }
            return m;
        }
        d += step;
        g = g_next;
        if g < tol {
            return d;
        }
    }
    return d;
}

// The share of the light deposited at its light-space point that receiver point p with unit normal
// n takes (caustics-core's `ReceiverHeights::share`): n · (−t0) / −t0_z, its area as the light sees
// it over its horizontal area; 0 where the map's height there lies above it by more than half a
// texel's rise at the map's steepest slope (something nearer the light covers it: a shadow map's
// depth test).
fn receiver_share(map: texture_2d<f32>, r: Receivers, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let t0 = r.t0.xyz;
    let bias = 0.5 * r.view.z * max(r.view.w, 1.0);
    if p.z < receiver_height(map, r, light_space(p, t0)) - bias {
        return 0.0;
    }
    return max(dot(n, -t0), 0.0) / -t0.z;
}
