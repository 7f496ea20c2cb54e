//! The light cube map of a point light: each generator's caustic triangles on its faces
//! (`cube.wgsl`) and its surfaces into the shadow distances (`shadow.wgsl`).

use caustics_core::techniques::caustic_triangles::cube::FAR;

use super::{CausticTriangles, GeneratorFrame};
use crate::pass::{Bind, MAP_TARGET, begin_compute, begin_render};
use crate::{GpuContext, GpuError, GpuTimer};
use wgpu::BufferUsages as B;

/// The light cube map of a point light on the GPU (paper 4, §4.2-4.3; CPU twin
/// `caustics_core::techniques::caustic_triangles::cube`): the six `C x C` faces stacked in one
/// `C x 6C` texture (face `f` in rows `f C .. (f + 1) C`, one viewport and scissor per face), `(Σ E,
/// Σ E d)` in red and green, and the shadow distances in a storage buffer. Every generator adds
/// into the same target.
pub struct LightCubeTarget {
    /// Side `C` of one face, texels.
    pub resolution: u32,
    /// The `C x 6C` render target: red `Σ E` (floor units), green `Σ E d` (`d` the light's
    /// distance to the receiver point, world units).
    pub texture: wgpu::Texture,
    /// View of `texture`, drawn into and sampled by the camera pass.
    pub view: wgpu::TextureView,
    /// `6 C²` `f32` distances from the light to the first surface per texel (index
    /// `(face C + row) C + col`), `FAR` where none: the shadow map of the direct light.
    pub shadow: wgpu::Buffer,
}

/// One generator's bindings to a [`LightCubeTarget`].
pub struct CubeBinds {
    cube: wgpu::BindGroup,
    shadow: wgpu::BindGroup,
}

impl CausticTriangles {
    /// Allocate a light cube map of `resolution` texels a face side; reset it with
    /// [`reset_cube`](Self::reset_cube) before the first generator draws into it.
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
            MAP_TARGET,
        );
        let view = texture.create_view(&Default::default());
        let shadow = ctx.buffer(
            "caustic-triangles light cube shadow distances",
            n * 4,
            B::STORAGE | B::COPY_DST | B::COPY_SRC,
        );
        ctx.check()?;
        Ok(LightCubeTarget {
            resolution,
            texture,
            view,
            shadow,
        })
    }

    /// Bind `frame`'s generator (its uniform, photon image, vertex irradiance, merge pyramid and
    /// distance map) to `target` for [`encode_cube`](Self::encode_cube).
    pub fn cube_binds(
        &self,
        ctx: &GpuContext,
        frame: &GeneratorFrame,
        target: &LightCubeTarget,
    ) -> CubeBinds {
        let cube = self.cube.bind(
            ctx,
            "caustic-triangles light cube map",
            &[
                &frame.uniform,
                &frame.photons,
                &frame.irradiance,
                &frame.pyramid,
            ],
        );
        let shadow = self.shadow.bind(
            ctx,
            "caustic-triangles light cube shadow distances",
            &[&frame.uniform, &frame.dm_buffer, &target.shadow],
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
        frame: &GeneratorFrame,
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
            let mut pass = begin_render(encoder, &mut timer, label, &[&target.view], clear);
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
}
