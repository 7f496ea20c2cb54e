//! Technique `volumes`: "Interactive rendering of caustics on underwater objects using illumination
//! volumes, colour and depth textures" (paper 3), the CPU twin of `caustics-gpu`'s `volumes` module,
//! pass for pass.
//!
//! # The method
//! - **Representation** (§3.1, §3.2, Fig. 3): each object gets a bounding box whose front face is
//!   perpendicular to the *refracted viewing ray* `v` (the ray from the camera to the object's centre,
//!   refracted at the flat water surface). An orthographic projection along `v` gives its *depth
//!   texture* (the depth of the nearest surface along `v` in every texel, with the surface normal
//!   beside it) and its *diffuse map* (the object's colour as seen along `v`). `planes` *reference
//!   planes* slice the box perpendicular to `v` at the centres of equal slabs of thickness `Δ`.
//! - **Fast intersection test** (§3.1, Fig. 2): a point on a reference plane is moved to texture space
//!   `(x', y', z')`; `(x', y')` indexes the depth texture and the point is accepted when the stored
//!   depth lies within the plane's acceptance range, `|depth − z'| ≤ Δ/2`. The threshold is the
//!   distance between planes: the ranges of neighbouring planes tile the box, so every surface point
//!   is accepted by exactly one plane.
//! - **Illumination volumes** (§3.2, Fig. 4): the water surface is a triangle lattice; the light
//!   refracted at each vertex sweeps an illumination volume below each triangle. Its intersection
//!   with a reference plane is a triangle whose vertex intensities follow Eq. 3,
//!   `Ic = Ii (Aw cos θi) / (Ad cos θt) exp(−K d)`, with `Ad` the intersection triangle's area, `θt`
//!   the angle between the vertex's refracted ray and the plane's normal and `d` the vertex's path in
//!   the water. The triangle is drawn additively into the object's *caustics map*; a fragment is kept
//!   only where the depth test accepts it, and then carries `Ic · max(0, −t · n)`, the irradiance on
//!   the surface of normal `n` (the Lambert factor of `Id` in Eq. 4, applied per beam because every
//!   beam has its own direction `t`). Finally `Io = Ic Id + Ia` over the diffuse map (Eq. 4), with
//!   the ambient term modulated by the object's colour, as a diffuse surface reflects it.
//!
//! # Units and layout
//! Every map holds relative irradiance, as the rest of the project: 1 is what the sun gives through
//! flat, clear water onto a horizontal surface. `Ii Aw cos θi` is the flux crossing the water
//! triangle, expressed as the triangle's area projected along the sun onto the horizontal
//! (`−L · (e₁ × e₂) / (2 |L_z|)`, as in [`crate::reference`]), times the Fresnel transmittance
//! relative to flat water `T(θi) / T(θ0)`. Under flat water a surface of normal `n` then receives
//! `max(0, −t₀ · n) / |t₀_z|` (the cosine law), and the floor 1.
//!
//! - One *caustics map* per object: `texture x texture` texels in the object's frame `(a, b, v)`, texel
//!   `(i, j)` centred at `a u + b w` with `u = u₀ + (j + ½) du`, `w = w₀ + (i + ½) dw`; the same texels
//!   as its depth texture and diffuse map.
//! - The *floor map*: the caustics-map square `[0, size]²` of the scene (like every other technique's),
//!   drawn from the same illumination volumes cut by the floor plane `z = 0`.
//! - With the pool's walls ([`VolumesInput::walls`]), the *walls' maps*
//!   ([`crate::walls`]'s layout): the same volumes cut by each wall's plane, drawn in the wall's
//!   texel space `(along, z)`; the water is then the square alone and nothing reaches the floor
//!   from beyond it ([`illumination::wall_pass`] argues why floor and walls each keep exactly
//!   their light).
//!
//! # Beyond the paper (stated)
//! - Shadows: one orthographic depth texture of all objects along the flat-water refracted sun `t₀`
//!   (a shadow map). Floor fragments behind an object, and object fragments behind another object or
//!   another part of themselves, are rejected. The paper leaves occlusion out; without it the floor
//!   under an object would be lit.
//! - The illumination volumes drawn for an object are those of the lattice cells whose light can
//!   reach its box (its footprint on the water widened by the waves' deflection), not the whole water.
//! - A terrain floor ([`VolumesSetup::with_floor`]): each lattice vertex's ray ends where it first
//!   meets the receivers' heights ([`illumination::meet_pass`]), as the paper's volumes end on its
//!   objects' depth textures; each volume is drawn in the light's space between its rays' ends with
//!   the flux over that triangle's area ([`illumination::received_floor_pass`]), and each floor
//!   texel looks it up with its face's cosine and the depth test ([`crate::receivers`]).
//!
//! # Where it departs from the reference
//! The acceptance range puts every beam slice up to `Δ/2` from the true surface along the view, so
//! a caustic lands displaced by up to `Δ/2 · tan(angle between t and v)` in texture space; only the
//! surface seen along `v` is represented (that is all the eye sees); fragments are point-sampled at
//! texel centres, so a focused beam thinner than a texel can be missed or land whole in one texel.
//!
//! Passes (GPU twin in `caustics-gpu/src/volumes`): [`representation::depth_pass`] (depth texture,
//! diffuse map, shadow map), [`illumination::water_pass`] (refracted rays at the lattice vertices),
//! [`illumination::slice_pass`] (illumination volumes × reference planes → object caustics map),
//! [`illumination::floor_pass`], [`illumination::wall_pass`] (with walls),
//! [`illumination::shade_pass`] (Eq. 4), and the refracted view of §3.3, [`view::view_pass`].

mod buffers;
pub mod illumination;
pub mod reference;
pub mod representation;
#[cfg(test)]
mod tests;
pub mod view;

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::grid::Grid;
use crate::map::CausticsMap;
use crate::mesh::{MeshBvh, TriangleMesh};
use crate::optics::{air_transmittance, refract};
use crate::receivers::Shared;
use crate::scene::{Material, Scene};
use crate::walls::WallMaps;

pub use representation::OrthoView;

use super::describe::{
    Descriptor, Kind, Param, ParamDefault as D, Receiver, check_params, read_params, serde_defaults,
};
use super::{Input, Job, JobOutput};

/// Paper 3 as registered.
pub const DESCRIPTOR: Descriptor = Descriptor {
    name: "volumes",
    table: "volumes",
    paper: "3",
    summary: "illumination volumes against colour + depth textures and reference planes, caustics on underwater objects",
    docs: "docs/volumes.md",
    input: Input::Water,
    receivers: &[Receiver::Floor, Receiver::Walls, Receiver::Objects],
    params: &[
        Param {
            sweep: &["5", "10", "25", "50"],
            ..Param::new(
                "planes",
                "reference planes",
                Kind::int(1, MAX_PLANES as i64),
                D::Int(10),
                "",
                "reference planes per object (§3.1; the paper's Fig. 6: 5 and 50)",
            )
        },
        Param::new(
            "texture",
            "object texture",
            Kind::int(2, MAX_TEXTURE as i64),
            D::Int(256),
            "texels per side",
            "each object's depth, diffuse and caustics textures",
        ),
        Param::new(
            "shadow",
            "shadow map",
            Kind::int(0, MAX_TEXTURE as i64),
            D::Int(512),
            "texels per side",
            "the shadow map along the refracted sun; 0 turns shadows off",
        ),
        Param::new(
            "water_cells",
            "water cells",
            Kind::int(0, MAX_TEXTURE as i64),
            D::Int(0),
            "per side",
            "water lattice cells along each side of the square; 0: the map's width",
        ),
        Param::on(
            "fresnel",
            "Fresnel",
            "each volume carries its Fresnel transmittance",
        ),
        Param::on(
            "absorption",
            "absorption",
            "exp(-K d) along each volume's path",
        ),
        Param::new(
            "ambient",
            "ambient",
            Kind::float(0.0, 1.0e6),
            D::Float(0.2),
            "",
            "Ia of Eq. 4, relative to the sun through flat water",
        ),
    ],
    fixed: &[],
    point_light: false,
    buffers: buffers::BUFFERS,
    draw_buffer: buffers::draw_buffer,
    reference: false,
    validate: |t| VolumesParams::from_table(t).map(|_| ()),
    own_defaults: serde_defaults::<VolumesParams>,
    cpu: run_cpu,
};

/// What a job gives paper 3 (both twins): its input (the scene's diffuse objects as receivers),
/// setup, and the water sampled on its lattice.
pub fn job_setup(
    job: &Job,
    table: &toml::Table,
) -> Result<(VolumesSetup, VolumesInput, Grid, bool)> {
    let params = VolumesParams::from_table(table)?;
    job.with_surface(DESCRIPTOR.name, |water, surface| {
        let input = VolumesInput::from_scene(job.scene)?;
        let setup = VolumesSetup::new(&params, &input)?.with_floor(job.floor(), None);
        let n = (input.size / setup.lattice.cell).round() as usize;
        let heights = crate::water::sample_grid(surface, n, n, water.size);
        Ok((setup, input, heights, water.wrap))
    })
}

fn run_cpu(
    job: &Job,
    table: &toml::Table,
    _progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<JobOutput> {
    let (setup, input, heights, wrap) = job_setup(job, table)?;
    let out = caustics(&setup, &input, &heights, wrap);
    Ok(JobOutput::floor(out.floor, out.walls))
}

/// The technique's parameters, `[caustics.volumes]` in a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VolumesParams {
    /// Reference planes per object (the paper's Fig. 6 uses 5 and 50).
    pub planes: u32,
    /// Side of each object's depth texture, diffuse map and caustics map, texels.
    pub texture: u32,
    /// Water lattice cells along each side of the scene square; 0: the caustics map's width.
    pub water_cells: u32,
    /// Side of the shadow map along the refracted sun, texels; 0 turns shadows off.
    pub shadow: u32,
    /// Each volume carries its Fresnel transmittance relative to flat water, `T(θi) / T(θ0)`
    /// (the `Ii` of Eq. 3 as the light that crosses the surface).
    pub fresnel: bool,
    /// Each volume's light is attenuated by `exp(−K d)` along its path `d` in the water (Eq. 3),
    /// with the scene's `K`.
    pub absorption: bool,
    /// `Ia` of Eq. 4, relative to the sun through flat water.
    pub ambient: f64,
}

impl Default for VolumesParams {
    fn default() -> Self {
        VolumesParams {
            planes: 10,
            texture: 256,
            water_cells: 0,
            shadow: 512,
            fresnel: true,
            absorption: true,
            ambient: 0.2,
        }
    }
}

/// The most reference planes: beyond this the slabs are thinner than a texel of any useful texture.
pub const MAX_PLANES: u32 = 512;
/// The largest texture side.
pub const MAX_TEXTURE: u32 = 4096;

impl VolumesParams {
    /// The `volumes` table of `table` (a scene's `[caustics]`), defaults where it is absent,
    /// checked as [`validate`](Self::validate) does.
    pub fn from_table(table: &toml::Table) -> Result<Self> {
        read_params(table, &DESCRIPTOR, Self::validate)
    }

    /// Check every value's range; the error names the field out of it.
    pub fn validate(&self) -> Result<()> {
        check_params(&DESCRIPTOR, self)
    }
}

/// One underwater object as the technique sees it.
#[derive(Clone, Debug)]
pub struct VolumesObject {
    /// Its surface, in the scene's frame (z up, the floor plane at z = 0), under the water.
    pub mesh: TriangleMesh,
    /// Linear RGB albedo: what the diffuse map holds where the object covers a texel.
    pub albedo: DVec3,
}

/// What the technique needs from a scene.
#[derive(Clone, Debug)]
pub struct VolumesInput {
    /// The scene's objects, all diffuse: the receivers of the caustics, in the scene's order.
    pub objects: Vec<VolumesObject>,
    /// Side of the water square `[0, size]²`, world units.
    pub size: f64,
    /// The water's rest level above the floor plane z = 0, world units.
    pub depth: f64,
    /// Index of refraction of the water (air is 1).
    pub ior: f64,
    /// Absorption coefficient `K` per RGB channel, per world unit of path in the water.
    pub absorption: DVec3,
    /// The direction the sunlight travels, z < 0 (need not be normalised).
    pub light: DVec3,
    /// The eye camera's position, world frame: it fixes each object's refracted viewing ray `v`
    /// (§3.1).
    pub camera: DVec3,
    /// Floor map resolution: texels along x.
    pub width: usize,
    /// Floor map resolution: texels along y.
    pub height: usize,
    /// The pool's walls receive light (`[floor] walls`): the water is the square alone
    /// and the wall pass draws the walls' maps ([`illumination::wall_pass`]).
    pub walls: bool,
}

impl VolumesInput {
    /// The technique's view of `scene`: an error where it has no water or a glass object.
    pub fn from_scene(scene: &Scene) -> Result<Self> {
        let water = scene.water.as_ref().ok_or_else(|| {
            Error::InvalidParameter(format!(
                "scene `{}` has no water: technique volumes casts caustics from a water surface",
                scene.name
            ))
        })?;
        let mut objects = Vec::new();
        for (k, o) in scene.objects.iter().enumerate() {
            match &o.material {
                Material::Diffuse { color } => objects.push(VolumesObject {
                    mesh: o.mesh.clone(),
                    albedo: *color,
                }),
                Material::Glass { .. } => {
                    return Err(Error::field(
                        format!("objects[{k}].material"),
                        "is glass: technique volumes receives caustics on diffuse objects only",
                    ));
                }
            }
        }
        Ok(VolumesInput {
            objects,
            size: water.size,
            depth: water.depth,
            ior: water.ior,
            absorption: water.absorption,
            light: scene.light.direction,
            camera: scene.camera.position,
            width: scene.caustics.width as usize,
            height: scene.caustics.height as usize,
            walls: scene.floor.walls,
        })
    }
}

/// The water triangle lattice: vertex `(i, j)` at `origin + (j, i) cell` on the surface, cells
/// `(i, j)` for `i < ny`, `j < nx`, two triangles each with diagonals alternating in a checkerboard
/// (as the reference's), so the lattice is its own mirror image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lattice {
    /// Vertex `(0, 0)`'s horizontal position `(x, y)`, world units: `(0, 0)` with walls; without
    /// them shifted back up the refracted sun and widened, so that the light reaching the floor
    /// square from beyond the water square is swept too.
    pub origin: DVec2,
    /// Side of a square cell, world units.
    pub cell: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
}

impl Lattice {
    /// Vertices, `(nx + 1)(ny + 1)`, indexed row-major `i (nx + 1) + j`.
    pub fn vertex_count(&self) -> usize {
        (self.nx + 1) * (self.ny + 1)
    }

    /// Horizontal position `(x, y)` of vertex `(i, j)` (row `i` along y, column `j` along x), world
    /// units.
    pub fn position(&self, i: usize, j: usize) -> DVec2 {
        self.origin + DVec2::new(j as f64, i as f64) * self.cell
    }

    /// Vertex indices of triangle `which` (0 or 1) of cell `(i, j)`.
    pub fn triangle(&self, i: usize, j: usize, which: usize) -> [usize; 3] {
        let w = self.nx + 1;
        let (v00, v01, v10, v11) = (
            i * w + j,
            i * w + j + 1,
            (i + 1) * w + j,
            (i + 1) * w + j + 1,
        );
        match ((i + j).is_multiple_of(2), which) {
            (true, 0) => [v00, v01, v11],
            (true, _) => [v00, v11, v10],
            (false, 0) => [v00, v01, v10],
            (false, _) => [v01, v11, v10],
        }
    }
}

/// A rectangle of lattice cells, `i0..i1` by `j0..j1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRect {
    /// First row of cells (along y).
    pub i0: usize,
    /// One past the last row.
    pub i1: usize,
    /// First column of cells (along x).
    pub j0: usize,
    /// One past the last column.
    pub j1: usize,
}

impl CellRect {
    /// Columns of cells it spans.
    pub fn cols(&self) -> usize {
        self.j1 - self.j0
    }
    /// Lattice triangles it holds, two per cell.
    pub fn triangles(&self) -> usize {
        2 * (self.i1 - self.i0) * self.cols()
    }
    /// Lattice triangle `k` of the rectangle (row-major cells, two triangles per cell).
    pub fn triangle(&self, lattice: &Lattice, k: usize) -> [usize; 3] {
        let cell = k / 2;
        lattice.triangle(
            self.i0 + cell / self.cols(),
            self.j0 + cell % self.cols(),
            k % 2,
        )
    }
}

/// One object's representation (§3.1-3.2): its view-aligned box and textures' frame, its reference
/// planes, and the lattice cells whose illumination volumes can reach it.
#[derive(Clone, Debug)]
pub struct ObjectView {
    /// The box around the object with its front face across the refracted viewing ray `v`, and
    /// the frame of its depth texture, diffuse map and caustics map.
    pub view: OrthoView,
    /// Reference planes slicing the box across `v` (§3.1).
    pub planes: usize,
    /// Linear RGB albedo of the object.
    pub albedo: DVec3,
    /// The lattice cells whose illumination volumes can reach the box.
    pub cells: CellRect,
}

impl ObjectView {
    /// Distance between reference planes, `Δ`: also the width of each plane's acceptance range.
    pub fn spacing(&self) -> f64 {
        self.view.extent().z / self.planes as f64
    }

    /// Depth of plane `k` below the box's front face, at the centre of its slab.
    pub fn plane_depth(&self, k: usize) -> f64 {
        (k as f64 + 0.5) * self.spacing()
    }
}

/// Everything the passes share, derived once (the GPU uploads the same numbers).
#[derive(Clone, Debug)]
pub struct VolumesSetup {
    /// The technique's parameters, checked.
    pub params: VolumesParams,
    /// Side of the water square `[0, size]²`, world units.
    pub size: f64,
    /// The water's rest level above the floor plane z = 0, world units.
    pub depth: f64,
    /// Index of refraction of the water.
    pub ior: f64,
    /// Air to water, `η = 1 / ior`: the ratio Snell's law takes for the sunlight entering.
    pub eta: f64,
    /// `K` per channel, zero without the absorption option.
    pub absorption: DVec3,
    /// Unit direction the sunlight travels, z < 0.
    pub light: DVec3,
    /// The flat-water refracted sun.
    pub t0: DVec3,
    /// `T(θ0)`, or 1 without the Fresnel option.
    pub t_flat: f64,
    /// The water triangle lattice the illumination volumes are swept from.
    pub lattice: Lattice,
    /// Floor map texels along x.
    pub width: usize,
    /// Floor map texels along y.
    pub height: usize,
    /// Each object's representation, in the input's order.
    pub objects: Vec<ObjectView>,
    /// The shadow map's frame (all objects along `t0`), `None` without shadows.
    pub shadow: Option<OrthoView>,
    /// Depth tolerance of the shadow test: three shadow-map texels.
    pub shadow_bias: f64,
    /// The pool's walls receive light ([`VolumesInput::walls`]).
    pub walls: bool,
    /// What the floor's light meets instead of the plane `z = 0` ([`VolumesSetup::with_floor`]).
    pub receivers: Option<Shared>,
}

/// A mesh the technique can use: not empty, not larger than the pool, under the water. An open mesh
/// is accepted (stated fallback): the depth texture needs only the surface seen along the view, and
/// an open mesh shadows with the surface it has.
pub fn check_mesh(mesh: &TriangleMesh, what: &str, size: f64, depth: f64) -> Result<()> {
    mesh.validate(what)?;
    let (lo, hi) = mesh.bounds();
    let extent = (hi - lo).max_element();
    if extent > size {
        return Err(Error::field(
            what,
            format!(
                "is {extent:.3} units across, larger than the pool of side {size}: its illumination volumes would cover more than the water"
            ),
        ));
    }
    if extent <= 0.0 {
        return Err(Error::field(
            what,
            "has no extent (all its vertices coincide)",
        ));
    }
    if hi.z >= depth {
        return Err(Error::field(
            what,
            format!(
                "reaches z = {:.3}, above the water level {depth}: technique volumes lights underwater objects",
                hi.z
            ),
        ));
    }
    if !mesh.is_closed() {
        tracing::warn!(
            "{what} is not closed: technique volumes uses the surface it has (the side seen along the view)"
        );
    }
    Ok(())
}

/// The refracted viewing direction towards `target` from a camera at `camera`: refracted at the flat
/// surface when the camera is above the water, straight otherwise.
pub fn refracted_view(camera: DVec3, target: DVec3, depth: f64, ior: f64) -> DVec3 {
    let d = (target - camera).normalize_or(DVec3::NEG_Z);
    if camera.z > depth && d.z < 0.0 {
        refract(d, DVec3::Z, 1.0 / ior).unwrap_or(DVec3::NEG_Z)
    } else {
        d
    }
}

impl VolumesSetup {
    /// The setup for `input` with `params`: checks the parameters, the light and every object's
    /// mesh ([`check_mesh`]), lays out the lattice and each object's box, planes and cells.
    pub fn new(params: &VolumesParams, input: &VolumesInput) -> Result<Self> {
        params.validate()?;
        let light = super::check_inputs(input.width, input.height, input.light)?;
        for (name, value) in [
            ("water size", input.size),
            ("water depth", input.depth),
            ("ior", input.ior),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::InvalidParameter(format!(
                    "technique volumes needs a positive {name}, got {value}"
                )));
            }
        }
        for (k, o) in input.objects.iter().enumerate() {
            check_mesh(&o.mesh, &format!("objects[{k}]"), input.size, input.depth)?;
        }
        let eta = 1.0 / input.ior;
        let t0 = refract(light, DVec3::Z, eta).expect("air to water never reflects totally");
        let cells = if params.water_cells == 0 {
            input.width
        } else {
            params.water_cells as usize
        };
        let cell = input.size / cells as f64;
        let lattice = if input.walls {
            // With walls the light enters the pool through its own surface only (as the
            // reference's traced domain with walls): the water square, nothing from beyond it.
            Lattice {
                origin: DVec2::ZERO,
                cell,
                nx: cells,
                ny: cells,
            }
        } else {
            // Shifted back by the mean travel of the refracted light, widened by the waves'
            // deflection, as the reference's traced domain.
            let travel = -t0.truncate() * (input.depth / -t0.z);
            let margin = 0.3 * input.depth + 2.0 * cell;
            let n = ((input.size + 2.0 * margin) / cell).ceil() as usize;
            Lattice {
                origin: travel - DVec2::splat(margin),
                cell,
                nx: n,
                ny: n,
            }
        };
        let objects = input
            .objects
            .iter()
            .map(|o| {
                let (lo, hi) = o.mesh.bounds();
                let v = refracted_view(input.camera, 0.5 * (lo + hi), input.depth, input.ior);
                let view = OrthoView::around(&[&o.mesh], v, params.texture as usize);
                ObjectView {
                    view,
                    planes: params.planes as usize,
                    albedo: o.albedo,
                    cells: footprint(&lattice, lo, hi, t0, input.depth),
                }
            })
            .collect();
        let meshes: Vec<&TriangleMesh> = input.objects.iter().map(|o| &o.mesh).collect();
        let shadow = (params.shadow > 0 && !meshes.is_empty())
            .then(|| OrthoView::around(&meshes, t0, params.shadow as usize));
        let shadow_bias = shadow
            .as_ref()
            .map_or(0.0, |s| 3.0 * s.texel().max_element());
        Ok(VolumesSetup {
            params: params.clone(),
            size: input.size,
            depth: input.depth,
            ior: input.ior,
            eta,
            absorption: if params.absorption {
                input.absorption
            } else {
                DVec3::ZERO
            },
            light,
            t0,
            t_flat: air_transmittance(params.fresnel, -light.z, input.ior),
            lattice,
            width: input.width,
            height: input.height,
            objects,
            shadow,
            shadow_bias,
            walls: input.walls,
            receivers: None,
        })
    }

    /// The floor's light meets `floor`'s terrain where it has one: each lattice vertex's ray ends
    /// on the receivers' map (at the map's resolution, `previous` where nothing it depends on
    /// changed), the volumes are drawn in the light's space and looked up per floor texel
    /// ([`crate::receivers`]). The walls and the objects keep their own passes.
    pub fn with_floor(mut self, floor: &crate::scene::Floor, previous: Option<&Shared>) -> Self {
        self.receivers = Shared::of_floor(
            previous, floor, false, self.size, self.depth, self.t0, self.width,
        );
        self
    }

    /// The walls' empty maps (their sizes) when the walls receive light.
    pub fn wall_layout(&self) -> Option<WallMaps> {
        self.walls
            .then(|| WallMaps::for_floor_map(self.width, self.height, self.size, self.depth))
    }

    /// All cells of the lattice: what the floor pass draws.
    pub fn all_cells(&self) -> CellRect {
        CellRect {
            i0: 0,
            i1: self.lattice.ny,
            j0: 0,
            j1: self.lattice.nx,
        }
    }
}

/// The lattice cells through which light can reach the box `lo..hi`: the box's corners traced back
/// up the flat-water refracted sun to the rest surface, widened by the waves' deflection.
fn footprint(lattice: &Lattice, lo: DVec3, hi: DVec3, t0: DVec3, depth: f64) -> CellRect {
    let mut a = DVec2::INFINITY;
    let mut b = DVec2::NEG_INFINITY;
    for k in 0..8 {
        let c = DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        let s = c.truncate() - t0.truncate() * ((depth - c.z) / -t0.z);
        a = a.min(s);
        b = b.max(s);
    }
    let margin = 0.3 * (depth - lo.z) + 2.0 * lattice.cell;
    let to_cell = |p: f64, o: f64| (p - o) / lattice.cell;
    let clamp = |x: f64, n: usize| x.clamp(0.0, n as f64) as usize;
    CellRect {
        i0: clamp(to_cell(a.y - margin, lattice.origin.y).floor(), lattice.ny),
        i1: clamp(to_cell(b.y + margin, lattice.origin.y).ceil(), lattice.ny),
        j0: clamp(to_cell(a.x - margin, lattice.origin.x).floor(), lattice.nx),
        j1: clamp(to_cell(b.x + margin, lattice.origin.x).ceil(), lattice.nx),
    }
}

/// One object's results, all `texture x texture` texels of its frame.
#[derive(Clone, Debug)]
pub struct ObjectMaps {
    /// `[depth, nx, ny, nz]`; a zero normal marks a texel the object does not cover.
    pub depth: Vec<[f32; 4]>,
    /// `[r, g, b, coverage]`.
    pub diffuse: Vec<[f32; 4]>,
    /// Relative irradiance on the surface, RGB.
    pub caustics: Vec<[f32; 3]>,
    /// `Io` of Eq. 4, RGB.
    pub image: Vec<[f32; 3]>,
}

/// The whole technique's output.
#[derive(Clone, Debug)]
pub struct VolumesOutput {
    /// Each object's maps, in the input's order.
    pub objects: Vec<ObjectMaps>,
    /// The floor's caustics map over the square `[0, size]²`, relative irradiance.
    pub floor: CausticsMap,
    /// The walls' maps ([`illumination::wall_pass`]), `None` without walls.
    pub walls: Option<WallMaps>,
    /// The shadow map (`[depth, n]` as a depth texture), empty without shadows.
    pub shadow: Vec<[f32; 4]>,
}

/// The whole technique on the CPU, the surface sampled as `heights` over the scene square (wrapped
/// when `wrap`).
pub fn caustics(
    setup: &VolumesSetup,
    input: &VolumesInput,
    heights: &Grid,
    wrap: bool,
) -> VolumesOutput {
    let bvhs: Vec<MeshBvh> = input.objects.iter().map(|o| o.mesh.bvh()).collect();
    let meshes: Vec<(&TriangleMesh, &MeshBvh)> =
        input.objects.iter().map(|o| &o.mesh).zip(&bvhs).collect();
    let shadow = setup
        .shadow
        .as_ref()
        .map_or_else(Vec::new, |v| representation::depth_pass(v, &meshes));
    let water = illumination::water_pass(setup, heights, wrap);
    let objects = setup
        .objects
        .iter()
        .enumerate()
        .map(|(k, o)| {
            let depth = representation::depth_pass(&o.view, &meshes[k..k + 1]);
            let diffuse = representation::diffuse_map(&depth, o.albedo);
            let caustics = illumination::slice_pass(setup, o, &depth, &water, &shadow);
            let image = illumination::shade_pass(&diffuse, &caustics, setup.params.ambient);
            ObjectMaps {
                depth,
                diffuse,
                caustics,
                image,
            }
        })
        .collect();
    let floor = match &setup.receivers {
        None => illumination::floor_pass(setup, &water, &shadow),
        Some(r) => {
            let hits = illumination::meet_pass(&water, r);
            let light = illumination::received_floor_pass(setup, r, &water, &hits, &shadow);
            crate::receivers::lookup(&light, r, wrap, DVec3::ZERO)
        }
    };
    let walls = setup
        .walls
        .then(|| illumination::wall_pass(setup, &water, &shadow));
    VolumesOutput {
        objects,
        floor,
        walls,
        shadow,
    }
}

/// The technique for a scene at its time, on the CPU.
pub fn render(scene: &Scene, params: &VolumesParams) -> Result<VolumesOutput> {
    let input = VolumesInput::from_scene(scene)?;
    let setup = VolumesSetup::new(params, &input)?.with_floor(&scene.floor, None);
    let water = scene.water.as_ref().expect("checked by from_scene");
    let surface = water.surface_at(scene.time)?;
    let n = (input.size / setup.lattice.cell).round() as usize;
    let heights = crate::water::sample_grid(surface.as_ref(), n, n, water.size);
    Ok(caustics(&setup, &input, &heights, water.wrap))
}
