//! A disk cache of reference images: a reference for the same scene, camera, size, guard band and
//! reference settings is computed once and reused (`obscura compare` and `demo`).
//!
//! Entries live in `$OBSCURA_CACHE_DIR`, else `$XDG_CACHE_HOME/obscura/references`, else
//! `~/.cache/obscura/references`. An entry is one file: the full key text on the first line, then
//! the image as little-endian f32. The key is checked on load, so a hash collision or a stale
//! format is a miss, never a wrong image. Scenes are keyed by their content
//! ([`Scene::fingerprint`]), so an edited file, or one loaded with other options, is recomputed.

use super::ground_truth::ReferenceSettings;
use crate::scene::Scene;
use crate::view::FrameView;
use std::path::{Path, PathBuf};

/// Bumped whenever the reference computation changes its results.
const FORMAT: &str = "obscura-reference-v2";

/// Where the entries live: `$OBSCURA_CACHE_DIR`, else `$XDG_CACHE_HOME/obscura/references`, else
/// `~/.cache/obscura/references` (under the temporary directory when `HOME` is unset too).
pub fn cache_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("OBSCURA_CACHE_DIR") {
        return PathBuf::from(dir);
    }
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    base.join("obscura").join("references")
}

/// The full key of a reference image.
pub fn key(scene: &Scene, view: &FrameView, settings: &ReferenceSettings) -> String {
    format!(
        "{FORMAT}|scene {:016x}|{:?}|{}x{}+{}|near {}|{:?}",
        scene.fingerprint(),
        view.camera,
        view.width,
        view.height,
        view.guard_band,
        view.near,
        settings
    )
}

fn entry_path(dir: &Path, key: &str) -> PathBuf {
    dir.join(format!(
        "{:016x}.ref",
        crate::hash::Fnv1a::of(key.as_bytes())
    ))
}

/// The cached image for `key` with `pixels` values, if present and intact.
pub fn load(dir: &Path, key: &str, pixels: usize) -> Option<Vec<f32>> {
    let bytes = std::fs::read(entry_path(dir, key)).ok()?;
    let newline = bytes.iter().position(|&b| b == b'\n')?;
    if &bytes[..newline] != key.as_bytes() || bytes.len() - newline - 1 != pixels * 4 {
        return None;
    }
    Some(
        bytes[newline + 1..]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect(),
    )
}

/// Store `image` under `key` (atomically; a failure only costs a recomputation next time).
pub fn store(dir: &Path, key: &str, image: &[f32]) -> Result<(), crate::error::Error> {
    std::fs::create_dir_all(dir).map_err(|e| crate::error::Error::Output {
        path: dir.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut bytes = Vec::with_capacity(key.len() + 1 + image.len() * 4);
    bytes.extend_from_slice(key.as_bytes());
    bytes.push(b'\n');
    bytes.extend(image.iter().flat_map(|v| v.to_le_bytes()));
    crate::output::write_atomically(&entry_path(dir, key), |tmp| {
        std::fs::write(tmp, &bytes).map_err(|e| e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Camera;
    use glam::Vec3;

    #[test]
    fn round_trip_and_key_mismatch() {
        let dir = std::env::temp_dir().join(format!("obscura-cache-test-{}", std::process::id()));
        let camera = Camera {
            eye: Vec3::new(0.0, 1.0, 3.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_deg: 60.0,
        };
        let view = FrameView::new(camera, 4, 2, 1, 1e-3);
        let settings = ReferenceSettings::default();
        let stairs = crate::scene::builtin("stairs").unwrap();
        let k = key(&stairs, &view, &settings);
        let image = [0.0, 0.25, 0.5, 0.75, 1.0, 0.125, 0.375, 0.625];
        assert!(load(&dir, &k, 8).is_none());
        store(&dir, &k, &image).unwrap();
        assert_eq!(load(&dir, &k, 8).unwrap(), image);
        // Any change of the inputs is another key; a wrong size is a miss.
        let other = ReferenceSettings {
            spp: 64,
            ..settings
        };
        assert_ne!(key(&stairs, &view, &other), k);
        let colonnade = crate::scene::builtin("colonnade").unwrap();
        assert_ne!(key(&colonnade, &view, &settings), k);
        let mut culled = stairs.clone();
        culled.set_sidedness(crate::scene::Sidedness::CullBackFaces);
        assert_ne!(
            key(&culled, &view, &settings),
            k,
            "other sides, other scene"
        );
        assert!(load(&dir, &k, 9).is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
