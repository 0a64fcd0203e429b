//! How passes chain. [`AmbientOcclusion`] is the part an engine embeds: its depth and normals in,
//! an AO texture out. [`renderer::Renderer`] adds our own G-buffer for scenes we load ourselves.

pub mod renderer;

use crate::filter::bilateral::BilateralBlur;
use crate::gpu::PassProfiler;
use crate::hidden::HiddenDepth;
use crate::kernels::{
    svao::SvaoKernel,
    vao::{HiddenSource, RayTracedScene, VaoKernel},
    AoKernel, FrameInputs,
};
use crate::raster::{gpu_scene::GpuScene, stochastic_depth::StochasticDepthMap};
use crate::settings::{AoSettings, Technique};
use crate::view::{FrameView, ScreenGeometry};
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
    /// trace rays or rasterise a stochastic depth map need the scene: use
    /// [`AmbientOcclusion::new_ray_traced`] or [`AmbientOcclusion::new_stochastic`] for them.
    pub fn new(
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
    ) -> Result<Self, Error> {
        let source = match settings.technique.hidden_depth() {
            HiddenDepth::None => HiddenSource::DepthBuffer,
            HiddenDepth::DualDepth => HiddenSource::DualDepth,
            HiddenDepth::ColumnRays => {
                return Err(Error::Input(format!(
                    "technique '{}' traces rays: create it with AmbientOcclusion::new_ray_traced and the scene",
                    settings.technique
                )))
            }
            HiddenDepth::StochasticDepth => {
                return Err(Error::Input(format!(
                    "technique '{}' rasterises a stochastic depth map: create it with AmbientOcclusion::new_stochastic and the scene",
                    settings.technique
                )))
            }
        };
        Self::build(device, settings, screen, source)
    }

    /// [`AmbientOcclusion::new`] for techniques that trace rays, with the scene they trace
    /// (call [`AmbientOcclusion::set_camera`] before each frame).
    pub fn new_ray_traced(
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
        scene: RayTracedScene,
    ) -> Result<Self, Error> {
        if settings.technique.hidden_depth() != HiddenDepth::ColumnRays {
            return Self::new(device, settings, screen);
        }
        Self::build(device, settings, screen, HiddenSource::ColumnRays(scene))
    }

    /// [`AmbientOcclusion::new`] for the stochastic-depth techniques (`sd-vao`, `sd-svao`), with
    /// the scene their map is rasterised from (call [`AmbientOcclusion::set_camera`] before each
    /// frame). The adapter says which sample counts the map can have; an unsupported
    /// `--sd-samples` is an error naming the supported ones.
    pub fn new_stochastic(
        adapter: &wgpu::Adapter,
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
        scene: &GpuScene,
    ) -> Result<Self, Error> {
        if settings.technique.hidden_depth() != HiddenDepth::StochasticDepth {
            return Self::new(device, settings, screen);
        }
        settings.validate()?;
        let map = StochasticDepthMap::new(
            adapter,
            device,
            &settings.stochastic_depth,
            settings.peel_separation,
            (screen.full_width(), screen.full_height()),
            scene,
            (settings.technique == Technique::SdSvao).then_some(settings.stochastic_depth.mask),
        )?;
        Self::build(
            device,
            settings,
            screen,
            HiddenSource::StochasticDepth(Box::new(map)),
        )
    }

    fn build(
        device: &wgpu::Device,
        settings: &AoSettings,
        screen: ScreenGeometry,
        source: HiddenSource,
    ) -> Result<Self, Error> {
        settings.validate()?;
        let view = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("view"),
            contents: bytemuck::bytes_of(&screen.uniform()),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let kernel: Box<dyn AoKernel> = match settings.technique {
            Technique::RtSvao | Technique::RtSvaoDense | Technique::SdSvao => {
                Box::new(SvaoKernel::new(
                    device,
                    &settings.vao,
                    &view,
                    source,
                    &screen,
                    settings.technique != Technique::RtSvaoDense,
                ))
            }
            Technique::Vao | Technique::VaoDual | Technique::RtVao | Technique::SdVao => {
                Box::new(VaoKernel::new(device, &settings.vao, &view, source))
            }
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

    /// The camera of the coming frame; techniques that trace rays or rasterise use it.
    pub fn set_camera(&self, queue: &wgpu::Queue, view: &FrameView) {
        self.kernel.set_camera(queue, view);
    }

    /// The stochastic depth map of the last frame (`sd-vao`, `sd-svao`): every sample layer of
    /// the framebuffer as linear depth, 0 = empty (see [`StochasticDepthMap::read_layers`]).
    /// `sd-svao`'s map is defined only at the pixels phase 1 requested; it reads as empty
    /// elsewhere. Waits for the GPU.
    pub fn read_stochastic_depth(&self, gpu: &crate::Gpu) -> Result<Option<Vec<Vec<f32>>>, Error> {
        let Some(map) = self.kernel.stochastic_depth() else {
            return Ok(None);
        };
        let mut layers = map.read_layers(gpu)?;
        if let Some(requests) = self.read_sd_requests(gpu)? {
            for layer in &mut layers {
                for (z, &r) in layer.iter_mut().zip(&requests) {
                    if r == 0 {
                        *z = 0.0;
                    }
                }
            }
        }
        Ok(Some(layers))
    }

    /// SD-SVAO: the SD-request mask of the last frame, one value per framebuffer pixel (guard
    /// band included), non-zero where phase 1 asked for the stochastic depth map. Waits for the
    /// GPU.
    pub fn read_sd_requests(&self, gpu: &crate::Gpu) -> Result<Option<Vec<u32>>, Error> {
        let Some(buffer) = self.kernel.sd_requests() else {
            return Ok(None);
        };
        Ok(Some(bytemuck::pod_collect_to_vec(&read_whole_buffer(
            gpu, buffer,
        )?)))
    }

    /// Rays of the last frame whose BVH traversal overflowed its stack (0 for techniques without
    /// rays). Waits for the GPU.
    pub fn read_stack_overflows(&self, gpu: &crate::Gpu) -> Result<u32, Error> {
        let Some(counter) = self.kernel.stack_overflows() else {
            return Ok(0);
        };
        let bytes = read_whole_buffer(gpu, counter)?;
        Ok(u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))
    }

    /// For two-phase techniques: per visible pixel, the bit mask of the samples phase 1 flagged
    /// for rays in the last frame (each flagged sample traces one ray in phase 2). Waits for the GPU.
    pub fn read_sample_masks(&self, gpu: &crate::Gpu) -> Result<Option<Vec<u32>>, Error> {
        let Some(records) = self.kernel.phase1_records() else {
            return Ok(None);
        };
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(&read_whole_buffer(gpu, records)?);
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

/// A GPU buffer's bytes (copied to a mappable buffer first). Waits for the GPU.
fn read_whole_buffer(gpu: &crate::Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, Error> {
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    gpu.queue.submit([encoder.finish()]);
    Ok(crate::gpu::read_buffer(gpu, &staging)?)
}
