//! The fly camera: yaw and pitch about world +Y (obscura's cameras are +Y up), moved with WASD/QE
//! and turned by dragging the mouse; it hands `Renderer` an ordinary [`Camera`] each frame and
//! prints itself as the flags (`--eye/--target/--fov`) and the camera-path keyframe other commands
//! read, so a view found here can be rendered, compared or benchmarked.

use glam::Vec3;
use obscura::scene::Camera;

/// Pitch stays this far from straight up or down (degrees), where yaw would be undefined.
const MAX_PITCH_DEG: f32 = 89.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub eye: Vec3,
    /// Radians about +Y; 0 looks along −Z.
    pub yaw: f32,
    /// Radians above the horizon.
    pub pitch: f32,
    /// Vertical field of view of the visible image, degrees.
    pub fov: f32,
    /// Distance to the target point handed out (only its direction matters to the image).
    pub focus: f32,
    /// World units per second.
    pub speed: f32,
}

/// What moves the camera this frame (from the keyboard and mouse).
#[derive(Clone, Copy, Debug, Default)]
pub struct Motion {
    /// Right, up, forward in [-1, 1] each.
    pub right: f32,
    pub up: f32,
    pub forward: f32,
    /// Shift held: four times faster.
    pub fast: bool,
    /// Mouse drag in points (x right, y down).
    pub drag: [f32; 2],
}

impl FlyCamera {
    /// Start from `camera`, moving at a speed suited to a scene of this diagonal.
    pub fn from_camera(camera: &Camera, scene_diagonal: f32) -> Self {
        let offset = camera.target - camera.eye;
        let dir = offset.normalize_or(Vec3::NEG_Z);
        Self {
            eye: camera.eye,
            yaw: dir.x.atan2(-dir.z),
            pitch: dir.y.clamp(-1.0, 1.0).asin(),
            fov: camera.fov_y_deg,
            focus: offset.length().max(1e-3),
            speed: (scene_diagonal * 0.25).max(1e-3),
        }
    }

    pub fn forward(&self) -> Vec3 {
        Vec3::new(
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
            -self.pitch.cos() * self.yaw.cos(),
        )
    }

    fn right(&self) -> Vec3 {
        Vec3::new(self.yaw.cos(), 0.0, self.yaw.sin())
    }

    pub fn target(&self) -> Vec3 {
        self.eye + self.forward() * self.focus
    }

    /// Apply one frame of motion over `dt` seconds.
    pub fn update(&mut self, motion: &Motion, dt: f32) {
        const RADIANS_PER_POINT: f32 = 0.004;
        self.yaw += motion.drag[0] * RADIANS_PER_POINT;
        let limit = MAX_PITCH_DEG.to_radians();
        self.pitch = (self.pitch - motion.drag[1] * RADIANS_PER_POINT).clamp(-limit, limit);
        let speed = self.speed * if motion.fast { 4.0 } else { 1.0 };
        let step =
            (self.forward() * motion.forward + self.right() * motion.right + Vec3::Y * motion.up)
                * speed
                * dt;
        if step.is_finite() {
            self.eye += step;
        }
    }

    /// The camera for the renderer; falls back to `last` if this one is degenerate (it cannot be,
    /// by the pitch limit, but a user's numbers are never trusted to be finite).
    pub fn camera(&self, last: &Camera) -> Camera {
        Camera::new(self.eye, self.target(), self.fov).unwrap_or(*last)
    }

    /// The flags that give this view to `render`, `compare`, `bench` and `view`.
    pub fn flags(&self) -> String {
        let t = self.target();
        format!(
            "--eye {} --target {} --fov {}",
            triple(self.eye),
            triple(t),
            short(self.fov)
        )
    }

    /// This view as one keyframe of a camera path (JSON).
    pub fn keyframe(&self, time: f32) -> String {
        let t = self.target();
        format!(
            "{{\"time\":{},\"eye\":[{}],\"target\":[{}],\"fov\":{}}}",
            short(time),
            triple(self.eye),
            triple(t),
            short(self.fov)
        )
    }
}

/// A number with four decimals, trailing zeros dropped (`1.5`, `-0.25`, `3`).
fn short(v: f32) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

fn triple(v: Vec3) -> String {
    format!("{},{},{}", short(v.x), short(v.y), short(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_the_direction_of_the_camera_it_starts_from() {
        let camera =
            Camera::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, 1.0, -1.0), 50.0).unwrap();
        let fly = FlyCamera::from_camera(&camera, 10.0);
        let dir = (camera.target - camera.eye).normalize();
        assert!((fly.forward() - dir).length() < 1e-5, "{:?}", fly.forward());
        assert!((fly.target() - camera.target).length() < 1e-4);
    }

    #[test]
    fn prints_flags_and_a_keyframe() {
        let camera = Camera::new(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 60.0).unwrap();
        let fly = FlyCamera::from_camera(&camera, 10.0);
        assert_eq!(fly.flags(), "--eye 0,1,5 --target 0,1,0 --fov 60");
        let key: serde_json::Value = serde_json::from_str(&fly.keyframe(0.0)).unwrap();
        let numbers = |v: &serde_json::Value| -> Vec<f64> {
            v.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        assert_eq!(numbers(&key["eye"]), [0.0, 1.0, 5.0]);
        assert_eq!(numbers(&key["target"]), [0.0, 1.0, 0.0]);
        assert_eq!(key["fov"].as_f64(), Some(60.0));
        assert_eq!(key["time"].as_f64(), Some(0.0));
    }

    #[test]
    fn moves_forward_and_turns() {
        let camera = Camera::new(Vec3::ZERO, Vec3::NEG_Z, 60.0).unwrap();
        let mut fly = FlyCamera::from_camera(&camera, 4.0);
        fly.update(
            &Motion {
                forward: 1.0,
                ..Motion::default()
            },
            1.0,
        );
        assert!(
            (fly.eye - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-5,
            "{:?}",
            fly.eye
        );
        fly.update(
            &Motion {
                drag: [0.0, -1e6],
                ..Motion::default()
            },
            0.0,
        );
        assert!(fly.pitch <= MAX_PITCH_DEG.to_radians() + 1e-6);
        assert!(Camera::new(fly.eye, fly.target(), fly.fov).is_ok());
    }
}
