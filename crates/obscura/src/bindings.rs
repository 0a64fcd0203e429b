//! The bind-group plan of the AO compute passes, shared by Rust and WGSL (docs/ARCHITECTURE.md):
//! group 0 the frame, 1 the estimator, 2 the hidden-depth source, 3 the schedule (WebGPU's default
//! limit is four groups). Every binding has a name here; [`wgsl_constants`] writes them as WGSL
//! `const`s in front of every composed shader, which uses them in its attributes
//! (`@group(GROUP_SOURCE) @binding(SOURCE_SD_NEAR)`), and every pipeline gets explicit layouts built
//! from the same constants. A shader and its layout that disagree fail at pipeline creation, and
//! the shader-validation test checks every technique row without a GPU.

/// Bind group indices, one per axis.
pub const GROUP_FRAME: u32 = 0;
/// Group 1: the estimator's parameters (its uniform, and a table for some).
pub const GROUP_ESTIMATOR: u32 = 1;
/// Group 2: the hidden-depth source's resources (second depth layer, BVH, stochastic depth maps).
pub const GROUP_SOURCE: u32 = 2;
/// Group 3: the schedule's buffers (two-phase), or a pass's own parameters and output in its place.
pub const GROUP_SCHEDULE: u32 = 3;
/// How many bind groups a pipeline layout has (WebGPU's default `maxBindGroups`).
pub const GROUP_COUNT: usize = 4;

/// Group 0, the frame (`shaders/frame/frame.wgsl`).
pub const FRAME_VIEW: u32 = 0;
/// The first depth layer: `R32Float` linear depth (−z, world units, 0 = background).
pub const FRAME_DEPTH: u32 = 1;
/// The view-space normals of the first layer.
pub const FRAME_NORMALS: u32 = 2;
/// The AO image the pass writes (write-only `r32float` storage texture, 1 = unoccluded).
pub const FRAME_AO_OUT: u32 = 3;
/// The bent normals the pass writes with `bent_normals` (write-only `rgba16float` storage texture,
/// view-space unit xyz; a 1×1 texture nobody writes otherwise).
pub const FRAME_BENT_OUT: u32 = 4;
/// The rays each visible pixel may cast this frame under a ray budget (`R32Uint`, read by the
/// hemisphere estimator with `hemisphere.ray_budget`, written by `filter::ray_budget`; a 1×1
/// texture nobody reads otherwise).
pub const FRAME_RAY_GRANT: u32 = 5;

/// Group 1, the estimator's parameters.
pub const ESTIMATOR_PARAMS: u32 = 0;
/// A table the estimator reads per pixel, where it has one (`estimators::layout_entries`): a
/// one-row `Rg32Float` texture (GTAO-VB: its sectors' summed directions per byte of a mask). A
/// texture rather than a buffer: the ray-traced sources use the eight storage buffers WebGPU
/// allows a stage, and a uniform array indexed per pixel is slow on NVIDIA.
pub const ESTIMATOR_TABLE: u32 = 1;

/// Group 2, the source. Each source uses its own bindings; a layout holds only one source's.
pub const SOURCE_SECOND_DEPTH: u32 = 0;
/// Column rays: the `RayCamera` uniform (camera-to-world matrix and near plane) of
/// `shaders/sources/column_trace.wgsl`.
pub const SOURCE_RAY_CAMERA: u32 = 0;
/// Column rays: the atomic count of rays whose BVH traversal overflowed its stack.
pub const SOURCE_STACK_OVERFLOWS: u32 = 1;
/// The six bindings of `shaders/common/bvh.wgsl` start here.
pub const SOURCE_BVH: u32 = 2;
/// BVH rays, two-phase phase 1: the drawn triangle each framebuffer pixel shows + 1 (`R32Uint`,
/// 0 = none; the G-buffer's visibility buffer), for the blocked proof of
/// `shaders/sources/bvh_rays_proof.wgsl` (a 1×1 stand-in turns it off).
pub const SOURCE_VISIBLE_TRIANGLES: u32 = 8;
/// BVH rays, two-phase phase 1: the drawn triangles those indices name.
pub const SOURCE_DRAWN_TRIANGLES: u32 = 9;
/// Stochastic depth: the projection's near plane (`vec4`, in `x`), to turn the maps' reversed-Z
/// values back into linear depth.
pub const SOURCE_SD_NEAR: u32 = 0;
/// Stochastic depth: one `u32` per framebuffer pixel, set to 1 by the two-phase schedule's
/// phase 1 where the map must be rasterised.
pub const SOURCE_SD_REQUEST: u32 = 1;
/// Stochastic depth: the map's depths (a storage buffer, S per pixel); the raster map binds its
/// `SdRaster` again at the next binding, for its width.
pub const SOURCE_SD_MAPS: u32 = 2;
/// Ray-traced stochastic depth: two `u32` per framebuffer pixel, the depth interval phase 1's
/// samples need there (`shaders/sources/ray_stochastic_depth/request.wgsl`).
pub const SOURCE_SD_INTERVAL: u32 = 6;
/// The multi-view schedule's second view: the camera's view and the transform into the second
/// (`shaders/schedules/multiview/point.wgsl`), after the maps' bindings.
pub const SOURCE_MULTIVIEW: u32 = 12;
/// Depth pyramid: each level's texel size and extent (`PyramidParams`).
pub const SOURCE_PYRAMID_PARAMS: u32 = 0;
/// Depth pyramid: levels 1 … L − 1 as the layers of one array texture.
pub const SOURCE_PYRAMID_LEVELS: u32 = 1;

/// Group 3, the two-phase schedule.
pub const SCHEDULE_PIXELS: u32 = 0;
/// The compacted list of flagged pixel indices phase 2 works through, after their count
/// (`WorkList` in schedules/two_phase.wgsl).
pub const SCHEDULE_WORK_LIST: u32 = 1;
/// Group 3 of the interleaved schedule: the 16 quarter-resolution depth layers.
pub const SCHEDULE_DEPTH_LAYERS: u32 = 0;
/// Group 0 of the two-phase schedule's indirect-arguments pass: the work list (its count).
pub const INDIRECT_WORK_LIST: u32 = 0;
/// The three `u32` workgroup counts of phase 2's indirect dispatch, written by the pass.
pub const INDIRECT_DISPATCH: u32 = 1;
/// Group 3 of the ground truth (its own parameters and output in the schedule's place).
pub const REFERENCE_PARAMS: u32 = 0;
/// Per visible pixel: the AO (`vao` model) or the occlusion summed over the rays so far
/// (`hemisphere` model).
pub const REFERENCE_OUT: u32 = 1;

/// Every named binding, for [`wgsl_constants`].
const NAMED: &[(&str, u32)] = &[
    ("GROUP_FRAME", GROUP_FRAME),
    ("GROUP_ESTIMATOR", GROUP_ESTIMATOR),
    ("GROUP_SOURCE", GROUP_SOURCE),
    ("GROUP_SCHEDULE", GROUP_SCHEDULE),
    ("FRAME_VIEW", FRAME_VIEW),
    ("FRAME_DEPTH", FRAME_DEPTH),
    ("FRAME_NORMALS", FRAME_NORMALS),
    ("FRAME_AO_OUT", FRAME_AO_OUT),
    ("FRAME_BENT_OUT", FRAME_BENT_OUT),
    ("FRAME_RAY_GRANT", FRAME_RAY_GRANT),
    ("ESTIMATOR_PARAMS", ESTIMATOR_PARAMS),
    ("ESTIMATOR_TABLE", ESTIMATOR_TABLE),
    ("SOURCE_SECOND_DEPTH", SOURCE_SECOND_DEPTH),
    ("SOURCE_RAY_CAMERA", SOURCE_RAY_CAMERA),
    ("SOURCE_STACK_OVERFLOWS", SOURCE_STACK_OVERFLOWS),
    ("SOURCE_BVH", SOURCE_BVH),
    ("SOURCE_VISIBLE_TRIANGLES", SOURCE_VISIBLE_TRIANGLES),
    ("SOURCE_DRAWN_TRIANGLES", SOURCE_DRAWN_TRIANGLES),
    ("SOURCE_SD_NEAR", SOURCE_SD_NEAR),
    ("SOURCE_SD_REQUEST", SOURCE_SD_REQUEST),
    ("SOURCE_SD_MAPS", SOURCE_SD_MAPS),
    ("SOURCE_SD_INTERVAL", SOURCE_SD_INTERVAL),
    ("SOURCE_MULTIVIEW", SOURCE_MULTIVIEW),
    ("SOURCE_PYRAMID_PARAMS", SOURCE_PYRAMID_PARAMS),
    ("SOURCE_PYRAMID_LEVELS", SOURCE_PYRAMID_LEVELS),
    ("SCHEDULE_PIXELS", SCHEDULE_PIXELS),
    ("SCHEDULE_WORK_LIST", SCHEDULE_WORK_LIST),
    ("SCHEDULE_DEPTH_LAYERS", SCHEDULE_DEPTH_LAYERS),
    ("INDIRECT_WORK_LIST", INDIRECT_WORK_LIST),
    ("INDIRECT_DISPATCH", INDIRECT_DISPATCH),
    ("REFERENCE_PARAMS", REFERENCE_PARAMS),
    ("REFERENCE_OUT", REFERENCE_OUT),
];

/// The binding names as WGSL constants (`const SOURCE_BVH: u32 = 2u;`).
pub fn wgsl_constants() -> String {
    let mut out = String::from("// Binding names, generated from src/bindings.rs.\n");
    for (name, value) in NAMED {
        out += &format!("const {name}: u32 = {value}u;\n");
    }
    out
}

/// Layout entries, all visible to compute.
pub mod entry {
    fn compute(binding: u32, ty: wgpu::BindingType) -> wgpu::BindGroupLayoutEntry {
        wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        }
    }

    /// A uniform buffer.
    pub fn uniform(binding: u32) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        )
    }

    /// A storage buffer, `read_only` or read-write.
    pub fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        )
    }

    /// A float texture read with `textureLoad` (not filterable: R32Float needs no feature).
    pub fn texture(binding: u32) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
        )
    }

    /// An unsigned-integer texture read with `textureLoad`.
    pub fn texture_uint(binding: u32) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Uint,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
        )
    }

    /// A float texture array (the scene's alpha-mask atlas).
    pub fn texture_array(binding: u32) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2Array,
                multisampled: false,
            },
        )
    }

    /// A depth texture, multisampled or not.
    pub fn depth_texture(binding: u32, multisampled: bool) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Depth,
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled,
            },
        )
    }

    /// A write-only `r32float` storage texture array.
    pub fn storage_texture_r32f_array(binding: u32) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format: wgpu::TextureFormat::R32Float,
                view_dimension: wgpu::TextureViewDimension::D2Array,
            },
        )
    }

    /// A write-only 2D storage texture of `format`.
    pub fn storage_texture(
        binding: u32,
        format: wgpu::TextureFormat,
    ) -> wgpu::BindGroupLayoutEntry {
        compute(
            binding,
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
        )
    }

    /// A write-only `rgba16float` storage texture.
    pub fn storage_texture_rgba16f(binding: u32) -> wgpu::BindGroupLayoutEntry {
        storage_texture(binding, wgpu::TextureFormat::Rgba16Float)
    }

    /// A write-only `r32float` storage texture.
    pub fn storage_texture_r32f(binding: u32) -> wgpu::BindGroupLayoutEntry {
        storage_texture(binding, wgpu::TextureFormat::R32Float)
    }
}

/// A bind group layout from `entries`.
pub fn layout(
    device: &wgpu::Device,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
) -> wgpu::BindGroupLayout {
    crate::gpu::kept_bind_group_layout(device, entries, || {
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries,
        })
    })
}

/// A bind group from `(binding, resource)` pairs: every binding by name, never by position.
pub fn group(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    resources: &[(u32, wgpu::BindingResource)],
) -> wgpu::BindGroup {
    crate::gpu::bind_group_at(device, label, layout, resources)
}

/// The frame group's layout: view, depth and normals, and (`with_output`) the AO image.
pub fn frame_layout(device: &wgpu::Device, with_output: bool) -> wgpu::BindGroupLayout {
    let mut entries = vec![
        entry::uniform(FRAME_VIEW),
        entry::texture(FRAME_DEPTH),
        entry::texture(FRAME_NORMALS),
    ];
    if with_output {
        entries.push(entry::storage_texture_r32f(FRAME_AO_OUT));
        entries.push(entry::storage_texture_rgba16f(FRAME_BENT_OUT));
        entries.push(entry::texture_uint(FRAME_RAY_GRANT));
    }
    layout(device, "frame", &entries)
}

/// The layouts of a pipeline, placed at their groups (`None` where a pass binds nothing).
pub fn by_group<'a>(
    layouts: &[(u32, &'a wgpu::BindGroupLayout)],
) -> [Option<&'a wgpu::BindGroupLayout>; GROUP_COUNT] {
    let mut out = [None; GROUP_COUNT];
    for &(group, layout) in layouts {
        out[group as usize] = Some(layout);
    }
    out
}

/// A compute pipeline with entry point `main` over explicit layouts, one per group (`None`: the
/// pass binds nothing in that group).
pub fn compute_pipeline(
    device: &wgpu::Device,
    label: &str,
    source: &str,
    constants: &[(&str, f64)],
    layouts: &[Option<&wgpu::BindGroupLayout>],
) -> wgpu::ComputePipeline {
    let module = crate::gpu::shader_module(device, label, source);
    let layout = crate::gpu::kept_pipeline_layout(device, layouts, || {
        device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: layouts,
            immediate_size: 0,
        })
    });
    crate::gpu::pipeline_from_module(device, label, &module, constants, Some(&layout))
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_binding_name_is_unique() {
        for (i, (a, _)) in super::NAMED.iter().enumerate() {
            assert!(super::NAMED[i + 1..].iter().all(|(b, _)| a != b), "{a}");
        }
    }
}
