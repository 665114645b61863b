//! Visibility raster: depth + visible triangle id (R32Uint), trivial fragment work.

use crate::error::Result;
use crate::frame::targets::{VisibilityTargets, VISIBILITY_DEPTH_FORMAT as DEPTH_FORMAT, VISIBILITY_ID_FORMAT as ID_FORMAT};
use crate::gpu::{Gpu, PipelineRef, Recorder};


pub struct VisibilityPass {
    pipeline: wgpu::RenderPipeline,
}


impl VisibilityPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/visibility.wgsl")?;
        let pipeline = gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("visibility_raster_pipeline"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 16,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Uint32],
                })],
            },
            primitive: wgpu::PrimitiveState { cull_mode: None, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(ID_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        });
        Ok(Self { pipeline })
    }


    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        label: &str,
        frame_uniforms: &wgpu::Buffer,
        vertices: &wgpu::Buffer,
        vertex_count: u32,
        targets: &VisibilityTargets,
    ) {
        let bind = rec.bind_group("visibility_frame_bind_group", PipelineRef::Render(&self.pipeline), 0, &[frame_uniforms.as_entire_binding()]);
        rec.in_debug_group(label, |rec| {
            let q = rec.timer.begin(label);
            let mut pass = rec.enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &targets.ids,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &targets.depth,
                    // Reverse-Z: 0 is infinitely far.
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(0.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: rec.timer.render_writes(q),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if vertex_count > 0 {
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.set_vertex_buffer(0, vertices.slice(..));
                pass.draw(0..vertex_count, 0..1);
            }
        });
    }
}
