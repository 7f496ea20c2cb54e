//! The uniform blocks, as `volumes/common.wgsl` and `volumes/view.wgsl` declare them, and the
//! refracted view's options.

use crate::pass::{f4, v4};
use caustics_core::techniques::volumes::view::ViewCamera;
use caustics_core::techniques::volumes::{OrthoView, VolumesSetup};

/// Mirrors `View` in `volumes/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewUniform {
    /// xyz: `a`, the view frame's first axis (texel columns), world frame; w: `res`, texels per
    /// side.
    pub a: [f32; 4],
    /// xyz: `b`, the second axis (texel rows); w: how far before the box's front face the depth
    /// rays start, world units (`ray_margin`).
    pub b: [f32; 4],
    /// xyz: `v`, the unit direction of projection, depth growing along it; w: the reference
    /// planes' spacing `Δ` (§3.1), 0 for the shadow map.
    pub v: [f32; 4],
    /// xyz: the box's near corner in frame coordinates `(a · p, b · p, v · p)`; w: 0.
    pub lo: [f32; 4],
    /// xy: a texel's size along `a` and `b`, world units; z: the box's depth along `v`; w: 0.
    pub texel: [f32; 4],
}

impl ViewUniform {
    /// `spacing`: the reference planes' `Δ` (0 for the shadow map).
    pub fn new(view: &OrthoView, spacing: f64) -> Self {
        let e = view.extent();
        let t = view.texel();
        let margin = caustics_core::techniques::volumes::representation::ray_margin(view);
        ViewUniform {
            a: v4(view.a, view.res as f64),
            b: v4(view.b, margin),
            v: v4(view.v, spacing),
            lo: v4(view.lo, 0.0),
            texel: [t.x as f32, t.y as f32, e.z as f32, 0.0],
        }
    }
}

/// Mirrors `Volumes` in `volumes/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumesUniform {
    /// xyz: the unit direction the sunlight travels, world frame; w: `η = 1 / ior`, air to water.
    pub light: [f32; 4],
    /// xyz: `K` per channel of Eq. 3's `exp(−K d)`, per world unit (0 without the absorption
    /// option); w: `T(θ0)`, flat water's Fresnel transmittance for the sun (1 without the Fresnel
    /// option).
    pub absorption: [f32; 4],
    /// xy: the water lattice's origin on the surface, world units; z: its cell's side; w: the side
    /// of the water's square, which the floor map covers.
    pub lattice: [f32; 4],
    /// x: the water's rest depth; y: its index of refraction; z: the shadow test's depth tolerance,
    /// world units; w: 1 with the Fresnel option, else 0.
    pub params: [f32; 4],
    /// x, y: the water lattice's cells along x and y; z, w: the floor map's width and height,
    /// texels.
    pub dims: [u32; 4],
    /// x: 1 where the heights tile; y: 1 with the shadow map; z: 1 where the walls receive light;
    /// w: the walls' maps' rows (0 without walls).
    pub flags: [u32; 4],
    /// The shadow map's view along the refracted sun (zero without shadows).
    pub shadow: ViewUniform,
}

impl VolumesUniform {
    /// The uniform for `s`; `wrap` is the water's edge rule (periodic heights).
    pub fn new(s: &VolumesSetup, wrap: bool) -> Self {
        VolumesUniform {
            light: v4(s.light, s.eta),
            absorption: v4(s.absorption, s.t_flat),
            lattice: f4([
                s.lattice.origin.x,
                s.lattice.origin.y,
                s.lattice.cell,
                s.size,
            ]),
            params: f4([
                s.depth,
                s.ior,
                s.shadow_bias,
                if s.params.fresnel { 1.0 } else { 0.0 },
            ]),
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
    /// The object's view-aligned box and textures' frame, or the shadow map's.
    pub view: ViewUniform,
    /// `i0, i1, j0, j1`: the rectangle of water lattice cells whose illumination volumes can reach
    /// the object, the cells the slice pass draws.
    pub cells: [u32; 4],
    /// The object's reference planes (§3.1; the paper's Fig. 6 uses 5 and 50).
    pub planes: u32,
    /// The first of the objects' trees the depth pass traces (the object's own index).
    pub root_first: u32,
    /// How many trees from `root_first` it traces: 1 for an object, all of them for the shadow
    /// map.
    pub root_count: u32,
    /// Padding to align `albedo`.
    pub _pad: u32,
    /// xyz: the object's diffuse albedo, linear RGB; w: the ambient `Ia` of Eq. 4, relative to the
    /// sun through flat water.
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
            albedo: v4(o.albedo, setup.params.ambient),
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
    /// xyz: the camera's eye, world coordinates; w: the ambient `Ia` of Eq. 4.
    pub position: [f32; 4],
    /// xyz: the unit direction the camera looks along; w: the number of objects.
    pub forward: [f32; 4],
    /// xyz: the camera's right vector times `tan(fov_y / 2)` times the aspect ratio; w: the image's
    /// width, pixels.
    pub right: [f32; 4],
    /// xyz: the camera's up vector times `tan(fov_y / 2)`; w: the image's height, pixels.
    pub up: [f32; 4],
    /// xyz: the floor's albedo, linear RGB; w: 1, unread.
    pub floor_albedo: [f32; 4],
}

/// The refracted view (§3.3) to render with the caustics: the camera and the floor's albedo.
#[derive(Clone, Copy, Debug)]
pub struct ViewOptions {
    /// The camera above the water, its right and up vectors scaled by the field of view.
    pub camera: ViewCamera,
    /// The floor's albedo, linear RGB: one colour for the whole floor (the scene's view takes its
    /// pattern's mean).
    pub floor_albedo: glam::DVec3,
}

impl CameraUniform {
    /// The uniform for the view `v` of `setup`'s objects.
    pub fn new(v: &ViewOptions, setup: &VolumesSetup) -> Self {
        let c = &v.camera;
        CameraUniform {
            position: v4(c.position, setup.params.ambient),
            forward: v4(c.forward, setup.objects.len() as f64),
            right: v4(c.right, c.width as f64),
            up: v4(c.up, c.height as f64),
            floor_albedo: v4(v.floor_albedo, 1.0),
        }
    }
}
