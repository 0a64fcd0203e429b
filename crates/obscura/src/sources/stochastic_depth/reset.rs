//! Resetting the stochastic depth map each frame (`shaders/sources/stochastic_depth/reset.wgsl`):
//! a compute pass empties every pixel's depths, then a full-screen pass writes the depth the map's
//! fragments must lie behind (the first layer plus the separation), and for a stenciled map
//! (`sd-svao`, seed 000 §3.9) the frame's stencil value, at the pixels phase 1 requested (or, with
//! `--sd-mask depth`, the far plane at the pixels phase 1 did not request). A map
//! that keeps every layer skips the second pass (its map pass clears the depth to 1). Timed as
//! `sd_clear` and `sd_reset`.

use crate::gpu::zero_fill::ZeroFill;
use crate::gpu::PassProfiler;
use std::sync::atomic::{AtomicU32, Ordering};

/// What a reset writes besides the empty map and the depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ResetScope {
    /// No stencil.
    All,
    /// The frame's stencil value at the requested pixels.
    Stenciled,
    /// No stencil: the far plane, which rejects every fragment, at the pixels not requested.
    RequestedByDepth,
}

/// Two steps of `format`'s depth where it may be 24-bit fixed point (reset.wgsl's
/// SD_CULL_QUANTUM), 0 for a float format. A device may store `Depth24Plus` as a float: two
/// 24-bit steps then only let a few more fragments reach the shader, which drops them.
fn cull_quantum(format: wgpu::TextureFormat) -> f64 {
    match format {
        wgpu::TextureFormat::Depth24Plus | wgpu::TextureFormat::Depth24PlusStencil8 => {
            2.0 / 16777215.0
        }
        _ => 0.0,
    }
}

pub(crate) struct SdReset {
    clear: ZeroFill,
    pipeline: wgpu::RenderPipeline,
    /// The bindings of the map pass's group 0 that the depth pass reads (its automatic layout
    /// holds only these): camera, first layer, `SdRaster`, and the request mask if stenciled.
    bindings: &'static [u32],
    /// Frames reset so far: the stencil value of a frame is `frames % 255 + 1`.
    frames: AtomicU32,
    /// Its timing names: `sd_clear` and `sd_reset` unless the map is renamed.
    pub clear_name: &'static str,
    pub name: &'static str,
}

impl SdReset {
    /// The reset for a map target of `format`; `module` is the map's (map.wgsl + reset.wgsl).
    pub fn new(
        device: &wgpu::Device,
        module: &wgpu::ShaderModule,
        format: wgpu::TextureFormat,
        scope: ResetScope,
    ) -> Self {
        let stencil = if scope == ResetScope::Stenciled {
            let replace = wgpu::StencilFaceState {
                compare: wgpu::CompareFunction::Always,
                pass_op: wgpu::StencilOperation::Replace,
                ..Default::default()
            };
            wgpu::StencilState {
                front: replace,
                back: replace,
                read_mask: 0xff,
                write_mask: 0xff,
            }
        } else {
            Default::default()
        };
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("sd reset"),
            layout: None,
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs_full_screen"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil,
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some(match scope {
                    ResetScope::All => "fs_reset_all",
                    ResetScope::Stenciled => "fs_reset_requested",
                    ResetScope::RequestedByDepth => "fs_reset_requested_by_depth",
                }),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &[("SD_CULL_QUANTUM", cull_quantum(format))],
                    ..Default::default()
                },
                targets: &[],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self {
            clear: ZeroFill::new(device),
            pipeline,
            bindings: match scope {
                ResetScope::All => &[0, 6, 7],
                ResetScope::Stenciled | ResetScope::RequestedByDepth => &[0, 6, 7, 10],
            },
            frames: AtomicU32::new(0),
            clear_name: "sd_clear",
            name: "sd_reset",
        }
    }

    /// Reset the map (`depths`) and, with `target`, the depth (and stencil) its
    /// fragments are tested against (timings [`SdReset::clear_name`], [`SdReset::name`]); `resources`: the map pass's
    /// bindings of group 0. Returns the frame's stencil value (1–255; 0 is what a new texture
    /// holds), which the map pass tests for.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        depths: &wgpu::Buffer,
        target: Option<&wgpu::TextureView>,
        resources: &[wgpu::BindingResource],
        mut profiler: Option<&mut PassProfiler>,
    ) -> u32 {
        let stencil_value = self.frames.fetch_add(1, Ordering::Relaxed) % 255 + 1;
        let name = self.name;
        let group = |pipeline_layout: &wgpu::BindGroupLayout, bindings: &[u32]| {
            let used: Vec<_> = bindings
                .iter()
                .map(|&b| (b, resources[b as usize].clone()))
                .collect();
            crate::gpu::bind_group_at(device, "sd reset", pipeline_layout, &used)
        };
        self.clear.encode(
            device,
            encoder,
            &[depths],
            self.clear_name,
            profiler.as_deref_mut(),
        );
        let Some(target) = target else {
            return stencil_value;
        };
        let bind_group = group(&self.pipeline.get_bind_group_layout(0), self.bindings);
        let timestamp_writes = profiler.as_deref_mut().map(|p| p.render_pass(name));
        let mut pass = super::begin(encoder, target, wgpu::LoadOp::Load, timestamp_writes);
        if let Some(p) = profiler.as_deref_mut() {
            p.begin_fragments(&mut pass, name);
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.set_stencil_reference(stencil_value);
        pass.draw(0..3, 0..1);
        if let Some(p) = profiler {
            p.end_fragments(&mut pass);
        }
        stencil_value
    }
}
