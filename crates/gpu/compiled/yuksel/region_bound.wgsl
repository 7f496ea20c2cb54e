@group(0) @binding(2)
var<storage, read_write> bound: array<atomic<u32>, 4>;

var<workgroup> group_bound: array<atomic<u32>, 4>;

@group(0) @binding(1)
var heights: texture_2d<f32>;

@compute @workgroup_size(16, 16)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    if local < 4u {
        atomicStore(&group_bound[local], 0u);
    }
    workgroupBarrier();
    let dims = textureDimensions(heights);
    if id.x < dims.x && id.y < dims.y {
        let cols = dims.x;
        let rows = dims.y;
        let dx = package_yuksel_common_u.size / f32(cols);
        let dy = package_yuksel_common_u.size / f32(rows);
        let l = package_yuksel_common_u.light.xyz;
        let i = id.y;
        let j = id.x;
        let h = textureLoad(heights, vec2<u32>(j, i), 0).x;
        let e = textureLoad(heights, vec2<u32>((j + 1u) % cols, i), 0).x;
        let w = textureLoad(heights, vec2<u32>((j + cols - 1u) % cols, i), 0).x;
        let n = textureLoad(heights, vec2<u32>(j, (i + 1u) % rows), 0).x;
        let s = textureLoad(heights, vec2<u32>(j, (i + rows - 1u) % rows), 0).x;
        let normal = package_shaders_optics__2height_field_normal(vec2<f32>((e - w) / (2.0 * dx), (n - s) / (2.0 * dy)));
        let tr = package_shaders_optics__1refract_dir(l, normal, package_yuksel_common_u.light.w);
        if -dot(l, normal) > 0.0 && tr.w != 0.0 && tr.z < 0.0 {
            let d = tr.xy / -tr.z * max(package_yuksel_common_u.depth + h, 0.0);
            atomicMax(&group_bound[0], package_shaders_reduce_ordered(-d.x));
            atomicMax(&group_bound[1], package_shaders_reduce_ordered(-d.y));
            atomicMax(&group_bound[2], package_shaders_reduce_ordered(d.x));
            atomicMax(&group_bound[3], package_shaders_reduce_ordered(d.y));
        }
    }
    workgroupBarrier();
    if local < 4u {
        atomicMax(&bound[local], atomicLoad(&group_bound[local]));
    }
}

fn package_shaders_optics__1refract_dir(incident: vec3<f32>, normal: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(incident, normal);
    let sin2_t = eta * eta * max(1.0 - cos_i * cos_i, 0.0);
    if sin2_t > 1.0 {
        return vec4<f32>(0.0);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return vec4<f32>(eta * incident + (eta * cos_i - cos_t) * normal, 1.0);
}

fn package_shaders_optics__2height_field_normal(gradient: vec2<f32>) -> vec3<f32> {
    return normalize(vec3<f32>(-gradient.x, -gradient.y, 1.0));
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

struct package_yuksel_common_Yuksel {
    light: vec4<f32>,
    pixel: vec2<f32>,
    centre_offset: vec2<f32>,
    attenuation: vec4<f32>,
    size: f32,
    depth: f32,
    ior: f32,
    fresnel: u32,
    width: u32,
    height: u32,
    n: u32,
    m: u32,
    wrap: u32,
    channel_base: u32,
    subsamples: u32,
    footprint: u32,
    phase: u32,
    split: f32,
    pre_tiles: u32,
    walls: u32,
    receivers: package_shaders_receivers_Receivers
}

@group(0) @binding(0)
var<uniform> package_yuksel_common_u: package_yuksel_common_Yuksel;
