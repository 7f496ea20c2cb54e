struct Patches {
    wrap: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32
}

@group(0) @binding(1)
var heights: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(heights)) {
        return;
    }
    let texel = package_shaders_water__2grid_hermite_texel(heights, vec2<i32>(id.xy), patches_params.wrap != 0u);
    textureStore(patches_out, vec2<i32>(id.xy), texel);
}

fn package_shaders_water__1grid_index(first: i32, k: i32, n: i32, wrap: bool) -> i32 {
    let c = first + k;
    if wrap {
        if n < 3 {
            return c % n;
        }
        return select(c, c - n, c >= n);
    }
    return clamp(c, 0, n - 1);
}

fn package_shaders_water__2grid_hermite_texel(tex: texture_2d<f32>, c: vec2<i32>, wrap: bool) -> vec4<f32> {
    let n = vec2<i32>(textureDimensions(tex));
    var first = c - 1;
    if wrap {
        first = ((first % n) + n) % n;
    }
    let x = vec3<i32>(package_shaders_water__1grid_index(first.x, 0, n.x, wrap), package_shaders_water__1grid_index(first.x, 1, n.x, wrap), package_shaders_water__1grid_index(first.x, 2, n.x, wrap));
    let y = vec3<i32>(package_shaders_water__1grid_index(first.y, 0, n.y, wrap), package_shaders_water__1grid_index(first.y, 1, n.y, wrap), package_shaders_water__1grid_index(first.y, 2, n.y, wrap));
    let h = textureLoad(tex, vec2<i32>(x.y, y.y), 0).r;
    let hu = 0.5 * (textureLoad(tex, vec2<i32>(x.z, y.y), 0).r - textureLoad(tex, vec2<i32>(x.x, y.y), 0).r);
    let hv = 0.5 * (textureLoad(tex, vec2<i32>(x.y, y.z), 0).r - textureLoad(tex, vec2<i32>(x.y, y.x), 0).r);
    let huv = 0.25 * (textureLoad(tex, vec2<i32>(x.z, y.z), 0).r - textureLoad(tex, vec2<i32>(x.x, y.z), 0).r - textureLoad(tex, vec2<i32>(x.z, y.x), 0).r + textureLoad(tex, vec2<i32>(x.x, y.x), 0).r);
    return vec4<f32>(h, hu, hv, huv);
}

@group(0) @binding(2)
var patches_out: texture_storage_2d<rgba32float, write>;

@group(0) @binding(0)
var<uniform> patches_params: Patches;
