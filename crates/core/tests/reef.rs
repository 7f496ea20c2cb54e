//! The built-in `reef`: a sea bed shelving across the square with rocks on it, under a swell.
//! Each technique's CPU twin against the reference there, at a small map (the same job both ways).

use caustics_core::metrics::compare;
use caustics_core::scene::Scene;
use caustics_core::techniques::{Job, Spec, reference};

fn reef(res: u32) -> Scene {
    let mut scene = Scene::builtin("reef").expect("built-in scene");
    scene.caustics.width = res;
    scene.caustics.height = res;
    scene
}

fn floor(spec: &Spec, job: &Job) -> caustics_core::map::CausticsMap {
    spec.run_cpu(job, &|_, _| {})
        .unwrap_or_else(|e| panic!("{}: {e}", spec.label))
        .caustics
        .into_floor(spec.name())
        .expect("a floor map")
}

/// The rocks stand on the slope under the water, a crate on the bed and a slab over it, and every
/// technique of the water follows the bed and leaves the sand under the objects dark: its map
/// against the reference's (the photon reference with the objects' meshes), each within 1.5x of
/// what it measured.
#[test]
fn every_technique_lights_the_reef_as_the_reference_does() {
    let scene = reef(128);
    let water = scene.water.as_ref().expect("water");
    let terrain = scene.floor.terrain.as_ref().expect("a sea bed");
    let (lo, hi) = terrain.min_max();
    assert!(lo >= 0.0 && (hi as f64) < water.depth, "{lo}..{hi}");
    assert_eq!(scene.objects.len(), 2, "the crate and the overhang");
    assert!(scene.floor.solids.is_some());
    let surface = water.surface_at(scene.time).expect("surface");
    let job = Job::new(&scene, Some(surface.as_ref()), 4);
    let truth = floor(&reference(), &job);
    // Measured relative L1 (CPU twins, 128², the reference's photons 16² a texel): yuksel 6.68 %,
    // volumes 8.18 %, caustic-triangles 6.92 % (flux +0.24 %), procedural 47.9 % (the paper's
    // look, not the light's flux).
    for (name, measured) in [
        ("yuksel", 0.0668f64),
        ("volumes", 0.0818),
        ("caustic-triangles", 0.0692),
        ("procedural", 0.479),
    ] {
        let spec: Spec = name.parse().expect("registered");
        let m = compare(&floor(&spec, &job), &truth);
        eprintln!("{name}: {m:?}");
        assert!(m.relative_l1 < 1.5 * measured, "{name}: {m:?}");
    }
}

/// The photon reference with mesh receivers (the truth of scenes with objects) marches the sea bed
/// as the reference does: on the reef without objects the two agree to the photons' noise.
#[test]
fn the_mesh_reference_follows_the_sea_bed() {
    use caustics_core::techniques::volumes::{self, reference as mesh};
    // The reef's sea bed alone: the reference is the flux tracer's.
    let mut scene = reef(128);
    scene.clear_objects();
    let water = scene.water.as_ref().expect("water");
    let surface = water.surface_at(scene.time).expect("surface");
    let job = Job::new(&scene, Some(surface.as_ref()), 2);
    let truth = floor(&reference(), &job);
    let input = volumes::VolumesInput::from_scene(&scene).expect("volumes input");
    let setup = volumes::VolumesSetup::new(&volumes::VolumesParams::default(), &input)
        .expect("volumes setup");
    let options = mesh::MeshReferenceOptions {
        object_maps: false,
        terrain: scene.floor.terrain.clone(),
        ..mesh::MeshReferenceOptions::per_texel(&setup, 8.0)
    };
    let m = compare(
        &mesh::mesh_reference(&setup, &input, surface.as_ref(), &options).floor,
        &truth,
    );
    eprintln!("mesh reference on the reef: {m:?}");
    // measured 2.97 % (the photons' noise at 8² a texel) and flux +3.5e-5; the plane z = 0 in its
    // place: 51.8 %
    assert!(m.relative_l1 < 0.05 && m.flux_error.abs() < 3.5e-4, "{m:?}");
}
