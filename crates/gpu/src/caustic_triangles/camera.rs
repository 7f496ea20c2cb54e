//! The camera pass of technique `caustic-triangles` on the GPU (paper 4, §4.3): the technique's own
//! final image. CPU twin: `caustics_core::techniques::caustic_triangles::camera`, where the shading
//! model is documented; WGSL `caustic_triangles/camera.wgsl`.
//!
//! [`CameraRenderer::render`] runs the whole technique for a scene's generators: per generator the
//! photon tracing pass, then (sun) its triangles added into one floor map, or (point light) its
//! vertex irradiance, its triangles on the light cube map faces and its shadow distances, and last
//! the camera pass, which reads every generator's distance map from one buffer (each at its
//! `dm_base`).

use caustics_core::scene::Camera;
use caustics_core::techniques::caustic_triangles::camera::CameraParams;
use caustics_core::techniques::caustic_triangles::{CausticTrianglesSetup, DistanceMap};

use super::CAMERA;
use super::{
    CausticTriangles, CausticTrianglesUniform, GeneratorFrame, LightCubeTarget, Reconstruction,
};
use crate::pass::{Bind, begin_compute, compute_pipeline, f4, v4};
use crate::{GpuContext, GpuError, GpuTimer};
use wgpu::BufferUsages as B;

/// Mirrors `CameraPass` in `caustic_triangles/camera.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CameraUniform {
    /// xyz: the eye, world units; w: `tan(fov_y / 2)`.
    pub position: [f32; 4],
    /// xyz: the eye's unit forward axis; w: the image's aspect (width / height).
    pub forward: [f32; 4],
    /// xyz: the eye's unit right axis; w: ambient irradiance, floor units.
    pub right: [f32; 4],
    /// xyz: the eye's unit up axis; w: relative bias of the shadow and caustic distance tests.
    pub up: [f32; 4],
    /// xyz: the sky's radiance, linear RGB, for rays that leave the scene; w: 0 the sun, 1 a
    /// point light.
    pub sky: [f32; 4],
    /// xyz: the floor's albedo, linear RGB; w: the point light's radiant intensity, floor units
    /// (0 under the sun).
    pub floor_albedo: [f32; 4],
    /// xyz: the albedo of diffuse surfaces other than the floor, linear RGB; w: 0.
    pub wall_albedo: [f32; 4],
    /// xyz: the light's colour times its intensity, linear RGB; w: 0.
    pub light_color: [f32; 4],
    /// xyz: the sun's unit direction of travel, or the point light's position (world units);
    /// w: cosine of the spot's half-angle, -2 for a bare point light or the sun.
    pub light: [f32; 4],
    /// xyz: the spot's unit axis (zero under the sun); w: 0.
    pub spot_axis: [f32; 4],
    /// xy: the floor map's origin (world units); z: its side; w: 0.
    pub floor: [f32; 4],
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Number of generators (glass objects) in the generators' storage buffer.
    pub generators: u32,
    /// Face side of the light cube map, texels (1, a stand-in, under the sun).
    pub cube: u32,
    /// Floor map width, texels (1, a stand-in, under a point light).
    pub map_width: u32,
    /// Floor map height, texels (1, a stand-in, under a point light).
    pub map_height: u32,
    /// Padding to a multiple of 16 bytes.
    pub _pad: [u32; 2],
}

/// The camera pass pipeline (and the technique's passes it drives).
pub struct CameraRenderer {
    pipeline: wgpu::ComputePipeline,
}

/// What a camera-pass run returns: linear RGB per pixel, rows top to bottom.
pub struct CameraImage {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// `width × height` pixels, row-major.
    pub rgb: Vec<[f32; 3]>,
}

impl CameraRenderer {
    /// Build the camera pass pipeline.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let pipeline = compute_pipeline(ctx, &CAMERA);
        ctx.check()?;
        Ok(CameraRenderer { pipeline })
    }

    /// The whole technique for `generators` (all lit by the same light: a sun or the same point
    /// light), ending in the camera pass from `camera`.
    pub fn render(
        &self,
        ctx: &GpuContext,
        ct: &CausticTriangles,
        generators: &[(&CausticTrianglesSetup, &DistanceMap)],
        camera: &Camera,
        params: &CameraParams,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<CameraImage, GpuError> {
        let Some(first) = generators.first() else {
            return Err(GpuError::Validation(
                "the camera pass needs one caustic generator at least".into(),
            ));
        };
        let point = first.0.point;
        let (w, h) = (camera.width, camera.height);
        ctx.check_buffer_size("caustic-triangles camera image", w as u64 * h as u64 * 16)?;
        let frames: Vec<GeneratorFrame> = generators
            .iter()
            .map(|(s, dm)| ct.frame(ctx, s, dm))
            .collect::<Result<_, _>>()?;
        // Every distance map in one buffer, each generator's uniform with its base.
        let mut dm_texels: Vec<[f32; 4]> = Vec::new();
        let mut uniforms = Vec::new();
        for (s, dm) in generators {
            let mut u = CausticTrianglesUniform::new(s, dm);
            u.dm_base = dm_texels.len() as u32;
            dm_texels.extend_from_slice(&dm.texels);
            uniforms.push(u);
        }
        ctx.check_buffer_size(
            "caustic-triangles distance maps",
            dm_texels.len() as u64 * 16,
        )?;
        let dm_buffer = ctx.buffer_init(
            "caustic-triangles camera distance maps",
            bytemuck::cast_slice(&dm_texels),
            B::STORAGE,
        );
        let gens_buffer = ctx.buffer_init(
            "caustic-triangles camera generators",
            bytemuck::cast_slice(&uniforms),
            B::STORAGE,
        );
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        for frame in &frames {
            let p = frame.setup.p as u32;
            let mut pass =
                begin_compute(&mut encoder, &mut timer, "caustic-triangles photon tracing");
            pass.set_pipeline(&ct.photon);
            pass.set_bind_group(0, &frame.photon_bind, &[]);
            pass.dispatch_workgroups(p.div_ceil(8), p.div_ceil(8), 1);
        }
        // The light's maps; the unused kind is a 1-texel stand-in.
        let cube_target: LightCubeTarget;
        let one_texel = |label| {
            ctx.texture_2d(
                label,
                (1, 1, 1),
                ct.map_format,
                wgpu::TextureUsages::TEXTURE_BINDING,
            )
        };
        let stand_in_map;
        let (cube_view, floor_view, shadow, map_size, cube_res) = match point {
            Some(_) => {
                let res = first.0.light_cube as u32;
                cube_target = ct.light_cube(ctx, res)?;
                ct.reset_cube(ctx, &cube_target);
                for (k, frame) in frames.iter().enumerate() {
                    let binds = ct.cube_binds(ctx, frame, &cube_target);
                    ct.encode_cube(
                        frame,
                        &binds,
                        &cube_target,
                        &mut encoder,
                        timer.as_deref_mut(),
                        k == 0,
                    );
                }
                stand_in_map = one_texel("caustic-triangles floor map stand-in");
                (
                    cube_target.view.clone(),
                    stand_in_map.create_view(&Default::default()),
                    cube_target.shadow.clone(),
                    (1, 1),
                    res,
                )
            }
            None => {
                for (k, frame) in frames.iter().enumerate() {
                    ct.encode_irradiance(frame, &mut encoder, timer.as_deref_mut());
                    ct.draw_floor(
                        frame,
                        &mut encoder,
                        timer.as_deref_mut(),
                        Reconstruction::Triangles,
                        &frames[0].map_view,
                        k == 0,
                    );
                }
                stand_in_map = one_texel("caustic-triangles light cube stand-in");
                let shadow = ctx.buffer("caustic-triangles shadow stand-in", 16, B::STORAGE);
                let f = &first.0.floor;
                (
                    stand_in_map.create_view(&Default::default()),
                    frames[0].map.create_view(&Default::default()),
                    shadow,
                    (f.width as u32, f.height as u32),
                    1,
                )
            }
        };
        let uniform = camera_uniform(
            camera,
            params,
            first.0,
            generators.len(),
            cube_res,
            map_size,
        );
        let uniform = ctx.uniform("caustic-triangles camera uniform", &uniform);
        let image = ctx.buffer(
            "caustic-triangles camera image",
            w as u64 * h as u64 * 16,
            B::STORAGE | B::COPY_SRC,
        );
        let bind = self.pipeline.bind(
            ctx,
            "caustic-triangles camera pass",
            &[
                &uniform,
                &dm_buffer,
                &gens_buffer,
                &shadow,
                &cube_view,
                &floor_view,
                &image,
            ],
        );
        {
            let mut pass = begin_compute(&mut encoder, &mut timer, "caustic-triangles camera pass");
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
        ctx.submit_timed(encoder, timer.as_deref());
        let texels: Vec<[f32; 4]> = ctx.read_buffer(&image)?;
        ctx.check()?;
        Ok(CameraImage {
            width: w,
            height: h,
            rgb: texels.into_iter().map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}

fn camera_uniform(
    camera: &Camera,
    params: &CameraParams,
    setup: &CausticTrianglesSetup,
    generators: usize,
    cube: u32,
    (map_width, map_height): (u32, u32),
) -> CameraUniform {
    // The frame of `Camera::ray`.
    let forward = (camera.target - camera.position).normalize();
    let right = forward.cross(glam::DVec3::Z).normalize_or(glam::DVec3::X);
    let up = right.cross(forward);
    let (light, spot_axis, mode, intensity) = match setup.point {
        Some(pl) => (
            v4(pl.position, pl.cone.map_or(-2.0, f64::cos)),
            v4(pl.axis, 0.0),
            1.0,
            pl.intensity(),
        ),
        None => (v4(setup.w, -2.0), [0.0; 4], 0.0, 0.0),
    };
    CameraUniform {
        position: v4(camera.position, (camera.fov_y.to_radians() * 0.5).tan()),
        forward: v4(forward, camera.width as f64 / camera.height as f64),
        right: v4(right, params.ambient),
        up: v4(up, params.bias),
        sky: v4(params.sky, mode),
        floor_albedo: v4(params.floor_albedo, intensity),
        wall_albedo: v4(params.wall_albedo, 0.0),
        light_color: v4(params.light_color, 0.0),
        light,
        spot_axis,
        floor: f4([
            setup.floor.origin.x,
            setup.floor.origin.y,
            setup.floor.size,
            0.0,
        ]),
        width: camera.width,
        height: camera.height,
        generators: generators as u32,
        cube,
        map_width,
        map_height,
        _pad: [0; 2],
    }
}

/// The technique's final image of a whole scene (every glass object a generator, the scene's
/// camera and light): on the GPU when `ctx` is given, else on the CPU twin; linear RGB, and which
/// of the two made it.
pub fn scene_image(
    ctx: Option<&GpuContext>,
    scene: &caustics_core::scene::Scene,
    params: &caustics_core::techniques::caustic_triangles::CausticTrianglesParams,
    camera_params: &CameraParams,
) -> Result<(CameraImage, &'static str), GpuError> {
    use caustics_core::techniques::caustic_triangles::camera;
    let Some(ctx) = ctx else {
        let rgb = camera::render_scene(scene, params, camera_params)?;
        return Ok((
            CameraImage {
                width: scene.camera.width,
                height: scene.camera.height,
                rgb,
            },
            "CPU",
        ));
    };
    let gens = camera::generators(scene, params)?;
    let pairs: Vec<_> = gens.iter().map(|g| (&g.setup, &g.dm)).collect();
    let ct = CausticTriangles::new(ctx)?;
    let image =
        CameraRenderer::new(ctx)?.render(ctx, &ct, &pairs, &scene.camera, camera_params, None)?;
    Ok((image, "GPU"))
}
