fn ordered(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    if (b & 2147483648u) != 0u {
        return ~b;
    }
    return b | 2147483648u;
}

fn unordered(u: u32) -> f32 {
    if (u & 2147483648u) != 0u {
        return bitcast<f32>(u & 2147483647u);
    }
    return bitcast<f32>(~u);
}
