//! The images egui draws from textures of ours.

use caustics_core::render::Image;
use caustics_gpu::GpuContext;

use super::super::ui::Shown;

/// An image egui draws from a texture of ours: registered once, rewritten in place, replaced
/// (under the same id) only when its size changes.
pub(super) struct GpuImage {
    texture: wgpu::Texture,
    pub(super) id: egui::TextureId,
    /// Whether `texture` is the viewer's own (written by [`set`](Self::set)) rather than the GPU
    /// frame's output ([`show`](Self::show)), which must never be written into.
    own: bool,
}

impl GpuImage {
    pub(super) fn new(ctx: &GpuContext, renderer: &mut egui_wgpu::Renderer) -> Self {
        let texture = image_texture(ctx, 1, 1);
        write_rgba(ctx, &texture, &[24, 26, 30, 255]);
        // egui's bind group for it.
        ctx.count_app(1, 0);
        let id = renderer.register_native_texture(
            &ctx.device,
            &texture.create_view(&Default::default()),
            wgpu::FilterMode::Linear,
        );
        GpuImage {
            texture,
            id,
            own: true,
        }
    }

    pub(super) fn set(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        width: u32,
        height: u32,
        rgba: &[u8],
    ) {
        if !self.own || (self.texture.width(), self.texture.height()) != (width, height) {
            self.replace(ctx, renderer, image_texture(ctx, width, height), true);
        }
        write_rgba(ctx, &self.texture, rgba);
    }

    /// Show picture `p`, and what the panel says of it.
    pub(super) fn picture(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        p: caustics_core::plot::Picture,
    ) -> Shown {
        self.set(ctx, renderer, p.width, p.height, &p.rgba);
        Shown {
            size: Some([p.width, p.height]),
            legend: p.legend,
            error: None,
        }
    }

    /// Show a texture of the GPU frame as it is: egui is told once per texture, no texel moves.
    pub(super) fn show(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        texture: &wgpu::Texture,
    ) {
        if self.texture != *texture {
            self.replace(ctx, renderer, texture.clone(), false);
        }
    }

    /// Draw `texture` under this image's id from now on (egui's bind group for it, counted).
    fn replace(
        &mut self,
        ctx: &GpuContext,
        renderer: &mut egui_wgpu::Renderer,
        texture: wgpu::Texture,
        own: bool,
    ) {
        self.texture = texture;
        self.own = own;
        ctx.count_app(1, 0);
        renderer.update_egui_texture_from_wgpu_texture(
            &ctx.device,
            &self.texture.create_view(&Default::default()),
            wgpu::FilterMode::Linear,
            self.id,
        );
    }
}

/// egui-wgpu reads a native texture as gamma-encoded `Rgba8Unorm`, which is what the final
/// image's sRGB bytes are.
fn image_texture(ctx: &GpuContext, width: u32, height: u32) -> wgpu::Texture {
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    let format = wgpu::TextureFormat::Rgba8Unorm;
    app_texture(ctx, "viewer image", (width, height), format, usage)
}

/// A 2D texture of the viewer's own, counted as the app's.
pub(super) fn app_texture(
    ctx: &GpuContext,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    ctx.count_app(1, 0);
    ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

fn write_rgba(ctx: &GpuContext, texture: &wgpu::Texture, rgba: &[u8]) {
    let (w, h) = (texture.width(), texture.height());
    debug_assert_eq!(rgba.len(), (w * h * 4) as usize);
    ctx.count_app(0, rgba.len() as u64);
    ctx.queue.write_texture(
        texture.as_image_copy(),
        rgba,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * w),
            rows_per_image: Some(h),
        },
        texture.size(),
    );
}

pub(super) fn rgba_of(image: &Image) -> Vec<u8> {
    image
        .rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}
