//! Headless GPU context: adapter selection, device creation with the features obscura uses when
//! the adapter has them, and validation errors turned into `Result`s instead of panics.

mod memo;
/// Layouts made once per device (`memo`), for `bindings`.
pub(crate) use memo::{
    bind_group_layout as kept_bind_group_layout, pipeline_layout as kept_pipeline_layout,
};
mod profiler;
mod readback;
pub mod zero_fill;

pub use profiler::{FrameFragments, FrameTimings, PassProfiler};
pub use readback::{
    read_buffer, read_buffer_async, read_buffer_copy, read_texture_bytes, read_texture_bytes_async,
    read_texture_f32, read_texture_f32_async, read_texture_layer_bytes, read_texture_rgba8,
};

use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// Where the GPU context comes from.
#[derive(Clone, Debug, Default)]
pub struct GpuOptions {
    /// Pick the first adapter whose name contains this (case-insensitive).
    pub adapter: Option<String>,
    /// Restrict to one backend (`vulkan`, `metal`, `dx12`, `gl`). Falls back to the
    /// `OBSCURA_BACKEND` environment variable.
    pub backend: Option<String>,
    /// Pick the N-th (from 0) of the adapters [`Gpu::all`] would use, in PCI bus order: the
    /// order in which `nvidia-smi`, NVML and so Ray's and CUDA's (with
    /// `CUDA_DEVICE_ORDER=PCI_BUS_ID`) GPU ids count a host's GPUs. It is how a Ray task given GPU
    /// id N finds that GPU among the Vulkan adapters, which `CUDA_VISIBLE_DEVICES` does not
    /// narrow.
    pub ordinal: Option<usize>,
}

/// What can go wrong with the GPU, each message saying what to do about it.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter at all, or none left by the adapter name and backend asked for.
    #[error(
        "no GPU adapter found{filter}. obscura needs Vulkan, Metal or DX12; on a machine without a GPU \
         install Mesa's software Vulkan driver (Debian/Ubuntu: `sudo apt-get install mesa-vulkan-drivers`)"
    )]
    NoAdapter {
        /// What narrowed the search, for the message (` matching 'x' on backend 'y'`; empty
        /// when nothing did).
        filter: String,
    },
    /// Adapters exist, but none whose name contains [`GpuOptions::adapter`].
    #[error(
        "no GPU adapter matching '{filter}'; the adapters here are: {}: pick one by a part of its name",
        available.join("; ")
    )]
    NoMatchingAdapter {
        /// The adapter name asked for.
        filter: String,
        /// Every adapter found, as `name (backend)`.
        available: Vec<String>,
    },
    /// [`GpuOptions::ordinal`] past the GPUs found.
    #[error(
        "GPU {ordinal} was asked for (counted from 0, in PCI bus order), but this machine has \
         {} such adapter(s): {}: ask for one of those, or check that the GPU's Vulkan driver is \
         installed on this node",
        available.len(),
        available.join("; ")
    )]
    NoSuchOrdinal {
        /// The ordinal asked for.
        ordinal: usize,
        /// The GPUs there are, in PCI bus order, as `name (bus id)` (the name alone where the
        /// driver reports no bus id).
        available: Vec<String>,
    },
    /// A backend name (`--backend`, `OBSCURA_BACKEND`) that is not vulkan, metal, dx12 or gl.
    #[error("unknown backend '{0}': use vulkan, metal, dx12 or gl")]
    UnknownBackend(String),
    /// The adapter refused to create a device.
    #[error("could not create a device on '{adapter}': {source}")]
    Device {
        /// The adapter's name.
        adapter: String,
        /// wgpu's error.
        source: wgpu::RequestDeviceError,
    },
    /// An adapter on wgpu's GL backend, whose shaders and formats obscura's passes do not fit
    /// ([`Gpu::check_backend`]).
    #[error(
        "'{adapter}' runs on wgpu's GL backend, where obscura's passes cannot run (its GLSL has no \
         textureLoad of depth textures, and R32Float is no render target there): use a Vulkan, \
         Metal or DX12 adapter (`obscura info` lists them; on Linux install your GPU's Vulkan \
         driver, or Mesa's software one: `sudo apt-get install mesa-vulkan-drivers`)"
    )]
    UnsupportedBackend {
        /// The adapter's name.
        adapter: String,
    },
    /// A storage buffer larger than the device binds or makes ([`check_storage_size`]), found
    /// before the buffer is made. [`crate::Renderer`] adds the image size and technique.
    #[error(
        "the {buffer} buffer needs {} MiB ({bytes} bytes), over this device's {limit_name} of {} \
         MiB ({limit} bytes)",
        mib(*bytes),
        mib(*limit)
    )]
    BufferTooLarge {
        /// The buffer's label (`occlusion pyramid`, `two-phase work list`, …).
        buffer: &'static str,
        /// The bytes it needs.
        bytes: u64,
        /// The limit it exceeds: `max_storage_buffer_binding_size` or `max_buffer_size`.
        limit_name: &'static str,
        /// That limit's value on this device, bytes.
        limit: u64,
    },
    /// wgpu validation errors raised since the last check ([`Gpu::check_errors`]), one a line.
    #[error("GPU validation error: {0}")]
    Validation(String),
    /// Anything else: an adapter limit or missing feature, a failed poll or buffer mapping.
    #[error("GPU error: {0}")]
    Other(String),
}

/// Bytes in MiB, rounded up, for messages.
fn mib(bytes: u64) -> u64 {
    bytes.div_ceil(1 << 20)
}

/// A storage buffer of `bytes` named `buffer` fits one binding and one buffer of a device with
/// `limits`; else [`GpuError::BufferTooLarge`]. Checked before the buffer is made: wgpu would
/// make it and report each bind group over it as a validation error of its own, long after
/// (issue 62: `render --size 7680x4320` on lavapipe's 128 MiB printed three).
pub fn check_storage_size(
    limits: &wgpu::Limits,
    buffer: &'static str,
    bytes: u64,
) -> Result<(), GpuError> {
    let too_large = |limit_name, limit| GpuError::BufferTooLarge {
        buffer,
        bytes,
        limit_name,
        limit,
    };
    if bytes > limits.max_storage_buffer_binding_size {
        return Err(too_large(
            "max_storage_buffer_binding_size",
            limits.max_storage_buffer_binding_size,
        ));
    }
    if bytes > limits.max_buffer_size {
        return Err(too_large("max_buffer_size", limits.max_buffer_size));
    }
    Ok(())
}

/// Adapter facts worth printing (`obscura info`) and recording next to benchmark numbers.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AdapterSummary {
    /// The adapter's name, as the driver reports it.
    pub name: String,
    /// wgpu's backend, `Debug`-formatted (`Vulkan`, `Metal`, `Dx12`, `Gl`).
    pub backend: String,
    /// `DiscreteGpu`, `IntegratedGpu`, `VirtualGpu`, `Cpu` (software, e.g. lavapipe) or `Other`.
    pub device_type: String,
    /// The driver's name (may be empty).
    pub driver: String,
    /// The driver's version or other details (may be empty).
    pub driver_info: String,
    /// Backend-specific vendor id, generally the PCI one (0x10de NVIDIA, 0x1002 AMD, 0x8086 Intel).
    pub vendor: u32,
    /// Backend-specific device id, generally the PCI one.
    pub device: u32,
    /// Timestamp queries are enabled: per-pass GPU times ([`PassProfiler`]) work.
    pub timestamp_queries: bool,
    /// Pipeline statistics queries (bench counts the fragments of each raster pass).
    pub pipeline_statistics: bool,
    /// Largest width or height of a 2D texture, pixels: bounds the framebuffer, guard band
    /// included.
    pub max_texture_dimension_2d: u32,
    /// Most layers of a texture array (the scene's base-colour textures take one each).
    pub max_texture_array_layers: u32,
    /// Largest storage buffer binding, bytes (bounds the scene's vertex and triangle buffers).
    pub max_storage_buffer_binding_size: u64,
    /// Largest compute workgroup size in x, y, z.
    pub max_compute_workgroup_size: [u32; 3],
    /// Most invocations in one compute workgroup.
    pub max_compute_invocations_per_workgroup: u32,
    /// MSAA sample counts a depth texture (`Depth32Float`) supports on this adapter.
    pub depth_msaa_sample_counts: Vec<u32>,
}

/// The device, its queue and what we know about the adapter. A cheap handle (wgpu's objects are
/// reference-counted): clones share the device, so a renderer, a viewer or a Python object can
/// each own one.
#[derive(Clone)]
pub struct Gpu {
    /// The adapter the device was created on.
    pub adapter: wgpu::Adapter,
    /// The device. [`Gpu::new`] creates it with the adapter's limits and those of the features
    /// obscura uses that the adapter has.
    pub device: wgpu::Device,
    /// The device's queue.
    pub queue: wgpu::Queue,
    /// What the adapter is and can do, read once at creation.
    pub summary: AdapterSummary,
    errors: Arc<Mutex<Vec<String>>>,
    /// What the device keeps for every renderer made on it (`memo`), released with the last
    /// clone of this `Gpu`.
    kept: Arc<memo::Kept>,
}

/// Backends from a name (`OBSCURA_BACKEND` / `--backend`).
fn parse_backend(name: &str) -> Result<wgpu::Backends, GpuError> {
    match name.to_ascii_lowercase().as_str() {
        "vulkan" | "vk" => Ok(wgpu::Backends::VULKAN),
        "metal" => Ok(wgpu::Backends::METAL),
        "dx12" | "d3d12" => Ok(wgpu::Backends::DX12),
        "gl" | "gles" | "opengl" => Ok(wgpu::Backends::GL),
        _ => Err(GpuError::UnknownBackend(name.to_string())),
    }
}

/// Discrete GPUs first, then integrated, virtual, and software (lavapipe) last; GL after others
/// because its timestamp and compute support is weaker.
fn adapter_rank(info: &wgpu::AdapterInfo) -> u32 {
    let device = match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Other => 3,
        wgpu::DeviceType::Cpu => 4,
    };
    let backend = u32::from(info.backend == wgpu::Backend::Gl);
    backend * 10 + device
}

/// `adapters` (best first, [`adapter_rank`]) narrowed to the device type and backend of the
/// first, in PCI bus order ([`bus_order`]).
fn same_kind_in_bus_order(adapters: Vec<wgpu::Adapter>) -> Vec<wgpu::Adapter> {
    let first = adapters[0].get_info();
    let mut same: Vec<wgpu::Adapter> = adapters
        .into_iter()
        .filter(|a| {
            let info = a.get_info();
            info.device_type == first.device_type && info.backend == first.backend
        })
        .collect();
    let ids: Vec<String> = same
        .iter()
        .map(|a| a.get_info().device_pci_bus_id)
        .collect();
    let order = bus_order(&ids);
    let mut slots: Vec<Option<wgpu::Adapter>> = same.drain(..).map(Some).collect();
    order
        .into_iter()
        .map(|i| slots[i].take().expect("a permutation"))
        .collect()
}

/// The order of adapters by their PCI bus ids (`domain:bus:device.function`, compared as
/// numbers, so `0000:1b:00.0` < `0000:9a:00.0` < `0001:00:00.0`), where every adapter reports
/// one; else their given order (an adapter without PCI bus information: a software or virtual
/// one, a driver without `VK_EXT_pci_bus_info`). A permutation of `0..ids.len()`.
fn bus_order(ids: &[String]) -> Vec<usize> {
    let keys: Option<Vec<Vec<u64>>> = ids.iter().map(|id| parse_pci_bus_id(id)).collect();
    let mut order: Vec<usize> = (0..ids.len()).collect();
    if let Some(keys) = keys {
        order.sort_by(|&a, &b| keys[a].cmp(&keys[b]));
    }
    order
}

/// `domain:bus:device.function` (hexadecimal fields, any width: Vulkan's `0000:1b:00.0`,
/// nvidia-smi's `00000000:1B:00.0`) as numbers; `None` if it is not one.
fn parse_pci_bus_id(id: &str) -> Option<Vec<u64>> {
    let fields: Vec<&str> = id.split([':', '.']).collect();
    if fields.len() != 4 {
        return None;
    }
    fields
        .iter()
        .map(|f| u64::from_str_radix(f, 16).ok())
        .collect()
}

/// Mesa's Vulkan window-system layer prints `XDG_RUNTIME_DIR is invalid or not set in the
/// environment` (twice: once per instance obscura probes) when the variable is unset or empty
/// (headless machines, containers, CI), which reads as an error although obscura opens no
/// window. This gives it a private directory (mode 0700, as the variable requires) in that case;
/// a set one is left alone, and any real error still prints. [`Gpu::new`] calls it, once, before
/// it makes a wgpu instance, so every user of the library has it; a program with threads of its
/// own that read the environment should call it first thing in `main` instead (it sets an
/// environment variable, which is not safe while another thread reads the environment).
pub fn quiet_headless_vulkan() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // Set and not empty: the user's (an empty value is as invalid to Mesa as none).
        if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|v| !v.is_empty()) {
            return;
        }
        let user = std::env::var("USER").unwrap_or_else(|_| "user".into());
        let dir = std::env::temp_dir().join(format!("obscura-runtime-{user}"));
        if std::fs::create_dir_all(&dir).is_err() {
            return;
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            if std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700)).is_err() {
                return;
            }
        }
        std::env::set_var("XDG_RUNTIME_DIR", &dir);
    });
}

impl Gpu {
    /// Pick an adapter (see [`GpuOptions`]) and create a device. Quiets Mesa's complaint about
    /// an unset `XDG_RUNTIME_DIR` first ([`quiet_headless_vulkan`]).
    pub fn new(options: &GpuOptions) -> Result<Self, GpuError> {
        let adapters = Self::adapters(options)?;
        let adapter = match options.ordinal {
            None => adapters.into_iter().next(),
            Some(ordinal) => {
                let mut gpus = same_kind_in_bus_order(adapters);
                if ordinal >= gpus.len() {
                    let available = gpus
                        .iter()
                        .map(|a| {
                            let info = a.get_info();
                            match info.device_pci_bus_id.as_str() {
                                "" => info.name,
                                bus => format!("{} ({bus})", info.name),
                            }
                        })
                        .collect();
                    return Err(GpuError::NoSuchOrdinal { ordinal, available });
                }
                Some(gpus.swap_remove(ordinal))
            }
        };
        Self::from_adapter(adapter.expect("adapters() returns at least one"))
    }

    /// A device on every adapter of the kind [`Gpu::new`] would pick (the same device type
    /// and backend as the best ranked one, after `options`' filters), in PCI bus order: the 8
    /// GPUs of an 8-GPU host, but not the software rasteriser beside them. The dataset runner's
    /// local executor gives one to each of its workers. At least one, or an error as for
    /// [`Gpu::new`]. `options.ordinal` is not applied here.
    pub fn all(options: &GpuOptions) -> Result<Vec<Self>, GpuError> {
        same_kind_in_bus_order(Self::adapters(options)?)
            .into_iter()
            .map(Self::from_adapter)
            .collect()
    }

    /// The adapters `options` allow, best first ([`adapter_rank`]); never empty (an error says
    /// what was asked for and what exists).
    fn adapters(options: &GpuOptions) -> Result<Vec<wgpu::Adapter>, GpuError> {
        quiet_headless_vulkan();
        let backend_name = options.backend.clone().or_else(|| {
            std::env::var("OBSCURA_BACKEND")
                .ok()
                .filter(|s| !s.is_empty())
        });
        let forced = backend_name.as_deref().map(parse_backend).transpose()?;
        // GL only when asked for or when nothing else exists: its compute and timestamp support is
        // weaker, and probing EGL on a headless machine prints noise.
        let mut adapters = Vec::new();
        for backends in forced.map_or(vec![wgpu::Backends::PRIMARY, wgpu::Backends::GL], |b| {
            vec![b]
        }) {
            let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
                backends,
                flags: wgpu::InstanceFlags::from_env_or_default(),
                ..wgpu::InstanceDescriptor::new_without_display_handle()
            });
            adapters = pollster::block_on(instance.enumerate_adapters(backends));
            if !adapters.is_empty() {
                break;
            }
        }
        if let Some(filter) = &options.adapter {
            let needle = filter.to_ascii_lowercase();
            let available: Vec<String> = adapters
                .iter()
                .map(|a| {
                    let info = a.get_info();
                    format!("{} ({:?})", info.name, info.backend)
                })
                .collect();
            adapters.retain(|a| a.get_info().name.to_ascii_lowercase().contains(&needle));
            if adapters.is_empty() && !available.is_empty() {
                return Err(GpuError::NoMatchingAdapter {
                    filter: filter.clone(),
                    available,
                });
            }
        }
        adapters.sort_by_key(|a| adapter_rank(&a.get_info()));
        if adapters.is_empty() {
            let mut filter = String::new();
            if let Some(a) = &options.adapter {
                filter += &format!(" matching '{a}'");
            }
            if let Some(b) = &backend_name {
                filter += &format!(" on backend '{b}'");
            }
            return Err(GpuError::NoAdapter { filter });
        }
        Ok(adapters)
    }

    fn from_adapter(adapter: wgpu::Adapter) -> Result<Self, GpuError> {
        let limits = adapter.limits();
        pollster::block_on(Self::from_adapter_async(adapter, limits))
    }

    /// A device on `adapter` with the features obscura uses that it has and `limits` (the
    /// adapter's own, as [`Gpu::new`] asks for, or fewer: a web page may ask for WebGPU's
    /// defaults, `wgpu::Limits::default()`, to see what runs on every browser). Async because a
    /// browser creates devices asynchronously (it cannot be waited for there); native callers
    /// may block on it.
    pub async fn from_adapter_async(
        adapter: wgpu::Adapter,
        limits: wgpu::Limits,
    ) -> Result<Self, GpuError> {
        let info = adapter.get_info();
        let features = adapter.features() & WANTED_FEATURES;
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("obscura"),
                required_features: features,
                required_limits: limits,
                ..Default::default()
            })
            .await
            .map_err(|source| GpuError::Device {
                adapter: info.name.clone(),
                source,
            })?;
        Ok(Self::from_device(adapter, device, queue))
    }

    /// Wrap a device the caller made (an engine's), with its adapter and queue. obscura uses the
    /// features the device has: without `TIMESTAMP_QUERY` there are no pass timings, without
    /// `SHADER_EARLY_DEPTH_TEST` the stochastic depth map is the same but slower. Validation
    /// errors the device does not capture are collected for [`Gpu::check_errors`]: this installs
    /// the device's uncaptured-error handler.
    pub fn from_device(adapter: wgpu::Adapter, device: wgpu::Device, queue: wgpu::Queue) -> Self {
        let gpu = Self::sharing_device(adapter, device, queue);
        let (sink, count) = (gpu.errors.clone(), gpu.kept.errors_raised());
        gpu.device
            .on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
                count.fetch_add(1, Ordering::SeqCst);
                sink.lock().unwrap().push(e.to_string());
            }));
        gpu
    }

    /// Wrap a device whose uncaptured-error handler belongs to the engine (Bevy's render
    /// recovery installs one): unlike [`Self::from_device`] this leaves the handler alone, so
    /// validation errors of obscura's passes reach the engine, and [`Self::check_errors`] and
    /// [`Self::finish`] report none. Catch set-up errors with an error scope instead
    /// (`device.push_error_scope`), as `bevy_obscura` does.
    pub fn sharing_device(
        adapter: wgpu::Adapter,
        device: wgpu::Device,
        queue: wgpu::Queue,
    ) -> Self {
        let info = adapter.get_info();
        let features = device.features();
        let limits = device.limits();
        let errors = Arc::new(Mutex::new(Vec::new()));
        let errors_raised = Arc::new(AtomicU64::new(0));
        // On wasm32 wgpu's handles are neither Send nor Sync (and so neither is `Gpu`), and the
        // table stays empty there (`memo`): the lint's concern does not arise.
        #[allow(clippy::arc_with_non_send_sync)]
        let kept = Arc::new(memo::Kept::new(&device, errors_raised));
        let depth_msaa_sample_counts = {
            let f = adapter.get_texture_format_features(wgpu::TextureFormat::Depth32Float);
            [1, 2, 4, 8, 16]
                .into_iter()
                .filter(|&n| f.flags.sample_count_supported(n))
                .collect()
        };
        let summary = AdapterSummary {
            name: info.name.clone(),
            backend: format!("{:?}", info.backend),
            device_type: format!("{:?}", info.device_type),
            driver: info.driver.clone(),
            driver_info: info.driver_info.clone(),
            vendor: info.vendor,
            device: info.device,
            timestamp_queries: features.contains(wgpu::Features::TIMESTAMP_QUERY),
            pipeline_statistics: features.contains(wgpu::Features::PIPELINE_STATISTICS_QUERY),
            max_texture_dimension_2d: limits.max_texture_dimension_2d,
            max_texture_array_layers: limits.max_texture_array_layers,
            max_storage_buffer_binding_size: limits.max_storage_buffer_binding_size,
            max_compute_workgroup_size: [
                limits.max_compute_workgroup_size_x,
                limits.max_compute_workgroup_size_y,
                limits.max_compute_workgroup_size_z,
            ],
            max_compute_invocations_per_workgroup: limits.max_compute_invocations_per_workgroup,
            depth_msaa_sample_counts,
        };
        Self {
            adapter,
            device,
            queue,
            summary,
            errors,
            kept,
        }
    }

    /// Whether obscura's passes can run on this adapter's backend: not on wgpu's GL backend
    /// (measured on Mesa's llvmpipe, OpenGL 4.5: naga's GLSL has no `textureLoad` of depth
    /// textures, and wgpu's downlevel rules refuse `R32Float` render targets), so
    /// [`crate::Renderer::new`] and [`crate::AmbientOcclusion::new`] refuse it with a message
    /// saying what to use instead, rather than a wgpu validation error. `obscura info` still
    /// describes a GL adapter.
    pub fn check_backend(&self) -> Result<(), GpuError> {
        backend_supported(&self.summary.name, self.adapter.get_info().backend)
    }

    /// Opens this device's table of shader modules, layouts and compute pipelines (`memo`) on
    /// this thread until the scope is dropped: what a constructor of renderers or passes makes
    /// inside it that an earlier one on this `Gpu` made already is reused instead of compiled
    /// again.
    /// Drops the shader modules, layouts and pipelines this device keeps for its renderers
    /// (`gpu::memo`). Needed only with [`Self::sharing_device`]: there obscura does not see the
    /// device's errors, so a creation that raised one (caught by the caller's error scope) may
    /// have been kept; forget it before trying again.
    pub fn forget_kept(&self) {
        self.kept.forget();
    }

    pub(crate) fn keeping(&self) -> memo::Scope {
        memo::enter(&self.kept)
    }

    /// Wait for all submitted work, then report any validation error raised since the last check.
    pub fn finish(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Other(e.to_string()))?;
        self.check_errors()
    }

    /// Report (and clear) validation errors raised so far.
    pub fn check_errors(&self) -> Result<(), GpuError> {
        let mut errors = self.errors.lock().unwrap();
        if errors.is_empty() {
            Ok(())
        } else {
            // One message each: a resource made twice over the same limit (two bind groups of
            // one buffer, say) raises the same error twice.
            let mut distinct: Vec<&str> = Vec::new();
            for e in errors.iter() {
                if !distinct.contains(&e.as_str()) {
                    distinct.push(e);
                }
            }
            let message = distinct.join("\n");
            errors.clear();
            Err(GpuError::Validation(message))
        }
    }
}

/// A storage buffer holding `contents`. Empty contents (a scene without triangles or
/// vertices) still bind: an empty buffer is below every binding's minimum size, so it gets 256
/// zero bytes, more than any one element the shaders read.
pub fn storage_buffer_init(device: &wgpu::Device, label: &str, contents: &[u8]) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: if contents.is_empty() {
            &[0; 256]
        } else {
            contents
        },
        usage: wgpu::BufferUsages::STORAGE,
    })
}

/// The scene's storage buffers `(label, bytes)` fit a device with `limits` ([`check_storage_size`]);
/// else one error naming the scene, the buffer and the limit, with the fix (the scene's size is
/// at fault, not the image's).
pub fn check_scene_buffers(
    limits: &wgpu::Limits,
    scene: &str,
    buffers: &[(&'static str, u64)],
) -> Result<(), GpuError> {
    for &(buffer, bytes) in buffers {
        check_storage_size(limits, buffer, bytes).map_err(|e| {
            GpuError::Other(format!(
                "scene '{scene}' is too large for this adapter: {e}; simplify the scene or split \
                 it, or use an adapter with larger storage buffers"
            ))
        })?;
    }
    Ok(())
}

/// A compute pipeline from WGSL source with entry point `main`, an automatic layout and values
/// for the shader's `override` constants.
pub fn compute_pipeline_with(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    let module = shader_module(device, label, source);
    pipeline_from_module(device, label, &module, constants, None)
}

/// A shader module from WGSL `source` with wgpu's bounds checks but without its loop bounding:
/// wgpu gives every loop a counter of its own, so that a loop the driver might prove infinite
/// cannot be compiled into undefined behaviour. On an H200 that counter cost the AO passes 4–20 %
/// (`rt-vao` 20 %, `sd-vao` 18 %, `sd-gtao-vb` 12 %, `gtao-vb` 9 %, `vao` 6 %) and the occlusion
/// pyramid 16 %; the bounds checks cost nothing measurable (BENCHMARKS.md, 2026-12-04).
///
/// Every loop in obscura's compute shaders ends: `for` loops count to a bound fixed before they
/// start (settings validated on the CPU, a BVH leaf's triangle count); the `while` loops over a
/// bit mask clear at least its lowest set bit each turn; the BVH walk (`common/bvh.wgsl`) enters
/// each node at most once, as every inner node's children come after it in the node array
/// (`bvh::wide::widen`, held by its tests), and its stack pops end at an empty stack.
pub fn shader_module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    let mut checks = wgpu::ShaderRuntimeChecks::checked();
    checks.force_loop_bounding = false;
    // SAFETY: bounds checks stay; every loop of the shaders given here ends (see above).
    unsafe { trusted_module(device, label, source, checks) }
}

/// The WGSL module `source` with all of wgpu's runtime checks (the raster passes').
pub fn checked_module(device: &wgpu::Device, label: &str, source: &str) -> wgpu::ShaderModule {
    dump_wgsl(label, source);
    memo::module(device, source, "all checks", || {
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        })
    })
}

/// With `OBSCURA_DUMP_WGSL=DIR` in the environment, write WGSL `source` to DIR, one file per
/// distinct source (named by its label and a hash of it): every module obscura makes passes
/// here ([`checked_module`], [`shader_module`]), so a run leaves the exact sources it compiled,
/// for `tools/wgsl-portability` to translate to Metal's and DirectX's shading languages. A
/// failed write is ignored: the dump must never change what the run does.
fn dump_wgsl(label: &str, source: &str) {
    let Some(dir) = std::env::var_os("OBSCURA_DUMP_WGSL") else {
        return;
    };
    let name: String = label
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let stem = format!("{name}-{:016x}", text_hash(source));
    LAST_DUMPED.with(|last| *last.borrow_mut() = Some((label.to_owned(), stem.clone())));
    let path = std::path::Path::new(&dir).join(format!("{stem}.wgsl"));
    if !path.exists() {
        dump_file(&path, source);
    }
}

thread_local! {
    /// The label and file stem of the module this thread dumped last: the pipeline made next
    /// with that label is made from it (every pipeline is made right after its module).
    static LAST_DUMPED: std::cell::RefCell<Option<(String, String)>> =
        const { std::cell::RefCell::new(None) };
}

/// With `OBSCURA_DUMP_WGSL=DIR`, write the `override` constants a compute pipeline was made with
/// beside its module's WGSL: `STEM.CONSTANTS_HASH.constants`, one `NAME=VALUE` line each (and
/// `#entry=NAME` for an entry point other than `main`), so that a tool can compile exactly what
/// the pipeline ran (`tools/pipeline-stats`: the driver's register count and other statistics).
/// `label` is its module's label; nothing is written for a pipeline whose module this thread did
/// not dump last.
pub(crate) fn dump_constants(label: &str, entry: &str, constants: &[(&str, f64)]) {
    let Some(dir) = std::env::var_os("OBSCURA_DUMP_WGSL") else {
        return;
    };
    let Some(stem) = LAST_DUMPED.with(|last| match &*last.borrow() {
        Some((l, stem)) if l == label => Some(stem.clone()),
        _ => None,
    }) else {
        return;
    };
    let mut text: String = constants
        .iter()
        .map(|(name, value)| format!("{name}={value}\n"))
        .collect();
    if entry != "main" {
        text.push_str(&format!("#entry={entry}\n"));
    }
    let path =
        std::path::Path::new(&dir).join(format!("{stem}.{:016x}.constants", text_hash(&text)));
    if !path.exists() {
        dump_file(&path, &text);
    }
}

/// The hash that names a dumped file after its contents.
fn text_hash(text: &str) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut hasher);
    hasher.finish()
}

/// Writes `text` to `path` through a file of this call's own, then a rename: tests on several
/// threads may write the same file at once. A failed write is ignored (see [`dump_wgsl`]).
fn dump_file(path: &std::path::Path, text: &str) {
    static CALLS: AtomicU32 = AtomicU32::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let Some(dir) = path.parent() else {
        return;
    };
    let temporary = dir.join(format!(".{}-{call}.tmp", std::process::id()));
    let _ = std::fs::create_dir_all(dir)
        .and_then(|()| std::fs::write(&temporary, text))
        .and_then(|()| std::fs::rename(&temporary, path));
}

/// The WGSL module `source` with only the runtime `checks` given.
///
/// # Safety
/// What [`wgpu::ShaderRuntimeChecks`] asks of a shader for each check left out.
unsafe fn trusted_module(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    checks: wgpu::ShaderRuntimeChecks,
) -> wgpu::ShaderModule {
    dump_wgsl(label, source);
    let desc = wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    };
    memo::module(device, source, &format!("{checks:?}"), || {
        // SAFETY: forwarded to the caller.
        unsafe { device.create_shader_module_trusted(desc, checks) }
    })
}

/// [`compute_pipeline_with`] without the bounds checks wgpu adds to every array and texture access.
///
/// # Safety
/// Every index and texel coordinate the shader uses must be in range by construction, for every
/// input the caller can bind (the caller validates texture sizes before binding).
pub unsafe fn compute_pipeline_unchecked(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    constants: &[(&str, f64)],
) -> wgpu::ComputePipeline {
    // SAFETY: forwarded to the caller (see above).
    let module = unsafe {
        trusted_module(
            device,
            label,
            source,
            wgpu::ShaderRuntimeChecks::unchecked(),
        )
    };
    pipeline_from_module(device, label, &module, constants, None)
}

/// A compute pipeline with entry point `main` from `module`: with `layout`, or an automatic one.
pub(crate) fn pipeline_from_module(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    constants: &[(&str, f64)],
    layout: Option<&wgpu::PipelineLayout>,
) -> wgpu::ComputePipeline {
    entry_pipeline(device, label, module, "main", constants, layout)
}

/// [`pipeline_from_module`] at entry point `entry` (modules with several passes: the ray
/// budget's, the à-trous filter's).
pub(crate) fn entry_pipeline(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    entry: &str,
    constants: &[(&str, f64)],
    layout: Option<&wgpu::PipelineLayout>,
) -> wgpu::ComputePipeline {
    dump_constants(label, entry, constants);
    let key = memo::PipelineKey {
        module: module.clone(),
        entry: entry.to_owned(),
        constants: constants
            .iter()
            .map(|&(name, value)| (name.to_owned(), value.to_bits()))
            .collect(),
        layout: layout.cloned(),
    };
    memo::compute_pipeline(device, key, || {
        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout,
            module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                // Shaders that use workgroup memory write it before reading it.
                zero_initialize_workgroup_memory: false,
            },
            cache: None,
        })
    })
}

/// [`Gpu::check_backend`] for adapter `adapter` on `backend`.
fn backend_supported(adapter: &str, backend: wgpu::Backend) -> Result<(), GpuError> {
    if backend == wgpu::Backend::Gl {
        return Err(GpuError::UnsupportedBackend {
            adapter: adapter.to_owned(),
        });
    }
    Ok(())
}

/// The optional features obscura uses where the adapter has them (and [`Gpu::new`] requests):
/// pass timings, fragment counts, render targets of the formats WebGPU does not guarantee
/// (the G-buffer's `R32Float`), early tests for the stochastic depth map, 64-bit atomics for
/// the visibility pass.
pub const WANTED_FEATURES: wgpu::Features = wgpu::Features::TIMESTAMP_QUERY
    .union(wgpu::Features::PIPELINE_STATISTICS_QUERY)
    .union(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
    .union(wgpu::Features::SHADER_EARLY_DEPTH_TEST)
    .union(wgpu::Features::SHADER_INT64)
    .union(wgpu::Features::SHADER_INT64_ATOMIC_MIN_MAX);

/// A bind group for group 0 of `pipeline` with `resources` at bindings 0, 1, 2, … in order
/// (the raster, blur and query passes, whose layouts are automatic; the AO passes name their
/// bindings: [`crate::bindings::group`]).
pub fn bind_group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[wgpu::BindingResource],
) -> wgpu::BindGroup {
    let numbered: Vec<_> = (0..).zip(resources.iter().cloned()).collect();
    bind_group_at(device, label, layout, &numbered)
}

/// A bind group from `(binding, resource)` pairs.
pub fn bind_group_at(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[(u32, wgpu::BindingResource)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = resources
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: resource.clone(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// A 2D texture of the given size, format and usage.
pub fn texture_2d(
    device: &wgpu::Device,
    label: &str,
    width: u32,
    height: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scene's buffers (the G-buffer's and the BVH's) are checked in order; the first over a
    /// limit names the scene, the buffer and the fix.
    #[test]
    fn scene_buffers_over_a_limit_name_the_scene_and_the_buffer() {
        let limits = wgpu::Limits {
            max_storage_buffer_binding_size: 128 << 20,
            max_buffer_size: 256 << 20,
            ..wgpu::Limits::default()
        };
        let fits = [("bvh nodes", 128 << 20), ("bvh triangles", 1)];
        assert!(check_scene_buffers(&limits, "big", &fits).is_ok());
        let over = [("bvh nodes", 1), ("bvh triangles", (128 << 20) + 1)];
        let e = check_scene_buffers(&limits, "big", &over)
            .unwrap_err()
            .to_string();
        for needle in [
            "scene 'big'",
            "bvh triangles buffer",
            "129 MiB",
            "simplify the scene",
        ] {
            assert!(e.contains(needle), "{needle:?} not in: {e}");
        }
    }

    #[test]
    fn storage_buffers_over_either_limit_are_refused_with_both_numbers() {
        let limits = wgpu::Limits {
            max_storage_buffer_binding_size: 128 << 20,
            max_buffer_size: 256 << 20,
            ..wgpu::Limits::default()
        };
        assert!(check_storage_size(&limits, "occlusion pyramid", 128 << 20).is_ok());
        let e = check_storage_size(&limits, "occlusion pyramid", 211_100_672)
            .unwrap_err()
            .to_string();
        for needle in [
            "occlusion pyramid",
            "202 MiB",
            "211100672",
            "max_storage_buffer_binding_size of 128 MiB",
        ] {
            assert!(e.contains(needle), "{needle:?} not in: {e}");
        }
        let limits = wgpu::Limits {
            max_buffer_size: 64 << 20,
            ..limits
        };
        let e = check_storage_size(&limits, "two-phase pixels", 100 << 20).unwrap_err();
        assert!(e.to_string().contains("max_buffer_size of 64 MiB"), "{e}");
    }

    #[test]
    fn the_gl_backend_is_refused_with_what_to_use_instead() {
        let err = backend_supported("llvmpipe (LLVM 15.0.6, 256 bits)", wgpu::Backend::Gl)
            .unwrap_err()
            .to_string();
        for needle in [
            "'llvmpipe (LLVM 15.0.6, 256 bits)'",
            "GL backend",
            "Vulkan",
            "mesa-vulkan-drivers",
        ] {
            assert!(err.contains(needle), "{needle}: {err}");
        }
        for backend in [
            wgpu::Backend::Vulkan,
            wgpu::Backend::Metal,
            wgpu::Backend::Dx12,
            wgpu::Backend::BrowserWebGpu,
        ] {
            assert!(backend_supported("any", backend).is_ok(), "{backend:?}");
        }
    }

    #[test]
    fn adapters_are_ordered_by_pci_bus_as_nvidia_smi_counts_them() {
        let ids = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        // Numeric, not textual: bus 0x9a after 0x1b, domain before bus, any field width.
        let order = bus_order(&ids(&[
            "0000:9a:00.0",
            "0001:00:00.0",
            "0000:1b:00.0",
            "0000:1B:00.1",
        ]));
        assert_eq!(order, vec![2, 3, 0, 1]);
        assert_eq!(
            parse_pci_bus_id("00000000:1B:00.0"),
            parse_pci_bus_id("0000:1b:00.0")
        );
        // One adapter without a bus id (lavapipe reports none): enumeration order is kept.
        assert_eq!(
            bus_order(&ids(&["0000:9a:00.0", "", "0000:1b:00.0"])),
            vec![0, 1, 2]
        );
        assert_eq!(parse_pci_bus_id("not a bus"), None);
    }

    #[test]
    fn an_ordinal_past_the_gpus_names_the_ones_there() {
        let options = GpuOptions {
            ordinal: Some(7),
            ..Default::default()
        };
        let error = Gpu::new(&options)
            .err()
            .expect("no machine here has 8 GPUs");
        let text = error.to_string();
        assert!(
            matches!(error, GpuError::NoSuchOrdinal { ordinal: 7, .. }),
            "{text}"
        );
        assert!(text.contains("GPU 7 was asked for"), "{text}");
        // The adapter that is there (lavapipe on CI) is named.
        let first = Gpu::new(&GpuOptions::default()).unwrap();
        assert!(text.contains(&first.summary.name), "{text}");
        // Ordinal 0 is the adapter `new` picks by default.
        let zero = Gpu::new(&GpuOptions {
            ordinal: Some(0),
            ..Default::default()
        })
        .unwrap();
        assert_eq!(zero.summary.name, first.summary.name);
    }
}
