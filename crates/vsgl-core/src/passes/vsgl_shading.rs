//! VSGL shading (compute): SG incoming radiance, diffuse and SG–ASG specular, interleaved.

use crate::error::Result;
use crate::frame::{ShadingInputs, VirtualLightList};
use crate::gpu::{for_each_chunk, interleaved_block_groups, traced_lights_per_dispatch, Gpu, PipelineVariants, Recorder};
use crate::passes::vsgl_gen::SHADOW_CANDIDATES;

use crate::shader_lib::constants::vsgl_shading::WORKGROUP;
/// Pixels each thread shades (register blocking; the shader's override `PIXELS_PER_THREAD`,
/// 1 … 4): every VSGL read from the workgroup tile serves that many (pixel, VSGL) pairs. The
/// pixels are neighbours of one interleave class along x, so a workgroup covers
/// (WORKGROUP·P) × WORKGROUP pixels of its class. Chosen here only, per variant, from an H200
/// at 1080p and 1024 VSGLs per pixel (docs/methods/vsgl.md, "What the shading loop keeps per VSGL"):
/// diffuse-only scenes 6.87 / 6.38 / 6.48 ms at P = 1 / 2 / 4; with specular lobes P = 2 gains
/// under 1% at interleave 1, loses 5% at 8×8 (0.383 → 0.403 ms) and P = 4 spills (16.2 → 24.9 ms).
pub const PIXELS_PER_THREAD_DIFFUSE_ONLY: u32 = 2;
pub const PIXELS_PER_THREAD_WITH_SPECULAR: u32 = 1;
const _: () = assert!(
    PIXELS_PER_THREAD_DIFFUSE_ONLY >= 1 && PIXELS_PER_THREAD_DIFFUSE_ONLY <= 4 && PIXELS_PER_THREAD_WITH_SPECULAR >= 1 && PIXELS_PER_THREAD_WITH_SPECULAR <= 4,
    "vsgl_shading.wgsl keeps 1 … 4 pixels per thread"
);

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ShadeParamsRaw {
    count: u32,
    interleave: u32,
    diffuse_mode: u32,
    first: u32,
    exact_texels: u32,
    plane_fade: u32,
    lighting_mode: u32,
    lambert_lobe: u32,
    shadow_candidates: u32,
    seed: u32,
    resample_target: u32,
    near_field_texels: u32,
}

/// How `vsgl_shading` shades each VSGL: the forms and switches the method chose.
#[derive(Clone, Copy, Debug)]
pub struct VsglShadingForm {
    pub diffuse: DiffuseMode,
    pub lighting: LightingMode,
    pub lambert_lobe: LambertLobe,
    /// Shade a VSGL of one texel (level 0, `kernel="node"`) as that texel exactly.
    pub exact_texels: bool,
    /// Fade the papers' diffuse form below each VSGL's tangent plane (`plane_fade=`).
    pub plane_fade: bool,
    /// With `plane_fade`, fade the receiver's glossy reflection of the diffuse lobe too (the
    /// emitter VSGLs: a receiver on the emitter's own plane must not mirror it).
    pub fade_glossy: bool,
}

/// Candidate texels per VSGL written by `vsgl_gen` ([`crate::passes::vsgl_gen::SHADOW_CANDIDATES`]
/// each) and what the shading pass does with them.
pub struct ShadingCandidates<'a> {
    pub buffer: &'a wgpu::Buffer,
    /// Seed of the per-(pixel, VSGL) pick of a shadow target.
    pub seed: u32,
    /// `shadow_target="resampled"`: aim each shadow ray at one of them (with ray tracing).
    pub resample_target: bool,
    /// `near_field="texels"`: shade them one by one where the receiver is inside a VSGL's
    /// Gaussian or behind its tangent plane.
    pub near_field: bool,
}

/// Most loop iterations (VSGLs per pixel) one dispatch runs: lavapipe (Mesa 22.3) silently
/// ends shader loops after 65536 iterations (seen: 131072 VSGLs at interleave=1 shaded as
/// 65536), so long lists are split over dispatches that add into the same targets.
/// With `visibility="raytrace"` (each VSGL also loops over BVH nodes): `traced_lights_per_dispatch`.
const VSGLS_PER_PIXEL_PER_DISPATCH: u32 = 16384;
/// The same with `near_field="texels"` on an adapter that caps an invocation's loop iterations
/// (lavapipe, `Gpu::caps_loop_iterations`): a pair near its VSGL also loops over its
/// SHADOW_CANDIDATES texels, so an invocation of 2 pixels may take 2·9 iterations per VSGL.
/// Measured on diffuse_cornell at 32² before this bound: mean indirect 0.535 of the reference at
/// N = 4096 and 0.063 at 8192 (whole invocations past the cap lost), 1.001 at 2048.
const CPU_NEAR_FIELD_VSGLS_PER_PIXEL_PER_DISPATCH: u32 = 2048;

/// Diffuse shading form.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiffuseMode {
    /// The papers' cosine-pulled-out form with A(λ) ≈ 2π/λ.
    Papers,
    /// The clamped cosine kept inside the integral (no light from below the horizon).
    Accurate,
    /// The SG product integral with the Lambert lobe as an SG (the 2015 poster, cheap for a few
    /// VSGLs; leaks light from lobes below the horizon).
    SgProduct,
}

impl DiffuseMode {
    /// Whether this form's diffuse term always fades out below a cluster's mean tangent plane
    /// (the specular term never needs it: the ASG form vanishes there). The
    /// accurate clamped cosine and the SG product integrate the incoming lobe's part above the
    /// receiver's horizon, so a plane lights itself (3.9% of its direct light at N = 4096)
    /// unless the cluster's own hemisphere is enforced. The papers' form fades only with the
    /// method's `plane_fade` (vsgl's default): its horizon clamp gives the lit side of a lone
    /// plane exactly 0, but not the back, which got about half the front's direct light.
    pub fn fades_below_tangent_plane(self) -> bool {
        self != DiffuseMode::Papers
    }

    /// `ShadeParams.diffuse_mode` of the shader.
    fn shader_code(self) -> u32 {
        match self {
            DiffuseMode::Papers => 0,
            DiffuseMode::Accurate => 1,
            DiffuseMode::SgProduct => 2,
        }
    }
}

/// Specular (glossy) shading form of the SG lighting, `lighting=` (the diffuse form of
/// `Accurate` is [`DiffuseMode::Accurate`], chosen by the method).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightingMode {
    /// The papers' SG–ASG product integral (`vsgl_specular`).
    Asg,
    /// The GGX NDF widened by the light's spread through the reflection Jacobian
    /// (`vsgl_specular_accurate`, after Tokuyoshi et al. 2024).
    Accurate,
    /// The two weighted by the receiver's share α/α' of the widened lobe
    /// (`vsgl_specular_blend`; docs/methods/vsgl.md, "SG lighting").
    Blend,
}

impl LightingMode {
    /// `ShadeParams.lighting_mode` of the shader.
    fn shader_code(self) -> u32 {
        match self {
            LightingMode::Asg => 0,
            LightingMode::Accurate => 1,
            LightingMode::Blend => 2,
        }
    }
}

/// How the Lambert lobe's SG is normalized (`lambert_lobe=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LambertLobe {
    /// [`LambertLobe::Hemisphere`] blended with an exact Lambertian point emitter where the
    /// cluster is compact as seen from the receiver (`lambert_exact_weight` in
    /// vsgl_shading.wgsl). An option: it wins on the closed diffuse box and loses where floor
    /// clusters light a wall at grazing angles (docs/methods/vsgl.md).
    ExactCompact,
    /// Over its own hemisphere, so a texel sends its whole diffuse power where a Lambertian
    /// surface can (`LAMBERT_LOBE_HEMISPHERE_GAIN` in sg.wgsl): 1 + e^(−λd) ≈ 1.101 times the
    /// papers' lobe.
    Hemisphere,
    /// Over the whole sphere, as the papers do [Tok16s Eq. 1]: 9.2% of each texel's diffuse
    /// power lies below its own plane and lights nothing.
    Papers,
}

impl LambertLobe {
    fn shader_code(self) -> u32 {
        match self {
            LambertLobe::Papers => 0,
            LambertLobe::Hemisphere => 1,
            LambertLobe::ExactCompact => 2,
        }
    }
}

pub struct VsglShadingPass {
    pipelines: PipelineVariants,
}

/// The pixels per thread of a variant, from its HAS_SPECULAR flag: what the shader's override
/// gets and what the dispatch is sized by.
fn pixels_per_thread(has_specular: bool) -> u32 {
    if has_specular {
        PIXELS_PER_THREAD_WITH_SPECULAR
    } else {
        PIXELS_PER_THREAD_DIFFUSE_ONLY
    }
}

fn numeric_constants(flags: &[(&'static str, bool)]) -> Vec<(&'static str, f64)> {
    let has_specular = flags.iter().any(|&(name, on)| name == "HAS_SPECULAR" && on);
    vec![("PIXELS_PER_THREAD", f64::from(pixels_per_thread(has_specular)))]
}

impl VsglShadingPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        Ok(Self { pipelines: PipelineVariants::with_numeric_constants(gpu, "passes/vsgl_shading.wgsl", "main", numeric_constants)? })
    }

    pub fn record(&self, rec: &mut Recorder<'_>, io: &ShadingInputs<'_>, lights: VirtualLightList<'_>, form: VsglShadingForm, candidates: Option<&ShadingCandidates<'_>>) {
        self.record_as(rec, "vsgl_shading", io, lights, form, candidates);
    }

    /// [`Self::record`] under another name in `frame.passes` and the timings (the emitter
    /// VSGLs' direct light is `emitter_direct`).
    pub fn record_as(&self, rec: &mut Recorder<'_>, name: &str, io: &ShadingInputs<'_>, lights: VirtualLightList<'_>, form: VsglShadingForm, candidates: Option<&ShadingCandidates<'_>>) {
        let ShadingInputs { frame_uniforms: frame, gbuffer, out, features, size, visibility } = *io;
        let VirtualLightList { records: vsgls, count, interleave } = lights;
        let VsglShadingForm { diffuse, lighting, lambert_lobe, exact_texels, plane_fade, fade_glossy } = form;
        let gpu = rec.gpu;
        let [specular] = features.specular_flags();
        let [traced, ism, paged] = visibility.flags();
        let pipeline = self.pipelines.get(gpu, &[specular, traced, ism, paged]);
        let pixels_per_thread = pixels_per_thread(specular.1);
        // `frame.passes` names the visibility variant.
        let label = format!("{name}{}", visibility.label_suffix());
        // Chunks are multiples of k² so the interleaved subsets stay j ≡ t (mod k²).
        let near_field = candidates.is_some_and(|c| c.near_field);
        let per_dispatch = if visibility.traced {
            traced_lights_per_dispatch(gpu)
        } else if near_field && gpu.caps_loop_iterations() {
            CPU_NEAR_FIELD_VSGLS_PER_PIXEL_PER_DISPATCH
        } else {
            VSGLS_PER_PIXEL_PER_DISPATCH
        };
        let chunk = per_dispatch * interleave * interleave;
        // Read only with candidates; a placeholder of its own otherwise.
        let placeholder = if candidates.is_none() { Some(rec.storage("vsgl_shading_shadow_candidates_placeholder_buffer", 32)) } else { None };
        let candidate_buffer = candidates.map(|c| c.buffer).or(placeholder.as_ref()).expect("a candidates buffer or its placeholder");
        for_each_chunk(count, chunk, |first, n| {
            let params = ShadeParamsRaw { count: n, interleave, diffuse_mode: diffuse.shader_code(), first, exact_texels: u32::from(exact_texels), plane_fade: u32::from(plane_fade) * if fade_glossy { 2 } else { 1 }, lighting_mode: lighting.shader_code(), lambert_lobe: lambert_lobe.shader_code(), shadow_candidates: u32::from(candidates.is_some()) * SHADOW_CANDIDATES, seed: candidates.map_or(0, |c| c.seed), resample_target: u32::from(candidates.is_some_and(|c| c.resample_target && visibility.traced)), near_field_texels: u32::from(candidates.is_some_and(|c| c.near_field)) };
            let uniform = rec.uniform("vsgl_shading_params_uniform_buffer", &params);
            rec.compute(
                &label,
                &pipeline,
                &[&[frame.as_entire_binding()], &[out.shading_bindings(&uniform, vsgls, gbuffer), vec![candidate_buffer.as_entire_binding()]].concat(), &visibility.bindings()],
                interleaved_block_groups(size, interleave, (WORKGROUP * pixels_per_thread, WORKGROUP)),
            );
        });
    }
}
