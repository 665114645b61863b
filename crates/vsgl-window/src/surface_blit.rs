//! The surface blit pass: the window's target texel for texel onto the surface texture
//! (`wgsl/surface_blit.wgsl`), which may differ in channel order from the target.

/// Pipeline of the blit for one surface format.
pub struct SurfaceBlitPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
}

impl SurfaceBlitPass {
    /// `view_format`: the non-sRGB format the surface texture is viewed in.
    pub fn new(device: &wgpu::Device, view_format: wgpu::TextureFormat) -> Self {
        let module = crate::pass_shader(device, "window_surface_blit", include_str!("../wgsl/surface_blit.wgsl"));
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("window_surface_blit_layout"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture { sample_type: wgpu::TextureSampleType::Float { filterable: false }, view_dimension: wgpu::TextureViewDimension::D2, multisampled: false },
                count: None,
            }],
        });
        let pipeline = crate::fullscreen_pipeline(device, "window_surface_blit", &module, &layout, view_format);
        Self { pipeline, layout }
    }

    pub fn record(&self, device: &wgpu::Device, encoder: &mut wgpu::CommandEncoder, source: &wgpu::TextureView, surface: &wgpu::TextureView) {
        let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("window_surface_blit_bind_group"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(source) }],
        });
        let mut pass = crate::target_pass(encoder, "window_surface_blit", surface, wgpu::LoadOp::Clear(wgpu::Color::BLACK));
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.draw(0..3, 0..1);
    }
}
