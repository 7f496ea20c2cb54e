//! The pictures of docs/cascaded.md, from the CPU twin of technique `cascaded` (the GPU passes agree
//! with it to 1e-5, crates/gpu/tests/cascaded_gpu.rs):
//!
//! `cargo run --release -p caustics-core --example cascaded_pictures [-- OUT_DIR]`
//! (default `docs/images/cascaded`).

use std::path::{Path, PathBuf};

use caustics_core::scene::Scene;
use caustics_core::techniques::cascaded::{
    self, CASCADES, CascadedParams, CascadedSetup, Dispersion, Splat,
};
use glam::DVec3;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 270;

fn srgb(v: f32) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0 + 0.5) as u8
}

/// Relative irradiance shown at `exposure`; pixels that see no floor (or lie beyond the last
/// cascade) dark blue.
fn save(path: &Path, w: usize, h: usize, rgb: impl Fn(usize) -> Option<[f32; 3]>, exposure: f32) {
    let mut img = image::RgbImage::new(w as u32, h as u32);
    for (k, p) in img.pixels_mut().enumerate() {
        *p = match rgb(k) {
            Some(c) => image::Rgb(c.map(|v| srgb(v * exposure))),
            None => image::Rgb([10, 16, 32]),
        };
    }
    img.save(path).unwrap();
    println!("wrote {}", path.display());
}

fn show(f: &cascaded::CascadedFrame) -> impl Fn(usize) -> Option<[f32; 3]> + '_ {
    move |k| (f.image[k][3] >= 0.0).then(|| [f.image[k][0], f.image[k][1], f.image[k][2]])
}

fn run(scene: &Scene, params: &CascadedParams) -> (CascadedSetup, cascaded::CascadedFrame) {
    let setup = CascadedSetup::from_scene(scene, params).unwrap();
    let water = cascaded::water_grid(scene, 128).unwrap();
    let t0 = std::time::Instant::now();
    let frame = cascaded::caustics(&setup, &water, scene.floor.terrain.as_ref());
    println!("  CPU twin: {:.1} s", t0.elapsed().as_secs_f64());
    (setup, frame)
}

fn main() {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "docs/images/cascaded".into()),
    );
    std::fs::create_dir_all(&out).unwrap();
    let mut far = Scene::builtin("shore").unwrap();
    far.camera.width = WIDTH;
    far.camera.height = HEIGHT;
    let mut near = far.clone();
    near.camera.position = DVec3::new(20.0, 12.0, 4.0);
    near.camera.target = DVec3::new(17.0, 15.0, 0.5);
    let params = CascadedParams {
        resolution: 1024,
        ..Default::default()
    };
    let (w, h) = (WIDTH as usize, HEIGHT as usize);

    for (name, scene) in [("far", &far), ("near", &near)] {
        println!("shore, {name}");
        let (setup, f) = run(scene, &params);
        save(&out.join(format!("shore-{name}.png")), w, h, show(&f), 0.5);
        if name == "near" {
            println!("shore, near, point splat");
            let point = CascadedParams {
                splat: Splat::Point,
                ..params.clone()
            };
            let (_, f) = run(scene, &point);
            save(&out.join("shore-near-point.png"), w, h, show(&f), 0.5);
        }
        if name == "far" {
            for k in 0..CASCADES {
                let m = f.cascade_map(&setup, k);
                save(
                    &out.join(format!("cascade-{k}.png")),
                    w,
                    h,
                    |p| (f.eye[p][3] != 0.0).then_some(m[p]),
                    0.5,
                );
            }
            // Which cascade each pixel reads: 0 red, 1 green, 2 blue, 3 grey; blends mix them.
            let colours = [
                [1.0, 0.2, 0.2],
                [0.2, 1.0, 0.2],
                [0.3, 0.4, 1.0],
                [0.6, 0.6, 0.6],
            ];
            save(
                &out.join("cascade-index.png"),
                w,
                h,
                |p| {
                    let c = f.image[p][3];
                    (c >= 0.0).then(|| {
                        let k = c.floor() as usize;
                        let t = c - k as f32;
                        let b = colours[(k + 1).min(3)];
                        std::array::from_fn(|i| colours[k][i] * (1.0 - t) + b[i] * t)
                    })
                },
                1.0,
            );
            println!("shore, far, no blending");
            let hard = CascadedParams {
                blend: 0.0,
                ..params.clone()
            };
            let (_, f) = run(scene, &hard);
            save(&out.join("seams-hard.png"), w, h, show(&f), 0.5);
        }
    }

    for (name, dispersion) in [
        ("wavelength", Dispersion::Wavelength),
        ("post", Dispersion::Post),
    ] {
        println!("shore, near, dispersion {name} (x20)");
        let p = CascadedParams {
            dispersion,
            dispersion_scale: 20.0,
            ..params.clone()
        };
        let (_, f) = run(&near, &p);
        save(
            &out.join(format!("dispersion-{name}.png")),
            w,
            h,
            show(&f),
            0.5,
        );
    }
}
