//! The uniform blocks and the copy band's buffer, as the WGSL files declare them.

use crate::receivers::ReceiversUniform;
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_core::techniques::caustic_triangles::{CausticTrianglesSetup, DistanceMap};
use caustics_core::walls::Wall;

/// Mirrors `CausticTriangles` in `caustic_triangles/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CausticTrianglesUniform {
    pub centre: [f32; 4],
    pub u: [f32; 4],
    pub v: [f32; 4],
    pub w: [f32; 4],
    pub rect: [f32; 4],
    pub floor: [f32; 4],
    pub p: u32,
    pub cube: u32,
    pub layers: u32,
    pub depth: u32,
    pub linear_steps: u32,
    pub secant_iterations: u32,
    pub fresnel: u32,
    pub area_rule: u32,
    pub width: u32,
    pub height: u32,
    pub light_cube: u32,
    /// Index of this generator's first texel in a buffer of several distance maps (the camera
    /// pass's); 0 in the generator's own.
    pub dm_base: u32,
    pub light: [f32; 4],
    pub spot: [f32; 4],
    pub merge_levels: u32,
    pub merge_small: f32,
    /// A water generator's lattice `P` (0 for glass).
    pub lattice: u32,
    pub wrap: u32,
    /// xyz: the water's absorption `K` (0 for glass).
    pub absorption: [f32; 4],
    /// Quads from an edge a shifted copy is drawn for (`WaterTransport::band`).
    pub band: u32,
    /// 1: the photon image tiles in the receiver's plane (`WaterTransport::periodic`).
    pub periodic: u32,
    pub _pad: [u32; 2],
}

impl CausticTrianglesUniform {
    pub fn new(s: &CausticTrianglesSetup, dm: &DistanceMap) -> Self {
        let v4 = |v: glam::DVec3, w: f64| [v.x as f32, v.y as f32, v.z as f32, w as f32];
        CausticTrianglesUniform {
            centre: v4(dm.centre, dm.radius),
            u: v4(s.u, s.ior),
            v: v4(s.v, s.flux),
            w: v4(s.w, s.splat_size),
            rect: [
                s.rect_lo.x as f32,
                s.rect_lo.y as f32,
                s.cell.x as f32,
                s.cell.y as f32,
            ],
            floor: [
                s.floor.origin.x as f32,
                s.floor.origin.y as f32,
                s.floor.size as f32,
                s.floor.texel_area() as f32,
            ],
            p: s.p as u32,
            cube: dm.resolution as u32,
            layers: dm.layers as u32,
            depth: s.depth,
            linear_steps: s.linear_steps,
            secant_iterations: s.secant_iterations,
            fresnel: s.fresnel as u32,
            area_rule: s.area_rule.code(),
            width: s.floor.width as u32,
            height: s.floor.height as u32,
            light_cube: s.light_cube as u32,
            dm_base: 0,
            light: match s.point {
                Some(pl) => v4(pl.position, 1.0),
                None => [0.0; 4],
            },
            spot: match s.point {
                Some(pl) => v4(pl.axis, pl.cone.map_or(-2.0, f64::cos)),
                None => [0.0, 0.0, 0.0, -2.0],
            },
            merge_levels: s.merge_levels,
            merge_small: (s.merge_texels * s.floor.texel_area()) as f32,
            lattice: s.water.map_or(0, |w| w.lattice as u32),
            wrap: s.water.is_some_and(|w| w.wrap) as u32,
            absorption: v4(s.absorption(), 0.0),
            band: s.water.map_or(0, |w| w.band as u32),
            periodic: s.water.is_some_and(|w| w.periodic) as u32,
            _pad: [0; 2],
        }
    }
}

/// Mirrors `WaterPhoton` in `caustic_triangles/water_photon.wgsl` (CPU twin: [`WaterSetup`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WaterPhotonUniform {
    pub light: [f32; 4],
    pub water: [f32; 4],
    pub lattice: u32,
    pub wrap: u32,
    pub fresnel: u32,
    /// 0: the floor; `1 + k`: wall `k` of `Wall::ALL` (its own photon image, `receiver_photon`).
    pub receiver: u32,
    /// What the floor's photons meet (the plane `z = 0` where `t0[3]` is 0).
    pub receivers: ReceiversUniform,
}

impl WaterPhotonUniform {
    pub fn new(ws: &WaterSetup) -> Self {
        Self::for_receiver(ws, None)
    }

    /// The uniform of receiver `wall`'s photon pass (`None`: the floor).
    pub fn for_receiver(ws: &WaterSetup, wall: Option<Wall>) -> Self {
        let l = ws.light;
        WaterPhotonUniform {
            light: [l.x as f32, l.y as f32, l.z as f32, ws.ior as f32],
            water: [
                ws.depth as f32,
                ws.size as f32,
                ws.spacing as f32,
                ws.t_flat as f32,
            ],
            lattice: ws.lattice as u32,
            wrap: ws.surface_wrap as u32,
            fresnel: ws.fresnel as u32,
            receiver: wall.map_or(0, |w| 1 + w.index() as u32),
            receivers: ReceiversUniform::of(ws.receivers.as_deref()),
        }
    }
}

/// Mirrors `CopyBand` in `caustic_triangles/common.wgsl`: the band of quads the shifted
/// copies of tiling water are drawn for as the copy band pass fits it, and their indirect draw.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CopyBandBuffer {
    pub band: u32,
    pub _pad: [u32; 3],
    /// `wgpu::util::DrawIndirectArgs`: vertex count, instance count, first vertex, first instance.
    pub draw: [u32; 4],
}

impl CopyBandBuffer {
    /// Before any copy band pass: the uniform's band stands (`u32::MAX` narrows nothing).
    pub fn unfitted() -> Self {
        CopyBandBuffer {
            band: u32::MAX,
            ..Default::default()
        }
    }
}
