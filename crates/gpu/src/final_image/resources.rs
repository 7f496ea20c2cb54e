//! The textures and buffers the final image binds: the layouts' entries, the uploads of CPU-made
//! inputs (caustics maps, walls' maps) and the storage buffers that may not be empty.

use crate::pass::float_texture;
use crate::receivers::LightSpaceUniform;
use caustics_core::map::CausticsMap;
use caustics_core::walls::WallMaps;

use crate::{GpuContext, GpuError};

pub(super) fn texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        // Read with textureLoad only, so 32-bit float textures need not be filterable.
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// Upload CPU-made walls' maps (the reference's) as the final image reads them: an `Rgba32Float`
/// 2D array texture of four layers, as wide as the widest wall
/// ([`WallsOutput`](crate::technique::WallsOutput)'s layout), and each layer's column count. Once
/// per set of maps, not per frame.
pub fn upload_walls(
    ctx: &GpuContext,
    maps: &WallMaps,
) -> Result<(wgpu::Texture, [u32; 4]), GpuError> {
    let cols = maps.maps.each_ref().map(|m| m.cols as u32);
    let width = cols.iter().copied().max().unwrap_or(1).max(1);
    let rows = maps.maps[0].rows as u32;
    let mut texels = vec![[0f32; 4]; (width * rows) as usize * 4];
    for (k, m) in maps.maps.iter().enumerate() {
        for i in 0..m.rows {
            for j in 0..m.cols {
                let t = m.texels[i * m.cols + j];
                texels[(k * rows as usize + i) * width as usize + j] = [t[0], t[1], t[2], 1.0];
            }
        }
    }
    let texture = float_texture(
        ctx,
        "walls' maps",
        wgpu::TextureFormat::Rgba32Float,
        (width, rows, 4),
        bytemuck::cast_slice(&texels),
    )?;
    Ok((texture, cols))
}

pub(super) fn storage_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A CPU caustics map as the `Rgba32Float` texture a technique's floor output is
/// ([`Output::Floor`](crate::technique::Output::Floor)), for
/// [`FinalImage::frame`](super::FinalImage::frame) or
/// [`FinalImage::render`](super::FinalImage::render).
pub fn upload_map(ctx: &GpuContext, map: &CausticsMap) -> Result<wgpu::Texture, GpuError> {
    float_texture(
        ctx,
        "caustics map",
        wgpu::TextureFormat::Rgba32Float,
        (map.width as u32, map.height as u32, 1),
        bytemuck::cast_slice(&rgba32(&map.texels)),
    )
}

/// A CPU technique's light-space deposit and its receivers' heights, uploaded for the final
/// image's objects, with the uniform that places them.
pub fn upload_light_space(
    ctx: &GpuContext,
    light: &caustics_core::receivers::LightSpace,
) -> Result<(wgpu::Texture, wgpu::Texture, LightSpaceUniform), GpuError> {
    let deposit = upload_map(ctx, &light.deposit)?;
    let heights = crate::receivers::heights_texture(ctx, Some(&light.receivers))?;
    let uniform = LightSpaceUniform::of(&light.receivers, light.absorption, light.wrap);
    Ok((deposit, heights, uniform))
}

/// `map`'s texels into mip 0 of `texture` (`Rgba32Float`, `COPY_DST`, at least the map's size):
/// a floor map the CPU made, for a texture that lives across frames.
pub fn write_map(ctx: &GpuContext, texture: &wgpu::Texture, map: &CausticsMap) {
    ctx.write_texture(
        texture.as_image_copy(),
        bytemuck::cast_slice(&rgba32(&map.texels)),
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(16 * map.width as u32),
            rows_per_image: Some(map.height as u32),
        },
        wgpu::Extent3d {
            width: map.width as u32,
            height: map.height as u32,
            depth_or_array_layers: 1,
        },
    );
}

/// An RGB image as `Rgba32Float` texels (alpha 1).
pub(super) fn rgba32(texels: &[[f32; 3]]) -> Vec<[f32; 4]> {
    texels.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect()
}
