//! The headless device: adapter choice, the device and queue, error scopes, waiting.
//!
//! No window and no surface here (the window crate makes one from the kept instance). Adapters are ranked discrete GPU → integrated → virtual → CPU
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
    /// PCI bus id as the driver gives it ("0000:17:00.0"); empty where it has none (lavapipe).
    pub pci_bus_id: String,
    /// The adapter's own limits, which the device is created with: the largest storage
    /// binding, the largest buffer, the largest 2D texture side.
    pub max_storage_binding_bytes: u64,
    pub max_buffer_bytes: u64,
    pub max_texture_side: u32,
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
        pci_bus_id: info.device_pci_bus_id.clone(),
        max_storage_binding_bytes: a.limits().max_storage_buffer_binding_size,
        max_buffer_bytes: a.limits().max_buffer_size,
        max_texture_side: a.limits().max_texture_dimension_2d,
    }
}

fn ranked_adapters(inst: &wgpu::Instance) -> Vec<wgpu::Adapter> {
    let mut v = pollster::block_on(inst.enumerate_adapters(wgpu::Backends::all()));
    v.sort_by_key(|a| rank(a.get_info().device_type));
    v
}

/// (domain, bus, device, function) of a PCI bus id written "DOMAIN:BUS:DEVICE.FUNCTION" or
/// "BUS:DEVICE.FUNCTION" in hexadecimal, any case and zero padding (NVML writes an 8-digit
/// domain, Vulkan drivers a 4-digit one); None for anything else.
pub fn parse_pci_bus_id(text: &str) -> Option<(u32, u32, u32, u32)> {
    let text = text.trim();
    let (head, function) = text.rsplit_once('.')?;
    let parts: Vec<&str> = head.split(':').collect();
    let (domain, bus, device) = match parts.as_slice() {
        [d, b, v] => (*d, *b, *v),
        [b, v] => ("0", *b, *v),
        _ => return None,
    };
    let hex = |s: &str| if s.is_empty() || s.len() > 8 { None } else { u32::from_str_radix(s, 16).ok() };
    Some((hex(domain)?, hex(bus)?, hex(device)?, hex(function)?))
}

/// Every adapter wgpu sees, best first.
pub fn adapters() -> Vec<AdapterSummary> {
    ranked_adapters(&instance()).iter().map(summary).collect()
}

/// Device, queue and what the adapter can do. Cheap to share (`Arc`).
pub struct Gpu {
    /// The instance and adapter the device came from: a window makes its surface with the
    /// first and asks the second whether it can present to it (`vsgl-window`).
    pub instance: wgpu::Instance,
    pub wgpu_adapter: wgpu::Adapter,
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
    /// Whether the adapter ends the loops of a shader invocation once it has run 65535 loop
    /// iterations in all, nested loops counted (lavapipe, a CPU adapter; an invocation past the
    /// cap loses its output). Passes whose loops grow with their input take smaller pieces of it
    /// per dispatch there (`traced_lights_per_dispatch`, the path tracer's samples per dispatch).
    pub fn caps_loop_iterations(&self) -> bool {
        self.adapter.device_type == "Cpu"
    }

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
            Some(f) if f.to_lowercase().starts_with("pci:") => {
                // A PCI bus id (what NVML and nvidia-smi give a cluster task for its GPU).
                let wanted = parse_pci_bus_id(&f[4..]);
                let found = all.into_iter().find(|a| wanted.is_some() && parse_pci_bus_id(&a.get_info().device_pci_bus_id) == wanted);
                found.ok_or_else(|| {
                    let seen: Vec<String> = adapters().into_iter().map(|a| format!("{} ({})", a.name, if a.pci_bus_id.is_empty() { "no bus id" } else { &a.pci_bus_id })).collect();
                    Error::NoAdapter(format!("no adapter at PCI bus id {:?}; adapters seen: {}", &f[4..], if seen.is_empty() { "none".into() } else { seen.join(", ") }))
                })?
            }
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
        Ok(Arc::new(Self { instance: inst, wgpu_adapter: adapter, device, queue, timestamps: summary.timestamps, adapter: summary, limits, variants_compiled: Default::default() }))
    }

    /// Blocks until the queue is idle.
    pub fn wait(&self, context: &str) -> Result<()> {
        self.wait_for(None, context)
    }

    /// Blocks until `submission` has finished (the whole queue when `None`), not waiting for
    /// work submitted after it: a frame in flight reads back while the next one runs.
    pub fn wait_for(&self, submission: Option<&wgpu::SubmissionIndex>, context: &str) -> Result<()> {
        self.device
            .poll(wgpu::PollType::Wait { submission_index: submission.cloned(), timeout: None })
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

#[cfg(test)]
mod tests {
    use super::parse_pci_bus_id;

    #[test]
    fn pci_bus_ids_compare_across_nvml_and_vulkan_spellings() {
        // NVML / nvidia-smi: 8-digit domain, upper case; Vulkan drivers: 4-digit, lower case.
        assert_eq!(parse_pci_bus_id("00000000:17:00.0"), parse_pci_bus_id("0000:17:00.0"));
        assert_eq!(parse_pci_bus_id("00000000:AB:1F.3"), Some((0, 0xab, 0x1f, 3)));
        assert_eq!(parse_pci_bus_id("ab:1f.3"), Some((0, 0xab, 0x1f, 3)));
        assert_ne!(parse_pci_bus_id("0000:17:00.0"), parse_pci_bus_id("0000:18:00.0"));
        for bad in ["", "llvmpipe", "0000:17:00", "0000:zz:00.0", "1:2:3:4.0", "000000000:17:00.0"] {
            assert_eq!(parse_pci_bus_id(bad), None, "{bad:?}");
        }
    }
}
