//! Instance, device selection, validation and the one compute queue.

use super::calibration::{self, Calibrator};
use super::creation_counts::{CreationCounters, CreationCounts};
use super::descriptor_pool_shelf::PoolShelf;
use super::device_info::{self, DeviceInfo};
use super::error::{VkError, VkResultExt};
use super::finished_frame::FinishedFrameKeeper;
use super::layer_extensions::{self, LeftOut};
use super::memory::GpuMemory;
use super::pipeline_cache::{CacheDevice, PipelineCache, PipelineCacheDir};
use super::pipeline_store::PipelineStore;
use super::validated_thread::ValidatedThreadClaim;
use super::validation::{self, ValidationLog};
use super::wait_report::WaitReporter;
use ash::vk;
use std::ffi::{CStr, CString};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

pub const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";
/// Environment variable that names the device (like `--device`).
pub const DEVICE_ENV: &str = "SWEEPLAB_DEVICE";
/// Environment variable that turns validation on (like `--validate`) when set to 1.
pub const VALIDATE_ENV: &str = "SWEEPLAB_VALIDATE";

#[derive(Clone, Debug, Default)]
pub struct ContextOptions {
    /// Device index or name substring; `None` picks the best (GPU before CPU).
    pub device: Option<String>,
    /// Khronos validation with synchronization validation, messages collected.
    pub validate: bool,
    /// With `validate`: best-practices checks too (`--validate=best-practices`,
    /// `SWEEPLAB_VALIDATE=best-practices`); the NVIDIA and AMD vendor checks
    /// come from [`BEST_PRACTICES_LAYER_ENABLES`], which the process sets.
    pub best_practices: bool,
    /// Where the driver's pipeline cache is kept between runs ([`super::pipeline_cache`]).
    pub pipeline_cache: PipelineCacheDir,
}

/// `VK_LAYER_ENABLES` for best-practices runs: the layer's best practices with
/// the NVIDIA and AMD vendor checks, and synchronization validation. Layers
/// before VK_EXT_layer_settings (1.3.239 here) take vendor checks this way
/// only; the binary sets it before creating the instance.
pub const BEST_PRACTICES_LAYER_ENABLES: &str = "VK_VALIDATION_FEATURE_ENABLE_BEST_PRACTICES_EXT:\
VALIDATION_CHECK_ENABLE_VENDOR_SPECIFIC_NVIDIA:VALIDATION_CHECK_ENABLE_VENDOR_SPECIFIC_AMD:\
VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT";

impl ContextOptions {
    /// Options with the environment overrides applied where the caller gave none.
    pub fn with_env(mut self) -> Self {
        if self.device.is_none() {
            self.device = std::env::var(DEVICE_ENV).ok().filter(|s| !s.trim().is_empty());
        }
        if !self.validate {
            let env = std::env::var(VALIDATE_ENV).unwrap_or_default();
            self.best_practices |= env.eq_ignore_ascii_case("best-practices");
            self.validate = env == "1" || env.eq_ignore_ascii_case("true") || self.best_practices;
        }
        self
    }
}

pub struct Context {
    pub entry: ash::Entry,
    pub instance: ash::Instance,
    debug_instance: Option<ash::ext::debug_utils::Instance>,
    messenger: vk::DebugUtilsMessengerEXT,
    validation: Option<ValidationLog>,
    pub physical_device: vk::PhysicalDevice,
    pub info: DeviceInfo,
    pub limits: vk::PhysicalDeviceLimits,
    pub device: ash::Device,
    /// Object names and command labels; present whenever VK_EXT_debug_utils is.
    pub debug_utils: Option<ash::ext::debug_utils::Device>,
    pub queue: vk::Queue,
    pub queue_family: u32,
    pub memory: Arc<GpuMemory>,
    /// shaderInt64 and shaderBufferInt64Atomics are enabled (the device has them).
    pub int64_atomics: bool,
    /// VK_KHR_push_descriptor, enabled where the device has it: the dispatch
    /// probe pushes a small set per block with it (lavapipe has it).
    pub push_descriptor: Option<ash::khr::push_descriptor::Device>,
    /// Reports on long waits for a submission ([`super::wait_report`]).
    wait_reporter: Mutex<Option<Arc<WaitReporter>>>,
    /// Specialization constants every pipeline gets beside its own: those a
    /// shared include declares (volume_fetch.glsl's filter), set by the layer
    /// that owns them before it creates pipelines.
    shared_specialization: Mutex<Vec<(u32, u32)>>,
    /// Device and host clocks read together, where the device can
    /// ([`super::calibration`]).
    pub calibrator: Option<Arc<Calibrator>>,
    /// The validation layer's header version (`1.3.239`), where validation is on.
    pub validation_layer: Option<String>,
    /// The device extensions enabled.
    pub device_extensions: Vec<String>,
    /// Device extensions left out because the validation layer would not know
    /// them ([`super::layer_extensions`]), each described.
    pub extensions_left_out: Vec<String>,
    /// The driver's pipeline cache, loaded from and saved to its file.
    pub pipeline_cache: PipelineCache,
    /// Pipelines compiled once and handed out again ([`super::pipeline_store`]).
    pub pipelines: PipelineStore,
    /// Descriptor pools handed on ([`super::descriptor_pool_shelf`]).
    pub descriptor_pools: Arc<PoolShelf>,
    /// The last `submit_and_wait` frame's command pool, kept until the next
    /// one has finished ([`super::finished_frame`]).
    pub finished_frame: FinishedFrameKeeper,
    /// What this context created so far ([`super::creation_counts`]).
    pub counters: CreationCounters,
    /// Held while a validated context lives ([`super::validated_thread`]);
    /// released after `drop` has destroyed the instance.
    _validated_thread: Option<ValidatedThreadClaim>,
}

struct Candidate {
    physical_device: vk::PhysicalDevice,
    info: DeviceInfo,
    queue_family: Option<u32>,
    api_version: u32,
    device_type: vk::PhysicalDeviceType,
}

/// The Vulkan loader, loaded once per process and never unloaded: each
/// context holding its own copy would dlopen and dlclose libvulkan (and with
/// it the layer and the driver) as contexts come and go on several threads.
fn load_entry() -> Result<ash::Entry, VkError> {
    static ENTRY: OnceLock<Result<ash::Entry, String>> = OnceLock::new();
    // SAFETY: loading libvulkan runs its initialisers; the OnceLock runs this once.
    let entry = ENTRY.get_or_init(|| unsafe { ash::Entry::load() }.map_err(|e| e.to_string()));
    entry.clone().map_err(VkError::Loader)
}

/// Held while an instance and its device are created or destroyed. Vulkan lets
/// threads do this at once, but loaders, layers and drivers keep process-wide
/// state in these calls, and concurrent creation is a known source of crashes
/// (Vulkan-Loader issue 200, wgpu issues 5930 and 10010); the suite creates
/// hundreds of contexts on two threads. Creation takes milliseconds, so
/// serializing it costs nothing measurable.
fn lifecycle_lock() -> MutexGuard<'static, ()> {
    static LIFECYCLE: Mutex<()> = Mutex::new(());
    // A panic while holding it leaves nothing half-done that the next caller reads.
    LIFECYCLE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The header version (`specVersion`) of layer `name`, where it is installed.
fn layer_version(entry: &ash::Entry, name: &CStr) -> Result<Option<u32>, VkError> {
    // SAFETY: plain enumeration call on a loaded entry.
    let layers = unsafe { entry.enumerate_instance_layer_properties() }.call("vkEnumerateInstanceLayerProperties")?;
    Ok(layers.iter().find(|l| l.layer_name_as_c_str() == Ok(name)).map(|l| l.spec_version))
}

/// The Khronos validation layer's header version where it is installed
/// (`sweeplab devices` prints it; a validated run's header too).
pub fn validation_layer_version() -> Result<Option<String>, VkError> {
    let entry = load_entry()?;
    Ok(layer_version(&entry, VALIDATION_LAYER)?.map(device_info::version_string))
}

fn has_instance_extension(entry: &ash::Entry, layer: Option<&CStr>, name: &CStr) -> Result<bool, VkError> {
    // SAFETY: plain enumeration call on a loaded entry.
    let exts = unsafe { entry.enumerate_instance_extension_properties(layer) }
        .call("vkEnumerateInstanceExtensionProperties")?;
    Ok(exts.iter().any(|e| e.extension_name_as_c_str().map(|n| n == name).unwrap_or(false)))
}

fn create_instance(
    entry: &ash::Entry,
    validate: bool,
    best_practices: bool,
    debug_utils: bool,
    surface_extensions: &[&CStr],
) -> Result<ash::Instance, VkError> {
    let app_name = CString::new("sweeplab").unwrap_or_default();
    let app = vk::ApplicationInfo::default()
        .application_name(&app_name)
        .engine_name(&app_name)
        .api_version(vk::API_VERSION_1_3);
    let mut layers = Vec::new();
    let mut extensions = Vec::new();
    if debug_utils {
        extensions.push(ash::ext::debug_utils::NAME.as_ptr());
    }
    for name in surface_extensions {
        if !has_instance_extension(entry, None, name)? {
            return Err(VkError::MissingExtension(name.to_string_lossy().into_owned()));
        }
        extensions.push(name.as_ptr());
    }
    let mut validation_features_ext = false;
    if validate {
        if layer_version(entry, VALIDATION_LAYER)?.is_none() {
            return Err(VkError::NoValidationLayer);
        }
        layers.push(VALIDATION_LAYER.as_ptr());
        if has_instance_extension(entry, Some(VALIDATION_LAYER), ash::ext::validation_features::NAME)? {
            extensions.push(ash::ext::validation_features::NAME.as_ptr());
            validation_features_ext = true;
        }
    }
    let sync_and_best_practices =
        [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION, vk::ValidationFeatureEnableEXT::BEST_PRACTICES];
    let enables = if best_practices { &sync_and_best_practices[..] } else { &sync_and_best_practices[..1] };
    let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(enables);
    let mut info = vk::InstanceCreateInfo::default()
        .application_info(&app)
        .enabled_layer_names(&layers)
        .enabled_extension_names(&extensions);
    if validation_features_ext {
        info = info.push_next(&mut features);
    }
    // SAFETY: every pointer in `info` refers to locals that outlive the call.
    unsafe { entry.create_instance(&info, None) }.call("vkCreateInstance")
}

/// The queue flags a context needs: compute, and graphics too for a window
/// (the viewer blits and draws its panel on the same queue).
fn queue_needs(window: bool) -> vk::QueueFlags {
    if window {
        vk::QueueFlags::COMPUTE | vk::QueueFlags::GRAPHICS
    } else {
        vk::QueueFlags::COMPUTE
    }
}

fn candidates(instance: &ash::Instance, window: bool) -> Result<Vec<Candidate>, VkError> {
    // SAFETY: instance is valid; enumeration has no other preconditions.
    let physical = unsafe { instance.enumerate_physical_devices() }.call("vkEnumeratePhysicalDevices")?;
    let mut out = Vec::new();
    for (index, pd) in physical.into_iter().enumerate() {
        let mut driver = vk::PhysicalDeviceDriverProperties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default().push_next(&mut driver);
        // SAFETY: pd comes from this instance; the chained struct lives on the stack.
        unsafe { instance.get_physical_device_properties2(pd, &mut props2) };
        let props = props2.properties;
        // SAFETY: pd comes from this instance.
        let families = unsafe { instance.get_physical_device_queue_family_properties(pd) };
        let queue_family = families.iter().position(|f| f.queue_flags.contains(queue_needs(window))).map(|i| i as u32);
        let valid_bits = queue_family.map(|q| families[q as usize].timestamp_valid_bits).unwrap_or(0);
        let info = DeviceInfo {
            index,
            name: props.device_name_as_c_str().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            device_type: device_info::type_name(props.device_type).to_string(),
            api_version: device_info::version_string(props.api_version),
            vendor_id: props.vendor_id,
            device_id: props.device_id,
            driver_version: device_info::driver_version_string(props.vendor_id, props.driver_version),
            driver_name: driver.driver_name_as_c_str().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            driver_info: driver.driver_info_as_c_str().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default(),
            timestamp_period_ns: props.limits.timestamp_period,
            timestamp_valid_bits: if props.limits.timestamp_compute_and_graphics == vk::TRUE || valid_bits > 0 {
                valid_bits
            } else {
                0
            },
        };
        out.push(Candidate {
            physical_device: pd,
            info,
            queue_family,
            api_version: props.api_version,
            device_type: props.device_type,
        });
    }
    Ok(out)
}

/// Lists the Vulkan devices without creating one.
pub fn list_devices() -> Result<Vec<DeviceInfo>, VkError> {
    let _lifecycle = lifecycle_lock();
    let entry = load_entry()?;
    let instance = create_instance(&entry, false, false, false, &[])?;
    let result = candidates(&instance, false).map(|c| c.into_iter().map(|c| c.info).collect());
    // SAFETY: no object created from this instance survives.
    unsafe { instance.destroy_instance(None) };
    result
}

impl Context {
    pub fn new(options: &ContextOptions) -> Result<Context, VkError> {
        Context::create(options, &[])
    }

    /// A context that can present to a window: `surface_extensions` are the
    /// instance extensions its surface needs (`ash_window` names them), and the
    /// device gets VK_KHR_swapchain. Headless contexts (`new`) have neither.
    pub fn for_window(options: &ContextOptions, surface_extensions: &[&CStr]) -> Result<Context, VkError> {
        if surface_extensions.is_empty() {
            return Err(VkError::Presentation("a window context needs its surface extensions".into()));
        }
        Context::create(options, surface_extensions)
    }

    fn create(options: &ContextOptions, surface_extensions: &[&CStr]) -> Result<Context, VkError> {
        // Before the lifecycle lock: a thread that waits here holds nothing the
        // claiming thread needs to drop its contexts.
        let validated_thread = options.validate.then(ValidatedThreadClaim::acquire);
        let _lifecycle = lifecycle_lock();
        let entry = load_entry()?;
        let layer = if options.validate { layer_version(&entry, VALIDATION_LAYER)? } else { None };
        let debug_utils_ext = has_instance_extension(&entry, None, ash::ext::debug_utils::NAME)? || options.validate;
        let instance =
            create_instance(&entry, options.validate, options.best_practices, debug_utils_ext, surface_extensions)?;

        let (debug_instance, messenger, validation) = if debug_utils_ext {
            let di = ash::ext::debug_utils::Instance::new(&entry, &instance);
            if options.validate {
                let log = ValidationLog::default();
                let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                    .message_severity(validation::reported_severities())
                    .message_type(
                        vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                            | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                            | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
                    )
                    .pfn_user_callback(Some(validation::messenger_callback))
                    .user_data(log.as_user_data());
                // SAFETY: the user data (the log's Arc) is kept in `self` until after the
                // messenger is destroyed in Drop.
                let messenger =
                    unsafe { di.create_debug_utils_messenger(&info, None) }.call("vkCreateDebugUtilsMessengerEXT")?;
                (Some(di), messenger, Some(log))
            } else {
                (Some(di), vk::DebugUtilsMessengerEXT::null(), None)
            }
        } else {
            (None, vk::DebugUtilsMessengerEXT::null(), None)
        };

        let cleanup_instance = |msg: VkError| {
            // SAFETY: only the messenger exists on this instance at this point.
            unsafe {
                if let Some(di) = &debug_instance {
                    if messenger != vk::DebugUtilsMessengerEXT::null() {
                        di.destroy_debug_utils_messenger(messenger, None);
                    }
                }
                instance.destroy_instance(None);
            }
            msg
        };

        let window = !surface_extensions.is_empty();
        let all = candidates(&instance, window).map_err(cleanup_instance)?;
        let chosen = match choose(&all, options.device.as_deref()) {
            Ok(c) => c,
            Err(e) => return Err(cleanup_instance(e)),
        };
        let cand = &all[chosen];
        let queue_family = match cand.queue_family {
            Some(q) => q,
            None => {
                return Err(cleanup_instance(VkError::MissingFeature {
                    device: cand.info.name.clone(),
                    missing: if window { "a queue with graphics and compute" } else { "a compute queue" }.into(),
                }))
            }
        };
        if cand.api_version < vk::API_VERSION_1_3 {
            return Err(cleanup_instance(VkError::MissingFeature {
                device: cand.info.name.clone(),
                missing: format!("Vulkan 1.3 (it reports {})", cand.info.api_version),
            }));
        }
        let swapchain = !surface_extensions.is_empty();
        let CreatedDevice { device, int64_atomics, calibration_ext, push_descriptor, enabled, left_out } =
            match create_device(&entry, &instance, cand, queue_family, swapchain, layer) {
                Ok(d) => d,
                Err(e) => return Err(cleanup_instance(e)),
            };
        // SAFETY: the family was requested with one queue at creation.
        let queue = unsafe { device.get_device_queue(queue_family, 0) };
        // SAFETY: properties are plain data of a valid physical device.
        let properties = unsafe { instance.get_physical_device_properties(cand.physical_device) };
        let limits = properties.limits;
        let pipeline_cache =
            match PipelineCache::open(&device, &CacheDevice::of(&properties), options.pipeline_cache.resolve()) {
                Ok(c) => c,
                Err(e) => {
                    // SAFETY: nothing was created on the device yet.
                    unsafe { device.destroy_device(None) };
                    return Err(cleanup_instance(e));
                }
            };
        if let Some(note) = &pipeline_cache.note {
            eprintln!("sweeplab: {note}; starting with an empty cache");
        }
        let memory = match GpuMemory::new(&instance, &device, cand.physical_device) {
            Ok(m) => Arc::new(m),
            Err(e) => {
                // SAFETY: only the pipeline cache was created on the device.
                unsafe {
                    device.destroy_pipeline_cache(pipeline_cache.raw, None);
                    device.destroy_device(None);
                }
                return Err(cleanup_instance(e));
            }
        };
        let debug_utils = debug_instance.as_ref().map(|_| ash::ext::debug_utils::Device::new(&instance, &device));
        let calibrator = calibration_ext.map(|name| Arc::new(Calibrator::new(&instance, &device, name)));
        let descriptor_pools = Arc::new(PoolShelf::new(&device));
        let finished_frame = FinishedFrameKeeper::new(&device);
        let push_descriptor = push_descriptor.then(|| ash::khr::push_descriptor::Device::new(&instance, &device));
        Ok(Context {
            entry,
            instance,
            debug_instance,
            messenger,
            validation,
            physical_device: cand.physical_device,
            info: cand.info.clone(),
            limits,
            device,
            debug_utils,
            queue,
            queue_family,
            memory,
            int64_atomics,
            push_descriptor,
            wait_reporter: Mutex::new(None),
            shared_specialization: Mutex::new(Vec::new()),
            calibrator,
            validation_layer: layer.map(device_info::version_string),
            device_extensions: enabled.iter().map(|n| n.to_string_lossy().into_owned()).collect(),
            extensions_left_out: left_out.iter().map(|l| l.describe()).collect(),
            descriptor_pools,
            finished_frame,
            pipeline_cache,
            pipelines: PipelineStore::default(),
            counters: CreationCounters::default(),
            _validated_thread: validated_thread,
        })
    }

    /// What this context created so far (pipelines, descriptor pools, images).
    pub fn creation_counts(&self) -> CreationCounts {
        self.counters.read()
    }

    /// Writes the pipeline cache to its file now (the context also does when
    /// it drops, if it compiled a pipeline); the bytes written, `None` where
    /// the cache is off.
    pub fn save_pipeline_cache(&self) -> Result<Option<usize>, VkError> {
        self.pipeline_cache.save(&self.device)
    }

    /// Sets (or with `None` clears) what reports on long waits for a
    /// submission ([`super::wait_report`]).
    pub fn set_wait_reporter(&self, reporter: Option<WaitReporter>) {
        *self.wait_reporter.lock().unwrap_or_else(|p| p.into_inner()) = reporter.map(Arc::new);
    }

    pub(super) fn wait_reporter(&self) -> Option<Arc<WaitReporter>> {
        self.wait_reporter.lock().unwrap_or_else(|p| p.into_inner()).clone()
    }

    /// Sets the shared specialization constant `id` to `value` for every
    /// pipeline created from now on (a shader that does not declare it ignores it).
    pub fn set_shared_specialization(&self, id: u32, value: u32) {
        let mut shared = self.shared_specialization.lock().unwrap_or_else(|p| p.into_inner());
        shared.retain(|(i, _)| *i != id);
        shared.push((id, value));
    }

    /// The shared specialization constants, (constant_id, value).
    pub fn shared_specialization(&self) -> Vec<(u32, u32)> {
        self.shared_specialization.lock().unwrap_or_else(|p| p.into_inner()).clone()
    }

    /// Validation messages collected so far (empty when validation is off).
    pub fn validation_messages(&self) -> Vec<String> {
        self.validation.as_ref().map(|v| v.messages()).unwrap_or_default()
    }

    /// Takes the validation messages collected so far.
    pub fn take_validation_messages(&self) -> Vec<String> {
        self.validation.as_ref().map(|v| v.take()).unwrap_or_default()
    }

    pub fn validation_enabled(&self) -> bool {
        self.validation.is_some()
    }

    /// The `device:` line the commands print: name, driver, API version, and
    /// with validation the layer's version beside it (a layer older than the
    /// driver's extensions is what this line lets a reader see), with what
    /// was left out for it, and lavapipe at a SIMD width on Mesa's shared
    /// shader cache (vk/lavapipe_shader_cache.rs).
    pub fn summary(&self) -> String {
        let validation = match &self.validation_layer {
            Some(layer) if self.validation_enabled() => format!(", validation on (layer {layer})"),
            _ if self.validation_enabled() => ", validation on".to_string(),
            _ => String::new(),
        };
        let left_out: String = self.extensions_left_out.iter().map(|l| format!("; {l}")).collect();
        let cache = super::lavapipe_shader_cache::shared_cache_warning_here(&self.info.name)
            .map(|w| format!("; {w}"))
            .unwrap_or_default();
        format!(
            "device: {} ({}, Vulkan {}){validation}{left_out}{cache}",
            self.info.name, self.info.driver_info, self.info.api_version
        )
    }

    pub fn timestamps_supported(&self) -> bool {
        self.info.timestamp_valid_bits > 0 && self.info.timestamp_period_ns > 0.0
    }

    /// Gives a Vulkan object a debug-utils name (RenderDoc, Nsight, validation).
    pub fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(du) = &self.debug_utils {
            let Ok(name) = CString::new(name) else { return };
            let info = vk::DebugUtilsObjectNameInfoEXT::default().object_handle(handle).object_name(&name);
            // SAFETY: the handle belongs to this device; naming has no other effect.
            let _ = unsafe { du.set_debug_utils_object_name(&info) };
        }
    }

    pub fn wait_idle(&self) -> Result<(), VkError> {
        // SAFETY: the device is valid for the life of the context.
        unsafe { self.device.device_wait_idle() }.call("vkDeviceWaitIdle")
    }

    /// Whether `format` supports `features` with optimal tiling.
    pub fn format_supports(&self, format: vk::Format, features: vk::FormatFeatureFlags) -> bool {
        // SAFETY: a query on a valid physical device.
        let props = unsafe { self.instance.get_physical_device_format_properties(self.physical_device, format) };
        props.optimal_tiling_features.contains(features)
    }
}

fn choose(all: &[Candidate], wanted: Option<&str>) -> Result<usize, VkError> {
    if all.is_empty() {
        return Err(VkError::NoDevice);
    }
    if let Some(w) = wanted {
        let infos: Vec<DeviceInfo> = all.iter().map(|c| c.info.clone()).collect();
        return device_info::pick(w, &infos).ok_or_else(|| VkError::DeviceNotFound {
            wanted: w.to_string(),
            available: infos.iter().map(|d| format!("{}: {}", d.index, d.name)).collect::<Vec<_>>().join(", "),
        });
    }
    let best = (0..all.len())
        .filter(|&i| all[i].queue_family.is_some() && all[i].api_version >= vk::API_VERSION_1_3)
        .min_by_key(|&i| device_info::type_rank(all[i].device_type))
        .unwrap_or(0);
    Ok(best)
}

fn create_device(
    entry: &ash::Entry,
    instance: &ash::Instance,
    cand: &Candidate,
    queue_family: u32,
    swapchain: bool,
    layer: Option<u32>,
) -> Result<CreatedDevice, VkError> {
    let mut have12 = vk::PhysicalDeviceVulkan12Features::default();
    let mut have13 = vk::PhysicalDeviceVulkan13Features::default();
    let mut have = vk::PhysicalDeviceFeatures2::default().push_next(&mut have12).push_next(&mut have13);
    // SAFETY: the chained structs live on the stack for the call.
    unsafe { instance.get_physical_device_features2(cand.physical_device, &mut have) };
    let extended_formats = have.features.shader_storage_image_extended_formats;
    let int64 = have.features.shader_int64;
    let mut missing = Vec::new();
    if have13.synchronization2 != vk::TRUE {
        missing.push("synchronization2");
    }
    // The shaders are SPIR-V 1.6, whose LocalSizeId execution mode needs it
    // (core in Vulkan 1.3; every 1.3 device has it).
    if have13.maintenance4 != vk::TRUE {
        missing.push("maintenance4");
    }
    if have12.host_query_reset != vk::TRUE {
        missing.push("hostQueryReset");
    }
    if have12.timeline_semaphore != vk::TRUE {
        missing.push("timelineSemaphore");
    }
    if extended_formats != vk::TRUE {
        missing.push("shaderStorageImageExtendedFormats");
    }
    // SAFETY: plain enumeration on a valid physical device.
    let device_extensions = unsafe { instance.enumerate_device_extension_properties(cand.physical_device) }
        .call("vkEnumerateDeviceExtensionProperties")?;
    let has_swapchain = device_extensions
        .iter()
        .any(|e| e.extension_name_as_c_str().map(|n| n == ash::khr::swapchain::NAME).unwrap_or(false));
    if swapchain && !has_swapchain {
        missing.push("VK_KHR_swapchain");
    }
    // The viewer's control panel draws with dynamic rendering.
    if swapchain && have13.dynamic_rendering != vk::TRUE {
        missing.push("dynamicRendering");
    }
    if !missing.is_empty() {
        return Err(VkError::MissingFeature { device: cand.info.name.clone(), missing: missing.join(", ") });
    }
    let mut enabled: Vec<&'static CStr> = if swapchain { vec![ash::khr::swapchain::NAME] } else { Vec::new() };
    // Calibrated timestamps put GPU scopes on the host's timeline (the trace).
    let (calibration_ext, mut left_out) =
        calibration::extension_to_enable(entry, instance, cand.physical_device, &device_extensions, layer);
    enabled.extend(calibration_ext);
    let offers_push_descriptor = device_extensions
        .iter()
        .any(|e| e.extension_name_as_c_str().map(|n| n == ash::khr::push_descriptor::NAME).unwrap_or(false));
    let (pushed, push_left_out) =
        layer_extensions::choose(if offers_push_descriptor { &[ash::khr::push_descriptor::NAME] } else { &[] }, layer);
    left_out.extend(push_left_out);
    let push_descriptor = !pushed.is_empty();
    enabled.extend(pushed);
    let extensions: Vec<*const std::ffi::c_char> = enabled.iter().map(|n| n.as_ptr()).collect();
    // 64-bit atomicMax of IPSVI's deterministic cache writes: enabled where the
    // device has it; IPSVI refuses to render without it (`Context::int64_atomics`).
    let int64_atomics = int64 == vk::TRUE && have12.shader_buffer_int64_atomics == vk::TRUE;
    let mut want12 = vk::PhysicalDeviceVulkan12Features::default()
        .host_query_reset(true)
        .timeline_semaphore(true)
        .shader_buffer_int64_atomics(int64_atomics);
    let mut want13 = vk::PhysicalDeviceVulkan13Features::default()
        .synchronization2(true)
        .maintenance4(true)
        .dynamic_rendering(swapchain);
    // r16ui / rgba16f storage images of the IPSVI cache.
    let core =
        vk::PhysicalDeviceFeatures::default().shader_storage_image_extended_formats(true).shader_int64(int64_atomics);
    let priorities = [1.0f32];
    let queues = [vk::DeviceQueueCreateInfo::default().queue_family_index(queue_family).queue_priorities(&priorities)];
    let info = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queues)
        .enabled_extension_names(&extensions)
        .enabled_features(&core)
        .push_next(&mut want12)
        .push_next(&mut want13);
    // SAFETY: all pointers in `info` refer to locals that outlive the call.
    let device = unsafe { instance.create_device(cand.physical_device, &info, None) }.call("vkCreateDevice")?;
    Ok(CreatedDevice { device, int64_atomics, calibration_ext, push_descriptor, enabled, left_out })
}

/// What [`create_device`] made and chose.
struct CreatedDevice {
    device: ash::Device,
    int64_atomics: bool,
    calibration_ext: Option<&'static CStr>,
    push_descriptor: bool,
    enabled: Vec<&'static CStr>,
    left_out: Vec<LeftOut>,
}

impl Drop for Context {
    fn drop(&mut self) {
        // SAFETY: we wait for the device to be idle, free the allocator, then destroy
        // device, messenger and instance in reverse order of creation.
        unsafe {
            let _ = self.device.device_wait_idle();
            self.finished_frame.clear();
            // After the wait: another thread's context need not wait for this GPU.
            let _lifecycle = lifecycle_lock();
            if Arc::strong_count(&self.memory) > 1 {
                eprintln!("sweeplab: GPU resources outlive the Vulkan context; leaking the device instead of destroying it under them");
                return;
            }
            // Kept pipelines and pools go before the device; the cache is
            // saved only where something was compiled into it.
            self.pipelines.clear();
            self.descriptor_pools.clear();
            if self.counters.read().pipelines > 0 {
                if let Err(e) = self.pipeline_cache.save(&self.device) {
                    eprintln!("sweeplab: the pipeline cache was not saved: {e}");
                }
            }
            self.device.destroy_pipeline_cache(self.pipeline_cache.raw, None);
            self.memory.destroy_allocator();
            self.device.destroy_device(None);
            if let Some(di) = &self.debug_instance {
                if self.messenger != vk::DebugUtilsMessengerEXT::null() {
                    di.destroy_debug_utils_messenger(self.messenger, None);
                }
            }
            self.instance.destroy_instance(None);
        }
    }
}
