//! `visibility=` of the virtual-light methods: what the shading passes bind in their group 2
//! (`frame::ShadingVisibility`) and which variant they run. `"none"`: unshadowed virtual lights (the papers'
//! accuracy configuration); placeholders are bound and the visibility code is compiled out.
//! `"raytrace"`: one shadow ray per (pixel, virtual light) through the scene's BVH — the path
//! tracer's, built once per scene upload — to the VPL, or to a VSGL's mean position.
//! `"ism"`: imperfect shadow maps (the papers' choice): before the lights of a batch are shaded,
//! [`VirtualLightVisibility::build_maps`] splats the scene's point set (kept with the upload)
//! into one octahedral depth map per light (`passes/ism.rs`); shading looks them up.

use super::{FrameContext, Options};
use super::choices::VisibilityChoice;
use crate::error::{Error, Result};
use crate::frame::{IsmLookupRaw, ShadingVisibility};
use crate::passes::ism::{IsmLayout, IsmPass, IsmSources};
use crate::upload::GpuPoints;
use bytemuck::Zeroable;
use std::sync::Arc;

/// Settings of `visibility="ism"` (options.rs: ism_size, ism_points, ism_points_per_map,
/// ism_bias, ism_pcf).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IsmSettings {
    pub size: u32,
    pub points: u32,
    pub points_per_map: u32,
    pub bias: f32,
    /// PCF window radius in texels (0: the receiver's texel alone).
    pub pcf_radius: u32,
}

/// Coarser levels of the pull-push pyramid (64² → 32² → 16² → 8²): holes up to ~8 texels wide
/// are filled; wider empty regions are directions in which no surface lies, and stay lit.
const ISM_PULL_LEVELS: u32 = 3;

/// The receiver's normal offset in texels' angular width at its distance (ism_lookup.wgsl):
/// measured on the tests' scenes (docs/methods/visibility.md), 1 texel leaves receivers shadowing
/// themselves at grazing incidence and 2 or more darken receivers seen through a door by
/// moving their direction off the opening; 1.5 does neither.
const ISM_NORMAL_OFFSET_TEXELS: f64 = 1.5;

/// The modes `visibility=` takes (options.rs lists the same).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum VisibilityMode {
    None,
    Ism(IsmSettings),
    RayTraced,
}

impl VisibilityMode {
    pub fn from_options(o: &Options) -> Result<Self> {
        Ok(match o.choice("visibility")? {
            VisibilityChoice::Raytrace => Self::RayTraced,
            VisibilityChoice::Ism => Self::Ism(IsmSettings {
                size: o.u32("ism_size")?,
                points: o.u32("ism_points")?,
                points_per_map: o.u32("ism_points_per_map")?,
                bias: o.f32("ism_bias")?,
                pcf_radius: o.u32("ism_pcf")?,
            }),
            VisibilityChoice::None => Self::None,
        })
    }

    /// With imperfect shadow maps, how many lights' maps fit in `bytes`; `None` otherwise.
    pub fn lights_within(&self, bytes: u64) -> Option<u32> {
        match self {
            Self::Ism(s) => Some((bytes / IsmLayout::new(s.size, ISM_PULL_LEVELS).bytes_per_map()).min(u32::MAX as u64) as u32),
            _ => None,
        }
    }
}

/// The maps of one frame: an atlas for up to `capacity` lights, rebuilt for each batch.
struct IsmMaps {
    settings: IsmSettings,
    layout: IsmLayout,
    atlas: wgpu::Buffer,
    capacity: u32,
    points: Arc<GpuPoints>,
}

/// A frame's virtual-light visibility: what the shading passes bind ([`ShadingVisibility`], which
/// it derefs to) and, with `visibility="ism"`, the maps it builds before each batch.
pub struct VirtualLightVisibility {
    ism: Option<IsmMaps>,
    shading: ShadingVisibility,
}

impl std::ops::Deref for VirtualLightVisibility {
    type Target = ShadingVisibility;
    fn deref(&self) -> &ShadingVisibility {
        &self.shading
    }
}

/// Bytes of a placeholder array binding: at least one BVH node (32) or triangle (48).
const PLACEHOLDER_BYTES: u64 = 64;

/// Bytes of a Vpl (`wgsl/common/vpl.wgsl`) and a VsglRaw record in 32-bit words; both start with
/// the light's position, which is all the maps need.
pub const VPL_RECORD_WORDS: u32 = (crate::passes::vpl_sample::VPL_BYTES / 4) as u32;
pub const VSGL_RECORD_WORDS: u32 = (crate::passes::vsgl_gen::VSGL_BYTES / 4) as u32;

impl VirtualLightVisibility {
    /// Placeholders for every group-2 binding: the shading variant without visibility code.
    fn unshadowed(ctx: &mut FrameContext<'_>, ids: wgpu::TextureView) -> Self {
        let nodes = ctx.rec.storage_written("visibility_placeholder_node_buffer", PLACEHOLDER_BYTES);
        let triangle_ids = ctx.rec.storage_written("visibility_placeholder_triangle_id_buffer", PLACEHOLDER_BYTES);
        let triangle_corners = ctx.rec.storage_written("visibility_placeholder_triangle_corner_buffer", PLACEHOLDER_BYTES);
        let ism_atlas = ctx.rec.storage_written("visibility_placeholder_ism_atlas_buffer", PLACEHOLDER_BYTES);
        let ism_lookup = ctx.rec.uniform("visibility_placeholder_ism_lookup_uniform_buffer", &IsmLookupRaw::zeroed());
        let shading = ShadingVisibility { traced: false, reads_ism: false, nodes, triangle_ids, triangle_corners, ids, ism_atlas, ism_lookup };
        Self { ism: None, shading }
    }

    /// `max_lights`: the most lights one batch shades (the maps of a batch are held at once).
    pub fn new(ctx: &mut FrameContext<'_>, mode: VisibilityMode, max_lights: u32) -> Result<Self> {
        let ids = ctx.visibility.ids.clone();
        let placeholder = |ctx: &mut FrameContext<'_>, label: &str| ctx.rec.storage_written(label, PLACEHOLDER_BYTES);
        match mode {
            VisibilityMode::None => {
                ctx.skip("vpl_shadow_maps", "visibility=\"none\": virtual lights are unshadowed");
                Ok(Self::unshadowed(ctx, ids))
            }
            // Pass-plan rule: when every surface lies on the scene's convex hull no segment
            // between a receiver and a virtual light (both on surfaces) can be blocked, so the
            // shadow rays would all pass; `plan="full"` casts them anyway (tests compare).
            VisibilityMode::RayTraced if !ctx.plan_full && ctx.gpu_scene.convex_shell(ctx.scene) => {
                ctx.skip("vpl_shadow_rays", "every surface lies on the scene's convex hull: no segment between two surface points can be blocked");
                Ok(Self::unshadowed(ctx, ids))
            }
            VisibilityMode::RayTraced => {
                let (bvh, built) = ctx.gpu_scene.bvh(ctx.gpu, ctx.scene)?;
                if built {
                    crate::gpu::frame_log::note_pass("bvh_build");
                } else {
                    ctx.skip("bvh_build", "the BVH built for this scene upload is reused");
                }
                let ism_atlas = placeholder(ctx, "visibility_placeholder_ism_atlas_buffer");
                let ism_lookup = ctx.rec.uniform("visibility_placeholder_ism_lookup_uniform_buffer", &IsmLookupRaw::zeroed());
                let shading = ShadingVisibility {
                    traced: true,
                    reads_ism: false,
                    nodes: bvh.nodes.clone(),
                    triangle_ids: bvh.triangle_ids.clone(),
                    triangle_corners: ctx.gpu_scene.raster_vertices.clone(),
                    ids,
                    ism_atlas,
                    ism_lookup,
                };
                Ok(Self { ism: None, shading })
            }
            VisibilityMode::Ism(settings) => {
                let (points, made) = ctx.gpu_scene.surface_points(ctx.gpu, ctx.scene, settings.points)?;
                if made {
                    crate::gpu::frame_log::note_pass("ism_points");
                } else {
                    ctx.skip("ism_points", "the point set made for this scene upload is reused");
                }
                let layout = IsmLayout::new(settings.size, ISM_PULL_LEVELS);
                let capacity = max_lights.max(1);
                let bytes = capacity as u64 * layout.bytes_per_map();
                let limit = ctx.gpu.limits.max_storage_buffer_binding_size as u64;
                if bytes > limit {
                    return Err(Error::invalid("ism_size", format!(
                        "{capacity} imperfect shadow maps of {0}² ({bytes} bytes with their pull-push levels) exceed this adapter's storage binding limit of {limit} bytes; use a smaller ism_size or fewer lights",
                        settings.size
                    )));
                }
                let atlas = ctx.rec.storage("ism_atlas_buffer", bytes);
                // √(4π) / size: the mean angular side of an octahedral texel.
                let texel_angle = (4.0 * std::f64::consts::PI).sqrt() / settings.size as f64;
                let lookup = IsmLookupRaw {
                    map_size: layout.size,
                    words_per_map: layout.words_per_map(),
                    distance_bias: settings.bias,
                    normal_offset: (ISM_NORMAL_OFFSET_TEXELS * texel_angle) as f32,
                    pcf_radius: settings.pcf_radius as i32,
                    _pad: [0; 3],
                };
                let ism_lookup = ctx.rec.uniform("ism_lookup_uniform_buffer", &lookup);
                let nodes = placeholder(ctx, "visibility_placeholder_node_buffer");
                let triangle_ids = placeholder(ctx, "visibility_placeholder_triangle_id_buffer");
                let triangle_corners = placeholder(ctx, "visibility_placeholder_triangle_corner_buffer");
                let ism = IsmMaps { settings, layout, atlas: atlas.clone(), capacity, points };
                let shading = ShadingVisibility { traced: false, reads_ism: true, nodes, triangle_ids, triangle_corners, ids, ism_atlas: atlas, ism_lookup };
                Ok(Self { ism: Some(ism), shading })
            }
        }
    }

    /// With `visibility="ism"`, builds the maps of lights 0 … count − 1 of `lights` (records
    /// of `record_words` words, position first) for the shading that follows; nothing otherwise.
    /// Every light's map is built, interleaved or not: each pixel class needs its own lights'.
    pub fn build_maps(&self, ctx: &mut FrameContext<'_>, lights: &wgpu::Buffer, count: u32, record_words: u32) -> Result<()> {
        let Some(maps) = &self.ism else { return Ok(()) };
        if count > maps.capacity {
            return Err(Error::invalid("num_lights", format!("{count} virtual lights in one batch exceed the {} imperfect shadow maps allocated", maps.capacity)));
        }
        let pass = ctx.passes.get::<IsmPass>()?;
        // Empty texels are key 0: clear what the previous batch (or frame) left.
        ctx.rec.enc.clear_buffer(&maps.atlas, 0, Some(count as u64 * maps.layout.bytes_per_map()));
        let sources = IsmSources {
            frame: ctx.frame_uniforms,
            points: &maps.points.buffer,
            point_count: maps.points.count,
            points_per_map: maps.settings.points_per_map,
            lights,
            light_count: count,
            record_words,
        };
        pass.record(&mut ctx.rec, &maps.atlas, maps.layout, &sources);
        Ok(())
    }
}
