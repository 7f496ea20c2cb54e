// Technique `cascaded`, eye-depth pass (what §3.5.1 samples): per screen pixel the view depth of the
// terrain its ray meets, the floor area it sees, the floor's height and
// its normal's z (0: no floor). CPU twin: `eye_pass`.

@group(0) @binding(0) var<uniform> cfg: Cascaded;
@group(0) @binding(1) var terrain: texture_2d<f32>;
@group(0) @binding(2) var eye_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= cfg.width || id.y >= cfg.height {
        return;
    }
    let half = cfg.eye_pos.w;
    let pixel = (2.0 * half * cfg.eye_fwd.w / f32(cfg.width)) * (2.0 * half / f32(cfg.height));
    let r = eye_ray(cfg, f32(id.x) + 0.5, f32(id.y) + 0.5);
    let len = length(r);
    let d = r / len;
    let s = terrain_hit(cfg, terrain, cfg.eye_pos.xyz, d);
    var out = vec4<f32>(0.0);
    if s >= 0.0 {
        let zv = s / len;
        let f = cfg.eye_pos.xyz + r * zv;
        let n = height_field_normal(terrain_height(cfg, terrain, f.xy).yz);
        let cos_g = max(abs(dot(d, n)), 1e-4);
        out = vec4<f32>(zv, zv * zv * pixel / (len * cos_g), f.z, n.z);
    }
    textureStore(eye_out, vec2<i32>(id.xy), out);
}
