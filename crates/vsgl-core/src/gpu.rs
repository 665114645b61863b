//! The headless GPU context: adapter choice, device, timestamp queries, dispatch and readback.
//!
//! No window and no surface. Adapters are ranked discrete GPU → integrated → virtual → CPU
//! (lavapipe); `VSGL_ADAPTER` or an explicit filter picks one by name substring.

use crate::error::{Error, Result};
use std::sync::Arc;

/// What `vsgl.adapters()` lists.
#[derive(Clone, Debug)]
pub struct AdapterSummary {
    pub name: String,
    pub backend: String,
    pub device_type: String,
    pub driver: String,
    pub timestamps: bool,
    /// wgpu's SUBGROUP feature (subgroup arithmetic in compute shaders).
    pub subgroups: bool,
}

const INSTALL_HINT: &str = "no usable GPU or CPU adapter was found by wgpu (Vulkan). \
On Debian/Ubuntu install a Vulkan driver and loader: \
`apt-get install mesa-vulkan-drivers libvulkan1` (lavapipe, a CPU Vulkan driver, is enough).";

fn instance() -> wgpu::Instance {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    // Vulkan on Linux/Windows, Metal on macOS, DX12 on Windows. GL is left out: headless EGL
    // is unreliable and lacks the compute features the passes use.
    desc.backends = wgpu::Backends::VULKAN | wgpu::Backends::METAL | wgpu::Backends::DX12;
    desc.flags = wgpu::InstanceFlags::empty();
    wgpu::Instance::new(desc)
}

fn rank(t: wgpu::DeviceType) -> u32 {
    match t {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 3,
        wgpu::DeviceType::Other => 4,
    }
}

fn summary(a: &wgpu::Adapter) -> AdapterSummary {
    let info = a.get_info();
    AdapterSummary {
        name: info.name.clone(),
        backend: format!("{:?}", info.backend).to_lowercase(),
        device_type: format!("{:?}", info.device_type),
        driver: format!("{} {}", info.driver, info.driver_info).trim().to_string(),
        timestamps: a.features().contains(wgpu::Features::TIMESTAMP_QUERY),
        subgroups: a.features().contains(wgpu::Features::SUBGROUP),
    }
}

fn ranked_adapters(inst: &wgpu::Instance) -> Vec<wgpu::Adapter> {
    let mut v = pollster::block_on(inst.enumerate_adapters(wgpu::Backends::all()));
    v.sort_by_key(|a| rank(a.get_info().device_type));
    v
}

/// Every adapter wgpu sees, best first.
pub fn adapters() -> Vec<AdapterSummary> {
    ranked_adapters(&instance()).iter().map(summary).collect()
}

/// Device, queue and what the adapter can do. Cheap to share (`Arc`).
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter: AdapterSummary,
    /// Whether passes can carry timestamp writes.
    pub timestamps: bool,
    pub limits: wgpu::Limits,
    /// Pipelines compiled by [`PipelineVariants`] so far (each variant once).
    pub variants_compiled: std::sync::atomic::AtomicUsize,
}

impl Gpu {
    /// Opens the best adapter, or the first whose name contains `filter` (case-insensitive);
    /// `filter = None` falls back to the `VSGL_ADAPTER` environment variable.
    pub fn new(filter: Option<&str>) -> Result<Arc<Self>> {
        let inst = instance();
        let all = ranked_adapters(&inst);
        let env = std::env::var("VSGL_ADAPTER").ok().filter(|s| !s.is_empty());
        let (filter, from_env) = match filter {
            Some(f) => (Some(f.to_string()), false),
            None => (env, true),
        };
        let adapter = match &filter {
            Some(f) => {
                let needle = f.to_lowercase();
                all.into_iter().find(|a| a.get_info().name.to_lowercase().contains(&needle)).ok_or_else(|| {
                    let names: Vec<String> = adapters().into_iter().map(|a| a.name).collect();
                    let source = if from_env { "VSGL_ADAPTER" } else { "adapter" };
                    Error::NoAdapter(format!(
                        "{source}={f:?} matches no adapter; available: {}",
                        if names.is_empty() { format!("none ({INSTALL_HINT})") } else { names.join(", ") }
                    ))
                })?
            }
            None => all.into_iter().next().ok_or_else(|| Error::NoAdapter(INSTALL_HINT.into()))?,
        };
        let summary = summary(&adapter);
        let mut features = wgpu::Features::empty();
        if summary.timestamps {
            features |= wgpu::Features::TIMESTAMP_QUERY;
        }
        if summary.subgroups {
            features |= wgpu::Features::SUBGROUP;
        }
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("vsgl_device"),
            required_features: features,
            required_limits: limits.clone(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| Error::NoAdapter(format!("adapter {:?} refused a device: {e}", summary.name)))?;
        // Errors are caught by scopes around each frame; anything that escapes is logged, never
        // a panic across the Python boundary.
        device.on_uncaptured_error(Arc::new(|e: wgpu::Error| log::error!("uncaptured wgpu error: {e}")));
        Ok(Arc::new(Self { device, queue, timestamps: summary.timestamps, adapter: summary, limits, variants_compiled: Default::default() }))
    }

    /// Compiles a composed WGSL shader, turning compilation errors into `Error::ShaderCompile`.
    pub fn shader(&self, path: &str) -> Result<wgpu::ShaderModule> {
        let src = crate::shader_lib::compose(path)?;
        // Validate with naga first so a broken shader is an error naming the file, not a
        // device-lost later.
        let module = naga::front::wgsl::parse_str(&src).map_err(|e| Error::ShaderCompile {
            file: path.into(),
            line: e.location(&src).map(|l| l.line_number).unwrap_or(0),
            message: e.emit_to_string(&src),
        })?;
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .map_err(|e| Error::ShaderCompile { file: path.into(), line: 0, message: e.emit_to_string(&src) })?;
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

    /// Reads back whole buffers (each must have COPY_SRC) as f32/u32 words, waiting for the GPU.
    pub fn read_buffers(&self, buffers: &[&wgpu::Buffer]) -> Result<Vec<Vec<u8>>> {
        let mut enc = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback_encoder") });
        let staging: Vec<wgpu::Buffer> = buffers
            .iter()
            .map(|b| {
                let s = self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("readback_staging_buffer"),
                    size: b.size(),
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                enc.copy_buffer_to_buffer(b, 0, &s, 0, b.size());
                s
            })
            .collect();
        self.queue.submit([enc.finish()]);
        for s in &staging {
            s.slice(..).map_async(wgpu::MapMode::Read, |_| {});
        }
        self.wait("readback")?;
        let mut out = Vec::with_capacity(staging.len());
        for s in &staging {
            let view = s
                .slice(..)
                .get_mapped_range()
                .map_err(|e| Error::Validation { context: "readback".into(), message: e.to_string() })?;
            out.push(view.to_vec());
            drop(view);
            s.unmap();
        }
        Ok(out)
    }

    /// Blocks until the queue is idle.
    pub fn wait(&self, context: &str) -> Result<()> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| Error::Validation { context: context.into(), message: format!("device poll failed: {e}") })
    }

    /// Runs `f` inside validation and out-of-memory error scopes and reports the first error.
    pub fn scoped<T>(&self, context: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let val = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let r = f();
        let v = pollster::block_on(val.pop());
        let o = pollster::block_on(oom.pop());
        if let Some(e) = o {
            return Err(Error::OutOfMemory { context: format!("{context}: {e}") });
        }
        if let Some(e) = v {
            return Err(Error::Validation { context: context.into(), message: e.to_string() });
        }
        r
    }
}

/// Binding types for [`Gpu::compute_pipeline_explicit`].
pub fn uniform_binding() -> wgpu::BindingType {
    wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Uniform, has_dynamic_offset: false, min_binding_size: None }
}
pub fn storage_binding(read_only: bool) -> wgpu::BindingType {
    wgpu::BindingType::Buffer { ty: wgpu::BufferBindingType::Storage { read_only }, has_dynamic_offset: false, min_binding_size: None }
}

/// Workgroups needed to cover `threads` with groups of `group` (callers count threads, not
/// groups, as kajiya does).
pub fn groups(threads: u32, group: u32) -> u32 {
    threads.div_ceil(group)
}

/// Per-pass GPU timestamps: two queries per pass, resolved once per frame.
pub struct PassTimer {
    pub query_set: Option<wgpu::QuerySet>,
    resolve: Option<wgpu::Buffer>,
    names: Vec<String>,
    capacity: u32,
    period_ns: f32,
}

impl PassTimer {
    pub fn new(gpu: &Gpu, capacity: u32) -> Self {
        let (query_set, resolve) = if gpu.timestamps {
            let qs = gpu.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame_timestamp_query_set"),
                ty: wgpu::QueryType::Timestamp,
                count: capacity * 2,
            });
            let rb = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame_timestamp_resolve_buffer"),
                size: capacity as u64 * 2 * 8,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            (Some(qs), Some(rb))
        } else {
            (None, None)
        };
        Self { query_set, resolve, names: Vec::new(), capacity, period_ns: gpu.queue.get_timestamp_period() }
    }

    /// A timer that records nothing (for work that is not a pass of its own).
    pub fn new_disabled() -> Self {
        Self { query_set: None, resolve: None, names: Vec::new(), capacity: 0, period_ns: 1.0 }
    }

    /// Registers a pass; returns the (begin, end) query indices when timestamps are on.
    pub fn begin(&mut self, name: &str) -> Option<(u32, u32)> {
        self.query_set.as_ref()?;
        let i = self.names.len() as u32;
        if i >= self.capacity {
            return None;
        }
        self.names.push(name.to_string());
        Some((2 * i, 2 * i + 1))
    }

    pub fn compute_writes(&self, q: Option<(u32, u32)>) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let (b, e) = q?;
        Some(wgpu::ComputePassTimestampWrites {
            query_set: self.query_set.as_ref()?,
            beginning_of_pass_write_index: Some(b),
            end_of_pass_write_index: Some(e),
        })
    }

    pub fn render_writes(&self, q: Option<(u32, u32)>) -> Option<wgpu::RenderPassTimestampWrites<'_>> {
        let (b, e) = q?;
        Some(wgpu::RenderPassTimestampWrites {
            query_set: self.query_set.as_ref()?,
            beginning_of_pass_write_index: Some(b),
            end_of_pass_write_index: Some(e),
        })
    }

    pub fn resolve(&self, enc: &mut wgpu::CommandEncoder) {
        if let (Some(qs), Some(rb)) = (&self.query_set, &self.resolve) {
            if !self.names.is_empty() {
                enc.resolve_query_set(qs, 0..self.names.len() as u32 * 2, rb, 0);
            }
        }
    }

    /// Milliseconds per pass (same name twice adds up), after the frame's submission.
    pub fn read(&self, gpu: &Gpu) -> Result<Vec<(String, f64)>> {
        let Some(rb) = &self.resolve else { return Ok(Vec::new()) };
        if self.names.is_empty() {
            return Ok(Vec::new());
        }
        let bytes = gpu.read_buffers(&[rb])?.remove(0);
        let ticks: &[u64] = bytemuck::cast_slice(&bytes);
        let mut out: Vec<(String, f64)> = Vec::new();
        for (i, name) in self.names.iter().enumerate() {
            let dt = ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * self.period_ns as f64 * 1e-6;
            match out.iter_mut().find(|(n, _)| n == name) {
                Some((_, t)) => *t += dt,
                None => out.push((name.clone(), dt)),
            }
        }
        Ok(out)
    }
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
        Self { label, path: path.into(), module, entry: entry.into(), bindings, compiled: Default::default() }
    }

    /// The pipeline with these boolean override constants (compiled now if it is the first use).
    pub fn get(&self, gpu: &Gpu, flags: &[(&'static str, bool)]) -> wgpu::ComputePipeline {
        crate::passes::note_variant(&self.path, &self.entry, flags);
        let mut compiled = self.compiled.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, p)) = compiled.iter().find(|(k, _)| k.as_slice() == flags) {
            return p.clone();
        }
        let constants: Vec<(&str, f64)> = flags.iter().map(|&(n, v)| (n, if v { 1.0 } else { 0.0 })).collect();
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
