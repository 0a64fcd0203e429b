//! What every rendering call shares: the image size and guard band, and the camera given as a
//! `Camera`, a camera name or nothing (the scene's default, by the CLI's rule).

use crate::errors::input;
use crate::scene::{Camera, Scene};
use pyo3::prelude::*;

/// The visible size and guard band of one call, checked as the CLI checks `--size`.
#[derive(Clone, Copy)]
pub struct Size {
    pub width: u32,
    pub height: u32,
    pub guard_band: u32,
}

/// The most pixels on a side (the CLI's `--size` limit).
const MAX_SIDE: u32 = 16384;

impl Size {
    /// `guard_band` None: the library's default for the height (64 px at 1080p, scaled).
    pub fn new(width: u32, height: u32, guard_band: Option<u32>) -> PyResult<Self> {
        if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
            return Err(input(format!(
                "size {width}x{height}: width and height must be 1 to {MAX_SIDE} px"
            )));
        }
        Ok(Size {
            width,
            height,
            guard_band: guard_band.unwrap_or_else(|| obscura::default_guard_band(height)),
        })
    }

    /// The library's renderer of this size for `scene` and `settings`.
    pub fn renderer(
        &self,
        gpu: &obscura::Gpu,
        scene: &obscura::scene::Scene,
        settings: &obscura::AoSettings,
    ) -> Result<obscura::Renderer, obscura::Error> {
        obscura::Renderer::new(
            gpu,
            scene,
            settings,
            self.width,
            self.height,
            self.guard_band,
        )
    }

    /// The frame of `camera` at this size, with the scene's near plane (what the reference
    /// traces and reports compare over).
    pub fn frame_view(
        &self,
        camera: obscura::scene::Camera,
        scene: &obscura::scene::Scene,
    ) -> obscura::FrameView {
        obscura::FrameView::new(
            camera,
            self.width,
            self.height,
            self.guard_band,
            obscura::near_plane(scene),
        )
    }
}

/// `camera=`: a `Camera`, a name of one of the scene's cameras, or None (the first named
/// camera, else an automatic one).
pub fn camera_of(
    py: Python<'_>,
    scene: &Bound<'_, Scene>,
    camera: Option<&Bound<'_, PyAny>>,
    size: Size,
) -> PyResult<Camera> {
    let aspect = size.width as f32 / size.height as f32;
    match camera {
        Some(c) if !c.is_none() => {
            if let Ok(c) = c.cast::<Camera>() {
                return Ok(c.get().clone());
            }
            let name: String = c
                .extract()
                .map_err(|_| input("camera must be a Camera, a camera name or None"))?;
            let c = scene.call_method1("camera", (name,))?;
            Ok(c.cast::<Camera>()?.get().clone())
        }
        _ => {
            let kwargs = pyo3::types::PyDict::new(py);
            kwargs.set_item("aspect", aspect)?;
            let c = scene.call_method("camera", (), Some(&kwargs))?;
            Ok(c.cast::<Camera>()?.get().clone())
        }
    }
}
