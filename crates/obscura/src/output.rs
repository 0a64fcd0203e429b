//! Writing images. Every file is written to a temporary sibling and renamed into place, so an
//! error (or Ctrl-C) never leaves a half-written output and never damages an existing file.

use crate::Error;
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

/// Write through `write` into a temporary file beside `path`, then rename it over `path`.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), Error> {
    let dir = parent_dir(path);
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("output");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("tmp");
    // Keep the real extension last: encoders pick the format from it.
    let tmp = dir.join(format!(".{name}.{}.partial.{ext}", std::process::id()));
    if let Ok(mut files) = IN_FLIGHT.lock() {
        files.push(tmp.clone());
    }
    let result = write(&tmp).and_then(|()| std::fs::rename(&tmp, path).map_err(|e| e.to_string()));
    if let Ok(mut files) = IN_FLIGHT.lock() {
        files.retain(|f| f != &tmp);
    }
    if let Err(message) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::Output {
            path: path.to_path_buf(),
            message,
        });
    }
    Ok(())
}

/// A single-channel image read back: `width × height` values, row-major.
pub struct AoImage {
    pub width: u32,
    pub height: u32,
    pub values: Vec<f32>,
}

/// Read an AO image written by [`write_ao`] (or any EXR/PNG): the first channel, as floats
/// (PNG values scaled to [0, 1]).
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
            let image = exr::prelude::read_first_rgba_layer_from_file(
                path,
                |resolution, _| {
                    (
                        resolution.width(),
                        vec![0.0f32; resolution.width() * resolution.height()],
                    )
                },
                |(width, values), position, (r, _g, _b, _a): (f32, f32, f32, f32)| {
                    values[position.y() * *width + position.x()] = r;
                },
            )
            .map_err(|e| fail(e.to_string()))?;
            let (width, values) = image.layer_data.channel_data.pixels;
            let height = values.len() / width.max(1);
            Ok(AoImage {
                width: width as u32,
                height: height as u32,
                values,
            })
        }
    }
}

/// A single-channel AO image (values in [0, 1]) as 8-bit PNG or float EXR.
pub fn write_ao(path: &Path, width: u32, height: u32, ao: &[f32]) -> Result<(), Error> {
    match ImageFormat::from_path(path)? {
        ImageFormat::Png => {
            let bytes: Vec<u8> = ao
                .iter()
                .map(|&v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
                .collect();
            write_atomically(path, |tmp| {
                image::save_buffer(tmp, &bytes, width, height, image::ExtendedColorType::L8)
                    .map_err(|e| e.to_string())
            })
        }
        ImageFormat::Exr => write_atomically(path, |tmp| {
            exr::prelude::write_rgb_file(tmp, width as usize, height as usize, |x, y| {
                let v = ao[y * width as usize + x];
                (v, v, v)
            })
            .map_err(|e| e.to_string())
        }),
    }
}

fn srgb_to_linear(c: f32) -> f32 {
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
    match ImageFormat::from_path(path)? {
        ImageFormat::Png => {
            let bytes: Vec<u8> = linear
                .iter()
                .flat_map(|c| c.map(|v| (linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0).round() as u8))
                .collect();
            write_atomically(path, |tmp| {
                image::save_buffer(tmp, &bytes, width, height, image::ExtendedColorType::Rgb8)
                    .map_err(|e| e.to_string())
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

/// The composite's file name next to an AO output: `ao.png` → `ao.composite.png`.
pub fn composite_path(path: &Path) -> PathBuf {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("ao");
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("png");
    path.with_file_name(format!("{stem}.composite.{ext}"))
}
