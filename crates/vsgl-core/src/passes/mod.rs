//! One GPU pass per module. Each owns its pipeline(s) and records itself into an encoder;
//! `crate::renderer` wires them top to bottom.

pub mod direct;
pub mod material;
pub mod shadow_map;
pub mod visibility;

/// Bind group entries for buffers/views in binding order 0, 1, 2, …
pub fn entries<'a>(resources: &[wgpu::BindingResource<'a>]) -> Vec<wgpu::BindGroupEntry<'a>> {
    resources
        .iter()
        .enumerate()
        .map(|(i, r)| wgpu::BindGroupEntry { binding: i as u32, resource: r.clone() })
        .collect()
}
