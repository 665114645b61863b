//! VSGL generation (compute): filtered importance sampling of the mipmapped RSM, with the
//! 2015 density kernel or the 2016 bisection ("integral") kernel.

use crate::error::Result;
use crate::frame::{MomentChains, Rsm};
use crate::gpu::{groups, Gpu, Recorder};
use crate::passes::vpl_sample::Sampling;

use crate::shader_lib::constants::vsgl_gen::WORKGROUP;

/// GPU twin of `VsglRaw` in `wgsl/common/vsgl_record.wgsl` (128 bytes = 32 f32).
pub const VSGL_FLOATS: usize = 32;
pub const VSGL_BYTES: u64 = 128;

/// Field names and widths of a VSGL record, in order (for `Frame.vsgls()`).
pub const VSGL_FIELDS: &[(&str, usize)] = &[
    ("mean", 3),
    ("variance", 1),
    ("diffuse_axis", 3),
    ("diffuse_sharpness", 1),
    ("diffuse_power", 3),
    ("level", 1),
    ("specular_axis", 3),
    ("specular_sharpness", 1),
    ("specular_power", 3),
    ("pdf", 1),
    ("center", 2),
    ("mass", 1),
    ("texels", 1),
    ("plane_normal", 3),
    ("plane_offset", 1),
    ("shadow_target", 3),
    ("_pad2", 1),
];
const _: () = {
    let mut total = 0;
    let mut i = 0;
    while i < VSGL_FIELDS.len() {
        total += VSGL_FIELDS[i].1;
        i += 1;
    }
    assert!(total == VSGL_FLOATS);
};

/// Kernel size rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// 2015: l = l_max − ½ log2(N p(s)).
    Density,
    /// 2016: (4^l/M) p̄(s, l) = K/N by bisection.
    Integral,
    /// Quadtree nodes: the coarsest node on the sampled texel's path whose
    /// probability mass is at most K/N, its moments read exactly (no filtering): unbiased totals.
    Node,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GenParamsRaw {
    count: u32,
    levels: u32,
    rsm_size: u32,
    sampling: u32,
    seed: u32,
    kernel: u32,
    bisection_steps: u32,
    chain_len: u32,
    light_offset: [f32; 3],
    k: f32,
    planes: u32,
    importance: u32,
    coherence: f32,
    shadow_candidates: u32,
    kernel_filter: u32,
    _pad: [u32; 3],
}

/// How the filtered kernels ("density", "integral") read the moment mips at their level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KernelFilter {
    /// [Tok16 §4]: the mips read trilinearly at the kernel's centre, bilinear within a level.
    Trilinear,
    /// The quadtree nodes that hold the centre at the two levels around the kernel's, blended by
    /// the level's fraction: a kernel of about a texel is that texel (experiments/vsgl_defaults_on_the_corpus.md).
    Nodes,
}

impl KernelFilter {
    /// `KERNEL_FILTER_*` of `vsgl_gen.wgsl`.
    fn shader_code(self) -> u32 {
        match self {
            KernelFilter::Trilinear => 0,
            KernelFilter::Nodes => 1,
        }
    }
}

/// What one generation dispatch needs besides the RSM.
#[derive(Clone, Copy)]
pub struct GenSettings<'a> {
    pub count: u32,
    pub sampling: Sampling,
    /// The Metropolis chains' positions, read for [`Sampling::Metropolis`] only.
    pub samples: Option<&'a wgpu::Buffer>,
    pub seed: u32,
    pub kernel: Kernel,
    pub k: f32,
    pub bisection_steps: u32,
    pub light_offset: [f32; 3],
    /// The sampling pyramid is a density other than the moments' weight (bidirectional
    /// importance, `brsm_mix`): kernel masses and estimator densities are read from it.
    pub importance: bool,
    /// Smallest mean-normal length a kernel may have (`coherence=`; 0: the papers' kernels).
    /// Needs chains with planes ([`MomentChains::has_planes`]); ignored without.
    pub coherence: f32,
    /// Where to write [`SHADOW_CANDIDATES`] candidate shadow targets per VSGL
    /// (`shadow_target="resampled"` with `visibility="raytrace"`; rows of
    /// [`SHADOW_CANDIDATE_BYTES`]), or none.
    pub shadow_candidates: Option<&'a wgpu::Buffer>,
    /// How "density" and "integral" read the mips ("node" reads its node whatever this says).
    pub filter: KernelFilter,
}

/// Candidate shadow targets per VSGL (`shadow_target="resampled"`): in the float64 model of
/// experiments/corpus_shadow_targets_and_bounds.md ("Which texel the shadow ray aims at") 4 keep 0.92 and 8 keep 0.95-0.97 of the
/// every-texel reference's shadowed light from FlightHelmet's 4-texel clusters.
pub const SHADOW_CANDIDATES: u32 = 8;
/// Bytes of one VSGL's candidates: per candidate its point and its normal, two vec4f rows.
pub const SHADOW_CANDIDATE_BYTES: u64 = SHADOW_CANDIDATES as u64 * 32;

pub struct VsglGenPass {
    pipeline: wgpu::ComputePipeline,
}

/// What VSGLs are generated from: the RSM, the density their texels are drawn by (level 0 of a
/// pyramid laid out as `rsm.pyramid`) and the RSM's mipmapped moments.
#[derive(Clone, Copy)]
pub struct GenSource<'a> {
    pub rsm: &'a Rsm,
    pub pdf: &'a wgpu::Buffer,
    pub chains: &'a MomentChains,
}

impl VsglGenPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/vsgl_gen.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("vsgl_gen_pipeline", &module, "main") })
    }

    /// VSGLs sampled by the RSM's own weight pyramid (its `GenSource` with `pdf: &rsm.pyramid`).
    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, chains: &MomentChains, s: &GenSettings<'_>, out: &wgpu::Buffer) {
        self.record_with_pdf(rec, "vsgl_gen", &GenSource { rsm, pdf: &rsm.pyramid, chains }, s, out);
    }

    /// VSGLs sampled by `source.pdf`, a pyramid in the layout of `rsm.pyramid` (`s.importance`
    /// says whether it differs from the moments' weight), timed as `label`.
    pub fn record_with_pdf(&self, rec: &mut Recorder<'_>, label: &str, source: &GenSource<'_>, s: &GenSettings<'_>, out: &wgpu::Buffer) {
        let GenSource { rsm, pdf, chains } = *source;
        let params = GenParamsRaw {
            count: s.count,
            levels: rsm.levels,
            rsm_size: rsm.size,
            sampling: match s.sampling { Sampling::Random => 0, Sampling::Stratified => 1, Sampling::Metropolis => 2 },
            seed: s.seed,
            kernel: match s.kernel { Kernel::Density => 0, Kernel::Integral => 1, Kernel::Node => 2 },
            bisection_steps: s.bisection_steps,
            chain_len: chains.chain_len,
            light_offset: s.light_offset,
            k: s.k,
            planes: u32::from(chains.has_planes()),
            importance: s.importance as u32,
            coherence: s.coherence,
            shadow_candidates: if s.shadow_candidates.is_some() { SHADOW_CANDIDATES } else { 0 },
            kernel_filter: s.filter.shader_code(),
            _pad: [0; 3],
        };
        // Unwritten without candidates: a small placeholder of its own (never one of the other
        // bindings, which would alias a writable binding).
        let placeholder;
        let candidates = match s.shadow_candidates {
            Some(b) => b,
            None => {
                placeholder = rec.storage("vsgl_shadow_candidates_placeholder_buffer", 32);
                &placeholder
            }
        };
        let uniform = rec.uniform("vsgl_gen_params_uniform_buffer", &params);
        rec.compute(
            label,
            &self.pipeline,
            &[&[
                uniform.as_entire_binding(),
                pdf.as_entire_binding(),
                rsm.level_offsets.as_entire_binding(),
                chains.buffer.as_entire_binding(),
                out.as_entire_binding(),
                // Unread unless sampling 2: the RSM positions stand in (read-only vec4f).
                s.samples.unwrap_or(&rsm.gbuffer.position).as_entire_binding(),
                candidates.as_entire_binding(),
            ]],
            (groups(s.count, WORKGROUP), 1, 1),
        );
    }
}
