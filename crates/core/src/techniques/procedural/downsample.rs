//! The downsample pass (`downsample.wgsl`, one per mip level): the texture variant's mip chain by
//! 2 x 2 box filtering.

/// Texture variant, the mip passes: level `k + 1` is the 2 x 2 box average of level `k`
/// (`(a + b + c + d) · ¼` in f32, in the order `downsample.wgsl` sums). Level 0 is `target²`.
pub fn mip_chain(level0: Vec<[f32; 3]>, target: usize) -> Vec<Vec<[f32; 3]>> {
    let map = crate::map::CausticsMap {
        width: target,
        height: target,
        size: 1.0,
        texels: level0,
    };
    map.pyramid().levels.into_iter().map(|l| l.texels).collect()
}
