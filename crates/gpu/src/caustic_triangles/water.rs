//! The water surface as the generator: its frame, the water photon pass (`water_photon.wgsl`),
//! the copy band of tiling water (`band_bound.wgsl`, `band.wgsl`) and the pool's walls as
//! receivers.

use caustics_core::grid::Grid;
use caustics_core::techniques::caustic_triangles::DistanceMap;
use caustics_core::techniques::caustic_triangles::water::WaterSetup;
use caustics_core::walls::{Wall, WallMaps};

use super::{
    BAND_BOUND, COPY_BAND, CausticTriangles, CausticTrianglesUniform, GeneratorFrame,
    Reconstruction, WaterPhotonUniform,
};
use std::sync::Arc;

use crate::pass::{Bind, begin_compute, wall_maps_texture};
use crate::receivers::{ReceiverFrame, heights_texture};
use crate::{GpuContext, GpuError, GpuTimer, WaterTextures};
use wgpu::BufferUsages as B;

/// Tiling water's copy band on the GPU: the bound pass's buffer and bind group, the band pass's, and
/// the height grid the bound pass covers.
struct BandPasses {
    bound: wgpu::Buffer,
    bound_bind: wgpu::BindGroup,
    band: wgpu::BindGroup,
    grid: (u32, u32),
}

/// The water surface as the generator: a [`GeneratorFrame`] whose photon image the water photon
/// pass writes from a height texture (no distance map), and whose shifted copies of tiling water
/// the copy band pass fits from the same texture. Built once per lattice, map and height-grid size;
/// every encode reads the heights afresh (the caller's texture, [`CausticTriangles::water_frame_with_water`],
/// or its own).
pub struct WaterFrame {
    /// The floor's generator frame: photon image, vertex irradiance, merge pyramid, floor map.
    pub frame: GeneratorFrame,
    /// The setup its uniforms hold; the band of `setup.setup.water` is the lattice's (every
    /// quad): the copy band pass narrows it on the GPU.
    pub setup: WaterSetup,
    /// The heights it uploaded itself ([`CausticTriangles::water_frame`]); `None` when it reads
    /// the caller's.
    pub heights: Option<wgpu::Texture>,
    /// The grid size of the heights it reads.
    pub grid: (u32, u32),
    /// The floor's water photon pass uniform ([`WaterPhotonUniform`]).
    pub water_uniform: wgpu::Buffer,
    water_bind: wgpu::BindGroup,
    /// The copy band pass's bind group (tiling water only).
    band_bind: Option<BandPasses>,
    /// The walls' receivers when the setup has walls ([`WaterSetup::with_walls`]).
    pub walls: Option<WallFrames>,
    /// The terrain's receivers when the setup has them ([`WaterSetup::with_receivers`]): the
    /// photons meet their heights, the triangles are drawn in the light's space, and the lookup
    /// writes the floor map.
    pub receivers: Option<ReceiverFrame>,
}

/// The pool's walls as receivers of a water frame (CPU twin `water::wall_caustics`):
/// each wall has its own photon image (the rays extended to its plane), vertex irradiance and
/// caustic triangles, a [`GeneratorFrame`] drawing into its layer of one 2-D array texture
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
    /// The wall's generator frame, drawing into its layer of [`WallFrames::texture`].
    pub frame: GeneratorFrame,
    /// The wall's water photon pass uniform ([`WaterPhotonUniform::for_receiver`]).
    pub water_uniform: wgpu::Buffer,
    water_bind: wgpu::BindGroup,
}

impl WaterFrame {
    /// The floor map: the receivers' lookup where the frame has receivers, else the triangles'.
    pub fn floor_map(&self) -> &wgpu::Texture {
        self.receivers
            .as_ref()
            .map_or(&self.frame.map, |r| &r.floor)
    }

    /// Whether `ws` fits this frame's buffers and bind groups (the same lattice, map size, wrap
    /// and receivers), so that [`set_setup`](Self::set_setup) can take it.
    pub fn fits(&self, ws: &WaterSetup) -> bool {
        let f = &self.setup.setup.floor;
        let same_receivers = match (&ws.receivers, &self.setup.receivers) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        same_receivers
            && (
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
            ctx.write_pod(&self.frame.uniform, &ct);
        }
        if bytemuck::bytes_of(&w) != bytemuck::bytes_of(&old_w) {
            ctx.write_pod(&self.water_uniform, &w);
        }
        if let Some(walls) = &mut self.walls {
            for (wall, wf) in Wall::ALL.into_iter().zip(&mut walls.walls) {
                let setup = ws.receiver_setup(Some(wall), &walls.layout);
                let old_ct = CausticTrianglesUniform::new(&wf.frame.setup, &no_distance_map());
                let ct = CausticTrianglesUniform::new(&setup, &no_distance_map());
                if bytemuck::bytes_of(&ct) != bytemuck::bytes_of(&old_ct) {
                    ctx.write_pod(&wf.frame.uniform, &ct);
                }
                let old_w = WaterPhotonUniform::for_receiver(&self.setup, Some(wall));
                let w = WaterPhotonUniform::for_receiver(ws, Some(wall));
                if bytemuck::bytes_of(&w) != bytemuck::bytes_of(&old_w) {
                    ctx.write_pod(&wf.water_uniform, &w);
                }
                wf.frame.setup = setup;
            }
        }
        self.setup = ws.clone();
        self.frame.setup = ws.setup.clone();
    }

    /// The bound pass's last result (the grid's steepest slope, its lowest and highest height:
    /// the CPU twin's `water::band_bound`), `None` for water that does not tile: a readback, for
    /// tests and tools.
    pub fn read_band_bound(&self, ctx: &GpuContext) -> Result<Option<[f32; 3]>, GpuError> {
        let Some(b) = &self.band_bind else {
            return Ok(None);
        };
        // reduce.wgsl's order-preserving map, undone.
        let unordered = |u: u32| {
            f32::from_bits(if u & 0x8000_0000 != 0 {
                u & 0x7fff_ffff
            } else {
                !u
            })
        };
        let raw: Vec<u32> = ctx.read_buffer(&b.bound)?;
        Ok(Some([
            unordered(raw[0]),
            -unordered(raw[1]),
            unordered(raw[2]),
        ]))
    }

    /// GPU memory the frame holds, bytes: its generator frame, the heights it uploaded, the
    /// photon uniforms, the receivers and the walls' frames and texture.
    pub fn bytes(&self) -> u64 {
        self.frame.bytes()
            + self
                .heights
                .as_ref()
                .map_or(0, |_| (self.grid.0 * self.grid.1) as u64 * 4)
            + 48
            + self.receivers.as_ref().map_or(0, |r| r.bytes())
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

impl CausticTriangles {
    /// A water frame that uploads `heights` itself, for one run (the run-once form and the tests).
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
        let water_uniform = ctx.uniform(
            "caustic-triangles water photons",
            &WaterPhotonUniform::new(ws),
        );
        let view = &water.heights;
        let receivers = match &ws.receivers {
            Some(r) => Some(
                self.lookup
                    .frame(ctx, r, &frame.map, ws.wrap(), glam::DVec3::ZERO)?,
            ),
            None => None,
        };
        let heights_of_receivers = match &receivers {
            Some(r) => r.heights.create_view(&Default::default()),
            None => heights_texture(ctx, None)?.create_view(&Default::default()),
        };
        let water_bind = self.water_photon.bind(
            ctx,
            "caustic-triangles water photons",
            &[
                &water_uniform,
                view,
                &frame.photons,
                &frame.paths,
                &heights_of_receivers,
            ],
        );
        let band_bind = ws.wrap().then(|| {
            let bound = ctx.buffer(BAND_BOUND.name, 16, B::STORAGE | B::COPY_DST | B::COPY_SRC);
            let bound_bind =
                self.band_bound
                    .bind(ctx, BAND_BOUND.name, &[&water_uniform, view, &bound]);
            let band = self.copy_band.bind(
                ctx,
                COPY_BAND.name,
                &[&water_uniform, &frame.uniform, &bound, &frame.copy_band],
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
            Some(self.wall_frames(ctx, ws, view, &heights_of_receivers)?)
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
            receivers,
        })
    }

    /// The walls' receivers of a water frame with walls, reading the heights through `heights`.
    fn wall_frames(
        &self,
        ctx: &GpuContext,
        ws: &WaterSetup,
        heights: &wgpu::TextureView,
        receiver_heights: &wgpu::TextureView,
    ) -> Result<WallFrames, GpuError> {
        let f = &ws.setup.floor;
        let layout = WallMaps::for_floor_map(f.width, f.height, ws.size, ws.depth);
        let label = "caustic-triangles wall maps";
        let texture = wall_maps_texture(ctx, label, &layout, self.map_format)?;
        let mut walls = Vec::with_capacity(4);
        for wall in Wall::ALL {
            let setup = ws.receiver_setup(Some(wall), &layout);
            let frame = self.frame_into_layer(
                ctx,
                &setup,
                &no_distance_map(),
                Some((&texture, wall.index() as u32)),
            )?;
            let water_uniform = ctx.uniform(
                "caustic-triangles wall photons",
                &WaterPhotonUniform::for_receiver(ws, Some(wall)),
            );
            let water_bind = self.water_photon.bind(
                ctx,
                "caustic-triangles wall photons",
                &[
                    &water_uniform,
                    heights,
                    &frame.photons,
                    &frame.paths,
                    receiver_heights,
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
        if let Some(r) = &wf.receivers {
            self.lookup.encode(r, encoder, timer.as_deref_mut());
        }
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
}
