//! What the driver made of the kernel: the statistics a Vulkan driver reports for a compiled compute
//! pipeline (`VK_KHR_pipeline_executable_properties`), e.g. registers per thread and spilled bytes on
//! NVIDIA. `caustic kernel-stats` prints them for a scene's pruned kernel.
//!
//! Why: wgpu does not expose these, and NVIDIA's `ncu` profiles CUDA only (it reports no kernels
//! for wgpu's Vulkan dispatches, 2026-11-24). Three traversal changes lost on the H100 by adding
//! state that stays live across loops (BENCHMARKS.md, "Three traversal and scheduling changes");
//! the register count is the figure that explains such a loss without a timing run. The pipeline
//! here is built with `ash` directly, from the same module and binding layout as `backend::gpu`'s,
//! but with the statistics flag that wgpu never sets.
use super::gpu::BINDINGS;
use super::variant::{self, Variant, DEFAULT_WORKGROUP};
use anyhow::{anyhow, bail, Context, Result};
use ash::vk;
use caustic_kernel::layout::INTEGRATOR_PATH;
use std::ffi::{CStr, CString};

/// One statistic of one executable, as the driver names it.
#[derive(Clone, Debug)]
pub struct Statistic {
    pub name: String,
    pub value: String,
}

/// One executable of a pipeline (a compute pipeline usually has one) and its statistics.
#[derive(Clone, Debug)]
pub struct Executable {
    pub name: String,
    pub stats: Vec<Statistic>,
}

const EXTENSION: &CStr = ash::khr::pipeline_executable_properties::NAME;

/// A Vulkan device on the first adapter that reports pipeline statistics (hardware adapters first).
struct Vulkan {
    _entry: ash::Entry,
    instance: ash::Instance,
    device: ash::Device,
    adapter: String,
}

impl Drop for Vulkan {
    fn drop(&mut self) {
        // SAFETY: every object created on the device was destroyed by `statistics` before it returned.
        unsafe {
            self.device.destroy_device(None);
            self.instance.destroy_instance(None);
        }
    }
}

impl Vulkan {
    fn new() -> Result<Self> {
        // SAFETY: loading the system's Vulkan loader, as wgpu does.
        let entry = unsafe { ash::Entry::load() }.context("cannot load the Vulkan loader")?;
        let app = vk::ApplicationInfo::default().api_version(vk::API_VERSION_1_2);
        let instance =
            unsafe { entry.create_instance(&vk::InstanceCreateInfo::default().application_info(&app), None) }
                .context("cannot create a Vulkan instance")?;
        match Self::open(&instance) {
            Ok((device, adapter)) => Ok(Vulkan { _entry: entry, instance, device, adapter }),
            Err(e) => {
                unsafe { instance.destroy_instance(None) };
                Err(e)
            }
        }
    }

    /// The device, with the extension and every Vulkan 1.2 feature the adapter has (the kernel
    /// declares the Vulkan memory model).
    fn open(instance: &ash::Instance) -> Result<(ash::Device, String)> {
        let mut adapters = unsafe { instance.enumerate_physical_devices() }?;
        let software = |p: &vk::PhysicalDevice| {
            unsafe { instance.get_physical_device_properties(*p) }.device_type == vk::PhysicalDeviceType::CPU
        };
        adapters.sort_by_key(software);
        for physical in adapters {
            let has_extension = unsafe { instance.enumerate_device_extension_properties(physical) }?
                .iter()
                .any(|e| e.extension_name_as_c_str() == Ok(EXTENSION));
            let properties = unsafe { instance.get_physical_device_properties(physical) };
            let name = properties
                .device_name_as_c_str()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            if !has_extension {
                continue;
            }
            let queue_family = unsafe { instance.get_physical_device_queue_family_properties(physical) }
                .iter()
                .position(|q| q.queue_flags.contains(vk::QueueFlags::COMPUTE))
                .ok_or_else(|| anyhow!("{name} has no compute queue"))? as u32;
            let mut v12 = vk::PhysicalDeviceVulkan12Features::default();
            let mut features = vk::PhysicalDeviceFeatures2::default().push_next(&mut v12);
            unsafe { instance.get_physical_device_features2(physical, &mut features) };
            let base = features.features;
            let mut statistics = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default()
                .pipeline_executable_info(true);
            let priorities = [1.0];
            let queues = [vk::DeviceQueueCreateInfo::default()
                .queue_family_index(queue_family)
                .queue_priorities(&priorities)];
            let extensions = [EXTENSION.as_ptr()];
            let create = vk::DeviceCreateInfo::default()
                .queue_create_infos(&queues)
                .enabled_extension_names(&extensions)
                .enabled_features(&base)
                .push_next(&mut v12)
                .push_next(&mut statistics);
            let device = unsafe { instance.create_device(physical, &create, None) }
                .with_context(|| format!("cannot open {name}"))?;
            return Ok((device, name));
        }
        bail!("no Vulkan adapter here reports pipeline statistics ({})", EXTENSION.to_string_lossy())
    }
}

/// What the driver receives from wgpu for entry point `entry` of `words`: wgpu reads a SPIR-V module
/// into naga's IR, sets its specialization constants there, and writes SPIR-V again (bounds checks
/// and loop bounding off, as `backend::gpu` asks). The driver compiles that, not rust-gpu's module.
fn through_naga(words: &[u32], entry: &str, constants: [u32; 2]) -> Result<Vec<u32>> {
    use naga::back::spv;
    use naga::proc::{BoundsCheckPolicies, BoundsCheckPolicy};
    let read = naga::front::spv::Options {
        adjust_coordinate_space: false,
        strict_capabilities: true,
        block_ctx_dump_prefix: None,
    };
    let module = naga::front::spv::parse_u8_slice(bytemuck::cast_slice(words), &read)
        .map_err(|e| anyhow!("naga cannot read the kernel: {e}"))?;
    let info =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
            .validate(&module)
            .map_err(|e| anyhow!("naga rejects the kernel: {e}"))?;
    let mut values = naga::back::PipelineConstants::default();
    // Only the constants the module still declares (a pruned one has none left).
    for (_, o) in module.overrides.iter() {
        if let Some(&value) = o.id.and_then(|id| constants.get(id as usize)) {
            values.insert(o.id.unwrap_or_default().to_string(), value as f64);
        }
    }
    let (module, info) = naga::back::pipeline_constants::process_overrides(
        &module,
        &info,
        Some((naga::ShaderStage::Compute, entry)),
        &values,
    )
    .map_err(|e| anyhow!("naga cannot set the kernel's constants: {e}"))?;
    let unchecked = BoundsCheckPolicy::Unchecked;
    let options = spv::Options {
        lang_version: (1, 3),
        bounds_check_policies: BoundsCheckPolicies {
            index: unchecked,
            buffer: unchecked,
            image_load: unchecked,
            binding_array: unchecked,
        },
        force_loop_bounding: false,
        ..Default::default()
    };
    let pipeline =
        spv::PipelineOptions { shader_stage: naga::ShaderStage::Compute, entry_point: entry.to_string() };
    spv::write_vec(&module, &info, &options, Some(&pipeline))
        .map_err(|e| anyhow!("naga cannot write the kernel: {e}"))
}

impl Vulkan {
    /// The driver's statistics for entry point `entry` of the SPIR-V module `words` (as the driver
    /// gets it from naga: `through_naga`), compiled with spec constants 0 and 1 set to `constants`
    /// (ignored by a module that has them frozen).
    fn statistics(&self, words: &[u32], entry: &str, constants: [u32; 2]) -> Result<Vec<Executable>> {
        let device = &self.device;
        let loader = ash::khr::pipeline_executable_properties::Device::new(&self.instance, device);
        let layout_bindings: Vec<vk::DescriptorSetLayoutBinding> = BINDINGS
            .iter()
            .map(|&b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b)
                    .descriptor_type(vk::DescriptorType::STORAGE_BUFFER)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let entry_name = CString::new(entry)?;
        // SAFETY: plain object creation on a live device; each object is destroyed below, in reverse.
        unsafe {
            let set_layout = device.create_descriptor_set_layout(
                &vk::DescriptorSetLayoutCreateInfo::default().bindings(&layout_bindings),
                None,
            )?;
            let set_layouts = [set_layout];
            let layout = device.create_pipeline_layout(
                &vk::PipelineLayoutCreateInfo::default().set_layouts(&set_layouts),
                None,
            )?;
            let module =
                device.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(words), None)?;
            let map = [
                vk::SpecializationMapEntry { constant_id: 0, offset: 0, size: 4 },
                vk::SpecializationMapEntry { constant_id: 1, offset: 4, size: 4 },
            ];
            let data: &[u8] = bytemuck::cast_slice(&constants);
            let specialization = vk::SpecializationInfo::default().map_entries(&map).data(data);
            let stage = vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::COMPUTE)
                .module(module)
                .name(&entry_name)
                .specialization_info(&specialization);
            let create = [vk::ComputePipelineCreateInfo::default()
                .flags(vk::PipelineCreateFlags::CAPTURE_STATISTICS_KHR)
                .stage(stage)
                .layout(layout)];
            let pipeline = device.create_compute_pipelines(vk::PipelineCache::null(), &create, None);
            let result = match pipeline {
                Ok(pipelines) => {
                    let read = read_statistics(&loader, pipelines[0]);
                    device.destroy_pipeline(pipelines[0], None);
                    read
                }
                Err((_, e)) => Err(anyhow!("the driver did not compile entry point {entry}: {e}")),
            };
            device.destroy_shader_module(module, None);
            device.destroy_pipeline_layout(layout, None);
            device.destroy_descriptor_set_layout(set_layout, None);
            result
        }
    }
}

/// # Safety
/// `pipeline` must be a live pipeline of the loader's device, created with the statistics flag.
unsafe fn read_statistics(
    loader: &ash::khr::pipeline_executable_properties::Device,
    pipeline: vk::Pipeline,
) -> Result<Vec<Executable>> {
    let info = vk::PipelineInfoKHR::default().pipeline(pipeline);
    let executables = unsafe { loader.get_pipeline_executable_properties(&info) }?;
    let mut out = Vec::new();
    for (index, executable) in executables.iter().enumerate() {
        let info = vk::PipelineExecutableInfoKHR::default().pipeline(pipeline).executable_index(index as u32);
        let stats = unsafe { loader.get_pipeline_executable_statistics(&info) }?
            .iter()
            .map(|s| Statistic {
                name: text(s.name_as_c_str()),
                // SAFETY: the union member read is the one `format` names.
                value: unsafe {
                    match s.format {
                        vk::PipelineExecutableStatisticFormatKHR::BOOL32 => (s.value.b32 != 0).to_string(),
                        vk::PipelineExecutableStatisticFormatKHR::INT64 => s.value.i64.to_string(),
                        vk::PipelineExecutableStatisticFormatKHR::UINT64 => s.value.u64.to_string(),
                        vk::PipelineExecutableStatisticFormatKHR::FLOAT64 => format!("{:.3}", s.value.f64),
                        _ => "?".to_string(),
                    }
                },
            })
            .collect();
        out.push(Executable { name: text(executable.name_as_c_str()), stats });
    }
    Ok(out)
}

fn text(s: Result<&CStr, std::ffi::FromBytesUntilNulError>) -> String {
    s.map(|c| c.to_string_lossy().into_owned()).unwrap_or_default()
}

/// One pipeline the GPU backend builds for a scene: which entry point and path loop, and what the
/// driver reports for it.
pub struct PipelineReport {
    pub entry: &'static str,
    /// The SPIR-V the driver compiled (naga's output).
    pub module: Vec<u32>,
    /// Its path loop and workgroup size.
    pub variant: Variant,
    pub adapter: String,
    pub executables: Vec<Executable>,
}

/// The driver's statistics for every pipeline `backend::gpu` builds for a scene with feature mask
/// `features` and integrator `integrator` on a hardware adapter: from the same module (pruned where
/// the backend prunes, `CAUSTIC_KERNEL_SPV` honoured), the camera entry point once per candidate
/// `Variant` (`CAUSTIC_PATH_LOOP` and `CAUSTIC_WORKGROUP` honoured), the light entry point (BDPT's and
/// VCM's: the light vertex cache's) once.
/// Without `with_statistics`, a missing adapter is no error: the reports then hold the modules alone.
pub fn scene(features: u32, integrator: u32, with_statistics: bool) -> Result<Vec<PipelineReport>> {
    use super::gpu::{camera_entry, kernel_words, LoopModules, CACHE_LIGHT_ENTRY, ENTRY_POINTS};
    use caustic_kernel::integrator::{traces_cached, traces_camera_paths, traces_light_paths};
    let words = kernel_words()?;
    let candidates = variant::candidates(integrator == INTEGRATOR_PATH, false)?;
    let mut wanted: Vec<(&'static str, Variant)> = Vec::new();
    if traces_camera_paths(integrator) {
        wanted.extend(candidates.iter().map(|&v| (camera_entry(integrator), v)));
    }
    if traces_light_paths(integrator) {
        wanted.push((ENTRY_POINTS[1], Variant { workgroup: DEFAULT_WORKGROUP, ..candidates[0] }));
    }
    if traces_cached(integrator) {
        wanted.push((CACHE_LIGHT_ENTRY, Variant { workgroup: DEFAULT_WORKGROUP, ..candidates[0] }));
    }
    // Every loop's module first: pruning is what takes long, and a later failure should not waste it.
    let variants: Vec<Variant> = wanted.iter().map(|w| w.1).collect();
    let mut entries: Vec<&str> = wanted.iter().map(|w| w.0).collect();
    entries.dedup();
    let modules = LoopModules::of(&words, features, &variants, &entries);
    // One device for every pipeline; without an adapter that reports statistics, why not (the
    // modules alone, for `--write-spirv`), unless they were asked for.
    let vulkan = match Vulkan::new() {
        Ok(v) => Ok(v),
        Err(e) if !with_statistics => Err(e.to_string()),
        Err(e) => return Err(e),
    };
    let mut reports = Vec::new();
    for (entry, variant) in wanted {
        let (module, _) = modules.module(variant.path_loop, variant.workgroup);
        let constants = [features, variant.path_loop.spec_value()];
        let module = through_naga(&module, entry, constants)?;
        let (adapter, executables) = match &vulkan {
            Ok(v) => match v.statistics(&module, entry, constants) {
                Ok(executables) => (v.adapter.clone(), executables),
                Err(e) if !with_statistics => (e.to_string(), Vec::new()),
                Err(e) => return Err(e),
            },
            Err(why) => (why.clone(), Vec::new()),
        };
        reports.push(PipelineReport { entry, module, variant, adapter, executables });
    }
    Ok(reports)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::gpu::kernel_words;
    use crate::backend::spirv::declares_spec_constant;

    /// What the driver gets: naga's module, for the one entry point, with the constants set. (The
    /// statistics themselves need an adapter that reports them, which CI's lavapipe does not.)
    #[test]
    fn the_driver_gets_one_entry_point_with_its_constants_set() {
        let words = kernel_words().unwrap();
        assert!(declares_spec_constant(&words, 0));
        let module = through_naga(&words, "entry::resolve", [0, 1]).unwrap();
        assert_eq!(module[0], 0x0723_0203);
        assert!(!declares_spec_constant(&module, 0) && !declares_spec_constant(&module, 1));
        const OP_ENTRY_POINT: u32 = 15;
        let entry_points =
            crate::backend::spirv::instructions(&module).filter(|i| i.1 == OP_ENTRY_POINT).count();
        assert_eq!(entry_points, 1);
        assert!(through_naga(&words, "entry::nowhere", [0, 1]).is_err());
    }

    /// A module pruned to the entry points a path-traced scene runs (`prune::pruned_to`) gives the
    /// driver the same words for them as the module with all six, the others gone: here the Cornell
    /// box's mask under the regenerating loop, and the light entry point of a light-tracing scene.
    #[test]
    fn entry_points_left_out_change_nothing_the_driver_gets_for_the_others() {
        use crate::backend::prune::{pruned, pruned_to};
        let words = kernel_words().unwrap();
        let scene = crate::load::load_scene(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/cornell-box.xml"),
            &[],
        )
        .unwrap();
        let mask = crate::prepare::buffers::build(&scene).unwrap().features;
        let all = pruned(&words, mask, 1).unwrap();
        for kept in [&["entry::render", "entry::resolve"][..], &["entry::light"]] {
            let some = pruned_to(&words, mask, 1, kept).unwrap();
            let names: Vec<String> = crate::backend::spirv::instructions(&some)
                .filter(|i| i.1 == 15)
                .map(|(at, _, len)| {
                    let bytes: Vec<u8> =
                        some[at + 3..at + len].iter().flat_map(|w| w.to_le_bytes()).collect();
                    String::from_utf8_lossy(&bytes).split('\0').next().unwrap().to_string()
                })
                .collect();
            assert_eq!(names, kept, "the entry points kept");
            assert!(some.len() < all.len(), "{} words against {}", some.len(), all.len());
            for entry in kept {
                let (a, b) = (
                    through_naga(&all, entry, [mask, 1]).unwrap(),
                    through_naga(&some, entry, [mask, 1]).unwrap(),
                );
                // The same code, instruction by instruction. Naga numbers the types in the order it
                // meets them, so ids and the type section's order may differ; and where any entry
                // point of a module uses a storage buffer atomically, naga makes every access to it
                // atomic (light tracing's splats make the render entry point's plain loads and
                // stores of the splat buffer relaxed atomics in the whole module; alone they stay the
                // plain accesses the kernel wrote).
                let body = |m: &[u32]| -> Vec<(u32, usize)> {
                    let all: Vec<(usize, u32, usize)> = crate::backend::spirv::instructions(m).collect();
                    let first = all.iter().position(|i| i.1 == 54).unwrap();
                    let plain = |(op, len)| match op {
                        227 => (61, 4), // OpAtomicLoad: OpLoad
                        228 => (62, 3), // OpAtomicStore: OpStore
                        _ => (op, len),
                    };
                    all[first..].iter().map(|i| plain((i.1, i.2))).collect()
                };
                assert!(body(&a) == body(&b), "{entry}: {} words against {}", b.len(), a.len());
            }
            // Negative control: an entry point left out is not there to build.
            assert!(through_naga(&some, "entry::cache_camera", [mask, 1]).is_err());
        }
    }
}
