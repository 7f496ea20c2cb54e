//! The techniques' intermediate buffers as any front end draws them (`techniques::buffers`): each
//! technique draws the buffers its descriptor lists, from its CPU twin's passes, and under flat
//! water their values are known without a simulation.

use glam::DVec3;

use caustics_core::plot::{NO_VALUE, Picture, heat};
use caustics_core::scene::{Scene, WaterSource};
use caustics_core::techniques::buffers::{Buffer, BufferInput, HEIGHTS, SceneHas};
use caustics_core::techniques::describe::picture;
use caustics_core::techniques::{REGISTRY, Spec, yuksel};
use caustics_core::water::Surface;

fn spec(s: &str) -> Spec {
    s.parse().unwrap()
}

fn input_for<'a>(
    spec: &'a Spec,
    scene: &'a Scene,
    surface: Option<&'a dyn Surface>,
) -> BufferInput<'a> {
    BufferInput {
        params: &spec.params,
        scene,
        water: scene.water.as_ref().zip(surface),
        light: scene.light.direction,
        map_size: 32,
    }
}

/// `key` (`cascade:2`) of `spec`'s technique on `scene`.
fn buffer(spec: &Spec, scene: &Scene, key: &str) -> Buffer {
    Buffer::parse(key, &Buffer::available(spec.entry, SceneHas::of(scene))).unwrap()
}

fn draw(spec: &Spec, input: &BufferInput, key: &str) -> caustics_core::Result<Picture> {
    picture(spec.entry, buffer(spec, input.scene, key), input)
}

fn not_blank(p: &Picture) -> usize {
    assert_eq!(p.rgba.len(), (p.width * p.height * 4) as usize);
    p.rgba
        .chunks(4)
        .filter(|t| t[0] > 40 || t[1] > 40 || t[2] > 40)
        .count()
}

/// Every registered technique draws every buffer it offers on every built-in scene it runs on,
/// a picture of its stated size that is not blank (for a buffer of several, one at least: a
/// yuksel channel far from where the light goes holds none).
#[test]
fn every_technique_draws_every_buffer_it_offers() {
    for name in ["pool", "glass", "objects"] {
        let scene = Scene::builtin(name).unwrap();
        let surface = scene.water.as_ref().map(|w| w.surface_at(0.0).unwrap());
        for entry in REGISTRY {
            let s = spec(&format!(
                "{}{}",
                entry.name,
                match entry.table {
                    "yuksel" => ":n=5,m=4",
                    "caustic-triangles" => ":photon_image=32,cube_resolution=32",
                    "volumes" => ":planes=3,texture=32,shadow=0",
                    "cascaded" => ":resolution=64",
                    _ => "",
                }
            ));
            let offered = Buffer::available(entry, SceneHas::of(&scene));
            if scene.water.is_none() {
                assert!(!offered.iter().any(|b| b.desc.key == HEIGHTS.key));
            }
            let input = input_for(&s, &scene, surface.as_deref());
            let has = SceneHas::of(&scene);
            for b in offered {
                let lit = (0..b.count(&s.own(), &has)).any(|index| {
                    let b = Buffer { index, ..b };
                    let p = picture(entry, b, &input)
                        .unwrap_or_else(|e| panic!("{} on {name}: {}: {e}", entry.name, b.name()));
                    not_blank(&p) > 0
                });
                assert!(lit, "{} on {name}: {} is blank", entry.name, b.name());
            }
        }
    }
}

#[test]
fn buffers_are_named_on_the_command_line_by_their_keys() {
    let scene = Scene::builtin("pool").unwrap();
    let cascaded = spec("cascaded");
    let available = Buffer::available(cascaded.entry, SceneHas::of(&scene));
    let two = Buffer::parse("cascade:2", &available).unwrap();
    assert_eq!(
        (two.desc.key, two.index, two.key()),
        ("cascade", 2, "cascade:2".into())
    );
    assert_eq!(Buffer::parse("cascade", &available).unwrap().index, 0);
    assert_eq!(
        Buffer::parse("heights", &available).unwrap().desc.key,
        HEIGHTS.key
    );
    let err = Buffer::parse("photon-hits", &available)
        .unwrap_err()
        .to_string();
    assert!(err.contains("heights, cascade:0"), "{err}");
    assert!(Buffer::parse("cascade:x", &available).is_err());
    let yuksel = spec("yuksel");
    let all = Buffer::available(yuksel.entry, SceneHas::of(&scene));
    assert_eq!(all.len(), 4, "heights and yuksel's three");
    for b in &all {
        assert_eq!(Buffer::parse(&b.key(), &all).unwrap(), *b);
    }
}

#[test]
fn caustic_triangles_shows_the_water_generators_photons() {
    let scene = Scene::builtin("pool").unwrap();
    let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
    let s = spec("caustic-triangles:photon_image=32");
    let available = Buffer::available(s.entry, SceneHas::of(&scene));
    assert!(
        !available.iter().any(|b| b.desc.key == "distance-layer"),
        "{available:?}"
    );
    let input = input_for(&s, &scene, Some(surface.as_ref()));
    for b in available {
        let p = picture(s.entry, b, &input).unwrap();
        assert!(not_blank(&p) > 0, "{} is blank", b.name());
        if b.desc.key != HEIGHTS.key {
            assert_eq!(
                (p.width, p.height),
                (33, 33),
                "{}: the (P+1)² lattice",
                b.name()
            );
        }
    }
}

#[test]
fn cascade_maps_show_caustics_in_the_cameras_view() {
    let mut scene = Scene::builtin("pool").unwrap();
    scene.camera.width = 64;
    scene.camera.height = 36;
    let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
    let s = spec("cascaded:resolution=64");
    let input = input_for(&s, &scene, Some(surface.as_ref()));
    // The pool is close to the camera: the nearest cascade holds it.
    let p = draw(&s, &input, "cascade:0").unwrap();
    assert_eq!((p.width, p.height), (64, 36), "the eye's image");
    assert!(not_blank(&p) > 64 * 36 / 4, "cascade 0 is nearly blank");
    let Err(err) = draw(&s, &input, "cascade:4") else {
        panic!("cascade 4 of 0..3 drawn");
    };
    assert!(err.to_string().contains("4 cascades"), "{err}");
}

#[test]
fn volumes_shows_each_objects_caustics_map() {
    let scene = Scene::builtin("objects").unwrap();
    let surface = scene.water.as_ref().unwrap().surface_at(0.5).unwrap();
    let s = spec("volumes:planes=3,texture=32,shadow=0");
    let input = input_for(&s, &scene, Some(surface.as_ref()));
    let objects = buffer(&s, &scene, "object");
    assert_eq!(
        objects.count(&s.own(), &SceneHas::of(&scene)),
        scene.objects.len() as u32
    );
    for k in 0..scene.objects.len() {
        let p = draw(&s, &input, &format!("object:{k}")).unwrap();
        assert_eq!((p.width, p.height), (32, 32));
        assert!(not_blank(&p) > 16, "object {k}'s map is blank");
    }
    let k = scene.objects.len();
    assert!(draw(&s, &input, &format!("object:{k}")).is_err());
    // Without objects there is no object map to offer.
    let pool = Scene::builtin("pool").unwrap();
    assert!(
        !Buffer::available(s.entry, SceneHas::of(&pool))
            .iter()
            .any(|b| b.desc.key == "object")
    );
}

#[test]
fn a_point_light_shows_its_light_cube_map() {
    let mut scene = Scene::builtin("glass").unwrap();
    let s = spec("caustic-triangles:photon_image=32,cube_resolution=32,light_cube=64");
    let offered = |scene: &Scene| {
        Buffer::available(s.entry, SceneHas::of(scene))
            .iter()
            .any(|b| b.desc.key == "light-cube")
    };
    assert!(!offered(&scene));
    let light_cube = Buffer::new(
        s.entry
            .buffers
            .iter()
            .find(|b| b.key == "light-cube")
            .unwrap(),
    );
    let sun = picture(s.entry, light_cube, &input_for(&s, &scene, None));
    assert!(sun.is_err(), "the sun has no light cube map");
    // docs/scenes/glass-lamp.toml's lamp.
    scene.light.position = Some(DVec3::new(0.15, 0.25, 0.75));
    assert!(offered(&scene));
    let p = picture(s.entry, light_cube, &input_for(&s, &scene, None)).unwrap();
    assert_eq!((p.width, p.height), (6 * 64, 64));
    assert!(not_blank(&p) > 0, "no caustic on the light cube map");
}

/// The value `v / top` a heat-ramp colour stands for: the nearest of 4096 points on the ramp.
fn unheat(rgb: &[u8]) -> f32 {
    (0..=4096)
        .map(|k| k as f32 / 4096.0)
        .min_by_key(|&t| {
            heat(t)
                .iter()
                .zip(rgb)
                .map(|(a, b)| a.abs_diff(*b) as u32)
                .sum::<u32>()
        })
        .unwrap()
}

/// The pool with its water made flat: every buffer's value is known without a simulation.
fn flat_pool() -> Scene {
    let mut scene = Scene::builtin("pool").unwrap();
    scene.water.as_mut().unwrap().source = WaterSource::Flat;
    scene
}

/// Under flat water each yuksel sample carries its share of flat water's flux (1 once times
/// k²: the flux picture is one colour, the ramp at 1 / 1.5), each of a pixel's k × k samples
/// lands at its own offset, the same in every pixel (a pattern of period k), and with one sample
/// a pixel pass 1 puts it into the one or two channels that offset straddles, the same in
/// every texel: each channel's picture is black or uniformly white, and a wrong channel,
/// offset or flux changes the colours.
#[test]
fn yuksel_buffers_under_flat_water_show_its_uniform_light() {
    let scene = flat_pool();
    let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
    // Every pixel's k × k samples (adaptive footprints would take one for flat water).
    let s = spec("yuksel:n=5,m=4,split=0");
    let input = input_for(&s, &scene, Some(surface.as_ref()));
    let flux = draw(&s, &input, "yuksel-flux").unwrap();
    let expect = heat(1.0 / 1.5);
    let off = flux
        .rgba
        .chunks(4)
        .map(|t| (0..3).map(|c| t[c].abs_diff(expect[c])).max().unwrap())
        .max()
        .unwrap();
    eprintln!("flux picture: largest step from the ramp at 1 / 1.5: {off}");
    // measured 0 steps
    assert_eq!(off, 0, "flux picture departs from flat water's flux");
    // Each pixel's k × k samples sit at their own places in it, the same in every pixel.
    let offset = draw(&s, &input, "yuksel-offset").unwrap();
    let k = yuksel::DEFAULT_SUBSAMPLES as usize;
    let w = offset.width as usize;
    let texel = |y: usize, x: usize| &offset.rgba[(y * w + x) * 4..(y * w + x) * 4 + 4];
    for y in 0..offset.height as usize {
        for x in 0..w {
            assert_eq!(texel(y, x), texel(y % k, x % k), "offset at ({y}, {x})");
        }
    }
    assert_ne!(
        texel(0, 0),
        texel(0, 1),
        "the samples of a pixel at one place"
    );
    // By default flat water lands whole: one record a pixel, repeated over its block.
    let whole = spec("yuksel:n=5,m=4");
    let input = input_for(&whole, &scene, Some(surface.as_ref()));
    let offset = draw(&whole, &input, "yuksel-offset").unwrap();
    let texel = |y: usize, x: usize| &offset.rgba[(y * w + x) * 4..(y * w + x) * 4 + 4];
    assert_eq!(
        texel(0, 0),
        texel(k - 1, k - 1),
        "flat water's pixel lands whole"
    );
    let flux = draw(&whole, &input, "yuksel-flux").unwrap();
    assert_eq!(
        &flux.rgba[..3],
        &expect[..],
        "its record carries the whole pixel's flux"
    );
    // One sample a pixel: it lands whole in the one or two channels its offset straddles.
    let one = spec("yuksel:n=5,m=4,subsamples=1");
    let channels = buffer(&one, &scene, "yuksel-channel");
    assert_eq!(
        channels.count(&one.own(), &SceneHas::of(&scene)),
        5,
        "M + 1"
    );
    let input = input_for(&one, &scene, Some(surface.as_ref()));
    let mut lit = Vec::new();
    for k in 0..5 {
        let p = draw(&one, &input, &format!("yuksel-channel:{k}")).unwrap();
        let white = p
            .rgba
            .chunks(4)
            .filter(|t| t[..3] == [255, 255, 255])
            .count();
        let black = p.rgba.chunks(4).filter(|t| t[..3] == [0, 0, 0]).count();
        let n = p.rgba.len() / 4;
        eprintln!("channel {k}: {white} white, {black} black of {n}");
        assert_eq!(white + black, n, "channel {k}: not one value");
        if white > 0 {
            lit.push(k);
        }
    }
    assert!((1..=2).contains(&lit.len()), "lit channels {lit:?}");
}

/// Under flat water the nearest cascade's map is the flat water's irradiance, 1 (on the ramp's
/// middle, 1 of a top of 2), up to the splat's sampling, where that cascade lights the view:
/// the mean value read back from the picture's colours.
#[test]
fn the_cascade_map_under_flat_water_reads_one() {
    let mut scene = flat_pool();
    scene.camera.width = 64;
    scene.camera.height = 36;
    scene.water.as_mut().unwrap().absorption = DVec3::ZERO;
    // The floor alone: a wall under flat water holds tan θt, not one.
    scene.floor.walls = false;
    let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
    let s = spec("cascaded:resolution=64");
    let input = input_for(&s, &scene, Some(surface.as_ref()));
    let p = draw(&s, &input, "cascade:0").unwrap();
    let values: Vec<f32> = p
        .rgba
        .chunks(4)
        .filter(|t| t[..3] != NO_VALUE)
        .map(|t| 2.0 * unheat(t))
        .collect();
    // Pixels beyond cascade 0's far plane take no light from it (black).
    let lit: Vec<f32> = values.iter().copied().filter(|&v| v > 0.5).collect();
    let mean = lit.iter().sum::<f32>() / lit.len() as f32;
    eprintln!(
        "cascade 0 under flat water: {} of {} pixels lit, mean {mean:.4}",
        lit.len(),
        values.len()
    );
    assert!(lit.len() > 64 * 36 / 2, "cascade 0 is nearly empty");
    // measured 1.0073 over 2108 of 2304 pixels
    assert!((mean - 1.0).abs() < 0.03, "mean {mean}");
}

/// Under flat water caustic-triangles' water photons all carry the same power (a white power
/// picture) and land on the lattice shifted by the refracted sun: the hit picture's red and
/// green are the floor's x and y, so they step by one lattice cell a column and a row.
#[test]
fn caustic_triangles_photons_under_flat_water_lie_on_the_shifted_lattice() {
    let scene = flat_pool();
    let surface = scene.water.as_ref().unwrap().surface_at(0.0).unwrap();
    let s = spec("caustic-triangles:photon_image=32");
    let input = input_for(&s, &scene, Some(surface.as_ref()));
    let power = draw(&s, &input, "photon-power").unwrap();
    let white = power
        .rgba
        .chunks(4)
        .filter(|t| t[..3] == [255, 255, 255])
        .count();
    eprintln!("photon power: {white} of {} white", power.rgba.len() / 4);
    assert_eq!(white, power.rgba.len() / 4, "photon powers differ");
    let hits = draw(&s, &input, "photon-hits").unwrap();
    let w = hits.width as usize;
    let at = |i: usize, j: usize, c: usize| hits.rgba[(i * w + j) * 4 + c] as f64;
    // One lattice cell in colour steps: 255 / P of the square (P + 1 vertices span it).
    let cell = 255.0 / (w - 1) as f64;
    let (mut worst, mut steps) = (0.0f64, 0usize);
    for i in 0..w {
        for j in 1..w {
            let x = (at(i, j - 1, 0), at(i, j, 0));
            let y = (at(j, i, 1), at(j - 1, i, 1));
            // Where the shifted lattice wraps or leaves the square (clamped to 0 or 255), the
            // step is not a cell.
            for (a, b) in [x, y] {
                if b > a && a > 0.0 && b < 255.0 {
                    worst = worst.max((b - a - cell).abs());
                    steps += 1;
                }
            }
        }
    }
    eprintln!("photon hits: {steps} steps of {cell:.2}, worst departure {worst:.2}");
    assert!(steps > w * (w - 1), "too few steps on the lattice: {steps}");
    // Colours are whole steps: a cell of 7.97 steps is 7 or 8 (measured worst 0.97 over 2013
    // steps).
    assert!(worst < 1.0, "hits off the lattice by {worst} steps");
}
