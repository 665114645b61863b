//! Spot-light shadow maps: depth only, one array layer per light, reverse-Z.

use crate::error::Result;
use crate::gpu::{Gpu, PipelineRef, Recorder};

pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

pub struct ShadowMapPass {
    pipeline: wgpu::RenderPipeline,
}

impl ShadowMapPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/shadow_map.wgsl")?;
        let pipeline = gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("shadow_map_pipeline"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 16,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
                })],
            },
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: None,
            multiview_mask: None,
            cache: None,
        });
        Ok(Self { pipeline })
    }

    /// A depth array with one layer per light (at least one, so the binding always exists).
    pub fn target(rec: &mut Recorder<'_>, size: u32, layers: u32) -> wgpu::Texture {
        let desc = wgpu::TextureDescriptor {
            label: Some("shadow_map_depth_texture"),
            size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: layers.max(1) },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        };
        rec.texture(&desc, size as u64 * size as u64 * layers.max(1) as u64 * 4)
    }

    /// Renders layer `i` from each light's view-projection (`view_projs[i]`); a `None` layer
    /// sees none of the scene (`views_seeing_scene`) and is left as it is: no shaded point looks
    /// it up. With an empty list it only clears layer 0.
    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        target: &wgpu::Texture,
        view_projs: &[Option<[[f32; 4]; 4]>],
        vertices: &wgpu::Buffer,
        vertex_count: u32,
    ) {
        let layers = view_projs.len().max(1);
        // Each layer's view uniform, made before the passes borrow the encoder.
        let binds: Vec<Option<wgpu::BindGroup>> = view_projs
            .iter()
            .map(|vp| {
                vp.as_ref().map(|vp| {
                    let uniform = rec.uniform("shadow_map_view_uniform_buffer", vp);
                    rec.bind_group("shadow_map_bind_group", PipelineRef::Render(&self.pipeline), 0, &[uniform.as_entire_binding()])
                })
            })
            .collect();
        let views: Vec<wgpu::TextureView> = (0..layers)
            .map(|layer| {
                rec.texture_view(target, &wgpu::TextureViewDescriptor {
                    label: Some("shadow_map_layer_view"),
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: layer as u32,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        rec.in_debug_group("shadow_map", |rec| {
            for (layer, view) in views.iter().enumerate() {
                if matches!(view_projs.get(layer), Some(None)) {
                    continue;
                }
                let q = rec.timer.begin("shadow_map");
                let mut pass = rec.enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("shadow_map_pass"),
                    color_attachments: &[],
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view,
                        depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Store }),
                        stencil_ops: None,
                    }),
                    timestamp_writes: rec.timer.render_writes(q),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                let Some(Some(bind)) = binds.get(layer) else { continue };
                if vertex_count == 0 {
                    continue;
                }
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, bind, &[]);
                pass.set_vertex_buffer(0, vertices.slice(..));
                pass.draw(0..vertex_count, 0..1);
            }
        });
    }
}
