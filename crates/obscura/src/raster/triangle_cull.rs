//! Triangle culling before the raster passes (`shaders/triangle_cull.wgsl`, issue 16): a compute
//! pass keeps, per draw of [`super::gbuffer::visibility_draws`], the triangles that may cover a
//! pixel centre (in the frustum, front-facing where back faces are culled, not between pixel
//! centres), in their order, and writes each draw's indirect arguments; the raster passes then
//! draw those lists ([`TriangleCull::record`]), their vertex shaders reading the triangle from
//! `drawn_triangles` (gbuffer.wgsl, bind group 1). Every fragment the uncull'd draws would make
//! is still made, in the same order (the test at the end of this file). Why: on the H100/H200 most of a
//! raster pass is spent on triangles before any fragment is shaded (BENCHMARKS.md), and compute
//! is far faster there than the raster units.

use super::chunks::Draw;
use super::gpu_scene::GpuScene;
use crate::gpu::PassProfiler;
use crate::view::FrameView;
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
    /// Its timing name.
    pub name: &'static str,
}

impl TriangleCull {
    /// The pass for `scene` (draw-ordered: the chunks index it), timed as `name`.
    pub fn new(device: &wgpu::Device, scene: &GpuScene, name: &'static str) -> Self {
        let pipeline = crate::gpu::compute_pipeline_with(
            device,
            "triangle cull",
            crate::shaders::TRIANGLE_CULL,
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
        let max_draws = scene.chunks.len() as u64;
        let draw_list = storage(
            "cull draw list",
            16 * max_draws,
            wgpu::BufferUsages::COPY_DST,
        );
        let drawn = storage(
            "drawn triangles",
            4 * u64::from(scene.triangle_count),
            wgpu::BufferUsages::empty(),
        );
        // Copied out only by the tests (`counts`).
        let args = storage(
            "cull draw args",
            16 * max_draws,
            wgpu::BufferUsages::INDIRECT | wgpu::BufferUsages::COPY_SRC,
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cull params"),
            size: std::mem::size_of::<CullParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = crate::gpu::bind_group(
            device,
            "triangle cull",
            &pipeline.get_bind_group_layout(0),
            &[
                params.as_entire_binding(),
                scene.positions.as_entire_binding(),
                scene.triangles.as_entire_binding(),
                draw_list.as_entire_binding(),
                drawn.as_entire_binding(),
                args.as_entire_binding(),
            ],
        );
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
            name,
        }
    }

    /// The coming frame: `draws` (the chunks `view` may see, [`super::gbuffer::visibility_draws`])
    /// seen through `view`.
    pub fn prepare(&self, queue: &wgpu::Queue, view: &FrameView, draws: Vec<Draw>) {
        let (width, height) = (view.full_width(), view.full_height());
        let params = CullParams {
            view: view.view_matrix().to_cols_array_2d(),
            projection: view.projection().to_cols_array_2d(),
            size: [width as f32, height as f32],
            draws: draws.len() as u32,
            #[cfg(test)]
            keep_all: u32::from(KEEP_EVERY_TRIANGLE.with(|k| k.get())),
            #[cfg(not(test))]
            keep_all: 0,
        };
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let list: Vec<[u32; 4]> = draws
            .iter()
            .map(|(group, t)| [t.start, t.end - t.start, *group as u32, 0])
            .collect();
        if !list.is_empty() {
            queue.write_buffer(&self.draw_list, 0, bytemuck::cast_slice(&list));
        }
        *self.draws.lock().unwrap() = draws;
    }

    /// Cull the prepared frame's triangles (timing: this pass's name).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, profiler: Option<&mut PassProfiler>) {
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
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.dispatch_workgroups(count.min(ROW), count.div_ceil(ROW), 1);
    }

    /// Draw the prepared frame's kept triangles: draw `i` with `pipelines[group]` and
    /// `bind_groups[group]` (group 0) and the kept list (group 1; the pipelines made with
    /// [`super::gbuffer::scene_layout`]).
    pub fn record(
        &self,
        pass: &mut wgpu::RenderPass,
        pipelines: &[wgpu::RenderPipeline],
        bind_groups: &[wgpu::BindGroup],
    ) {
        pass.set_bind_group(1, &self.drawn_group, &[]);
        let mut current = None;
        for (i, (group, triangles)) in self.draws.lock().unwrap().iter().enumerate() {
            if triangles.is_empty() {
                continue;
            }
            if current != Some(*group) {
                current = Some(*group);
                pass.set_pipeline(&pipelines[*group]);
                pass.set_bind_group(0, &bind_groups[*group], &[]);
            }
            pass.draw_indirect(&self.args, 16 * i as u64);
        }
    }
}

#[cfg(test)]
impl TriangleCull {
    /// Triangles submitted and kept by the last frame (waits for the GPU).
    pub fn counts(&self, gpu: &crate::Gpu) -> (u32, u32) {
        let draws = self.draws.lock().unwrap().clone();
        let bytes = crate::gpu::read_buffer_copy(gpu, &self.args).unwrap();
        let args: &[[u32; 4]] = bytemuck::cast_slice(&bytes);
        let submitted = draws.iter().map(|(_, t)| t.end - t.start).sum();
        let kept = args[..draws.len()].iter().map(|a| a[0] / 3).sum();
        (submitted, kept)
    }
}

#[cfg(test)]
mod tests {
    use super::KEEP_EVERY_TRIANGLE;
    use crate::{scene, AoSettings, Gpu, GpuOptions, Renderer, Technique};

    /// Every built-in scene and camera, culled and not: the G-buffer, the peeled layer and the
    /// stochastic depth maps (full and limited to requested pixels) are bit-identical, and the
    /// culling keeps fewer triangles than it is given.
    #[test]
    fn culling_changes_no_pixel_and_drops_triangles() {
        if std::env::var_os("XDG_RUNTIME_DIR").is_none_or(|v| v.is_empty()) {
            std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir());
        }
        let gpu =
            Gpu::new(&GpuOptions::default()).expect("a GPU adapter (install mesa-vulkan-drivers)");
        let (mut submitted, mut kept) = (0, 0);
        for name in scene::builtin_names() {
            let scene = scene::builtin(name).unwrap();
            for named in &scene.cameras {
                for technique in [Technique::VaoDual, Technique::SdVao, Technique::SdSvao] {
                    let settings = AoSettings::preset(technique, crate::settings::Preset::Medium);
                    let frame = |keep_all: bool| {
                        KEEP_EVERY_TRIANGLE.with(|k| k.set(keep_all));
                        let mut r = Renderer::new(&gpu, &scene, &settings, 96, 64, 8).unwrap();
                        r.render(&named.camera, None).unwrap();
                        KEEP_EVERY_TRIANGLE.with(|k| k.set(false));
                        let g = r.read_gbuffer().unwrap();
                        let counts = r.gbuffer().cull_counts(&gpu);
                        let images = (
                            g.depth,
                            g.normals,
                            r.read_second_layer().unwrap(),
                            r.read_stochastic_depth().unwrap(),
                            r.read_ao().unwrap(),
                        );
                        (images, counts)
                    };
                    let (culled, counts) = frame(false);
                    let (whole, all) = frame(true);
                    let what = format!("{name} {} {technique}", named.name);
                    assert_eq!(
                        all.0, all.1,
                        "{what}: the uncull'd twin keeps every triangle"
                    );
                    assert!(culled == whole, "{what}: culling changed the frame");
                    submitted += counts.0;
                    kept += counts.1;
                }
            }
        }
        assert!(
            u64::from(kept) * 10 < u64::from(submitted) * 9,
            "culling kept {kept} of {submitted} triangles"
        );
    }
}
