//! What does the Vulkan driver make of obscura's compute shaders? Timings say how long a pass
//! takes, not why; on NVIDIA's driver a pass's register count decides how many warps an SM
//! keeps in flight (65,536 registers per SM: 32 a thread for all 64 warps, 64 for half of
//! them), which explains passes that slow down when they gain a few live values (bent normals,
//! BENCHMARKS.md). This tool compiles the compute pipelines an obscura run dumped with
//! `OBSCURA_DUMP_WGSL=DIR` (each module's WGSL and, beside it, the `override` constants each
//! pipeline was made with: `STEM.HASH.constants`) and prints the statistics the driver reports
//! through VK_KHR_pipeline_executable_properties (NVIDIA: register count, binary size; Mesa's
//! drivers: instruction counts and more).
//!
//! The SPIR-V is written by naga as wgpu 29's Vulkan backend writes it for obscura's AO passes
//! (`gpu::shader_module`: bounds checks on, loop bounding off, `override`s resolved for the
//! pipeline's entry point: `main`, or the one its constants file names), so the driver sees the
//! same program up to naga's choice of ids. After the driver's own lines, each pass gets the
//! warps an SM keeps in flight by its registers and group size.
//!
//! Usage: `cargo run --release --manifest-path tools/pipeline-stats/Cargo.toml -- DIR [FILTER]`:
//! every pipeline whose file name contains FILTER (all without it), one block each; with
//! `PIPELINE_STATS_IR=1` also the text of the driver's internal representations, where it has
//! any (NVIDIA's 580 driver gives none). Exit status 1 when a pipeline failed to compile, 2 when
//! there is no Vulkan device or DIR is unusable. A device without the extension (lavapipe)
//! compiles the pipelines and reports nothing more.

use ash::vk;
use naga::back::{pipeline_constants::process_overrides, spv};
use naga::valid::{Capabilities, ValidationFlags, Validator};
use std::ffi::CStr;
use std::process::ExitCode;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let Some(dir) = args.next() else {
        eprintln!("usage: pipeline-stats DIR [FILTER] (DIR from an OBSCURA_DUMP_WGSL run)");
        return ExitCode::from(2);
    };
    let filter = args.next().unwrap_or_default();
    let pipelines = match dumped_pipelines(&dir, &filter) {
        Ok(p) if !p.is_empty() => p,
        Ok(_) => {
            eprintln!("{dir}: no STEM.HASH.constants files (matching '{filter}'): run obscura with OBSCURA_DUMP_WGSL={dir} first");
            return ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("{dir}: {e}");
            return ExitCode::from(2);
        }
    };
    // SAFETY: the Vulkan calls below follow the specification's valid usage for every handle
    // they make, and everything made is destroyed before the device and instance.
    let driver = match unsafe { Driver::new() } {
        Ok(d) => d,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    println!("device: {}", driver.name);
    let mut failed = 0;
    for p in &pipelines {
        println!("\n{} [{}]", p.name, p.constants_line());
        let stats = spirv(p).and_then(|(words, layout, threads)| {
            let lines = unsafe { driver.statistics(&words, &layout, &p.entry) }?;
            Ok((lines, threads))
        });
        match stats {
            Ok((lines, threads)) => {
                lines.iter().for_each(|l| println!("  {l}"));
                let registers = lines
                    .iter()
                    .find_map(|l| l.strip_prefix("Register Count: ")?.parse::<u32>().ok());
                if let Some(registers) = registers {
                    println!(
                        "  warps an SM by registers: {} of 64 ({threads}-thread groups; an SM of \
                         65,536 registers, as NVIDIA's since Kepler)",
                        warps_by_registers(registers, threads)
                    );
                }
            }
            Err(e) => {
                println!("  FAILED: {e}");
                failed += 1;
            }
        }
    }
    // SAFETY: nothing made from the device is alive any more.
    unsafe { driver.destroy() };
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// One dumped pipeline: its module's WGSL and its constants.
struct Dumped {
    name: String,
    source: String,
    entry: String,
    constants: Vec<(String, f64)>,
}

impl Dumped {
    fn constants_line(&self) -> String {
        let entry = (self.entry != "main").then(|| format!("entry {}", self.entry));
        let all: Vec<String> = entry
            .into_iter()
            .chain(self.constants.iter().map(|(n, v)| format!("{n}={v}")))
            .collect();
        all.join(" ")
    }
}

fn dumped_pipelines(dir: &str, filter: &str) -> Result<Vec<Dumped>, String> {
    let entries = std::fs::read_dir(dir).map_err(|e| e.to_string())?;
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".constants") && n.contains(filter))
        .collect();
    names.sort();
    let mut out = Vec::new();
    for name in names {
        let stem = name.split('.').next().unwrap_or_default();
        let path = std::path::Path::new(dir);
        let source = std::fs::read_to_string(path.join(format!("{stem}.wgsl")))
            .map_err(|e| format!("{stem}.wgsl: {e}"))?;
        let text = std::fs::read_to_string(path.join(&name)).map_err(|e| format!("{name}: {e}"))?;
        let mut constants = Vec::new();
        let mut entry = "main".to_owned();
        for line in text.lines().filter(|l| !l.is_empty()) {
            if let Some(name) = line.strip_prefix("#entry=") {
                entry = name.to_owned();
                continue;
            }
            let parsed = line
                .split_once('=')
                .and_then(|(n, v)| v.parse::<f64>().ok().map(|v| (n.to_owned(), v)));
            constants.push(parsed.ok_or_else(|| format!("{name}: bad line '{line}'"))?);
        }
        out.push(Dumped {
            name,
            source,
            entry,
            constants,
        });
    }
    Ok(out)
}

/// How many warps an NVIDIA SM keeps in flight for a pass of `registers` a thread in groups of
/// `threads` invocations, by registers alone: registers are given out 8 a thread (256 a warp),
/// a group runs whole or not at all, at most 64 warps and 32 groups an SM. Shared memory can
/// lower it further (the tool prints each pass's).
fn warps_by_registers(registers: u32, threads: u32) -> u32 {
    let per_warp = registers.max(1).div_ceil(8) * 8 * 32;
    let group_warps = threads.max(1).div_ceil(32);
    let groups = (65_536 / per_warp / group_warps).min(32);
    (groups * group_warps).min(64)
}

/// The descriptor types of the module's bindings, by group: (binding, type, count).
type Layout = Vec<Vec<(u32, vk::DescriptorType, u32)>>;

/// Pipeline `p`'s entry point as SPIR-V (naga's writer keeps only that one), with its
/// resources' layout and its workgroup's invocation count.
fn spirv(p: &Dumped) -> Result<(Vec<u32>, Layout, u32), String> {
    let source = p.source.replace("@early_depth_test(force)", "");
    let module = naga::front::wgsl::parse_str(&source).map_err(|e| e.emit_to_string(&source))?;
    let info = Validator::new(ValidationFlags::all(), Capabilities::all())
        .validate(&module)
        .map_err(|e| e.emit_to_string(&source))?;
    let constants = p.constants.iter().cloned().collect();
    let point = (naga::ShaderStage::Compute, p.entry.as_str());
    let (module, info) =
        process_overrides(&module, &info, Some(point), &constants).map_err(|e| e.to_string())?;
    let layout = layout_of(&module);
    let threads = module
        .entry_points
        .iter()
        .find(|e| e.name == p.entry)
        .map_or(1, |e| e.workgroup_size.iter().product());
    // As wgpu-hal 30's Vulkan adapter sets them for a Vulkan 1.3 device, with the runtime checks
    // obscura's AO passes keep (gpu::shader_module: loop bounding off).
    let mut options = spv::Options {
        lang_version: (1, 6),
        force_loop_bounding: false,
        ..Default::default()
    };
    options.flags.remove(spv::WriterFlags::DEBUG);
    options.bounds_check_policies = naga::proc::BoundsCheckPolicies {
        index: naga::proc::BoundsCheckPolicy::Restrict,
        buffer: naga::proc::BoundsCheckPolicy::Unchecked,
        image_load: naga::proc::BoundsCheckPolicy::Unchecked,
        binding_array: naga::proc::BoundsCheckPolicy::Unchecked,
    };
    let pipeline = spv::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: p.entry.clone(),
    };
    let words =
        spv::write_vec(&module, &info, &options, Some(&pipeline)).map_err(|e| e.to_string())?;
    Ok((words, layout, threads))
}

fn layout_of(module: &naga::Module) -> Layout {
    let mut groups: Layout = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(binding) = &var.binding else {
            continue;
        };
        let mut inner = &module.types[var.ty].inner;
        let mut count = 1;
        if let naga::TypeInner::BindingArray { base, size } = inner {
            count = match size {
                naga::ArraySize::Constant(n) => n.get(),
                _ => 1,
            };
            inner = &module.types[*base].inner;
        }
        let kind = match (var.space, inner) {
            (naga::AddressSpace::Uniform, _) => vk::DescriptorType::UNIFORM_BUFFER,
            (naga::AddressSpace::Storage { .. }, _) => vk::DescriptorType::STORAGE_BUFFER,
            (
                _,
                naga::TypeInner::Image {
                    class: naga::ImageClass::Storage { .. },
                    ..
                },
            ) => vk::DescriptorType::STORAGE_IMAGE,
            (_, naga::TypeInner::Image { .. }) => vk::DescriptorType::SAMPLED_IMAGE,
            (_, naga::TypeInner::Sampler { .. }) => vk::DescriptorType::SAMPLER,
            (_, naga::TypeInner::AccelerationStructure { .. }) => {
                vk::DescriptorType::ACCELERATION_STRUCTURE_KHR
            }
            _ => continue,
        };
        let group = binding.group as usize;
        if groups.len() <= group {
            groups.resize(group + 1, Vec::new());
        }
        groups[group].push((binding.binding, kind, count));
    }
    groups
}

/// A Vulkan device with VK_KHR_pipeline_executable_properties on (the first GPU that has it,
/// discrete ones first; else the first device, which only compiles the pipelines: lavapipe has
/// no statistics), every core, 1.1, 1.2 and 1.3 feature it offers enabled.
struct Driver {
    _entry: ash::Entry,
    instance: ash::Instance,
    device: ash::Device,
    executables: Option<ash::khr::pipeline_executable_properties::Device>,
    name: String,
}

impl Driver {
    unsafe fn new() -> Result<Self, String> {
        let entry = unsafe { ash::Entry::load() }
            .map_err(|e| format!("no Vulkan loader (libvulkan.so.1): {e}"))?;
        let app = vk::ApplicationInfo::default().api_version(vk::API_VERSION_1_3);
        let instance = unsafe {
            entry.create_instance(
                &vk::InstanceCreateInfo::default().application_info(&app),
                None,
            )
        }
        .map_err(|e| format!("vkCreateInstance: {e}"))?;
        let wanted = ash::khr::pipeline_executable_properties::NAME;
        let mut candidates = Vec::new();
        for pd in unsafe { instance.enumerate_physical_devices() }.unwrap_or_default() {
            let props = unsafe { instance.get_physical_device_properties(pd) };
            let name = props
                .device_name_as_c_str()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let extensions =
                unsafe { instance.enumerate_device_extension_properties(pd) }.unwrap_or_default();
            let has = extensions
                .iter()
                .any(|e| e.extension_name_as_c_str().is_ok_and(|n| n == wanted));
            let version = format!(
                "{name} (Vulkan {}.{}, driver {:#x})",
                vk::api_version_major(props.api_version),
                vk::api_version_minor(props.api_version),
                props.driver_version
            );
            if !has {
                eprintln!("{version}: no {}", wanted.to_string_lossy());
            }
            let discrete = props.device_type == vk::PhysicalDeviceType::DISCRETE_GPU;
            candidates.push(((!has, !discrete), pd, version, props.api_version, has));
        }
        candidates.sort_by_key(|c| c.0);
        let Some((_, pd, name, api, has)) = candidates.into_iter().next() else {
            unsafe { instance.destroy_instance(None) };
            return Err("no Vulkan device".into());
        };
        let family = unsafe { instance.get_physical_device_queue_family_properties(pd) }
            .iter()
            .position(|q| q.queue_flags.contains(vk::QueueFlags::COMPUTE))
            .unwrap_or(0) as u32;
        let mut exec = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default();
        let mut v11 = vk::PhysicalDeviceVulkan11Features::default();
        let mut v12 = vk::PhysicalDeviceVulkan12Features::default();
        let mut v13 = vk::PhysicalDeviceVulkan13Features::default();
        let mut features = vk::PhysicalDeviceFeatures2::default().push_next(&mut exec);
        if api >= vk::API_VERSION_1_2 {
            features = features.push_next(&mut v11).push_next(&mut v12);
        }
        if api >= vk::API_VERSION_1_3 {
            features = features.push_next(&mut v13);
        }
        unsafe { instance.get_physical_device_features2(pd, &mut features) };
        let priorities = [1.0];
        let queues = [vk::DeviceQueueCreateInfo::default()
            .queue_family_index(family)
            .queue_priorities(&priorities)];
        let extensions = if has {
            vec![wanted.as_ptr()]
        } else {
            Vec::new()
        };
        let info = vk::DeviceCreateInfo::default()
            .queue_create_infos(&queues)
            .enabled_extension_names(&extensions)
            .push_next(&mut features);
        let device = unsafe { instance.create_device(pd, &info, None) }
            .map_err(|e| format!("vkCreateDevice on {name}: {e}"))?;
        let executables =
            has.then(|| ash::khr::pipeline_executable_properties::Device::new(&instance, &device));
        Ok(Self {
            _entry: entry,
            instance,
            device,
            executables,
            name,
        })
    }

    /// The driver's statistics for a compute pipeline of entry point `entry` of `words` over
    /// `layout`, one line each.
    unsafe fn statistics(
        &self,
        words: &[u32],
        layout: &Layout,
        entry: &str,
    ) -> Result<Vec<String>, String> {
        let entry = std::ffi::CString::new(entry).map_err(|e| e.to_string())?;
        let d = &self.device;
        let module = unsafe {
            d.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(words), None)
        }
        .map_err(|e| format!("vkCreateShaderModule: {e}"))?;
        let mut sets = Vec::new();
        for group in layout {
            let bindings: Vec<_> = group
                .iter()
                .map(|&(binding, kind, count)| {
                    vk::DescriptorSetLayoutBinding::default()
                        .binding(binding)
                        .descriptor_type(kind)
                        .descriptor_count(count)
                        .stage_flags(vk::ShaderStageFlags::COMPUTE)
                })
                .collect();
            let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
            sets.push(
                unsafe { d.create_descriptor_set_layout(&info, None) }
                    .map_err(|e| e.to_string())?,
            );
        }
        let pipeline_layout = unsafe {
            d.create_pipeline_layout(
                &vk::PipelineLayoutCreateInfo::default().set_layouts(&sets),
                None,
            )
        }
        .map_err(|e| e.to_string())?;
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(&entry);
        let flags = match self.executables {
            Some(_) => vk::PipelineCreateFlags::CAPTURE_STATISTICS_KHR,
            None => vk::PipelineCreateFlags::empty(),
        };
        let info = vk::ComputePipelineCreateInfo::default()
            .flags(flags)
            .stage(stage)
            .layout(pipeline_layout);
        let made = unsafe { d.create_compute_pipelines(vk::PipelineCache::null(), &[info], None) };
        let result = match made {
            Ok(pipelines) => {
                let lines = unsafe { self.read(pipelines[0]) };
                unsafe { d.destroy_pipeline(pipelines[0], None) };
                lines
            }
            Err((_, e)) => Err(format!("vkCreateComputePipelines: {e}")),
        };
        unsafe {
            d.destroy_pipeline_layout(pipeline_layout, None);
            sets.iter()
                .for_each(|&s| d.destroy_descriptor_set_layout(s, None));
            d.destroy_shader_module(module, None);
        }
        result
    }

    unsafe fn read(&self, pipeline: vk::Pipeline) -> Result<Vec<String>, String> {
        let Some(ext) = &self.executables else {
            return Ok(vec!["compiled (the driver reports no statistics)".into()]);
        };
        let info = vk::PipelineInfoKHR::default().pipeline(pipeline);
        let executables = unsafe { ext.get_pipeline_executable_properties(&info) }
            .map_err(|e| format!("vkGetPipelineExecutablePropertiesKHR: {e}"))?;
        let mut lines = Vec::new();
        for (index, exe) in executables.iter().enumerate() {
            let name = exe
                .name_as_c_str()
                .map(CStr::to_string_lossy)
                .unwrap_or_default();
            lines.push(format!(
                "executable {index}: {name} (subgroup size {})",
                exe.subgroup_size
            ));
            let exe_info = vk::PipelineExecutableInfoKHR::default()
                .pipeline(pipeline)
                .executable_index(index as u32);
            let stats = unsafe { ext.get_pipeline_executable_statistics(&exe_info) }
                .map_err(|e| format!("vkGetPipelineExecutableStatisticsKHR: {e}"))?;
            for s in &stats {
                let name = s
                    .name_as_c_str()
                    .map(CStr::to_string_lossy)
                    .unwrap_or_default();
                // SAFETY: the union member read is the one `format` names.
                let value = unsafe {
                    match s.format {
                        vk::PipelineExecutableStatisticFormatKHR::BOOL32 => {
                            (s.value.b32 != 0).to_string()
                        }
                        vk::PipelineExecutableStatisticFormatKHR::INT64 => s.value.i64.to_string(),
                        vk::PipelineExecutableStatisticFormatKHR::UINT64 => s.value.u64.to_string(),
                        _ => format!("{:.3}", s.value.f64),
                    }
                };
                lines.push(format!("{name}: {value}"));
            }
            for (title, text) in unsafe { self.representations(&exe_info) } {
                lines.push(format!(
                    "representation {title}: {} lines",
                    text.lines().count()
                ));
                if std::env::var_os("PIPELINE_STATS_IR").is_some() {
                    lines.extend(text.lines().map(|l| format!("| {l}")));
                }
            }
        }
        Ok(lines)
    }

    /// The driver's internal representations of an executable (text ones only), where it gives
    /// any: two calls for their sizes, a third for their text (ash's wrapper makes only the first).
    unsafe fn representations(
        &self,
        exe_info: &vk::PipelineExecutableInfoKHR,
    ) -> Vec<(String, String)> {
        let Some(ext) = &self.executables else {
            return Vec::new();
        };
        let fp = ext
            .fp()
            .get_pipeline_executable_internal_representations_khr;
        let device = ext.device();
        let mut count = 0u32;
        let mut reps = Vec::new();
        unsafe {
            if fp(device, exe_info, &mut count, std::ptr::null_mut()) != vk::Result::SUCCESS {
                return Vec::new();
            }
            reps.resize(
                count as usize,
                vk::PipelineExecutableInternalRepresentationKHR::default(),
            );
            if fp(device, exe_info, &mut count, reps.as_mut_ptr()) != vk::Result::SUCCESS {
                return Vec::new();
            }
        }
        let mut buffers: Vec<Vec<u8>> = reps.iter().map(|r| vec![0u8; r.data_size]).collect();
        for (r, b) in reps.iter_mut().zip(buffers.iter_mut()) {
            r.p_data = b.as_mut_ptr().cast();
        }
        if unsafe { fp(device, exe_info, &mut count, reps.as_mut_ptr()) } != vk::Result::SUCCESS {
            return Vec::new();
        }
        reps.iter()
            .zip(&buffers)
            .filter(|(r, _)| r.is_text != 0)
            .map(|(r, b)| {
                let title = r
                    .name_as_c_str()
                    .map(CStr::to_string_lossy)
                    .unwrap_or_default();
                let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
                (
                    title.into_owned(),
                    String::from_utf8_lossy(&b[..end]).into_owned(),
                )
            })
            .collect()
    }

    unsafe fn destroy(self) {
        unsafe {
            self.device.destroy_device(None);
            self.instance.destroy_instance(None);
        }
    }
}

#[cfg(test)]
mod tests {
    /// The occupancy table of BENCHMARKS.md (2026-12-05): 8 × 32-thread groups keep 64 warps at
    /// up to 32 registers, 48 at 40, 40 at 48, 32 at 64; 64-thread groups 24 warps at 80.
    #[test]
    fn warps_by_registers_follow_the_allocation_steps() {
        for (registers, threads, warps) in [
            (29, 256, 64),
            (32, 256, 64),
            (39, 256, 48),
            (48, 256, 40),
            (57, 256, 32),
            (64, 256, 32),
            (80, 64, 24),
            (63, 64, 32),
            (16, 64, 64),
        ] {
            assert_eq!(
                super::warps_by_registers(registers, threads),
                warps,
                "{registers} × {threads}"
            );
        }
    }
}
