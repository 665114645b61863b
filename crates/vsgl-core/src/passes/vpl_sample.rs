//! VPL sampling (compute): importance sampling of the RSM by hierarchical sample warping, or
//! every texel as a VPL (the reference).

use crate::error::Result;
use crate::frame::Rsm;
use crate::gpu::{groups, storage_binding, uniform_binding, Gpu, PipelineVariants, Recorder};
use crate::plan::ShaderFeatures;

use crate::shader_lib::constants::vpl_sample::WORKGROUP;

/// GPU twin of `Vpl` in `wgsl/common/vpl.wgsl` (80 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VplRaw {
    pub position: [f32; 3],
    pub roughness: f32,
    pub normal: [f32; 3],
    pub _pad0: f32,
    pub flux_diffuse: [f32; 3],
    pub _pad1: f32,
    pub flux_specular: [f32; 3],
    pub _pad2: f32,
    pub to_light: [f32; 3],
    pub _pad3: f32,
}
pub const VPL_BYTES: u64 = 80;
const _: () = assert!(std::mem::size_of::<VplRaw>() == VPL_BYTES as usize);

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SampleParamsRaw {
    count: u32,
    levels: u32,
    rsm_size: u32,
    mode: u32,
    seed: u32,
    first: u32,
    _pad: [u32; 2],
}

/// How importance-sampled VPL positions are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sampling {
    /// Fibonacci lattice (low discrepancy), rotated per seed.
    Stratified,
    /// Seeded random numbers.
    Random,
    /// The states of Metropolis–Hastings chains kept across frames (`methods::metropolis`).
    Metropolis,
}

pub struct VplSamplePass {
    importance: PipelineVariants,
    every_texel: PipelineVariants,
}

impl VplSamplePass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/vpl_sample.wgsl")?;
        // Both entry points share one layout (every_texel ignores the pyramid bindings).
        let mut bindings = vec![uniform_binding()];
        bindings.extend([storage_binding(true); 7]);
        bindings.push(storage_binding(false));
        bindings.push(storage_binding(true));
        Ok(Self {
            importance: PipelineVariants::from_module(module.clone(), "passes/vpl_sample.wgsl", "importance", Some(bindings.clone())),
            every_texel: PipelineVariants::from_module(module, "passes/vpl_sample.wgsl", "every_texel", Some(bindings)),
        })
    }

    fn dispatch(&self, rec: &mut Recorder<'_>, label: &str, pipeline: &wgpu::ComputePipeline, params: SampleParamsRaw, source: &VplSource<'_>, (pdf, samples): (&wgpu::Buffer, Option<&wgpu::Buffer>)) {
        let (rsm, out) = (source.rsm, source.out);
        let uniform = rec.uniform("vpl_sample_params_uniform_buffer", &params);
        rec.compute(
            label,
            pipeline,
            &[&[
                uniform.as_entire_binding(),
                source.light.as_entire_binding(),
                pdf.as_entire_binding(),
                rsm.level_offsets.as_entire_binding(),
                rsm.gbuffer.position.as_entire_binding(),
                rsm.gbuffer.normal.as_entire_binding(),
                rsm.flux_diffuse.as_entire_binding(),
                rsm.flux_specular.as_entire_binding(),
                out.as_entire_binding(),
                // Unread unless mode 2: the RSM positions stand in (read-only vec4f).
                samples.unwrap_or(&rsm.gbuffer.position).as_entire_binding(),
            ]],
            (groups(params.count, WORKGROUP), 1, 1),
        );
    }

    /// `draw.count` VPLs with p ∝ `draw.pdf` (level 0 of a pyramid in the layout of
    /// `rsm.pyramid`: that pyramid itself, Φ·(R_d + R_s), or the bidirectional importance of
    /// `brsm_mix`), estimator weights 1/(N p).
    pub fn record_importance(&self, rec: &mut Recorder<'_>, source: &VplSource<'_>, draw: &ImportanceDraw<'_>) {
        let gpu = rec.gpu;
        let rsm = source.rsm;
        let params = SampleParamsRaw {
            count: draw.count,
            levels: rsm.levels,
            rsm_size: rsm.size,
            mode: match draw.sampling { Sampling::Stratified => 0, Sampling::Random => 1, Sampling::Metropolis => 2 },
            seed: draw.seed,
            first: 0,
            _pad: [0; 2],
        };
        let pipeline = self.importance.get(gpu, &source.features.specular_flags());
        self.dispatch(rec, "vpl_sample", &pipeline, params, source, (draw.pdf, draw.samples));
    }

    /// Texels `first .. first + count` as VPLs of weight Φ·R.
    pub fn record_every_texel(&self, rec: &mut Recorder<'_>, source: &VplSource<'_>, first: u32, count: u32) {
        let gpu = rec.gpu;
        let rsm = source.rsm;
        let params = SampleParamsRaw { count, levels: rsm.levels, rsm_size: rsm.size, mode: 0, seed: 0, first, _pad: [0; 2] };
        // Reported as its own variant in `frame.passes`, timed as `vpl_sample`.
        let pipeline = self.every_texel.get(gpu, &source.features.specular_flags());
        self.dispatch(rec, "vpl_sample[every_texel]", &pipeline, params, source, (&rsm.pyramid, None));
    }
}

/// What VPLs are made from and into: one light's RSM, the light's record, the VPL buffer.
pub struct VplSource<'a> {
    /// The light's `LightRaw` record.
    pub light: &'a wgpu::Buffer,
    pub rsm: &'a Rsm,
    /// The VPL records written.
    pub out: &'a wgpu::Buffer,
    pub features: ShaderFeatures,
}

/// How [`VplSamplePass::record_importance`] draws its texels.
pub struct ImportanceDraw<'a> {
    /// VPLs to draw.
    pub count: u32,
    /// The density, level 0 of a pyramid laid out as `rsm.pyramid`.
    pub pdf: &'a wgpu::Buffer,
    pub sampling: Sampling,
    pub seed: u32,
    /// The Metropolis chains' positions, read for [`Sampling::Metropolis`] only.
    pub samples: Option<&'a wgpu::Buffer>,
}

