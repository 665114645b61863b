//! The desktop window of vsgl's live view (`python -m vsgl view`, `Renderer.view`).
//!
//! A winit window presents the renderer's own frames: a frame is rendered with its `ldr` image
//! kept on the GPU (`RenderOptions::keep_on_gpu`), copied into the window's image buffers, drawn
//! into the window's target by the composition pass (two methods side by side with a divider),
//! the egui panel drawn over it, and the target blitted onto the surface. Nothing is read back;
//! a screenshot copies the target, so it is the frame presented, not a frame rendered again.
//!
//! Events leave the window as [`InputEvent`]s in the remote-frame-buffer format the notebook view
//! uses, so one camera-control and one scene-edit module (Python's `vsgl.camera_control` and
//! `vsgl.scene_edit`) serve both views. Without a display the same frame path runs offscreen
//! ([`ViewWindow::offscreen`]): for timing on machines with no display, and for tests.
//!
//! `vsgl-core` stays windowless: this crate is the only one that links winit and egui.

mod compose;
mod events;
mod panel;
mod surface_blit;
mod target;
mod window;

pub use events::InputEvent;
pub use panel::{Control, PanelChange, PanelSpec, PanelValue};
pub use window::{ViewWindow, WindowError};

/// A pass's shader module: `wgsl/fullscreen.wgsl` (the vertex stage) followed by the pass's own
/// fragment stage.
pub(crate) fn pass_shader(device: &wgpu::Device, label: &str, fragment: &str) -> wgpu::ShaderModule {
    let source = format!("{}\n{fragment}", include_str!("../wgsl/fullscreen.wgsl"));
    device.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some(label), source: wgpu::ShaderSource::Wgsl(source.into()) })
}

/// A pipeline that draws one triangle covering its target from `vs_main` / `fs_main`.
pub(crate) fn fullscreen_pipeline(device: &wgpu::Device, label: &str, module: &wgpu::ShaderModule, layout: &wgpu::BindGroupLayout, format: wgpu::TextureFormat) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor { label: Some(label), bind_group_layouts: &[Some(layout)], immediate_size: 0 });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState { module, entry_point: Some("vs_main"), compilation_options: Default::default(), buffers: &[] },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A render pass with one colour attachment, stored.
pub(crate) fn target_pass<'e>(encoder: &'e mut wgpu::CommandEncoder, label: &str, view: &wgpu::TextureView, load: wgpu::LoadOp<wgpu::Color>) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment { view, depth_slice: None, resolve_target: None, ops: wgpu::Operations { load, store: wgpu::StoreOp::Store } })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

#[cfg(test)]
mod tests {
    /// Each pass's WGSL, with the shared vertex stage, parses and validates (no GPU needed).
    #[test]
    fn the_window_shaders_validate() {
        for (name, fragment) in [("compose", include_str!("../wgsl/compose.wgsl")), ("surface_blit", include_str!("../wgsl/surface_blit.wgsl"))] {
            let source = format!("{}\n{fragment}", include_str!("../wgsl/fullscreen.wgsl"));
            let module = naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&source)));
            naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
                .validate(&module)
                .unwrap_or_else(|e| panic!("{name}: {e:?}"));
            assert!(module.entry_points.iter().any(|e| e.name == "vs_main") && module.entry_points.iter().any(|e| e.name == "fs_main"), "{name}");
        }
    }
}
