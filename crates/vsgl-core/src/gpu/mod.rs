//! The GPU wing: everything about talking to wgpu that is not a pass — the device
//! ([`device`]), shader modules and pipeline variants ([`pipelines`]), recording dispatches
//! ([`dispatch`]), the per-renderer cache of passes ([`pass_cache`]), buffers and readback
//! ([`buffers`]), the buffers and textures kept from frame to frame ([`resources`]) and the bind
//! groups over them ([`bind_groups`]), per-pass timestamps ([`timer`]) and the
//! per-frame log of allocations and variants ([`frame_log`]). Passes and methods build on it;
//! it depends on neither.

pub mod bind_groups;
pub mod buffers;
pub mod device;
pub mod dispatch;
pub mod frame_log;
pub mod pass_cache;
pub mod pipelines;
pub mod resources;
pub mod timer;

pub use bind_groups::PipelineRef;
pub use buffers::{kept_staging_buffer, read_staging, read_staging_with, storage_buffer};
pub use device::{adapters, AdapterSummary, Gpu};
pub use pass_cache::{Pass, PassCache};
pub use dispatch::{entries, for_each_chunk, groups, interleaved_block_groups, interleaved_groups, traced_lights_per_dispatch, Recorder};
pub use pipelines::{storage_binding, uniform_binding, PipelineVariants};
pub use resources::FrameResources;
pub use timer::PassTimer;
