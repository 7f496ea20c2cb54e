//! Recording a frame's passes: depth textures and shadow map, water, slices, floor, walls, shade
//! and the refracted view.

use caustics_core::walls::Wall;

use super::{Volumes, VolumesFrame};
use crate::GpuTimer;
use crate::pass::{begin_compute, begin_render};

impl Volumes {
    /// Record the technique's passes for `frame`.
    pub fn encode(
        &self,
        frame: &VolumesFrame,
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
        if let Some(r) = &frame.receivers {
            let mut pass = begin_compute(encoder, &mut timer, "volumes meet");
            pass.set_pipeline(&self.meet);
            pass.set_bind_group(0, &r.meet_bind, &[]);
            let n = (r.hits.size() / 16) as u32;
            pass.dispatch_workgroups(n.div_ceil(64), 1, 1);
        }
        for (k, o) in frame.objects.iter().enumerate() {
            let label = format!("volumes slices, object {k}");
            let mut pass = begin_render(encoder, &mut timer, &label, &[&o.caustics_view], true);
            pass.set_pipeline(&self.slices);
            pass.set_bind_group(0, &o.slices_bind, &[]);
            pass.draw(0..o.vertices, 0..1);
        }
        {
            let mut pass = begin_render(
                encoder,
                &mut timer,
                "volumes floor",
                &[&frame.floor_view],
                true,
            );
            pass.set_pipeline(match frame.receivers {
                None => &self.floor,
                Some(_) => &self.floor_receivers,
            });
            pass.set_bind_group(0, &frame.floor_bind, &[]);
            let triangles = 2 * frame.setup.lattice.nx * frame.setup.lattice.ny;
            pass.draw(0..(3 * triangles) as u32, 0..1);
        }
        if let Some(r) = &frame.receivers {
            self.lookup.encode(&r.frame, encoder, timer.as_deref_mut());
        }
        if let Some(walls) = &frame.walls {
            let triangles = 2 * frame.setup.lattice.nx * frame.setup.lattice.ny;
            for (k, (layer, map)) in walls.layers.iter().zip(&walls.layout.maps).enumerate() {
                let label = format!("volumes wall {}", Wall::ALL[k].suffix());
                let mut pass = begin_render(encoder, &mut timer, &label, &[layer], true);
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
}
