//! One GPU pass per module. Each owns its pipeline(s) and records itself into an encoder; the
//! methods (`crate::methods`) and the frame script (`crate::renderer`) wire them together.
//! Shared targets live in `crate::frame`, GPU plumbing in `crate::gpu`.

pub mod aov_pack;
pub mod brsm_importance;
pub mod brsm_importance_filter;
pub mod brsm_mix;
pub mod brsm_view_gbuffer;
pub mod denoise;
pub mod direct;
pub mod ism;
pub mod kmeans_assign;
pub mod kmeans_centres;
pub mod kmeans_grid;
pub mod kmeans_sums;
pub mod lpv_geometry;
pub mod lpv_geometry_merge;
pub mod lpv_inject;
pub mod lpv_lookup;
pub mod lpv_propagate;
pub mod material;
pub mod metropolis_step;
pub mod moment_mips;
pub mod pathtrace;
pub mod pdf_mips;
pub mod radix_sort;
pub mod rsm_flux;
pub mod shadow_map;
pub mod visibility;
pub mod vpl_sample;
pub mod vpl_shading;
pub mod vsgl2_reduce;
pub mod vsgl_gen;
pub mod vsgl_moments;
pub mod vsgl_shading;

/// Every pass is created from the device alone (see [`crate::gpu::Pass`]).
macro_rules! passes_from_device {
    ($($pass:ty),* $(,)?) => {
        $(impl crate::gpu::Pass for $pass {
            fn create(gpu: &crate::gpu::Gpu) -> crate::error::Result<Self> {
                <$pass>::new(gpu)
            }
        })*
    };
}

passes_from_device!(
    aov_pack::AovPackPass,
    brsm_importance::BrsmImportancePass,
    brsm_importance_filter::BrsmImportanceFilterPass,
    brsm_mix::BrsmMixPass,
    brsm_view_gbuffer::BrsmViewPass,
    denoise::DenoisePass,
    direct::DirectPass,
    ism::IsmPass,
    kmeans_assign::KmeansAssignPass,
    kmeans_centres::KmeansCentresPass,
    kmeans_grid::KmeansGridPass,
    kmeans_sums::KmeansSumsPass,
    lpv_geometry::LpvGeometryPass,
    lpv_geometry_merge::LpvGeometryMergePass,
    lpv_inject::LpvInjectPass,
    lpv_lookup::LpvLookupPass,
    lpv_propagate::LpvPropagatePass,
    material::MaterialPass,
    metropolis_step::MetropolisStepPass,
    moment_mips::MomentMipsPass,
    pathtrace::PathTracePass,
    pdf_mips::PdfMipsPass,
    radix_sort::RadixSortPass,
    rsm_flux::RsmFluxPass,
    shadow_map::ShadowMapPass,
    visibility::VisibilityPass,
    vpl_sample::VplSamplePass,
    vpl_shading::VplShadingPass,
    vsgl2_reduce::Vsgl2Reduce,
    vsgl_gen::VsglGenPass,
    vsgl_moments::VsglMomentsPass,
    vsgl_shading::VsglShadingPass,
);
