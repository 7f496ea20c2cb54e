// Technique `yuksel`, the last pass (ours): the map the passes made at the region's level, bilinear
// at each map pixel's centre (wrapped or clamped as the water is), which keeps the flux of a
// periodic map; at level 0 a copy. CPU twin: `upsample` in caustics-core's yuksel.rs.

@group(0) @binding(0) var<uniform> u: Yuksel;
@group(0) @binding(1) var<storage, read> region: YukselRegion;
@group(0) @binding(2) var coarse: texture_2d<f32>;
@group(0) @binding(3) var map_out: texture_storage_2d<rgba32float, write>;

fn coarse_index(k: i32, n: i32) -> i32 {
    if u.wrap != 0u {
        return ((k % n) + n) % n;
    }
    return clamp(k, 0, n - 1);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= u.width || id.y >= u.height {
        return;
    }
    if region.level == 0u {
        textureStore(map_out, vec2<i32>(id.xy), textureLoad(coarse, vec2<i32>(id.xy), 0));
        return;
    }
    let size = vec2<i32>(level_size(u.width, u.height, region.level));
    let scale = f32(1u << region.level);
    let p = (vec2<f32>(id.xy) + 0.5) / scale - 0.5;
    let p0 = floor(p);
    let f = p - p0;
    let c0 = coarse_index(i32(p0.x), size.x);
    let c1 = coarse_index(i32(p0.x) + 1, size.x);
    let r0 = coarse_index(i32(p0.y), size.y);
    let r1 = coarse_index(i32(p0.y) + 1, size.y);
    let a = textureLoad(coarse, vec2<i32>(c0, r0), 0);
    let b = textureLoad(coarse, vec2<i32>(c1, r0), 0);
    let c = textureLoad(coarse, vec2<i32>(c0, r1), 0);
    let d = textureLoad(coarse, vec2<i32>(c1, r1), 0);
    let top = a + (b - a) * f.x;
    let bottom = c + (d - c) * f.x;
    textureStore(map_out, vec2<i32>(id.xy), vec4<f32>((top + (bottom - top) * f.y).rgb, 1.0));
}
