// Technique `caustic-triangles` (paper 4): the uniform block every pass shares. Mirrors
// `CausticTrianglesUniform` in caustic_triangles/mod.rs and `CausticTrianglesSetup` in
// caustics-core/src/techniques/caustic_triangles/mod.rs.
struct CausticTriangles {
    centre: vec4<f32>,  // xyz: the distance map's reference point; w: radius holding its surfaces
    u: vec4<f32>,       // xyz: light-space u; w: index of refraction of the generator
    v: vec4<f32>,       // xyz: light-space v; w: power of one photon before Fresnel (floor-area units)
    w: vec4<f32>,       // xyz: direction the light travels; w: splat side, texels
    rect: vec4<f32>,    // xy: photon image's light-space lower corner; zw: one texel's size
    floor: vec4<f32>,   // xy: floor window origin; z: its side; w: map texel area
    p: u32,             // photon image side
    cube: u32,          // distance map face side
    layers: u32,
    depth: u32,
    linear_steps: u32,
    secant_iterations: u32,
    fresnel: u32,
    area_rule: u32,     // 0: paper (half the 4-neighbour triangles), 1: hat (a third of the drawn ones)
    width: u32,         // floor map
    height: u32,
    light_cube: u32,    // face side of the light cube map (point light)
    dm_base: u32,       // first texel of this generator's distance map in a buffer of several
    light: vec4<f32>,   // xyz: the point light; w: 0 the sun, 1 a point light
    spot: vec4<f32>,    // xyz: spot axis; w: cos of its half-angle, -2 for a bare point light
    merge_levels: u32,  // levels of the merge pyramid (0: no merging)
    merge_small: f32,   // a block merges below this floor area (merge_texels x texel area)
    lattice: u32,       // a water generator's lattice P (photon image P + 1); 0 for glass
    wrap: u32,          // 1: tiling water, every primitive drawn at nine offsets of +-size
    absorption: vec4<f32>, // xyz: the water's K per channel (0 for glass)
    band: u32,          // quads from an edge a shifted copy is drawn for (tiling water)
    periodic: u32,      // 1: the photon image tiles in the receiver's plane (a tiling surface's floor)
}

// The quads copy k is drawn for, (i0, i1, j0, j1): all for the unshifted copy, the `band` quads
// along the edge its light crosses for a shifted one, the ends on multiples of the largest merged
// block (CPU twin: `CausticTrianglesSetup::copy_rect`).
fn copy_rect(c: CausticTriangles, k: u32) -> vec4<u32> {
    let quads = c.p - 1u;
    if c.wrap == 0u {
        return vec4<u32>(0u, quads, 0u, quads);
    }
    let block = 1u << c.merge_levels;
    let band = (c.band + block - 1u) / block * block;
    var r = array<vec2<u32>, 3>(vec2<u32>((quads - min(band, quads)) / block * block, quads),
                                vec2<u32>(0u, quads), vec2<u32>(0u, min(band, quads)));
    let rows = r[k / 3u];
    let cols = r[k % 3u];
    return vec4<u32>(rows.x, rows.y, cols.x, cols.y);
}

// Offset of copy (instance) k of a primitive: ((k mod 3) - 1, (k div 3) - 1) size for tiling
// water (CPU twin: `CausticTrianglesSetup::copies`).
fn copy_offset(c: CausticTriangles, k: u32) -> vec2<f32> {
    if c.wrap == 0u {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(f32(k % 3u) - 1.0, f32(k / 3u) - 1.0) * c.floor.z;
}

// Whether the floor box [lo, hi] meets the map's square.
fn meets_square(c: CausticTriangles, lo: vec2<f32>, hi: vec2<f32>) -> bool {
    return all(hi >= c.floor.xy) && all(lo <= c.floor.xy + c.floor.z);
}

// The area of the triangle a b c.
fn tri_area(a: vec2<f32>, b: vec2<f32>, c: vec2<f32>) -> f32 {
    let e = b - a;
    let f = c - a;
    return 0.5 * abs(e.x * f.y - e.y * f.x);
}

// Blocks per side of level k of the merge pyramid, and the level's offset (CPU twin: merge::layout).
fn pyr_side(p: u32, k: u32) -> u32 {
    return (p - 1u) >> k;
}

fn pyr_offset(p: u32, k: u32) -> u32 {
    var off = 0u;
    for (var j = 0u; j < k; j++) {
        let n = pyr_side(p, j);
        off += n * n;
    }
    return off;
}

// Floor point to map pixel coordinates.
fn to_pixel(c: CausticTriangles, p: vec2<f32>) -> vec2<f32> {
    return (p - c.floor.xy) / c.floor.z * vec2<f32>(f32(c.width), f32(c.height));
}

// Map pixel coordinates to clip space: row 0 of the map (y = floor origin) is framebuffer row 0.
fn pixel_to_clip(c: CausticTriangles, px: vec2<f32>) -> vec4<f32> {
    let ndc = vec2<f32>(2.0 * px.x / f32(c.width) - 1.0, 1.0 - 2.0 * px.y / f32(c.height));
    return vec4<f32>(ndc, 0.0, 1.0);
}

// A vertex every invalid primitive collapses to, outside the clip volume (the paper's trick).
const CULLED: vec4<f32> = vec4<f32>(-4.0, -4.0, 0.0, 1.0);

// The band of quads the shifted copies of tiling water are drawn for, as the GPU fits it from the
// heights it reads (`band.wgsl`), and the indirect draw of those copies. Mirrors the copy-band
// buffer of caustic_triangles/mod.rs (`CopyBandBuffer`). `band` is u32::MAX where nothing narrows
// the uniform's `band` (glass, a water frame before its first band pass).
struct CopyBand {
    band: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    // vertex_count, instance_count, first_vertex, first_instance: the eight shifted copies.
    draw: array<u32, 4>,
}

// `c` with its band narrowed to the one the GPU fitted.
fn with_band(c: CausticTriangles, b: CopyBand) -> CausticTriangles {
    var n = c;
    n.band = min(c.band, b.band);
    return n;
}

// Copy (0..9) drawn by instance `instance`: instance 8 is the unshifted copy 4, drawn first over
// every quad; instances 0..8 are the shifted copies 0, 1, 2, 3, 5, 6, 7, 8 over their bands, one
// draw (direct, or indirect with the GPU's band) with no first instance to offset.
fn copy_of_instance(instance: u32) -> u32 {
    if instance == 8u {
        return 4u;
    }
    return instance + select(0u, 1u, instance >= 4u);
}
