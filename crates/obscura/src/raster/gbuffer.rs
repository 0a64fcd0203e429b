//! The G-buffer pass (`shaders/gbuffer.wgsl`): linear depth (`R32Float`) and camera-facing
//! view-space face normals (`Rgba16Float`) over the guard-banded framebuffer, with a reversed-Z
//! `Depth32Float` buffer for visibility; when asked for, a second depth layer by depth peeling
//! (`shaders/depth_peel.wgsl`, seed 000 §2.1); and base colour (`Rgba8UnormSrgb`) only on request
//! ([`GBuffer::render_albedo`], for composites), by its own pass with the same draws.
//!
//! The back-face-culled triangles (never alpha-tested: alpha-tested materials keep their back
//! faces) are drawn first with a fragment shader without `discard`, so the hardware may test their
//! depth before shading them; the others may discard.

use super::gpu_scene::GpuScene;
use crate::gpu::PassProfiler;
use crate::shaders;
use crate::view::FrameView;
use wgpu::util::DeviceExt;

/// Linear depth: −z in world units, 0 = background (also the peeled second layer's format).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// View-space unit normals facing the camera in xyz (0 = background).
pub const NORMAL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Base colour for composites (white where nothing is drawn).
pub const ALBEDO_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const Z_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// `Camera` of gbuffer.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct CameraUniform {
    view: [[f32; 4]; 4],
    projection: [[f32; 4]; 4],
}

impl CameraUniform {
    pub fn new(view: &FrameView) -> Self {
        Self {
            view: view.view_matrix().to_cols_array_2d(),
            projection: view.projection().to_cols_array_2d(),
        }
    }
}

/// The depth-peeling pass: the second layer and what it needs.
struct Peel {
    /// Back faces culled / kept, as the main pass.
    pipelines: [wgpu::RenderPipeline; 2],
    params: wgpu::Buffer,
    depth: wgpu::Texture,
}

/// The G-buffer's targets and pipelines over the guard-banded framebuffer: what
/// [`crate::AmbientOcclusion`] reads for our own scenes ([`crate::Renderer`]).
pub struct GBuffer {
    /// Linear depth ([`DEPTH_FORMAT`]): −z in world units, 0 = background.
    pub depth: wgpu::Texture,
    /// View-space normals facing the camera ([`NORMAL_FORMAT`]), face or shading normals.
    pub normals: wgpu::Texture,
    /// Base colour ([`ALBEDO_FORMAT`]), written only by [`GBuffer::render_albedo`].
    pub albedo: wgpu::Texture,
    z: wgpu::Texture,
    /// Back faces culled (no alpha test) / kept (double-sided and alpha-tested materials).
    pipelines: [wgpu::RenderPipeline; 2],
    /// The base-colour pass, the same way.
    albedo_pipelines: [wgpu::RenderPipeline; 2],
    camera: wgpu::Buffer,
    peel: Option<Peel>,
}

impl GBuffer {
    /// Targets for a framebuffer of `width`×`height` (guard band included). With
    /// `peel_separation`, a second depth layer is peeled too: the nearest surface more than that
    /// many world units behind the first. `shading_normals`: the normals target interpolates the
    /// scene's vertex normals ([`GpuScene::shading_normals`]) instead of taking face normals.
    pub fn new(
        device: &wgpu::Device,
        width: u32,
        height: u32,
        peel_separation: Option<f32>,
        shading_normals: bool,
    ) -> Self {
        let target = |label, format| {
            crate::gpu::texture_2d(
                device,
                label,
                width,
                height,
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        let source = shaders::with_common(
            &[shaders::MATERIAL, shaders::VERTEX_NORMAL, shaders::GBUFFER],
            shaders::DEPTH_PEEL,
        );
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("gbuffer"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let depth = wgpu::DepthStencilState {
            format: Z_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        };
        let scene_layout = scene_layout(device);
        let normal_constants = [("SHADING_NORMALS", f64::from(u8::from(shading_normals)))];
        let pipeline = |cull_mode,
                        fragment: &str,
                        targets: &[Option<wgpu::ColorTargetState>],
                        layout: Option<&wgpu::PipelineLayout>| {
            ScenePipeline {
                layout,
                module: &module,
                cull_mode,
                depth_stencil: depth.clone(),
                multisample: Default::default(),
                fragment,
                targets,
                // Only the G-buffer's own fragments write normals.
                constants: if fragment.starts_with("fs_peel") || fragment == "fs_albedo" {
                    &[]
                } else {
                    &normal_constants
                },
            }
            .create(device)
        };
        let gbuffer_targets = [DEPTH_FORMAT, NORMAL_FORMAT].map(|f| Some(f.into()));
        let albedo_targets = [Some(ALBEDO_FORMAT.into())];
        let peel = peel_separation.map(|separation| {
            let targets = [Some(DEPTH_FORMAT.into())];
            Peel {
                pipelines: [Some(wgpu::Face::Back), None]
                    .map(|cull| pipeline(cull, "fs_peel", &targets, None)),
                params: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("peel params"),
                    contents: bytemuck::cast_slice(&[separation, 0.0, 0.0, 0.0]),
                    usage: wgpu::BufferUsages::UNIFORM,
                }),
                depth: target("second depth layer", DEPTH_FORMAT),
            }
        });
        Self {
            depth: target("linear depth", DEPTH_FORMAT),
            normals: target("normals", NORMAL_FORMAT),
            albedo: target("albedo", ALBEDO_FORMAT),
            z: target("z", Z_FORMAT),
            pipelines: [
                pipeline(
                    Some(wgpu::Face::Back),
                    "fs_opaque",
                    &gbuffer_targets,
                    Some(&scene_layout),
                ),
                pipeline(None, "fs_main", &gbuffer_targets, Some(&scene_layout)),
            ],
            albedo_pipelines: [Some(wgpu::Face::Back), None]
                .map(|cull| pipeline(cull, "fs_albedo", &albedo_targets, Some(&scene_layout))),
            camera: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gbuffer camera"),
                size: std::mem::size_of::<CameraUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            peel,
        }
    }

    /// The second depth layer (linear, 0 = none), when depth peeling was asked for.
    pub fn second_layer(&self) -> Option<&wgpu::Texture> {
        self.peel.as_ref().map(|p| &p.depth)
    }

    /// Rasterise `scene` seen through `view`. Timings: `gbuffer`, and `depth_peel` when peeling.
    pub fn render(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        view: &FrameView,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        let camera = CameraUniform::new(view);
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(&camera));
        let targets = [
            (&self.depth, wgpu::Color::TRANSPARENT),
            (&self.normals, wgpu::Color::TRANSPARENT),
        ];
        let resources = scene_resources(&self.camera, scene, Vec::new());
        self.draw(
            device,
            encoder,
            scene,
            &self.pipelines,
            &resources,
            &targets,
            "gbuffer",
            profiler.as_deref_mut(),
        );
        if let Some(peel) = &self.peel {
            let first = self.depth.create_view(&Default::default());
            let resources = scene_resources(
                &self.camera,
                scene,
                vec![
                    wgpu::BindingResource::TextureView(&first),
                    peel.params.as_entire_binding(),
                ],
            );
            let targets = [(&peel.depth, wgpu::Color::TRANSPARENT)];
            self.draw(
                device,
                encoder,
                scene,
                &peel.pipelines,
                &resources,
                &targets,
                "depth_peel",
                profiler,
            );
        }
    }

    /// Base colour of the last [`GBuffer::render`]'s view into [`GBuffer::albedo`] (white where
    /// nothing is): the same draws and depth test, so the same fragments win.
    pub fn render_albedo(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
    ) {
        let resources = scene_resources(&self.camera, scene, Vec::new());
        let targets = [(&self.albedo, wgpu::Color::WHITE)];
        self.draw(
            device,
            encoder,
            scene,
            &self.albedo_pipelines,
            &resources,
            &targets,
            "albedo",
            None,
        );
    }

    /// One raster pass of the whole scene: culled triangles, then the ones that keep back faces.
    #[allow(clippy::too_many_arguments)]
    fn draw(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        pipelines: &[wgpu::RenderPipeline; 2],
        resources: &[wgpu::BindingResource],
        targets: &[(&wgpu::Texture, wgpu::Color)],
        name: &str,
        profiler: Option<&mut PassProfiler>,
    ) {
        let bind_groups = pipelines
            .each_ref()
            .map(|p| crate::gpu::bind_group(device, name, &p.get_bind_group_layout(0), resources));
        let views: Vec<_> = targets
            .iter()
            .map(|(t, _)| t.create_view(&Default::default()))
            .collect();
        let attachments: Vec<_> = views
            .iter()
            .zip(targets)
            .map(|(view, (_, clear))| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(*clear),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let z_view = self.z.create_view(&Default::default());
        let mut profiler = profiler;
        let timestamp_writes = profiler.as_deref_mut().map(|p| p.render_pass(name));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(name),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &z_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        if let Some(p) = profiler.as_deref_mut() {
            p.begin_fragments(&mut pass, name);
        }
        draw_scene(&mut pass, scene, pipelines, &bind_groups);
        if let Some(p) = profiler {
            p.end_fragments(&mut pass);
        }
    }
}

/// Draw the whole scene: the back-face-culled triangles with `pipelines[0]`, the ones that keep
/// back faces with `pipelines[1]`.
pub(crate) fn draw_scene(
    pass: &mut wgpu::RenderPass,
    scene: &GpuScene,
    pipelines: &[wgpu::RenderPipeline; 2],
    bind_groups: &[wgpu::BindGroup; 2],
) {
    let ranges = [
        0..scene.culled_count,
        scene.culled_count..scene.triangle_count,
    ];
    for ((pipeline, bind_group), range) in pipelines.iter().zip(bind_groups).zip(ranges) {
        if range.is_empty() {
            continue;
        }
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(range.start * 3..range.end * 3, 0..1);
    }
}

/// Bindings 0–5 of gbuffer.wgsl (camera and scene), then `extra` from binding 6 on.
pub(crate) fn scene_resources<'a>(
    camera: &'a wgpu::Buffer,
    scene: &'a GpuScene,
    extra: Vec<wgpu::BindingResource<'a>>,
) -> Vec<wgpu::BindingResource<'a>> {
    let mut r = vec![
        camera.as_entire_binding(),
        scene.positions.as_entire_binding(),
        scene.attributes.as_entire_binding(),
        scene.triangles.as_entire_binding(),
        scene.materials.as_entire_binding(),
        wgpu::BindingResource::TextureView(&scene.textures),
    ];
    r.extend(extra);
    r
}

/// The explicit layout of gbuffer.wgsl's group 0 (camera and scene, bindings 0–5, the order of
/// [`scene_resources`]): the G-buffer's fragment shaders use different subsets of it, which
/// automatic layouts would leave out.
pub(crate) fn scene_layout(device: &wgpu::Device) -> wgpu::PipelineLayout {
    let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
    let storage = |binding| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let entries = [
        wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: stages,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        },
        storage(1),
        storage(2),
        storage(3),
        storage(4),
        wgpu::BindGroupLayoutEntry {
            binding: 5,
            visibility: stages,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2Array,
                multisampled: false,
            },
            count: None,
        },
    ];
    let group = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("scene"),
        entries: &entries,
    });
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("scene"),
        bind_group_layouts: &[Some(&group)],
        immediate_size: 0,
    })
}

/// A raster pipeline over the scene's vertices (`vs_main` of gbuffer.wgsl, pulled from storage).
pub(crate) struct ScenePipeline<'a> {
    /// `None`: an automatic layout (passes that bind more than the scene).
    pub layout: Option<&'a wgpu::PipelineLayout>,
    pub module: &'a wgpu::ShaderModule,
    pub cull_mode: Option<wgpu::Face>,
    pub depth_stencil: wgpu::DepthStencilState,
    pub multisample: wgpu::MultisampleState,
    pub fragment: &'a str,
    pub targets: &'a [Option<wgpu::ColorTargetState>],
    /// Pipeline-overridable constants of both stages (e.g. gbuffer.wgsl's `SHADING_NORMALS`).
    pub constants: &'a [(&'a str, f64)],
}

impl ScenePipeline<'_> {
    pub fn create(self, device: &wgpu::Device) -> wgpu::RenderPipeline {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(self.fragment),
            layout: self.layout,
            vertex: wgpu::VertexState {
                module: self.module,
                entry_point: Some("vs_main"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: self.constants,
                    ..Default::default()
                },
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState {
                cull_mode: self.cull_mode,
                ..Default::default()
            },
            depth_stencil: Some(self.depth_stencil),
            multisample: self.multisample,
            fragment: Some(wgpu::FragmentState {
                module: self.module,
                entry_point: Some(self.fragment),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: self.constants,
                    ..Default::default()
                },
                targets: self.targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}
