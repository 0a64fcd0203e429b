//! Triangle culling before the raster passes (`shaders/raster/triangle_cull.wgsl`, issue 16): a compute
//! pass keeps, per draw of [`super::gbuffer::visibility_draws`], the triangles that may cover a
//! pixel centre (in the frustum, front-facing where back faces are culled, not between pixel
//! centres), in their order, and writes each draw's indirect arguments; the raster passes then
//! draw those lists ([`TriangleCull::record`]), their vertex shaders reading the triangle from
//! `drawn_triangles` (gbuffer.wgsl, bind group 1). Every fragment the uncull'd draws would make
//! is still made, in the same order (the test at the end of this file). Why: on the H100/H200 most of a
//! raster pass is spent on triangles before any fragment is shaded (BENCHMARKS.md), and compute
//! is far faster there than the raster units.
//!
//! With occlusion culling ([`TriangleCull::new`] given the pass's depth buffer), the pass runs in
//! two phases (Haar and Aaltonen, "GPU-Driven Rendering Pipelines", SIGGRAPH 2015): the first
//! list holds the triangles a pixel showed last frame ([`CullList::SeenLastFrame`]); once they
//! are drawn, [`TriangleCull::encode_second`] builds the [`OcclusionPyramid`] of their depths and
//! keeps the other triangles that are not behind them everywhere ([`CullList::NotHidden`]). Each
//! pixel's nearest fragment is still drawn; only the order of exactly equal depths can change,
//! and only for triangles the phases split (the test below holds still and moving cameras
//! bit-identical on the built-in scenes).

use super::chunks::Draw;
use super::gpu_scene::GpuScene;
use super::occlusion_pyramid::OcclusionPyramid;
use crate::gpu::PassProfiler;
use crate::view::FrameView;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Mutex;

/// `CullParams` of triangle_cull.wgsl.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CullParams {
    view: [[f32; 4]; 4],
    projection: [[f32; 4]; 4],
    size: [f32; 2],
    draws: u32,
    keep_all: u32,
    phase: u32,
    keep_all_list: u32,
    list_triangles: u32,
    list_draws: u32,
    _pad: [u32; 2],
}

/// The triangle lists a [`TriangleCull`] writes (the number is the list's place in its buffers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum CullList {
    /// Every triangle that may cover a pixel centre: the only list without occlusion culling;
    /// with it, written on request ([`TriangleCull::prepare`]) for passes that must not be
    /// occlusion-culled by the first layer (depth peeling).
    All = 0,
    /// Occlusion culling's first phase: of those, the ones a pixel showed last frame.
    SeenLastFrame = 1,
    /// Its second phase: the others, unless the first phase's depths hide them.
    NotHidden = 2,
}

/// Occlusion culling's state.
struct Occlusion {
    pyramid: OcclusionPyramid,
    /// The current frame number, from 1 on (`u32` 0), then per triangle the last frame number
    /// at which a pixel showed it (written by the G-buffer's resolve,
    /// [`TriangleCull::seen_binding`]).
    seen_frame: wgpu::Buffer,
    frame: AtomicU32,
    /// The second phase's parameters and bindings.
    second_params: wgpu::Buffer,
    second_bind_group: wgpu::BindGroup,
}

#[cfg(test)]
thread_local! {
    /// Tests: the passes prepared on this thread keep every triangle (the uncull'd twin).
    pub(crate) static KEEP_EVERY_TRIANGLE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The shader's workgroups per dispatch row (`ROW`).
const ROW: u32 = 65535;

/// The layout of bind group 1 of every pipeline that draws culled triangles
/// ([`super::gbuffer::scene_layout`]): the kept triangles, read by the vertex shaders.
pub(crate) fn drawn_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("drawn triangles"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    })
}

/// The culling pass and its outputs for one draw-ordered scene ([`GpuScene::draw_ordered`]).
pub(crate) struct TriangleCull {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// Per draw `(first triangle, count, group, 0)`.
    draw_list: wgpu::Buffer,
    /// `draw_indirect` arguments per draw.
    args: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The kept triangles of each draw, from its first triangle on, as the raster pipelines'
    /// group 1 ([`drawn_layout`]: equal layouts are compatible, so one bind group serves every
    /// pipeline).
    drawn_group: wgpu::BindGroup,
    /// The draws of the coming frame (their order is the arguments' order).
    draws: Mutex<Vec<Draw>>,
    /// Draws per list in `args` (the scene's chunk count) and triangles per list in the kept
    /// lists.
    max_draws: u32,
    triangles: u32,
    occlusion: Option<Occlusion>,
    /// Its timing name.
    pub name: &'static str,
}

impl TriangleCull {
    /// The pass for `scene` (draw-ordered: the chunks index it), timed as `name`; with `occlusion`,
    /// the depth buffer (`Depth32Float`, reversed Z) of the pass that draws [`CullList::SeenLastFrame`],
    /// occlusion culling in two phases.
    pub fn new(
        device: &wgpu::Device,
        scene: &GpuScene,
        name: &'static str,
        occlusion: Option<&wgpu::Texture>,
    ) -> Self {
        let pipeline = crate::gpu::compute_pipeline_with(
            device,
            "triangle cull",
            &crate::shaders::with_common(
                &[crate::shaders::OCCLUSION_PYRAMID_LAYOUT],
                crate::shaders::TRIANGLE_CULL,
            ),
            &[],
        );
        let storage = |label, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        // Read-only storage, not a uniform: why in triangle_cull.wgsl (lavapipe's uniform inlining).
        let parameters = |label| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: std::mem::size_of::<CullParams>() as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let lists = if occlusion.is_some() { 3 } else { 1 };
        let max_draws = scene.chunks.len() as u64;
        let draw_list = storage(
            "cull draw list",
            16 * max_draws,
            wgpu::BufferUsages::COPY_DST,
        );
        let drawn = storage(
            "drawn triangles",
            4 * lists * u64::from(scene.triangle_count),
            wgpu::BufferUsages::empty(),
        );
        // Copied out only by the tests (`counts`).
        let args = storage(
            "cull draw args",
            16 * lists * max_draws,
            wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC,
        );
        let params = parameters("cull params");
        let pyramid = occlusion.map(|z| OcclusionPyramid::new(device, z));
        let seen_frame = storage(
            "triangles seen",
            if occlusion.is_some() {
                4 * (1 + u64::from(scene.triangle_count))
            } else {
                16
            },
            wgpu::BufferUsages::COPY_DST,
        );
        // Without occlusion culling the pyramid binding is a placeholder the shader never reads.
        let pyramid_buffer = pyramid.as_ref().map_or_else(
            || storage("no pyramid", 16, wgpu::BufferUsages::empty()),
            |p| p.buffer.clone(),
        );
        let layout = pipeline.get_bind_group_layout(0);
        let bind_group_with = |params: &wgpu::Buffer| {
            crate::gpu::bind_group(
                device,
                "triangle cull",
                &layout,
                &[
                    params.as_entire_binding(),
                    scene.positions.as_entire_binding(),
                    scene.triangles.as_entire_binding(),
                    draw_list.as_entire_binding(),
                    drawn.as_entire_binding(),
                    args.as_entire_binding(),
                    seen_frame.as_entire_binding(),
                    pyramid_buffer.as_entire_binding(),
                ],
            )
        };
        let bind_group = bind_group_with(&params);
        let occlusion = pyramid.map(|pyramid| {
            let second_params = parameters("cull params, second phase");
            Occlusion {
                second_bind_group: bind_group_with(&second_params),
                second_params,
                pyramid,
                seen_frame: seen_frame.clone(),
                frame: AtomicU32::new(0),
            }
        });
        let drawn_group = crate::gpu::bind_group(
            device,
            "drawn triangles",
            &drawn_layout(device),
            &[drawn.as_entire_binding()],
        );
        Self {
            pipeline,
            drawn_group,
            params,
            draw_list,
            args,
            bind_group,
            draws: Mutex::new(Vec::new()),
            max_draws: max_draws as u32,
            triangles: scene.triangle_count,
            occlusion,
            name,
        }
    }

    /// The coming frame: `draws` (the chunks `view` may see, [`super::gbuffer::visibility_draws`])
    /// seen through `view`. With occlusion culling, `all_too` also asks the first phase for
    /// [`CullList::All`].
    pub fn prepare(&self, queue: &wgpu::Queue, view: &FrameView, draws: Vec<Draw>, all_too: bool) {
        let (width, height) = (view.full_width(), view.full_height());
        // A dispatch's phase is the number of the list it writes.
        let params = |list: CullList| {
            let phase = list as u32;
            CullParams {
                view: view.view_matrix().to_cols_array_2d(),
                projection: view.projection().to_cols_array_2d(),
                size: [width as f32, height as f32],
                draws: draws.len() as u32,
                #[cfg(test)]
                keep_all: u32::from(KEEP_EVERY_TRIANGLE.with(|k| k.get())),
                #[cfg(not(test))]
                keep_all: 0,
                phase,
                keep_all_list: u32::from(all_too),
                list_triangles: phase * self.triangles,
                list_draws: phase * self.max_draws,
                _pad: [0; 2],
            }
        };
        match &self.occlusion {
            None => queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params(CullList::All))),
            Some(o) => {
                let frame = o.frame.fetch_add(1, Ordering::Relaxed) + 1;
                queue.write_buffer(&o.seen_frame, 0, bytemuck::bytes_of(&frame));
                queue.write_buffer(
                    &self.params,
                    0,
                    bytemuck::bytes_of(&params(CullList::SeenLastFrame)),
                );
                queue.write_buffer(
                    &o.second_params,
                    0,
                    bytemuck::bytes_of(&params(CullList::NotHidden)),
                );
            }
        }
        let list: Vec<[u32; 4]> = draws
            .iter()
            .map(|(group, t)| [t.start, t.end - t.start, *group as u32, 0])
            .collect();
        if !list.is_empty() {
            queue.write_buffer(&self.draw_list, 0, bytemuck::cast_slice(&list));
        }
        *self.draws.lock().unwrap() = draws;
    }

    /// The current frame number, then per triangle the last frame number at which a pixel
    /// showed it: what the pass that draws [`CullList::SeenLastFrame`] writes after it
    /// ([`None`] without occlusion culling).
    pub fn seen_binding(&self) -> Option<wgpu::BindingResource<'_>> {
        self.occlusion
            .as_ref()
            .map(|o| o.seen_frame.as_entire_binding())
    }

    /// Cull the prepared frame's triangles: without occlusion culling, [`CullList::All`]; with
    /// it, the first phase (timing: this pass's name).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut PassProfiler>) {
        self.dispatch(encoder, &self.bind_group, profiler);
    }

    /// Occlusion culling's second phase, after the first phase's triangles are drawn into the
    /// depth buffer given to [`TriangleCull::new`]: their occlusion pyramid, then
    /// [`CullList::NotHidden`] (timings: `occlusion_pyramid` and this pass's name). Nothing
    /// without occlusion culling.
    pub fn encode_second(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        mut profiler: Option<&mut PassProfiler>,
    ) {
        if let Some(o) = &self.occlusion {
            o.pyramid.encode(encoder, profiler.as_deref_mut());
            self.dispatch(encoder, &o.second_bind_group, profiler);
        }
    }

    fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        bind_group: &wgpu::BindGroup,
        profiler: Option<&mut PassProfiler>,
    ) {
        let count = self.draws.lock().unwrap().len() as u32;
        if count == 0 {
            return;
        }
        let timestamp_writes = profiler.map(|p| p.compute_pass(self.name));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.name),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(count.min(ROW), count.div_ceil(ROW), 1);
    }

    /// Draw the prepared frame's kept triangles of `list`: draw `i` with `pipelines[group]` and
    /// `bind_groups[group]` (group 0) and the kept list (group 1; the pipelines made with
    /// [`super::gbuffer::scene_layout`]).
    pub fn record(
        &self,
        pass: &mut wgpu::RenderPass,
        pipelines: &[wgpu::RenderPipeline],
        bind_groups: &[wgpu::BindGroup],
        list: CullList,
    ) {
        pass.set_bind_group(1, &self.drawn_group, &[]);
        let draws = self.draws.lock().unwrap();
        // Each run of one group's draws is one multi-draw (wgpu loops where the adapter has
        // none); draws given no triangles have zero counts and go with their run. On the H200
        // that made depth peeling 2 % faster on Crytek Sponza than a draw each (BENCHMARKS.md,
        // issue 16).
        let mut start = list as u64 * u64::from(self.max_draws);
        for run in draws.chunk_by(|a, b| a.0 == b.0) {
            let group = run[0].0;
            pass.set_pipeline(&pipelines[group]);
            pass.set_bind_group(0, &bind_groups[group], &[]);
            pass.multi_draw_indirect(&self.args, 16 * start, run.len() as u32);
            start += run.len() as u64;
        }
    }
}

#[cfg(test)]
impl TriangleCull {
    /// Triangles submitted and kept by the last frame (waits for the GPU): kept in
    /// [`CullList::All`], or with occlusion culling in each phase's list.
    pub fn counts(&self, gpu: &crate::gpu::Gpu) -> (u32, Vec<u32>) {
        let draws = self.draws.lock().unwrap().clone();
        let bytes = crate::gpu::read_buffer_copy(gpu, &self.args).unwrap();
        let args: &[[u32; 4]] = bytemuck::cast_slice(&bytes);
        let submitted = draws.iter().map(|(_, t)| t.end - t.start).sum();
        let lists = match self.occlusion {
            None => vec![CullList::All],
            Some(_) => vec![CullList::SeenLastFrame, CullList::NotHidden],
        };
        let kept = lists
            .into_iter()
            .map(|list| {
                let first = list as usize * self.max_draws as usize;
                args[first..first + draws.len()]
                    .iter()
                    .map(|a| a[0] / 3)
                    .sum()
            })
            .collect();
        (submitted, kept)
    }
}

#[cfg(test)]
mod tests {
    use super::KEEP_EVERY_TRIANGLE;
    use crate::pipeline::renderer::Renderer;
    use crate::raster::test_support::{gpu, moved};
    use crate::scene;
    use crate::settings::AoSettings;
    use crate::technique::Technique;

    /// Every built-in scene and camera, culled and not: the G-buffer, the peeled layer and the
    /// stochastic depth maps (full and limited to requested pixels) are bit-identical, and the
    /// culling keeps fewer triangles than it is given. Each renderer draws a sequence of frames —
    /// the camera, the camera turned and moved, the camera again twice — so the G-buffer's
    /// occlusion culling is checked on its first frame (no history), after a camera move (last
    /// frame's visible set from another view) and still (the steady state); the last must draw
    /// fewer triangles than the first, which has only the frustum and back-face tests.
    #[test]
    fn culling_changes_no_pixel_and_drops_triangles() {
        let gpu = gpu();
        let (mut submitted, mut kept) = (0, 0);
        let (mut first_frame, mut still) = (0, 0);
        for name in scene::builtin_names() {
            let scene = scene::builtin(name).unwrap();
            for named in &scene.cameras {
                let camera = named.camera;
                let moved = moved(&scene, &camera);
                let cameras = [&camera, &moved, &camera, &camera];
                for technique in [Technique::VaoDual, Technique::SdVao, Technique::SdSvao] {
                    let settings = AoSettings::preset(technique, crate::settings::Preset::Medium);
                    let frames = |keep_all: bool| {
                        KEEP_EVERY_TRIANGLE.with(|k| k.set(keep_all));
                        let mut r = Renderer::new(&gpu, &scene, &settings, 96, 64, 8).unwrap();
                        KEEP_EVERY_TRIANGLE.with(|k| k.set(false));
                        cameras
                            .iter()
                            .map(|&camera| {
                                KEEP_EVERY_TRIANGLE.with(|k| k.set(keep_all));
                                r.render(camera, None).unwrap();
                                KEEP_EVERY_TRIANGLE.with(|k| k.set(false));
                                let g = r.read_gbuffer().unwrap();
                                let images = (
                                    g.depth,
                                    g.normals,
                                    r.read_second_layer().unwrap(),
                                    r.read_stochastic_depth().unwrap(),
                                    r.read_ao().unwrap(),
                                );
                                (images, r.gbuffer().cull_counts(&gpu))
                            })
                            .collect::<Vec<_>>()
                    };
                    let culled = frames(false);
                    let whole = frames(true);
                    for (f, ((images, counts), (whole_images, all))) in
                        culled.iter().zip(&whole).enumerate()
                    {
                        let what = format!("{name} {} {technique}, frame {f}", named.name);
                        assert_eq!(
                            all.1.iter().sum::<u32>(),
                            all.0,
                            "{what}: the uncull'd twin keeps every triangle"
                        );
                        assert!(images == whole_images, "{what}: culling changed the frame");
                        submitted += counts.0;
                        kept += counts.1.iter().sum::<u32>();
                    }
                    first_frame += culled[0].1 .1.iter().sum::<u32>();
                    still += culled[3].1 .1.iter().sum::<u32>();
                }
            }
        }
        assert!(
            u64::from(kept) * 10 < u64::from(submitted) * 9,
            "culling kept {kept} of {submitted} triangles"
        );
        eprintln!(
            "occlusion culling: {still} triangles drawn still, {first_frame} on the first frame"
        );
        assert!(
            still < first_frame,
            "occlusion culling drew {still} triangles still, {first_frame} on the first frame"
        );
    }
}
