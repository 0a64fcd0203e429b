//! Camera paths: keyframed cameras, so AO can be rendered and judged in motion (issue 13; the
//! seed papers argue from motion: halos that pop as the camera moves, seed 001 §1, and flicker
//! at the border and near edges, seed 002 Fig. 8 and 13).
//!
//! A path is a list of keyframes (time in seconds, eye, target, vertical field of view). Between
//! keyframes:
//! - the eye follows a Catmull–Rom spline: a cubic Hermite curve whose velocity at each keyframe
//!   is the central difference of its neighbours over their times, `(p[i+1] − p[i−1]) /
//!   (t[i+1] − t[i−1])` (one-sided at the ends), so unevenly spaced keyframes keep a smooth speed;
//! - the view direction turns along the great circle between the keyframes' directions (slerp)
//!   and the eye–target distance and field of view change linearly;
//! - with [`Interpolation::Linear`] the eye moves on straight lines instead (what glTF's LINEAR
//!   samplers do; the direction is still slerped, as glTF slerps rotations).
//!
//! Paths come from the built-in scenes ([`Scene::paths`]), from JSON files ([`CameraPath::from_json_file`],
//! format in `docs/PATHS.md`) or, for any scene, from [`CameraPath::orbit`].

use std::path::Path;

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::{Camera, CameraError, Scene};

/// One keyframe of a [`CameraPath`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Keyframe {
    /// Seconds from the path's start; strictly increasing along the path.
    pub time: f32,
    /// Camera position, world space.
    pub eye: Vec3,
    /// The point looked at, world space.
    pub target: Vec3,
    /// Vertical field of view of the visible image, degrees (60 where a file leaves it out).
    #[serde(default = "default_fov", alias = "fov_y_deg")]
    pub fov: f32,
}

fn default_fov() -> f32 {
    60.0
}

/// How the eye moves between keyframes (the view direction is always slerped).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Interpolation {
    /// A Catmull–Rom spline through the keyframes' eyes (the default).
    #[default]
    CatmullRom,
    /// Straight lines between the keyframes' eyes.
    Linear,
}

/// A named, validated list of keyframes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CameraPath {
    /// The name `--path` chooses it by.
    pub name: String,
    /// How the eye moves between keyframes.
    pub interpolation: Interpolation,
    keyframes: Vec<Keyframe>,
}

/// A path file as written by hand: an object with keyframes, or just the list of keyframes.
#[derive(Deserialize)]
#[serde(untagged)]
enum PathFile {
    Full {
        #[serde(default)]
        name: Option<String>,
        #[serde(default)]
        interpolation: Interpolation,
        keyframes: Vec<Keyframe>,
    },
    Keyframes(Vec<Keyframe>),
}

/// A camera path that cannot be used, with what to do about it.
#[derive(Debug, thiserror::Error)]
pub enum PathError {
    /// No keyframes at all.
    #[error("camera path '{name}' has no keyframes: give at least one {{\"time\", \"eye\", \"target\"}}")]
    Empty {
        /// The path's name (or file).
        name: String,
    },
    /// Times not strictly increasing, or not finite.
    #[error(
        "camera path '{name}': keyframe {index} has time {time}, which is not after the previous \
         keyframe's {previous}: times must be finite and strictly increasing"
    )]
    Times {
        /// The path's name (or file).
        name: String,
        /// Index of the offending keyframe.
        index: usize,
        /// Its time.
        time: f32,
        /// The time before it.
        previous: f32,
    },
    /// A keyframe's camera is not a valid camera (eye at target, bad field of view, …).
    #[error("camera path '{name}': keyframe {index}: {source}")]
    Camera {
        /// The path's name (or file).
        name: String,
        /// Index of the offending keyframe.
        index: usize,
        /// Why the camera is invalid.
        source: CameraError,
    },
    /// The file cannot be read or is not a path file.
    #[error(
        "cannot read camera path file '{file}': {message} (expected JSON: {{\"name\": \"…\", \
         \"keyframes\": [{{\"time\": 0, \"eye\": [x, y, z], \"target\": [x, y, z], \"fov\": 60}}, …]}}; \
         see docs/PATHS.md)"
    )]
    File {
        /// The file.
        file: String,
        /// What went wrong.
        message: String,
    },
    /// The scene has no path of that name.
    #[error(
        "scene '{scene}' has no camera path '{name}': use one of {available}, or a .json path file"
    )]
    Unknown {
        /// The name asked for.
        name: String,
        /// The scene.
        scene: String,
        /// The names it has, comma-separated.
        available: String,
    },
    /// A frame count of zero.
    #[error("--frames 0 samples nothing: give at least 1 frame (2 or more to see motion)")]
    NoFrames,
}

impl CameraPath {
    /// Moves every keyframe's eye and target through `f` ([`crate::scene::Scene::recentre`]).
    pub(crate) fn move_points(&mut self, f: impl Fn(Vec3) -> Vec3) {
        for k in &mut self.keyframes {
            k.eye = f(k.eye);
            k.target = f(k.target);
        }
    }

    /// A path from keyframes, validated: at least one keyframe, finite and strictly increasing
    /// times, and a valid camera at every keyframe.
    pub fn new(
        name: impl Into<String>,
        interpolation: Interpolation,
        keyframes: Vec<Keyframe>,
    ) -> Result<Self, PathError> {
        let name = name.into();
        if keyframes.is_empty() {
            return Err(PathError::Empty { name });
        }
        for (index, k) in keyframes.iter().enumerate() {
            let previous = if index == 0 {
                f32::NEG_INFINITY
            } else {
                keyframes[index - 1].time
            };
            if !k.time.is_finite() || k.time <= previous {
                return Err(PathError::Times {
                    name,
                    index,
                    time: k.time,
                    previous,
                });
            }
            if let Err(source) = Camera::new(k.eye, k.target, k.fov) {
                return Err(PathError::Camera {
                    name,
                    index,
                    source,
                });
            }
        }
        Ok(Self {
            name,
            interpolation,
            keyframes,
        })
    }

    /// Reads a path file (JSON; format in `docs/PATHS.md`). A file without a name is named after
    /// the file.
    pub fn from_json_file(file: &Path) -> Result<Self, PathError> {
        let shown = file.display().to_string();
        let text = std::fs::read_to_string(file).map_err(|e| PathError::File {
            file: shown.clone(),
            message: e.to_string(),
        })?;
        let stem = file
            .file_stem()
            .map_or_else(|| shown.clone(), |s| s.to_string_lossy().into_owned());
        Self::from_json_str(&text, &stem).map_err(|e| match e {
            PathError::File { message, .. } => PathError::File {
                file: shown,
                message,
            },
            other => other,
        })
    }

    /// Parses a path from JSON text; `default_name` names a path whose JSON gives none.
    pub fn from_json_str(text: &str, default_name: &str) -> Result<Self, PathError> {
        let parsed: PathFile = serde_json::from_str(text).map_err(|e| PathError::File {
            file: default_name.to_string(),
            message: e.to_string(),
        })?;
        match parsed {
            PathFile::Full {
                name,
                interpolation,
                keyframes,
            } => Self::new(
                name.unwrap_or_else(|| default_name.to_string()),
                interpolation,
                keyframes,
            ),
            PathFile::Keyframes(keyframes) => {
                Self::new(default_name, Interpolation::default(), keyframes)
            }
        }
    }

    /// The path as JSON in the file format [`CameraPath::from_json_str`] reads.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("paths serialise")
    }

    /// An orbit for any scene: the eye swings `degrees` in total about the vertical axis through
    /// `camera`'s target (half each way, keyframes every quarter), keeping its height, distance
    /// and field of view. Two seconds long.
    pub fn orbit(
        name: impl Into<String>,
        camera: &Camera,
        degrees: f32,
    ) -> Result<Self, PathError> {
        let offset = camera.eye - camera.target;
        let keyframes = (0..5)
            .map(|i| {
                let angle = (i as f32 / 4.0 - 0.5) * degrees.to_radians();
                Keyframe {
                    time: i as f32 * 0.5,
                    eye: camera.target + Quat::from_rotation_y(angle) * offset,
                    target: camera.target,
                    fov: camera.fov_y_deg,
                }
            })
            .collect();
        Self::new(name, Interpolation::CatmullRom, keyframes)
    }

    /// The keyframes, in time order.
    pub fn keyframes(&self) -> &[Keyframe] {
        &self.keyframes
    }

    /// First and last keyframe times.
    pub fn time_range(&self) -> (f32, f32) {
        let first = self.keyframes[0].time;
        (first, self.keyframes.last().map_or(first, |k| k.time))
    }

    /// The camera at time `t` (clamped to the path's time range).
    pub fn camera_at(&self, t: f32) -> Result<Camera, CameraError> {
        let keys = &self.keyframes;
        let (first, last) = self.time_range();
        let t = if t.is_finite() {
            t.clamp(first, last)
        } else {
            first
        };
        // The segment [i, i + 1] holding t (the last one for t == last).
        let i = keys
            .partition_point(|k| k.time <= t)
            .saturating_sub(1)
            .min(keys.len().saturating_sub(2));
        if keys.len() == 1 {
            let k = keys[0];
            return Camera::new(k.eye, k.target, k.fov);
        }
        let (a, b) = (keys[i], keys[i + 1]);
        let dt = b.time - a.time;
        let u = ((t - a.time) / dt).clamp(0.0, 1.0);
        let eye = match self.interpolation {
            Interpolation::Linear => a.eye.lerp(b.eye, u),
            Interpolation::CatmullRom => {
                let va = self.velocity(i);
                let vb = self.velocity(i + 1);
                hermite(a.eye, va * dt, b.eye, vb * dt, u)
            }
        };
        let (da, db) = (a.target - a.eye, b.target - b.eye);
        let turn = Quat::from_rotation_arc(da.normalize(), db.normalize());
        let direction = Quat::IDENTITY.slerp(turn, u) * da.normalize();
        let distance = da.length() + (db.length() - da.length()) * u;
        let fov = a.fov + (b.fov - a.fov) * u;
        Camera::new(eye, eye + direction * distance, fov)
    }

    /// The eye's velocity at keyframe `i` (Catmull–Rom: central difference over time).
    fn velocity(&self, i: usize) -> Vec3 {
        let keys = &self.keyframes;
        let lo = i.saturating_sub(1);
        let hi = (i + 1).min(keys.len() - 1);
        (keys[hi].eye - keys[lo].eye) / (keys[hi].time - keys[lo].time)
    }

    /// `frames` cameras at evenly spaced times from the first keyframe to the last (both
    /// included; one frame: the first keyframe), with their times.
    pub fn sample(&self, frames: u32) -> Result<Vec<(f32, Camera)>, PathError> {
        if frames == 0 {
            return Err(PathError::NoFrames);
        }
        let (first, last) = self.time_range();
        (0..frames)
            .map(|f| {
                let t = if frames == 1 {
                    first
                } else {
                    first + (last - first) * f as f32 / (frames - 1) as f32
                };
                self.camera_at(t)
                    .map(|c| (t, c))
                    .map_err(|source| PathError::Camera {
                        name: format!("{} at t = {t}", self.name),
                        index: f as usize,
                        source,
                    })
            })
            .collect()
    }
}

/// Cubic Hermite interpolation between `p0` and `p1` with end tangents `m0`, `m1` (already
/// scaled to the segment), at `u` in [0, 1].
fn hermite(p0: Vec3, m0: Vec3, p1: Vec3, m1: Vec3, u: f32) -> Vec3 {
    let (u2, u3) = (u * u, u * u * u);
    p0 * (2.0 * u3 - 3.0 * u2 + 1.0)
        + m0 * (u3 - 2.0 * u2 + u)
        + p1 * (-2.0 * u3 + 3.0 * u2)
        + m1 * (u3 - u2)
}

impl Scene {
    /// The scene's path called `name`; for a scene without paths of its own (files without an
    /// animated camera), `orbit` is a 40° orbit around its default camera's target.
    pub fn path(&self, name: &str, aspect: f32) -> Result<CameraPath, PathError> {
        if let Some(p) = self.paths.iter().find(|p| p.name == name) {
            return Ok(p.clone());
        }
        if self.paths.is_empty() && name == ORBIT {
            return CameraPath::orbit(ORBIT, &self.default_camera(aspect), 40.0);
        }
        Err(PathError::Unknown {
            name: name.to_string(),
            scene: self.name.clone(),
            available: self.path_names().join(", "),
        })
    }

    /// The names [`Scene::path`] accepts.
    pub fn path_names(&self) -> Vec<String> {
        if self.paths.is_empty() {
            vec![ORBIT.to_string()]
        } else {
            self.paths.iter().map(|p| p.name.clone()).collect()
        }
    }
}

/// The automatic path of scenes that have none.
const ORBIT: &str = "orbit";

#[cfg(test)]
mod tests;
