const MAX_CELLS: u32 = 128u;

const NEAR: f32 = 0.001;

struct Vertex {
    @builtin(position)
    clip: vec4<f32>,
    @location(0)
    world: vec3<f32>
}

fn cells() -> vec2<u32> {
    return min(textureDimensions(package__1final_image__2final_image_inputs__1water_height), vec2<u32>(MAX_CELLS));
}

@fragment
fn fs_main(in: Vertex) -> @location(0) vec4<f32> {
    return vec4<f32>(distance(in.world, package__1final_image__2final_image_inputs_params.camera_position), 0.0, 0.0, 1.0);
}

struct package__1final_image__2final_image_inputs_FinalImage {
    camera_position: vec3<f32>,
    exposure: f32,
    camera_forward: vec3<f32>,
    sun_disk: f32,
    camera_right: vec3<f32>,
    water_size: f32,
    camera_up: vec3<f32>,
    water_level: f32,
    sun: vec3<f32>,
    sun_intensity: f32,
    sun_water: vec3<f32>,
    t_flat: f32,
    light_color: vec3<f32>,
    ior: f32,
    absorption: vec3<f32>,
    scene_size: f32,
    map_size: f32,
    width: u32,
    height: u32,
    supersampling: u32,
    object_count: u32,
    flags: u32,
    _pad: u32,
    tone_map: u32,
    ambient: vec3<f32>,
    sun_cos_radius: f32,
    sky: array<vec4<f32>, 6>,
    slope_spread: f32,
    sun_variance: f32,
    slope_cols: u32,
    slope_rows: u32
}

@group(0) @binding(7)
var<storage, read> package__1final_image__2final_image_inputs__1slab_max: array<u32>;

fn package__1final_image__2final_image_inputs__1slope_bound() -> f32 {
    return bitcast<f32>(package__1final_image__2final_image_inputs__1slab_max[1]) * 1.5 + 1e-6;
}

@group(0) @binding(1)
var package__1final_image__2final_image_inputs__1water_height: texture_2d<f32>;

const package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE: u32 = 16u;

@group(0) @binding(0)
var<uniform> package__1final_image__2final_image_inputs_params: package__1final_image__2final_image_inputs_FinalImage;

fn package_shaders_water__2grid_sample_hermite(patches: texture_2d<f32>, p: vec2<f32>, size: f32, wrap: bool) -> vec3<f32> {
    let dims = vec2<f32>(textureDimensions(patches));
    let texel = size / dims;
    let uv = p / texel - 0.5;
    let base = floor(uv);
    let f = uv - base;
    let n = vec2<i32>(dims);
    var c0 = vec2<i32>(base);
    var c1 = c0 + 1;
    var keep = vec4<f32>(1.0);
    if wrap {
        c0 = ((c0 % n) + n) % n;
        c1 = select(c0 + 1, c0 + 1 - n, c0 + 1 >= n);
    }
    else {
        keep = vec4<f32>(select(0.0, 1.0, c0.x >= 0 && c0.x < n.x), select(0.0, 1.0, c0.y >= 0 && c0.y < n.y), select(0.0, 1.0, c1.x >= 0 && c1.x < n.x), select(0.0, 1.0, c1.y >= 0 && c1.y < n.y));
        c0 = clamp(c0, vec2<i32>(0), n - 1);
        c1 = clamp(c1, vec2<i32>(0), n - 1);
    }
    let k00 = vec4<f32>(1.0, keep.x, keep.y, keep.x * keep.y);
    let k10 = vec4<f32>(1.0, keep.z, keep.y, keep.z * keep.y);
    let k01 = vec4<f32>(1.0, keep.x, keep.w, keep.x * keep.w);
    let k11 = vec4<f32>(1.0, keep.z, keep.w, keep.z * keep.w);
    let p00 = textureLoad(patches, c0, 0) * k00;
    let p10 = textureLoad(patches, vec2<i32>(c1.x, c0.y), 0) * k10;
    let p01 = textureLoad(patches, vec2<i32>(c0.x, c1.y), 0) * k01;
    let p11 = textureLoad(patches, c1, 0) * k11;
    let bu = package_shaders_water_hermite(f.x);
    let bv = package_shaders_water_hermite(f.y);
    let row0 = bu[0].x * vec2<f32>(p00.x, p00.z) + bu[0].y * vec2<f32>(p10.x, p10.z) + bu[0].z * vec2<f32>(p00.y, p00.w) + bu[0].w * vec2<f32>(p10.y, p10.w);
    let row1 = bu[0].x * vec2<f32>(p01.x, p01.z) + bu[0].y * vec2<f32>(p11.x, p11.z) + bu[0].z * vec2<f32>(p01.y, p01.w) + bu[0].w * vec2<f32>(p11.y, p11.w);
    let drow0 = bu[1].x * vec2<f32>(p00.x, p00.z) + bu[1].y * vec2<f32>(p10.x, p10.z) + bu[1].z * vec2<f32>(p00.y, p00.w) + bu[1].w * vec2<f32>(p10.y, p10.w);
    let drow1 = bu[1].x * vec2<f32>(p01.x, p01.z) + bu[1].y * vec2<f32>(p11.x, p11.z) + bu[1].z * vec2<f32>(p01.y, p01.w) + bu[1].w * vec2<f32>(p11.y, p11.w);
    let h = bv[0].x * row0.x + bv[0].y * row1.x + bv[0].z * row0.y + bv[0].w * row1.y;
    let hu = bv[0].x * drow0.x + bv[0].y * drow1.x + bv[0].z * drow0.y + bv[0].w * drow1.y;
    let hv = bv[1].x * row0.x + bv[1].y * row1.x + bv[1].z * row0.y + bv[1].w * row1.y;
    return vec3<f32>(h, hu / texel.x, hv / texel.y);
}

fn package_shaders_water_hermite(t: f32) -> array<vec4<f32>, 2> {
    let t2 = t * t;
    let t3 = t2 * t;
    let w = vec4<f32>(2.0 * t3 - 3.0 * t2 + 1.0, -2.0 * t3 + 3.0 * t2, t3 - 2.0 * t2 + t, t3 - t2);
    let dw = vec4<f32>(6.0 * t2 - 6.0 * t, -6.0 * t2 + 6.0 * t, 3.0 * t2 - 4.0 * t + 1.0, 3.0 * t2 - 2.0 * t);
    return array<vec4<f32>, 2>(w, dw);
}

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> Vertex {
    let n = cells();
    let quad = index / 6u;
    let corner = array<vec2<u32>, 6>(vec2<u32>(0u, 0u), vec2<u32>(1u, 0u), vec2<u32>(1u, 1u), vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(0u, 1u))[index % 6u];
    let ij = vec2<f32>(vec2<u32>(quad % (n.x + 1u), quad / (n.x + 1u)) + corner) - 0.5;
    let xy = ij * (package__1final_image__2final_image_inputs_params.water_size / vec2<f32>(n));
    let wrap = (package__1final_image__2final_image_inputs_params.flags & package__1final_image__2final_image_inputs__2FLAG_WRAP_SURFACE) != 0u;
    let h = package_shaders_water__2grid_sample_hermite(package__1final_image__2final_image_inputs__1water_height, xy, package__1final_image__2final_image_inputs_params.water_size, wrap).x;
    let cell = package__1final_image__2final_image_inputs_params.water_size / vec2<f32>(n);
    let raise = package__1final_image__2final_image_inputs__1slope_bound() * length(cell);
    let world = vec3<f32>(xy, package__1final_image__2final_image_inputs_params.water_level + h + raise);
    let v = world - package__1final_image__2final_image_inputs_params.camera_position;
    let right = package__1final_image__2final_image_inputs_params.camera_right;
    let up = package__1final_image__2final_image_inputs_params.camera_up;
    let forward = package__1final_image__2final_image_inputs_params.camera_forward;
    let w = dot(v, forward) / dot(forward, forward);
    return Vertex(vec4<f32>(dot(v, right) / dot(right, right), dot(v, up) / dot(up, up), NEAR, w), world);
}
