//! The files a scene file refers to (glTF buffers and images, OBJ material libraries and
//! textures): read only from the scene's own folder and only where they are regular files (issue
//! 62, defect 2). A scene from elsewhere could otherwise make obscura read any file the user can
//! (`../../.ssh/id_rsa`, `/etc/passwd`, `%2e%2e/…`, `file:///…`) into its buffers and images, or
//! hang it on a FIFO or `/dev/zero`. Everything here looks at metadata only: nothing is opened
//! before it passes.

use std::path::{Path, PathBuf};

use super::SceneError;

/// How [`crate::scene::load_with`] treats the files a scene file refers to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Read referenced files outside the scene file's folder too (`--allow-outside-files`). Off by
    /// default: a scene should not read what it did not come with. Either way only regular files
    /// are read.
    pub allow_outside_files: bool,
}

/// The scene file's folder, as the loaders join references to it ("." for a bare file name).
pub(crate) fn folder(scene: &Path) -> &Path {
    match scene.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Refuses `file`, which scene file `scene` names as `uri`, unless it is a regular file inside
/// the scene's folder (or anywhere, with `options.allow_outside_files`). A file that does not
/// exist passes: nothing can be read from it, and the loader reports it as it always has.
/// Symbolic links are followed (a link inside the folder to a file outside it is outside).
pub(crate) fn check(
    scene: &Path,
    uri: &str,
    file: &Path,
    options: &LoadOptions,
) -> Result<(), SceneError> {
    let Ok(canonical) = file.canonicalize() else {
        return Ok(());
    };
    if !options.allow_outside_files {
        let dir = folder(scene);
        let dir = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
        if !canonical.starts_with(&dir) {
            return Err(SceneError::OutsideFolder {
                scene: scene.to_path_buf(),
                uri: uri.to_string(),
                dir,
            });
        }
    }
    // Metadata, not open: opening a FIFO blocks until a writer comes.
    match std::fs::metadata(&canonical) {
        Ok(m) if m.is_file() => Ok(()),
        Ok(_) => Err(SceneError::NotRegularFile {
            scene: scene.to_path_buf(),
            uri: uri.to_string(),
        }),
        Err(_) => Ok(()),
    }
}

/// Percent-decodes `uri` (glTF's relative references are URIs: `%2e%2e/` is `../`); `None`
/// where the result is not UTF-8.
pub(crate) fn percent_decode(uri: &str) -> Option<String> {
    let bytes = uri.as_bytes();
    let mut decoded = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |j: usize| bytes.get(j).and_then(|&c| (c as char).to_digit(16));
        match (bytes[i], hex(i + 1), hex(i + 2)) {
            (b'%', Some(hi), Some(lo)) => {
                decoded.push((hi * 16 + lo) as u8);
                i += 3;
            }
            (c, _, _) => {
                decoded.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8(decoded).ok()
}

/// The file the `gltf` crate reads for a buffer or image `uri` of a glTF file in folder `base`,
/// as its importer resolves it: `data:` URIs (embedded) and other schemes (refused by `gltf`)
/// name none; `file://` and `file:` the rest as it stands; anything else is percent-decoded and
/// joined to `base`.
pub(crate) fn gltf_uri_file(base: &Path, uri: &str) -> Option<PathBuf> {
    if uri.contains(':') {
        let rest = uri
            .strip_prefix("file://")
            .or_else(|| uri.strip_prefix("file:"))?;
        Some(PathBuf::from(rest))
    } else {
        percent_decode(uri).map(|p| base.join(p))
    }
}
