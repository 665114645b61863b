//! What a shading pass (`passes/vpl_shading.rs`, `passes/vsgl_shading.rs`) binds for
//! virtual-light visibility in its group 2, and which variant it runs: the BVH's nodes, its
//! leaf-ordered triangle ids and the triangles' corners, the camera's triangle ids, the imperfect shadow maps and how to read them
//! (placeholders for what the variant does not read). `methods/visibility.rs` makes them from
//! `visibility=`; the passes only bind them.

use crate::gpu::buffers::{later_storage_pages, spans_pages, storage_pages};

/// GPU twin of `IsmLookup` in `wgsl/common/ism_lookup.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct IsmLookupRaw {
    pub map_size: u32,
    pub words_per_map: u32,
    pub distance_bias: f32,
    pub normal_offset: f32,
    pub pcf_radius: i32,
    pub _pad: [u32; 3],
}
const _: () = assert!(std::mem::size_of::<IsmLookupRaw>() == 32);

/// Group 2 of the shading passes and the variant it selects.
pub struct ShadingVisibility {
    /// One shadow ray per (pixel, virtual light) through `nodes` / `triangle_ids` /
    /// `triangle_corners`.
    pub traced: bool,
    /// Imperfect shadow maps in `ism_atlas`, read as `ism_lookup` says.
    pub reads_ism: bool,
    pub nodes: wgpu::Buffer,
    pub triangle_ids: wgpu::Buffer,
    pub triangle_corners: wgpu::Buffer,
    pub ids: wgpu::TextureView,
    pub ism_atlas: wgpu::Buffer,
    pub ism_lookup: wgpu::Buffer,
}

impl ShadingVisibility {
    /// The override constants choosing the shading variant (`STORAGE_PAGED`: the BVH's nodes or
    /// corners span more than one binding's page).
    pub fn flags(&self) -> [(&'static str, bool); 3] {
        let paged = self.traced && (spans_pages(&self.nodes) || spans_pages(&self.triangle_corners));
        [("VISIBILITY_TRACED", self.traced), ("VISIBILITY_ISM", self.reads_ism), ("STORAGE_PAGED", paged)]
    }

    /// What `frame.passes` adds to a shading pass's name: its visibility variant.
    pub fn label_suffix(&self) -> &'static str {
        if self.traced {
            "[raytrace]"
        } else if self.reads_ism {
            "[ism]"
        } else {
            ""
        }
    }

    /// Group 2 of the shading passes.
    pub fn bindings(&self) -> Vec<wgpu::BindingResource<'_>> {
        let [nodes, ..] = storage_pages(&self.nodes);
        let [corners, ..] = storage_pages(&self.triangle_corners);
        let first = [
            nodes,
            self.triangle_ids.as_entire_binding(),
            wgpu::BindingResource::TextureView(&self.ids),
            self.ism_atlas.as_entire_binding(),
            self.ism_lookup.as_entire_binding(),
            corners,
        ];
        first.into_iter().chain(later_storage_pages(&[&self.nodes, &self.triangle_corners])).collect()
    }
}
