//! How fast the reference converges and what it costs: a built-in scene's caustics map at a given
//! resolution for increasing triangulation density, each against a much finer run.
//!
//! `cargo run --release -p caustics-core --example reference_convergence -- [scene] [resolution]`

use std::time::Instant;

use caustics_core::reference::{ReferenceInput, ReferenceOptions, reference};
use caustics_core::scene::Scene;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "pool".into());
    let res: u32 = args.next().map_or(Ok(512), |s| s.parse())?;
    let mut scene = Scene::builtin(&name)?;
    scene.caustics.width = res;
    scene.caustics.height = res;
    let surface = scene
        .water
        .as_ref()
        .ok_or("scene has no water")?
        .surface_at(scene.time)?;
    let input = ReferenceInput::from_scene(&scene, surface.as_ref())?;
    let run = |cpt: u32| {
        let t = Instant::now();
        let opts = ReferenceOptions {
            cells_per_texel: cpt,
            ..Default::default()
        };
        let m = reference(&input, &opts, &|_, _| {}).expect("reference");
        (m, t.elapsed().as_secs_f64())
    };
    let truth_cpt = 32;
    let (truth, truth_s) = run(truth_cpt);
    let t = truth.mean_channel();
    let mean = t.mean();
    println!("scene `{name}`, {res} x {res}, against {truth_cpt} cells per texel ({truth_s:.2} s)");
    println!("| cells per texel | time (s) | relative L1 | RMSE / mean | max abs |");
    println!("|---|---|---|---|---|");
    for cpt in [1, 2, 4, 8, 16] {
        let (m, s) = run(cpt);
        let g = m.mean_channel();
        let n = g.data.len() as f64;
        let l1: f64 = g
            .data
            .iter()
            .zip(&t.data)
            .map(|(a, b)| (a - b).abs() as f64)
            .sum::<f64>()
            / n
            / mean;
        let rmse = (g
            .data
            .iter()
            .zip(&t.data)
            .map(|(a, b)| ((a - b) as f64).powi(2))
            .sum::<f64>()
            / n)
            .sqrt()
            / mean;
        let max = g
            .data
            .iter()
            .zip(&t.data)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        println!(
            "| {cpt} | {s:.2} | {:.3} % | {:.3} % | {max:.3} |",
            100.0 * l1,
            100.0 * rmse
        );
    }
    Ok(())
}
