//! The display image: what the viewer shows, one RGBA8 texture egui draws as it is.
//!
//! The AO, composite, normals and depth views are one small compute pass over obscura's own
//! textures (`display.wgsl`), so the interactive path never reads the GPU back: that is what
//! keeps it at frame rate at 1080p. The debug views that exist only as CPU read-backs (stochastic
//! depth layer, sample masks, requested pixels, the reference) are written into the same texture
//! from the CPU instead ([`Display::write_grey`]).

use anyhow::Result;
// eframe's wgpu is the crate obscura uses (one version in the lock file).
use eframe::wgpu;
use obscura::gpu as ogpu;
use obscura::Gpu;

/// Format of the display texture: egui takes its values as display (sRGB-encoded) values.
pub const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// What the GPU display pass draws (the modes of `display.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GpuMode {
    Ao = 0,
    Composite = 1,
    Normals = 2,
    Depth = 3,
}

/// The inputs of one display pass.
pub struct DisplayInputs<'a> {
    pub mode: GpuMode,
    pub ao_a: &'a wgpu::Texture,
    /// Shown right of `split_x` (the same as `ao_a` without a split).
    pub ao_b: &'a wgpu::Texture,
    pub split_x: Option<u32>,
    pub depth: &'a wgpu::Texture,
    pub normals: &'a wgpu::Texture,
    /// Needed by [`GpuMode::Composite`] only; any framebuffer-sized texture otherwise.
    pub albedo: &'a wgpu::Texture,
    pub guard_band: u32,
    pub depth_max: f32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    mode: u32,
    split_x: u32,
    guard_band: u32,
    depth_max: f32,
}

pub struct Display {
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    texture: wgpu::Texture,
}

impl Display {
    pub fn new(gpu: &Gpu, width: u32, height: u32) -> Self {
        let pipeline = ogpu::compute_pipeline_with(
            &gpu.device,
            "viewer display",
            include_str!("display.wgsl"),
            &[],
        );
        let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("viewer display params"),
            size: std::mem::size_of::<Params>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Self {
            pipeline,
            params,
            texture: Self::target(gpu, width, height),
        }
    }

    fn target(gpu: &Gpu, width: u32, height: u32) -> wgpu::Texture {
        ogpu::texture_2d(
            &gpu.device,
            "viewer display image",
            width.max(1),
            height.max(1),
            FORMAT,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
        )
    }

    /// The image egui shows (and `--screenshot` saves).
    pub fn texture(&self) -> &wgpu::Texture {
        &self.texture
    }

    /// Reallocate the image for a new size; true when it changed (egui must be told).
    pub fn resize(&mut self, gpu: &Gpu, width: u32, height: u32) -> bool {
        if (self.texture.width(), self.texture.height()) == (width.max(1), height.max(1)) {
            return false;
        }
        self.texture = Self::target(gpu, width, height);
        true
    }

    /// Record the display pass into `encoder`.
    pub fn encode(&self, gpu: &Gpu, encoder: &mut wgpu::CommandEncoder, input: &DisplayInputs) {
        let params = Params {
            mode: input.mode as u32,
            split_x: input.split_x.unwrap_or(u32::MAX),
            guard_band: input.guard_band,
            depth_max: input.depth_max.max(1e-6),
        };
        gpu.queue
            .write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let views = [
            view(input.ao_a),
            view(input.ao_b),
            view(input.depth),
            view(input.normals),
            view(input.albedo),
            view(&self.texture),
        ];
        let mut resources: Vec<wgpu::BindingResource> = views
            .iter()
            .map(wgpu::BindingResource::TextureView)
            .collect();
        resources.push(self.params.as_entire_binding());
        let group = ogpu::bind_group(
            &gpu.device,
            "viewer display",
            &self.pipeline.get_bind_group_layout(0),
            &resources,
        );
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("viewer display"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups(
            self.texture.width().div_ceil(8),
            self.texture.height().div_ceil(8),
            1,
        );
    }

    /// Write a CPU image of the display's size: grey values in [0, 1] (NaN: background).
    pub fn write_grey(&self, gpu: &Gpu, grey: &[f32]) {
        let rgba: Vec<u8> = grey
            .iter()
            .flat_map(|&v| {
                if v.is_nan() {
                    BACKGROUND
                } else {
                    let g = (v.clamp(0.0, 1.0) * 255.0).round() as u8;
                    [g, g, g, 255]
                }
            })
            .collect();
        let (w, h) = (self.texture.width(), self.texture.height());
        if rgba.len() != (w * h * 4) as usize {
            return;
        }
        gpu.queue.write_texture(
            self.texture.as_image_copy(),
            &rgba,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * w),
                rows_per_image: Some(h),
            },
            self.texture.size(),
        );
    }

    /// The image as RGBA8 rows (waits for the GPU).
    pub fn read_rgba(&self, gpu: &Gpu) -> Result<Vec<u8>> {
        Ok(ogpu::read_texture_rgba8(gpu, &self.texture)?)
    }
}

/// The background colour of CPU images, as `display.wgsl`'s `BACKGROUND` (sRGB bytes).
pub const BACKGROUND: [u8; 4] = [31, 36, 46, 255];
