//! The pre-pass's and pass 1's textures as the viewer shows them (`techniques::buffers`): each
//! sample's hit offset and flux (§5) and a channel of pass 1 (Fig. 5), drawn by the CPU twin's
//! passes for any front end.

use crate::Result;
use crate::grid::Grid;
use crate::plot::{Picture, flip_rows, heat_picture};
use crate::techniques::buffers::{Buffer, BufferDesc, BufferInput, Index, Needs, no_buffers};
use crate::techniques::heights_for;

use super::{MAX_M, Tier, YukselParams, YukselSetup, pass1, prepass};

/// The pre-pass's and pass 1's textures, as the viewer shows them.
pub(super) const BUFFERS: &[BufferDesc] = &[
    BufferDesc {
        key: "yuksel-offset",
        label: "yuksel pre-pass: hit offset",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "yuksel-flux",
        label: "yuksel pre-pass: flux",
        index: None,
        needs: Needs::Anything,
    },
    BufferDesc {
        key: "yuksel-channel",
        label: "yuksel pass 1: channel {k}",
        // M + 1 channels; with M chosen from the water, as many as it may choose (a channel past
        // the chosen M is drawn as the last).
        index: Some(Index {
            name: "channel",
            count: |own, _| {
                own.get("m")
                    .and_then(|v| v.as_integer())
                    .map_or(MAX_M, |m| m.max(0) as u32)
                    + 1
            },
        }),
        needs: Needs::Anything,
    },
];

/// The pre-pass (§4.1: each sample's hit offset and flux) and pass 1 (§4.2: channel `k` of the
/// `M + 1`, what each sample row gave the row `k - M/2` away), at the region's level.
pub(super) fn draw_buffer(input: &BufferInput, buffer: Buffer) -> Result<Picture> {
    let (w, surface) = input.water()?;
    let n = input.map_size;
    let heights = heights_for(w, surface, n, n);
    let params = YukselParams::from_table(input.params)?;
    let mut setup = YukselSetup::new(
        &params,
        n,
        n,
        w.size,
        w.depth,
        w.ior,
        w.absorption,
        w.wrap,
        input.light,
    )?;
    setup.fit_region(&heights);
    // The samples are the region's level's (k × k per pixel of it).
    let coarse = setup.at_level(setup.region.level);
    let pre = prepass(&coarse, &heights);
    let (pw, ph) = coarse.prepass_size();
    match buffer.desc.key {
        "yuksel-offset" => {
            // δ in pixels: red for x, green for y, mid-grey at no offset, saturating at N/2.
            let reach = (setup.region.n / 2).max(1) as f32;
            let rgba = flip_rows(pw, ph, |t| {
                let p = pre[t];
                let c = |d: f32| ((0.5 + 0.5 * d / reach).clamp(0.0, 1.0) * 255.0) as u8;
                [c(p[0]), c(p[1]), 128, 255]
            });
            Ok(Picture {
                width: pw as u32,
                height: ph as u32,
                rgba,
                legend: format!("hit offset: red x, green y, grey 0, saturated at ±{reach} px"),
            })
        }
        "yuksel-flux" => {
            // Each of a pixel's k × k samples carries 1 / k² of its light: times k², 1 is what
            // flat water gives a whole pixel, whatever k.
            let g = Grid {
                cols: pw,
                rows: ph,
                // A pixel of `t × t` records: each carries 1/t² of its light.
                data: pre
                    .iter()
                    .map(|p| {
                        let t = Tier::side(p[2], coarse.subsamples) as f32;
                        p[3] * t * t
                    })
                    .collect(),
            };
            Ok(heat_picture(&g, 1.5, |top| {
                format!(
                    "sample flux x t² (its t x t share of a pixel; 1: flat water): black 0, white {top:.2}"
                )
            }))
        }
        "yuksel-channel" => {
            let p1 = pass1(&setup, &pre, 0);
            let (w1, h1) = setup.pass1_size();
            let ch = setup.region.m + 1;
            let k = (buffer.index as usize).min(setup.region.m);
            let g = Grid {
                cols: w1,
                rows: h1,
                data: (0..w1 * h1).map(|t| p1[t * ch + k]).collect(),
            };
            Ok(heat_picture(&g, 1e-6, |top| {
                format!(
                    "channel {k} of {ch} (row offset {}): black 0, white {top:.2}",
                    k as i64 - setup.region.m as i64 / 2 - setup.region.shift[1] as i64
                )
            }))
        }
        _ => no_buffers(input, buffer),
    }
}
