use super::*;
use crate::reference::{ReferenceInput, ReferenceOptions, reference};
use crate::techniques::cascaded::{CascadedParams, CascadedSetup, eye_pass};

/// A pixel's samples are n-rooks on its n² x n² sub-grid, each at a sub-cell's centre: their
/// coordinates along each axis are exactly the n² sub-cells' centres, so they average to the
/// pixel's centre.
#[test]
fn samples_are_n_rooks_about_the_pixels_centre() {
    assert_eq!(sample_offset(0, 0, 1), (0.5, 0.5));
    for n in 2..=8 {
        let cells = (n * n) as f64;
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        for sy in 0..n {
            for sx in 0..n {
                let (x, y) = sample_offset(sx, sy, n);
                xs.push((x * cells - 0.5).round() as i64);
                ys.push((y * cells - 0.5).round() as i64);
                for v in [x, y] {
                    let k = v * cells - 0.5;
                    assert!((k - k.round()).abs() < 1e-9, "{n}: {v}");
                }
            }
        }
        xs.sort();
        ys.sort();
        let all: Vec<i64> = (0..(n * n) as i64).collect();
        assert_eq!((xs, ys), (all.clone(), all), "{n}");
    }
}

/// Beyond a terrain's caustics map (which does not tile) the floor gets the flat water's
/// light, not the map's edge stretched to the horizon: with a map that is dark everywhere,
/// the shore's far rows (whose floor lies beyond the 32 m square) render as without a map,
/// while the near rows, inside the map, are darker.
#[test]
fn beyond_a_terrain_map_the_floor_is_lit_as_under_flat_water() {
    let mut scene = Scene::builtin("shore").unwrap();
    scene.camera.width = 160;
    scene.camera.height = 90;
    let water = scene.water.as_ref().unwrap();
    let surface = water.surface_at(scene.time).unwrap();
    let dark = CausticsMap::new(32, 32, water.size);
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let s = Some(surface.as_ref());
    let none = |_: usize, _: usize| {};
    let flat = render(&scene, s, None, None, &options, &none);
    let mapped = render(
        &scene,
        s,
        Some(Caustics::Floor(&dark)),
        None,
        &options,
        &none,
    );
    fn row(img: &Image, y: usize) -> &[u8] {
        &img.rgb[y * 160 * 3..(y + 1) * 160 * 3]
    }
    // Rows 26-28: the water just below the horizon (row 25 at 90 rows), far enough that every
    // refracted view ray there meets the floor beyond the map (row 29 already has a few
    // inside it).
    for y in 26..29 {
        assert_eq!(row(&flat, y), row(&mapped, y), "row {y}");
    }
    let near = |img: &Image| row(img, 80).iter().map(|&v| v as u64).sum::<u64>();
    assert!(
        near(&mapped) < near(&flat),
        "the dark map darkens the near floor"
    );
}

/// The reference's walls' maps light the pool's walls the camera sees under a low sun, and
/// only where the scene's walls are on.
#[test]
fn walls_maps_light_the_walls() {
    let mut scene = Scene::builtin("pool").unwrap();
    scene.camera.width = 160;
    scene.camera.height = 90;
    scene.caustics.width = 64;
    scene.caustics.height = 64;
    scene.light.direction = DVec3::new(0.8, 0.6, -0.6).normalize();
    let water = scene.water.as_ref().unwrap();
    let surface = water.surface_at(scene.time).unwrap();
    let input = ReferenceInput::from_scene(&scene, surface.as_ref()).unwrap();
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let out = crate::reference::reference_with_walls(&input, &options, &|_, _| {}).unwrap();
    let walls = out.walls.as_ref().unwrap();
    let caustics = Some(Caustics::Floor(&out.floor));
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let s = Some(surface.as_ref());
    let none = |_: usize, _: usize| {};
    let unlit = render(&scene, s, caustics, None, &options, &none);
    let lit = render(&scene, s, caustics, Some(walls), &options, &none);
    let (mut brighter, mut darker, mut sum) = (0, 0, 0.0);
    for (a, b) in unlit.rgb.iter().zip(&lit.rgb) {
        brighter += (b > a) as usize;
        darker += (b < a) as usize;
        sum += a.abs_diff(*b) as f64;
    }
    let mean = sum / lit.rgb.len() as f64;
    eprintln!(
        "walls' maps: mean change {mean:.2} steps, {brighter} channels brighter, {darker} darker"
    );
    // Measured 1.90 steps, every changed channel brighter: light is only added.
    assert!(mean > 0.5, "{mean}");
    assert_eq!(darker, 0);
    scene.floor.walls = false;
    let off = render(&scene, s, caustics, Some(walls), &options, &none);
    assert_eq!(
        off.rgb,
        render(&scene, s, caustics, None, &options, &none).rgb
    );
}

/// All the light is the sun's: its direct light, the sky and the sky's ambient light scale with
/// its intensity together, so twice the intensity at half the exposure is the same picture
/// (the pool with its walls in view, the objects, the shore's terrain and sky). Measured: the
/// same bytes.
#[test]
fn every_light_scales_with_the_suns_intensity() {
    for name in ["pool", "objects", "shore"] {
        let mut scene = Scene::builtin(name).unwrap();
        scene.camera.width = 96;
        scene.camera.height = 54;
        let water = scene.water.clone().unwrap();
        let surface = water.surface_at(scene.time).unwrap();
        let options = RenderOptions {
            supersampling: 1,
            ..Default::default()
        };
        let none = |_: usize, _: usize| {};
        let once = render(&scene, Some(surface.as_ref()), None, None, &options, &none);
        scene.light.intensity *= 2.0;
        let halved = RenderOptions {
            exposure: options.exposure * 0.5,
            ..options
        };
        let twice = render(&scene, Some(surface.as_ref()), None, None, &halved, &none);
        let off = once
            .rgb
            .iter()
            .zip(&twice.rgb)
            .filter(|(a, b)| a.abs_diff(**b) > 1)
            .count();
        assert_eq!(off, 0, "{name}: {off} channels differ by more than a step");
    }
}

/// A floor map projected to the eye (each pixel holds the map at its straight ray's floor
/// point, as `cascaded` makes its image) and read back as eye-space caustics lights the final
/// image as the map itself does: the two differ only where a refracted ray's floor point is
/// hidden from the eye's straight rays and by the extra bilinear read.
#[test]
fn eye_space_caustics_read_where_the_floor_projects() {
    // The shore with a 5 m/s ocean on a 128 grid, whose caustics a 128² map resolves
    // (the built-in light breeze's wavelets alias at this size, which the test does not
    // measure).
    let text = crate::scene::BUILTIN_SCENES
        .iter()
        .find(|(n, _)| *n == "shore")
        .unwrap()
        .1
        .replace(
            "resolution = 256, wind_speed = 2.0",
            "resolution = 128, wind_speed = 5.0",
        );
    let mut scene = Scene::from_toml(&text, std::path::Path::new("."), "shore").unwrap();
    assert!(matches!(
        &scene.water.as_ref().unwrap().source,
        crate::scene::WaterSource::Ocean(o) if o.params().wind_speed == 5.0
    ));
    scene.camera.width = 160;
    scene.camera.height = 90;
    scene.caustics.width = 128;
    scene.caustics.height = 128;
    let water = scene.water.as_ref().unwrap();
    let surface = water.surface_at(scene.time).unwrap();
    let input = ReferenceInput::from_scene(&scene, surface.as_ref()).unwrap();
    let options = ReferenceOptions {
        cells_per_texel: 2,
        ..Default::default()
    };
    let map = reference(&input, &options, &|_, _| {}).unwrap();
    let setup = CascadedSetup::from_scene(&scene, &CascadedParams::default()).unwrap();
    let eye = eye_pass(&setup, scene.floor.terrain.as_ref());
    let e = &setup.eye;
    let texels = eye
        .iter()
        .enumerate()
        .map(|(p, t)| {
            if t[3] == 0.0 {
                return [0.0, 0.0, 0.0, -1.0];
            }
            let (x, y) = ((p % e.width) as f64 + 0.5, (p / e.width) as f64 + 0.5);
            let f = e.position + e.ray(x, y) * t[0] as f64;
            let c = map.sample(f.x, f.y, false);
            [c[0], c[1], c[2], 0.0]
        })
        .collect();
    let image = EyeSpaceCaustics {
        width: e.width,
        height: e.height,
        texels,
    };
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let s = Some(surface.as_ref());
    let a = render(
        &scene,
        s,
        Some(Caustics::Floor(&map)),
        None,
        &options,
        &|_, _| {},
    );
    let b = render(
        &scene,
        s,
        Some(Caustics::EyeSpace(&image)),
        None,
        &options,
        &|_, _| {},
    );
    let flat = render(&scene, s, None, None, &options, &|_, _| {});
    // The nearer half of the floor, where a pixel sees less than a map texel (in the distance
    // the two sample the map's detail at different points: aliasing, not a misplaced read),
    // without the last rows, whose refracted floor points project below the image.
    let rows =
        (scene.camera.height as usize / 2) * 160 * 3..(scene.camera.height as usize - 3) * 160 * 3;
    let mean = |x: &Image, y: &Image| {
        x.rgb[rows.clone()]
            .iter()
            .zip(&y.rgb[rows.clone()])
            .map(|(p, q)| p.abs_diff(*q) as f64)
            .sum::<f64>()
            / rows.len() as f64
    };
    let (same, caustics) = (mean(&a, &b), mean(&a, &flat));
    eprintln!(
        "map vs the same map through the eye: mean |Δ| {same:.3} steps; map vs flat-water \
         lighting {caustics:.3} steps"
    );
    assert!(caustics > 0.5, "{caustics}");
    assert!(same < 0.2 * caustics, "{same} vs {caustics}");
}

/// A diffuse object under flat, clear water is lit as the floor is: the top of a grey box and the
/// grey floor beside it, both horizontal and unshadowed, show the same pixel under a sun 60° from
/// the zenith. The refracted beam lights a horizontal surface with E cos θi T whatever its
/// depth; lighting the box by E T (n · r) instead makes its top cos θt / cos θi = 1.52 times
/// brighter.
#[test]
fn an_object_under_the_water_is_lit_as_the_floor_at_its_side() {
    let scene = Scene::from_toml(
        r#"
            [water]
            size = 4.0
            depth = 1.0
            absorption = [0.0, 0.0, 0.0]
            [floor]
            pattern = "plain"
            [light]
            direction = [0.8660254, 0.0, -0.5]
            [camera]
            position = [2.0, 1.9, 3.0]
            target = [2.0, 2.0, 0.0]
            fov_y = 40.0
            resolution = [64, 64]
            [[objects]]
            shape = { kind = "cuboid", half_extents = [0.4, 0.4, 0.3] }
            position = [2.0, 2.0, 0.0]
            material = { kind = "diffuse", color = [0.7, 0.7, 0.7] }
        "#,
        std::path::Path::new("."),
        "box",
    )
    .unwrap();
    let water = scene.water.as_ref().unwrap();
    let surface = water.surface_at(scene.time).unwrap();
    let options = RenderOptions {
        supersampling: 1,
        ..Default::default()
    };
    let image = render(
        &scene,
        Some(surface.as_ref()),
        None,
        None,
        &options,
        &|_, _| {},
    );
    let px = |x: usize, y: usize| -> [u8; 3] {
        let i = (y * 64 + x) * 3;
        [image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]]
    };
    // The box's top fills the middle; its shadow falls to the right (the sun shines towards +x).
    let (top, floor, shadow) = (px(32, 32), px(6, 32), px(56, 32));
    eprintln!("box top {top:?}, floor {floor:?}, the box's shadow {shadow:?}");
    assert!(
        shadow[0] as u16 + 40 < floor[0] as u16,
        "no shadow: {shadow:?} {floor:?}"
    );
    // Measured: the same bytes.
    for c in 0..3 {
        assert!(top[c].abs_diff(floor[c]) <= 1, "{top:?} {floor:?}");
    }
}
