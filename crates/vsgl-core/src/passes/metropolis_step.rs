//! One Metropolis–Hastings step per chain (compute) for `sampling="metropolis"`: moves each of
//! an RSM view's chains (kept by the renderer from frame to frame, `methods::metropolis`) and
//! writes the samples the VPL and VSGL sampling passes then read instead of warping. The
//! proposal and its acceptance ratio are derived in `wgsl/passes/metropolis_step.wgsl`.

use crate::error::Result;
use crate::frame::uniforms::FrameUniforms;
use crate::frame::Rsm;
use crate::gpu::{groups, Gpu, Recorder};

use crate::shader_lib::constants::metropolis_step::WORKGROUP;

/// Bytes per chain state and per sample (one vec4f each).
pub const STATE_BYTES: u64 = 16;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct StepParamsRaw {
    count: u32,
    kept: u32,
    rsm_size: u32,
    levels: u32,
    seed: u32,
    stratified: u32,
    orthographic: u32,
    jump: f32,
    right: [f32; 3],
    radius: f32,
    up: [f32; 3],
    rsm_space: u32,
    forward: [f32; 3],
    _pad1: f32,
    view_origin: [f32; 3],
    _pad2: f32,
}

/// One view's step.
pub struct StepSettings<'a> {
    /// Chains of the view.
    pub count: u32,
    /// Chains that continue from their stored state (the rest start from the warp).
    pub kept: u32,
    pub seed: u32,
    pub stratified: bool,
    /// States are RSM positions (`chain_space="rsm"`), not world points.
    pub rsm_space: bool,
    /// Probability of the independence (warp) move.
    pub jump: f32,
    /// Random-walk half-width in texels.
    pub radius: f32,
    /// The RSM view.
    pub view: &'a FrameUniforms,
    /// The view's origin relative to the chains' origin (computed in f64 by the caller).
    pub view_origin: [f32; 3],
}

pub struct MetropolisStepPass {
    pipeline: wgpu::ComputePipeline,
}

impl MetropolisStepPass {
    pub fn new(gpu: &Gpu) -> Result<Self> {
        let module = gpu.shader("passes/metropolis_step.wgsl")?;
        Ok(Self { pipeline: gpu.compute_pipeline("metropolis_step_pipeline", &module, "main") })
    }

    /// `pyramid`: the target's weight pyramid in the layout of `rsm.pyramid` (the RSM's own, or
    /// brsm's re-weighted one); `chains`: this view's range of the kept chain buffer;
    /// `samples`: `count` vec4f written.
    pub fn record(&self, rec: &mut Recorder<'_>, rsm: &Rsm, pyramid: &wgpu::Buffer, s: &StepSettings<'_>, chains: wgpu::BindingResource<'_>, samples: &wgpu::Buffer) {
        let v3 = |v: [f32; 4]| [v[0], v[1], v[2]];
        let params = StepParamsRaw {
            count: s.count,
            kept: s.kept,
            rsm_size: rsm.size,
            levels: rsm.levels,
            seed: s.seed,
            stratified: s.stratified as u32,
            orthographic: s.view.orthographic,
            jump: s.jump,
            right: v3(s.view.cam_right),
            radius: s.radius,
            up: v3(s.view.cam_up),
            rsm_space: s.rsm_space as u32,
            forward: v3(s.view.cam_forward),
            _pad1: 0.0,
            view_origin: s.view_origin,
            _pad2: 0.0,
        };
        let uniform = rec.uniform("metropolis_step_params_uniform_buffer", &params);
        rec.compute(
            "metropolis_step",
            &self.pipeline,
            &[&[
                uniform.as_entire_binding(),
                pyramid.as_entire_binding(),
                rsm.level_offsets.as_entire_binding(),
                rsm.gbuffer.position.as_entire_binding(),
                rsm.gbuffer.geo_normal.as_entire_binding(),
                chains,
                samples.as_entire_binding(),
            ]],
            (groups(s.count, WORKGROUP), 1, 1),
        );
    }
}
