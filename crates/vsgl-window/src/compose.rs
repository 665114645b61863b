//! The composition pass: the methods' packed `ldr` images into the window's target
//! (`wgsl/compose.wgsl`), side by side with a divider when two methods are compared.

use wgpu::util::DeviceExt;

/// Pipeline of the composition pass (made once per window).
pub struct ComposePass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

/// What one composition draws: the images' buffers (RGBA8 words, rows top to bottom, at byte
/// offset 0) and where the right image starts.
pub struct ComposeInputs<'a> {
    pub size: (u32, u32),
    pub left: &'a wgpu::Buffer,
    /// The right image and the first column it is shown from (the divider's column).
    pub right: Option<(&'a wgpu::Buffer, u32)>,
}

impl ComposePass {
    pub fn new(device: &wgpu::Device, target_format: wgpu::TextureFormat) -> Self {
        let module = crate::pass_shader(device, "window_compose", include_str!("../wgsl/compose.wgsl"));
        let storage = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Storage { read_only: true }, has_dynamic_offset: false, min_binding_size: None },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("window_compose_layout"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Uniform, has_dynamic_offset: false, min_binding_size: None },
                    count: None,
                },
                storage(1),
                storage(2),
            ],
        });
        let pipeline = crate::fullscreen_pipeline(device, "window_compose", &module, &layout, target_format);
        Self { pipeline, layout }
    }

    /// Records the composition into `target` (the whole of it is drawn).
    pub fn record(&self, device: &wgpu::Device, encoder: &mut wgpu::CommandEncoder, inputs: &ComposeInputs<'_>, target: &wgpu::TextureView) {
        let (split, images) = match inputs.right {
            Some((_, split)) => (split, 2u32),
            None => (inputs.size.0, 1u32),
        };
        let params = [inputs.size.0, inputs.size.1, split, images];
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("window_compose_uniform"),
            contents: bytemuck::cast_slice(&params),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let right = inputs.right.map_or(inputs.left, |(b, _)| b);
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("window_compose_bind_group"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: inputs.left.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: right.as_entire_binding() },
            ],
        });
        let mut pass = crate::target_pass(encoder, "window_compose", target, wgpu::LoadOp::Clear(wgpu::Color::BLACK));
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.draw(0..3, 0..1);
    }
}
