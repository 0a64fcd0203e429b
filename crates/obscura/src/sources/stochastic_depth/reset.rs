//! Resetting the stochastic depth map each frame (`shaders/sources/stochastic_depth/reset.wgsl`): depth back to empty
//! everywhere (`sd-vao`) or only at the pixels phase 1 requested (`sd-svao`, seed 000 §3.9), where
//! a stenciled map also gets the frame's stencil value. A draw rather than a load-op clear:
//! measured on the H100 (BENCHMARKS.md), clearing a 4× depth-stencil target of 1080p + 64 px cost
//! 0.94 ms, more than rasterising colonnade's whole map into it.

use crate::gpu::PassProfiler;
use crate::shaders;
use std::sync::atomic::{AtomicU32, Ordering};
use wgpu::util::DeviceExt;

/// Which pixels a reset touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ResetScope {
    /// Every pixel (the full map).
    All,
    /// Requested pixels only; `stencil`: also write the frame's stencil value there.
    Requested { stencil: bool },
}

pub(crate) struct SdReset {
    pipeline: wgpu::RenderPipeline,
    scope: ResetScope,
    /// The framebuffer width, for indexing the request mask.
    width: wgpu::Buffer,
    /// Frames reset so far: the stencil value of a frame is `frames % 255 + 1`.
    frames: AtomicU32,
    /// Its timing name: `sd_reset` unless the map is renamed.
    pub name: &'static str,
}

impl SdReset {
    pub fn new(
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
        multisample: wgpu::MultisampleState,
        (width, height): (u32, u32),
        scope: ResetScope,
    ) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("sd reset"),
            source: wgpu::ShaderSource::Wgsl(shaders::STOCHASTIC_DEPTH_RESET.into()),
        });
        let stencil = if scope == (ResetScope::Requested { stencil: true }) {
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
                module: &module,
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
            multisample,
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(match scope {
                    ResetScope::All => "fs_reset_all",
                    ResetScope::Requested { .. } => "fs_reset_requested",
                }),
                compilation_options: Default::default(),
                targets: &[],
            }),
            multiview_mask: None,
            cache: None,
        });
        Self {
            pipeline,
            scope,
            width: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("sd reset width"),
                contents: bytemuck::cast_slice(&[width, height, 0, 0]),
                usage: wgpu::BufferUsages::UNIFORM,
            }),
            frames: AtomicU32::new(0),
            name: "sd_reset",
        }
    }

    /// The stencil value of the next frame (1–255; 0 is what a new texture holds). Call once per
    /// frame, before [`SdReset::encode`] for each of its maps.
    pub fn next_frame(&self) -> u32 {
        self.frames.fetch_add(1, Ordering::Relaxed) % 255 + 1
    }

    /// Reset `target` (timing [`SdReset::name`], `sd_reset` unless renamed). `request`: the SD-request mask, needed
    /// for [`ResetScope::Requested`].
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        request: Option<&wgpu::Buffer>,
        stencil_value: u32,
        profiler: Option<&mut PassProfiler>,
    ) {
        let name = self.name;
        let bind_group = match (self.scope, request) {
            (ResetScope::Requested { .. }, Some(request)) => Some(crate::gpu::bind_group(
                device,
                "sd reset",
                &self.pipeline.get_bind_group_layout(0),
                &[request.as_entire_binding(), self.width.as_entire_binding()],
            )),
            (ResetScope::Requested { .. }, None) => {
                panic!("a map limited to requested pixels is rendered with its request mask")
            }
            (ResetScope::All, _) => None,
        };
        let mut profiler = profiler;
        let timestamp_writes = profiler.as_deref_mut().map(|p| p.render_pass(name));
        let mut pass = super::begin(encoder, target, timestamp_writes);
        if let Some(p) = profiler.as_deref_mut() {
            p.begin_fragments(&mut pass, name);
        }
        pass.set_pipeline(&self.pipeline);
        if let Some(bind_group) = &bind_group {
            pass.set_bind_group(0, bind_group, &[]);
        }
        pass.set_stencil_reference(stencil_value);
        pass.draw(0..3, 0..1);
        if let Some(p) = profiler {
            p.end_fragments(&mut pass);
        }
    }
}
