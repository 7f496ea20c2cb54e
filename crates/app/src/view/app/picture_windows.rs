//! The map and buffer windows' pictures: the techniques' floor maps, their difference, and the
//! buffer a technique makes on the way, refreshed only when their inputs changed.

use anyhow::Result;

use caustics_core::techniques::buffers::BufferInput;

use super::super::pictures;
use super::super::ui::Shown;
use super::{BufferKey, Viewer};

impl Viewer {
    /// Refresh the map and buffer pictures whose windows are open and whose inputs changed.
    pub(super) fn update_pictures(&mut self) -> Result<()> {
        let m = &mut self.model;
        // The GPU frame's maps stay on the GPU: read back for the window when they are new or
        // not yet read (the window opened on a still frame); on the CPU path the slots hold theirs.
        if m.show_map && !m.quality.cpu_image {
            let sides = m.sides();
            self.renderer
                .read_maps(&mut m.slots[..sides], m.stats.rendered)?;
        }
        let ctx = self.renderer.gpu().expect("the viewer always has a device");
        if m.show_map {
            for k in 0..m.sides() {
                let slot = &m.slots[k];
                if !slot.map_changed && m.maps[k].size.is_some() {
                    continue;
                }
                m.maps[k] = match (&slot.caustics, &slot.error) {
                    (Some(caustics), _) => self.map_images[k].picture(
                        ctx,
                        &mut self.egui_renderer,
                        pictures::caustics_picture(caustics, slot.walls.as_ref()),
                    ),
                    (None, Some(e)) => Shown::error(e.clone()),
                    (None, None) => Shown::error("no water, no map"),
                };
            }
            if m.split
                && (m.slots[0].map_changed || m.slots[1].map_changed || m.difference.size.is_none())
            {
                m.difference = match (m.slots[0].floor_map(), m.slots[1].floor_map()) {
                    (Some(a), Some(b)) => match pictures::difference_picture(a, b) {
                        Some(p) => self
                            .difference_image
                            .picture(ctx, &mut self.egui_renderer, p),
                        None => Shown::error("the maps differ in size"),
                    },
                    _ => Shown::error("needs two floor maps"),
                };
            }
            // Shown: a redraw without a new map (a still frame) builds and uploads nothing.
            let sides = m.sides();
            for slot in &mut m.slots[..sides] {
                slot.map_changed = false;
            }
        }
        if m.show_buffers
            && let Some(render) = self.last_render.as_ref()
        {
            let key = BufferKey {
                buffer: m.buffer,
                choice: m.slots[0].choice.clone(),
                render: render.clone(),
            };
            if self.last_buffer.as_ref() != Some(&key) {
                // The GPU frame keeps its water on the GPU: the buffer views (CPU twins) take the
                // surface of this frame when they need it.
                if self.renderer.surface.is_none()
                    && let Some(w) = m.water.as_mut()
                {
                    self.renderer.surface = Some(self.renderer.cpu_surface(w)?);
                }
                let ctx = self.renderer.gpu().expect("the viewer always has a device");
                let water = m
                    .water
                    .as_ref()
                    .zip(self.renderer.surface.as_deref())
                    .map(|(w, s)| (w.technique_water(), s));
                let choice = &m.slots[0].choice;
                let spec = choice.spec()?;
                let input = BufferInput {
                    params: &spec.params,
                    scene: &self.renderer.scene,
                    water,
                    light: m.sun.direction(),
                    map_size: m.quality.map_size as usize,
                };
                m.buffer_shown = match caustics_core::techniques::describe::picture(
                    choice.entry,
                    m.buffer,
                    &input,
                ) {
                    Ok(p) => self.buffer_image.picture(ctx, &mut self.egui_renderer, p),
                    Err(e) => Shown::error(format!("{e:#}")),
                };
                self.last_buffer = Some(key);
            }
        }
        Ok(())
    }
}
