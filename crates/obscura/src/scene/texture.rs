//! Texture import shared by the loaders: every texture becomes RGBA8, at most 1024 px a side.
//!
//! Downscaling happens here, at load time, so that the rasteriser's alpha test, the BVH's alpha
//! test and the colour composite all read the same texels (see [`super::Texture::alpha_at`]).

use image::{imageops, RgbaImage};

use super::Texture;

/// Largest width or height kept; larger images are scaled down to fit.
pub const MAX_TEXTURE_SIZE: u32 = 1024;

/// Turns a decoded RGBA8 image into a [`Texture`], scaling it down (Triangle filter, aspect kept)
/// when a side exceeds [`MAX_TEXTURE_SIZE`].
pub(crate) fn texture_from_rgba(name: String, image: RgbaImage) -> Texture {
    let (w, h) = image.dimensions();
    let image = if w > MAX_TEXTURE_SIZE || h > MAX_TEXTURE_SIZE {
        let scale = MAX_TEXTURE_SIZE as f64 / f64::from(w.max(h));
        let nw = ((f64::from(w) * scale).round() as u32).clamp(1, MAX_TEXTURE_SIZE);
        let nh = ((f64::from(h) * scale).round() as u32).clamp(1, MAX_TEXTURE_SIZE);
        log::info!("texture '{name}': {w}x{h} scaled down to {nw}x{nh}");
        imageops::resize(&image, nw, nh, imageops::FilterType::Triangle)
    } else {
        image
    };
    Texture {
        name,
        width: image.width(),
        height: image.height(),
        rgba8: image.into_raw(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_textures_are_scaled_to_fit_1024() {
        let img = RgbaImage::from_pixel(2048, 512, image::Rgba([10, 20, 30, 40]));
        let t = texture_from_rgba("big".into(), img);
        assert_eq!((t.width, t.height), (1024, 256));
        assert_eq!(t.rgba8.len(), 1024 * 256 * 4);
        assert_eq!(&t.rgba8[..4], &[10, 20, 30, 40]);

        let tall = RgbaImage::new(3, 5000);
        let t = texture_from_rgba("tall".into(), tall);
        assert_eq!((t.width, t.height), (1, 1024));

        let small = RgbaImage::new(1024, 7);
        let t = texture_from_rgba("small".into(), small);
        assert_eq!((t.width, t.height), (1024, 7));
    }
}
