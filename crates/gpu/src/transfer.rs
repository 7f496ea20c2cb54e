//! Moving data between the CPU and the GPU: height fields up as textures, results back from buffers
//! and textures (with the row padding wgpu requires).

use crate::{GpuContext, GpuError};
use wgpu::BufferUsages as B;

impl GpuContext {
    /// Read a whole buffer (which must have `COPY_SRC` usage) as plain data.
    pub fn read_buffer<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer) -> Result<Vec<T>, GpuError> {
        let size = buffer.size();
        let staging = self.buffer("readback", size, B::COPY_DST | B::MAP_READ);
        let mut encoder = self.encoder("readback");
        encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit([encoder.finish()]);
        self.map_and_copy(&staging, |bytes| bytemuck::cast_slice(bytes).to_vec())
    }

    /// Read mip level 0 of a 2-D texture (with `COPY_SRC` usage) whose texels are `T` (e.g. `f32` for
    /// `R32Float`, `[f32; 4]` for `Rgba32Float`, `[u8; 4]` for `Rgba8Unorm`), rows from row 0.
    pub fn read_texture<T: bytemuck::Pod>(
        &self,
        texture: &wgpu::Texture,
    ) -> Result<Vec<T>, GpuError> {
        self.read_texture_layer(texture, 0)
    }

    /// [`read_texture`](Self::read_texture) of array layer `layer`.
    pub fn read_texture_layer<T: bytemuck::Pod>(
        &self,
        texture: &wgpu::Texture,
        layer: u32,
    ) -> Result<Vec<T>, GpuError> {
        self.read_texture_mip(texture, layer, 0)
    }

    /// [`read_texture_layer`](Self::read_texture_layer) of mip level `mip`.
    pub fn read_texture_mip<T: bytemuck::Pod>(
        &self,
        texture: &wgpu::Texture,
        layer: u32,
        mip: u32,
    ) -> Result<Vec<T>, GpuError> {
        let size = texture.size().mip_level_size(mip, texture.dimension());
        let (w, h) = (size.width, size.height);
        let texel = std::mem::size_of::<T>() as u32;
        let row = w * texel;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let staging = self.buffer(
            "texture readback",
            padded as u64 * h as u64,
            B::COPY_DST | B::MAP_READ,
        );
        let mut encoder = self.encoder("readback");
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                mip_level: mip,
                origin: wgpu::Origin3d {
                    x: 0,
                    y: 0,
                    z: layer,
                },
                ..texture.as_image_copy()
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        self.map_and_copy(&staging, |bytes| {
            let mut out = Vec::with_capacity((w * h) as usize);
            for r in 0..h as usize {
                let start = r * padded as usize;
                out.extend_from_slice(bytemuck::cast_slice(&bytes[start..start + row as usize]));
            }
            out
        })
    }

    /// Read a technique's output texture (`Rgba32Float`, or `Rgba16Float` where the device cannot
    /// blend 32-bit floats) as `[f32; 4]` texels: for tests, `--raw` and the viewer's map window.
    pub fn read_rgba_f32(&self, texture: &wgpu::Texture) -> Result<Vec<[f32; 4]>, GpuError> {
        self.read_rgba_f32_layer(texture, 0)
    }

    /// [`read_rgba_f32`](Self::read_rgba_f32) of array layer `layer` (a wall map, [`crate::technique::Technique::walls`]).
    pub fn read_rgba_f32_layer(
        &self,
        texture: &wgpu::Texture,
        layer: u32,
    ) -> Result<Vec<[f32; 4]>, GpuError> {
        Ok(match texture.format() {
            wgpu::TextureFormat::Rgba16Float => self
                .read_texture_layer::<[u16; 4]>(texture, layer)?
                .into_iter()
                .map(|t| t.map(f16_to_f32))
                .collect(),
            _ => self.read_texture_layer(texture, layer)?,
        })
    }

    /// A technique's map texture ([`read_rgba_f32`](Self::read_rgba_f32)) as a caustics map over
    /// a `size`-metre square.
    pub fn read_map(
        &self,
        texture: &wgpu::Texture,
        size: f64,
    ) -> Result<caustics_core::map::CausticsMap, GpuError> {
        Ok(caustics_core::map::CausticsMap {
            width: texture.width() as usize,
            height: texture.height() as usize,
            size,
            texels: self
                .read_rgba_f32(texture)?
                .into_iter()
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
        })
    }

    /// Submit `encoder`, the timestamps of its passes resolved into `timer` first.
    pub fn submit_timed(&self, mut encoder: wgpu::CommandEncoder, timer: Option<&crate::GpuTimer>) {
        if let Some(t) = timer {
            t.resolve(&mut encoder);
        }
        self.queue.submit([encoder.finish()]);
    }

    fn map_and_copy<R>(
        &self,
        staging: &wgpu::Buffer,
        f: impl FnOnce(&[u8]) -> R,
    ) -> Result<R, GpuError> {
        self.traffic.readback();
        let slice = staging.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.wait()?;
        rx.recv()
            .map_err(|_| GpuError::Readback("the map callback never ran".into()))?
            .map_err(|e| GpuError::Readback(e.to_string()))?;
        let out = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| GpuError::Readback(e.to_string()))?;
            f(&view)
        };
        staging.unmap();
        Ok(out)
    }
}

impl GpuContext {
    /// Upload a height field as an `R32Float` texture (row 0 first), checking the device's limits.
    pub fn upload_grid(
        &self,
        what: &str,
        grid: &caustics_core::grid::Grid,
    ) -> Result<wgpu::Texture, GpuError> {
        self.check_texture_size(what, grid.cols as u32, grid.rows as u32)?;
        let texture = self.texture_2d(
            what,
            (grid.cols as u32, grid.rows as u32, 1),
            wgpu::TextureFormat::R32Float,
            wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
        );
        self.write_grid(&texture, grid);
        Ok(texture)
    }

    /// Overwrite an `R32Float` texture of the grid's size with the grid.
    pub fn write_grid(&self, texture: &wgpu::Texture, grid: &caustics_core::grid::Grid) {
        debug_assert_eq!(
            (texture.width(), texture.height()),
            (grid.cols as u32, grid.rows as u32)
        );
        self.write_texture(
            texture.as_image_copy(),
            bytemuck::cast_slice(&grid.data),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(grid.cols as u32 * 4),
                rows_per_image: Some(grid.rows as u32),
            },
            texture.size(),
        );
    }
}

/// A read-back buffer made once for `layers` textures of one size and format, for a loop that
/// reads the same textures every frame (`caustics bake`): the copies are recorded into the frame's
/// own encoder and each frame costs one map, nothing created.
pub struct Readback {
    staging: wgpu::Buffer,
    width: u32,
    height: u32,
    padded: u32,
    layers: u32,
    format: wgpu::TextureFormat,
}

impl Readback {
    /// For `layers` textures like `texture`, a technique's floor map (`Rgba32Float`, or
    /// `Rgba16Float`, [`crate::technique::Output`]).
    pub fn new(ctx: &GpuContext, texture: &wgpu::Texture, layers: u32) -> Self {
        let (width, height, format) = (texture.width(), texture.height(), texture.format());
        let texel = format.block_copy_size(None).unwrap_or(16);
        let padded = (width * texel).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT)
            * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let staging = ctx.buffer(
            "frame readback",
            padded as u64 * height as u64 * layers as u64,
            B::COPY_DST | B::MAP_READ,
        );
        Readback {
            staging,
            width,
            height,
            padded,
            layers,
            format,
        }
    }

    /// The textures' size, texels.
    pub fn size(&self) -> (usize, usize) {
        (self.width as usize, self.height as usize)
    }

    /// Record the copy of `texture` (of the size and format this was made for) into `encoder`, as
    /// layer `layer` of the next read.
    pub fn record(&self, encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture, layer: u32) {
        debug_assert!(layer < self.layers);
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &self.staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: self.padded as u64 * self.height as u64 * layer as u64,
                    bytes_per_row: Some(self.padded),
                    rows_per_image: Some(self.height),
                },
            },
            texture.size(),
        );
    }

    /// After the submission holding [`record`](Self::record)'s copies: the texels, row 0 first,
    /// layer after layer.
    pub fn read_rgba_f32(&self, ctx: &GpuContext) -> Result<Vec<[f32; 4]>, GpuError> {
        let (w, padded) = (self.width as usize, self.padded as usize);
        let h = self.height as usize * self.layers as usize;
        let half = self.format == wgpu::TextureFormat::Rgba16Float;
        ctx.map_and_copy(&self.staging, |bytes| {
            let mut out = Vec::with_capacity(w * h);
            for r in 0..h {
                let row = &bytes[r * padded..];
                if half {
                    let texels: &[[u16; 4]] = bytemuck::cast_slice(&row[..w * 8]);
                    out.extend(texels.iter().map(|t| t.map(f16_to_f32)));
                } else {
                    out.extend_from_slice(bytemuck::cast_slice(&row[..w * 16]));
                }
            }
            out
        })
    }
}

/// IEEE half to single precision: the texels of `Rgba16Float` maps read back.
pub fn f16_to_f32(h: u16) -> f32 {
    half::f16::from_bits(h).to_f32()
}
