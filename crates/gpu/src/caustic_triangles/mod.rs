//! Technique `caustic-triangles` on the GPU: "Caustic Triangles on the GPU" (Umenhoffer, Patow &
//! Szirmay-Kalos). The method, the area rules and where it departs from the paper are documented
//! with its CPU twin, `caustics_core::techniques::caustic_triangles`, which these passes mirror one
//! for one:
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | photon tracing (compute, §4.1) | `caustic_triangles/photon.wgsl` + `distance_map.wgsl` | `photon_pass` |
//! | vertex irradiance (compute, §5) | `caustic_triangles/irradiance.wgsl` | `irradiance_pass` |
//! | caustic triangles (render, §4.2) | `caustic_triangles/triangles.wgsl` + `merge.wgsl` | `triangles_pass` |
//! | merge pyramid (compute, §5, with `merge_levels`) | `caustic_triangles/pyramid.wgsl` | `merge::pyramid_pass` |
//! | splatting baseline (render) | `caustic_triangles/splat.wgsl` | `splat_pass` |
//! | caustic triangles on the light cube map faces (render, §4.2, point light) | `caustic_triangles/cube.wgsl` | `cube::cube_triangles_pass` |
//! | light cube shadow distances (compute, §4.3) | `caustic_triangles/shadow.wgsl` | `cube::shadow_pass` |
//! | camera pass (compute, §4.3), [`camera`] | `caustic_triangles/camera.wgsl` | `camera::camera_pass` |
//! | water photon pass (compute, the water surface as the generator) | `caustic_triangles/water_photon.wgsl` | `water::photon_pass` |
//! | copy band (compute, tiling water: a bound over every texel, then one thread) | `caustic_triangles/band_bound.wgsl`, `band.wgsl` | `water::copy_band` |
//!
//! With the water surface as the generator ([`WaterFrame`], `caustics_core::techniques::
//! caustic_triangles::water`) the water photon pass replaces the photon tracing pass and also
//! writes each photon's refracted path length; the triangles and splats read it for Beer-Lambert
//! absorption and draw nine instances (offsets of `±size`) of each primitive for tiling water. The
//! eight shifted copies are drawn only over the band of quads whose light can cross an edge; the
//! copy band pass fits that band on the GPU from the heights it reads and writes the indirect draw
//! of the shifted copies, so a frame never reads the heights on the CPU (the CPU twin fits the same
//! bound in f64, `WaterSetup::fit_band`; any band at least the light's reach draws the same map).
//!
//! With the pool's walls (`WaterSetup::with_walls`) nothing wraps; each wall is a
//! receiver of its own ([`WallFrames`]): the water photon pass again with the uniform's `receiver`
//! (the rays extended to the wall's plane, `water::receiver_photon`), vertex irradiance and
//! triangles into its layer of a 4-layer wall-map texture (`water::wall_caustics`).
//!
//! The layered distance map is built on the CPU ([`DistanceMap::build`]) and uploaded as a storage
//! buffer; the photon hit location image and the vertex irradiances are storage buffers that the
//! vertex shaders read (no vertex buffers: 6 vertices per photon-image quad, 6 per splat). The floor
//! map is drawn with additive blending into `Rgba32Float` where the adapter has
//! `FLOAT32_BLENDABLE`, otherwise into `Rgba16Float` (blendable everywhere; about 3 significant
//! digits, ~0.2 % of the total lost to rounding in accumulation).

pub mod camera;
pub mod technique;

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::caustic_triangles::cube::{FAR, LightCube};
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_core::techniques::caustic_triangles::{CausticTrianglesSetup, DistanceMap};
use caustics_core::walls::{Wall, WallMaps};

use crate::pass::{additive_pipeline, begin_compute, bind_group, compute_pipeline};
use crate::shaders::{OPTICS, PassSource, REDUCE, WATER};
use crate::{GpuContext, GpuError, GpuTimer, WaterTextures};

const COMMON: &str = include_str!("common.wgsl");
const DISTANCE_MAP: &str = include_str!("distance_map.wgsl");
const MERGE: &str = include_str!("merge.wgsl");
const WATER_SETUP: &str = include_str!("water_setup.wgsl");

pub const PHOTON: PassSource = PassSource {
    name: "caustic-triangles photon tracing",
    shared: &[OPTICS, COMMON, DISTANCE_MAP],
    file: "caustic_triangles/photon.wgsl",
    source: include_str!("photon.wgsl"),
};
pub const IRRADIANCE: PassSource = PassSource {
    name: "caustic-triangles vertex irradiance",
    shared: &[COMMON],
    file: "caustic_triangles/irradiance.wgsl",
    source: include_str!("irradiance.wgsl"),
};
pub const TRIANGLES: PassSource = PassSource {
    name: "caustic-triangles triangles",
    shared: &[COMMON, MERGE],
    file: "caustic_triangles/triangles.wgsl",
    source: include_str!("triangles.wgsl"),
};
pub const PYRAMID: PassSource = PassSource {
    name: "caustic-triangles merge pyramid",
    shared: &[COMMON],
    file: "caustic_triangles/pyramid.wgsl",
    source: include_str!("pyramid.wgsl"),
};
pub const CUBE: PassSource = PassSource {
    name: "caustic-triangles light cube map",
    shared: &[COMMON, MERGE],
    file: "caustic_triangles/cube.wgsl",
    source: include_str!("cube.wgsl"),
};
pub const SHADOW: PassSource = PassSource {
    name: "caustic-triangles light cube shadow distances",
    shared: &[COMMON, DISTANCE_MAP],
    file: "caustic_triangles/shadow.wgsl",
    source: include_str!("shadow.wgsl"),
};
pub const WATER_PHOTON: PassSource = PassSource {
    name: "caustic-triangles water photons",
    shared: &[OPTICS, WATER, WATER_SETUP],
    file: "caustic_triangles/water_photon.wgsl",
    source: include_str!("water_photon.wgsl"),
};
pub const COPY_BAND: PassSource = PassSource {
    name: "caustic-triangles copy band",
    shared: &[COMMON, WATER_SETUP, REDUCE],
    file: "caustic_triangles/band.wgsl",
    source: include_str!("band.wgsl"),
};
pub const BAND_BOUND: PassSource = PassSource {
    name: "caustic-triangles band bound",
    shared: &[COMMON, WATER_SETUP, REDUCE],
    file: "caustic_triangles/band_bound.wgsl",
    source: include_str!("band_bound.wgsl"),
};
pub const SPLAT: PassSource = PassSource {
    name: "caustic-triangles splats",
    shared: &[COMMON],
    file: "caustic_triangles/splat.wgsl",
    source: include_str!("splat.wgsl"),
};

/// Every pass of the technique, for its registry entry.
pub const PASSES: &[&PassSource] = &[
    &PHOTON,
    &IRRADIANCE,
    &TRIANGLES,
    &PYRAMID,
    &CUBE,
    &SHADOW,
    &WATER_PHOTON,
    &COPY_BAND,
    &BAND_BOUND,
    &SPLAT,
    &camera::CAMERA,
];

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
        }
    }
}

/// Tiling water's copy band on the GPU: the bound pass's buffer and bind group, the band pass's, and
/// the height grid the bound pass covers.
struct BandPasses {
    bound: wgpu::Buffer,
    bound_bind: wgpu::BindGroup,
    band: wgpu::BindGroup,
    grid: (u32, u32),
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

/// How the photon hits become the floor map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reconstruction {
    /// The paper's caustic triangles.
    Triangles,
    /// The fixed-size splatting baseline.
    Splats,
}

/// The technique's pipelines, built once per device for one floor-map format.
pub struct CausticTriangles {
    pub(crate) photon: wgpu::ComputePipeline,
    pub(crate) irradiance: wgpu::ComputePipeline,
    pyramid: wgpu::ComputePipeline,
    triangles: wgpu::RenderPipeline,
    splat: wgpu::RenderPipeline,
    cube: wgpu::RenderPipeline,
    shadow: wgpu::ComputePipeline,
    water_photon: wgpu::ComputePipeline,
    copy_band: wgpu::ComputePipeline,
    band_bound: wgpu::ComputePipeline,
    /// `Rgba32Float` with `FLOAT32_BLENDABLE`, else `Rgba16Float` (floor and light cube maps).
    pub map_format: wgpu::TextureFormat,
}

/// One generator's resources: the distance map, the photon image, the vertex irradiances, the
/// floor map, and the bind groups. Built once; encode it every frame the light or object moves
/// (the uniform and distance map can be rewritten in place for the same sizes).
pub struct Frame {
    pub setup: CausticTrianglesSetup,
    pub uniform: wgpu::Buffer,
    pub dm_buffer: wgpu::Buffer,
    pub photons: wgpu::Buffer,
    /// Refracted path length per photon (a water generator's; zeros for glass).
    pub paths: wgpu::Buffer,
    pub irradiance: wgpu::Buffer,
    pub map: wgpu::Texture,
    pub map_view: wgpu::TextureView,
    pub(crate) photon_bind: wgpu::BindGroup,
    pub(crate) irradiance_bind: wgpu::BindGroup,
    /// The merge pyramid (§5) and one bind group per level.
    pub pyramid: wgpu::Buffer,
    pyramid_binds: Vec<wgpu::BindGroup>,
    /// The band the GPU fitted and the indirect draw of the shifted copies ([`CopyBandBuffer`]).
    pub copy_band: wgpu::Buffer,
    /// Whether the shifted copies are drawn indirectly from `copy_band` (a water frame of tiling
    /// water, whose copy band pass writes it) rather than from the setup's band.
    gpu_band: bool,
    triangles_bind: wgpu::BindGroup,
    splat_bind: wgpu::BindGroup,
    bytes: u64,
}

impl Frame {
    /// GPU memory this frame's buffers and map take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }
}

/// What one GPU run reads back.
pub struct GpuOutput {
    pub photons: Vec<[f32; 4]>,
    pub irradiance: Vec<f32>,
    pub map: CausticsMap,
}

impl CausticTriangles {
    /// Pipelines for the best floor-map format this device blends.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let format = if ctx
            .device
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE)
        {
            wgpu::TextureFormat::Rgba32Float
        } else {
            wgpu::TextureFormat::Rgba16Float
        };
        Self::with_format(ctx, format)
    }

    /// Pipelines for a given floor-map format (`Rgba32Float` needs `FLOAT32_BLENDABLE`).
    pub fn with_format(
        ctx: &GpuContext,
        map_format: wgpu::TextureFormat,
    ) -> Result<Self, GpuError> {
        let t = CausticTriangles {
            photon: compute_pipeline(ctx, &PHOTON),
            irradiance: compute_pipeline(ctx, &IRRADIANCE),
            pyramid: compute_pipeline(ctx, &PYRAMID),
            triangles: additive_pipeline(ctx, &TRIANGLES, map_format),
            splat: additive_pipeline(ctx, &SPLAT, map_format),
            cube: additive_pipeline(ctx, &CUBE, map_format),
            shadow: compute_pipeline(ctx, &SHADOW),
            water_photon: compute_pipeline(ctx, &WATER_PHOTON),
            copy_band: compute_pipeline(ctx, &COPY_BAND),
            band_bound: compute_pipeline(ctx, &BAND_BOUND),
            map_format,
        };
        ctx.check()?;
        Ok(t)
    }

    pub fn frame(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
    ) -> Result<Frame, GpuError> {
        self.frame_drawing_into(ctx, setup, dm, None)
    }

    /// A frame whose floor map is `map` when given (a floor map of the setup's size and this
    /// format that several generators draw into, [`draw_floor`](Self::draw_floor) with `clear`
    /// for the first only), else its own.
    pub fn frame_drawing_into(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        map: Option<&wgpu::Texture>,
    ) -> Result<Frame, GpuError> {
        self.frame_into_layer(ctx, setup, dm, map.map(|m| (m, 0)))
    }

    /// [`frame_drawing_into`](Self::frame_drawing_into) a layer of a shared 2-D array texture at
    /// least as wide as the setup's map (the wall maps: the map in the layer's first columns).
    pub fn frame_into_layer(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        map: Option<(&wgpu::Texture, u32)>,
    ) -> Result<Frame, GpuError> {
        use wgpu::BufferUsages as B;
        let (w, h) = (setup.floor.width as u32, setup.floor.height as u32);
        ctx.check_texture_size("caustic-triangles floor map", w, h)?;
        let p = setup.p as u64;
        let dm_bytes = dm.texels.len() as u64 * 16;
        ctx.check_buffer_size("caustic-triangles distance map", dm_bytes)?;
        ctx.check_buffer_size("caustic-triangles photon image", p * p * 16)?;
        let uniform = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("caustic-triangles uniform"),
            contents: bytemuck::bytes_of(&CausticTrianglesUniform::new(setup, dm)),
            usage: B::UNIFORM | B::COPY_DST,
        });
        let dm_buffer = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("caustic-triangles distance map"),
            contents: bytemuck::cast_slice(&dm.texels),
            usage: B::STORAGE | B::COPY_DST,
        });
        let photons = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("caustic-triangles photon image"),
            size: p * p * 16,
            usage: B::STORAGE | B::COPY_SRC | B::COPY_DST,
            mapped_at_creation: false,
        });
        let paths = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("caustic-triangles photon path lengths"),
            size: p * p * 4,
            usage: B::STORAGE | B::COPY_SRC,
            mapped_at_creation: false,
        });
        let irradiance = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("caustic-triangles vertex irradiance"),
            size: p * p * 4,
            usage: B::STORAGE | B::COPY_SRC,
            mapped_at_creation: false,
        });
        let own_map = map.is_none();
        let layer = map.map_or(0, |m| m.1);
        let map = match map.map(|m| m.0) {
            Some(m) => {
                if m.width() < w
                    || (m.height(), m.format()) != (h, self.map_format)
                    || layer >= m.depth_or_array_layers()
                {
                    return Err(GpuError::Validation(format!(
                        "caustic-triangles: a shared floor map of {} x {} {:?} for a {w} x {h} {:?} frame",
                        m.width(),
                        m.height(),
                        m.format(),
                        self.map_format
                    )));
                }
                m.clone()
            }
            None => ctx.texture_2d(
                "caustic-triangles floor map",
                (w, h, 1),
                self.map_format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::TEXTURE_BINDING,
            ),
        };
        let map_view = map.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2),
            base_array_layer: layer,
            array_layer_count: Some(1),
            ..Default::default()
        });
        let photon_bind = bind_group(
            ctx,
            "caustic-triangles photon tracing",
            &self.photon.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                dm_buffer.as_entire_binding(),
                photons.as_entire_binding(),
            ],
        );
        let irradiance_bind = bind_group(
            ctx,
            "caustic-triangles vertex irradiance",
            &self.irradiance.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                photons.as_entire_binding(),
                irradiance.as_entire_binding(),
            ],
        );
        let (sides, offsets) = caustics_core::techniques::caustic_triangles::merge::layout(
            setup.p,
            setup.merge_levels,
        );
        let pyramid_texels = (offsets.last().unwrap() + sides.last().unwrap().pow(2)) as u64;
        ctx.check_buffer_size(
            "caustic-triangles merge pyramid",
            pyramid_texels.max(1) * 16,
        )?;
        let pyramid = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("caustic-triangles merge pyramid"),
            size: pyramid_texels.max(1) * 16,
            usage: B::STORAGE | B::COPY_SRC,
            mapped_at_creation: false,
        });
        let pyramid_binds = (0..=setup.merge_levels)
            .map(|k| {
                let level = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("caustic-triangles merge level"),
                    contents: bytemuck::cast_slice(&[k, 0u32, 0, 0]),
                    usage: B::UNIFORM,
                });
                bind_group(
                    ctx,
                    "caustic-triangles merge pyramid",
                    &self.pyramid.get_bind_group_layout(0),
                    &[
                        uniform.as_entire_binding(),
                        photons.as_entire_binding(),
                        irradiance.as_entire_binding(),
                        pyramid.as_entire_binding(),
                        level.as_entire_binding(),
                    ],
                )
            })
            .collect();
        let copy_band = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("caustic-triangles copy band"),
            contents: bytemuck::bytes_of(&CopyBandBuffer::unfitted()),
            usage: B::STORAGE | B::INDIRECT | B::COPY_SRC,
        });
        let triangles_bind = bind_group(
            ctx,
            "caustic-triangles triangles",
            &self.triangles.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                photons.as_entire_binding(),
                irradiance.as_entire_binding(),
                pyramid.as_entire_binding(),
                paths.as_entire_binding(),
                copy_band.as_entire_binding(),
            ],
        );
        let splat_bind = bind_group(
            ctx,
            "caustic-triangles splats",
            &self.splat.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                photons.as_entire_binding(),
                paths.as_entire_binding(),
            ],
        );
        ctx.check()?;
        let texel = self.map_format.block_copy_size(None).unwrap_or(16) as u64;
        Ok(Frame {
            setup: setup.clone(),
            uniform,
            dm_buffer,
            photons,
            paths,
            irradiance,
            map,
            map_view,
            photon_bind,
            irradiance_bind,
            pyramid,
            pyramid_binds,
            triangles_bind,
            splat_bind,
            copy_band,
            gpu_band: false,
            bytes: dm_bytes
                + p * p * 24
                + own_map as u64 * (w * h) as u64 * texel
                + 176
                + std::mem::size_of::<CopyBandBuffer>() as u64,
        })
    }

    /// Record the photon tracing pass, then the reconstruction into the floor map (cleared first).
    pub fn encode(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
    ) {
        self.encode_photons(frame, encoder, timer.as_deref_mut());
        self.encode_reconstruction(frame, encoder, timer, reconstruction);
    }

    /// Record the photon tracing pass alone (§4.1) into `frame.photons`.
    pub fn encode_photons(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let p = frame.setup.p as u32;
        let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles photon tracing");
        pass.set_pipeline(&self.photon);
        pass.set_bind_group(0, &frame.photon_bind, &[]);
        pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
    }

    /// Record the reconstruction only (vertex irradiance and triangles, or splats) from the photon
    /// image already in `frame.photons`, into the floor map (cleared first).
    pub fn encode_reconstruction(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
    ) {
        if reconstruction == Reconstruction::Triangles {
            self.encode_irradiance(frame, encoder, timer.as_deref_mut());
        }
        self.draw_floor(frame, encoder, timer, reconstruction, &frame.map_view, true);
    }

    /// The vertex irradiance pass (§5), then, with `merge_levels`, the merge pyramid level by level.
    pub fn encode_irradiance(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        let p = frame.setup.p as u32;
        {
            let mut pass =
                begin_compute(encoder, &mut timer, "caustic-triangles vertex irradiance");
            pass.set_pipeline(&self.irradiance);
            pass.set_bind_group(0, &frame.irradiance_bind, &[]);
            pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
        }
        if frame.setup.merge_levels == 0 {
            return;
        }
        for (k, bind) in frame.pyramid_binds.iter().enumerate() {
            let n = (p - 1) >> k;
            let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles merge pyramid");
            pass.set_pipeline(&self.pyramid);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(n.div_ceil(8).max(1), n.div_ceil(8).max(1), 1);
        }
    }

    /// The floor-map render pass alone (triangles from the vertex irradiances already computed, or
    /// splats) into `target` (a floor map of this frame's size), cleared first or added to
    /// (several generators into one map).
    pub fn draw_floor(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
        target: &wgpu::TextureView,
        clear: bool,
    ) {
        let p = frame.setup.p as u32;
        let copies = frame.setup.copies().len() as u32;
        let label = match reconstruction {
            Reconstruction::Triangles => "caustic-triangles triangles",
            Reconstruction::Splats => "caustic-triangles splats",
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: if clear {
                        wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                    } else {
                        wgpu::LoadOp::Load
                    },
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: timer.as_mut().and_then(|t| t.render_pass(label)),
            occlusion_query_set: None,
            multiview_mask: None,
        });
        // The map may fill only the first columns of its target (a wall map in its layer).
        let f = &frame.setup.floor;
        pass.set_viewport(0.0, 0.0, f.width as f32, f.height as f32, 0.0, 1.0);
        match reconstruction {
            Reconstruction::Triangles => {
                pass.set_pipeline(&self.triangles);
                pass.set_bind_group(0, &frame.triangles_bind, &[]);
                let all = 6 * (p - 1) * (p - 1);
                if copies == 1 {
                    pass.draw(0..all, 0..1);
                } else {
                    // The unshifted copy (instance 8) over every quad, the eight shifted ones
                    // (instances 0..8, `copy_of_instance` in common.wgsl) over their bands only
                    // (`copy_rect`): an edge band is at most `band` quads deep. The band is the
                    // GPU's own where the copy band pass fitted it, else the setup's.
                    pass.draw(0..all, 8..9);
                    if frame.gpu_band {
                        pass.draw_indirect(
                            &frame.copy_band,
                            std::mem::offset_of!(CopyBandBuffer, draw) as u64,
                        );
                    } else {
                        let area =
                            |(i0, i1, j0, j1): (usize, usize, usize, usize)| (i1 - i0) * (j1 - j0);
                        let most = (0..9)
                            .filter(|&k| k != 4)
                            .map(|k| area(frame.setup.copy_rect(k)))
                            .max()
                            .unwrap_or(0) as u32;
                        pass.draw(0..(6 * most).min(all), 0..8);
                    }
                }
            }
            Reconstruction::Splats => {
                pass.set_pipeline(&self.splat);
                pass.set_bind_group(0, &frame.splat_bind, &[]);
                pass.draw(0..6 * p * p, 0..copies);
            }
        }
    }

    /// Read the floor map back (either format) as a caustics map.
    pub fn read_map(&self, ctx: &GpuContext, frame: &Frame) -> Result<CausticsMap, GpuError> {
        let f = &frame.setup.floor;
        let texels = ctx.read_rgba_f32(&frame.map)?;
        Ok(CausticsMap {
            width: f.width,
            height: f.height,
            size: f.size,
            texels: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }

    /// Run the technique once and read everything back.
    pub fn run(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        reconstruction: Reconstruction,
    ) -> Result<GpuOutput, GpuError> {
        let frame = self.frame(ctx, setup, dm)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode(&frame, &mut encoder, None, reconstruction);
        ctx.queue.submit([encoder.finish()]);
        let map = self.read_map(ctx, &frame)?;
        Ok(GpuOutput {
            photons: ctx.read_buffer(&frame.photons)?,
            irradiance: ctx.read_buffer(&frame.irradiance)?,
            map,
        })
    }
}

impl CausticTriangles {
    /// The reconstruction alone from a given photon hit location image (`setup.p²` texels,
    /// `(x, y, Φ, σ)`), e.g. a synthetic one in a test; `dm` only has to fit the frame.
    pub fn reconstruct(
        &self,
        ctx: &GpuContext,
        setup: &CausticTrianglesSetup,
        dm: &DistanceMap,
        photons: &[[f32; 4]],
        reconstruction: Reconstruction,
    ) -> Result<GpuOutput, GpuError> {
        assert_eq!(photons.len(), setup.p * setup.p, "photon image size");
        let frame = self.frame(ctx, setup, dm)?;
        ctx.write_buffer(&frame.photons, 0, bytemuck::cast_slice(photons));
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_reconstruction(&frame, &mut encoder, None, reconstruction);
        ctx.queue.submit([encoder.finish()]);
        let map = self.read_map(ctx, &frame)?;
        Ok(GpuOutput {
            photons: ctx.read_buffer(&frame.photons)?,
            irradiance: ctx.read_buffer(&frame.irradiance)?,
            map,
        })
    }
}

/// The water surface as the generator: a [`Frame`] whose photon image the water photon pass
/// writes from a height texture (no distance map), and whose shifted copies of tiling water the
/// copy band pass fits from the same texture. Built once per lattice, map and height-grid size;
/// every encode reads the heights afresh (the caller's texture, [`CausticTriangles::water_frame_with_water`],
/// or its own, rewritten by [`update_heights`](Self::update_heights)).
pub struct WaterFrame {
    pub frame: Frame,
    /// The setup its uniforms hold; the band of `setup.setup.water` is the lattice's (every
    /// quad): the copy band pass narrows it on the GPU.
    pub setup: WaterSetup,
    /// The heights it uploaded itself ([`CausticTriangles::water_frame`]); `None` when it reads
    /// the caller's.
    pub heights: Option<wgpu::Texture>,
    /// The grid size of the heights it reads.
    pub grid: (u32, u32),
    pub water_uniform: wgpu::Buffer,
    water_bind: wgpu::BindGroup,
    /// The copy band pass's bind group (tiling water only).
    band_bind: Option<BandPasses>,
    /// The walls' receivers when the setup has walls ([`WaterSetup::with_walls`]).
    pub walls: Option<WallFrames>,
}

/// The pool's walls as receivers of a water frame (CPU twin `water::wall_caustics`):
/// each wall has its own photon image (the rays extended to its plane), vertex irradiance and
/// caustic triangles, a [`Frame`] drawing into its layer of one 2-D array texture
/// ([`crate::technique::Technique::walls`]'s layout).
pub struct WallFrames {
    /// 4 layers in `Wall::ALL`'s order, as wide as the widest wall map, as tall as the maps.
    pub texture: wgpu::Texture,
    /// Empty maps: the walls' sizes.
    pub layout: WallMaps,
    /// One per wall, in `Wall::ALL`'s order.
    pub walls: Vec<WallFrame>,
}

/// One wall's receiver: its frame and its photon pass's uniform and bind group.
pub struct WallFrame {
    pub frame: Frame,
    pub water_uniform: wgpu::Buffer,
    water_bind: wgpu::BindGroup,
}

impl WaterFrame {
    /// Overwrite the heights with a grid of the same size, in a frame that uploaded its own (the
    /// copy band pass refits the band on the GPU at the next encode).
    pub fn update_heights(&mut self, ctx: &GpuContext, heights: &Grid) -> Result<(), GpuError> {
        let Some(texture) = &self.heights else {
            return Err(GpuError::BadOption(
                "caustic-triangles water frame: it reads the caller's heights texture; write that instead".into(),
            ));
        };
        if (heights.cols as u32, heights.rows as u32) != self.grid {
            return Err(GpuError::Validation(format!(
                "caustic-triangles water heights: a {} x {} grid for a {} x {} frame",
                heights.cols, heights.rows, self.grid.0, self.grid.1
            )));
        }
        ctx.write_grid(texture, heights);
        Ok(())
    }

    /// Whether `ws` fits this frame's buffers and bind groups (the same lattice, map size and
    /// wrap), so that [`set_setup`](Self::set_setup) can take it.
    pub fn fits(&self, ws: &WaterSetup) -> bool {
        let f = &self.setup.setup.floor;
        (
            ws.lattice,
            ws.setup.floor.width,
            ws.setup.floor.height,
            ws.setup.merge_levels,
            ws.wrap(),
        ) == (
            self.setup.lattice,
            f.width,
            f.height,
            self.setup.setup.merge_levels,
            self.setup.wrap(),
        )
    }

    /// Take a new sun, water depth, index or parameters (a setup that [`fits`](Self::fits)): two
    /// uniform writes, none when nothing changed.
    pub fn set_setup(&mut self, ctx: &GpuContext, ws: &WaterSetup) {
        debug_assert!(self.fits(ws));
        let old_ct = CausticTrianglesUniform::new(&self.frame.setup, &no_distance_map());
        let old_w = WaterPhotonUniform::new(&self.setup);
        let ct = CausticTrianglesUniform::new(&ws.setup, &no_distance_map());
        let w = WaterPhotonUniform::new(ws);
        if bytemuck::bytes_of(&ct) != bytemuck::bytes_of(&old_ct) {
            ctx.write_buffer(&self.frame.uniform, 0, bytemuck::bytes_of(&ct));
        }
        if bytemuck::bytes_of(&w) != bytemuck::bytes_of(&old_w) {
            ctx.write_buffer(&self.water_uniform, 0, bytemuck::bytes_of(&w));
        }
        if let Some(walls) = &mut self.walls {
            for (wall, wf) in Wall::ALL.into_iter().zip(&mut walls.walls) {
                let setup = ws.receiver_setup(Some(wall), &walls.layout);
                let old_ct = CausticTrianglesUniform::new(&wf.frame.setup, &no_distance_map());
                let ct = CausticTrianglesUniform::new(&setup, &no_distance_map());
                if bytemuck::bytes_of(&ct) != bytemuck::bytes_of(&old_ct) {
                    ctx.write_buffer(&wf.frame.uniform, 0, bytemuck::bytes_of(&ct));
                }
                let old_w = WaterPhotonUniform::for_receiver(&self.setup, Some(wall));
                let w = WaterPhotonUniform::for_receiver(ws, Some(wall));
                if bytemuck::bytes_of(&w) != bytemuck::bytes_of(&old_w) {
                    ctx.write_buffer(&wf.water_uniform, 0, bytemuck::bytes_of(&w));
                }
                wf.frame.setup = setup;
            }
        }
        self.setup = ws.clone();
        self.frame.setup = ws.setup.clone();
    }

    pub fn bytes(&self) -> u64 {
        self.frame.bytes()
            + self
                .heights
                .as_ref()
                .map_or(0, |_| (self.grid.0 * self.grid.1) as u64 * 4)
            + 48
            + self.walls.as_ref().map_or(0, |w| {
                let t = &w.texture;
                let texel = t.format().block_copy_size(None).unwrap_or(16) as u64;
                w.walls.iter().map(|f| f.frame.bytes() + 48).sum::<u64>()
                    + (t.width() * t.height() * 4) as u64 * texel
            })
    }
}

/// A water frame's distance map, unused: one texel fills its binding.
fn no_distance_map() -> DistanceMap {
    DistanceMap {
        resolution: 1,
        layers: 1,
        centre: glam::DVec3::ZERO,
        radius: 0.0,
        texels: vec![[0.0; 4]],
    }
}

/// What one water run reads back.
pub struct WaterGpuOutput {
    pub photons: Vec<[f32; 4]>,
    pub paths: Vec<f32>,
    pub irradiance: Vec<f32>,
    pub map: CausticsMap,
    /// The wall maps when the setup has walls.
    pub walls: Option<WallMaps>,
}

impl CausticTriangles {
    /// A water frame that uploads `heights` itself (rewrite them with
    /// [`WaterFrame::update_heights`]).
    pub fn water_frame(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &Grid,
    ) -> Result<WaterFrame, GpuError> {
        let texture = ctx.upload_grid("caustic-triangles water heights", heights)?;
        let mut wf = self.water_frame_with_water(ctx, ws, &WaterTextures::of(&texture))?;
        wf.heights = Some(texture);
        Ok(wf)
    }

    /// A water frame reading the caller's heights (any grid size: the passes sample it
    /// bicubically, as the CPU twin samples its grid). The band of `ws` is kept as an upper bound
    /// the GPU's fit narrows (a fresh [`WaterSetup`] has every quad).
    pub fn water_frame_with_water(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        water: &WaterTextures,
    ) -> Result<WaterFrame, GpuError> {
        let mut frame = self.frame(ctx, &ws.setup, &no_distance_map())?;
        let water_uniform = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("caustic-triangles water photons"),
            contents: bytemuck::bytes_of(&WaterPhotonUniform::new(ws)),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        });
        let view = wgpu::BindingResource::TextureView(&water.heights);
        let water_bind = bind_group(
            ctx,
            "caustic-triangles water photons",
            &self.water_photon.get_bind_group_layout(0),
            &[
                water_uniform.as_entire_binding(),
                view.clone(),
                frame.photons.as_entire_binding(),
                frame.paths.as_entire_binding(),
            ],
        );
        let band_bind = ws.wrap().then(|| {
            let bound = ctx.create_buffer(&wgpu::BufferDescriptor {
                label: Some(BAND_BOUND.name),
                size: 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bound_bind = bind_group(
                ctx,
                BAND_BOUND.name,
                &self.band_bound.get_bind_group_layout(0),
                &[
                    water_uniform.as_entire_binding(),
                    view.clone(),
                    bound.as_entire_binding(),
                ],
            );
            let band = bind_group(
                ctx,
                COPY_BAND.name,
                &self.copy_band.get_bind_group_layout(0),
                &[
                    water_uniform.as_entire_binding(),
                    frame.uniform.as_entire_binding(),
                    bound.as_entire_binding(),
                    frame.copy_band.as_entire_binding(),
                ],
            );
            BandPasses {
                bound,
                bound_bind,
                band,
                grid: (water.cols, water.rows),
            }
        });
        frame.gpu_band = band_bind.is_some();
        let walls = if ws.walls {
            Some(self.wall_frames(ctx, ws, &view)?)
        } else {
            None
        };
        ctx.check()?;
        Ok(WaterFrame {
            frame,
            setup: ws.clone(),
            heights: None,
            grid: (water.cols, water.rows),
            water_uniform,
            water_bind,
            band_bind,
            walls,
        })
    }

    /// The walls' receivers of a water frame with walls, reading the heights through `heights`.
    fn wall_frames(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &wgpu::BindingResource,
    ) -> Result<WallFrames, GpuError> {
        let f = &ws.setup.floor;
        let layout = WallMaps::for_floor_map(f.width, f.height, ws.size, ws.depth);
        let cols = layout.maps.iter().map(|m| m.cols).max().unwrap_or(1) as u32;
        let rows = layout.maps[0].rows as u32;
        ctx.check_texture_size("caustic-triangles wall maps", cols, rows)?;
        let texture = ctx.texture_2d(
            "caustic-triangles wall maps",
            (cols, rows, 4),
            self.map_format,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let mut walls = Vec::with_capacity(4);
        for wall in Wall::ALL {
            let setup = ws.receiver_setup(Some(wall), &layout);
            let frame = self.frame_into_layer(
                ctx,
                &setup,
                &no_distance_map(),
                Some((&texture, wall.index() as u32)),
            )?;
            let water_uniform = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("caustic-triangles wall photons"),
                contents: bytemuck::bytes_of(&WaterPhotonUniform::for_receiver(ws, Some(wall))),
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            });
            let water_bind = bind_group(
                ctx,
                "caustic-triangles wall photons",
                &self.water_photon.get_bind_group_layout(0),
                &[
                    water_uniform.as_entire_binding(),
                    heights.clone(),
                    frame.photons.as_entire_binding(),
                    frame.paths.as_entire_binding(),
                ],
            );
            walls.push(WallFrame {
                frame,
                water_uniform,
                water_bind,
            });
        }
        Ok(WallFrames {
            texture,
            layout,
            walls,
        })
    }

    /// Read a water frame's wall maps back (`None` without walls).
    pub fn read_walls(
        &self,
        ctx: &GpuContext,
        wf: &WaterFrame,
    ) -> Result<Option<WallMaps>, GpuError> {
        let Some(walls) = &wf.walls else {
            return Ok(None);
        };
        let mut maps = walls.layout.clone();
        crate::technique::WallsOutput::of(&walls.texture, &walls.layout).read(ctx, &mut maps)?;
        Ok(Some(maps))
    }

    /// Record the water photon pass, then the reconstruction into the floor map (cleared first).
    pub fn encode_water(
        &self,
        wf: &WaterFrame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        reconstruction: Reconstruction,
    ) {
        let p = wf.frame.setup.p as u32;
        {
            let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles water photons");
            pass.set_pipeline(&self.water_photon);
            pass.set_bind_group(0, &wf.water_bind, &[]);
            pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
        }
        if let Some(b) = &wf.band_bind {
            encoder.clear_buffer(&b.bound, 0, None);
            {
                let mut pass = begin_compute(encoder, &mut timer, BAND_BOUND.name);
                pass.set_pipeline(&self.band_bound);
                pass.set_bind_group(0, &b.bound_bind, &[]);
                pass.dispatch_workgroups(b.grid.0.div_ceil(16), b.grid.1.div_ceil(16), 1);
            }
            let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles copy band");
            pass.set_pipeline(&self.copy_band);
            pass.set_bind_group(0, &b.band, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        self.encode_reconstruction(&wf.frame, encoder, timer.as_deref_mut(), reconstruction);
        for wall in wf.walls.iter().flat_map(|w| &w.walls) {
            {
                let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles wall photons");
                pass.set_pipeline(&self.water_photon);
                pass.set_bind_group(0, &wall.water_bind, &[]);
                pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
            }
            self.encode_reconstruction(&wall.frame, encoder, timer.as_deref_mut(), reconstruction);
        }
    }

    /// The water generator once, its floor map read back (the Runner's frame).
    pub fn water_caustics(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &Grid,
        timer: Option<&mut GpuTimer>,
    ) -> Result<CausticsMap, GpuError> {
        Ok(self.water_caustics_walls(ctx, ws, heights, timer)?.0)
    }

    /// [`water_caustics`](Self::water_caustics) with the wall maps when `ws` has walls.
    pub fn water_caustics_walls(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &Grid,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<(CausticsMap, Option<WallMaps>), GpuError> {
        let wf = self.water_frame(ctx, ws, heights)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_water(
            &wf,
            &mut encoder,
            timer.as_deref_mut(),
            Reconstruction::Triangles,
        );
        if let Some(t) = timer {
            t.resolve(&mut encoder);
        }
        ctx.queue.submit([encoder.finish()]);
        let map = self.read_map(ctx, &wf.frame)?;
        let walls = self.read_walls(ctx, &wf)?;
        ctx.check()?;
        Ok((map, walls))
    }

    /// The water generator once, everything read back.
    pub fn run_water(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &Grid,
        reconstruction: Reconstruction,
    ) -> Result<WaterGpuOutput, GpuError> {
        let wf = self.water_frame(ctx, ws, heights)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_water(&wf, &mut encoder, None, reconstruction);
        ctx.queue.submit([encoder.finish()]);
        let map = self.read_map(ctx, &wf.frame)?;
        Ok(WaterGpuOutput {
            photons: ctx.read_buffer(&wf.frame.photons)?,
            paths: ctx.read_buffer(&wf.frame.paths)?,
            irradiance: ctx.read_buffer(&wf.frame.irradiance)?,
            map,
            walls: self.read_walls(ctx, &wf)?,
        })
    }
}

/// The light cube map of a point light on the GPU (paper 4, §4.2-4.3; CPU twin
/// `caustics_core::techniques::caustic_triangles::cube`): the six `C x C` faces stacked in one
/// `C x 6C` texture (face `f` in rows `f C .. (f + 1) C`, one viewport and scissor per face), `(Σ E,
/// Σ E d)` in red and green, and the shadow distances in a storage buffer. Every generator adds
/// into the same target.
pub struct LightCubeTarget {
    pub resolution: u32,
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    pub shadow: wgpu::Buffer,
}

/// One generator's bindings to a [`LightCubeTarget`].
pub struct CubeBinds {
    cube: wgpu::BindGroup,
    shadow: wgpu::BindGroup,
}

impl CausticTriangles {
    pub fn light_cube(
        &self,
        ctx: &GpuContext,
        resolution: u32,
    ) -> Result<LightCubeTarget, GpuError> {
        ctx.check_texture_size(
            "caustic-triangles light cube map",
            resolution,
            6 * resolution,
        )?;
        let n = 6 * resolution as u64 * resolution as u64;
        ctx.check_buffer_size("caustic-triangles light cube shadow distances", n * 4)?;
        let texture = ctx.texture_2d(
            "caustic-triangles light cube map",
            (resolution, 6 * resolution, 1),
            self.map_format,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let view = texture.create_view(&Default::default());
        let shadow = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("caustic-triangles light cube shadow distances"),
            size: n * 4,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        ctx.check()?;
        Ok(LightCubeTarget {
            resolution,
            texture,
            view,
            shadow,
        })
    }

    pub fn cube_binds(
        &self,
        ctx: &GpuContext,
        frame: &Frame,
        target: &LightCubeTarget,
    ) -> CubeBinds {
        let cube = bind_group(
            ctx,
            "caustic-triangles light cube map",
            &self.cube.get_bind_group_layout(0),
            &[
                frame.uniform.as_entire_binding(),
                frame.photons.as_entire_binding(),
                frame.irradiance.as_entire_binding(),
                frame.pyramid.as_entire_binding(),
            ],
        );
        let shadow = bind_group(
            ctx,
            "caustic-triangles light cube shadow distances",
            &self.shadow.get_bind_group_layout(0),
            &[
                frame.uniform.as_entire_binding(),
                frame.dm_buffer.as_entire_binding(),
                target.shadow.as_entire_binding(),
            ],
        );
        CubeBinds { cube, shadow }
    }

    /// Reset the shadow distances to "no surface" before the first generator's
    /// [`encode_cube`](Self::encode_cube) (a queue write: it lands before the next submission).
    pub fn reset_cube(&self, ctx: &GpuContext, target: &LightCubeTarget) {
        let n = 6 * target.resolution as usize * target.resolution as usize;
        ctx.write_buffer(&target.shadow, 0, bytemuck::cast_slice(&vec![FAR; n]));
    }

    /// Record one generator's reconstruction into the light cube map (§4.2): the vertex irradiance
    /// pass, its caustic triangles drawn into each face (cleared first when `clear`), and its
    /// surfaces into the shadow distances. The photon image must be in `frame.photons`.
    pub fn encode_cube(
        &self,
        frame: &Frame,
        binds: &CubeBinds,
        target: &LightCubeTarget,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
        clear: bool,
    ) {
        let p = frame.setup.p as u32;
        let c = target.resolution;
        self.encode_irradiance(frame, encoder, timer.as_deref_mut());
        {
            let label = "caustic-triangles light cube map";
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target.view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: if clear {
                            wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                        } else {
                            wgpu::LoadOp::Load
                        },
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: timer.as_mut().and_then(|t| t.render_pass(label)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.cube);
            pass.set_bind_group(0, &binds.cube, &[]);
            for face in 0..6 {
                pass.set_viewport(0.0, (face * c) as f32, c as f32, c as f32, 0.0, 1.0);
                pass.set_scissor_rect(0, face * c, c, c);
                pass.draw(0..6 * (p - 1) * (p - 1), face..face + 1);
            }
        }
        let mut pass = begin_compute(encoder, &mut timer, "caustic-triangles shadow distances");
        pass.set_pipeline(&self.shadow);
        pass.set_bind_group(0, &binds.shadow, &[]);
        pass.dispatch_workgroups(c.div_ceil(8), (6 * c).div_ceil(8), 1);
    }

    /// Read a light cube map back as the CPU twin's [`LightCube`].
    pub fn read_cube(
        &self,
        ctx: &GpuContext,
        target: &LightCubeTarget,
        position: glam::DVec3,
    ) -> Result<LightCube, GpuError> {
        let texels = ctx.read_rgba_f32(&target.texture)?;
        Ok(LightCube {
            resolution: target.resolution as usize,
            position,
            caustic: texels.into_iter().map(|t| [t[0], t[1]]).collect(),
            shadow: ctx.read_buffer(&target.shadow)?,
        })
    }
}
