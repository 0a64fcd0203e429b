//! glTF materials and base-colour images → [`Material`]s and RGBA8 [`Texture`]s.

use glam::{Mat3, Vec2};
use gltf::image::Format;
use gltf::material::AlphaMode as GltfAlpha;
use gltf::Document;
use image::RgbaImage;

use super::super::texture::texture_from_rgba;
use super::super::{AlphaMode, Material, Scene};

/// Where a material's base-colour texture is read: the TEXCOORD set, and the affine map of
/// `KHR_texture_transform` applied to it (identity without the extension).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct BaseColorUv {
    pub set: u32,
    pub transform: Mat3,
}

impl Default for BaseColorUv {
    fn default() -> Self {
        BaseColorUv {
            set: 0,
            transform: Mat3::IDENTITY,
        }
    }
}

impl BaseColorUv {
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.transform.transform_point2(uv)
    }
}

/// `KHR_texture_transform`'s matrix (the extension's README): translation · rotation · scale,
/// the rotation turning UVs by `rotation` radians counter-clockwise in UV space, i.e. the
/// matrix rows (cos, sin) and (−sin, cos).
fn texture_transform(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> Mat3 {
    let (sin, cos) = rotation.sin_cos();
    let turn = Mat3::from_cols_array(&[cos, -sin, 0.0, sin, cos, 0.0, 0.0, 0.0, 1.0]);
    Mat3::from_translation(Vec2::from(offset)) * turn * Mat3::from_scale(Vec2::from(scale))
}

/// Converts every glTF material (same order, so primitive material indices carry over) and the
/// images used as base-colour textures. Returns, per material, where its base-colour texture
/// is read.
pub(super) fn convert(
    doc: &Document,
    images: &[gltf::image::Data],
    scene: &mut Scene,
) -> Result<Vec<BaseColorUv>, String> {
    // glTF image index -> our texture index; only images used as base colour are converted.
    let mut texture_of_image: Vec<Option<u32>> = vec![None; images.len()];
    let mut uvs = Vec::new();
    for (i, m) in doc.materials().enumerate() {
        let pbr = m.pbr_metallic_roughness();
        let mut base_color_texture = None;
        let mut uv = BaseColorUv::default();
        // The specular-glossiness workflow (KHR_materials_pbrSpecularGlossiness, which older
        // exporters wrote): where a material has it, its diffuse colour and texture are what
        // the metallic-roughness base colour is otherwise, alpha included (the extension's
        // README); the metallic-roughness values are then a fallback for readers without it.
        let spec_gloss = m.pbr_specular_glossiness();
        let (factor, texture_info) = match &spec_gloss {
            Some(sg) => (sg.diffuse_factor(), sg.diffuse_texture()),
            None => (pbr.base_color_factor(), pbr.base_color_texture()),
        };
        if let Some(info) = texture_info {
            let image = info.texture().source();
            let index = image.index();
            let data = images
                .get(index)
                .ok_or_else(|| format!("material {i} uses image {index}, which was not loaded"))?;
            if texture_of_image[index].is_none() {
                let name = image
                    .name()
                    .map(str::to_string)
                    .or_else(|| {
                        // A file name, not a whole base64 `data:` URI.
                        let uri = doc.as_json().images.get(index)?.uri.as_ref()?;
                        (!uri.starts_with("data:")).then(|| uri.clone())
                    })
                    .unwrap_or_else(|| format!("image{index}"));
                let rgba = to_rgba8(data).map_err(|e| format!("image {index} ('{name}'): {e}"))?;
                texture_of_image[index] = Some(scene.textures.len() as u32);
                scene.textures.push(texture_from_rgba(name, rgba));
            }
            base_color_texture = texture_of_image[index];
            uv.set = info.tex_coord();
            if let Some(t) = info.texture_transform() {
                uv.set = t.tex_coord().unwrap_or(uv.set);
                uv.transform = texture_transform(t.offset(), t.rotation(), t.scale());
            }
        }
        let alpha_mode = match m.alpha_mode() {
            GltfAlpha::Opaque => AlphaMode::Opaque,
            GltfAlpha::Mask => AlphaMode::Mask {
                cutoff: m.alpha_cutoff().unwrap_or(0.5),
            },
            GltfAlpha::Blend => AlphaMode::Blend,
        };
        scene.materials.push(Material {
            name: m
                .name()
                .map_or_else(|| format!("material{i}"), str::to_string),
            base_color: factor,
            base_color_texture,
            alpha_mode,
            double_sided: m.double_sided(),
        });
        uvs.push(uv);
    }
    Ok(uvs)
}

/// Any decoded glTF image as RGBA8.
///
/// `gltf` names formats after their channel count, but decodes through the `image` crate, so one
/// channel is luma and two are luma + alpha (grey replicated to RGB). 16-bit and float data are
/// native-endian samples; they are rounded to 8 bits (floats clamped to 0..1 as stored: only PNG
/// and JPEG are decoded here, which never produce float images).
pub(super) fn to_rgba8(data: &gltf::image::Data) -> Result<RgbaImage, String> {
    let (channels, bytes) = match data.format {
        Format::R8 => (1, 1),
        Format::R8G8 => (2, 1),
        Format::R8G8B8 => (3, 1),
        Format::R8G8B8A8 => (4, 1),
        Format::R16 => (1, 2),
        Format::R16G16 => (2, 2),
        Format::R16G16B16 => (3, 2),
        Format::R16G16B16A16 => (4, 2),
        Format::R32G32B32FLOAT => (3, 4),
        Format::R32G32B32A32FLOAT => (4, 4),
    };
    let texels = u64::from(data.width) * u64::from(data.height);
    let expected = texels * channels * bytes;
    if texels == 0 || data.pixels.len() as u64 != expected {
        return Err(format!(
            "{}x{} {:?} image holds {} bytes, expected {expected}",
            data.width,
            data.height,
            data.format,
            data.pixels.len()
        ));
    }
    let sample = |s: &[u8]| -> u8 {
        match *s {
            [v] => v,
            [a, b] => ((u32::from(u16::from_ne_bytes([a, b])) * 255 + 32767) / 65535) as u8,
            [a, b, c, d] => {
                // NaN clamps to 0 through `as u8` saturation.
                (f32::from_ne_bytes([a, b, c, d]).clamp(0.0, 1.0) * 255.0).round() as u8
            }
            _ => 0,
        }
    };
    let mut rgba = Vec::with_capacity(texels as usize * 4);
    for px in data.pixels.chunks_exact((channels * bytes) as usize) {
        let c: Vec<u8> = px.chunks_exact(bytes as usize).map(sample).collect();
        let texel = match c.as_slice() {
            [l] => [*l, *l, *l, 255],
            [l, a] => [*l, *l, *l, *a],
            [r, g, b] => [*r, *g, *b, 255],
            [r, g, b, a] => [*r, *g, *b, *a],
            _ => [0, 0, 0, 255],
        };
        rgba.extend_from_slice(&texel);
    }
    RgbaImage::from_raw(data.width, data.height, rgba)
        .ok_or_else(|| "image buffer does not match its size".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn data(format: Format, w: u32, h: u32, pixels: Vec<u8>) -> gltf::image::Data {
        gltf::image::Data {
            pixels,
            format,
            width: w,
            height: h,
        }
    }

    #[test]
    fn converts_every_format_to_rgba8() {
        let one = |format, pixels| to_rgba8(&data(format, 1, 1, pixels)).unwrap().into_raw();
        assert_eq!(one(Format::R8, vec![7]), [7, 7, 7, 255]);
        assert_eq!(one(Format::R8G8, vec![7, 9]), [7, 7, 7, 9]);
        assert_eq!(one(Format::R8G8B8, vec![1, 2, 3]), [1, 2, 3, 255]);
        assert_eq!(one(Format::R8G8B8A8, vec![1, 2, 3, 4]), [1, 2, 3, 4]);
        let w = |v: u16| v.to_ne_bytes();
        assert_eq!(one(Format::R16, w(65535).to_vec()), [255, 255, 255, 255]);
        let la: Vec<u8> = [w(0x8080), w(0)].concat();
        assert_eq!(one(Format::R16G16, la), [128, 128, 128, 0]);
        let rgb: Vec<u8> = [w(0), w(257), w(65535)].concat();
        assert_eq!(one(Format::R16G16B16, rgb), [0, 1, 255, 255]);
        let rgba: Vec<u8> = [w(0), w(257), w(65535), w(514)].concat();
        assert_eq!(one(Format::R16G16B16A16, rgba), [0, 1, 255, 2]);
        let f = |v: f32| v.to_ne_bytes();
        let rgbf: Vec<u8> = [f(0.5), f(2.0), f(f32::NAN)].concat();
        assert_eq!(one(Format::R32G32B32FLOAT, rgbf), [128, 255, 0, 255]);
        let rgbaf: Vec<u8> = [f(0.0), f(1.0), f(-1.0), f(0.25)].concat();
        assert_eq!(one(Format::R32G32B32A32FLOAT, rgbaf), [0, 255, 0, 64]);
    }

    #[test]
    fn rejects_size_mismatch() {
        let err = to_rgba8(&data(Format::R8G8B8, 2, 2, vec![0; 11])).unwrap_err();
        assert!(err.contains("11 bytes"), "{err}");
        assert!(to_rgba8(&data(Format::R8, 0, 5, vec![])).is_err());
    }
}
