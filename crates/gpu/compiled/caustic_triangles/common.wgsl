const CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

struct CausticTriangles {
    centre: vec4<f32>,
    u: vec4<f32>,
    v: vec4<f32>,
    w: vec4<f32>,
    rect: vec4<f32>,
    floor: vec4<f32>,
    p: u32,
    cube: u32,
    layers: u32,
    depth: u32,
    linear_steps: u32,
    secant_iterations: u32,
    fresnel: u32,
    area_rule: u32,
    width: u32,
    height: u32,
    light_cube: u32,
    dm_base: u32,
    light: vec4<f32>,
    spot: vec4<f32>,
    merge_levels: u32,
    merge_small: f32,
    lattice: u32,
    wrap: u32,
    absorption: vec4<f32>,
    band: u32,
    periodic: u32
}

struct CopyBand {
    band: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    draw: array<u32, 4>
}

fn copies(c: CausticTriangles) -> u32 {
    return select(1u, 9u, c.wrap != 0u);
}

fn copy_of_instance(instance: u32) -> u32 {
    if instance == 8u {
        return 4u;
    }
    return instance + select(0u, 1u, instance >= 4u);
}

fn copy_offset(c: CausticTriangles, k: u32) -> vec2<f32> {
    if c.wrap == 0u {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(f32(k % 3u) - 1.0, f32(k / 3u) - 1.0) * c.floor.z;
}

fn copy_rect(c: CausticTriangles, k: u32) -> vec4<u32> {
    let quads = c.p - 1u;
    if c.wrap == 0u {
        return vec4<u32>(0u, quads, 0u, quads);
    }
    let block = 1u << c.merge_levels;
    let band = (c.band + block - 1u) / block * block;
    var r = array<vec2<u32>, 3>(vec2<u32>((quads - min(band, quads)) / block * block, quads), vec2<u32>(0u, quads), vec2<u32>(0u, min(band, quads)));
    let rows = r[k / 3u];
    let cols = r[k % 3u];
    return vec4<u32>(rows.x, rows.y, cols.x, cols.y);
}

fn meets_square(c: CausticTriangles, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    return all(hi >= c.floor.xy) && all(lo <= c.floor.xy + c.floor.z);
}

fn pixel_to_clip(c: CausticTriangles, px: vec2<f32>) -> vec4<f32> {
    let ndc = vec2<f32>(2.0 * px.x / f32(c.width) - 1.0, 1.0 - 2.0 * px.y / f32(c.height));
    return vec4<f32>(ndc, 0.0, 1.0);
}

fn pyr_offset(p: u32, k: u32) -> u32 {
    var off = 0u;
    for (var j = 0u; j < k; j++) {
        let n = pyr_side(p, j);
        off += n * n;
    }
    return off;
}

fn pyr_side(p: u32, k: u32) -> u32 {
    return (p - 1u) >> k;
}

fn to_pixel(c: CausticTriangles, p: vec2<f32>) -> vec2<f32> {
    return (p - c.floor.xy) / c.floor.z * vec2<f32>(f32(c.width), f32(c.height));
}

fn with_band(c: CausticTriangles, b: CopyBand) -> CausticTriangles {
    var n = c;
    n.band = min(c.band, b.band);
    return n;
}
