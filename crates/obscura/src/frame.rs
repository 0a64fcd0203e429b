//! What every AO pass reads: the frame's first depth layer and normals (guard-banded framebuffer)
//! and its screen geometry, bound as group 0 (`shaders/frame/frame.wgsl`) with the AO output.

use crate::bindings::{
    self, FRAME_AO_OUT, FRAME_BENT_OUT, FRAME_DEPTH, FRAME_NORMALS, FRAME_RAY_GRANT, FRAME_VIEW,
};
use crate::error::Error;
use crate::view::ScreenGeometry;

/// The frame inputs of one encode. Textures cover the whole guard-banded framebuffer.
pub struct FrameInputs<'a> {
    /// Linear view depth (`R32Float`, world units, 0 = background).
    pub depth: &'a wgpu::TextureView,
    /// View-space unit normals facing the camera (any float format; xyz used).
    pub normals: &'a wgpu::TextureView,
    /// The second depth layer from depth peeling (`R32Float`, linear, 0 = none), for `vao-dual`.
    pub second_layer: Option<&'a wgpu::TextureView>,
    /// The screen geometry the textures and the AO output are sized by.
    pub screen: ScreenGeometry,
    /// The uniform of `screen` (`View` in `shaders/common/view.wgsl`).
    pub view: &'a wgpu::Buffer,
}

impl FrameInputs<'_> {
    /// Group 0 of an AO pass writing `output` (`R32Float` storage of the visible size) and, with
    /// `bent_normals`, `bent` (`Rgba16Float` of the same size; a 1×1 one otherwise), reading the
    /// rays each pixel may cast from `ray_grant` under a ray budget (`R32Uint`, visible size; a
    /// 1×1 one otherwise).
    pub(crate) fn group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        output: &wgpu::TextureView,
        bent: &wgpu::TextureView,
        ray_grant: &wgpu::TextureView,
    ) -> wgpu::BindGroup {
        bindings::group(
            device,
            "frame",
            layout,
            &[
                (FRAME_VIEW, self.view.as_entire_binding()),
                (FRAME_DEPTH, wgpu::BindingResource::TextureView(self.depth)),
                (
                    FRAME_NORMALS,
                    wgpu::BindingResource::TextureView(self.normals),
                ),
                (FRAME_AO_OUT, wgpu::BindingResource::TextureView(output)),
                (FRAME_BENT_OUT, wgpu::BindingResource::TextureView(bent)),
                (
                    FRAME_RAY_GRANT,
                    wgpu::BindingResource::TextureView(ray_grant),
                ),
            ],
        )
    }
}

/// Workgroups covering `width`×`height` with 32×8 threads. Measured on an H200 (BENCHMARKS.md):
/// 8×8 groups cost 0.025 ms at 1080p even for a pass that only reads and writes one texel per
/// pixel, 32×8 groups 0.013 ms (fewer workgroup launches).
pub(crate) fn workgroups_32x8(width: u32, height: u32) -> (u32, u32, u32) {
    (width.div_ceil(32), height.div_ceil(8), 1)
}

/// The checks every texture handed to obscura passes: 2D, single-sampled, the framebuffer's size,
/// `TEXTURE_BINDING` usage, and one of `formats`. Errors name the texture and the fix.
pub(crate) fn check_texture(
    screen: &ScreenGeometry,
    what: &str,
    texture: &wgpu::Texture,
    formats: &[wgpu::TextureFormat],
) -> Result<(), Error> {
    check_shape(screen, what, texture)?;
    if !formats.contains(&texture.format()) {
        return Err(Error::Input(format!(
            "{what} texture is {:?}: use one of {formats:?}",
            texture.format()
        )));
    }
    Ok(())
}

/// [`check_texture`] for a texture read as floats (any format with a float sample type).
pub(crate) fn check_float_texture(
    screen: &ScreenGeometry,
    what: &str,
    texture: &wgpu::Texture,
) -> Result<(), Error> {
    check_shape(screen, what, texture)?;
    let float = matches!(
        texture.format().sample_type(None, None),
        Some(wgpu::TextureSampleType::Float { .. })
    );
    if !float {
        return Err(Error::Input(format!(
            "{what} texture is {:?}, which is not read as floats: use a float or unorm format \
             (e.g. Rgba16Float, Rgba8Unorm)",
            texture.format()
        )));
    }
    Ok(())
}

fn check_shape(screen: &ScreenGeometry, what: &str, texture: &wgpu::Texture) -> Result<(), Error> {
    if !texture
        .usage()
        .contains(wgpu::TextureUsages::TEXTURE_BINDING)
    {
        return Err(Error::Input(format!(
            "{what} texture lacks the TEXTURE_BINDING usage (it has {:?}): create it with \
             TextureUsages::TEXTURE_BINDING",
            texture.usage()
        )));
    }
    if texture.sample_count() != 1 {
        return Err(Error::Input(format!(
            "{what} texture has {} samples: resolve it to a single-sampled texture first",
            texture.sample_count()
        )));
    }
    if texture.dimension() != wgpu::TextureDimension::D2 || texture.depth_or_array_layers() != 1 {
        return Err(Error::Input(format!(
            "{what} texture must be one 2D layer (it is {:?} with {} layers)",
            texture.dimension(),
            texture.depth_or_array_layers()
        )));
    }
    let (fw, fh) = (screen.full_width(), screen.full_height());
    if (texture.width(), texture.height()) != (fw, fh) {
        return Err(Error::Input(format!(
            "{what} texture is {}x{}, but the screen geometry ({}x{} visible + {} px guard band) \
             needs {fw}x{fh}",
            texture.width(),
            texture.height(),
            screen.width,
            screen.height,
            screen.guard_band
        )));
    }
    Ok(())
}
