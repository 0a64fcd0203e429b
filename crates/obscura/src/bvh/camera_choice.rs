//! The camera of a view as a front end's user names it (the CLI's `--camera`, `--eye`,
//! `--target`, `--up`, `--fov`; the Python package's `camera=`, `eye=`, …): one rule for both,
//! so that the same words give the same camera. Here rather than in `scene` because a scene that
//! names no camera gets an automatic one, which probes the scene's BVH ([`super::framing`]).

use super::framing::{auto_camera, Placement};
use super::Bvh;
use crate::scene::{Camera, CameraError, ExtentError, Scene, SceneError};
use glam::{DVec3, Vec3};

/// Which camera: a named one, or an eye and target, or (neither) the scene's first named camera,
/// else an automatic one. `fov_y_deg` replaces any of these cameras' field of view.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CameraChoice {
    /// A camera the scene names ([`Scene::camera`]).
    pub name: Option<String>,
    /// Eye and target, in the scene file's coordinates ([`Scene::from_file_point`]).
    pub eye_target: Option<(DVec3, DVec3)>,
    /// The image's up direction with `eye_target` (default: [`Camera::new`]'s).
    pub up: Option<Vec3>,
    /// Vertical field of view of the visible image, degrees (default: the camera's, or 60).
    pub fov_y_deg: Option<f32>,
}

/// The camera a [`CameraChoice`] gave, with the name reports use for it.
#[derive(Clone, Debug, PartialEq)]
pub struct ChosenCamera {
    /// The camera, validated.
    pub camera: Camera,
    /// Its name in reports: the camera's name, `custom` (eye and target) or `auto`.
    pub name: String,
    /// Where an automatic camera was put (`None`: not automatic).
    pub placement: Option<Placement>,
}

/// Why a camera cannot be chosen: the scene's coordinates are unusable, it names no such camera,
/// or the camera is degenerate.
#[derive(Debug, thiserror::Error)]
pub enum CameraChoiceError {
    /// The scene's bounds are too large for 32-bit floats (said before any camera).
    #[error(transparent)]
    Extent(#[from] ExtentError),
    /// A camera name the scene does not have.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A degenerate camera (eye at the target, up along the view, a bad field of view).
    #[error(transparent)]
    Camera(#[from] CameraError),
}

impl CameraChoice {
    /// The camera for `scene` at `aspect` (width / height of the visible image), validated.
    pub fn choose(&self, scene: &Scene, aspect: f32) -> Result<ChosenCamera, CameraChoiceError> {
        // Coordinates too large for f32 are the scene's fault, not the (framed) camera's: say so
        // first. A zero extent is only a warning, which the renderer logs.
        scene.check_extent()?;
        let mut placement = None;
        let (mut camera, name) = match (&self.name, self.eye_target) {
            (Some(name), _) => (scene.camera(name)?, name.clone()),
            (None, Some((eye, target))) => {
                // The file's coordinates: a scene far from its origin was re-centred on load.
                let (eye, target) = (scene.from_file_point(eye), scene.from_file_point(target));
                let mut camera = Camera::new(eye, target, self.fov_y_deg.unwrap_or(60.0))?;
                camera.up = self.up.unwrap_or(camera.up);
                (camera, "custom".to_string())
            }
            (None, None) => match scene.cameras.first() {
                Some(named) => (named.camera, named.name.clone()),
                None => {
                    let (camera, place) = auto_camera(scene, &Bvh::build(scene), aspect);
                    placement = Some(place);
                    (camera, "auto".to_string())
                }
            },
        };
        if let Some(fov) = self.fov_y_deg {
            camera.fov_y_deg = fov;
        }
        camera.validate()?;
        Ok(ChosenCamera {
            camera,
            name,
            placement,
        })
    }
}

impl ChosenCamera {
    /// What to tell the user of an automatic camera (`None` for any other): where it was put, in
    /// the file's coordinates with shortest round-trip digits, so that passing them back gives
    /// this very camera; as the CLI's flags (`--eye X --target Y --fov F`) where `flags`, else as
    /// keyword arguments (`eye=(x, y, z), target=(…), fov=F`, the Python package's).
    pub fn note(&self, scene: &Scene, flags: bool) -> Option<String> {
        let placement = self.placement?;
        let point = |p: Vec3| {
            let q = scene.origin + p.as_dvec3();
            if scene.origin == DVec3::ZERO {
                [p.x.to_string(), p.y.to_string(), p.z.to_string()]
            } else {
                [q.x.to_string(), q.y.to_string(), q.z.to_string()]
            }
        };
        let (eye, target, fov) = (
            point(self.camera.eye),
            point(self.camera.target),
            self.camera.fov_y_deg,
        );
        let how = if flags {
            format!(
                "--eye {} --target {} --fov {fov}",
                eye.join(","),
                target.join(",")
            )
        } else {
            format!(
                "eye=({}), target=({}), fov={fov}",
                eye.join(", "),
                target.join(", ")
            )
        };
        Some(format!(
            "'{}' names no camera: an automatic camera {} it, {how}",
            scene.name,
            placement.name()
        ))
    }
}
