//! The verification layer: the f64 oracle of the WGSL math ([`oracle`]), the GPU harness that
//! evaluates single WGSL functions on the GPU ([`harness`]), and the f32-vs-f64 stability suite
//! built on both ([`stability`]). No rendering code depends on it; it exists only to verify the
//! GPU math.

pub mod harness;
pub mod oracle;
pub mod stability;
