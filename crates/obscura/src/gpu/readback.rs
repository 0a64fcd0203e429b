//! Copy textures back to the CPU (tests, image output, the CPU oracle's inputs).

use super::{Gpu, GpuError};

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
    let data = read_buffer(gpu, &buffer)?;
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
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    gpu.finish()?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| GpuError::Other(format!("mapping a readback buffer failed: {e}")))?
        .to_vec();
    buffer.unmap();
    Ok(data)
}

/// Read a texture of 32-bit float channels (`R32Float`: 1, `Rgba32Float`: 4, …).
pub fn read_texture_f32(
    gpu: &Gpu,
    texture: &wgpu::Texture,
    channels: u32,
) -> Result<Vec<f32>, GpuError> {
    let bytes = read_texture_bytes(gpu, texture, 4 * channels)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// Read an 8-bit RGBA texture.
pub fn read_texture_rgba8(gpu: &Gpu, texture: &wgpu::Texture) -> Result<Vec<u8>, GpuError> {
    read_texture_bytes(gpu, texture, 4)
}
