//! Each object's caustics map (§3.2), as the viewer shows it.

use crate::Result;
use crate::plot::{Picture, rgb_picture};
use crate::techniques::buffers::{Buffer, BufferDesc, BufferInput, Index, Needs, check_index};
use crate::water::sample_grid;

use super::{VolumesInput, VolumesParams, VolumesSetup, caustics};

pub(super) const BUFFERS: &[BufferDesc] = &[BufferDesc {
    key: "object",
    label: "object {k}: caustics map",
    index: Some(Index {
        name: "object",
        count: |_, has| has.objects,
    }),
    needs: Needs::Objects,
}];

/// Object `k`'s caustics map, in its texture's own layout (the view along the refracted sun).
pub(super) fn draw_buffer(input: &BufferInput, buffer: Buffer) -> Result<Picture> {
    let (scene, surface) = input.scene_with_water()?;
    let params = VolumesParams::from_table(input.params)?;
    let vin = VolumesInput::from_scene(&scene)?;
    let count = vin.objects.len();
    let k = check_index(buffer.index, count, "objects")?;
    let setup = VolumesSetup::new(&params, &vin)?;
    let water = scene.water.as_ref().expect("set by scene_with_water");
    let n = (vin.size / setup.lattice.cell).round() as usize;
    let heights = sample_grid(surface, n, n, water.size);
    let out = caustics(&setup, &vin, &heights, water.wrap);
    let maps = &out.objects[k];
    let side = (maps.caustics.len() as f64).sqrt() as usize;
    Ok(rgb_picture(
        side,
        side,
        |t| (maps.depth[t][1..].iter().any(|v| *v != 0.0)).then(|| maps.caustics[t]),
        &format!("object {k} of {count}, relative irradiance"),
    ))
}
