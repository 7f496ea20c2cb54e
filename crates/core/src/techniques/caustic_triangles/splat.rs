//! The splatting baseline, CPU twin of `caustic_triangles/splat.wgsl`: each valid photon as a
//! square splat of fixed size (the method the paper argues against, Fig. 1).

use super::CausticTrianglesSetup;
use super::photon::{pos, valid};
use super::triangles::{attenuated, to_map};
use crate::map::CausticsMap;

/// The splatting baseline: each valid photon as a square of `splat_size` texels.
pub fn splat_pass(setup: &CausticTrianglesSetup, photons: &[[f32; 4]]) -> CausticsMap {
    splat_pass_with_paths(setup, photons, None)
}

/// [`splat_pass`] for a water generator: each splat attenuated by `exp(−K d)` of its own path,
/// drawn at every offset of [`CausticTrianglesSetup::copies`], the lattice's repeated last row
/// and column left out ([`WaterTransport::lattice`](super::WaterTransport::lattice)).
pub fn splat_pass_with_paths(
    setup: &CausticTrianglesSetup,
    photons: &[[f32; 4]],
    paths: Option<&[f32]>,
) -> CausticsMap {
    let f = &setup.floor;
    let s = setup.splat_size;
    let k = setup.absorption();
    let lattice = setup.water.map_or(usize::MAX, |w| w.lattice);
    let mut acc = vec![[0.0f32; 3]; f.width * f.height];
    let splats = photons
        .iter()
        .enumerate()
        .filter(|(n, t)| valid(t) && n / setup.p < lattice && n % setup.p < lattice);
    let copies = setup.copies();
    for ((n, t), &off) in splats.flat_map(|x| copies.iter().map(move |o| (x, o))) {
        let c = f.to_pixel(pos(t) + off);
        let d = paths.map_or(0.0, |p| p[n] as f64);
        let value = attenuated(t[2] as f64 / (s * s * f.texel_area()), d, k);
        // Texel centres in [c − s/2, c + s/2).
        let j0 = ((c.x - s / 2.0 - 0.5).ceil().max(0.0)) as i64;
        let j1 = ((c.x + s / 2.0 - 0.5).ceil() - 1.0).min(f.width as f64 - 1.0) as i64;
        let i0 = ((c.y - s / 2.0 - 0.5).ceil().max(0.0)) as i64;
        let i1 = ((c.y + s / 2.0 - 0.5).ceil() - 1.0).min(f.height as f64 - 1.0) as i64;
        for i in i0..=i1 {
            for j in j0..=j1 {
                let a = &mut acc[i as usize * f.width + j as usize];
                a.iter_mut().zip(value).for_each(|(a, v)| *a += v);
            }
        }
    }
    to_map(f, acc)
}
