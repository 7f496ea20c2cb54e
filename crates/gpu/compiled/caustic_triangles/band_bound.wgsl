@group(0) @binding(2)
var<storage, read_write> bound: array<atomic<u32>, 4>;

var<workgroup> group_bound: array<atomic<u32>, 3>;

@group(0) @binding(1)
var heights: texture_2d<f32>;

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if local < 3u {
        atomicStore(&group_bound[local], 0u);
    }
    workgroupBarrier();
    let dims = textureDimensions(heights);
    if id.x < dims.x && id.y < dims.y {
        let cols = dims.x;
        let rows = dims.y;
        let dx = w.water.y / f32(cols);
        let dy = w.water.y / f32(rows);
        let i = id.y;
        let j = id.x;
        let h = textureLoad(heights, vec2<u32>(j, i), 0).x;
        let hx = textureLoad(heights, vec2<u32>((j + 1u) % cols, i), 0).x;
        let hy = textureLoad(heights, vec2<u32>(j, (i + 1u) % rows), 0).x;
        atomicMax(&group_bound[0], package_shaders_reduce_ordered(max(abs(hx - h) / dx, abs(hy - h) / dy)));
        atomicMax(&group_bound[1], package_shaders_reduce_ordered(-h));
        atomicMax(&group_bound[2], package_shaders_reduce_ordered(h));
    }
    workgroupBarrier();
    if local < 3u {
        atomicMax(&bound[local], atomicLoad(&group_bound[local]));
    }
}

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

struct package_shaders_receivers_Receivers {
    view: vec4<f32>,
    t0: vec4<f32>
}

fn package_shaders_reduce_ordered(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    if (b & 2147483648u) != 0u {
        return ~b;
    }
    return b | 2147483648u;
}

@group(0) @binding(0)
var<uniform> w: package__1caustic_triangles__1water_setup_WaterPhoton;
