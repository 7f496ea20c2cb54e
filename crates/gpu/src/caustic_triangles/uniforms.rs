//! The uniform blocks and the copy band's buffer, as the WGSL files declare them.

use crate::pass::{f4, v4};
use crate::receivers::ReceiversUniform;
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_core::techniques::caustic_triangles::{CausticTrianglesSetup, DistanceMap};
use caustics_core::walls::Wall;

/// Mirrors `CausticTriangles` in `caustic_triangles/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CausticTrianglesUniform {
    /// xyz: the distance map's reference point (§3), world units; w: radius of the sphere around
    /// it that holds the generator's surfaces.
    pub centre: [f32; 4],
    /// xyz: the light frame's u axis (across the light); w: the generator's index of refraction.
    pub u: [f32; 4],
    /// xyz: the light frame's v axis (`w × u`); w: power of one photon before the Fresnel factors,
    /// floor-area units.
    pub v: [f32; 4],
    /// xyz: the direction the light travels (a point light: from the light to the generator's
    /// bounding-sphere centre); w: side of the baseline's square splats, map texels.
    pub w: [f32; 4],
    /// xy: the photon image's lower corner in light space; zw: one texel's size (world units for
    /// the sun, `tan` of the angle off `w` for a point light).
    pub rect: [f32; 4],
    /// xy: the floor map's origin (world units); z: its side; w: one map texel's area.
    pub floor: [f32; 4],
    /// Side of the photon hit location image, photons (§4.1; `P + 1` for a water lattice).
    pub p: u32,
    /// Face side of the distance map, texels.
    pub cube: u32,
    /// Layers of the distance map (§3).
    pub layers: u32,
    /// Most refractions / total internal reflections along a photon path.
    pub depth: u32,
    /// Linear search steps per ray segment of the distance-map search (§3).
    pub linear_steps: u32,
    /// Secant search iterations per hit (§3).
    pub secant_iterations: u32,
    /// 1: each refraction weights the photon by its Fresnel transmittance (§4.1); 0: it passes
    /// all the power.
    pub fresnel: u32,
    /// How a vertex's area is taken (§4.2): 0 the paper's (half the 4-neighbour triangles), 1 the
    /// hat rule (a third of the drawn ones).
    pub area_rule: u32,
    /// Floor map width, texels.
    pub width: u32,
    /// Floor map height, texels.
    pub height: u32,
    /// Face side of the light cube map, texels (used under a point light).
    pub light_cube: u32,
    /// Index of this generator's first texel in a buffer of several distance maps (the camera
    /// pass's); 0 in the generator's own.
    pub dm_base: u32,
    /// xyz: the point light's position, world units; w: 0 the sun (xyz unused), 1 a point light.
    pub light: [f32; 4],
    /// xyz: the spot's unit axis; w: cosine of its half-angle, -2 for a bare point light or the
    /// sun.
    pub spot: [f32; 4],
    /// Levels of the merge pyramid of small caustic triangles (§5; 0: no merging).
    pub merge_levels: u32,
    /// A block of quads merges when its corner quad covers less floor than this (`merge_texels`
    /// map texels' area), world units².
    pub merge_small: f32,
    /// A water generator's lattice `P` (0 for glass).
    pub lattice: u32,
    /// 1: tiling water, every primitive drawn at nine offsets of ±size; 0 otherwise.
    pub wrap: u32,
    /// xyz: the water's absorption `K` (0 for glass).
    pub absorption: [f32; 4],
    /// Quads from an edge a shifted copy is drawn for (`WaterTransport::band`).
    pub band: u32,
    /// 1: the photon image tiles in the receiver's plane (`WaterTransport::periodic`).
    pub periodic: u32,
    /// Padding to a multiple of 16 bytes.
    pub _pad: [u32; 2],
}

impl CausticTrianglesUniform {
    /// The block for generator `s` and its distance map `dm` (`dm_base` 0).
    pub fn new(s: &CausticTrianglesSetup, dm: &DistanceMap) -> Self {
        CausticTrianglesUniform {
            centre: v4(dm.centre, dm.radius),
            u: v4(s.u, s.ior),
            v: v4(s.v, s.flux),
            w: v4(s.w, s.splat_size),
            rect: f4([s.rect_lo.x, s.rect_lo.y, s.cell.x, s.cell.y]),
            floor: f4([
                s.floor.origin.x,
                s.floor.origin.y,
                s.floor.size,
                s.floor.texel_area(),
            ]),
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

/// Mirrors `WaterPhoton` in `caustic_triangles/water_setup.wgsl` (CPU twin: [`WaterSetup`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct WaterPhotonUniform {
    /// xyz: unit direction the sunlight travels (`z < 0`); w: the water's index of refraction.
    pub light: [f32; 4],
    /// x: the rest level's height above the floor; y: side of the water square; z: lattice
    /// spacing `size / P` (all world units); w: `T(θ0)`, flat water's Fresnel transmittance (1
    /// without Fresnel).
    pub water: [f32; 4],
    /// Quads per side of the lattice, `P` (`P + 1` photons a side).
    pub lattice: u32,
    /// 1: the surface tiles, its heights sampled wrapped at the square's edges.
    pub wrap: u32,
    /// 1: each photon's power is weighted by its Fresnel transmittance relative to flat water.
    pub fresnel: u32,
    /// 0: the floor; `1 + k`: wall `k` of `Wall::ALL` (its own photon image, `receiver_photon`).
    pub receiver: u32,
    /// What the floor's photons meet (the plane `z = 0` where `t0[3]` is 0).
    pub receivers: ReceiversUniform,
    /// xy: where photon `(0, 0)` lies ([`WaterSetup::origin`]); zw: unused.
    pub origin: [f32; 4],
}

impl WaterPhotonUniform {
    /// The uniform of the floor's photon pass.
    pub fn new(ws: &WaterSetup) -> Self {
        Self::for_receiver(ws, None)
    }

    /// The uniform of receiver `wall`'s photon pass (`None`: the floor).
    pub fn for_receiver(ws: &WaterSetup, wall: Option<Wall>) -> Self {
        let l = ws.light;
        WaterPhotonUniform {
            light: v4(l, ws.ior),
            water: f4([ws.depth, ws.size, ws.spacing, ws.t_flat]),
            lattice: ws.lattice as u32,
            wrap: ws.surface_wrap as u32,
            fresnel: ws.fresnel as u32,
            receiver: wall.map_or(0, |w| 1 + w.index() as u32),
            receivers: ReceiversUniform::of(ws.receivers.as_deref()),
            origin: [ws.origin.x as f32, ws.origin.y as f32, 0.0, 0.0],
        }
    }
}

/// Mirrors `CopyBand` in `caustic_triangles/common.wgsl`: the band of quads the shifted
/// copies of tiling water are drawn for as the copy band pass fits it, and their indirect draw.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CopyBandBuffer {
    /// Quads from an edge the shifted copies are drawn for, as fitted; `u32::MAX` before the
    /// first fit (the uniform's `band` then stands).
    pub band: u32,
    /// Padding that puts `draw` at byte 16.
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
