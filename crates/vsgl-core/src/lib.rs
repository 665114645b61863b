//! vsgl-core: a real-time renderer of one-bounce glossy indirect illumination with virtual
//! spherical Gaussian lights (Tokuyoshi 2015, 2016) on wgpu. No Python here: `vsgl-py` binds it.

pub mod error;
pub mod frame;
pub mod gpu;
pub mod image_io;
pub mod methods;
pub mod passes;
pub mod plan;
pub mod progress;
pub mod renderer;
pub mod rng;
pub mod scene;
pub mod setting;
pub mod shader_lib;
pub mod upload;
pub mod verify;

pub use error::{Error, Result};
pub use renderer::{Frame, RenderOptions, Renderer};
pub use setting::Setting;
