//! Animated glTF cameras as camera paths (issue 13, docs/PATHS.md): a perspective camera whose
//! node has translation or rotation channels becomes a path named after the camera.
//!
//! The node's local transform is evaluated as glTF 2.0 §3.11 defines it (LINEAR: lerp for
//! translation, slerp for rotation; STEP: the earlier key; CUBICSPLINE: the cubic Hermite curve
//! of the key's value and tangents) at every key time of its channels, and for CUBICSPLINE also at
//! three points between keys, since the path moves linearly between its keyframes. The parent
//! nodes' transforms are taken as they stand (an animated parent is not followed), and the path's
//! cameras keep +Y up (a roll of the camera is not followed).

use glam::{Mat4, Quat, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::animation::util::ReadOutputs;
use gltf::animation::{Channel, Interpolation, Property};
use gltf::{buffer, Document, Node};

use super::super::{CameraPath, Keyframe};
use super::checks;

/// Points evaluated between two keys of a CUBICSPLINE channel (besides the keys).
const CUBIC_SUBSTEPS: usize = 3;

/// One animated property of the camera node.
struct Track<T> {
    times: Vec<f32>,
    /// One value per key; CUBICSPLINE: (in-tangent, value, out-tangent) per key.
    values: Vec<T>,
    interpolation: Interpolation,
}

/// What a track's values need to be interpolated.
trait Animated: Copy {
    fn lerp(self, other: Self, u: f32) -> Self;
    fn scaled_add(self, other: Self, a: f32, b: f32) -> Self;
    fn finish(self) -> Self {
        self
    }
}

impl Animated for Vec3 {
    fn lerp(self, other: Self, u: f32) -> Self {
        Vec3::lerp(self, other, u)
    }
    fn scaled_add(self, other: Self, a: f32, b: f32) -> Self {
        self * a + other * b
    }
}

impl Animated for Quat {
    fn lerp(self, other: Self, u: f32) -> Self {
        self.slerp(other, u)
    }
    fn scaled_add(self, other: Self, a: f32, b: f32) -> Self {
        self * a + other * b
    }
    fn finish(self) -> Self {
        self.normalize()
    }
}

impl<T: Animated> Track<T> {
    fn key_value(&self, k: usize) -> T {
        match self.interpolation {
            Interpolation::CubicSpline => self.values[3 * k + 1],
            _ => self.values[k],
        }
    }

    /// The value at time `t` (clamped to the track's keys).
    fn sample(&self, t: f32) -> T {
        let n = self.times.len();
        if n == 1 || t <= self.times[0] {
            return self.key_value(0);
        }
        if t >= self.times[n - 1] {
            return self.key_value(n - 1);
        }
        let k = self.times.partition_point(|&k| k <= t) - 1;
        let dt = self.times[k + 1] - self.times[k];
        let u = (t - self.times[k]) / dt;
        match self.interpolation {
            Interpolation::Step => self.key_value(k),
            Interpolation::Linear => self.key_value(k).lerp(self.key_value(k + 1), u),
            Interpolation::CubicSpline => {
                // glTF 2.0 Appendix C: p(u) = h00 v_k + h10 dt b_k + h01 v_k+1 + h11 dt a_k+1.
                let (u2, u3) = (u * u, u * u * u);
                let out_tangent = self.values[3 * k + 2];
                let in_tangent = self.values[3 * (k + 1)];
                let a = self.key_value(k).scaled_add(
                    out_tangent,
                    2.0 * u3 - 3.0 * u2 + 1.0,
                    (u3 - 2.0 * u2 + u) * dt,
                );
                let b = self.key_value(k + 1).scaled_add(
                    in_tangent,
                    -2.0 * u3 + 3.0 * u2,
                    (u3 - u2) * dt,
                );
                a.scaled_add(b, 1.0, 1.0).finish()
            }
        }
    }

    /// Whether the values match the key count (glTF: one per key, three for CUBICSPLINE).
    fn consistent(&self) -> bool {
        let per_key = if self.interpolation == Interpolation::CubicSpline {
            3
        } else {
            1
        };
        !self.times.is_empty() && self.values.len() == per_key * self.times.len()
    }
}

/// A translation or rotation channel's key times and values have the types glTF 2.0 §3.11
/// allows them (times float; translations float VEC3; rotations VEC4 of floats or normalized
/// 8- or 16-bit integers) and lie in their buffer views.
fn check_channel(channel: &Channel) -> Result<(), String> {
    use DataType::{F32, I16, I8, U16, U8};
    let sampler = channel.sampler();
    checks::accessor(&sampler.input(), Dimensions::Scalar, &[F32], "key time")?;
    let output = sampler.output();
    match channel.target().property() {
        Property::Translation => checks::accessor(&output, Dimensions::Vec3, &[F32], "translation"),
        _ => checks::accessor(
            &output,
            Dimensions::Vec4,
            &[F32, I8, U8, I16, U16],
            "rotation",
        ),
    }
}

/// The path of the camera on `node` (whose parent's world transform is `parent`), if some
/// animation moves or turns that node; `Err` names what is wrong with its channels.
pub(super) fn camera_path(
    doc: &Document,
    buffers: &[buffer::Data],
    node: &Node,
    parent: Mat4,
    name: &str,
    fov_deg: f32,
) -> Option<Result<CameraPath, String>> {
    let mut translation: Option<Track<Vec3>> = None;
    let mut rotation: Option<Track<Quat>> = None;
    for animation in doc.animations() {
        for channel in animation.channels() {
            if channel.target().node().index() != node.index()
                || !matches!(
                    channel.target().property(),
                    Property::Translation | Property::Rotation
                )
            {
                continue;
            }
            // The `gltf` crate's readers trust the accessors' types (an unexpected rotation type
            // panics inside it), so they are checked first, with the bytes they read.
            if let Err(e) = check_channel(&channel) {
                return Some(Err(e));
            }
            let reader = channel.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
            let (Some(inputs), Some(outputs)) = (reader.read_inputs(), reader.read_outputs())
            else {
                return Some(Err(format!(
                    "the animation of camera '{name}' has a channel without key times or values"
                )));
            };
            let times: Vec<f32> = inputs.collect();
            let interpolation = channel.sampler().interpolation();
            match outputs {
                ReadOutputs::Translations(values) => {
                    translation = Some(Track {
                        times,
                        values: values.map(Vec3::from).collect(),
                        interpolation,
                    });
                }
                ReadOutputs::Rotations(values) => {
                    rotation = Some(Track {
                        times,
                        values: values.into_f32().map(Quat::from_array).collect(),
                        interpolation,
                    });
                }
                _ => {}
            }
        }
    }
    if translation.is_none() && rotation.is_none() {
        return None;
    }
    if translation.as_ref().is_some_and(|t| !t.consistent())
        || rotation.as_ref().is_some_and(|t| !t.consistent())
    {
        return Some(Err(format!(
            "the animation of camera '{name}' has a channel whose values do not match its key times"
        )));
    }
    let (scale, rest_rotation, rest_translation) = node.transform().decomposed();
    let scale = Vec3::from(scale);
    let cubic = translation
        .as_ref()
        .is_some_and(|t| t.interpolation == Interpolation::CubicSpline)
        || rotation
            .as_ref()
            .is_some_and(|r| r.interpolation == Interpolation::CubicSpline);
    let substeps = if cubic { CUBIC_SUBSTEPS } else { 0 };
    let mut keys: Vec<f32> = translation
        .iter()
        .flat_map(|t| t.times.iter().copied())
        .chain(rotation.iter().flat_map(|r| r.times.iter().copied()))
        .filter(|t| t.is_finite())
        .collect();
    keys.sort_by(f32::total_cmp);
    keys.dedup();
    let mut times = Vec::new();
    for (i, &t) in keys.iter().enumerate() {
        times.push(t);
        if let Some(&next) = keys.get(i + 1) {
            for s in 1..=substeps {
                times.push(t + (next - t) * s as f32 / (substeps + 1) as f32);
            }
        }
    }
    let keyframes = times
        .into_iter()
        .map(|time| {
            let t = translation
                .as_ref()
                .map_or(Vec3::from(rest_translation), |track| track.sample(time));
            let r = rotation
                .as_ref()
                .map_or(Quat::from_array(rest_rotation), |track| track.sample(time));
            let world = parent * Mat4::from_scale_rotation_translation(scale, r, t);
            let eye = world.transform_point3(Vec3::ZERO);
            Keyframe {
                time,
                eye,
                target: eye + world.transform_vector3(Vec3::NEG_Z).normalize_or_zero(),
                fov: fov_deg,
            }
        })
        .collect();
    Some(
        CameraPath::new(name, crate::scene::Interpolation::Linear, keyframes)
            .map_err(|e| e.to_string()),
    )
}
