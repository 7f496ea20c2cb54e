//! The pictures and error tables of docs/volumes.md: technique `volumes` (its CPU twin; the GPU passes
//! agree with it, crates/gpu/tests/volumes_gpu.rs) against the reference with mesh receivers on the
//! built-in scene `objects`, for 5 and 50 reference planes (the paper's Fig. 6).
//!
//! `cargo run --release -p caustics-core --example volumes_pictures [-- OUT_DIR]`
//! (default `docs/images/volumes`).

use std::path::{Path, PathBuf};
use std::time::Instant;

use caustics_core::mesh::MeshBvh;
use caustics_core::optics::{fresnel_transmittance, height_field_normal, refract};
use caustics_core::scene::Scene;
use caustics_core::techniques::volumes::reference::{
    MeshReference, MeshReferenceOptions, comparable, mesh_reference,
};
use caustics_core::techniques::volumes::representation::covered;
use caustics_core::techniques::volumes::view::{
    SKY, ViewCamera, flat_floor_light, floor_texel, surface_hit, view_pass,
};
use caustics_core::techniques::volumes::{self, VolumesInput, VolumesParams, VolumesSetup};
use caustics_core::water::GridSurface;
use glam::DVec3;

/// The floor's albedo in the refracted view: the pool tiles' colour.
const FLOOR_ALBEDO: DVec3 = DVec3::new(0.62, 0.78, 0.82);

/// The refracted view as the reference sees it: each viewing ray refracted at the same surface and
/// traced exactly (BVHs) to the first object or the floor, lit by the reference's irradiance there
/// (the object map's texel the hit projects into), with the same Fresnel, sky and absorption as the
/// technique's view pass.
fn reference_view(
    setup: &VolumesSetup,
    input: &VolumesInput,
    cam: &ViewCamera,
    heights: &caustics_core::grid::Grid,
    wrap: bool,
    reference: &MeshReference,
) -> Vec<[f32; 3]> {
    let bvhs: Vec<MeshBvh> = input.objects.iter().map(|o| o.mesh.bvh()).collect();
    let sky = DVec3::from(SKY);
    let ambient = setup.params.ambient;
    (0..cam.width * cam.height)
        .map(|k| {
            let d = cam.dir(k % cam.width, k / cam.width);
            if d.z >= 0.0 {
                return sky.as_vec3().to_array();
            }
            let (s, grad) = surface_hit(setup, heights, wrap, cam.position, d);
            let n = height_field_normal(grad);
            let cos_i = -d.dot(n);
            let Some(r) = refract(d, n, setup.eta).filter(|_| cos_i > 0.0) else {
                return sky.as_vec3().to_array();
            };
            let tr = fresnel_transmittance(cos_i, 1.0, setup.ior);
            let t_floor = s.z / -r.z;
            let mut best: Option<(usize, f64)> = None;
            for (o, (obj, bvh)) in input.objects.iter().zip(&bvhs).enumerate() {
                let limit = best.map_or(t_floor, |b| b.1);
                if let Some((t, _)) = bvh.intersect(&obj.mesh, s, r, limit) {
                    best = Some((o, t));
                }
            }
            let (path, under) = match best {
                Some((o, t)) => {
                    let view = &setup.objects[o].view;
                    let px = view.to_pixel(view.to_frame(s + r * t));
                    let res = view.res as f64;
                    let e = if px.x >= 0.0 && px.y >= 0.0 && px.x < res && px.y < res {
                        let e = reference.objects[o][px.y as usize * view.res + px.x as usize];
                        DVec3::new(e[0] as f64, e[1] as f64, e[2] as f64)
                    } else {
                        DVec3::ZERO
                    };
                    (t, input.objects[o].albedo * (e + ambient))
                }
                None => {
                    let e = floor_texel(&reference.floor, (s + r * t_floor).truncate())
                        .unwrap_or_else(|| flat_floor_light(setup));
                    (t_floor, FLOOR_ALBEDO * (e + ambient))
                }
            };
            let c = under * (-setup.absorption * path).exp() * tr + sky * (1.0 - tr);
            c.as_vec3().to_array()
        })
        .collect()
}

const NAMES: [&str; 3] = ["teapot", "ball", "block"];

fn srgb(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// Panels of `res x res` side by side, each pixel an RGB (`None`: background), row 0 at the top.
fn save_panels(path: &Path, res: usize, panels: &[&dyn Fn(usize) -> Option<[f32; 3]>]) {
    let gap = 4;
    let w = panels.len() * res + (panels.len() - 1) * gap;
    let mut img = image::RgbImage::from_pixel(w as u32, res as u32, image::Rgb([255, 255, 255]));
    for (p, f) in panels.iter().enumerate() {
        for i in 0..res {
            for j in 0..res {
                let c = match f(i * res + j) {
                    Some(c) => c.map(srgb),
                    None => [12, 20, 36],
                };
                img.put_pixel((p * (res + gap) + j) as u32, i as u32, image::Rgb(c));
            }
        }
    }
    img.save(path).unwrap();
    println!("wrote {}", path.display());
}

/// `Σ|t − r| / Σ r` and `Σt / Σr − 1` over the texels of `mask`, mean channel.
fn errors(t: &[[f32; 3]], r: &[[f32; 3]], mask: impl Fn(usize) -> bool) -> (f64, f64) {
    let (mut d, mut st, mut sr) = (0.0, 0.0, 0.0);
    for k in 0..t.len() {
        if !mask(k) {
            continue;
        }
        let a = (t[k][0] + t[k][1] + t[k][2]) as f64 / 3.0;
        let b = (r[k][0] + r[k][1] + r[k][2]) as f64 / 3.0;
        d += (a - b).abs();
        st += a;
        sr += b;
    }
    (d / sr, st / sr - 1.0)
}

fn main() {
    let out: PathBuf = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "docs/images/volumes".into())
        .into();
    std::fs::create_dir_all(&out).unwrap();
    let mut scene = Scene::builtin("objects").unwrap();
    scene.camera.width = 512;
    scene.camera.height = 512;
    let cam = ViewCamera::new(&scene.camera);
    let water = scene.water.as_ref().unwrap();
    let surface = water.surface_at(scene.time).unwrap();
    let input = VolumesInput::from_scene(&scene).unwrap();
    let base = VolumesParams {
        texture: 256,
        ..Default::default()
    };
    let setup0 = VolumesSetup::new(&base, &input).unwrap();
    let n = (input.size / setup0.lattice.cell).round() as usize;
    let heights = caustics_core::water::sample_grid(surface.as_ref(), n, n, water.size);
    // The reference traces the very surface the technique samples.
    let sampled = GridSurface {
        grid: heights.clone(),
        size: water.size,
        edge: water.edge(),
    };
    let t = Instant::now();
    let reference = mesh_reference(
        &setup0,
        &input,
        &sampled,
        &MeshReferenceOptions::per_texel(&setup0, 24.0),
    );
    println!(
        "reference: {} photons in {:.1} s",
        reference.photons,
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let coarse = mesh_reference(
        &setup0,
        &input,
        &sampled,
        &MeshReferenceOptions {
            seed: 7,
            ..MeshReferenceOptions::per_texel(&setup0, 12.0)
        },
    );
    println!(
        "reference at half the photon density: {:.1} s",
        t.elapsed().as_secs_f64()
    );
    report_convergence(&setup0, &reference, &coarse);

    let ref_view = reference_view(&setup0, &input, &cam, &heights, water.wrap, &reference);
    let mut views = Vec::new();
    println!("\n| planes | object | relative L1 | flux error |");
    println!("|---|---|---|---|");
    for planes in [5u32, 50] {
        let params = VolumesParams {
            planes,
            ..base.clone()
        };
        let setup = VolumesSetup::new(&params, &input).unwrap();
        let t = Instant::now();
        let result = volumes::caustics(&setup, &input, &heights, water.wrap);
        eprintln!(
            "{planes} planes: CPU twin {:.1} s",
            t.elapsed().as_secs_f64()
        );
        for (k, (o, view)) in result.objects.iter().zip(&setup.objects).enumerate() {
            eprintln!(
                "{}: box {:.3} deep along the view, Δ = {:.4}",
                NAMES[k],
                view.view.extent().z,
                view.spacing()
            );
            let mask = comparable(&o.depth, view.view.v);
            let (l1, flux) = errors(&o.caustics, &reference.objects[k], |i| mask[i]);
            println!("| {planes} | {} | {l1:.3} | {flux:+.3} |", NAMES[k]);
            let res = view.view.res;
            // Eq. 4 for both, then the caustics alone, so the error shows where it is.
            let ambient = params.ambient as f32;
            let shaded = |e: &[[f32; 3]], i: usize| {
                let d = o.diffuse[i];
                (d[3] > 0.0).then(|| std::array::from_fn(|c| 0.6 * d[c] * (e[i][c] + ambient)))
            };
            let tech = |i: usize| shaded(&o.caustics, i);
            let refr = |i: usize| shaded(&reference.objects[k], i);
            let diff = |i: usize| {
                covered(&o.depth[i]).then(|| {
                    let d = (o.caustics[i][1] - reference.objects[k][i][1]) * 0.5;
                    [d.max(0.0), 0.0, (-d).max(0.0)]
                })
            };
            save_panels(
                &out.join(format!("{}_{planes}.png", NAMES[k])),
                res,
                &[&tech, &refr, &diff],
            );
        }
        let view = view_pass(
            &setup,
            &cam,
            &heights,
            water.wrap,
            &result.objects,
            &result.floor,
            None,
            FLOOR_ALBEDO,
        );
        let (l1, flux) = errors(&view, &ref_view, |_| true);
        println!("| {planes} | refracted view (§3.3) | {l1:.3} | {flux:+.3} |");
        views.push(view);
        let (l1, flux) = errors(&result.floor.texels, &reference.floor.texels, |_| true);
        println!("| {planes} | floor | {l1:.3} | {flux:+.3} |");
        let res = setup.width;
        let show = |m: &[[f32; 3]], i: usize| {
            let e = m[i];
            Some(e.map(|v| 0.35 * v))
        };
        let tech = |i: usize| show(&result.floor.texels, i);
        let refr = |i: usize| show(&reference.floor.texels, i);
        // Flip rows so the picture has y up, as the scene is seen from above.
        let flip = |f: &dyn Fn(usize) -> Option<[f32; 3]>, i: usize| {
            f((res - 1 - i / res) * res + i % res)
        };
        // The floor map does not depend on the planes: one picture.
        if planes != 5 {
            continue;
        }
        save_panels(
            &out.join("floor.png"),
            res,
            &[&|i| flip(&tech, i), &|i| flip(&refr, i)],
        );
    }
    let show = |v: &[[f32; 3]], i: usize| Some(v[i].map(|c| 0.8 * c));
    save_panels(
        &out.join("view.png"),
        512,
        &[&|i| show(&views[0], i), &|i| show(&views[1], i), &|i| {
            show(&ref_view, i)
        }],
    );
}

fn report_convergence(setup: &VolumesSetup, fine: &MeshReference, coarse: &MeshReference) {
    println!("\nreference convergence (24 vs 12 photons per texel side):");
    for (k, o) in setup.objects.iter().enumerate() {
        let (l1, _) = errors(&coarse.objects[k], &fine.objects[k], |i| {
            fine.objects[k][i][1] > 0.0
        });
        let _ = o;
        println!("  {}: relative L1 {l1:.3}", NAMES[k]);
    }
    let (l1, _) = errors(&coarse.floor.texels, &fine.floor.texels, |_| true);
    println!("  floor: relative L1 {l1:.3}");
}
