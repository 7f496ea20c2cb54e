// Min and max across workgroups with atomics on u32: `ordered(x)` keeps the order of f32 values as
// u32 values (negative floats' bits inverted, positive ones' sign bit set), so `atomicMax` on it is
// a max of the floats and `atomicMax` on `ordered(-x)` a min; 0 lies below every encoded value, so
// a buffer cleared to 0 holds "nothing yet". Each workgroup reduces into workgroup atomics first, so
// the storage buffer sees one atomic per workgroup per value.

fn ordered(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    if (b & 0x80000000u) != 0u {
        return ~b;
    }
    return b | 0x80000000u;
}

fn unordered(u: u32) -> f32 {
    if (u & 0x80000000u) != 0u {
        return bitcast<f32>(u & 0x7fffffffu);
    }
    return bitcast<f32>(~u);
}
