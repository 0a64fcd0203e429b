//! How passes chain. [`AmbientOcclusion`] is the part an engine embeds: its depth and normals in,
//! an AO texture out. [`renderer::Renderer`] adds our own G-buffer for scenes we load ourselves.

pub mod renderer;

use crate::filter::bilateral::BilateralBlur;
use crate::gpu::PassProfiler;
use crate::hidden::HiddenDepth;
use crate::kernels::{
    svao::SvaoKernel,
    vao::{RayTracedScene, VaoKernel},
    AoKernel, FrameInputs,
};
use crate::settings::{AoSettings, Technique};
use crate::view::ScreenGeometry;
use crate::Error;
use wgpu::util::DeviceExt;

/// AO for one screen configuration: the technique's kernel, then (optionally) the blur.
///
/// The output is an `R32Float` texture of the *visible* size (no guard band), 1 = unoccluded.
pub struct AmbientOcclusion {
    settings: AoSettings,
    screen: ScreenGeometry,
    kernel: Box<dyn AoKernel>,
    blur: Option<BilateralBlur>,
    raw: wgpu::Texture,
    blurred: wgpu::Texture,
}

impl AmbientOcclusion {
    /// Build pipelines and images for `screen`. `settings` are validated first. Techniques that
    /// trace rays need the scene: use [`AmbientOcclusion::new_ray_traced`] for them.
    pub fn new(
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
    ) -> Result<Self, Error> {
        if settings.technique.hidden_depth() == HiddenDepth::ColumnRays {
            return Err(Error::Input(format!(
                "technique '{}' traces rays: create it with AmbientOcclusion::new_ray_traced and the scene",
                settings.technique
            )));
        }
        Self::build(device, settings, screen, None)
    }

    /// [`AmbientOcclusion::new`] for any technique, with the scene its rays are traced through
    /// (call [`AmbientOcclusion::set_camera`] before each frame).
    pub fn new_ray_traced(
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
        scene: RayTracedScene,
    ) -> Result<Self, Error> {
        Self::build(device, settings, screen, Some(scene))
    }

    fn build(
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
        scene: Option<RayTracedScene>,
    ) -> Result<Self, Error> {
        settings.validate()?;
        let view = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("view"),
            contents: bytemuck::bytes_of(&screen.uniform()),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let rays = match settings.technique.hidden_depth() {
            HiddenDepth::None | HiddenDepth::DualDepth => None,
            HiddenDepth::ColumnRays => scene,
        };
        let kernel: Box<dyn AoKernel> = match (settings.technique, rays) {
            (Technique::RtSvao | Technique::RtSvaoDense, Some(rays)) => Box::new(SvaoKernel::new(
                device,
                &settings.vao,
                &view,
                rays,
                (screen.width, screen.height),
                settings.technique == Technique::RtSvao,
            )),
            (technique, rays) => Box::new(VaoKernel::new(
                device,
                &settings.vao,
                &view,
                rays,
                technique == Technique::VaoDual,
            )),
        };
        let blur = settings.blur.enabled.then(|| {
            BilateralBlur::new(device, &settings.blur, &view, screen.width, screen.height)
        });
        let ao_texture = |label| {
            crate::gpu::texture_2d(
                device,
                label,
                screen.width,
                screen.height,
                wgpu::TextureFormat::R32Float,
                wgpu::TextureUsages::STORAGE_BINDING
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC,
            )
        };
        Ok(Self {
            settings: *settings,
            screen,
            kernel,
            raw: ao_texture("ao raw"),
            blurred: ao_texture("ao blurred"),
            blur,
        })
    }

    /// The camera of the coming frame (view space → world space) and its near plane; only
    /// techniques that trace rays use it.
    pub fn set_camera(&self, queue: &wgpu::Queue, camera_to_world: glam::Mat4, near: f32) {
        self.kernel.set_camera(queue, camera_to_world, near);
    }

    /// Rays of the last frame whose BVH traversal overflowed its stack (0 for techniques without
    /// rays). Waits for the GPU.
    pub fn read_stack_overflows(&self, gpu: &crate::Gpu) -> Result<u32, Error> {
        let Some(counter) = self.kernel.stack_overflows() else {
            return Ok(0);
        };
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("stack overflow readback"),
            size: 4,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(counter, 0, &staging, 0, 4);
        gpu.queue.submit([encoder.finish()]);
        let bytes = crate::gpu::read_buffer(gpu, &staging)?;
        Ok(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
    }

    /// For two-phase techniques: per visible pixel, the bit mask of the samples phase 1 flagged
    /// for rays in the last frame (each flagged sample traces one ray in phase 2). Waits for the GPU.
    pub fn read_sample_masks(&self, gpu: &crate::Gpu) -> Result<Option<Vec<u32>>, Error> {
        let Some(records) = self.kernel.phase1_records() else {
            return Ok(None);
        };
        let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("mask readback"),
            size: records.size(),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(records, 0, &staging, 0, records.size());
        gpu.queue.submit([encoder.finish()]);
        let words: Vec<u32> =
            bytemuck::pod_collect_to_vec(&crate::gpu::read_buffer(gpu, &staging)?);
        let pixels = (self.screen.width * self.screen.height) as usize;
        Ok(Some(
            words.chunks_exact(4).take(pixels).map(|r| r[0]).collect(),
        ))
    }

    pub fn settings(&self) -> &AoSettings {
        &self.settings
    }

    pub fn screen(&self) -> ScreenGeometry {
        self.screen
    }

    /// Record the kernel and the blur. `depth` (`R32Float`, linear) and `normals` (a float format,
    /// view space) must cover the guard-banded framebuffer: `(width + 2g) × (height + 2g)`.
    pub fn encode(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        depth: &wgpu::Texture,
        normals: &wgpu::Texture,
        profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        self.encode_with_second_layer(device, encoder, depth, normals, None, profiler)
    }

    /// [`AmbientOcclusion::encode`] with the second depth layer `vao-dual` needs (linear
    /// `R32Float`, the same size as `depth`, e.g. from depth peeling).
    pub fn encode_with_second_layer(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        depth: &wgpu::Texture,
        normals: &wgpu::Texture,
        second_layer: Option<&wgpu::Texture>,
        mut profiler: Option<&mut PassProfiler>,
    ) -> Result<(), Error> {
        let needs_second = self.settings.technique.hidden_depth() == HiddenDepth::DualDepth;
        if needs_second && second_layer.is_none() {
            return Err(Error::Input(format!(
                "technique '{}' needs the second depth layer: use encode_with_second_layer",
                self.settings.technique
            )));
        }
        let (fw, fh) = (self.screen.full_width(), self.screen.full_height());
        let second_layer = second_layer.filter(|_| needs_second);
        let layers = [
            ("depth", Some(depth)),
            ("normals", Some(normals)),
            ("second depth layer", second_layer),
        ];
        for (what, texture) in layers.into_iter().filter_map(|(w, t)| t.map(|t| (w, t))) {
            if (texture.width(), texture.height()) != (fw, fh) {
                return Err(Error::Input(format!(
                    "AO {what} texture is {}x{}, but the screen geometry ({}x{} visible + {} px guard band) needs {fw}x{fh}",
                    texture.width(),
                    texture.height(),
                    self.screen.width,
                    self.screen.height,
                    self.screen.guard_band
                )));
            }
        }
        if depth.format() != wgpu::TextureFormat::R32Float {
            return Err(Error::Input(format!(
                "AO depth texture is {:?}: it must be R32Float linear view depth",
                depth.format()
            )));
        }
        let depth = depth.create_view(&Default::default());
        let normals = normals.create_view(&Default::default());
        let second = second_layer.map(|t| t.create_view(&Default::default()));
        let inputs = FrameInputs {
            depth: &depth,
            normals: &normals,
            second_layer: second.as_ref(),
            screen: self.screen,
        };
        let raw = self.raw.create_view(&Default::default());
        self.kernel
            .encode(device, encoder, &inputs, &raw, profiler.as_deref_mut());
        if let Some(blur) = &self.blur {
            let blurred = self.blurred.create_view(&Default::default());
            blur.encode(device, encoder, &inputs, &raw, &blurred, profiler);
        }
        Ok(())
    }

    /// The final AO (blurred if the blur is enabled).
    pub fn output(&self) -> &wgpu::Texture {
        if self.blur.is_some() {
            &self.blurred
        } else {
            &self.raw
        }
    }

    /// The kernel's AO before the blur.
    pub fn raw_output(&self) -> &wgpu::Texture {
        &self.raw
    }
}
