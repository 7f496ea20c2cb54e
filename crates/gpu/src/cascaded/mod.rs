//! Technique `cascaded` on the GPU: cascaded caustic maps (Bäcklund, paper 5). The method, the
//! passes and the choices made where the paper's copy stops are documented with its CPU twin,
//! `caustics_core::techniques::cascaded`, which these passes mirror one for one:
//!
//! | pass | WGSL | CPU twin | runs |
//! |---|---|---|---|
//! | eye depth (compute) | `cascaded/eye.wgsl` | `eye::eye_pass` | once |
//! | water G-buffer (compute) | `cascaded/water.wgsl` | `water::water_gbuffer` | per cascade |
//! | terrain G-buffer (compute) | `cascaded/terrain.wgsl` | `terrain::terrain_gbuffer` | per cascade, optional |
//! | photons + splat (compute, atomics) | `cascaded/photons.wgsl` | `photons::photons` | per cascade |
//! | composition (compute) | `cascaded/compose.wgsl` | `compose::compose` | once |
//! | post-process dispersion (compute) | `cascaded/disperse.wgsl` | `disperse::disperse` | once, optional |
//!
//! **Why compute for the G-buffers.** The paper rasterises the water and terrain meshes from the
//! sun. Our water and terrain are height fields, not meshes: one invocation per light texel
//! intersects its sun ray with them exactly as the CPU twin does (Newton on the water, a march plus
//! bisection on the terrain), with no tessellation to choose and no mesh to build per frame, and the
//! two twins agree to f32 rounding. A rasterised mesh would agree only to its tessellation.
//!
//! **Why atomics for the splat.** Every photon adds `round(w · 2^14)` to its pixel, or split in
//! integer shares over its footprint's pixels, with `atomicAdd` on `u32` in a storage buffer (one
//! per cascade, pixel and channel). Integer sums are exact and do not
//! depend on the order the photons arrive in, so the GPU agrees with the CPU twin bit for bit wherever
//! both place a photon in the same pixel, on every adapter; it needs neither `FLOAT32_BLENDABLE`
//! (without which additive blending into `Rgba32Float` is refused) nor a lossy `Rgba16Float` target
//! (~0.2 % lost, GPU-NOTES), and the photon pass stays a compute pass that reads the G-buffers
//! directly, with no vertex buffer of points. A pixel holds up to 2^18 photons of full weight before
//! it wraps.
//!
//! The G-buffers are transient: one water and one terrain G-buffer serve the four cascades in turn;
//! only the screen-space caustic maps are kept per cascade.

use caustics_core::grid::Grid;
use caustics_core::techniques::cascaded::{
    Brightness, CASCADES, CascadedSetup, Dispersion, FIXED_SCALE, Placement, Splat,
    screen_buffer_len,
};

use crate::pass::{Bind, begin_compute, compute_pipeline, f4, v4};

pub mod technique;
use crate::shaders::passes;
use crate::{GpuContext, GpuError, GpuTimer};
use wgpu::BufferUsages as B;

passes! {
    EYE = "cascaded eye depth", "cascaded/eye.wgsl";
    WATER_GBUFFER = "cascaded water G-buffer", "cascaded/water.wgsl";
    TERRAIN_GBUFFER = "cascaded terrain G-buffer", "cascaded/terrain.wgsl";
    PHOTONS = "cascaded photons", "cascaded/photons.wgsl";
    COMPOSE = "cascaded composition", "cascaded/compose.wgsl";
    DISPERSE = "cascaded dispersion", "cascaded/disperse.wgsl";
}

/// Mirrors `Cascaded` in `cascaded/common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CascadedUniform {
    /// xyz: unit direction the sunlight travels (world, pointing down); w: the water's rest level
    /// (z of the still surface), world units.
    pub light: [f32; 4],
    /// xyz: the light view's u axis (horizontal, across the sun); w: side of the scene square,
    /// world units.
    pub e_u: [f32; 4],
    /// xyz: the light view's v axis (`light × e_u`); w: Fresnel transmittance `T(θ0)` of flat
    /// water, which the physical brightness divides by.
    pub e_v: [f32; 4],
    /// This cascade's sun view (`CascadeView`): u0, v0 (light-view origin of texel (0, 0)'s
    /// corner) and du, dv (one texel's size), world units.
    pub view: [f32; 4],
    /// This cascade: w0 (light-view depth its texels' sun rays start at), its far plane (eye
    /// view depth), the flux one of its photons carries (`photon_flux`), 0.
    pub view2: [f32; 4],
    /// xyz: the eye's position, world; w: `tan(fov_y / 2)`.
    pub eye_pos: [f32; 4],
    /// xyz: the eye's unit forward axis; w: the image's aspect (width / height).
    pub eye_fwd: [f32; 4],
    /// xyz: the eye's unit right axis; w: the eye's near plane (view depth, world units).
    pub eye_right: [f32; 4],
    /// xyz: the eye's unit up axis; w: the fraction of a cascade's depth interval over which it
    /// blends into the next (0: hard seams).
    pub eye_up: [f32; 4],
    /// rgb: the water's refractive index per channel (all equal unless wavelength dispersion,
    /// §3.6); w: the scene's single IOR.
    pub ior: [f32; 4],
    /// rgb: Beer-Lambert absorption coefficient `K` per channel, per world unit; w: `C` of the
    /// ramp brightness (§3.4.3).
    pub absorption: [f32; 4],
    /// The ramp brightness (§3.4.3): MIN_DEPTH, MAX_DEPTH, width of the shallow ramp (world
    /// units of water column), and the splat's fixed-point scale (`FIXED_SCALE`).
    pub ramps: [f32; 4],
    /// Lowest and highest terrain height (padded, world units), 1 with the terrain pass and 0
    /// for the plane z = 0, 0.
    pub terrain: [f32; 4],
    /// Post-process dispersion: the floor shift per unit of water column of red (xy) and blue
    /// (zw), relative to green.
    pub post: [f32; 4],
    /// Far plane of each of the four cascades, eye view depth in world units.
    pub fars: [f32; 4],
    /// Flux one photon carries in each of the four cascades (`photon_flux`).
    pub fluxes: [f32; 4],
    /// Eye image width, pixels.
    pub width: u32,
    /// Eye image height, pixels.
    pub height: u32,
    /// Light-view G-buffer side, texels (the `resolution` parameter).
    pub res: u32,
    /// Index of the cascade this block serves (0 for the eye, composition and dispersion passes).
    pub cascade: u32,
    /// Bit 0: plane placement (else Eq. 3.3); bit 1: physical brightness (else the ramps); bit 2:
    /// wavelength dispersion; bit 3: footprint splat (else points).
    pub flags: u32,
    /// 1: the water tiles (its heights are sampled wrapped at the square's edges), 0: clamped.
    pub wrap: u32,
    /// 1: the pool's walls receive light (`CascadedSetup::walls`).
    pub walls: u32,
    /// Padding to a multiple of 16 bytes.
    pub _pad: u32,
}

impl CascadedUniform {
    /// The block cascade `k` of `s` reads.
    pub fn new(s: &CascadedSetup, k: usize) -> Self {
        let p = &s.params;
        let c = &s.cascades[k];
        let e = &s.eye;
        let (lo, hi, has) = s
            .terrain_range
            .map_or((0.0, 0.0, 0.0), |(a, b)| (a, b, 1.0));
        let mut flags = 0;
        if p.placement == Placement::Plane {
            flags |= 1;
        }
        if p.brightness == Brightness::Physical {
            flags |= 2;
        }
        if p.dispersion == Dispersion::Wavelength {
            flags |= 4;
        }
        if p.splat == Splat::Footprint {
            flags |= 8;
        }
        CascadedUniform {
            light: v4(s.light, s.level),
            e_u: v4(s.e_u, s.size),
            e_v: v4(s.e_v, s.t_flat),
            view: [c.u0 as f32, c.v0 as f32, c.du as f32, c.dv as f32],
            view2: [c.w0 as f32, c.far as f32, s.photon_flux(k) as f32, 0.0],
            eye_pos: v4(e.position, e.half),
            eye_fwd: v4(e.forward, e.aspect),
            eye_right: v4(e.right, p.near),
            eye_up: v4(e.up, p.blend),
            ior: f4([s.ior[0], s.ior[1], s.ior[2], s.ior_mono]),
            absorption: v4(s.absorption, p.c),
            ramps: f4([p.min_depth, p.max_depth, p.shallow_ramp, FIXED_SCALE]),
            terrain: [lo as f32, hi as f32, has as f32, 0.0],
            post: f4([
                s.post_shift[0].x,
                s.post_shift[0].y,
                s.post_shift[2].x,
                s.post_shift[2].y,
            ]),
            fars: std::array::from_fn(|n| s.cascades[n].far as f32),
            fluxes: std::array::from_fn(|n| s.photon_flux(n) as f32),
            width: e.width as u32,
            height: e.height as u32,
            res: s.res as u32,
            cascade: k as u32,
            flags,
            wrap: s.wrap as u32,
            walls: s.walls as u32,
            _pad: 0,
        }
    }
}

/// The technique's pipelines, built once per device.
pub struct Cascaded {
    eye: wgpu::ComputePipeline,
    water: wgpu::ComputePipeline,
    terrain: wgpu::ComputePipeline,
    photons: wgpu::ComputePipeline,
    compose: wgpu::ComputePipeline,
    disperse: wgpu::ComputePipeline,
}

/// One frame's resources for a setup, bind groups included: built once, encoded every frame (the
/// water texture bound at creation is read afresh by every encode).
pub struct CascadedResources {
    /// The setup the uniforms were written from.
    pub setup: CascadedSetup,
    /// Per cascade, the uniform block its passes read (cascade 0's also serves the eye,
    /// composition and dispersion passes).
    uniforms: Vec<wgpu::Buffer>,
    /// The eye-depth pass's output, per pixel `[view depth, floor area seen, floor z, N_z]`
    /// (`Rgba32Float`, zeros where no floor is seen).
    pub eye: wgpu::Texture,
    /// Water G-buffer, `res²` texels of `[light-view depth, n.x, n.y, n.z]` (`Rgba32Float`),
    /// rewritten by each cascade in turn.
    pub gwater: wgpu::Texture,
    /// Terrain G-buffer, `res²` texels of the terrain's light-view depth (`R32Float`), rewritten
    /// by each cascade in turn; 1 texel, never read, without the terrain pass.
    pub gterrain: wgpu::Texture,
    /// Screen-space caustic maps of every cascade, fixed-point `u32` sums (`round(w · 2^14)`)
    /// laid out `cascade × height × width × 3`.
    pub acc: wgpu::Buffer,
    /// The composed image, per pixel `[r, g, b, cascade]` of relative irradiance (`Rgba32Float`).
    pub image: wgpu::Texture,
    /// The image after post-process dispersion, only under [`Dispersion::Post`].
    pub dispersed: Option<wgpu::Texture>,
    eye_bind: wgpu::BindGroup,
    /// Per cascade: water, terrain, photon bind groups.
    cascades: Vec<[wgpu::BindGroup; 3]>,
    compose_bind: wgpu::BindGroup,
    disperse_bind: Option<wgpu::BindGroup>,
    _terrain: wgpu::Texture,
    /// Bytes of GPU memory: G-buffers (shared by the cascades), one cascade's screen map, the rest.
    pub gbuffer_bytes: u64,
    /// Bytes of one cascade's screen-space caustic map (12 per pixel).
    pub cascade_map_bytes: u64,
    /// Bytes of the eye, image and dispersed textures, the terrain heights and the uniforms.
    pub other_bytes: u64,
}

impl CascadedResources {
    /// GPU memory the frame holds, bytes (the four cascades' screen maps included).
    pub fn bytes(&self) -> u64 {
        self.gbuffer_bytes + CASCADES as u64 * self.cascade_map_bytes + self.other_bytes
    }

    /// Whether `setup` fits this frame's textures and buffers (the same G-buffer resolution, eye
    /// image size, terrain pass and dispersion), so that [`set_setup`](Self::set_setup) can take
    /// it: a new camera pose, sun, water level or parameters of the same sizes.
    pub fn fits(&self, setup: &CascadedSetup) -> bool {
        let key = |s: &CascadedSetup| {
            (
                s.res,
                s.eye.width,
                s.eye.height,
                s.terrain_range.is_some(),
                s.params.dispersion == Dispersion::Post,
            )
        };
        key(setup) == key(&self.setup)
    }

    /// Take a setup that [`fits`](Self::fits): the cascades' uniform writes, only those that
    /// changed.
    pub fn set_setup(&mut self, ctx: &GpuContext, setup: &CascadedSetup) {
        debug_assert!(self.fits(setup));
        for (k, buffer) in self.uniforms.iter().enumerate() {
            let old = CascadedUniform::new(&self.setup, k);
            let new = CascadedUniform::new(setup, k);
            if bytemuck::bytes_of(&old) != bytemuck::bytes_of(&new) {
                ctx.write_pod(buffer, &new);
            }
        }
        self.setup = setup.clone();
    }
}

/// One pass of a frame, for [`Cascaded::encode_pass`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// Eye depth, once (clears the screen-space maps first).
    Eye,
    /// Cascade `k`'s water G-buffer (§3.3).
    Water(usize),
    /// Cascade `k`'s terrain G-buffer (§3.3), only with the terrain pass.
    Terrain(usize),
    /// Cascade `k`'s photons, refracted, placed and splatted (§3.4).
    Photons(usize),
    /// Composition of the cascades by eye depth (§3.5), once.
    Compose,
    /// Post-process dispersion (§3.6), once, only under [`Dispersion::Post`].
    Disperse,
}

impl Pass {
    /// The label its timestamps carry.
    pub fn label(&self) -> String {
        match self {
            Pass::Eye => "eye depth".into(),
            Pass::Water(k) => format!("water G-buffer {k}"),
            Pass::Terrain(k) => format!("terrain G-buffer {k}"),
            Pass::Photons(k) => format!("photons {k}"),
            Pass::Compose => "composition".into(),
            Pass::Disperse => "dispersion".into(),
        }
    }
}

/// What a frame read back: the eye pass, the fixed-point maps, the final image.
pub struct GpuCascadedFrame {
    /// Per pixel `[view depth, floor area seen, floor z, N_z]`, as the CPU twin's
    /// `CascadedFrame::eye`.
    pub eye: Vec<[f32; 4]>,
    /// Every cascade's fixed-point screen-space caustic map, `cascade × height × width × 3`.
    pub acc: Vec<u32>,
    /// The final image, per pixel `[r, g, b, cascade]` of relative irradiance (dispersed under
    /// [`Dispersion::Post`]).
    pub image: Vec<[f32; 4]>,
}

impl Cascaded {
    /// Build the six compute pipelines.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let c = Cascaded {
            eye: compute_pipeline(ctx, &EYE),
            water: compute_pipeline(ctx, &WATER_GBUFFER),
            terrain: compute_pipeline(ctx, &TERRAIN_GBUFFER),
            photons: compute_pipeline(ctx, &PHOTONS),
            compose: compute_pipeline(ctx, &COMPOSE),
            disperse: compute_pipeline(ctx, &DISPERSE),
        };
        ctx.check()?;
        Ok(c)
    }

    /// Allocate a frame. `water` is a texture whose red channel holds the water's heights over the
    /// scene square (an `R32Float` grid, or `GpuOcean`'s `Rgba32Float` height-and-slopes texture),
    /// read through `grid_sample`; `terrain` the floor's heights (`None`: the plane z = 0).
    pub fn frame(
        &self,
        ctx: &GpuContext,
        setup: &CascadedSetup,
        water: &wgpu::TextureView,
        terrain: Option<&Grid>,
    ) -> Result<CascadedResources, GpuError> {
        use wgpu::TextureUsages as U;
        let res = setup.res as u32;
        let (w, h) = (setup.eye.width as u32, setup.eye.height as u32);
        ctx.check_texture_size("cascaded caustic map (light-view G-buffer)", res, res)?;
        ctx.check_texture_size("cascaded screen image", w, h)?;
        let acc_bytes = screen_buffer_len(setup) as u64 * 4;
        ctx.check_buffer_size("cascaded screen-space caustic maps", acc_bytes)?;
        let storage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let f32x4 = wgpu::TextureFormat::Rgba32Float;
        let eye = ctx.texture_2d("cascaded eye depth", (w, h, 1), f32x4, storage);
        let gwater = ctx.texture_2d("cascaded water G-buffer", (res, res, 1), f32x4, storage);
        // Without the terrain pass the photons take the plane z = 0 and never read it.
        let tres = if setup.terrain_range.is_some() {
            res
        } else {
            1
        };
        let gterrain = ctx.texture_2d(
            "cascaded terrain G-buffer",
            (tres, tres, 1),
            wgpu::TextureFormat::R32Float,
            storage,
        );
        let image = ctx.texture_2d("cascaded image", (w, h, 1), f32x4, storage);
        let dispersed = (setup.params.dispersion == Dispersion::Post)
            .then(|| ctx.texture_2d("cascaded dispersed image", (w, h, 1), f32x4, storage));
        let acc = ctx.buffer(
            "cascaded screen-space caustic maps",
            acc_bytes,
            B::STORAGE | B::COPY_SRC | B::COPY_DST,
        );
        let terrain_grid = match (terrain, setup.terrain_range) {
            (Some(g), Some(_)) => g.clone(),
            _ => Grid::new(1, 1),
        };
        let terrain_tex = ctx.upload_grid("cascaded terrain heights", &terrain_grid)?;
        let terrain_view = terrain_tex.create_view(&Default::default());
        let uniforms: Vec<wgpu::Buffer> = (0..CASCADES)
            .map(|k| ctx.uniform("cascaded uniform", &CascadedUniform::new(setup, k)))
            .collect();
        let eye_view = eye.create_view(&Default::default());
        let gwater_view = gwater.create_view(&Default::default());
        let gterrain_view = gterrain.create_view(&Default::default());
        let image_view = image.create_view(&Default::default());
        let eye_bind = self
            .eye
            .bind(ctx, EYE.name, &[&uniforms[0], &terrain_view, &eye_view]);
        let cascades = uniforms
            .iter()
            .map(|u| {
                [
                    self.water
                        .bind(ctx, WATER_GBUFFER.name, &[&u, water, &gwater_view]),
                    self.terrain.bind(
                        ctx,
                        TERRAIN_GBUFFER.name,
                        &[&u, &terrain_view, &gterrain_view],
                    ),
                    self.photons.bind(
                        ctx,
                        PHOTONS.name,
                        &[&u, &gwater_view, &gterrain_view, &acc, &eye_view],
                    ),
                ]
            })
            .collect();
        let compose_bind = self.compose.bind(
            ctx,
            COMPOSE.name,
            &[&uniforms[0], &eye_view, &acc, &image_view],
        );
        let disperse_bind = dispersed.as_ref().map(|d| {
            self.disperse.bind(
                ctx,
                DISPERSE.name,
                &[
                    &uniforms[0],
                    &eye_view,
                    &image_view,
                    &d.create_view(&Default::default()),
                ],
            )
        });
        ctx.check()?;
        let screen = w as u64 * h as u64;
        Ok(CascadedResources {
            setup: setup.clone(),
            uniforms,
            eye,
            gwater,
            gterrain,
            acc,
            image,
            dispersed,
            eye_bind,
            cascades,
            compose_bind,
            disperse_bind,
            _terrain: terrain_tex,
            gbuffer_bytes: res as u64 * res as u64 * 16 + tres as u64 * tres as u64 * 4,
            cascade_map_bytes: screen * 12,
            other_bytes: screen * 16 * (2 + (setup.params.dispersion == Dispersion::Post) as u64)
                + terrain_grid.data.len() as u64 * 4
                + CASCADES as u64 * std::mem::size_of::<CascadedUniform>() as u64,
        })
    }

    fn dispatch(
        encoder: &mut wgpu::CommandEncoder,
        timer: &mut Option<&mut GpuTimer>,
        label: &str,
        pipeline: &wgpu::ComputePipeline,
        bind: &wgpu::BindGroup,
        (w, h): (u32, u32),
    ) {
        let mut pass = begin_compute(encoder, timer, label);
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind, &[]);
        pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
    }

    /// The passes of one frame, in order (the terrain G-buffer only when the setup has it, the
    /// dispersion only under post-process dispersion).
    pub fn passes(setup: &CascadedSetup) -> Vec<Pass> {
        let mut v = vec![Pass::Eye];
        for k in 0..CASCADES {
            v.push(Pass::Water(k));
            if setup.terrain_range.is_some() {
                v.push(Pass::Terrain(k));
            }
            v.push(Pass::Photons(k));
        }
        v.push(Pass::Compose);
        if setup.params.dispersion == Dispersion::Post {
            v.push(Pass::Disperse);
        }
        v
    }

    /// Record one pass (the screen-space maps are cleared before the eye pass).
    pub fn encode_pass(
        &self,
        frame: &CascadedResources,
        encoder: &mut wgpu::CommandEncoder,
        pass: Pass,
        timer: &mut Option<&mut GpuTimer>,
    ) {
        let res = frame.setup.res as u32;
        let screen = (frame.setup.eye.width as u32, frame.setup.eye.height as u32);
        let label = pass.label();
        let (pipeline, bind, size) = match pass {
            Pass::Eye => {
                encoder.clear_buffer(&frame.acc, 0, None);
                (&self.eye, &frame.eye_bind, screen)
            }
            Pass::Water(k) => (&self.water, &frame.cascades[k][0], (res, res)),
            Pass::Terrain(k) => (&self.terrain, &frame.cascades[k][1], (res, res)),
            Pass::Photons(k) => (&self.photons, &frame.cascades[k][2], (res, res)),
            Pass::Compose => (&self.compose, &frame.compose_bind, screen),
            Pass::Disperse => match &frame.disperse_bind {
                Some(b) => (&self.disperse, b, screen),
                None => return,
            },
        };
        Self::dispatch(encoder, timer, &label, pipeline, bind, size);
    }

    /// Record cascade `k`'s G-buffer passes (water, then terrain when the setup has the pass).
    pub fn encode_gbuffers(
        &self,
        frame: &CascadedResources,
        encoder: &mut wgpu::CommandEncoder,
        k: usize,
        timer: &mut Option<&mut GpuTimer>,
    ) {
        self.encode_pass(frame, encoder, Pass::Water(k), timer);
        if frame.setup.terrain_range.is_some() {
            self.encode_pass(frame, encoder, Pass::Terrain(k), timer);
        }
    }

    /// The texture a frame's image ends in (`Rgba32Float`: `[r, g, b, cascade]`, as the CPU twin's
    /// `CascadedFrame::image`).
    pub fn output<'f>(&self, frame: &'f CascadedResources) -> &'f wgpu::Texture {
        frame.dispersed.as_ref().unwrap_or(&frame.image)
    }

    /// Record the whole technique. Returns the texture the image ends in.
    pub fn encode<'f>(
        &self,
        frame: &'f CascadedResources,
        encoder: &mut wgpu::CommandEncoder,
        mut timer: Option<&mut GpuTimer>,
    ) -> &'f wgpu::Texture {
        for pass in Self::passes(&frame.setup) {
            self.encode_pass(frame, encoder, pass, &mut timer);
        }
        self.output(frame)
    }

    /// Run cascade `k`'s G-buffer passes alone and read them back (water, terrain).
    pub fn gbuffers(
        &self,
        ctx: &GpuContext,
        frame: &CascadedResources,
        k: usize,
    ) -> Result<(Vec<[f32; 4]>, Vec<f32>), GpuError> {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_gbuffers(frame, &mut encoder, k, &mut None);
        ctx.queue.submit([encoder.finish()]);
        Ok((
            ctx.read_texture(&frame.gwater)?,
            ctx.read_texture(&frame.gterrain)?,
        ))
    }

    /// Run the technique once on `frame` and read everything back, each pass timed into `timer`
    /// when there is one (the viewer's overlay).
    pub fn run(
        &self,
        ctx: &GpuContext,
        frame: &CascadedResources,
        mut timer: Option<&mut GpuTimer>,
    ) -> Result<GpuCascadedFrame, GpuError> {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let out = self.encode(frame, &mut encoder, timer.as_deref_mut());
        ctx.submit_timed(encoder, timer.as_deref());
        Ok(GpuCascadedFrame {
            eye: ctx.read_texture(&frame.eye)?,
            acc: ctx.read_buffer(&frame.acc)?,
            image: ctx.read_texture(out)?,
        })
    }

    /// The whole technique from height grids: upload the water, build a frame, run it, each pass
    /// timed into `timer` when there is one.
    pub fn caustics(
        &self,
        ctx: &GpuContext,
        setup: &CascadedSetup,
        water: &Grid,
        terrain: Option<&Grid>,
        timer: Option<&mut GpuTimer>,
    ) -> Result<GpuCascadedFrame, GpuError> {
        let tex = ctx.upload_grid("cascaded water heights", water)?;
        let view = tex.create_view(&Default::default());
        let frame = self.frame(ctx, setup, &view, terrain)?;
        self.run(ctx, &frame, timer)
    }
}
