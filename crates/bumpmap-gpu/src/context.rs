//! The adapter, device and queue, and what wgpu reports outside a call's return value: a lost
//! device (its callback) and errors no scope caught (the uncaptured-error handler). Both are
//! recorded here and turned into [`GpuError`]s at the next check, never into panics.

use std::sync::{Arc, Mutex};

use crate::error::GpuError;

/// An open device with its fault records.
pub struct Context {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter says of itself.
    pub info: wgpu::AdapterInfo,
    faults: Arc<Mutex<Faults>>,
    /// The adapter, and the instance it came from: a window's surface is made from them.
    pub(crate) adapter: wgpu::Adapter,
    pub(crate) instance: wgpu::Instance,
}

#[derive(Default)]
struct Faults {
    lost: Option<String>,
    uncaptured: Option<String>,
}

impl Context {
    /// Opens the first adapter wgpu offers (honouring `WGPU_BACKEND`, `WGPU_ADAPTER_NAME` and
    /// `WGPU_POWER_PREF`) with its own limits.
    pub fn new() -> Result<Self, GpuError> {
        // A browser's main thread may not wait (pollster's condvar panics there): the web gets
        // the refusal, and `Auto` the CPU, until the backend opens asynchronously.
        if cfg!(target_arch = "wasm32") {
            return Err(GpuError::NoAdapter(
                "the GPU backend waits on its device, which a web page may not do; it does not open on the web yet"
                    .into(),
            ));
        }
        pollster::block_on(Self::open())
    }

    async fn open() -> Result<Self, GpuError> {
        // Without WGPU_BACKEND: the primary backends (Vulkan, Metal, DX12) first, and GL only
        // if none has an adapter. Loading the GL backend loads libEGL, whose exit-time
        // destructors race with threads still ending (a "double free" abort about once in a
        // hundred runs on Mesa 25) — a process that never needed GL should not carry it.
        let tries = match wgpu::Backends::from_env() {
            Some(chosen) => vec![chosen],
            None => vec![wgpu::Backends::PRIMARY, wgpu::Backends::GL],
        };
        let mut last = None;
        for backends in tries {
            let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
            desc.backends = backends;
            desc.flags = wgpu::InstanceFlags::from_build_config().with_env();
            let instance = wgpu::Instance::new(desc);
            match wgpu::util::initialize_adapter_from_env_or_default(&instance, None).await {
                Ok(adapter) => return Self::with_adapter(instance, adapter).await,
                Err(e) => last = Some(e.to_string()),
            }
        }
        Err(GpuError::NoAdapter(last.unwrap_or_default()))
    }

    async fn with_adapter(instance: wgpu::Instance, adapter: wgpu::Adapter) -> Result<Self, GpuError> {
        let info = adapter.get_info();
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("bumpmap"),
                required_features: wgpu::Features::empty(),
                required_limits: adapter.limits(),
                experimental_features: wgpu::ExperimentalFeatures::disabled(),
                memory_hints: wgpu::MemoryHints::Performance,
                trace: wgpu::Trace::Off,
            })
            .await
            .map_err(|e| GpuError::RequestDevice(e.to_string()))?;
        let faults = Arc::new(Mutex::new(Faults::default()));
        let f = faults.clone();
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            let mut f = f.lock().unwrap_or_else(|p| p.into_inner());
            f.uncaptured.get_or_insert_with(|| e.to_string());
        }));
        let f = faults.clone();
        device.set_device_lost_callback(move |reason, message| {
            let mut f = f.lock().unwrap_or_else(|p| p.into_inner());
            f.lost = Some(if message.is_empty() { format!("{reason:?}") } else { format!("{reason:?}: {message}") });
        });
        Ok(Self { device, queue, info, faults, adapter, instance })
    }

    /// The adapter's largest 2D texture side.
    pub fn max_texture_side(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// Fails with what went wrong since the last check: a lost device first, then an error
    /// no scope caught (which is then cleared).
    pub fn check(&self) -> Result<(), GpuError> {
        let mut f = self.faults.lock().unwrap_or_else(|p| p.into_inner());
        if let Some(lost) = &f.lost {
            return Err(GpuError::DeviceLost(lost.clone()));
        }
        match f.uncaptured.take() {
            Some(e) => Err(GpuError::Wgpu(e)),
            None => Ok(()),
        }
    }

    /// Destroys the device, as a driver reset would: every later call fails with
    /// [`GpuError::DeviceLost`]. For tests of that path.
    pub fn lose_device(&self) {
        self.device.destroy();
        let _ = self.device.poll(wgpu::PollType::wait_indefinitely());
    }
}
