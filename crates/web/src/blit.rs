//! The page's last pass: each side's final image drawn into its half of the canvas (or the whole
//! canvas when one side shows). A side's bind group is made again only when the renderer's image
//! texture changes (a new size, a new technique), so a steady frame creates nothing here either.

use caustics_gpu::GpuContext;

pub struct Blit {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    bound: Vec<Option<(wgpu::Texture, wgpu::BindGroup)>>,
}

impl Blit {
    pub fn new(ctx: &GpuContext, format: wgpu::TextureFormat) -> Self {
        let device = &ctx.device;
        let module = device.create_shader_module(wgpu::include_wgsl!("blit.wgsl"));
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("page image"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("page image"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = ctx.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("page image"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            multiview_mask: None,
            cache: None,
        });
        let sampler = ctx.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("page image"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        Blit {
            pipeline,
            layout,
            sampler,
            bound: Vec::new(),
        }
    }

    /// Draw `images` side by side over `target` (`size` pixels), a gap of `gap` pixels between
    /// them; a side without an image stays the clear colour.
    pub fn draw(
        &mut self,
        ctx: &GpuContext,
        target: &wgpu::TextureView,
        size: (u32, u32),
        images: &[Option<&wgpu::Texture>],
        gap: u32,
    ) {
        self.bound.resize_with(images.len(), || None);
        for (slot, image) in self.bound.iter_mut().zip(images) {
            match image {
                Some(t) if slot.as_ref().is_none_or(|(bound, _)| bound != *t) => {
                    let view = t.create_view(&Default::default());
                    let group = ctx.create_bind_group(&wgpu::BindGroupDescriptor {
                        label: Some("page image"),
                        layout: &self.layout,
                        entries: &[
                            wgpu::BindGroupEntry {
                                binding: 0,
                                resource: wgpu::BindingResource::TextureView(&view),
                            },
                            wgpu::BindGroupEntry {
                                binding: 1,
                                resource: wgpu::BindingResource::Sampler(&self.sampler),
                            },
                        ],
                    });
                    *slot = Some(((*t).clone(), group));
                }
                Some(_) => {}
                None => *slot = None,
            }
        }
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("page image"),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("page image"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.06,
                            g: 0.07,
                            b: 0.09,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.pipeline);
            let n = images.len().max(1) as u32;
            let gaps = gap * (n - 1);
            let width = size.0.saturating_sub(gaps) / n;
            for (k, slot) in self.bound.iter().enumerate() {
                let Some((_, group)) = slot else { continue };
                if width == 0 || size.1 == 0 {
                    continue;
                }
                let x = k as u32 * (width + gap);
                pass.set_viewport(x as f32, 0.0, width as f32, size.1 as f32, 0.0, 1.0);
                pass.set_bind_group(0, group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        ctx.queue.submit([encoder.finish()]);
    }
}
