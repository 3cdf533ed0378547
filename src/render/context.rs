//! The wgpu device: prefers a hardware adapter, falls back to any (software Vulkan on machines
//! without a GPU), logs what it got, and can be forced with environment variables.
//!
//! - `WGPU_BACKEND=vulkan|gl|...` restricts backends (wgpu's own variable).
//! - `BOUNCELAB_ADAPTER=<substring>` picks the first adapter whose name contains it
//!   (`WGPU_ADAPTER_NAME` is honoured too); `BOUNCELAB_ADAPTER=cpu` picks a software adapter.

use std::sync::Arc;

/// Optional features used when the adapter has them.
pub fn wanted_features() -> wgpu::Features {
    wgpu::Features::TIMESTAMP_QUERY
        | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS
        | wgpu::Features::FLOAT32_FILTERABLE
        | wgpu::Features::FLOAT32_BLENDABLE
}

/// Why no device could be created.
#[derive(Debug, thiserror::Error)]
pub enum ContextError {
    /// No adapter at all (on Linux without a GPU: install `mesa-vulkan-drivers`).
    #[error("no GPU adapter found{0}; on Linux without a GPU install mesa-vulkan-drivers (software Vulkan)")]
    NoAdapter(String),
    /// The adapter refused the device.
    #[error("cannot create a device on {adapter}: {message}")]
    Device { adapter: String, message: String },
}

/// A device, its queue and what the adapter is.
#[derive(Clone)]
pub struct GpuContext {
    /// The adapter the device was created on.
    pub adapter: Arc<wgpu::Adapter>,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Name, backend, device type, driver.
    pub info: wgpu::AdapterInfo,
}

impl GpuContext {
    /// Creates a headless device, preferring hardware.
    pub fn new_headless() -> Result<Self, ContextError> {
        pollster::block_on(Self::new_headless_async())
    }

    async fn new_headless_async() -> Result<Self, ContextError> {
        // Vulkan/Metal/DX12 first; GL only if none of them has an adapter (or WGPU_BACKEND asks).
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        desc.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
        let mut adapters = wgpu::Instance::new(desc).enumerate_adapters(wgpu::Backends::all()).await;
        if adapters.is_empty() {
            let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
            adapters = instance.enumerate_adapters(wgpu::Backends::all()).await;
        }
        let adapter = choose_adapter(adapters).ok_or_else(|| ContextError::NoAdapter(String::new()))?;
        Self::from_adapter(adapter).await
    }

    /// Creates a device on wgpu's noop backend: validates shaders and pipelines, runs nothing.
    pub fn new_noop() -> Result<Self, ContextError> {
        pollster::block_on(async {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = wgpu::Backends::NOOP;
            desc.backend_options.noop = wgpu::NoopBackendOptions { enable: true, ..Default::default() };
            let instance = wgpu::Instance::new(desc);
            let adapter = instance
                .request_adapter(&wgpu::RequestAdapterOptions::default())
                .await
                .map_err(|e| ContextError::NoAdapter(format!(" (noop: {e})")))?;
            Self::from_adapter(adapter).await
        })
    }

    async fn from_adapter(adapter: wgpu::Adapter) -> Result<Self, ContextError> {
        let info = adapter.get_info();
        let (device, queue) = adapter
            .request_device(&device_descriptor(&adapter))
            .await
            .map_err(|e| ContextError::Device { adapter: info.name.clone(), message: e.to_string() })?;
        log::info!(
            "GPU adapter: {} ({:?}, {:?}, driver {} {})",
            info.name,
            info.backend,
            info.device_type,
            info.driver,
            info.driver_info
        );
        Ok(Self { adapter: Arc::new(adapter), device, queue, info })
    }

    /// Logs uncaptured wgpu errors instead of panicking (interactive and CLI use; tests keep
    /// wgpu's default, which panics, so validation errors fail them).
    pub fn log_errors(&self) {
        log_device_errors(&self.device);
    }

    /// Whether GPU timestamps are available.
    pub fn has_timestamps(&self) -> bool {
        self.device.features().contains(wgpu::Features::TIMESTAMP_QUERY)
    }

    /// One line describing the adapter.
    pub fn describe(&self) -> String {
        format!("{} ({:?}, {:?})", self.info.name, self.info.backend, self.info.device_type)
    }
}

/// The device descriptor used everywhere (also by the editor's eframe setup): the wanted
/// optional features the adapter has, and the adapter's real limits.
pub fn device_descriptor(adapter: &wgpu::Adapter) -> wgpu::DeviceDescriptor<'static> {
    wgpu::DeviceDescriptor {
        label: Some("bouncelab device"),
        required_features: adapter.features() & wanted_features(),
        required_limits: adapter.limits(),
        ..Default::default()
    }
}

fn rank(t: wgpu::DeviceType) -> u8 {
    match t {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    }
}

fn choose_adapter(mut adapters: Vec<wgpu::Adapter>) -> Option<wgpu::Adapter> {
    let forced = std::env::var("BOUNCELAB_ADAPTER").or_else(|_| std::env::var("WGPU_ADAPTER_NAME")).ok();
    if let Some(want) = forced.map(|s| s.to_lowercase()) {
        let pos = adapters.iter().position(|a| {
            let info = a.get_info();
            (want == "cpu" && info.device_type == wgpu::DeviceType::Cpu) || info.name.to_lowercase().contains(&want)
        });
        match pos {
            Some(i) => return Some(adapters.swap_remove(i)),
            None => log::warn!("no adapter matches {want:?}; choosing automatically"),
        }
    }
    // Hardware first; among equals prefer Vulkan/Metal/DX12 over GL.
    adapters.sort_by_key(|a| {
        let info = a.get_info();
        (rank(info.device_type), u8::from(info.backend == wgpu::Backend::Gl))
    });
    adapters.into_iter().next()
}

/// Routes uncaptured errors of `device` to the log.
pub fn log_device_errors(device: &wgpu::Device) {
    device.on_uncaptured_error(std::sync::Arc::new(|e| log::error!("wgpu: {e}")));
}
