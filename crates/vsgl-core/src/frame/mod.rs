//! Frame data shared between passes: GPU twins of the per-frame uniforms and lights
//! ([`uniforms`]), the per-frame targets ([`targets`]) and a light's RSM with its pyramids
//! ([`rsm`]). Passes and methods read and write these; nothing here records GPU work.

pub mod lpv;
pub mod rsm;
pub mod shading_inputs;
pub mod shading_visibility;
pub mod targets;
pub mod uniforms;

pub use rsm::{pyramid_layout, MomentChains, Rsm, RsmLight};
pub use shading_inputs::{ShadingInputs, VirtualLightList};
pub use shading_visibility::{IsmLookupRaw, ShadingVisibility};
pub use targets::{GBuffer, IndirectTargets, VisibilityTargets};
