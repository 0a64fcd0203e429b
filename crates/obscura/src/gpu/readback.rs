//! Copy textures back to the CPU (tests, image output, the CPU oracle's inputs).
//!
//! Each read is an async function at heart, because a browser maps buffers only from its event
//! loop (WebGPU: wgpu's `poll` cannot wait there, the page must yield); the blocking functions
//! native code uses wait on it with `pollster`, which on native returns as soon as the device
//! poll inside has run the mapping's callback.

use super::{Gpu, GpuError};
use std::future::Future;
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};

/// Read a whole 2D texture with `bytes_per_texel` bytes per texel into a tightly packed vector.
pub fn read_texture_bytes(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, GpuError> {
    read_texture_layer_bytes(gpu, texture, 0, bytes_per_texel)
}

/// [`read_texture_bytes`] of array layer `layer`.
pub fn read_texture_layer_bytes(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    layer: u32,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, GpuError> {
    pollster::block_on(read_texture_layer_bytes_async(
        gpu,
        texture,
        layer,
        bytes_per_texel,
    ))
}

/// [`read_texture_bytes`] without blocking (the only way on the web).
pub async fn read_texture_bytes_async(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, GpuError> {
    read_texture_layer_bytes_async(gpu, texture, 0, bytes_per_texel).await
}

async fn read_texture_layer_bytes_async(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    layer: u32,
    bytes_per_texel: u32,
) -> Result<Vec<u8>, GpuError> {
    let (width, height) = (texture.width(), texture.height());
    let row = width * bytes_per_texel;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d {
                x: 0,
                y: 0,
                z: layer,
            },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);
    let data = read_buffer_async(gpu, &buffer).await?;
    let mut out = Vec::with_capacity((row * height) as usize);
    for y in 0..height as usize {
        let start = y * padded as usize;
        out.extend_from_slice(&data[start..start + row as usize]);
    }
    Ok(out)
}

/// Copy a `COPY_SRC` buffer into a staging buffer and read it (waits for the GPU).
pub fn read_buffer_copy(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let staging = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: buffer.size(),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, buffer.size());
    gpu.queue.submit([encoder.finish()]);
    read_buffer(gpu, &staging)
}

/// Wait for the GPU, then copy a `MAP_READ` buffer's contents out.
pub fn read_buffer(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    pollster::block_on(read_buffer_async(gpu, buffer))
}

/// [`read_buffer`] without blocking: resolves when the buffer is mapped (on native at once, the
/// device poll in [`Gpu::finish`] having waited; in a browser when its event loop maps it).
pub async fn read_buffer_async(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let slice = buffer.slice(..);
    let mapped = Mapped::default();
    let done = mapped.0.clone();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let mut state = done.lock().unwrap();
        state.result = Some(result.map_err(|e| e.to_string()));
        if let Some(waker) = state.waker.take() {
            waker.wake();
        }
    });
    gpu.finish()?;
    mapped
        .await
        .map_err(|e| GpuError::Other(format!("mapping a readback buffer failed: {e}")))?;
    let data = slice.get_mapped_range().to_vec();
    buffer.unmap();
    Ok(data)
}

/// The outcome of one `map_async`, as a future (a one-shot channel; a crate for it would be a
/// dependency for twenty lines).
#[derive(Default)]
struct Mapped(Arc<Mutex<MapState>>);

#[derive(Default)]
struct MapState {
    result: Option<Result<(), String>>,
    waker: Option<Waker>,
}

impl Future for Mapped {
    type Output = Result<(), String>;

    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        let mut state = self.0.lock().unwrap();
        match state.result.take() {
            Some(result) => Poll::Ready(result),
            None => {
                state.waker = Some(cx.waker().clone());
                Poll::Pending
            }
        }
    }
}

/// Read a texture of 32-bit float channels (`R32Float`: 1, `Rgba32Float`: 4, …).
pub fn read_texture_f32(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    channels: u32,
) -> Result<Vec<f32>, GpuError> {
    pollster::block_on(read_texture_f32_async(gpu, texture, channels))
}

/// [`read_texture_f32`] without blocking (the only way on the web).
pub async fn read_texture_f32_async(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    channels: u32,
) -> Result<Vec<f32>, GpuError> {
    let bytes = read_texture_bytes_async(gpu, texture, 4 * channels).await?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// Read an 8-bit RGBA texture.
pub fn read_texture_rgba8(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<u8>, GpuError> {
    read_texture_bytes(gpu, texture, 4)
}
