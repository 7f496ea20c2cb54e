//! The uniform blocks, as `volumes/common.wgsl` and `volumes/view.wgsl` declare them, and the
//! refracted view's options.

use caustics_core::techniques::volumes::view::ViewCamera;
use caustics_core::techniques::volumes::{OrthoView, VolumesSetup};

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
