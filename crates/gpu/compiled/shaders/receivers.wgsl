struct Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn light_space(p: vec3<f32>, t0: vec3<f32>) -> vec2<f32> {
    return p.xy + t0.xy * (p.z / -t0.z);
}

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
    let tol = 0.0001 * r.view.z;
    var d = 0.0;
    for (var k = 0; k < 256; k++) {
        let step = max(g / rate, tol);
        let p = s + t * (d + step);
        let g_next = p.z - receiver_height(map, r, light_space(p, t0));
        if g_next <= 0.0 {
            var a = d;
            var ga = g;
            var b = d + step;
            var gb = g_next;
            var m = b;
            var side = 0;
            for (var n = 0; n < 24; n++) {
                m = (a * gb - b * ga) / (gb - ga);
                let pm = s + t * m;
                let gm = pm.z - receiver_height(map, r, light_space(pm, t0));
                if gm > 0.0 {
                    a = m;
                    ga = gm;
                    if side == 1 {
                        gb *= 0.5;
                    }
                    side = 1;
                }
                else {
                    b = m;
                    gb = gm;
                    if side == -1 {
                        ga *= 0.5;
                    }
                    side = -1;
                }
                if abs(gm) < tol || b - a < tol {
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
