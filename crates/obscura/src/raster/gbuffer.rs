//! The G-buffer (`shaders/raster/gbuffer.wgsl`): linear depth (`R32Float`) and camera-facing
//! view-space face normals (`Rgba16Float`) over the guard-banded framebuffer; when asked for, a
//! second depth layer by depth peeling (`shaders/raster/depth_peel.wgsl`, seed 000 §2.1); and base colour
//! (`Rgba8UnormSrgb`) only on request ([`GBuffer::render_albedo`], for composites), by its own
//! pass with the same draws.
//!
//! Two passes make depth and normals: a raster pass that stores only the visible triangle per
//! pixel (a visibility buffer, `R32Uint`, with a reversed-Z `Depth32Float` buffer), then a compute
//! pass (`shaders/raster/gbuffer_resolve.wgsl`) that computes the surface point at each pixel centre from
//! that triangle. Rasterisation is the scarce resource on the compute GPUs we measure on
//! (BENCHMARKS.md, issue 16); compute is not. The triangles that are never alpha-tested are drawn
//! first with a fragment shader without `discard`, so the hardware may test their depth before
//! shading them; the alpha-tested ones last. Within each group the visibility pass draws the
//! scene's chunks nearest first and skips those outside the view ([`super::chunks`]), so fewer
//! hidden fragments are shaded. Triangles are culled in compute first (`raster::triangle_cull`);
//! the visibility pass with occlusion culling in two phases (last frame's visible triangles, then
//! the others their depths do not hide).

use super::chunks::{self, Draw};
use super::gpu_scene::GpuScene;
use super::triangle_cull::{CullList, TriangleCull};
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
/// Depth peeling's own depth buffer, which only picks the nearest of the fragments its shader
/// keeps (the shader decides what lies behind the first layer, from the linear depth): 24 bits
/// made the peeling pass 11–13 % faster than the G-buffer's 32-bit buffer on an H200
/// (BENCHMARKS.md, issue 16). Of two kept fragments within one 24-bit step of each other the
/// first drawn wins, so the peeled layer can lie that much (z²/near · 2⁻²⁴) behind the nearest;
/// `tests::depth_peeling_in_24_bits_keeps_the_layer_within_a_step` holds it to two such steps.
const PEEL_Z_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth24Plus;
/// The visible triangle's index + 1 per pixel. Never cleared: where the pass's depth buffer holds
/// its clear value (0) no triangle was drawn, and the resolves read it there as background. Why:
/// on the H200 clearing this target cost 0.15 ms of the visibility pass's 1.07 on Crytek Sponza
/// (BENCHMARKS.md, issue 16), and the depth buffer is cleared anyway.
const VISIBILITY_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;

/// Where the visibility pass leaves each pixel's visible triangle.
enum Visibility {
    /// A colour target ([`VISIBILITY_FORMAT`]) beside the depth buffer.
    Target(wgpu::Texture),
    /// No colour target: a storage buffer of one 64-bit word per pixel that the fragments fill by
    /// `atomicMax` and the resolve empties (`shaders/raster/gbuffer_visibility_atomic.wgsl`), where the
    /// device has [`visibility_words_available`].
    Words(wgpu::Buffer),
}

/// Whether this device's visibility pass can store by 64-bit atomics instead of a colour target
/// (wgpu features `SHADER_INT64`, `SHADER_INT64_ATOMIC_MIN_MAX` and `SHADER_EARLY_DEPTH_TEST`,
/// requested by [`crate::Gpu`] where the adapter has them), at sizes whose 8 bytes a pixel fit
/// one storage binding. Either way the G-buffer is the same.
pub fn visibility_words_available(device: &wgpu::Device) -> bool {
    device.features().contains(
        wgpu::Features::SHADER_INT64
            | wgpu::Features::SHADER_INT64_ATOMIC_MIN_MAX
            | wgpu::Features::SHADER_EARLY_DEPTH_TEST,
    )
}

/// Whether the words of a `width`×`height` framebuffer fit one storage binding of a device
/// with `limits` (not at 4096 × 4096 + 1 px on lavapipe's 128 MiB, say); larger framebuffers
/// get the colour target.
fn visibility_words_fit(limits: &wgpu::Limits, width: u32, height: u32) -> bool {
    let bytes = visibility_words_bytes(width, height);
    bytes <= limits.max_storage_buffer_binding_size && bytes <= limits.max_buffer_size
}

/// The bytes of the words of a `width`×`height` framebuffer: 8 a pixel, in whole 2×2 quads
/// (`shaders/raster/visibility_words_index.wgsl`), so an odd side is rounded up.
fn visibility_words_bytes(width: u32, height: u32) -> u64 {
    8 * u64::from(width.next_multiple_of(2)) * u64::from(height.next_multiple_of(2))
}

#[cfg(test)]
thread_local! {
    /// Tests: G-buffers made on this thread use the colour target even where the device has
    /// the atomics (the twin of [`Visibility::Words`]).
    pub(crate) static VISIBILITY_TARGET_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// Tests: G-buffers made on this thread peel with this depth format instead of
    /// [`PEEL_Z_FORMAT`] (the 32-bit twin).
    pub(crate) static PEEL_Z_OVERRIDE: std::cell::Cell<Option<wgpu::TextureFormat>> = const { std::cell::Cell::new(None) };
}

/// Depth peeling's depth format: [`PEEL_Z_FORMAT`] (in tests, the thread's override).
fn peel_z_format() -> wgpu::TextureFormat {
    #[cfg(test)]
    if let Some(format) = PEEL_Z_OVERRIDE.with(|f| f.get()) {
        return format;
    }
    PEEL_Z_FORMAT
}

/// `Camera` of gbuffer.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct CameraUniform {
    view: [[f32; 4]; 4],
    projection: [[f32; 4]; 4],
    inverse_projection: [[f32; 4]; 4],
}

impl CameraUniform {
    pub fn new(view: &FrameView) -> Self {
        let projection = view.projection();
        Self {
            view: view.view_matrix().to_cols_array_2d(),
            projection: projection.to_cols_array_2d(),
            // Inverted in f64: the resolve's pixel rays are as exact as the projection allows.
            inverse_projection: projection.as_dmat4().inverse().as_mat4().to_cols_array_2d(),
        }
    }
}

/// The depth-peeling pass: the second layer and what it needs.
struct Peel {
    /// Back faces culled / double-sided / alpha-tested, as the visibility pass.
    pipelines: [wgpu::RenderPipeline; 3],
    params: wgpu::Buffer,
    /// The peeled layer's triangle per pixel ([`VISIBILITY_FORMAT`]).
    visibility: wgpu::Texture,
    /// Its linear depth from the triangle (`shaders/raster/depth_peel_resolve.wgsl`).
    resolve: wgpu::ComputePipeline,
    depth: wgpu::Texture,
    /// The pass's depth buffer ([`PEEL_Z_FORMAT`]); the G-buffer's own keeps the first layer.
    z: wgpu::Texture,
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
    /// The visible triangle per pixel.
    visibility: Visibility,
    /// The visibility pass: back faces culled / double-sided / alpha-tested
    /// ([`GpuScene`]'s three groups).
    visibility_pipelines: [wgpu::RenderPipeline; 3],
    /// Depth and normals from the visibility buffer.
    resolve: wgpu::ComputePipeline,
    /// The base-colour pass, the same way.
    albedo_pipelines: [wgpu::RenderPipeline; 3],
    camera: wgpu::Buffer,
    peel: Option<Peel>,
    /// The triangles each frame's passes draw (the visibility pass, depth peeling, base colour).
    cull: TriangleCull,
    /// The drawn triangle each pixel shows + 1 (`R32Uint`, 0 = none), written by the resolve
    /// where kept ([`GBuffer::visible_triangles`]); 1×1 and never written otherwise.
    triangles: wgpu::Texture,
    keep_triangles: bool,
}

impl GBuffer {
    /// Targets for a framebuffer of `width`×`height` (guard band included). With
    /// `peel_separation`, a second depth layer is peeled too: the nearest surface more than that
    /// many world units behind the first. `scene`: the scene [`GBuffer::render`] will draw; where
    /// it [has shading normals](GpuScene::shading_normals), the normals target interpolates them
    /// instead of taking face normals. With `keep_triangles`, the resolve also keeps the
    /// triangle each pixel shows ([`GBuffer::visible_triangles`]).
    pub fn new(
        device: &wgpu::Device,
        (width, height): (u32, u32),
        peel_separation: Option<f32>,
        keep_triangles: bool,
        scene: &GpuScene,
    ) -> Result<Self, crate::gpu::GpuError> {
        // The occlusion culling's pyramid is the one storage buffer here that grows with the
        // framebuffer (the visibility words fall back to a colour target where they do not fit).
        crate::gpu::check_storage_size(
            &device.limits(),
            "occlusion pyramid",
            super::occlusion_pyramid::bytes(width, height),
        )?;
        let target_with = |label, format, extra| {
            crate::gpu::texture_2d(
                device,
                label,
                width,
                height,
                format,
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
                    | extra,
            )
        };
        let target = |label, format| target_with(label, format, wgpu::TextureUsages::empty());
        let scene_shaders = [shaders::MATERIAL, shaders::VERTEX_NORMAL, shaders::GBUFFER];
        let module = &crate::gpu::checked_module(
            device,
            "gbuffer",
            &shaders::with_common(&scene_shaders, shaders::DEPTH_PEEL),
        );
        let depth = wgpu::DepthStencilState {
            format: Z_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater),
            stencil: Default::default(),
            bias: Default::default(),
        };
        let gbuffer_layout = scene_layout(device, &[]);
        let shading_normals = scene.shading_normals;
        let normal_constants = [("SHADING_NORMALS", f64::from(u8::from(shading_normals)))];
        let visibility_targets = [Some(VISIBILITY_FORMAT.into())];
        let albedo_targets = [Some(ALBEDO_FORMAT.into())];
        let words = visibility_words_available(device)
            && visibility_words_fit(&device.limits(), width, height);
        #[cfg(test)]
        let words = words && !VISIBILITY_TARGET_ONLY.with(|v| v.get());
        // The resolves, after the header that reads the pass's visibility (`visible_triangle`).
        let resolve_pipeline = |label, main, load: &[&str], constants: &[(&str, f64)]| {
            crate::gpu::compute_pipeline_with(
                device,
                label,
                &shaders::with_common(
                    &[
                        &[
                            shaders::MATERIAL,
                            shaders::VERTEX_NORMAL,
                            shaders::GBUFFER,
                            shaders::GBUFFER_RESOLVE,
                        ],
                        load,
                    ]
                    .concat(),
                    main,
                ),
                constants,
            )
        };
        let peel = peel_separation.map(|separation| {
            // Depth peeling keeps its colour target: with words and no depth test it was slower
            // on Crytek Sponza (BENCHMARKS.md, issue 16), whose hidden layers all store.
            let layout = scene_layout(device, &behind_first_layer_entries());
            let peel_format = peel_z_format();
            let peel_depth = wgpu::DepthStencilState {
                format: peel_format,
                ..depth.clone()
            };
            let pipelines = group_pipelines(
                device,
                module,
                &peel_depth,
                ("fs_peel", "fs_peel_masked"),
                &visibility_targets,
                Some(&layout),
            );
            Peel {
                pipelines,
                params: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("peel params"),
                    contents: bytemuck::cast_slice(&[separation, 0.0, 0.0, 0.0]),
                    usage: wgpu::BufferUsages::UNIFORM,
                }),
                visibility: target("second layer visibility", VISIBILITY_FORMAT),
                resolve: resolve_pipeline(
                    "depth peel resolve",
                    shaders::DEPTH_PEEL_RESOLVE,
                    &[shaders::VISIBILITY_TARGET_LOAD],
                    &[],
                ),
                depth: target_with(
                    "second depth layer",
                    DEPTH_FORMAT,
                    wgpu::TextureUsages::STORAGE_BINDING,
                ),
                z: target("depth peeling z", peel_format),
            }
        });
        let (visibility, visibility_pipelines, visibility_load) = if words {
            // Its module on its own: 64-bit atomics need device features the other pipelines do
            // without. The words are binding 6, after the scene's; the framebuffer's width
            // gives each fragment's word.
            let constants = format!(
                "const VISIBILITY_WIDTH: u32 = {width}u;\nconst VISIBILITY_WORDS_BINDING: u32 = 6u;"
            );
            let module = crate::gpu::checked_module(
                device,
                "visibility words",
                &shaders::with_common(
                    &[
                        &scene_shaders[..],
                        &[
                            &constants,
                            shaders::VISIBILITY_WORDS_INDEX,
                            shaders::VISIBILITY_WORDS_STORE,
                        ],
                    ]
                    .concat(),
                    shaders::GBUFFER_VISIBILITY_ATOMIC,
                ),
            );
            let layout = scene_layout(
                device,
                &[(
                    wgpu::ShaderStages::FRAGMENT,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                )],
            );
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("visibility words"),
                size: visibility_words_bytes(width, height),
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            (
                Visibility::Words(buffer),
                group_pipelines(
                    device,
                    &module,
                    &depth,
                    ("fs_visibility_words", "fs_visibility_words_masked"),
                    &[],
                    Some(&layout),
                ),
                &[
                    shaders::VISIBILITY_WORDS_INDEX,
                    shaders::VISIBILITY_WORDS_LOAD,
                ][..],
            )
        } else {
            (
                Visibility::Target(target("visibility", VISIBILITY_FORMAT)),
                group_pipelines(
                    device,
                    module,
                    &depth,
                    ("fs_visibility", "fs_visibility_masked"),
                    &visibility_targets,
                    Some(&gbuffer_layout),
                ),
                &[shaders::VISIBILITY_TARGET_LOAD][..],
            )
        };
        let z = target("z", Z_FORMAT);
        let depth_target = target_with(
            "linear depth",
            DEPTH_FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING,
        );
        // Occlusion culling against the visibility pass's own depth buffer.
        let cull = TriangleCull::new(device, &scene.draw_ordered(), "triangle_cull", Some(&z));
        Ok(Self {
            depth: depth_target,
            normals: target_with(
                "normals",
                NORMAL_FORMAT,
                wgpu::TextureUsages::STORAGE_BINDING,
            ),
            albedo: target("albedo", ALBEDO_FORMAT),
            z,
            visibility,
            visibility_pipelines,
            resolve: resolve_pipeline(
                "gbuffer resolve",
                shaders::GBUFFER_RESOLVE_MAIN,
                visibility_load,
                &normal_constants,
            ),
            albedo_pipelines: [Some(wgpu::Face::Back), None, None].map(|cull_mode| {
                ScenePipeline {
                    layout: Some(&gbuffer_layout),
                    module,
                    cull_mode,
                    depth_stencil: depth.clone(),
                    multisample: Default::default(),
                    vertex: "vs_main",
                    fragment: "fs_albedo",
                    targets: &albedo_targets,
                }
                .create(device)
            }),
            camera: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gbuffer camera"),
                size: std::mem::size_of::<CameraUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            peel,
            cull,
            triangles: {
                let (w, h) = if keep_triangles {
                    (width, height)
                } else {
                    (1, 1)
                };
                crate::gpu::texture_2d(
                    device,
                    "visible triangles",
                    w,
                    h,
                    wgpu::TextureFormat::R32Uint,
                    wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING,
                )
            },
            keep_triangles,
        })
    }

    /// The drawn triangle (in [`GpuScene::draw_ordered`]'s order) each framebuffer pixel of the
    /// last frame shows, + 1 (`R32Uint`, 0 = background), where the G-buffer was made to keep it.
    pub fn visible_triangles(&self) -> Option<&wgpu::Texture> {
        self.keep_triangles.then_some(&self.triangles)
    }

    /// Triangles the last frame's culling was given, and kept by each phase of the visibility
    /// pass (tests; waits for the GPU).
    #[cfg(test)]
    pub(crate) fn cull_counts(&self, gpu: &crate::gpu::Gpu) -> (u32, Vec<u32>) {
        self.cull.counts(gpu)
    }

    /// The visibility pass's depth buffer (reversed-Z [`Z_FORMAT`], the framebuffer's size) as
    /// the last frame left it.
    pub(crate) fn z_buffer(&self) -> &wgpu::Texture {
        &self.z
    }

    /// The second depth layer (linear, 0 = none), when depth peeling was asked for.
    pub fn second_layer(&self) -> Option<&wgpu::Texture> {
        self.peel.as_ref().map(|p| &p.depth)
    }

    /// Rasterise `scene` seen through `view`. Timings: `triangle_cull` and `gbuffer` (the
    /// visibility pass; each for both phases of its occlusion culling), `occlusion_pyramid`,
    /// `gbuffer_resolve`, and `depth_peel` and `depth_peel_resolve` when peeling.
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
        // Chunks nearest first: triangle indices (the visibility buffers) refer to this order.
        let scene = &scene.draw_ordered();
        self.cull.prepare(
            queue,
            view,
            visibility_draws(scene, view),
            self.peel.is_some(),
        );
        // Occlusion culling in two phases (super::triangle_cull): last frame's visible triangles,
        // then the others that their depths do not hide, into the same targets.
        self.cull.encode(encoder, profiler.as_deref_mut());
        let (targets, extra) = match &self.visibility {
            Visibility::Target(texture) => (vec![(texture, None)], Vec::new()),
            Visibility::Words(buffer) => (Vec::new(), vec![buffer.as_entire_binding()]),
        };
        let resources = scene_resources(&self.camera, scene, extra);
        for (list, clear) in [
            (CullList::SeenLastFrame, true),
            (CullList::NotHidden, false),
        ] {
            if !clear {
                self.cull.encode_second(encoder, profiler.as_deref_mut());
            }
            self.draw(
                device,
                encoder,
                &self.visibility_pipelines,
                &resources,
                &targets,
                // Both phases keep the depth: the pyramid reads the first's; the resolve reads
                // the second's to tell where no triangle was drawn.
                DrawLists {
                    lists: &[list],
                    clear,
                    keep_depth: true,
                    z: &self.z,
                },
                "gbuffer",
                profiler.as_deref_mut(),
            );
        }
        let z = self.z.create_view(&Default::default());
        let (depth, normals) = (
            self.depth.create_view(&Default::default()),
            self.normals.create_view(&Default::default()),
        );
        let visibility_view;
        let triangles = self.triangles.create_view(&Default::default());
        let mut outputs = vec![
            (7, wgpu::BindingResource::TextureView(&depth)),
            (8, wgpu::BindingResource::TextureView(&normals)),
            (11, wgpu::BindingResource::TextureView(&triangles)),
        ];
        match &self.visibility {
            Visibility::Target(texture) => {
                visibility_view = texture.create_view(&Default::default());
                outputs.push((6, wgpu::BindingResource::TextureView(&visibility_view)));
                outputs.push((9, wgpu::BindingResource::TextureView(&z)));
            }
            Visibility::Words(buffer) => outputs.push((6, buffer.as_entire_binding())),
        }
        outputs.extend(self.cull.seen_binding().map(|seen| (10, seen)));
        self.resolve(
            device,
            encoder,
            scene,
            &self.resolve,
            (self.depth.width(), self.depth.height()),
            true,
            outputs,
            "gbuffer_resolve",
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
            let targets = [(&peel.visibility, None)];
            // Every triangle: those the first layer hides are what peeling looks for.
            self.draw(
                device,
                encoder,
                &peel.pipelines,
                &resources,
                &targets,
                DrawLists {
                    lists: &[CullList::All],
                    clear: true,
                    keep_depth: false,
                    z: &peel.z,
                },
                "depth_peel",
                profiler.as_deref_mut(),
            );
            let (visibility, depth) = (
                peel.visibility.create_view(&Default::default()),
                peel.depth.create_view(&Default::default()),
            );
            self.resolve(
                device,
                encoder,
                scene,
                &peel.resolve,
                (peel.depth.width(), peel.depth.height()),
                false,
                vec![
                    (6, wgpu::BindingResource::TextureView(&visibility)),
                    (7, wgpu::BindingResource::TextureView(&depth)),
                    (8, wgpu::BindingResource::TextureView(&z)),
                ],
                "depth_peel_resolve",
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
        let scene = &scene.draw_ordered();
        let resources = scene_resources(&self.camera, scene, Vec::new());
        let targets = [(&self.albedo, Some(wgpu::Color::WHITE))];
        self.draw(
            device,
            encoder,
            &self.albedo_pipelines,
            &resources,
            &targets,
            DrawLists {
                lists: &[CullList::SeenLastFrame, CullList::NotHidden],
                clear: true,
                keep_depth: false,
                z: &self.z,
            },
            "albedo",
            None,
        );
    }

    /// A visibility buffer's resolve `pipeline` over the framebuffer of `size`: the scene (its
    /// vertex attributes where `reads_attributes`), then `resources` (the visibility buffer, the
    /// outputs and what else the resolve reads, at their bindings from 6 on); timed as `name`.
    #[allow(clippy::too_many_arguments)]
    fn resolve(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        pipeline: &wgpu::ComputePipeline,
        size: (u32, u32),
        reads_attributes: bool,
        resources: Vec<(u32, wgpu::BindingResource)>,
        name: &str,
        profiler: Option<&mut PassProfiler>,
    ) {
        // Resolves read no materials or textures (bindings 4 and 5); the peeled layer's no
        // vertex attributes either (binding 2: only the G-buffer's normals interpolate them).
        let resources: Vec<_> = (0..)
            .zip(scene_resources(&self.camera, scene, Vec::new()))
            .take(4)
            .filter(|(binding, _)| *binding != 2 || reads_attributes)
            .chain(resources)
            .collect();
        let bind_group =
            crate::gpu::bind_group_at(device, name, &pipeline.get_bind_group_layout(0), &resources);
        let timestamp_writes = profiler.map(|p| p.compute_pass(name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(name),
            timestamp_writes,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(size.0.div_ceil(8), size.1.div_ceil(8), 1);
    }

    /// One raster pass of the scene: the frame's culled draws of `lists.lists` in order
    /// ([`TriangleCull::record`]) into `targets`, each with its clear colour (`None`: never
    /// cleared, see [`VISIBILITY_FORMAT`]).
    #[allow(clippy::too_many_arguments)]
    fn draw(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &[wgpu::RenderPipeline],
        resources: &[wgpu::BindingResource],
        targets: &[(&wgpu::Texture, Option<wgpu::Color>)],
        lists: DrawLists,
        name: &str,
        profiler: Option<&mut PassProfiler>,
    ) {
        let bind_groups: Vec<_> = pipelines
            .iter()
            .map(|p| crate::gpu::bind_group(device, name, &p.get_bind_group_layout(0), resources))
            .collect();
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
                        load: match clear {
                            Some(colour) if lists.clear => wgpu::LoadOp::Clear(*colour),
                            _ => wgpu::LoadOp::Load,
                        },
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let z_view = lists.z.create_view(&Default::default());
        let mut profiler = profiler;
        let timestamp_writes = profiler.as_deref_mut().map(|p| p.render_pass(name));
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(name),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &z_view,
                depth_ops: Some(wgpu::Operations {
                    load: if lists.clear {
                        wgpu::LoadOp::Clear(0.0)
                    } else {
                        wgpu::LoadOp::Load
                    },
                    store: if lists.keep_depth {
                        wgpu::StoreOp::Store
                    } else {
                        wgpu::StoreOp::Discard
                    },
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
        for &list in lists.lists {
            self.cull.record(&mut pass, pipelines, &bind_groups, list);
        }
        if let Some(p) = profiler {
            p.end_fragments(&mut pass);
        }
    }
}

/// What one raster pass of [`GBuffer`] draws: the culled `lists`, in order, into targets it clears
/// first (`clear`: the depth buffer, and the colour targets given a clear colour) or adds to;
/// `keep_depth` stores the depth buffer for what comes after.
struct DrawLists<'a> {
    lists: &'a [CullList],
    clear: bool,
    keep_depth: bool,
    /// The depth buffer the draws test against.
    z: &'a wgpu::Texture,
}

/// The visibility pass's draws: the chunks `view` may see ([`super::chunks`]), nearest first
/// within each of [`GpuScene::visibility_ranges`]' groups, group `g` with pipeline `g`.
pub(crate) fn visibility_draws(scene: &GpuScene, view: &FrameView) -> Vec<Draw> {
    let visible = chunks::visible_front_to_back(
        &scene.chunks,
        view.projection() * view.view_matrix(),
        view.camera.eye,
    );
    let groups = scene.visibility_ranges();
    (0..groups.len())
        .flat_map(|g| {
            let group = groups[g].clone();
            visible
                .iter()
                .filter(move |c| group.contains(&c.triangles.start))
                .map(move |c| (g, c.triangles.clone()))
        })
        .collect()
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
/// [`scene_resources`]), then `extra` (stages and type) from binding 6 on: the G-buffer's
/// shaders use different subsets of it, which automatic layouts would leave out.
pub(crate) fn scene_layout(
    device: &wgpu::Device,
    extra: &[(wgpu::ShaderStages, wgpu::BindingType)],
) -> wgpu::PipelineLayout {
    let group = scene_group_layout(device, wgpu::ShaderStages::VERTEX_FRAGMENT, extra);
    let drawn = super::triangle_cull::drawn_layout(device);
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("scene"),
        bind_group_layouts: &[Some(&group), Some(&drawn)],
        immediate_size: 0,
    })
}

/// The bind group layout of [`scene_layout`]'s group 0: bindings 0–5 visible to `stages`, then
/// `extra` from binding 6 on (also for the compute passes that read the scene).
pub(crate) fn scene_group_layout(
    device: &wgpu::Device,
    stages: wgpu::ShaderStages,
    extra: &[(wgpu::ShaderStages, wgpu::BindingType)],
) -> wgpu::BindGroupLayout {
    let storage = wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only: true },
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let scene = [
        wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        storage,
        storage,
        storage,
        storage,
        wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2Array,
            multisampled: false,
        },
    ]
    .map(|ty| (stages, ty));
    let entries: Vec<_> = (0..)
        .zip(scene.iter().chain(extra))
        .map(|(binding, &(visibility, ty))| wgpu::BindGroupLayoutEntry {
            binding,
            visibility,
            ty,
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("scene"),
        entries: &entries,
    })
}

/// Bindings 6 and 7 of the passes that draw what lies behind the first layer (depth peeling,
/// the stochastic depth map), for [`scene_layout`]: the first layer's linear depth and the pass's
/// uniform parameters, read by the fragment shader.
pub(crate) fn behind_first_layer_entries() -> Vec<(wgpu::ShaderStages, wgpu::BindingType)> {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    vec![
        (
            fragment,
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
        ),
        (
            fragment,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        ),
    ]
}

/// The pipelines of [`GpuScene`]'s three groups of a pass: back faces culled, double-sided (both
/// with `vs_visibility` and the `opaque` fragment entry point), alpha-tested (`vs_main`, every
/// value interpolated, and `masked`).
fn group_pipelines(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    depth_stencil: &wgpu::DepthStencilState,
    (opaque, masked): (&str, &str),
    targets: &[Option<wgpu::ColorTargetState>],
    layout: Option<&wgpu::PipelineLayout>,
) -> [wgpu::RenderPipeline; 3] {
    let pipeline = |cull_mode, vertex, fragment| {
        ScenePipeline {
            layout,
            module,
            cull_mode,
            depth_stencil: depth_stencil.clone(),
            multisample: Default::default(),
            vertex,
            fragment,
            targets,
        }
        .create(device)
    };
    [
        pipeline(Some(wgpu::Face::Back), "vs_visibility", opaque),
        pipeline(None, "vs_visibility", opaque),
        pipeline(None, "vs_main", masked),
    ]
}

/// A raster pipeline over the scene's vertices (pulled from storage by gbuffer.wgsl).
pub(crate) struct ScenePipeline<'a> {
    /// `None`: an automatic layout (passes that bind more than the scene).
    pub layout: Option<&'a wgpu::PipelineLayout>,
    pub module: &'a wgpu::ShaderModule,
    pub cull_mode: Option<wgpu::Face>,
    pub depth_stencil: wgpu::DepthStencilState,
    pub multisample: wgpu::MultisampleState,
    /// The vertex entry point: `vs_main` (every interpolated value) or `vs_visibility`.
    pub vertex: &'a str,
    pub fragment: &'a str,
    pub targets: &'a [Option<wgpu::ColorTargetState>],
}

impl ScenePipeline<'_> {
    pub fn create(self, device: &wgpu::Device) -> wgpu::RenderPipeline {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(self.fragment),
            layout: self.layout,
            vertex: wgpu::VertexState {
                module: self.module,
                entry_point: Some(self.vertex),
                compilation_options: Default::default(),
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
                compilation_options: Default::default(),
                targets: self.targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{
        visibility_words_available, visibility_words_fit, PEEL_Z_OVERRIDE, VISIBILITY_TARGET_ONLY,
    };
    use crate::pipeline::renderer::Renderer;
    use crate::raster::test_support::{gpu, moved};
    use crate::scene;
    use crate::settings::AoSettings;
    use crate::technique::Technique;

    /// Words only where 8 bytes a pixel fit one storage binding and one buffer.
    #[test]
    fn visibility_words_only_where_they_fit() {
        let limits = wgpu::Limits {
            max_storage_buffer_binding_size: 128 << 20,
            max_buffer_size: 256 << 20,
            ..Default::default()
        };
        assert!(visibility_words_fit(&limits, 4096, 4096));
        assert!(!visibility_words_fit(&limits, 4096, 4097));
        assert!(visibility_words_fit(&limits, 1920 + 128, 1080 + 128));
        let small_buffers = wgpu::Limits {
            max_buffer_size: 64 << 20,
            ..limits
        };
        assert!(!visibility_words_fit(&small_buffers, 4096, 4096));
        assert!(visibility_words_fit(&small_buffers, 2048, 4096));
    }

    /// The visibility pass by 64-bit atomics leaves the same G-buffer (depth, normals, the peeled
    /// layer, the AO) as its colour-target twin on every built-in scene and camera, frame after
    /// frame (the resolve empties the words it reads, so a frame of another view before must
    /// leave nothing behind). The first camera of each scene also at odd sides (109 × 77 with
    /// the band), where the words' last 2×2 quads of a row and of the image are half used.
    #[test]
    fn visibility_words_equal_the_colour_target() {
        let gpu = gpu();
        assert!(
            visibility_words_available(&gpu.device),
            "{} lacks 64-bit atomics or early fragment tests (lavapipe has them)",
            gpu.summary.name
        );
        let settings = AoSettings::preset(Technique::VaoDual, crate::settings::Preset::Medium);
        for name in scene::builtin_names() {
            let scene = scene::builtin(name).unwrap();
            let sizes = scene.cameras.iter().enumerate().flat_map(|(c, named)| {
                let odd = (c == 0).then_some((named, (95, 63, 7)));
                std::iter::once((named, (96, 64, 8))).chain(odd)
            });
            for (named, (width, height, band)) in sizes {
                let camera = named.camera;
                let moved = moved(&scene, &camera);
                let frames = |target_only: bool| {
                    VISIBILITY_TARGET_ONLY.with(|v| v.set(target_only));
                    let mut r =
                        Renderer::new(&gpu, &scene, &settings, width, height, band).unwrap();
                    VISIBILITY_TARGET_ONLY.with(|v| v.set(false));
                    [&camera, &moved, &camera]
                        .iter()
                        .map(|&camera| {
                            r.render(camera, None).unwrap();
                            let g = r.read_gbuffer().unwrap();
                            (
                                g.depth,
                                g.normals,
                                r.read_second_layer().unwrap(),
                                r.read_ao().unwrap(),
                            )
                        })
                        .collect::<Vec<_>>()
                };
                let words = frames(false);
                let target = frames(true);
                for (f, (a, b)) in words.iter().zip(&target).enumerate() {
                    assert!(
                        a.0.iter().any(|&z| z > 0.0),
                        "{name} {} {width}×{height}, frame {f}: nothing drawn",
                        named.name
                    );
                    assert!(
                        a == b,
                        "{name} {} {width}×{height}, frame {f}: the visibility words changed the frame",
                        named.name
                    );
                }
            }
        }
    }

    /// Depth peeling's 24-bit depth buffer (`PEEL_Z_FORMAT`) against a 32-bit one, on every
    /// built-in scene and camera: the G-buffer is the same, and the peeled layer is too except
    /// where two kept surfaces lie within one 24-bit step of each other (reversed Z: d = near /
    /// z, so a step of 2⁻²⁴ in d is z² / near · 2⁻²⁴ in depth), where the first drawn may win
    /// over the nearer; there it lies at most two steps behind.
    #[test]
    fn depth_peeling_in_24_bits_keeps_the_layer_within_a_step() {
        let gpu = gpu();
        let settings = AoSettings::preset(Technique::VaoDual, crate::settings::Preset::Medium);
        let (mut pixels, mut differ) = (0usize, 0usize);
        for name in scene::builtin_names() {
            let scene = scene::builtin(name).unwrap();
            let near = f64::from(crate::view::near_plane(&scene));
            for named in &scene.cameras {
                let render = |format: Option<wgpu::TextureFormat>| {
                    PEEL_Z_OVERRIDE.with(|f| f.set(format));
                    let mut r = Renderer::new(&gpu, &scene, &settings, 96, 64, 8).unwrap();
                    PEEL_Z_OVERRIDE.with(|f| f.set(None));
                    r.render(&named.camera, None).unwrap();
                    (
                        r.read_gbuffer().unwrap().depth,
                        r.read_second_layer().unwrap().unwrap(),
                    )
                };
                let (first, second) = render(None);
                let (first_32, second_32) = render(Some(wgpu::TextureFormat::Depth32Float));
                assert_eq!(
                    first, first_32,
                    "{name} {}: the G-buffer changed",
                    named.name
                );
                assert!(
                    second_32.iter().any(|&z| z > 0.0),
                    "{name} {}: nothing peeled",
                    named.name
                );
                for (i, (&a, &b)) in second.iter().zip(&second_32).enumerate() {
                    pixels += 1;
                    if a == b {
                        continue;
                    }
                    differ += 1;
                    let (a, b) = (f64::from(a), f64::from(b));
                    let z = a.max(b);
                    let step = z * z / near * 2f64.powi(-24);
                    assert!(
                        a > 0.0 && b > 0.0 && a >= b && a - b <= 2.0 * step,
                        "{name} {}, pixel {i}: peeled {a} in 24 bits, {b} in 32 (step {step})",
                        named.name
                    );
                }
            }
        }
        println!("depth peeling in 24 bits: {differ} of {pixels} pixels differ");
        assert!(differ * 100 < pixels, "{differ} of {pixels} pixels differ");
    }
}
