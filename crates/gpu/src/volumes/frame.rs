//! One scene's resources: what a frame allocates and binds for every pass, and the uniform writes
//! that refit it to a new sun or camera.

use caustics_core::grid::Grid;
use caustics_core::techniques::volumes::{VolumesInput, VolumesSetup};
use caustics_core::walls::WallMaps;
use glam::DVec3;

use super::{CameraUniform, PassUniform, ViewOptions, Volumes, VolumesUniform};
use crate::bvh::FlatBvhs;
use crate::pass::{
    Bind, MAP_TARGET, STORAGE_OUT, array_view, bind_group, layer_view, storage_buffer,
    wall_maps_texture,
};
use crate::receivers::{ReceiverFrame, ReceiversUniform};
use crate::technique::WallsOutput;
use crate::{GpuContext, GpuError, WaterTextures};

pub(super) struct ObjectFrame {
    /// The object's layer of the frame's depth-texture and image arrays.
    pub(super) layer: u32,
    /// Its [`PassUniform`].
    uniform: wgpu::Buffer,
    pub(super) caustics: wgpu::Texture,
    pub(super) caustics_view: wgpu::TextureView,
    pub(super) diffuse: wgpu::Texture,
    pub(super) depth_bind: wgpu::BindGroup,
    pub(super) slices_bind: wgpu::BindGroup,
    pub(super) shade_bind: wgpu::BindGroup,
    pub(super) vertices: u32,
    pub(super) res: u32,
}

/// One scene's resources: the BVH buffers, textures per object, the water buffer, the floor map and
/// every bind group. Built once; encode it every frame (it reads the heights afresh).
pub struct VolumesFrame {
    /// The setup the frame was built for: the sun, water, lattice and objects' views it uploads.
    pub setup: VolumesSetup,
    /// The heights it uploaded itself ([`Volumes::frame`]); `None` when it reads the caller's
    /// ([`Volumes::frame_with_water`]).
    heights: Option<wgpu::Texture>,
    wrap: bool,
    /// The [`VolumesUniform`] every pass reads.
    uniform: wgpu::Buffer,
    /// The water pass's output: one [`WaterVertex`](caustics_core::techniques::volumes::illumination::WaterVertex)
    /// (eight floats) per lattice vertex, the refracted surface point, its Fresnel weight and the
    /// refracted direction.
    pub water: wgpu::Buffer,
    /// The shadow map, its depth pass's bind group and [`PassUniform`].
    pub(super) shadow: Option<(wgpu::Texture, wgpu::BindGroup, wgpu::Buffer)>,
    pub(super) objects: Vec<ObjectFrame>,
    pub(super) bvh_bind: wgpu::BindGroup,
    pub(super) water_bind: wgpu::BindGroup,
    pub(super) floor_bind: wgpu::BindGroup,
    /// The floor pass's map: the floor map on the plane `z = 0`, the light-space deposit over
    /// receivers ([`VolumesFrame::floor_map`]).
    pub floor: wgpu::Texture,
    pub(super) floor_view: wgpu::TextureView,
    /// Over a terrain: where the rays meet it, and its lookup.
    pub(super) receivers: Option<FrameReceivers>,
    /// The walls' maps when the setup has walls.
    pub walls: Option<WallsFrame>,
    /// Every object's depth texture and final image (Eq. 4), one layer each.
    pub(super) depths: wgpu::Texture,
    pub(super) images: wgpu::Texture,
    /// The refracted view's image, bind group and its copy of every object's [`PassUniform`], when
    /// one was asked for.
    pub(super) view: Option<(wgpu::Texture, wgpu::BindGroup, wgpu::Buffer)>,
    bytes: u64,
}

/// A frame's receivers: the meeting pass's hits and bind group, the floor pass over them, and the
/// lookup that writes the floor map.
pub(super) struct FrameReceivers {
    pub(super) hits: wgpu::Buffer,
    pub(super) meet_bind: wgpu::BindGroup,
    pub(super) frame: ReceiverFrame,
}

impl VolumesFrame {
    /// The floor map: the receivers' lookup over a terrain, else the floor pass's map.
    pub fn floor_map(&self) -> &wgpu::Texture {
        self.receivers
            .as_ref()
            .map_or(&self.floor, |r| &r.frame.floor)
    }

    /// GPU memory the frame's buffers and textures take, bytes.
    pub fn bytes(&self) -> u64 {
        self.bytes
    }

    /// Whether `setup` fits this frame's buffers, textures and bind groups (the same parameters,
    /// map, lattice size and objects), so that [`set_setup`](Self::set_setup) can take it. A new
    /// sun moves the lattice, the shadow map's frame and each object's cells; a new camera turns
    /// each object's view: none of that changes a size.
    pub fn fits(&self, setup: &VolumesSetup) -> bool {
        let s = &self.setup;
        setup.params == s.params
            && setup.receivers == s.receivers
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
        ctx.write_pod(&self.uniform, &VolumesUniform::new(setup, self.wrap));
        if let (Some((_, _, buffer)), Some(view)) = (&self.shadow, &setup.shadow) {
            let u = PassUniform::shadow(view, setup.objects.len());
            ctx.write_pod(buffer, &u);
        }
        let uniforms: Vec<PassUniform> = (0..setup.objects.len())
            .map(|k| PassUniform::object(setup, k))
            .collect();
        for ((o, u), view) in self.objects.iter_mut().zip(&uniforms).zip(&setup.objects) {
            ctx.write_pod(&o.uniform, u);
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
    /// The walls' maps, one `Rgba32Float` layer per wall in `Wall::ALL`'s order.
    pub texture: wgpu::Texture,
    /// Empty maps: the walls' sizes.
    pub layout: WallMaps,
    pub(super) layers: Vec<wgpu::TextureView>,
    pub(super) bind: wgpu::BindGroup,
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

impl Volumes {
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
    ) -> Result<VolumesFrame, GpuError> {
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
    ) -> Result<VolumesFrame, GpuError> {
        use wgpu::BufferUsages as B;
        use wgpu::TextureUsages as U;
        let (w, h) = (setup.width as u32, setup.height as u32);
        ctx.check_texture_size("volumes floor map", w, h)?;
        let bvhs = FlatBvhs::of(input.objects.iter().map(|o| &o.mesh));
        // A scene without objects binds one unused node and slot.
        let tri_buf = storage_buffer(ctx, "volumes BVH triangles", &bvhs.triangles)?;
        let node_buf = storage_buffer(ctx, "volumes BVH nodes", &bvhs.nodes)?;
        let roots = bvhs.roots;
        let mut root_list: Vec<u32> = roots.clone();
        root_list.push(0);
        let root_buf = storage_buffer(ctx, "volumes roots", &root_list)?;
        let mut bytes = node_buf.size() + tri_buf.size() + root_buf.size();
        let bvh_bind = bind_group(
            ctx,
            "volumes BVH",
            &self.depth.get_bind_group_layout(1),
            &[&node_buf, &tri_buf],
        );
        let uniform = ctx.uniform("volumes uniform", &VolumesUniform::new(setup, wrap));
        let pass_uniform = |p: PassUniform| ctx.uniform("volumes pass uniform", &p);
        let depth_texture = |label: &str, res: u32| -> Result<wgpu::Texture, GpuError> {
            ctx.check_texture_size(label, res, res)?;
            Ok(ctx.texture_2d(
                label,
                (res, res, 1),
                wgpu::TextureFormat::Rgba32Float,
                STORAGE_OUT,
            ))
        };
        // The shadow map, or a 1 x 1 stand-in the shaders never read (flags.y = 0).
        let (shadow_tex, shadow) = match &setup.shadow {
            Some(view) => {
                let res = view.res as u32;
                let tex = depth_texture("volumes shadow map", res)?;
                let u = pass_uniform(PassUniform::shadow(view, roots.len()));
                let bind = self.depth.bind(
                    ctx,
                    "volumes shadow map",
                    &[&u, &root_buf, &tex.create_view(&Default::default())],
                );
                bytes += (res * res) as u64 * 16;
                (tex.clone(), Some((tex, bind, u)))
            }
            None => (depth_texture("volumes shadow stand-in", 1)?, None),
        };
        let shadow_view = shadow_tex.create_view(&Default::default());

        let lattice_vertices = setup.lattice.vertex_count() as u64;
        ctx.check_buffer_size("volumes water vertices", lattice_vertices * 32)?;
        let water = ctx.buffer(
            "volumes water",
            lattice_vertices * 32,
            B::STORAGE | B::COPY_SRC,
        );
        bytes += water.size();
        let water_bind =
            self.water
                .bind(ctx, "volumes water", &[&uniform, &heights.heights, &water]);
        let map_texture = |label: &str, w: u32, h: u32| {
            ctx.texture_2d(label, (w, h, 1), self.map_format, MAP_TARGET)
        };
        let texel_bytes = if self.map_format == wgpu::TextureFormat::Rgba16Float {
            8
        } else {
            16
        };
        let floor = map_texture("volumes floor map", w, h);
        bytes += (w * h) as u64 * texel_bytes;
        let (floor_bind, receivers) = match &setup.receivers {
            None => (
                self.floor
                    .bind(ctx, "volumes floor", &[&uniform, &water, &shadow_view]),
                None,
            ),
            Some(r) => {
                let frame = self.lookup.frame(ctx, &r.0, &floor, wrap, DVec3::ZERO)?;
                let r_uniform = ctx.uniform("volumes receivers", &ReceiversUniform::of(Some(&r.0)));
                let hits = ctx.buffer("volumes hits", lattice_vertices * 16, B::STORAGE);
                bytes += hits.size() + frame.bytes();
                let heights_view = frame.heights.create_view(&Default::default());
                let meet_bind = self.meet.bind(
                    ctx,
                    "volumes meet",
                    &[&r_uniform, &water, &heights_view, &hits],
                );
                let floor_bind = self.floor_receivers.bind(
                    ctx,
                    "volumes floor over receivers",
                    &[
                        &uniform,
                        &water,
                        &shadow_view,
                        &r_uniform,
                        &heights_view,
                        &hits,
                    ],
                );
                let receivers = FrameReceivers {
                    hits,
                    meet_bind,
                    frame,
                };
                (floor_bind, Some(receivers))
            }
        };
        let floor_map = receivers.as_ref().map_or(&floor, |r| &r.frame.floor);

        let walls = match setup.wall_layout() {
            None => None,
            Some(layout) => {
                let texture =
                    wall_maps_texture(ctx, "volumes wall maps", &layout, self.map_format)?;
                bytes += (texture.width() * texture.height() * 4) as u64 * texel_bytes;
                let layers = (0..4).map(|k| layer_view(&texture, k)).collect();
                let bind = self
                    .walls
                    .bind(ctx, "volumes walls", &[&uniform, &water, &shadow_view]);
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
                STORAGE_OUT,
            )
        };
        let depths = array("volumes depth textures");
        let images = array("volumes images");
        bytes += (res_all * res_all * layers) as u64 * 32;
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
            let depth_bind = self
                .depth
                .bind(ctx, "volumes depth", &[&u, &root_buf, &depth_view]);
            let slices_bind = self.slices.bind(
                ctx,
                "volumes slices",
                &[&uniform, &u, &water, &depth_view, &shadow_view],
            );
            let shade_bind = self.shade.bind(
                ctx,
                "volumes shade",
                &[
                    &u,
                    &depth_view,
                    &caustics_view,
                    &diffuse.create_view(&Default::default()),
                    &layer_view(&images, k as u32),
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
                    STORAGE_OUT,
                );
                bytes += (w * h) as u64 * 16;
                if pass_uniforms.is_empty() {
                    pass_uniforms.push(PassUniform::default());
                }
                let camera = ctx.uniform("volumes camera", &CameraUniform::new(v, setup));
                let object_buf = ctx.buffer_init(
                    "volumes objects",
                    bytemuck::cast_slice(&pass_uniforms),
                    B::STORAGE | B::COPY_DST,
                );
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
                let bind = self.view.bind(
                    ctx,
                    "volumes view",
                    &[
                        &uniform,
                        &camera,
                        &heights.heights,
                        &object_buf,
                        &array_view(&depths),
                        &array_view(&images),
                        &floor_map.create_view(&Default::default()),
                        &image.create_view(&Default::default()),
                        &array_view(walls_texture),
                    ],
                );
                Some((image, bind, object_buf))
            }
        };
        ctx.check()?;
        Ok(VolumesFrame {
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
            receivers,
            walls,
            depths,
            images,
            view,
            bytes,
        })
    }
}
