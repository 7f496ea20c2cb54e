//! The generator's stages as the viewer shows them: its layered distance map (§3), the photon hit
//! location image and the power each photon carries (§4.1), the irradiance at each photon-image
//! vertex (§5), and a point light's light cube map (§4.2).

use crate::grid::Grid;
use crate::plot::{Picture, flip_rows, heat, heat_picture};
use crate::techniques::buffers::{Buffer, BufferDesc, BufferInput, Index, Needs, no_buffers};
use crate::{Error, Result};

use super::{
    CausticTrianglesParams, CausticTrianglesSetup, DistanceMap, GlassScene, camera, cube,
    irradiance_pass, photon_pass, photon_power, water,
};

pub(super) const BUFFERS: &[BufferDesc] = &[
    BufferDesc {
        key: "photon-hits",
        label: "photon hit location image",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "photon-power",
        label: "photon power",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "vertex-irradiance",
        label: "vertex irradiance",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "distance-layer",
        label: "distance map: layer {k}",
        index: Some(Index {
            name: "layer",
            count: |own, _| {
                own.get("layers")
                    .and_then(|v| v.as_integer())
                    .unwrap_or(1)
                    .max(1) as u32
            },
        }),
        needs: Needs::NoWater,
    },
    BufferDesc {
        key: "light-cube",
        label: "light cube map",
        index: None,
        needs: Needs::PointLight,
    },
];

pub(super) fn draw_buffer(input: &BufferInput, buffer: Buffer) -> Result<Picture> {
    match buffer.desc.key {
        "light-cube" => light_cube_picture(input),
        "photon-hits" | "photon-power" | "vertex-irradiance" | "distance-layer" => {
            generator_picture(buffer, input)
        }
        _ => no_buffers(input, buffer),
    }
}

/// The buffers of the scene's generator, from the CPU twin's passes: its water surface where it
/// has water, else its first glass object.
fn generator_picture(buffer: Buffer, input: &BufferInput) -> Result<Picture> {
    let params = CausticTrianglesParams::from_table(input.params)?;
    let distance_layer = buffer.desc.key == "distance-layer";
    let (setup, photons) = match input.water {
        Some((w, surface)) => {
            if distance_layer {
                return Err(Error::Unavailable(
                    "the water surface is traced as a height field, not a distance map".into(),
                ));
            }
            let n = input.map_size;
            let ws = water::WaterSetup::new(&params, w, input.light, n, n)?;
            let heights = crate::techniques::heights_for(w, surface, n, n);
            let (photons, _) = water::photon_pass(&ws, &heights);
            (ws.setup, photons)
        }
        None => {
            let gs = GlassScene::from_scene(input.scene, 0)?;
            let dm =
                DistanceMap::build(&gs, params.cube_resolution as usize, params.layers as usize);
            if distance_layer {
                return Ok(distance_picture(&dm, buffer.index as usize));
            }
            let setup = CausticTrianglesSetup::new(&params, &gs)?;
            let photons = photon_pass(&setup, &dm);
            (setup, photons)
        }
    };
    let p = setup.p;
    let valid = |t: &[f32; 4]| t[2] >= 0.0;
    match buffer.desc.key {
        "photon-hits" => {
            // The floor position each photon reached, as a colour: red along x, green along y
            // over the floor square; black where the photon is invalid (missed the generator,
            // left the floor, or ran out of events).
            let size = input.scene.size as f32;
            let rgba = flip_rows(p, p, |t| {
                let h = &photons[t];
                if !valid(h) {
                    return [0, 0, 0, 255];
                }
                let c = |v: f32| ((v / size).clamp(0.0, 1.0) * 255.0) as u8;
                [c(h[0]), c(h[1]), 96, 255]
            });
            let count = photons.iter().filter(|h| valid(h)).count();
            Ok(Picture {
                width: p as u32,
                height: p as u32,
                rgba,
                legend: format!(
                    "{count} of {} photons valid: red = floor x, green = floor y, black invalid",
                    p * p
                ),
            })
        }
        "photon-power" => {
            let g = Grid {
                cols: p,
                rows: p,
                data: photons.iter().map(|h| h[2].max(0.0)).collect(),
            };
            Ok(heat_picture(&g, 1e-12, |top| {
                format!(
                    "photon power: black 0, white {top:.3e} floor-area units (total {:.4})",
                    photon_power(&photons)
                )
            }))
        }
        _ => {
            let e = irradiance_pass(&setup, &photons);
            // Irradiance spans decades between the focus and the rim: a log scale.
            let g = Grid {
                cols: p,
                rows: p,
                data: e.iter().map(|v| (1.0 + v.max(0.0)).log10()).collect(),
            };
            Ok(heat_picture(&g, 1e-6, |top| {
                format!(
                    "vertex irradiance, log scale: black 0, white {:.1} (relative to the unobstructed light)",
                    10f32.powf(top) - 1.0
                )
            }))
        }
    }
}

/// The light cube map of a point light (§4.2): every glass generator's caustic triangles drawn
/// onto its six faces, as the CPU twin's `render_scene` does.
fn light_cube_picture(input: &BufferInput) -> Result<Picture> {
    let params = CausticTrianglesParams::from_table(input.params)?;
    let gens = camera::generators(input.scene, &params)?;
    let Some(light) = gens[0].setup.point else {
        return Err(Error::Unavailable(
            "the light cube map belongs to a point or spot light; this scene has the sun".into(),
        ));
    };
    let mut cube = cube::LightCube::new(params.light_cube as usize, light.position);
    for g in &gens {
        let out = super::caustics(&g.setup, &g.dm);
        cube::cube_triangles_pass(&g.setup, &out.photons, &out.irradiance, &mut cube);
    }
    let c = cube.resolution;
    // Irradiance spans decades between a focus and the rest: a log scale, as for the vertices.
    let log: Vec<f32> = cube
        .caustic
        .iter()
        .map(|t| (1.0 + t[0].max(0.0)).log10())
        .collect();
    let top = log.iter().copied().fold(1e-6f32, f32::max);
    let mut rgba = Vec::with_capacity(6 * c * c * 4);
    for row in (0..c).rev() {
        for face in 0..6 {
            for col in 0..c {
                let [r, g, b] = heat(log[(face * c + row) * c + col] / top);
                rgba.extend([r, g, b, 255]);
            }
        }
    }
    Ok(Picture {
        width: 6 * c as u32,
        height: c as u32,
        rgba,
        legend: format!(
            "caustic irradiance on faces +x −x +y −y +z −z, log scale: black 0, white {:.1}",
            10f32.powf(top) - 1.0
        ),
    })
}

/// The six faces of one layer of a layered distance map side by side (+x, −x, +y, −y, +z, −z):
/// the glass's distance through a heat ramp (white at the map's radius), diffuse occluders in
/// blue, no surface black.
fn distance_picture(dm: &DistanceMap, layer: usize) -> Picture {
    let c = dm.resolution;
    let layer = layer.min(dm.layers.saturating_sub(1));
    let r = dm.radius.max(1e-9) as f32;
    let mut rgba = Vec::with_capacity(6 * c * c * 4);
    for row in (0..c).rev() {
        for face in 0..6 {
            for col in 0..c {
                let s = dm.texels[((layer * 6 + face) * c + row) * c + col][3];
                let [cr, cg, cb] = if s > 0.0 {
                    heat(0.15 + 0.85 * (s / r))
                } else if s < 0.0 {
                    let t = (-s / r).clamp(0.0, 1.0);
                    [40, (60.0 + 100.0 * t) as u8, (140.0 + 115.0 * t) as u8]
                } else {
                    [0, 0, 0]
                };
                rgba.extend([cr, cg, cb, 255]);
            }
        }
    }
    Picture {
        width: 6 * c as u32,
        height: c as u32,
        rgba,
        legend: format!(
            "layer {layer} of {}, faces +x −x +y −y +z −z: glass by distance (white {r:.3}), occluders blue, none black",
            dm.layers
        ),
    }
}
