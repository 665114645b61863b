//! `sampling="metropolis"` of `vpl` and `vsgl`: temporally coherent RSM sampling by
//! Metropolis–Hastings (Barák, Bittner and Havran 2013; compared in Tok16 §6). Each virtual light
//! of each RSM view is a Markov chain whose state (a world-space surface point) the renderer
//! keeps from frame to frame; every frame one step (`passes::metropolis_step`, where the
//! proposal and the acceptance ratio are derived) moves it, and the sampling passes read the
//! chain's position instead of a warped sample. docs/methods/metropolis.md, "Metropolis–Hastings
//! sampling", has the rules and measurements.

use super::brsm::Importance;
use super::rsm_lights::LightRsm;
use super::FrameContext;
use crate::error::{Error, Result};
use crate::passes::vpl_sample::Sampling;
use crate::passes::metropolis_step::{MetropolisStepPass, StepSettings, STATE_BYTES};
use glam::DVec3;

/// Probability of the independence move (a fresh draw from the warp) in each step: small, so
/// few virtual lights jump per frame, but non-zero, so chains cross regions of zero density.
pub const JUMP_PROBABILITY: f32 = 1.0 / 32.0;
/// Half-width of the random walk as a fraction of the RSM side (2 texels at 64², 8 at 256²),
/// so a chain's move covers the same part of the light's view at every RSM size.
pub const STEP_FRACTION: f32 = 1.0 / 32.0;

/// Where a chain's state lives between frames (`chain_space=`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChainSpace {
    /// The surface point, reprojected into each frame's RSM (stays put when the light moves).
    World,
    /// The continuous RSM position (moves with the light's view).
    Rsm,
}

/// How `vpl` and `vsgl` draw RSM texels: `sampling`, `chain_space` and `seed`
/// (`options::common::SAMPLING_OPTIONS`), parsed once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexelSampling {
    pub sampling: Sampling,
    /// Where a Metropolis chain's state lives between frames.
    pub chain_space: ChainSpace,
    pub seed: u32,
}

impl TexelSampling {
    pub fn from_options(o: &super::Options) -> Result<Self> {
        Ok(Self { sampling: o.choice("sampling")?, chain_space: o.choice("chain_space")?, seed: o.u32("seed")? })
    }
}

/// What the chains were made for; any change starts them afresh from the warp.
#[derive(Clone, Debug, PartialEq, Eq)]
struct ChainKey {
    method: &'static str,
    space: ChainSpace,
    /// The target density's kind (`importance=` and its settings): chains at equilibrium for
    /// one density are not for another.
    importance: Importance,
    num_lights: u32,
    rsm_size: u32,
    /// RSM views of each light, in order (1 spot or directional, 6 point).
    views: Vec<usize>,
    /// The scene's geometry as uploaded: vertex count and bounds (centre and diagonal, as
    /// bits). Not the scene instance: `render_sequence` renders a copy, and a sequence followed
    /// by `render` calls on the original should continue the chains.
    geometry: (u32, [u64; 3], u64),
}

/// The chains a renderer keeps between frames (one per virtual light per RSM view).
pub struct MetropolisChains {
    key: ChainKey,
    /// Per view slot `stride` chain states (vec4f: position relative to `origin`, w = 1 when
    /// set), `stride` = num_lights rounded up to a multiple of 16 so each view's range starts
    /// at a multiple of 256 bytes (the storage binding offset alignment wgpu accepts anywhere).
    buffer: wgpu::Buffer,
    /// World point the stored positions are relative to (the scene's anchor when made).
    origin: DVec3,
    /// Chains of each view that hold a state (its share of the previous frame that ran it).
    kept: Vec<u32>,
    /// The seed of the frame that made the chains: with `importance="brsm"` it seeds the
    /// view's VSGLs of every frame the chains continue, so a static view keeps one target
    /// density (`target_seed`).
    seed: u32,
}

/// How a method steps its chains.
pub struct MetropolisSampling {
    pub method: &'static str,
    pub num_lights: u32,
    pub rsm_size: u32,
    pub seed: u32,
    pub space: ChainSpace,
    /// Where the target density comes from (`importance=`).
    pub importance: Importance,
}

impl MetropolisSampling {
    fn key(&self, ctx: &FrameContext<'_>) -> ChainKey {
        let views = ctx.light_sources.iter().map(|l| if l.has_cube_faces() { 6 } else { 1 }).collect();
        let g = ctx.gpu_scene;
        let geometry = (g.raster_vertex_count, g.anchor.to_array().map(f64::to_bits), ctx.extent.to_bits());
        ChainKey { method: self.method, space: self.space, importance: self.importance, num_lights: self.num_lights, rsm_size: self.rsm_size, views, geometry }
    }

    /// The seed of the view VSGLs that make this frame's `importance="brsm"` target: the seed
    /// the chains were made with while they continue, this frame's when they start afresh.
    /// Why not this frame's seed: every step keeps *this frame's* target invariant, and chains
    /// distributed by last frame's density are not distributed by a different one after a
    /// step, so a target that changed with the seed would bias every estimate that divides by
    /// it. With one seed per chain lifetime the importance map of a static view is the same
    /// in every frame; a moving camera or light changes it, as a moving light changes the
    /// RSM's own weights (docs/methods/metropolis.md, "Metropolis–Hastings sampling").
    pub fn target_seed(&self, ctx: &FrameContext<'_>) -> u32 {
        let key = self.key(ctx);
        match ctx.chains.as_ref() {
            Some(c) if c.key == key => c.seed,
            _ => self.seed,
        }
    }

    /// Steps the chains of `light`'s view (made afresh first if the key changed) towards the
    /// density of `pyramid` (the RSM's weights, or the brsm re-weighted pyramid: the one the
    /// sampling passes then divide by) and returns the buffer of `light.budget` samples
    /// (vec4f: continuous RSM position in texels, p).
    pub fn step(&self, ctx: &mut FrameContext<'_>, light: &LightRsm<'_>, pyramid: &wgpu::Buffer) -> Result<wgpu::Buffer> {
        let key = self.key(ctx);
        let views: usize = key.views.iter().sum();
        let stride = (self.num_lights as u64).div_ceil(16) * 16;
        let limit = ctx.gpu.limits.max_storage_buffer_binding_size;
        if stride * STATE_BYTES > limit {
            return Err(Error::invalid("num_lights", format!("{} Metropolis chains ({} bytes) exceed this adapter's storage binding limit of {limit} bytes", self.num_lights, stride * STATE_BYTES)));
        }
        let fresh = !matches!(ctx.chains.as_ref(), Some(c) if c.key == key);
        if fresh {
            let buffer = ctx.gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("metropolis_chain_buffer"),
                size: (views as u64 * stride * STATE_BYTES).max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            *ctx.chains = Some(MetropolisChains { key, buffer, origin: ctx.gpu_scene.anchor, kept: vec![0; views], seed: self.seed });
        }
        let chains = ctx.chains.as_mut().expect("made above");
        let kept = chains.kept[light.slot].min(light.budget);
        chains.kept[light.slot] = light.budget;
        let (buffer, origin) = (chains.buffer.clone(), chains.origin);
        // The view's ray origin relative to the chains' origin, in f64 (the anchor may move when
        // the scene is uploaded again; positions stay relative to the first one).
        let o = light.view.view_origin;
        let view_origin = (ctx.gpu_scene.anchor + DVec3::new(o[0] as f64, o[1] as f64, o[2] as f64) - origin).as_vec3().to_array();
        let samples = ctx.rec.storage_written("metropolis_sample_buffer", self.num_lights as u64 * STATE_BYTES);
        let settings = StepSettings {
            count: light.budget,
            kept,
            seed: self.seed,
            stratified: true,
            rsm_space: self.space == ChainSpace::Rsm,
            jump: JUMP_PROBABILITY,
            radius: (STEP_FRACTION * self.rsm_size as f32).max(1.0),
            view: light.view,
            view_origin,
        };
        let range = wgpu::BufferBinding {
            buffer: &buffer,
            offset: light.slot as u64 * stride * STATE_BYTES,
            size: wgpu::BufferSize::new(stride * STATE_BYTES),
        };
        ctx.passes.get::<MetropolisStepPass>()?.record(&mut ctx.rec, light.rsm, pyramid, &settings, wgpu::BindingResource::Buffer(range), &samples);
        Ok(samples)
    }
}

/// Forgets the chains: the next `sampling="metropolis"` frame starts them from the warp.
pub fn reset(chains: &mut Option<MetropolisChains>) {
    *chains = None;
}
