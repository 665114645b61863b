//! The one error type of vsgl-core. `vsgl-py/src/errors.rs` maps each variant to a Python
//! exception; nothing reachable from Python panics.

use std::path::Path;

#[derive(thiserror::Error, Debug)]
pub enum Error {
    /// No usable GPU or CPU adapter; the message says how to get one.
    #[error("{0}")]
    NoAdapter(String),
    /// A malformed or hostile scene file, naming the file and the element.
    #[error("{file}: {element}: {message}")]
    Scene { file: String, element: String, message: String },
    /// A shader failed to compose or compile.
    #[error("shader {file}:{line}: {message}")]
    ShaderCompile { file: String, line: u32, message: String },
    /// wgpu reported a validation error (a bug in vsgl, or a device limit).
    #[error("GPU validation error in {context}: {message}")]
    Validation { context: String, message: String },
    #[error("GPU out of memory in {context}")]
    OutOfMemory { context: String },
    /// A frame computed NaN or Inf values (counted on the GPU as the AOVs are packed): the
    /// message names the AOVs and counts. vsgl never hands such a frame out.
    #[error("{message}; the inputs are beyond what f32 shading represents (extreme intensities or scales), or this is a bug in vsgl: please report it with the scene and settings")]
    NonFinite { message: String },
    /// A long render stopped between GPU batches at the caller's request (Ctrl-C).
    #[error("{0}")]
    Interrupted(String),
    /// A bad argument value, naming the argument and what was expected.
    #[error("{argument}: {message}")]
    InvalidArgument { argument: String, message: String },
    /// The scene and settings need more of a device resource than the adapter has (shadow-map
    /// layers or memory, the light list): the message names the limit, the numbers and how to
    /// stay within it. Raised at the start of a render, before any GPU work.
    #[error("{0}")]
    ResourceLimit(String),
}

pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    pub fn scene(file: &Path, element: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Scene { file: file.display().to_string(), element: element.into(), message: message.into() }
    }
    pub fn invalid(argument: impl Into<String>, message: impl Into<String>) -> Self {
        Error::InvalidArgument { argument: argument.into(), message: message.into() }
    }
}
