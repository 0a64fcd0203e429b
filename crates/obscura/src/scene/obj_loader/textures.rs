//! An OBJ material's textures: `map_Kd` (the base colour) and `map_d` (the alpha mask that
//! cuts leaves and fences out of their quads), found on disk however the file names them.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use image::{DynamicImage, GrayImage, RgbaImage};

use super::super::texture::texture_from_rgba;
use super::super::{Scene, Texture};

/// The file a texture or material-library statement names, relative to the first of `dirs`
/// that has it (the OBJ's folder, then each material library's: a library in a subfolder names
/// its textures from there). Files written on Windows name paths with backslashes, and
/// `map_Kd -s 1 1 1 leaf.png`'s options come before the name (the MTL format's `-o`, `-s`,
/// `-bm`, … options, which `tobj` keeps in the name): the name as given, then with `/` for
/// `\`, then its last word, whichever exists first (else the name as given in the first
/// folder, for the error message).
pub(super) fn resolve(dirs: &[PathBuf], name: &str) -> PathBuf {
    let name = name.trim();
    let last_word = name.split_whitespace().last().unwrap_or(name);
    let candidates = [
        name.to_string(),
        name.replace('\\', "/"),
        last_word.to_string(),
        last_word.replace('\\', "/"),
    ];
    candidates
        .iter()
        .flat_map(|c| dirs.iter().map(move |d| d.join(c)))
        .find(|p| p.is_file())
        .unwrap_or_else(|| {
            dirs.first()
                .map_or_else(|| PathBuf::from(name), |d| d.join(name))
        })
}

/// The textures loaded so far, by file (or file pair), each once.
#[derive(Default)]
pub(super) struct TextureCache {
    images: HashMap<PathBuf, Option<DynamicImage>>,
    textures: HashMap<(Option<PathBuf>, Option<PathBuf>), Option<MaterialTexture>>,
}

/// A material's scene texture, and whether its alpha is a `map_d` mask.
#[derive(Clone, Copy)]
pub(super) struct MaterialTexture {
    pub index: u32,
    pub masked: bool,
}

impl TextureCache {
    /// The scene texture of a material with base colour `color` and alpha mask `mask` (either
    /// may be absent; `None` when both are, or neither loads). With a mask the texture's alpha
    /// is the mask (its alpha channel where it has one that is not all opaque, else its grey
    /// level: white opaque) at the mask's resolution, its colour the base colour image's
    /// nearest texel; without, the base colour image as it is.
    pub fn material_texture(
        &mut self,
        obj: &Path,
        color: Option<PathBuf>,
        mask: Option<PathBuf>,
        scene: &mut Scene,
    ) -> Option<MaterialTexture> {
        let key = (color.clone(), mask.clone());
        if let Some(&index) = self.textures.get(&key) {
            return index;
        }
        for file in color.iter().chain(mask.iter()) {
            self.load(obj, file);
        }
        let decoded =
            |file: &Option<PathBuf>| file.as_ref().and_then(|p| self.images.get(p)?.as_ref());
        let (color_image, mask_image) = (decoded(&color), decoded(&mask));
        let texture = match (color_image, mask_image) {
            (color, Some(mask)) => Some(masked(
                color.map(|c| c.to_rgba8()),
                &mask_alpha(mask),
                mask_name(color.as_ref().and(key.0.as_deref()), key.1.as_deref()),
            )),
            (Some(color), None) => Some(texture_from_rgba(
                key.0
                    .as_ref()
                    .map_or(String::new(), |p| p.display().to_string()),
                color.to_rgba8(),
            )),
            (None, None) => None,
        };
        let is_masked = mask_image.is_some();
        let entry = texture.map(|t| {
            scene.textures.push(t);
            MaterialTexture {
                index: (scene.textures.len() - 1) as u32,
                masked: is_masked,
            }
        });
        self.textures.insert(key, entry);
        entry
    }

    /// Decodes image `file` once; a failure is a warning and leaves it out.
    fn load(&mut self, obj: &Path, file: &Path) {
        self.images
            .entry(file.to_path_buf())
            .or_insert_with(|| match image::open(file) {
                Ok(img) => Some(img),
                Err(e) => {
                    log::warn!(
                        "{}: texture '{}' cannot be loaded ({e}); the material goes without it",
                        obj.display(),
                        file.display()
                    );
                    None
                }
            });
    }
}

fn mask_name(color: Option<&Path>, mask: Option<&Path>) -> String {
    let name = |p: Option<&Path>| p.map_or(String::new(), |p| p.display().to_string());
    format!("{} (alpha from {})", name(color), name(mask))
}

/// A `map_d` image as alpha: its alpha channel where it has one that is not all opaque, else
/// its grey level (the usual black-and-white mask).
fn mask_alpha(mask: &DynamicImage) -> GrayImage {
    if mask.color().has_alpha() {
        let rgba = mask.to_rgba8();
        if rgba.pixels().any(|p| p[3] < 255) {
            let (w, h) = rgba.dimensions();
            return GrayImage::from_fn(w, h, |x, y| image::Luma([rgba.get_pixel(x, y)[3]]));
        }
    }
    mask.to_luma8()
}

/// The mask's alpha at its own resolution, with the colour image's nearest texel (white without
/// one).
fn masked(color: Option<RgbaImage>, alpha: &GrayImage, name: String) -> Texture {
    let (w, h) = alpha.dimensions();
    let combined = RgbaImage::from_fn(w, h, |x, y| {
        let rgb = color.as_ref().map_or([255, 255, 255], |c| {
            let cx = ((u64::from(x) * u64::from(c.width())) / u64::from(w)) as u32;
            let cy = ((u64::from(y) * u64::from(c.height())) / u64::from(h)) as u32;
            let p = c.get_pixel(cx.min(c.width() - 1), cy.min(c.height() - 1));
            [p[0], p[1], p[2]]
        });
        image::Rgba([rgb[0], rgb[1], rgb[2], alpha.get_pixel(x, y)[0]])
    });
    texture_from_rgba(name, combined)
}
