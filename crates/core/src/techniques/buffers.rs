//! Intermediate buffers: the stages of a technique as pictures, so that its work can be watched as
//! the water moves (the viewer's buffer window; any front end). Each technique lists its buffers in
//! its [`Descriptor`](super::Descriptor) and draws them with its CPU twin's passes (the GPU passes
//! keep their textures to themselves and match the twin to the tolerances their tests state), from
//! the same input, only while a view asks. The water's heights are every water technique's.
//!
//! These are the kinds a descriptor is made of, so they know no descriptor: the buffers an entry
//! offers ([`Buffer::available`]) and drawing one ([`super::describe::picture`]) are the
//! descriptor's, in [`super::describe`].

use glam::DVec3;

use crate::plot::Picture;
use crate::scene::{Scene, Water};
use crate::water::Surface;
use crate::{Error, Result};

/// One kind of buffer a technique can show.
#[derive(Debug)]
pub struct BufferDesc {
    /// What `--buffer` takes: `yuksel-offset`, or `cascade` for `cascade:K`.
    pub key: &'static str,
    /// Its name in a view, `{k}` standing for the index of an indexed buffer.
    pub label: &'static str,
    /// Whether it is one of several (`cascade:0` to `cascade:3`), and of how many.
    pub index: Option<Index>,
    /// What a scene needs for it to be shown.
    pub needs: Needs,
}

/// The index of a buffer that is one of several.
#[derive(Debug)]
pub struct Index {
    /// What one is called (`channel`, `cascade`).
    pub name: &'static str,
    /// How many there are for the technique's own parameter table in a scene with what
    /// [`SceneHas`] says.
    pub count: fn(&toml::Table, &SceneHas) -> u32,
}

/// What a scene must have for a buffer to be offered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Needs {
    /// Nothing beyond a scene the technique runs on.
    Anything,
    /// A scene without water (a glass generator's distance map: the water is traced as a height
    /// field).
    NoWater,
    /// A point or spot light (a light cube map).
    PointLight,
    /// Objects under the water.
    Objects,
}

/// The water's heights on the map's lattice, as the grid-based techniques read them.
pub const HEIGHTS: BufferDesc = BufferDesc {
    key: "heights",
    label: "water heights",
    index: None,
    needs: Needs::Anything,
};

/// A buffer to show: one of a technique's kinds, and its index.
#[derive(Clone, Copy, Debug)]
pub struct Buffer {
    /// Its kind.
    pub desc: &'static BufferDesc,
    /// Which of several (`K` in `cascade:K`); 0 for a buffer that is not indexed.
    pub index: u32,
}

impl PartialEq for Buffer {
    fn eq(&self, other: &Self) -> bool {
        self.desc.key == other.desc.key && self.index == other.index
    }
}

impl Eq for Buffer {}

impl Buffer {
    /// The first (index 0) buffer of kind `desc`.
    pub fn new(desc: &'static BufferDesc) -> Self {
        Buffer { desc, index: 0 }
    }

    /// Its name in a view: the label with `{k}` replaced by its index (`yuksel pass 1: channel 2`).
    pub fn name(&self) -> String {
        self.desc.label.replace("{k}", &self.index.to_string())
    }

    /// How many of its kind there are (1 for a buffer that is not indexed).
    pub fn count(&self, own: &toml::Table, has: &SceneHas) -> u32 {
        self.desc.index.as_ref().map_or(1, |i| (i.count)(own, has))
    }

    /// The name `--buffer` takes: `heights`, `cascade:2`.
    pub fn key(&self) -> String {
        if self.desc.index.is_some() {
            format!("{}:{}", self.desc.key, self.index)
        } else {
            self.desc.key.to_string()
        }
    }

    /// Whether `self` and `other` are the same kind (any index).
    pub fn same_kind(&self, other: &Buffer) -> bool {
        self.desc.key == other.desc.key
    }

    /// The buffer a [`key`](Self::key) names (`:K` may be left out for 0), if it is one of
    /// `available`; else an error listing those.
    pub fn parse(s: &str, available: &[Buffer]) -> Result<Buffer> {
        let (name, index) = match s.split_once(':') {
            Some((n, k)) => (
                n,
                k.parse::<u32>()
                    .map_err(|_| Error::Unavailable(format!("`{s}`: `{k}` is not an index")))?,
            ),
            None => (s, 0),
        };
        available
            .iter()
            .find(|b| b.desc.key == name && (b.desc.index.is_some() || index == 0))
            .map(|b| Buffer {
                desc: b.desc,
                index,
            })
            .ok_or_else(|| {
                let keys: Vec<String> = available.iter().map(Buffer::key).collect();
                Error::Unavailable(format!(
                    "no buffer `{s}` for this technique here; it has: {}",
                    keys.join(", ")
                ))
            })
    }
}

/// What of a scene decides which buffers a technique has there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneHas {
    /// The scene has water (the water techniques' buffers).
    pub water: bool,
    /// A point or spot light (a light cube map).
    pub point_light: bool,
    /// Objects under the water (receivers of paper 3's caustics): how many.
    pub objects: u32,
}

impl SceneHas {
    /// What `scene` has.
    pub fn of(scene: &Scene) -> Self {
        SceneHas {
            water: scene.water.is_some(),
            point_light: scene.light.position.is_some(),
            objects: scene.objects.len() as u32,
        }
    }
}

/// The inputs of a buffer computation.
pub struct BufferInput<'a> {
    /// The parameter tables keyed by table, as a [`super::Spec`]'s.
    pub params: &'a toml::Table,
    /// The scene with the frame's sun and map size (the glass generators' buffers read it).
    pub scene: &'a Scene,
    /// The water as the technique sees it and its surface this frame, in a scene with water.
    pub water: Option<(&'a Water, &'a dyn Surface)>,
    /// The frame's sun: the unit direction the sunlight travels, z < 0, world frame.
    pub light: DVec3,
    /// Side of the square caustics map the buffers are drawn at, texels (the water's heights are
    /// sampled on this lattice).
    pub map_size: usize,
}

impl<'a> BufferInput<'a> {
    /// The water and its surface, or the error a water buffer gives without them.
    pub fn water(&self) -> Result<(&'a Water, &'a dyn Surface)> {
        self.water
            .ok_or_else(|| Error::Unavailable("the scene has no water".into()))
    }

    /// The scene as the water techniques see it this frame: the water as animated, the frame's
    /// sun.
    pub fn scene_with_water(&self) -> Result<(Scene, &'a dyn Surface)> {
        let (water, surface) = self.water()?;
        let mut scene = self.scene.clone();
        scene.water = Some(water.clone());
        scene.light.direction = self.light;
        Ok((scene, surface))
    }
}

/// How a technique draws one of its buffers.
pub type DrawBuffer = fn(&BufferInput, Buffer) -> Result<Picture>;

/// The entry of a technique without buffers of its own.
pub fn no_buffers(_: &BufferInput, buffer: Buffer) -> Result<Picture> {
    Err(Error::Unavailable(format!(
        "no buffer `{}` for this technique",
        buffer.key()
    )))
}

/// An index below `count`, or the error naming the range (`what`: "objects", "cascades").
pub fn check_index(index: u32, count: usize, what: &str) -> Result<usize> {
    let k = index as usize;
    if k >= count {
        return Err(Error::Unavailable(format!(
            "there are {count} {what} (0 to {})",
            count.saturating_sub(1)
        )));
    }
    Ok(k)
}
