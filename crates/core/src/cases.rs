//! The generated, seeded test surfaces on which every technique is measured against the reference
//! (`caustics compare`): four kinds of water, four suns, shallow and deep water; and the receivers
//! (`caustics compare --receivers`): one water over a flat floor, a sand bar, rocks and the walls.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use crate::grid::Grid;
use crate::scene::{Albedo, Floor, FloorPattern, Material, Object, Solids, Water, WaterSource};
use crate::water::ocean::OceanParams;
use crate::water::ripple::{Drop, RippleParams};
use crate::water::waves::Wave;

/// One comparison case: water over a flat floor under a sun.
#[derive(Clone, Debug)]
pub struct Case {
    /// `<surface>-<sun>-<depth>` (e.g. `waves-mid-deep`), or `receivers-<receiver>`.
    pub name: String,
    /// The water: one of [`SURFACES`] on the unit square, wrapping, at one of [`DEPTHS`].
    pub water: Water,
    /// The receiver under the water: a plain flat floor, or one of [`RECEIVERS`].
    pub floor: Floor,
    /// The direction the sunlight travels, unit length, pointing down (z < 0).
    pub light: DVec3,
    /// Simulation time at which the water is frozen, seconds.
    pub time: f64,
    /// Opaque objects under the water (`receivers-objects`); their meshes are also the floor's
    /// [`Floor::solids`].
    pub objects: Vec<Object>,
}

/// The kinds of water the cases use.
pub const SURFACES: &[&str] = &["waves", "lens", "ocean", "ripples"];
/// Sun angles from the zenith, degrees: 60 and 80 are where the waves throw the light furthest
/// and most one-sidedly (a gather region fixed in pixels loses it).
pub const SUNS: &[(&str, f64)] = &[
    ("overhead", 0.0),
    ("mid", 30.0),
    ("low", 60.0),
    ("grazing", 80.0),
];
/// Rest depths on the unit square.
pub const DEPTHS: &[(&str, f64)] = &[("shallow", 0.15), ("deep", 0.5)];

fn source(kind: &str) -> WaterSource {
    match kind {
        "waves" => {
            let w = |a, l, d: [f64; 2], phase| Wave {
                amplitude: a,
                wavelength: l,
                direction: d,
                phase,
                period: None,
            };
            WaterSource::Waves(vec![
                w(0.0020, 0.25, [1.0, 0.3], 0.0),
                w(0.0015, 0.17, [-0.4, 1.0], 1.3),
                w(0.0010, 0.12, [0.8, -0.6], 2.2),
            ])
        }
        "lens" => {
            // A Gaussian bump, 0.5 % of the square high and 0.06 wide: a converging lens.
            let n = 256;
            WaterSource::HeightField(Grid::from_fn(n, n, |i, j| {
                let p = DVec2::new(j as f64 + 0.5, i as f64 + 0.5) / n as f64 - 0.5;
                (0.005 * (-p.length_squared() / (2.0 * 0.06 * 0.06)).exp()) as f32
            }))
        }
        "ocean" => WaterSource::Ocean(Box::new(
            crate::water::ocean::Ocean::new(
                &OceanParams {
                    resolution: 128,
                    wind_speed: 4.0,
                    rms_height: Some(0.0015),
                    seed: 11,
                    ..Default::default()
                },
                1.0,
            )
            .expect("valid ocean"),
        )),
        "ripples" => WaterSource::Ripple(RippleParams {
            resolution: 256,
            drops: (0..5)
                .map(|k| {
                    let a = k as f64 * TAU / 5.0;
                    Drop {
                        position: [0.5 + 0.28 * a.cos(), 0.5 + 0.28 * a.sin()],
                        radius: 0.05,
                        strength: -0.004,
                    }
                })
                .collect(),
            ..Default::default()
        }),
        other => panic!("unknown case surface {other}"),
    }
}

/// All cases (`quick`: the mid sun and the deep water only).
pub fn cases(quick: bool) -> Vec<Case> {
    let mut out = Vec::new();
    for &surface in SURFACES {
        for &(sun, zenith) in SUNS {
            for &(depth_name, depth) in DEPTHS {
                if quick && (sun != "mid" || depth_name != "deep") {
                    continue;
                }
                let z = zenith.to_radians();
                // The sun's azimuth is off the axes so that nothing lines up with the texel grid.
                let light = DVec3::new(z.sin() * 0.8, z.sin() * 0.6, -z.cos()).normalize();
                out.push(Case {
                    name: format!("{surface}-{sun}-{depth_name}"),
                    water: Water {
                        source: source(surface),
                        size: 1.0,
                        depth,
                        ior: 1.333,
                        wrap: true,
                        absorption: DVec3::ZERO,
                    },
                    floor: Floor {
                        terrain: None,
                        solids: None,
                        albedo: Albedo::Pattern(FloorPattern::Plain),
                        walls: false,
                        deck: Default::default(),
                    },
                    light,
                    time: 0.0,
                    objects: Vec::new(),
                });
            }
        }
    }
    out
}

/// The receivers `caustics compare --receivers` measures, as the cases' name suffixes.
pub const RECEIVERS: &[&str] = &["flat", "sand-bar", "rocks", "walls", "objects"];

/// The receivers' terrains rise inside the square and lie flat at its edges: where the water
/// wraps and a terrain does not tile, the light that crosses an edge meets a different floor on
/// each side of it, and the reference and the techniques settle that seam each their own way. A
/// border as wide as the light's travel and the waves' throw keeps every case clear of it.
const BORDER: f64 = 0.25;

/// `0` in the border, rising smoothly (cosine) to `1` at the square's centre line along `x`.
fn ridge(x: f64) -> f64 {
    let u = ((x - BORDER) / (1.0 - 2.0 * BORDER)).clamp(0.0, 1.0);
    0.5 - 0.5 * (TAU * u).cos()
}

/// A sand bar: a ridge along y whose crest stands 60 % of the way up to the water, its faces up
/// to 62° steep on the unit square under 0.5 of water, rippled 10 % along its length where it
/// rises.
pub fn sand_bar(depth: f64) -> Grid {
    let n = 128;
    Grid::from_fn(n, n, |i, j| {
        let (x, y) = ((j as f64 + 0.5) / n as f64, (i as f64 + 0.5) / n as f64);
        let ripple = 1.0 + 0.1 * ridge(y) * (TAU * 4.0 * y).sin();
        (0.6 * depth * ridge(x) * ripple / 1.1) as f32
    })
}

/// Rocks on a flat bed: three round mounds 6 % of the square wide (their standard deviation)
/// standing 40-55 % of the way up to the water, faces up to 70° steep: under a sun 30° from the
/// zenith their far sides turn almost edge-on to the refracted light.
pub fn rocks(depth: f64) -> Grid {
    let n = 128;
    let rocks = [(0.4, 0.42, 0.55), (0.6, 0.55, 0.45), (0.45, 0.62, 0.4)];
    Grid::from_fn(n, n, |i, j| {
        let p = DVec2::new(j as f64 + 0.5, i as f64 + 0.5) / n as f64;
        let h: f64 = rocks
            .iter()
            .map(|&(x, y, top)| {
                top * (-(p - DVec2::new(x, y)).length_squared() / (2.0 * 0.06 * 0.06)).exp()
            })
            .sum();
        (depth * h) as f32
    })
}

/// Objects on the flat floor: a box standing on it, 30 % of the way up to the water, and a slab
/// held 40 % of the way up (an overhang) that takes the light the floor under it would get. Both
/// are diffuse: the light that meets them stays off the floor.
pub fn crate_and_overhang(depth: f64) -> Vec<Object> {
    let placed = |half: DVec3, base: DVec3| Object {
        mesh: crate::mesh::cuboid(half)
            .transformed(glam::DAffine3::from_translation(base + DVec3::Z * half.z)),
        material: Material::Diffuse {
            color: DVec3::splat(0.8),
        },
    };
    vec![
        placed(
            DVec3::new(0.08, 0.06, 0.15 * depth),
            DVec3::new(0.35, 0.4, 0.0),
        ),
        placed(
            DVec3::new(0.1, 0.07, 0.02),
            DVec3::new(0.62, 0.58, 0.4 * depth),
        ),
    ]
}

/// The receivers' cases: the gentle waves under the mid sun over deep water (the surface cases'
/// `waves-mid-deep`), over each of [`RECEIVERS`].
pub fn receiver_cases() -> Vec<Case> {
    let base = cases(true)
        .into_iter()
        .find(|c| c.name == "waves-mid-deep")
        .expect("the quick cases hold waves-mid-deep");
    RECEIVERS
        .iter()
        .map(|&r| {
            let mut c = base.clone();
            c.name = format!("receivers-{r}");
            let depth = c.water.depth;
            match r {
                "sand-bar" => c.floor.terrain = Some(sand_bar(depth)),
                "rocks" => c.floor.terrain = Some(rocks(depth)),
                "walls" => c.floor.walls = true,
                "objects" => {
                    c.objects = crate_and_overhang(depth);
                    c.floor.solids = Solids::of(&c.objects);
                }
                _ => {}
            }
            c
        })
        .collect()
}
