@group(0) @binding(0)
var<uniform> level: package__1final_image__1water_slopes_SlopeLevel;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= level.cols || id.y >= level.rows {
        return;
    }
    var first = vec4<f32>(0.0);
    var xy = 0.0;
    var n = 0.0;
    for (var i = 2u * id.y; i < min(2u * id.y + 2u, level.below_rows); i++) {
        for (var j = 2u * id.x; j < min(2u * id.x + 2u, level.below_cols); j++) {
            let k = (level.below_offset + i * level.below_cols + j) * 5u;
            first += vec4<f32>(moments[k], moments[k + 1u], moments[k + 2u], moments[k + 3u]);
            xy += moments[k + 4u];
            n += 1.0;
        }
    }
    let k = (level.offset + id.y * level.cols + id.x) * 5u;
    moments[k] = first.x / n;
    moments[k + 1u] = first.y / n;
    moments[k + 2u] = first.z / n;
    moments[k + 3u] = first.w / n;
    moments[k + 4u] = xy / n;
}

@group(0) @binding(1)
var<storage, read_write> moments: array<f32>;

struct package__1final_image__1water_slopes_SlopeLevel {
    size: f32,
    wrap: u32,
    offset: u32,
    cols: u32,
    rows: u32,
    below_offset: u32,
    below_cols: u32,
    below_rows: u32
}
