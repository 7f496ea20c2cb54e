//! Technique `volumes` on the GPU: caustics on underwater objects from illumination volumes, colour
//! and depth textures and reference planes (paper 3). The method, its units and where it departs
//! from the reference are documented with its CPU twin, `caustics_core::techniques::volumes`, which
//! these passes mirror one for one:
//!
//! | pass | WGSL | CPU twin |
//! |---|---|---|
//! | depth texture / shadow map (compute, BVH rays) | `volumes/depth.wgsl` + `bvh.wgsl` | `representation::depth_pass` |
//! | water (compute) | `volumes/water.wgsl` | `illumination::water_pass` |
//! | illumination volumes × reference planes (raster, additive) | `volumes/slices.wgsl` | `illumination::slice_pass` |
//! | floor map (raster, additive) | `volumes/floor.wgsl` | `illumination::floor_pass` |
//! | walls' maps, with walls (raster, additive, one layer per wall) | `volumes/walls.wgsl` | `illumination::wall_pass` |
//! | diffuse map and Eq. 4 (compute) | `volumes/shade.wgsl` | `diffuse_map`, `shade_pass` |
//! | refracted view, §3.3 (compute) | `volumes/view.wgsl` | `view::view_pass` |
//!
//! The slices are rasterised with additive blending, as the paper draws them: one triangle per
//! (reference plane, water triangle), pulled from the water buffer by the vertex shader, the depth
//! test of §3.1 in the fragment shader. The caustics maps are `Rgba32Float` where the adapter has
//! `FLOAT32_BLENDABLE`, otherwise `Rgba16Float` (blendable everywhere, about 3 significant digits).
//! The depth textures are cast as one BVH ray per texel (the same trees the CPU walks) rather than
//! rasterised: the same nearest surface at the same texel centres, and the CPU twin can follow it
//! exactly.

use caustics_core::grid::Grid;
use caustics_core::map::CausticsMap;
use caustics_core::techniques::volumes::illumination::WaterVertex;
use caustics_core::techniques::volumes::view::ViewCamera;
use caustics_core::techniques::volumes::{ObjectMaps, OrthoView, VolumesInput, VolumesSetup};

use crate::bvh::{FlatBvhs, GpuBvhNode, GpuBvhTriangle};
use crate::pass::{additive_pipeline, begin_compute, bind_group, compute_pipeline};
use crate::shaders::{BVH, OPTICS, PassSource, WATER};
use crate::technique::WallsOutput;
use crate::{GpuContext, GpuError, GpuTimer, WaterTextures};
use caustics_core::walls::{Wall, WallMaps};

pub mod technique;

const COMMON: &str = include_str!("common.wgsl");

pub const DEPTH: PassSource = PassSource {
    name: "volumes depth",
    shared: &[COMMON, BVH],
    file: "volumes/depth.wgsl",
    source: include_str!("depth.wgsl"),
};
pub const WATER_PASS: PassSource = PassSource {
    name: "volumes water",
    shared: &[OPTICS, WATER, COMMON],
    file: "volumes/water.wgsl",
    source: include_str!("water.wgsl"),
};
pub const SLICES: PassSource = PassSource {
    name: "volumes slices",
    shared: &[COMMON],
    file: "volumes/slices.wgsl",
    source: include_str!("slices.wgsl"),
};
pub const FLOOR: PassSource = PassSource {
    name: "volumes floor",
    shared: &[COMMON],
    file: "volumes/floor.wgsl",
    source: include_str!("floor.wgsl"),
};
pub const WALLS: PassSource = PassSource {
    name: "volumes walls",
    shared: &[COMMON],
    file: "volumes/walls.wgsl",
    source: include_str!("walls.wgsl"),
};
pub const VIEW: PassSource = PassSource {
    name: "volumes view",
    shared: &[OPTICS, WATER, COMMON],
    file: "volumes/view.wgsl",
    source: include_str!("view.wgsl"),
};
pub const SHADE: PassSource = PassSource {
    name: "volumes shade",
    shared: &[COMMON],
    file: "volumes/shade.wgsl",
    source: include_str!("shade.wgsl"),
};

/// Every pass of the technique, for its registry entry.
pub const PASSES: &[&PassSource] = &[&DEPTH, &WATER_PASS, &SLICES, &FLOOR, &WALLS, &VIEW, &SHADE];

/// Mirrors `View` in `volumes/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewUniform {
    pub a: [f32; 4],
    pub b: [f32; 4],
    pub v: [f32; 4],
    pub lo: [f32; 4],
    pub texel: [f32; 4],
}

impl ViewUniform {
    /// `spacing`: the reference planes' `Δ` (0 for the shadow map).
    pub fn new(view: &OrthoView, spacing: f64) -> Self {
        let e = view.extent();
        let t = view.texel();
        let margin = caustics_core::techniques::volumes::representation::ray_margin(view);
        ViewUniform {
            a: [
                view.a.x as f32,
                view.a.y as f32,
                view.a.z as f32,
                view.res as f32,
            ],
            b: [
                view.b.x as f32,
                view.b.y as f32,
                view.b.z as f32,
                margin as f32,
            ],
            v: [
                view.v.x as f32,
                view.v.y as f32,
                view.v.z as f32,
                spacing as f32,
            ],
            lo: [view.lo.x as f32, view.lo.y as f32, view.lo.z as f32, 0.0],
            texel: [t.x as f32, t.y as f32, e.z as f32, 0.0],
        }
    }
}

/// Mirrors `Volumes` in `volumes/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumesUniform {
    pub light: [f32; 4],
    pub absorption: [f32; 4],
    pub lattice: [f32; 4],
    pub params: [f32; 4],
    pub dims: [u32; 4],
    pub flags: [u32; 4],
    pub shadow: ViewUniform,
}

impl VolumesUniform {
    pub fn new(s: &VolumesSetup, wrap: bool) -> Self {
        VolumesUniform {
            light: [
                s.light.x as f32,
                s.light.y as f32,
                s.light.z as f32,
                s.eta as f32,
            ],
            absorption: [
                s.absorption.x as f32,
                s.absorption.y as f32,
                s.absorption.z as f32,
                s.t_flat as f32,
            ],
            lattice: [
                s.lattice.origin.x as f32,
                s.lattice.origin.y as f32,
                s.lattice.cell as f32,
                s.size as f32,
            ],
            params: [
                s.depth as f32,
                s.ior as f32,
                s.shadow_bias as f32,
                if s.params.fresnel { 1.0 } else { 0.0 },
            ],
            dims: [
                s.lattice.nx as u32,
                s.lattice.ny as u32,
                s.width as u32,
                s.height as u32,
            ],
            flags: [
                wrap as u32,
                s.shadow.is_some() as u32,
                s.walls as u32,
                s.wall_layout().map_or(0, |w| w.maps[0].rows as u32),
            ],
            shadow: s
                .shadow
                .as_ref()
                .map_or_else(ViewUniform::default, |v| ViewUniform::new(v, 0.0)),
        }
    }
}

/// Mirrors `Pass` in `volumes/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PassUniform {
    pub view: ViewUniform,
    pub cells: [u32; 4],
    pub planes: u32,
    pub root_first: u32,
    pub root_count: u32,
    pub _pad: u32,
    pub albedo: [f32; 4],
}

impl PassUniform {
    /// Object `k`'s depth, slice and shade passes: its view, reference planes and lattice cells.
    pub fn object(setup: &VolumesSetup, k: usize) -> Self {
        let o = &setup.objects[k];
        let c = o.cells;
        PassUniform {
            view: ViewUniform::new(&o.view, o.spacing()),
            cells: [c.i0 as u32, c.i1 as u32, c.j0 as u32, c.j1 as u32],
            planes: o.planes as u32,
            root_first: k as u32,
            root_count: 1,
            _pad: 0,
            albedo: [
                o.albedo.x as f32,
                o.albedo.y as f32,
                o.albedo.z as f32,
                setup.params.ambient as f32,
            ],
        }
    }

    /// The shadow map's depth pass: every object's tree along the refracted sun.
    pub fn shadow(view: &OrthoView, objects: usize) -> Self {
        PassUniform {
            view: ViewUniform::new(view, 0.0),
            root_first: 0,
            root_count: objects as u32,
            ..Default::default()
        }
    }
}

/// Mirrors `Camera` in `volumes/view.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CameraUniform {
    pub position: [f32; 4],
    pub forward: [f32; 4],
    pub right: [f32; 4],
    pub up: [f32; 4],
    pub floor_albedo: [f32; 4],
}

/// The refracted view (§3.3) to render with the caustics: the camera and the floor's albedo.
#[derive(Clone, Copy, Debug)]
pub struct ViewOptions {
    pub camera: ViewCamera,
    pub floor_albedo: glam::DVec3,
}

impl CameraUniform {
    pub fn new(v: &ViewOptions, setup: &VolumesSetup) -> Self {
        let c = &v.camera;
        let f = |a: glam::DVec3, w: f64| [a.x as f32, a.y as f32, a.z as f32, w as f32];
        CameraUniform {
            position: f(c.position, setup.params.ambient),
            forward: f(c.forward, setup.objects.len() as f64),
            right: f(c.right, c.width as f64),
            up: f(c.up, c.height as f64),
            floor_albedo: f(v.floor_albedo, 1.0),
        }
    }
}

/// The technique's pipelines, built once per device for one caustics-map format.
pub struct Volumes {
    depth: wgpu::ComputePipeline,
    water: wgpu::ComputePipeline,
    slices: wgpu::RenderPipeline,
    floor: wgpu::RenderPipeline,
    walls: wgpu::RenderPipeline,
    shade: wgpu::ComputePipeline,
    view: wgpu::ComputePipeline,
    /// `Rgba32Float` with `FLOAT32_BLENDABLE`, else `Rgba16Float`.
    pub map_format: wgpu::TextureFormat,
}

struct ObjectFrame {
    /// The object's layer of the frame's depth-texture and image arrays.
    layer: u32,
    /// Its [`PassUniform`].
    uniform: wgpu::Buffer,
    caustics: wgpu::Texture,
    caustics_view: wgpu::TextureView,
    diffuse: wgpu::Texture,
    depth_bind: wgpu::BindGroup,
    slices_bind: wgpu::BindGroup,
    shade_bind: wgpu::BindGroup,
    vertices: u32,
    res: u32,
}

/// One scene's resources: the BVH buffers, textures per object, the water buffer, the floor map and
/// every bind group. Built once; encode it every frame (upload new heights with
/// [`Frame::update_heights`]).
pub struct Frame {
    pub setup: VolumesSetup,
    /// The heights it uploaded itself ([`Volumes::frame`]); `None` when it reads the caller's
    /// ([`Volumes::frame_with_water`]).
    heights: Option<wgpu::Texture>,
    wrap: bool,
    /// The [`VolumesUniform`] every pass reads.
    uniform: wgpu::Buffer,
    pub water: wgpu::Buffer,
    /// The shadow map, its depth pass's bind group and [`PassUniform`].
    shadow: Option<(wgpu::Texture, wgpu::BindGroup, wgpu::Buffer)>,
    objects: Vec<ObjectFrame>,
    bvh_bind: wgpu::BindGroup,
    water_bind: wgpu::BindGroup,
    floor_bind: wgpu::BindGroup,
    pub floor: wgpu::Texture,
    floor_view: wgpu::TextureView,
    /// The walls' maps when the setup has walls.
    pub walls: Option<WallsFrame>,
    /// Every object's depth texture and final image (Eq. 4), one layer each.
    depths: wgpu::Texture,
    images: wgpu::Texture,
    /// The refracted view's image, bind group and its copy of every object's [`PassUniform`], when
    /// one was asked for.
    view: Option<(wgpu::Texture, wgpu::BindGroup, wgpu::Buffer)>,
    bytes: u64,
}

impl Frame {
    /// GPU memory the frame's buffers and textures take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Replace the height field (same size) for the next encode, in a frame that uploaded its own.
    pub fn update_heights(&self, ctx: &GpuContext, heights: &Grid) {
        if let Some(t) = &self.heights {
            ctx.write_grid(t, heights);
        }
    }

    /// Whether `setup` fits this frame's buffers, textures and bind groups (the same parameters,
    /// map, lattice size and objects), so that [`set_setup`](Self::set_setup) can take it. A new
    /// sun moves the lattice, the shadow map's frame and each object's cells; a new camera turns
    /// each object's view: none of that changes a size.
    pub fn fits(&self, setup: &VolumesSetup) -> bool {
        let s = &self.setup;
        setup.params == s.params
            && setup.walls == s.walls
            && (setup.width, setup.height) == (s.width, s.height)
            && (setup.lattice.nx, setup.lattice.ny) == (s.lattice.nx, s.lattice.ny)
            && setup.shadow.as_ref().map(|v| v.res) == s.shadow.as_ref().map(|v| v.res)
            && setup.objects.len() == s.objects.len()
            && setup
                .objects
                .iter()
                .zip(&s.objects)
                .all(|(a, b)| a.view.res == b.view.res && slice_vertices(a).is_some())
    }

    /// Take a new sun or camera (a setup that [`fits`](Self::fits)): uniform writes only, and each
    /// object's slice draw resized to its new cells.
    pub fn set_setup(&mut self, ctx: &GpuContext, setup: &VolumesSetup) {
        debug_assert!(self.fits(setup));
        ctx.write_buffer(
            &self.uniform,
            0,
            bytemuck::bytes_of(&VolumesUniform::new(setup, self.wrap)),
        );
        if let (Some((_, _, buffer)), Some(view)) = (&self.shadow, &setup.shadow) {
            let u = PassUniform::shadow(view, setup.objects.len());
            ctx.write_buffer(buffer, 0, bytemuck::bytes_of(&u));
        }
        let uniforms: Vec<PassUniform> = (0..setup.objects.len())
            .map(|k| PassUniform::object(setup, k))
            .collect();
        for ((o, u), view) in self.objects.iter_mut().zip(&uniforms).zip(&setup.objects) {
            ctx.write_buffer(&o.uniform, 0, bytemuck::bytes_of(u));
            o.vertices = slice_vertices(view).expect("fits checked the count");
        }
        if let Some((_, _, buffer)) = &self.view
            && !uniforms.is_empty()
        {
            ctx.write_buffer(buffer, 0, bytemuck::cast_slice(&uniforms));
        }
        self.setup = setup.clone();
    }

    /// Triangles the slice pass draws per frame (all objects, all planes).
    pub fn slice_triangles(&self) -> u64 {
        self.objects.iter().map(|o| o.vertices as u64 / 3).sum()
    }
}

/// The pool's walls as receivers of a frame (CPU twin `illumination::wall_pass`): one
/// layer per wall of a 2-D array texture in `Wall::ALL`'s order, as wide as the widest wall map
/// and as tall as the maps ([`crate::technique::Technique::walls`]'s layout), made once.
pub struct WallsFrame {
    pub texture: wgpu::Texture,
    /// Empty maps: the walls' sizes.
    pub layout: WallMaps,
    layers: Vec<wgpu::TextureView>,
    bind: wgpu::BindGroup,
}

impl WallsFrame {
    /// The final image's view of the maps.
    pub fn output(&self) -> WallsOutput<'_> {
        WallsOutput::of(&self.texture, &self.layout)
    }
}

/// Vertices of an object's slice draw (one triangle per reference plane and lattice triangle of its
/// cells), `None` beyond what one draw can take.
fn slice_vertices(o: &caustics_core::techniques::volumes::ObjectView) -> Option<u32> {
    u32::try_from(o.cells.triangles() as u64 * o.planes as u64 * 3).ok()
}

/// What one GPU run reads back.
pub struct GpuOutput {
    pub objects: Vec<ObjectMaps>,
    pub floor: CausticsMap,
    /// The walls' maps, `None` without walls.
    pub walls: Option<WallMaps>,
    pub shadow: Vec<[f32; 4]>,
    pub water: Vec<WaterVertex>,
    /// The refracted view, row 0 at the top (empty without one).
    pub view: Vec<[f32; 3]>,
}

impl Volumes {
    /// Pipelines for the best caustics-map format this device blends.
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

    /// Pipelines for a given caustics-map format (`Rgba32Float` needs `FLOAT32_BLENDABLE`).
    pub fn with_format(
        ctx: &GpuContext,
        map_format: wgpu::TextureFormat,
    ) -> Result<Self, GpuError> {
        let v = Volumes {
            depth: compute_pipeline(ctx, &DEPTH),
            water: compute_pipeline(ctx, &WATER_PASS),
            slices: additive_pipeline(ctx, &SLICES, map_format),
            floor: additive_pipeline(ctx, &FLOOR, map_format),
            walls: additive_pipeline(ctx, &WALLS, map_format),
            shade: compute_pipeline(ctx, &SHADE),
            view: compute_pipeline(ctx, &VIEW),
            map_format,
        };
        ctx.check()?;
        Ok(v)
    }

    /// Allocate a frame for `setup` (built from `input`), with the refracted view when `view` is
    /// given, and upload the meshes and the heights.
    pub fn frame(
        &self,
        ctx: &GpuContext,
        setup: &VolumesSetup,
        input: &VolumesInput,
        heights: &Grid,
        wrap: bool,
        view: Option<&ViewOptions>,
    ) -> Result<Frame, GpuError> {
        let texture = ctx.upload_grid("volumes height field", heights)?;
        let mut frame =
            self.frame_with_water(ctx, setup, input, &WaterTextures::of(&texture), wrap, view)?;
        frame.bytes += (heights.cols * heights.rows) as u64 * 4;
        frame.heights = Some(texture);
        Ok(frame)
    }

    /// Allocate a frame for `setup` (built from `input`) that reads the caller's heights (any grid
    /// size: the water pass samples it bicubically, as the CPU twin samples its grid), and upload
    /// the meshes' trees.
    pub fn frame_with_water(
        &self,
        ctx: &GpuContext,
        setup: &VolumesSetup,
        input: &VolumesInput,
        heights: &WaterTextures,
        wrap: bool,
        view: Option<&ViewOptions>,
    ) -> Result<Frame, GpuError> {
        use wgpu::BindingResource::TextureView as View;
        use wgpu::BufferUsages as B;
        use wgpu::TextureUsages as U;
        let (w, h) = (setup.width as u32, setup.height as u32);
        ctx.check_texture_size("volumes floor map", w, h)?;
        let FlatBvhs {
            mut nodes,
            mut triangles,
            roots,
        } = FlatBvhs::of(input.objects.iter().map(|o| &o.mesh));
        // Bindings may not be empty: a scene without objects binds one unused node and slot.
        if nodes.is_empty() {
            nodes.push(GpuBvhNode::default());
            triangles.push(GpuBvhTriangle::default());
        }
        let storage = |label: &str, bytes: &[u8]| {
            ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: B::STORAGE,
            })
        };
        ctx.check_buffer_size("volumes BVH triangles", triangles.len() as u64 * 96)?;
        let node_buf = storage("volumes BVH nodes", bytemuck::cast_slice(&nodes));
        let tri_buf = storage("volumes BVH triangles", bytemuck::cast_slice(&triangles));
        let mut root_list: Vec<u32> = roots.clone();
        root_list.push(0);
        let root_buf = storage("volumes roots", bytemuck::cast_slice(&root_list));
        let mut bytes = node_buf.size() + tri_buf.size() + root_buf.size();
        let bvh_bind = bind_group(
            ctx,
            "volumes BVH",
            &self.depth.get_bind_group_layout(1),
            &[node_buf.as_entire_binding(), tri_buf.as_entire_binding()],
        );
        let uniform = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("volumes uniform"),
            contents: bytemuck::bytes_of(&VolumesUniform::new(setup, wrap)),
            usage: B::UNIFORM | B::COPY_DST,
        });
        let pass_uniform = |p: PassUniform| {
            ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("volumes pass uniform"),
                contents: bytemuck::bytes_of(&p),
                usage: B::UNIFORM | B::COPY_DST,
            })
        };
        let depth_texture = |label: &str, res: u32| -> Result<wgpu::Texture, GpuError> {
            ctx.check_texture_size(label, res, res)?;
            Ok(ctx.texture_2d(
                label,
                (res, res, 1),
                wgpu::TextureFormat::Rgba32Float,
                U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC,
            ))
        };
        // The shadow map, or a 1 x 1 stand-in the shaders never read (flags.y = 0).
        let (shadow_tex, shadow) = match &setup.shadow {
            Some(view) => {
                let res = view.res as u32;
                let tex = depth_texture("volumes shadow map", res)?;
                let u = pass_uniform(PassUniform::shadow(view, roots.len()));
                let bind = bind_group(
                    ctx,
                    "volumes shadow map",
                    &self.depth.get_bind_group_layout(0),
                    &[
                        u.as_entire_binding(),
                        root_buf.as_entire_binding(),
                        View(&tex.create_view(&Default::default())),
                    ],
                );
                bytes += (res * res) as u64 * 16;
                (tex.clone(), Some((tex, bind, u)))
            }
            None => (depth_texture("volumes shadow stand-in", 1)?, None),
        };
        let shadow_view = shadow_tex.create_view(&Default::default());

        let lattice_vertices = setup.lattice.vertex_count() as u64;
        ctx.check_buffer_size("volumes water vertices", lattice_vertices * 32)?;
        let water = ctx.create_buffer(&wgpu::BufferDescriptor {
            label: Some("volumes water"),
            size: lattice_vertices * 32,
            usage: B::STORAGE | B::COPY_SRC,
            mapped_at_creation: false,
        });
        bytes += water.size();
        let water_bind = bind_group(
            ctx,
            "volumes water",
            &self.water.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                View(&heights.heights),
                water.as_entire_binding(),
            ],
        );
        let map_texture = |label: &str, w: u32, h: u32| {
            ctx.texture_2d(
                label,
                (w, h, 1),
                self.map_format,
                U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
            )
        };
        let texel_bytes = if self.map_format == wgpu::TextureFormat::Rgba16Float {
            8
        } else {
            16
        };
        let floor = map_texture("volumes floor map", w, h);
        bytes += (w * h) as u64 * texel_bytes;
        let floor_bind = bind_group(
            ctx,
            "volumes floor",
            &self.floor.get_bind_group_layout(0),
            &[
                uniform.as_entire_binding(),
                water.as_entire_binding(),
                View(&shadow_view),
            ],
        );

        let walls = match setup.wall_layout() {
            None => None,
            Some(layout) => {
                let cols = layout.maps.iter().map(|m| m.cols).max().unwrap_or(1) as u32;
                let rows = layout.maps[0].rows as u32;
                ctx.check_texture_size("volumes wall maps", cols, rows)?;
                let texture = ctx.texture_2d(
                    "volumes wall maps",
                    (cols, rows, 4),
                    self.map_format,
                    U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC,
                );
                bytes += (cols * rows * 4) as u64 * texel_bytes;
                let layers = (0..4)
                    .map(|k| {
                        texture.create_view(&wgpu::TextureViewDescriptor {
                            dimension: Some(wgpu::TextureViewDimension::D2),
                            base_array_layer: k,
                            array_layer_count: Some(1),
                            ..Default::default()
                        })
                    })
                    .collect();
                let bind = bind_group(
                    ctx,
                    "volumes walls",
                    &self.walls.get_bind_group_layout(0),
                    &[
                        uniform.as_entire_binding(),
                        water.as_entire_binding(),
                        View(&shadow_view),
                    ],
                );
                Some(WallsFrame {
                    texture,
                    layout,
                    layers,
                    bind,
                })
            }
        };

        // One layer per object (all objects share the texture size); one unused layer without any.
        let res_all = setup.params.texture;
        ctx.check_texture_size("volumes depth texture", res_all, res_all)?;
        let layers = (setup.objects.len() as u32).max(1);
        let array = |label: &str| {
            ctx.texture_2d(
                label,
                (res_all, res_all, layers),
                wgpu::TextureFormat::Rgba32Float,
                U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC,
            )
        };
        let depths = array("volumes depth textures");
        let images = array("volumes images");
        bytes += (res_all * res_all * layers) as u64 * 32;
        let layer_view = |t: &wgpu::Texture, k: u32| {
            t.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: k,
                array_layer_count: Some(1),
                ..Default::default()
            })
        };
        let mut pass_uniforms = Vec::new();
        let mut objects = Vec::new();
        for (k, o) in setup.objects.iter().enumerate() {
            let res = o.view.res as u32;
            let object_uniform = PassUniform::object(setup, k);
            pass_uniforms.push(object_uniform);
            let u = pass_uniform(object_uniform);
            let depth_view = layer_view(&depths, k as u32);
            let caustics = map_texture("volumes caustics map", res, res);
            let caustics_view = caustics.create_view(&Default::default());
            let diffuse = depth_texture("volumes diffuse map", res)?;
            bytes += (res * res) as u64 * (16 + texel_bytes);
            let depth_bind = bind_group(
                ctx,
                "volumes depth",
                &self.depth.get_bind_group_layout(0),
                &[
                    u.as_entire_binding(),
                    root_buf.as_entire_binding(),
                    View(&depth_view),
                ],
            );
            let slices_bind = bind_group(
                ctx,
                "volumes slices",
                &self.slices.get_bind_group_layout(0),
                &[
                    uniform.as_entire_binding(),
                    u.as_entire_binding(),
                    water.as_entire_binding(),
                    View(&depth_view),
                    View(&shadow_view),
                ],
            );
            let shade_bind = bind_group(
                ctx,
                "volumes shade",
                &self.shade.get_bind_group_layout(0),
                &[
                    u.as_entire_binding(),
                    View(&depth_view),
                    View(&caustics_view),
                    View(&diffuse.create_view(&Default::default())),
                    View(&layer_view(&images, k as u32)),
                ],
            );
            let Some(vertices) = slice_vertices(o) else {
                return Err(GpuError::TooLarge {
                    what: format!("volumes slices of objects[{k}]"),
                    size: format!(
                        "{} vertices",
                        o.cells.triangles() as u64 * o.planes as u64 * 3
                    ),
                    limit: format!("{} per draw", u32::MAX),
                });
            };
            objects.push(ObjectFrame {
                layer: k as u32,
                uniform: u,
                caustics,
                caustics_view,
                diffuse,
                depth_bind,
                slices_bind,
                shade_bind,
                vertices,
                res,
            });
        }
        let view = match view {
            None => None,
            Some(v) => {
                let (w, h) = (v.camera.width as u32, v.camera.height as u32);
                ctx.check_texture_size("volumes refracted view", w, h)?;
                let image = ctx.texture_2d(
                    "volumes refracted view",
                    (w, h, 1),
                    wgpu::TextureFormat::Rgba32Float,
                    U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC,
                );
                bytes += (w * h) as u64 * 16;
                if pass_uniforms.is_empty() {
                    pass_uniforms.push(PassUniform::default());
                }
                let camera = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("volumes camera"),
                    contents: bytemuck::bytes_of(&CameraUniform::new(v, setup)),
                    usage: B::UNIFORM,
                });
                let object_buf = ctx.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("volumes objects"),
                    contents: bytemuck::cast_slice(&pass_uniforms),
                    usage: B::STORAGE | B::COPY_DST,
                });
                let array_view = |t: &wgpu::Texture| {
                    t.create_view(&wgpu::TextureViewDescriptor {
                        dimension: Some(wgpu::TextureViewDimension::D2Array),
                        ..Default::default()
                    })
                };
                // Without walls the view binds a one-texel stand-in it never reads (flags.z = 0).
                let stand_in;
                let walls_texture = match &walls {
                    Some(w) => &w.texture,
                    None => {
                        stand_in = ctx.texture_2d(
                            "volumes wall maps stand-in",
                            (1, 1, 1),
                            self.map_format,
                            U::TEXTURE_BINDING,
                        );
                        &stand_in
                    }
                };
                let bind = bind_group(
                    ctx,
                    "volumes view",
                    &self.view.get_bind_group_layout(0),
                    &[
                        uniform.as_entire_binding(),
                        camera.as_entire_binding(),
                        View(&heights.heights),
                        object_buf.as_entire_binding(),
                        View(&array_view(&depths)),
                        View(&array_view(&images)),
                        View(&floor.create_view(&Default::default())),
                        View(&image.create_view(&Default::default())),
                        View(&array_view(walls_texture)),
                    ],
                );
                Some((image, bind, object_buf))
            }
        };
        ctx.check()?;
        Ok(Frame {
            setup: setup.clone(),
            heights: None,
            wrap,
            uniform,
            water,
            shadow,
            objects,
            bvh_bind,
            water_bind,
            floor_bind,
            floor_view: floor.create_view(&Default::default()),
            floor,
            walls,
            depths,
            images,
            view,
            bytes,
        })
    }

    /// Record the technique's passes for `frame`.
    pub fn encode(
        &self,
        frame: &Frame,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) {
        {
            let mut pass = begin_compute(encoder, &mut timer, "volumes depth textures");
            pass.set_pipeline(&self.depth);
            pass.set_bind_group(1, &frame.bvh_bind, &[]);
            if let Some((tex, bind, _)) = &frame.shadow {
                pass.set_bind_group(0, bind, &[]);
                pass.dispatch_workgroups(tex.width().div_ceil(8), tex.height().div_ceil(8), 1);
            }
            for o in &frame.objects {
                pass.set_bind_group(0, &o.depth_bind, &[]);
                pass.dispatch_workgroups(o.res.div_ceil(8), o.res.div_ceil(8), 1);
            }
        }
        {
            let mut pass = begin_compute(encoder, &mut timer, "volumes water");
            pass.set_pipeline(&self.water);
            pass.set_bind_group(0, &frame.water_bind, &[]);
            let n = frame.setup.lattice.vertex_count() as u32;
            pass.dispatch_workgroups(n.div_ceil(64), 1, 1);
        }
        for (k, o) in frame.objects.iter().enumerate() {
            let label = format!("volumes slices, object {k}");
            let label = label.as_str();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &[color_attachment(&o.caustics_view)],
                depth_stencil_attachment: None,
                timestamp_writes: timer.as_mut().and_then(|t| t.render_pass(label)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.slices);
            pass.set_bind_group(0, &o.slices_bind, &[]);
            pass.draw(0..o.vertices, 0..1);
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("volumes floor"),
                color_attachments: &[color_attachment(&frame.floor_view)],
                depth_stencil_attachment: None,
                timestamp_writes: timer.as_mut().and_then(|t| t.render_pass("volumes floor")),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.floor);
            pass.set_bind_group(0, &frame.floor_bind, &[]);
            let triangles = 2 * frame.setup.lattice.nx * frame.setup.lattice.ny;
            pass.draw(0..(3 * triangles) as u32, 0..1);
        }
        if let Some(walls) = &frame.walls {
            let triangles = 2 * frame.setup.lattice.nx * frame.setup.lattice.ny;
            for (k, (layer, map)) in walls.layers.iter().zip(&walls.layout.maps).enumerate() {
                let label = format!("volumes wall {}", Wall::ALL[k].suffix());
                let label = label.as_str();
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some(label),
                    color_attachments: &[color_attachment(layer)],
                    depth_stencil_attachment: None,
                    timestamp_writes: timer.as_mut().and_then(|t| t.render_pass(label)),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(&self.walls);
                pass.set_bind_group(0, &walls.bind, &[]);
                // The wall's own columns: the shader's clip space spans them, the rest of a
                // narrower wall's layer stays clear.
                pass.set_viewport(0.0, 0.0, map.cols as f32, map.rows as f32, 0.0, 1.0);
                pass.draw(0..(3 * triangles) as u32, k as u32..k as u32 + 1);
            }
        }
        if !frame.objects.is_empty() {
            let mut pass = begin_compute(encoder, &mut timer, "volumes shade");
            pass.set_pipeline(&self.shade);
            for o in &frame.objects {
                pass.set_bind_group(0, &o.shade_bind, &[]);
                pass.dispatch_workgroups(o.res.div_ceil(8), o.res.div_ceil(8), 1);
            }
        }
        if let Some((image, bind, _)) = &frame.view {
            let mut pass = begin_compute(encoder, &mut timer, "volumes view");
            pass.set_pipeline(&self.view);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(image.width().div_ceil(8), image.height().div_ceil(8), 1);
        }
    }

    fn read_map(
        &self,
        ctx: &GpuContext,
        texture: &wgpu::Texture,
    ) -> Result<Vec<[f32; 3]>, GpuError> {
        let texels = ctx.read_rgba_f32(texture)?;
        Ok(texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect())
    }

    /// Read everything a frame made back.
    pub fn read(&self, ctx: &GpuContext, frame: &Frame) -> Result<GpuOutput, GpuError> {
        let mut objects = Vec::new();
        for o in &frame.objects {
            let image: Vec<[f32; 4]> = ctx.read_texture_layer(&frame.images, o.layer)?;
            objects.push(ObjectMaps {
                depth: ctx.read_texture_layer(&frame.depths, o.layer)?,
                diffuse: ctx.read_texture(&o.diffuse)?,
                caustics: self.read_map(ctx, &o.caustics)?,
                image: image.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
            });
        }
        let s = &frame.setup;
        Ok(GpuOutput {
            objects,
            floor: CausticsMap {
                width: s.width,
                height: s.height,
                size: s.size,
                texels: self.read_map(ctx, &frame.floor)?,
            },
            walls: match &frame.walls {
                Some(w) => Some(read_walls(ctx, w)?),
                None => None,
            },
            shadow: match &frame.shadow {
                Some((tex, _, _)) => ctx.read_texture(tex)?,
                None => Vec::new(),
            },
            water: ctx.read_buffer(&frame.water)?,
            view: match &frame.view {
                Some((tex, _, _)) => {
                    let texels: Vec<[f32; 4]> = ctx.read_texture(tex)?;
                    texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect()
                }
                None => Vec::new(),
            },
        })
    }

    /// Run the technique once and read everything back.
    pub fn run(
        &self,
        ctx: &GpuContext,
        setup: &VolumesSetup,
        input: &VolumesInput,
        heights: &Grid,
        wrap: bool,
        view: Option<&ViewOptions>,
    ) -> Result<GpuOutput, GpuError> {
        let frame = self.frame(ctx, setup, input, heights, wrap, view)?;
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode(&frame, &mut encoder, None);
        ctx.queue.submit([encoder.finish()]);
        ctx.wait()?;
        self.read(ctx, &frame)
    }
}

/// The walls' maps of a frame, read back.
fn read_walls(ctx: &GpuContext, walls: &WallsFrame) -> Result<WallMaps, GpuError> {
    let mut maps = walls.layout.clone();
    walls.output().read(ctx, &mut maps)?;
    Ok(maps)
}

fn color_attachment(view: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations {
            load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
            store: wgpu::StoreOp::Store,
        },
    })
}
