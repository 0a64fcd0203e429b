//! Writing the report files: PNG encoding and all-or-nothing staging.

use super::ReportError;
use ::image::codecs::png::PngEncoder;
use ::image::{ExtendedColorType, ImageEncoder};
use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Pixel layout of [`write_png`]'s input.
#[derive(Clone, Copy)]
pub(super) enum Color {
    /// One byte per pixel.
    Grey,
    /// Three bytes per pixel.
    Rgb,
}

/// AO values as 8-bit grey: clamped to `[0, 1]`, times 255, rounded (the
/// same mapping as `output::write_ao`, so the pictures match the renderer's).
pub(super) fn grey8(ao: &[f32]) -> Vec<u8> {
    ao.iter()
        .map(|&v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect()
}

/// Encodes `pixels` as a PNG into `out`.
pub(super) fn write_png(
    out: &mut dyn Write,
    width: u32,
    height: u32,
    pixels: &[u8],
    color: Color,
) -> Result<(), String> {
    let color = match color {
        Color::Grey => ExtendedColorType::L8,
        Color::Rgb => ExtendedColorType::Rgb8,
    };
    PngEncoder::new(out)
        .write_image(pixels, width, height, color)
        .map_err(|e| format!("PNG encoding failed: {e}"))
}

/// A file written under its temporary name, waiting to be renamed.
struct Staged {
    partial: PathBuf,
    target: PathBuf,
}

/// Files of one report, first written as `.NAME.partial` siblings and only
/// renamed into place by [`Staging::commit`] once all of them were written.
/// Dropping a `Staging` without committing (an error return) removes its
/// temporary files, so a failure leaves nothing behind.
pub(super) struct Staging {
    dir: PathBuf,
    staged: Vec<Staged>,
}

impl Staging {
    pub(super) fn new(dir: &Path) -> Self {
        Staging {
            dir: dir.to_path_buf(),
            staged: Vec::new(),
        }
    }

    /// Writes `name` (a plain file name in the directory) to its temporary
    /// sibling through `write`.
    pub(super) fn stage(
        &mut self,
        name: &str,
        write: impl FnOnce(&mut dyn Write) -> Result<(), String>,
    ) -> Result<(), ReportError> {
        let target = self.dir.join(name);
        // A rename onto a directory fails; finding out now, before anything
        // was renamed, keeps the commit all-or-nothing in this case.
        if target.is_dir() {
            return Err(ReportError::Io {
                path: target,
                message: "a directory is in the way of this report file: remove or rename it, \
                          or write the report into another directory"
                    .to_owned(),
            });
        }
        let partial = self.dir.join(format!(".{name}.partial"));
        let result = File::create(&partial)
            .map_err(|e| {
                format!(
                    "could not create the temporary file '{}': {e} (check that the directory \
                     is writable)",
                    partial.display()
                )
            })
            .and_then(|file| {
                let mut out = BufWriter::new(file);
                write(&mut out)?;
                // `BufWriter`'s drop would swallow a failing final write
                // (e.g. a full disk).
                out.into_inner()
                    .map_err(|e| e.error().to_string())
                    .map(drop)
            });
        match result {
            Ok(()) => {
                self.staged.push(Staged { partial, target });
                Ok(())
            }
            Err(message) => {
                // If `partial` could not be created, this fails harmlessly;
                // in particular it never removes a directory.
                let _ = fs::remove_file(&partial);
                Err(ReportError::Io {
                    path: target,
                    message,
                })
            }
        }
    }

    /// Renames every staged file into place, in staging order. Should a
    /// rename fail (rare: same directory, and directories in the way were
    /// rejected by [`Staging::stage`]), the files renamed so far are removed
    /// again, so that the directory does not hold a mix of this report and an
    /// older one that only looks complete.
    pub(super) fn commit(mut self) -> Result<(), ReportError> {
        let staged = std::mem::take(&mut self.staged);
        for (i, s) in staged.iter().enumerate() {
            if let Err(e) = fs::rename(&s.partial, &s.target) {
                for done in &staged[..i] {
                    let _ = fs::remove_file(&done.target);
                }
                for pending in &staged[i..] {
                    let _ = fs::remove_file(&pending.partial);
                }
                return Err(ReportError::Io {
                    path: s.target.clone(),
                    message: format!("could not rename '{}' into place: {e}", s.partial.display()),
                });
            }
        }
        Ok(())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        for s in &self.staged {
            let _ = fs::remove_file(&s.partial);
        }
    }
}
