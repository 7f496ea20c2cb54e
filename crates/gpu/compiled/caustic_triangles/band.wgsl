const BIG: f32 = 3e38;

const PI: f32 = 3.14159265358979;

@group(0) @binding(2)
var<storage, read> bound: array<u32, 4>;

@compute @workgroup_size(1)
fn main() {
    var slope = 0.0;
    var lo = BIG;
    var hi = -BIG;
    if bound[2] != 0u {
        slope = package_shaders_reduce_unordered(bound[0]);
        lo = -package_shaders_reduce_unordered(bound[1]);
        hi = package_shaders_reduce_unordered(bound[2]);
    }
    let h_max = hi + 0.25 * (hi - lo);
    let tilt = atan(slope * 1.25 * sqrt(2.0));
    let zenith = acos(clamp(-w.light.z, -1.0, 1.0));
    let incidence = min(zenith + tilt, 0.5 * PI);
    let refracted = asin(sin(incidence) / w.light.w);
    let lean = refracted + tilt;
    var band = w.lattice;
    if lean < radians(89.0) && h_max < BIG && slope < BIG {
        let reach = max(w.water.x + h_max, 0.0) * tan(lean);
        band = min(u32(ceil(reach / w.water.z)) + 2u, w.lattice);
    }
    out.band = band;
    let c = package__1caustic_triangles_common__1with_band(u, out);
    var most = 0u;
    for (var k = 0u; k < 9u; k++) {
        if k != 4u {
            let r = package__1caustic_triangles_common__1copy_rect(c, k);
            most = max(most, (r.y - r.x) * (r.w - r.z));
        }
    }
    let quads = u.p - 1u;
    out.draw = array<u32, 4>(min(6u * most, 6u * quads * quads), 8u, 0u, 0u);
}

@group(0) @binding(3)
var<storage, read_write> out: package__1caustic_triangles_common_CopyBand;

struct package__1caustic_triangles__1water_setup_WaterPhoton {
    light: vec4<f32>,
    water: vec4<f32>,
    lattice: u32,
    wrap: u32,
    fresnel: u32,
    receiver: u32,
    receivers: package_shaders_receivers_Receivers,
    origin: vec4<f32>
}

struct package__1caustic_triangles_common_CausticTriangles {
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

struct package__1caustic_triangles_common_CopyBand {
    band: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
    draw: array<u32, 4>
}

fn package__1caustic_triangles_common__1copy_rect(c: package__1caustic_triangles_common_CausticTriangles, k: u32) -> vec4<u32> {
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

fn package__1caustic_triangles_common__1with_band(c: package__1caustic_triangles_common_CausticTriangles, b: package__1caustic_triangles_common_CopyBand) -> package__1caustic_triangles_common_CausticTriangles {
    var n = c;
    n.band = min(c.band, b.band);
    return n;
}

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn package_shaders_reduce_unordered(u: u32) -> f32 {
    if (u & 2147483648u) != 0u {
        return bitcast<f32>(u & 2147483647u);
    }
    return bitcast<f32>(~u);
}

@group(0) @binding(1)
var<uniform> u: package__1caustic_triangles_common_CausticTriangles;

@group(0) @binding(0)
var<uniform> w: package__1caustic_triangles__1water_setup_WaterPhoton;
