//! The few lines every pass repeats: a compute pipeline from a [`PassSource`] with the layout the
//! shader implies, a bind group whose binding `k` is the `k`-th resource, a (timed) compute or
//! render pass, 2-D textures and their views, storage buffers, and uniform vectors packed as `f32`.

use caustics_core::walls::WallMaps;

use crate::shaders::PassSource;
use crate::{GpuContext, GpuError, GpuTimer};

/// `v` and `w` as a WGSL `vec4<f32>`.
pub(crate) fn v4(v: glam::DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

/// `v` as a WGSL `vec3<f32>`.
pub(crate) fn f3(v: glam::DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

/// Four values as a WGSL `vec4<f32>`.
pub(crate) fn f4(v: [f64; 4]) -> [f32; 4] {
    v.map(|x| x as f32)
}

/// The usage of a texture a compute pass writes and later passes read or copy out.
pub const STORAGE_OUT: wgpu::TextureUsages = wgpu::TextureUsages::STORAGE_BINDING
    .union(wgpu::TextureUsages::TEXTURE_BINDING)
    .union(wgpu::TextureUsages::COPY_SRC);

/// The usage of a texture a render pass draws into and later passes read or copy out.
pub const MAP_TARGET: wgpu::TextureUsages = wgpu::TextureUsages::RENDER_ATTACHMENT
    .union(wgpu::TextureUsages::TEXTURE_BINDING)
    .union(wgpu::TextureUsages::COPY_SRC);

/// A compute pipeline of a pass's `main`, its layout derived from the shader.
pub fn compute_pipeline(ctx: &GpuContext, source: &PassSource) -> wgpu::ComputePipeline {
    let module = source.module(&ctx.device);
    ctx.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(source.name),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// Something a bind group entry can hold: a whole buffer, a texture view, a sampler, or any
/// [`wgpu::BindingResource`] (a buffer range).
pub trait Binding {
    /// The entry's resource.
    fn resource(&self) -> wgpu::BindingResource<'_>;
}

impl<T: Binding + ?Sized> Binding for &T {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        (**self).resource()
    }
}

impl Binding for wgpu::Buffer {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        self.as_entire_binding()
    }
}

impl Binding for wgpu::TextureView {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::TextureView(self)
    }
}

impl Binding for wgpu::Sampler {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::Sampler(self)
    }
}

impl Binding for wgpu::BindingResource<'_> {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        self.clone()
    }
}

/// A bind group for `layout`, binding `k` to `resources[k]`.
pub fn bind_group(
    ctx: &GpuContext,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[&dyn Binding],
) -> wgpu::BindGroup {
    let numbered = resources.iter().enumerate();
    let entries: Vec<_> = numbered.map(|(k, &r)| (k as u32, r)).collect();
    bind_group_at(ctx, label, layout, &entries)
}

/// A bind group for `layout` with each `(binding, resource)`.
pub fn bind_group_at(
    ctx: &GpuContext,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    entries: &[(u32, &dyn Binding)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = entries
        .iter()
        .map(|&(binding, r)| wgpu::BindGroupEntry {
            binding,
            resource: r.resource(),
        })
        .collect();
    ctx.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// Bind groups for a pipeline's group 0, whose layout the shader implies.
pub trait Bind {
    /// Group 0's layout.
    fn layout0(&self) -> wgpu::BindGroupLayout;

    /// A bind group for group 0, binding `k` to `resources[k]`.
    fn bind(&self, ctx: &GpuContext, label: &str, resources: &[&dyn Binding]) -> wgpu::BindGroup {
        bind_group(ctx, label, &self.layout0(), resources)
    }

    /// A bind group for group 0 with each `(binding, resource)`.
    fn bind_at(
        &self,
        ctx: &GpuContext,
        label: &str,
        entries: &[(u32, &dyn Binding)],
    ) -> wgpu::BindGroup {
        bind_group_at(ctx, label, &self.layout0(), entries)
    }
}

impl Bind for wgpu::ComputePipeline {
    fn layout0(&self) -> wgpu::BindGroupLayout {
        self.get_bind_group_layout(0)
    }
}

impl Bind for wgpu::RenderPipeline {
    fn layout0(&self) -> wgpu::BindGroupLayout {
        self.get_bind_group_layout(0)
    }
}

/// A compute pass named `label`, timed when there is a timer.
pub fn begin_compute<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    timer: &mut Option<&mut GpuTimer>,
    label: &str,
) -> wgpu::ComputePass<'e> {
    encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes: timer.as_deref_mut().and_then(|t| t.compute_pass(label)),
    })
}

/// A render pass named `label` into `views`, each cleared to zero first when `clear` (else added
/// to), timed when there is a timer.
pub fn begin_render<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    timer: &mut Option<&mut GpuTimer>,
    label: &str,
    views: &[&wgpu::TextureView],
    clear: bool,
) -> wgpu::RenderPass<'e> {
    let load = match clear {
        true => wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
        false => wgpu::LoadOp::Load,
    };
    let attachments: Vec<_> = views
        .iter()
        .map(|&view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load,
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect();
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &attachments,
        depth_stencil_attachment: None,
        timestamp_writes: timer.as_deref_mut().and_then(|t| t.render_pass(label)),
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// A 2-D texture (or array of `layers`) of one mip level.
fn texture_2d_descriptor<'a>(
    label: &'a str,
    (width, height, layers): (u32, u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::TextureDescriptor<'a> {
    wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    }
}

impl GpuContext {
    /// A 2-D texture (or array of `layers`) of one mip level, refused with a named error by the
    /// caller's size check beforehand.
    pub fn texture_2d(
        &self,
        label: &str,
        size: (u32, u32, u32),
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> wgpu::Texture {
        self.create_texture(&texture_2d_descriptor(label, size, format, usage))
    }

    /// A 2-D texture of `levels` mip levels from `size` down.
    pub fn texture_mips(
        &self,
        label: &str,
        (width, height): (u32, u32),
        levels: u32,
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> wgpu::Texture {
        self.create_texture(&wgpu::TextureDescriptor {
            mip_level_count: levels,
            ..texture_2d_descriptor(label, (width, height, 1), format, usage)
        })
    }

    /// A command encoder named `label`.
    pub fn encoder(&self, label: &str) -> wgpu::CommandEncoder {
        let desc = wgpu::CommandEncoderDescriptor { label: Some(label) };
        self.device.create_command_encoder(&desc)
    }
}

/// A 2-D view of layer `layer` of an array texture.
pub fn layer_view(texture: &wgpu::Texture, layer: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2),
        base_array_layer: layer,
        array_layer_count: Some(1),
        ..Default::default()
    })
}

/// A 2-D array view of all the layers of a texture.
pub fn array_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

/// A view of mip level `level` of a texture alone.
pub fn mip_view(texture: &wgpu::Texture, level: u32) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        base_mip_level: level,
        mip_level_count: Some(1),
        ..Default::default()
    })
}

/// A sampled texture of one mip level, `layers` deep, holding `texels` (layer after layer), its size
/// refused by name where the device cannot hold it.
pub fn float_texture(
    ctx: &GpuContext,
    what: &str,
    format: wgpu::TextureFormat,
    (width, height, layers): (u32, u32, u32),
    texels: &[u8],
) -> Result<wgpu::Texture, GpuError> {
    ctx.check_texture_size(what, width, height)?;
    let texel = format
        .block_copy_size(None)
        .expect("an uncompressed format");
    debug_assert_eq!(texels.len(), (width * height * layers * texel) as usize);
    let usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
    Ok(ctx.create_texture_with_data(
        &texture_2d_descriptor(what, (width, height, layers), format, usage),
        wgpu::util::TextureDataOrder::LayerMajor,
        texels,
    ))
}

/// The four layers of a pool's walls' maps laid out as `layout`, each as wide as the widest wall:
/// the render target a technique draws the walls' light into, its size refused by name where the
/// device cannot hold it.
pub fn wall_maps_texture(
    ctx: &GpuContext,
    label: &str,
    layout: &WallMaps,
    format: wgpu::TextureFormat,
) -> Result<wgpu::Texture, GpuError> {
    let cols = layout.maps.iter().map(|m| m.cols).max().unwrap_or(1) as u32;
    let rows = layout.maps[0].rows as u32;
    ctx.check_texture_size(label, cols, rows)?;
    Ok(ctx.texture_2d(label, (cols, rows, 4), format, MAP_TARGET))
}

/// A storage buffer holding `items`, its size refused by name where the device cannot hold it. A
/// storage binding may not be empty: one default element stands for none.
pub fn storage_buffer<T: bytemuck::Pod + Default>(
    ctx: &GpuContext,
    what: &str,
    items: &[T],
) -> Result<wgpu::Buffer, GpuError> {
    let fallback = [T::default()];
    let items = if items.is_empty() {
        &fallback[..]
    } else {
        items
    };
    let bytes: &[u8] = bytemuck::cast_slice(items);
    ctx.check_buffer_size(what, bytes.len() as u64)?;
    Ok(ctx.buffer_init(what, bytes, wgpu::BufferUsages::STORAGE))
}

/// The best format this device can add light into with blending: `Rgba32Float` where it has
/// `FLOAT32_BLENDABLE`, else `Rgba16Float` (blendable everywhere, about 3 significant digits).
pub fn blendable_map_format(ctx: &GpuContext) -> wgpu::TextureFormat {
    if ctx
        .device
        .features()
        .contains(wgpu::Features::FLOAT32_BLENDABLE)
    {
        wgpu::TextureFormat::Rgba32Float
    } else {
        wgpu::TextureFormat::Rgba16Float
    }
}

/// A render pipeline without vertex buffers (`vs_main` pulls its vertices from storage buffers or
/// makes them from its index) whose `fs_main` writes `targets`. Triangle list, no culling: folded
/// caustic triangles and slices of folded illumination volumes face either way.
pub fn pulled_pipeline(
    ctx: &GpuContext,
    label: &str,
    module: &wgpu::ShaderModule,
    targets: &[Option<wgpu::ColorTargetState>],
) -> wgpu::RenderPipeline {
    ctx.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: None,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A [`pulled_pipeline`] that adds every fragment into one colour target: how caustic triangles
/// (paper 4) and illumination volume slices (paper 3) accumulate irradiance.
pub fn additive_pipeline(
    ctx: &GpuContext,
    source: &PassSource,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    let add = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    let target = wgpu::ColorTargetState {
        format,
        blend: Some(wgpu::BlendState {
            color: add,
            alpha: add,
        }),
        write_mask: wgpu::ColorWrites::ALL,
    };
    pulled_pipeline(
        ctx,
        source.name,
        &source.module(&ctx.device),
        &[Some(target)],
    )
}
