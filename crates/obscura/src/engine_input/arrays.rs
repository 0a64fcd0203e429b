//! The engine path for a caller with arrays in CPU memory instead of its own wgpu textures (the
//! Python package's `engine_ao`, a tool reading an engine's frame captures): the arrays are
//! uploaded as the textures an engine would hand over (NDC depth as `R32Float`, normals as
//! `Rgba32Float`), then [`EngineInput`] and [`AmbientOcclusion`] run exactly as for an engine, and
//! the AO comes back. No second code path: only the upload and the read-back are added.

use super::{EngineFrame, EngineInput, EngineNormals, NormalEncoding};
use crate::error::Error;
use crate::gpu::{texture_2d, Gpu};
use crate::pipeline::AmbientOcclusion;
use crate::settings::AoSettings;
use crate::sources::SceneResources;
use crate::view::ScreenGeometry;
use glam::Mat4;

/// The engine's normals as an array of the framebuffer (xyz per pixel, row-major, top row
/// first; need not be unit length).
#[derive(Clone, Copy, Debug)]
pub enum NormalArray<'a> {
    /// None: reconstructed from the depth.
    Reconstruct,
    /// View-space normals (right-handed, camera looking down −Z).
    View(&'a [[f32; 3]]),
    /// World-space normals, with the view matrix (world to view) that turns them.
    World(&'a [[f32; 3]], Mat4),
}

/// One frame as arrays: `depth` holds NDC z in [0, 1] of every framebuffer pixel (guard band
/// included: [`ScreenGeometry::full_width`] × [`ScreenGeometry::full_height`], row-major, top
/// row first), any depth convention `projection` rasterises with.
#[derive(Clone, Copy, Debug)]
pub struct EngineArrays<'a> {
    /// NDC z per framebuffer pixel.
    pub depth: &'a [f32],
    /// The projection the depth was rendered with.
    pub projection: Mat4,
    /// The normals, or none.
    pub normals: NormalArray<'a>,
}

/// The AO of `frame` with `settings` (a technique that needs no scene triangles), the visible
/// size (`screen.width × screen.height`, row-major), 1 = unoccluded. `screen` is usually
/// [`ScreenGeometry::from_projection`] of the same projection. An array of the wrong length is
/// an [`Error::Input`] naming it.
pub fn ao_from_arrays(
    gpu: &Gpu,
    settings: &AoSettings,
    screen: ScreenGeometry,
    frame: &EngineArrays,
) -> Result<Vec<f32>, Error> {
    let size = (screen.full_width(), screen.full_height());
    let texels = size.0 as usize * size.1 as usize;
    let check = |what: &str, len: usize| {
        if len == texels {
            Ok(())
        } else {
            Err(Error::Input(format!(
                "the {what} array has {len} pixels, but the framebuffer ({}x{} with the guard \
                 band) has {texels}: give one value per framebuffer pixel",
                size.0, size.1
            )))
        }
    };
    check("depth", frame.depth.len())?;
    let ao = AmbientOcclusion::new(gpu, settings, screen, SceneResources::default())?;
    let depth = upload(
        gpu,
        size,
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(frame.depth),
    );
    let rgba =
        |n: &[[f32; 3]]| -> Vec<[f32; 4]> { n.iter().map(|v| [v[0], v[1], v[2], 0.0]).collect() };
    let normal_texture = match frame.normals {
        NormalArray::Reconstruct => None,
        NormalArray::View(n) | NormalArray::World(n, _) => {
            check("normals", n.len())?;
            let texels = rgba(n);
            Some(upload(
                gpu,
                size,
                wgpu::TextureFormat::Rgba32Float,
                bytemuck::cast_slice(&texels),
            ))
        }
    };
    let normals = match (frame.normals, &normal_texture) {
        (NormalArray::View(_), Some(texture)) => EngineNormals::View {
            texture,
            encoding: NormalEncoding::Signed,
        },
        (NormalArray::World(_, view_from_world), Some(texture)) => EngineNormals::World {
            texture,
            encoding: NormalEncoding::Signed,
            view_from_world,
        },
        _ => EngineNormals::Reconstruct,
    };
    let input = EngineInput::new(gpu, screen);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let engine_frame = EngineFrame {
        depth: &depth,
        projection: frame.projection,
        normals,
    };
    let textures = input.encode(&mut encoder, &engine_frame)?;
    ao.encode(&mut encoder, textures, None)?;
    gpu.queue.submit([encoder.finish()]);
    ao.read_output()
}

/// A sampled texture of `format` (`texels`: 4 or 16 bytes each) holding `bytes`.
fn upload(
    gpu: &Gpu,
    (w, h): (u32, u32),
    format: wgpu::TextureFormat,
    bytes: &[u8],
) -> wgpu::Texture {
    let texture = texture_2d(
        &gpu.device,
        "engine array",
        w,
        h,
        format,
        wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
    );
    let texel = (bytes.len() / (w as usize * h as usize).max(1)) as u32;
    gpu.queue.write_texture(
        texture.as_image_copy(),
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(texel * w),
            rows_per_image: None,
        },
        texture.size(),
    );
    texture
}
