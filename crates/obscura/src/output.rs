//! Writing images. Every file is written to a temporary sibling and renamed into place, so an
//! error (or Ctrl-C) never leaves a half-written output and never damages an existing file.

use crate::error::Error;
use std::path::{Path, PathBuf};

/// Output formats, chosen by the file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit greyscale / sRGB colour.
    Png,
    /// 32-bit float, linear.
    Exr,
}

impl ImageFormat {
    /// The format `path`'s extension names (`.png` or `.exr`, any case); any other is an
    /// [`Error::Input`] saying which to use.
    pub fn from_path(path: &Path) -> Result<Self, Error> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
        {
            Some(e) if e == "png" => Ok(ImageFormat::Png),
            Some(e) if e == "exr" => Ok(ImageFormat::Exr),
            _ => Err(Error::Input(format!(
                "output '{}' has no supported extension: use .png (8-bit) or .exr (32-bit float)",
                path.display()
            ))),
        }
    }
}

/// Fails early, before any GPU work, when `path` cannot be written.
pub fn check_writable(path: &Path) -> Result<ImageFormat, Error> {
    let format = ImageFormat::from_path(path)?;
    let dir = parent_dir(path);
    if !dir.is_dir() {
        return Err(Error::Input(format!(
            "output directory '{}' of '{}' does not exist: create it first",
            dir.display(),
            path.display()
        )));
    }
    if path.is_dir() {
        return Err(Error::Input(format!(
            "output '{}' is a directory: give a file name",
            path.display()
        )));
    }
    Ok(format)
}

fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Temporary files being written right now, so an interrupt handler can remove them
/// ([`remove_partial_files`]).
static IN_FLIGHT: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Remove every temporary file still being written (call from a Ctrl-C handler before exiting):
/// an interrupted run leaves neither a half-written output nor a stray temporary file.
pub fn remove_partial_files() {
    if let Ok(files) = IN_FLIGHT.lock() {
        for f in files.iter() {
            let _ = std::fs::remove_file(f);
        }
    }
}

/// The `attempt`-th name [`write_atomically`] tries for its temporary file beside `path`: hidden,
/// the process id (concurrent runs do not collide), a counter after the first, and the real
/// extension last (encoders pick the format from it).
pub fn partial_file_name(path: &Path, attempt: u32) -> PathBuf {
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("output");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("tmp");
    let pid = std::process::id();
    parent_dir(path).join(match attempt {
        0 => format!(".{name}.{pid}.partial.{ext}"),
        k => format!(".{name}.{pid}.{k}.partial.{ext}"),
    })
}

/// How many names [`write_atomically`] tries before giving up.
const PARTIAL_ATTEMPTS: u32 = 100;

/// The identity of a file (device and inode on Unix), to tell whether the name still holds the
/// file we created.
#[cfg(unix)]
fn identity(m: &std::fs::Metadata) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    Some((m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn identity(_: &std::fs::Metadata) -> Option<(u64, u64)> {
    None
}

/// Write through `write` into a temporary file beside `path`, then rename it over `path`.
///
/// The temporary file is created here, exclusively (issue 62, defect 3): its name is predictable
/// (`.NAME.PID.partial.EXT`), and opening an existing name would follow a symbolic link planted
/// there and overwrite the link's target. `create_new` refuses any existing name, a link included
/// (without following it), and the next name is tried. `write` then reopens the file by path (the
/// encoders write to paths), so before the rename the name must still hold the regular file
/// created here; anything else (a link swapped in meanwhile) is refused and left alone.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), Error> {
    let fail = |message: String| Error::Output {
        path: path.to_path_buf(),
        message,
    };
    let mut created = None;
    for attempt in 0..PARTIAL_ATTEMPTS {
        let tmp = partial_file_name(path, attempt);
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(file) => {
                created = Some((tmp, file.metadata().ok().and_then(|m| identity(&m))));
                break;
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => {
                return Err(fail(format!(
                    "cannot create a temporary file '{}' beside it: {e}",
                    tmp.display()
                )))
            }
        }
    }
    let Some((tmp, id)) = created else {
        return Err(fail(format!(
            "{PARTIAL_ATTEMPTS} temporary names beside it are taken (e.g. '{}'): remove the \
             stale '.*.partial.*' files there",
            partial_file_name(path, 0).display()
        )));
    };
    if let Ok(mut files) = IN_FLIGHT.lock() {
        files.push(tmp.clone());
    }
    let still_ours = || match std::fs::symlink_metadata(&tmp) {
        Ok(m) if m.file_type().is_file() && identity(&m) == id => Ok(()),
        _ => Err(format!(
            "the temporary file '{}' was replaced while it was written (by a link or another \
             file); nothing was renamed: check who else writes to that folder",
            tmp.display()
        )),
    };
    let result = write(&tmp)
        .and_then(|()| still_ours())
        .and_then(|()| std::fs::rename(&tmp, path).map_err(|e| e.to_string()));
    if let Ok(mut files) = IN_FLIGHT.lock() {
        files.retain(|f| f != &tmp);
    }
    if let Err(message) = result {
        // Only what is still ours: a name someone else swapped in is not removed either.
        if still_ours().is_ok() {
            let _ = std::fs::remove_file(&tmp);
        }
        return Err(fail(message));
    }
    Ok(())
}

/// A single-channel image read back: `width × height` values, row-major.
pub struct AoImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` values, row-major from the top row (AO: 1 = unoccluded).
    pub values: Vec<f32>,
}

/// Read an AO image written by [`write_ao`] (or any EXR/PNG): its one channel (`Y`, else `R`,
/// else the first; PNG grey, alpha dropped), as floats (PNG values scaled to [0, 1]).
pub fn read_ao(path: &Path) -> Result<AoImage, Error> {
    let fail = |message: String| {
        Error::Input(format!("cannot read image '{}': {message}", path.display()))
    };
    match ImageFormat::from_path(path)? {
        ImageFormat::Png => {
            let image = image::open(path)
                .map_err(|e| fail(e.to_string()))?
                .to_luma32f();
            Ok(AoImage {
                width: image.width(),
                height: image.height(),
                values: image.into_raw(),
            })
        }
        ImageFormat::Exr => {
            let image = exr::prelude::read_first_flat_layer_from_file(path)
                .map_err(|e| fail(e.to_string()))?;
            let layer = image.layer_data;
            let channels = &layer.channel_data.list;
            let named = |name: &str| channels.iter().find(|c| c.name.to_string() == name);
            let channel = named("Y")
                .or_else(|| named("R"))
                .or(channels.first())
                .ok_or_else(|| fail("it has no channels".into()))?;
            Ok(AoImage {
                width: layer.size.width() as u32,
                height: layer.size.height() as u32,
                values: channel.sample_data.values_as_f32().collect(),
            })
        }
    }
}

/// A single-channel AO image (values in [0, 1]): 8-bit grey PNG, or float EXR with one channel
/// `Y`.
pub fn write_ao(path: &Path, width: u32, height: u32, ao: &[f32]) -> Result<(), Error> {
    write_ao_image(path, width, height, ao, None)
}

/// [`write_ao`] that marks the background (`covered[i]` false: no geometry at pixel `i`): alpha 0
/// there in a PNG (grey + alpha), so an auto-framed model stands out from its white
/// surroundings. EXR stays one channel (`Y`, background 1): its readers take AO as data.
pub fn write_ao_covered(
    path: &Path,
    width: u32,
    height: u32,
    ao: &[f32],
    covered: &[bool],
) -> Result<(), Error> {
    write_ao_image(path, width, height, ao, Some(covered))
}

fn write_ao_image(
    path: &Path,
    width: u32,
    height: u32,
    ao: &[f32],
    covered: Option<&[bool]>,
) -> Result<(), Error> {
    let grey = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    match ImageFormat::from_path(path)? {
        ImageFormat::Png => {
            let (bytes, color): (Vec<u8>, _) = match covered {
                None => (
                    ao.iter().map(|&v| grey(v)).collect(),
                    image::ExtendedColorType::L8,
                ),
                Some(covered) => (
                    ao.iter()
                        .zip(covered)
                        .flat_map(|(&v, &c)| [grey(v), if c { 255 } else { 0 }])
                        .collect(),
                    image::ExtendedColorType::La8,
                ),
            };
            write_atomically(path, |tmp| {
                image::save_buffer(tmp, &bytes, width, height, color).map_err(|e| e.to_string())
            })
        }
        ImageFormat::Exr => {
            let bytes = ao_exr_bytes(width, height, ao)?;
            write_atomically(path, |tmp| {
                std::fs::write(tmp, &bytes).map_err(|e| e.to_string())
            })
        }
    }
}

/// The float EXR file [`write_ao`] writes (one channel `Y`), in memory: what a web page offers
/// for download and hands its tests, to compare with the CLI's file (`obscura diff`).
pub fn ao_exr_bytes(width: u32, height: u32, ao: &[f32]) -> Result<Vec<u8>, Error> {
    use exr::prelude::{Image, SpecificChannels, WritableImage};
    let pixels = width as usize * height as usize;
    if ao.len() != pixels {
        return Err(Error::Input(format!(
            "an AO image of {width}x{height} has {pixels} values, not {}",
            ao.len()
        )));
    }
    let channels = SpecificChannels::build()
        .with_channel("Y")
        .with_pixel_fn(|p| (ao[p.y() * width as usize + p.x()],));
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_channels((width as usize, height as usize), channels)
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| Error::Input(format!("cannot encode the AO as EXR: {e}")))?;
    Ok(bytes.into_inner())
}

/// An sRGB-encoded value in [0, 1] as linear light.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// AO × base colour (`albedo` sRGB-encoded), as sRGB PNG or linear EXR.
pub fn write_composite(
    path: &Path,
    width: u32,
    height: u32,
    ao: &[f32],
    albedo: &[[u8; 4]],
) -> Result<(), Error> {
    let linear: Vec<[f32; 3]> = ao
        .iter()
        .zip(albedo)
        .map(|(&a, c)| [0, 1, 2].map(|i| srgb_to_linear(f32::from(c[i]) / 255.0) * a))
        .collect();
    write_rgb(path, width, height, &linear, None)
}

/// A simple lit composite, so that AO reads on any model (a grey model under plain AO × colour
/// is grey on grey): base colour × (sky light × AO + sun), written as sRGB PNG with the background
/// transparent, or as linear RGB EXR.
///
/// `normals` are world-space unit normals of the visible pixels, zero where there is no geometry.
/// The light is fixed and documented rather than physical: a hemisphere sky of radiance 1 above
/// fading to 0.25 below (`0.625 + 0.375 n_y`, the irradiance of such a sky up to π), darkened by
/// AO as ambient light is in engines, plus an unshadowed sun of strength 0.6 from
/// `normalize(0.4, 1, 0.3)` (AO does not darken direct light). Total weights keep a white,
/// unoccluded, sun-facing surface near 1.
pub fn write_lit_composite(
    path: &Path,
    width: u32,
    height: u32,
    ao: &[f32],
    albedo: &[[u8; 4]],
    normals: &[glam::Vec3],
) -> Result<(), Error> {
    let sun = glam::Vec3::new(0.4, 1.0, 0.3).normalize();
    let linear: Vec<[f32; 3]> = ao
        .iter()
        .zip(albedo)
        .zip(normals)
        .map(|((&a, c), n)| {
            let sky = 0.625 + 0.375 * n.y;
            let light = 0.55 * sky * a + 0.6 * n.dot(sun).max(0.0);
            [0, 1, 2].map(|i| srgb_to_linear(f32::from(c[i]) / 255.0) * light)
        })
        .collect();
    let covered: Vec<bool> = normals.iter().map(|n| *n != glam::Vec3::ZERO).collect();
    write_rgb(path, width, height, &linear, Some(&covered))
}

/// Linear RGB as sRGB PNG (alpha 0 where `covered` is false) or linear EXR.
fn write_rgb(
    path: &Path,
    width: u32,
    height: u32,
    linear: &[[f32; 3]],
    covered: Option<&[bool]>,
) -> Result<(), Error> {
    let encode =
        |c: &[f32; 3]| c.map(|v| (linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as u8);
    match ImageFormat::from_path(path)? {
        ImageFormat::Png => {
            let (bytes, color): (Vec<u8>, _) = match covered {
                None => (
                    linear.iter().flat_map(encode).collect(),
                    image::ExtendedColorType::Rgb8,
                ),
                Some(covered) => (
                    linear
                        .iter()
                        .zip(covered)
                        .flat_map(|(c, &k)| {
                            let [r, g, b] = encode(c);
                            [r, g, b, if k { 255 } else { 0 }]
                        })
                        .collect(),
                    image::ExtendedColorType::Rgba8,
                ),
            };
            write_atomically(path, |tmp| {
                image::save_buffer(tmp, &bytes, width, height, color).map_err(|e| e.to_string())
            })
        }
        ImageFormat::Exr => write_atomically(path, |tmp| {
            exr::prelude::write_rgb_file(tmp, width as usize, height as usize, |x, y| {
                let c = linear[y * width as usize + x];
                (c[0], c[1], c[2])
            })
            .map_err(|e| e.to_string())
        }),
    }
}

/// The lit composite's file name next to an AO output: `ao.png` → `ao.lit.png`.
pub fn lit_path(path: &Path) -> PathBuf {
    tagged_sibling(path, "lit")
}

/// `dir/stem.TAG.ext` for `dir/stem.ext`.
fn tagged_sibling(path: &Path, tag: &str) -> PathBuf {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("ao");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("png");
    path.with_file_name(format!("{stem}.{tag}.{ext}"))
}

/// The composite's file name next to an AO output: `ao.png` → `ao.composite.png`.
pub fn composite_path(path: &Path) -> PathBuf {
    tagged_sibling(path, "composite")
}

/// The bent-normal image's file name next to an AO output: `ao.png` → `ao.bent.png`.
pub fn bent_normals_path(path: &Path) -> PathBuf {
    tagged_sibling(path, "bent")
}

/// Bent normals (`bent_normals`; [`crate::AmbientOcclusion::bent_normals`]): view-space unit
/// vectors (right-handed, camera looking down −Z), `w` 1 on geometry and 0 on background. PNG:
/// RGBA8 with RGB = round(255 · (0.5 · xyz + 0.5)), no sRGB curve (a normal map's usual
/// encoding), alpha 255 on geometry and 0 on background. EXR: the raw xyz as RGB floats (0 on
/// background).
pub fn write_bent_normals(
    path: &Path,
    width: u32,
    height: u32,
    bent: &[[f32; 4]],
) -> Result<(), Error> {
    match ImageFormat::from_path(path)? {
        ImageFormat::Png => {
            let encode = |v: f32| ((0.5 * v + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8;
            let bytes: Vec<u8> = bent
                .iter()
                .flat_map(|b| {
                    [
                        encode(b[0]),
                        encode(b[1]),
                        encode(b[2]),
                        if b[3] > 0.0 { 255 } else { 0 },
                    ]
                })
                .collect();
            write_atomically(path, |tmp| {
                image::save_buffer(tmp, &bytes, width, height, image::ExtendedColorType::Rgba8)
                    .map_err(|e| e.to_string())
            })
        }
        ImageFormat::Exr => write_atomically(path, |tmp| {
            exr::prelude::write_rgb_file(tmp, width as usize, height as usize, |x, y| {
                let b = bent[y * width as usize + x];
                (b[0], b[1], b[2])
            })
            .map_err(|e| e.to_string())
        }),
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    /// Issue 62, defect 3: a symbolic link planted at the temporary file's predictable name must
    /// not be followed.
    #[test]
    fn a_planted_link_at_the_temporary_name_is_not_followed() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("ao.png");
        let victim = dir.path().join("victim.txt");
        std::fs::write(&victim, b"precious").unwrap();
        // The first two names this process would use, both links to the victim (a dangling
        // link too: create_new must not create its target either).
        std::os::unix::fs::symlink(&victim, partial_file_name(&out, 0)).unwrap();
        let absent = dir.path().join("absent.txt");
        std::os::unix::fs::symlink(&absent, partial_file_name(&out, 1)).unwrap();
        write_atomically(&out, |tmp| {
            std::fs::write(tmp, b"image").map_err(|e| e.to_string())
        })
        .unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
        assert!(!absent.exists());
        assert_eq!(std::fs::read(&out).unwrap(), b"image");
        // The planted links are not ours to remove; our own temporary file is gone.
        assert!(partial_file_name(&out, 0).symlink_metadata().is_ok());
        assert!(!partial_file_name(&out, 2).exists());

        // A link swapped in while the encoder writes is refused, not renamed into place.
        let out2 = dir.path().join("ao2.png");
        let err = write_atomically(&out2, |tmp| {
            std::fs::remove_file(tmp).unwrap();
            std::os::unix::fs::symlink(&victim, tmp).unwrap();
            Ok(())
        })
        .unwrap_err();
        assert!(err.to_string().contains("was replaced"), "{err}");
        assert!(!out2.exists());
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
    }
}
