//! Shader modules and compute pipelines: composed WGSL compiled with errors that name the real
//! `file:line`, automatic or explicit layouts, and plan-driven override-constant variants.

use super::Gpu;
use crate::error::Result;

impl Gpu {
    /// Compiles a composed WGSL shader, turning compilation errors into `Error::ShaderCompile`.
    pub fn shader(&self, path: &str) -> Result<wgpu::ShaderModule> {
        let src = crate::shader_lib::compose(path)?;
        // Validate with naga first so a broken shader is an error naming the file and line, not
        // a device-lost later.
        crate::shader_lib::validate(path, &src)?;
        Ok(self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(path),
            source: wgpu::ShaderSource::Wgsl(src.into()),
        }))
    }

    /// A compute pipeline with an automatic layout from `path`'s entry point `main`.
    pub fn compute_pipeline(&self, label: &str, module: &wgpu::ShaderModule, entry: &str) -> wgpu::ComputePipeline {
        self.compute_pipeline_with(label, module, entry, &[])
    }

    /// A compute pipeline with an explicit single bind group 0 of `bindings` (in binding order),
    /// for modules whose entry points use different subsets of the same bindings (an automatic
    /// layout would differ per entry point).
    pub fn compute_pipeline_explicit(&self, label: &str, module: &wgpu::ShaderModule, entry: &str, bindings: &[wgpu::BindingType]) -> wgpu::ComputePipeline {
        self.compute_pipeline_explicit_with(label, module, entry, bindings, &[])
    }

    /// [`Gpu::compute_pipeline_explicit`] with override constants.
    pub fn compute_pipeline_explicit_with(&self, label: &str, module: &wgpu::ShaderModule, entry: &str, bindings: &[wgpu::BindingType], constants: &[(&str, f64)]) -> wgpu::ComputePipeline {
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
            .iter()
            .enumerate()
            .map(|(i, ty)| wgpu::BindGroupLayoutEntry { binding: i as u32, visibility: wgpu::ShaderStages::COMPUTE, ty: *ty, count: None })
            .collect();
        let bgl = self.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries });
        let layout = self.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: Some(&layout),
            module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions { constants, ..Default::default() },
            cache: None,
        })
    }

    /// A compute pipeline with an automatic layout and override constants (`WGSL override`).
    /// wgpu derives the automatic layout before the constants apply, so every variant of an
    /// entry point has the same bind group layouts and takes the same bind groups.
    pub fn compute_pipeline_with(&self, label: &str, module: &wgpu::ShaderModule, entry: &str, constants: &[(&str, f64)]) -> wgpu::ComputePipeline {
        self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: None,
            module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions { constants, ..Default::default() },
            cache: None,
        })
    }

}

/// Binding types for [`Gpu::compute_pipeline_explicit`].
pub fn uniform_binding() -> wgpu::BindingType {
    wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Uniform, has_dynamic_offset: false, min_binding_size: None }
}
pub fn storage_binding(read_only: bool) -> wgpu::BindingType {
    wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Storage { read_only }, has_dynamic_offset: false, min_binding_size: None }
}

/// The override-constant variants of one compute entry point, each compiled on first use and
/// kept: a frame's plan picks a variant (e.g. `HAS_SPECULAR = false` for a diffuse-only scene),
/// so a renderer never compiles a variant no scene of its asked for, and never twice.
pub struct PipelineVariants {
    label: String,
    path: String,
    module: wgpu::ShaderModule,
    entry: String,
    /// `Some`: one explicit bind group 0 of these bindings (see `compute_pipeline_explicit`).
    bindings: Option<Vec<wgpu::BindingType>>,
    /// Numeric override constants of a variant, a function of its flags (build settings of the
    /// pass that its host code must agree on, such as vsgl_shading's pixels per thread), given
    /// after the flags. Being a function of the flags keeps the flags the cache key.
    numeric: fn(&[(&'static str, bool)]) -> Vec<(&'static str, f64)>,
    compiled: std::sync::Mutex<Vec<(Vec<(&'static str, bool)>, wgpu::ComputePipeline)>>,
}

impl PipelineVariants {
    /// Variants with automatic layouts.
    pub fn new(gpu: &Gpu, path: &str, entry: &str) -> Result<Self> {
        Ok(Self::from_module(gpu.shader(path)?, path, entry, None))
    }

    /// Variants of `module`'s `entry`, with an explicit bind group 0 of `bindings` when given.
    pub fn from_module(module: wgpu::ShaderModule, path: &str, entry: &str, bindings: Option<Vec<wgpu::BindingType>>) -> Self {
        let label = format!("{}_{entry}", path.trim_start_matches("passes/").trim_end_matches(".wgsl"));
        Self { label, path: path.into(), module, entry: entry.into(), bindings, numeric: |_| Vec::new(), compiled: Default::default() }
    }

    /// Variants with automatic layouts whose pipelines also get the numeric override constants
    /// `numeric(flags)` (a pass's numeric settings that its host code and shader must agree on;
    /// the host computes them from the same flags). One shader module serves every variant.
    pub fn with_numeric_constants(gpu: &Gpu, path: &str, entry: &str, numeric: fn(&[(&'static str, bool)]) -> Vec<(&'static str, f64)>) -> Result<Self> {
        Ok(Self { numeric, ..Self::new(gpu, path, entry)? })
    }

    /// The pipeline with these boolean override constants (compiled now if it is the first use).
    pub fn get(&self, gpu: &Gpu, flags: &[(&'static str, bool)]) -> wgpu::ComputePipeline {
        super::frame_log::note_variant(&self.path, &self.entry, flags);
        let mut compiled = self.compiled.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, p)) = compiled.iter().find(|(k, _)| k.as_slice() == flags) {
            return p.clone();
        }
        let constants: Vec<(&str, f64)> = flags.iter().map(|&(n, v)| (n, if v { 1.0 } else { 0.0 })).chain((self.numeric)(flags)).collect();
        let names: Vec<String> = flags.iter().map(|(n, v)| format!("{n}={}", *v as u8)).collect();
        let label = format!("{}_pipeline[{}]", self.label, names.join(","));
        let p = match &self.bindings {
            Some(b) => gpu.compute_pipeline_explicit_with(&label, &self.module, &self.entry, b, &constants),
            None => gpu.compute_pipeline_with(&label, &self.module, &self.entry, &constants),
        };
        compiled.push((flags.to_vec(), p.clone()));
        gpu.variants_compiled.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        p
    }
}
