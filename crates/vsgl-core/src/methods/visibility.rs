//! `visibility=` of the virtual-light methods (issue 17): what the shading passes bind in their
//! group 2 and which variant they run. `"none"`: unshadowed virtual lights (the papers'
//! accuracy configuration); placeholders are bound and the shadow-ray code is compiled out.
//! `"raytrace"`: one shadow ray per (pixel, virtual light) through the scene's BVH — the path
//! tracer's, built once per scene upload — to the VPL, or to a VSGL's mean position.

use super::{FrameContext, Options};
use crate::error::Result;

/// The modes `visibility=` takes (options.rs lists the same).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VisibilityMode {
    None,
    RayTraced,
}

impl VisibilityMode {
    pub fn from_options(o: &Options) -> Result<Self> {
        Ok(if o.str("visibility")? == "raytrace" { Self::RayTraced } else { Self::None })
    }
}

/// What a shading pass binds for visibility in its group 2: the BVH's nodes and triangles and
/// the camera's triangle ids.
pub struct VirtualLightVisibility {
    pub traced: bool,
    nodes: wgpu::Buffer,
    triangles: wgpu::Buffer,
    ids: wgpu::TextureView,
}

/// Bytes of a placeholder array binding: at least one BVH node (32) or triangle (48).
const PLACEHOLDER_BYTES: u64 = 64;

impl VirtualLightVisibility {
    pub fn new(ctx: &mut FrameContext<'_>, mode: VisibilityMode) -> Result<Self> {
        let ids = ctx.visibility.ids.clone();
        // Pass-plan rule: when every surface lies on the scene's convex hull no segment between
        // a receiver and a virtual light (both on surfaces) can be blocked, so the shadow rays
        // would all pass; `plan="full"` casts them anyway (tests/test_visibility.py compares).
        let unblockable = mode == VisibilityMode::RayTraced && !ctx.plan_full && ctx.gpu_scene.convex_shell(ctx.scene);
        if unblockable {
            ctx.skip("vpl_shadow_rays", "every surface lies on the scene's convex hull: no segment between two surface points can be blocked");
        }
        if mode == VisibilityMode::None || unblockable {
            if mode == VisibilityMode::None {
                ctx.skip("vpl_shadow_maps", "visibility=\"none\": virtual lights are unshadowed");
            }
            let nodes = ctx.rec.storage_written("visibility_placeholder_node_buffer", PLACEHOLDER_BYTES);
            let triangles = ctx.rec.storage_written("visibility_placeholder_triangle_buffer", PLACEHOLDER_BYTES);
            return Ok(Self { traced: false, nodes, triangles, ids });
        }
        let (bvh, built) = ctx.gpu_scene.bvh(ctx.gpu, ctx.scene)?;
        if built {
            crate::gpu::frame_log::note_pass("bvh_build");
        } else {
            ctx.skip("bvh_build", "the BVH built for this scene upload is reused");
        }
        Ok(Self { traced: true, nodes: bvh.nodes.clone(), triangles: bvh.triangles.clone(), ids })
    }

    /// The override constant choosing the shading variant.
    pub fn flag(&self) -> (&'static str, bool) {
        ("VISIBILITY_TRACED", self.traced)
    }

    /// Group 2 of the shading passes.
    pub fn bindings(&self) -> [wgpu::BindingResource<'_>; 3] {
        [self.nodes.as_entire_binding(), self.triangles.as_entire_binding(), wgpu::BindingResource::TextureView(&self.ids)]
    }
}
