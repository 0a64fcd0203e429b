//! Camera construction and validation, and the bounds helpers a framing camera needs.
//!
//! A camera that fails [`Camera::validate`] would give a NaN view matrix and a black or garbage
//! frame several passes later; checking here turns that into one clear message.

use glam::{Mat4, Vec3};

use super::{Bounds, Camera, CameraError};

/// `|cos|` between up and view direction above which they count as parallel (about 0.8°): closer
/// than that, `look_at` loses precision and the roll of the image becomes arbitrary.
const PARALLEL_COS: f32 = 0.9999;

/// Vertical field of view of [`Camera::framing`], degrees.
const FRAMING_FOV_Y_DEG: f32 = 60.0;

impl Camera {
    /// A camera at `eye` looking at `target` with up = +Y.
    ///
    /// For a view straight down (up) +Y would be parallel to the view direction, so the image's
    /// up is -Z (+Z) instead: the top of a top-down image then points along -Z ("north").
    pub fn new(eye: Vec3, target: Vec3, fov_y_deg: f32) -> Result<Camera, CameraError> {
        let dir = (target - eye).normalize_or_zero();
        let up = if dir.dot(Vec3::Y) <= -PARALLEL_COS {
            Vec3::NEG_Z
        } else if dir.dot(Vec3::Y) >= PARALLEL_COS {
            Vec3::Z
        } else {
            Vec3::Y
        };
        let camera = Camera {
            eye,
            target,
            up,
            fov_y_deg,
        };
        camera.validate()?;
        Ok(camera)
    }

    /// Checks that the camera gives a well-defined view: finite numbers, a field of view strictly
    /// inside (0°, 180°), eye away from target, and an up vector not along the view direction.
    pub fn validate(&self) -> Result<(), CameraError> {
        for (what, v) in [("eye", self.eye), ("target", self.target), ("up", self.up)] {
            if !v.is_finite() {
                return Err(CameraError::NonFinite {
                    what,
                    value: format!("{v}"),
                });
            }
        }
        if !self.fov_y_deg.is_finite() {
            return Err(CameraError::NonFinite {
                what: "field of view",
                value: format!("{}", self.fov_y_deg),
            });
        }
        if !(self.fov_y_deg > 0.0 && self.fov_y_deg < 180.0) {
            return Err(CameraError::FieldOfView {
                fov_y_deg: self.fov_y_deg,
            });
        }
        // Relative test: a camera 1e-3 m from its target is fine near the origin but is lost in
        // rounding at 1e5 m from it.
        let scale = self
            .eye
            .abs()
            .max_element()
            .max(self.target.abs().max_element())
            .max(1.0);
        let offset = self.target - self.eye;
        if offset.length() <= 1e-6 * scale {
            return Err(CameraError::EyeAtTarget {
                eye: self.eye,
                target: self.target,
            });
        }
        let forward = offset.normalize();
        let up = self.up.normalize_or_zero();
        if up == Vec3::ZERO || forward.dot(up).abs() >= PARALLEL_COS {
            return Err(CameraError::UpParallel {
                up: self.up,
                forward,
            });
        }
        Ok(())
    }

    /// World-to-view matrix (right-handed, looking down -Z; docs/ARCHITECTURE.md
    /// "Conventions"): glam's right-handed `look_at` (glam 0.34 moved `Mat4::look_at_rh` into
    /// `glam::camera`).
    pub fn view_matrix(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye, self.target, self.up.normalize_or_zero())
    }

    /// Unit view direction (eye towards target).
    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye).normalize_or_zero()
    }

    /// A camera that shows all of `bounds`: it looks at the centre from direction
    /// normalize(1, 0.6, 1.4) (front-right, above: a conventional three-quarter view), with a 60°
    /// vertical field of view, far enough that the bounding sphere fits both the vertical and the
    /// horizontal field of view of an image with aspect ratio `aspect` (width / height).
    pub fn framing(bounds: &Bounds, aspect: f32) -> Camera {
        let (center, radius) = if bounds.min.is_finite() && bounds.max.is_finite() {
            (bounds.center(), 0.5 * bounds.diagonal())
        } else {
            (Vec3::ZERO, 1.0)
        };
        // An empty or point-like scene still gets a usable camera.
        let radius = if radius > 1e-6 { radius } else { 1.0 };
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        let half_y = (0.5 * FRAMING_FOV_Y_DEG).to_radians();
        let half_x = (half_y.tan() * aspect).atan();
        let distance = radius / half_y.min(half_x).sin();
        let dir = Vec3::new(1.0, 0.6, 1.4).normalize();
        Camera {
            eye: center + dir * distance,
            target: center,
            up: Vec3::Y,
            fov_y_deg: FRAMING_FOV_Y_DEG,
        }
    }
}

impl Bounds {
    /// Centre of the box.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Length of the box diagonal (0 for a point, or for an empty scene).
    pub fn diagonal(&self) -> f32 {
        (self.max - self.min).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_rejects_bad_fov_with_the_value_in_the_message() {
        for fov in [0.0, 180.0, -5.0, 200.0] {
            let err = Camera::new(Vec3::Z, Vec3::ZERO, fov).unwrap_err();
            assert!(
                matches!(err, CameraError::FieldOfView { .. }),
                "{fov}: {err}"
            );
            assert!(err.to_string().contains(&format!("{fov}")), "{err}");
        }
        let err = Camera::new(Vec3::Z, Vec3::ZERO, f32::NAN).unwrap_err();
        assert!(matches!(err, CameraError::NonFinite { .. }), "{err}");
        assert!(err.to_string().contains("NaN"), "{err}");
        assert!(Camera::new(Vec3::Z, Vec3::ZERO, 179.9).is_ok());
        assert!(Camera::new(Vec3::Z, Vec3::ZERO, 0.01).is_ok());
    }

    #[test]
    fn new_rejects_non_finite_positions_and_eye_at_target() {
        let err = Camera::new(Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::ZERO, 60.0).unwrap_err();
        assert!(err.to_string().contains("eye"), "{err}");
        let p = Vec3::new(1.0, 2.0, 3.0);
        let err = Camera::new(p, p, 60.0).unwrap_err();
        assert!(matches!(err, CameraError::EyeAtTarget { .. }), "{err}");
        // Relative: 1 mm apart 100 km from the origin is lost in rounding, but fine near 0.
        let far = Vec3::splat(1e5);
        assert!(Camera::new(far, far + Vec3::X * 1e-3, 60.0).is_err());
        assert!(Camera::new(Vec3::ZERO, Vec3::X * 1e-3, 60.0).is_ok());
    }

    #[test]
    fn straight_down_and_up_views_pick_a_z_up_vector() {
        let down = Camera::new(Vec3::new(1.0, 10.0, 2.0), Vec3::new(1.0, 0.0, 2.0), 60.0).unwrap();
        assert_eq!(down.up, Vec3::NEG_Z);
        assert!(down.view_matrix().is_finite());
        assert!((down.forward() - Vec3::NEG_Y).length() < 1e-6);
        let up = Camera::new(Vec3::ZERO, Vec3::Y * 3.0, 45.0).unwrap();
        assert_eq!(up.up, Vec3::Z);
        assert!(up.view_matrix().is_finite());
        // A tilted view keeps +Y.
        let tilted = Camera::new(Vec3::new(0.0, 5.0, 1.0), Vec3::ZERO, 45.0).unwrap();
        assert_eq!(tilted.up, Vec3::Y);
    }

    #[test]
    fn validate_rejects_up_parallel_to_view() {
        let c = Camera {
            eye: Vec3::ZERO,
            target: Vec3::new(0.0, 0.0, -1.0),
            up: Vec3::new(0.0, 0.0, 2.0),
            fov_y_deg: 60.0,
        };
        assert!(matches!(c.validate(), Err(CameraError::UpParallel { .. })));
        let zero_up = Camera {
            up: Vec3::ZERO,
            ..c
        };
        assert!(zero_up.validate().is_err());
    }

    #[test]
    fn view_matrix_looks_down_negative_z() {
        let c = Camera::new(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 60.0).unwrap();
        let target_view = c.view_matrix().transform_point3(c.target);
        assert!(target_view.x.abs() < 1e-5 && target_view.y.abs() < 1e-5);
        assert!((target_view.z + 5.0).abs() < 1e-5, "{target_view}");
    }

    #[test]
    fn framing_fits_the_bounding_sphere() {
        let b = Bounds {
            min: Vec3::new(-1.0, 0.0, -2.0),
            max: Vec3::new(3.0, 2.0, 2.0),
        };
        assert_eq!(b.center(), Vec3::new(1.0, 1.0, 0.0));
        assert!((b.diagonal() - 6.0).abs() < 1e-5);
        for aspect in [0.5, 1.0, 16.0 / 9.0] {
            let c = Camera::framing(&b, aspect);
            c.validate().unwrap();
            assert_eq!(c.target, b.center());
            let d = (c.eye - c.target).length();
            let r = 0.5 * b.diagonal();
            // The sphere's angular radius fits both half-angles.
            let half_y = 30f32.to_radians();
            let half_x = (half_y.tan() * aspect).atan();
            let angular = (r / d).asin();
            assert!(angular <= half_y + 1e-4 && angular <= half_x + 1e-4);
            assert!((angular - half_y.min(half_x)).abs() < 1e-4);
            let dir = (c.eye - c.target).normalize();
            assert!((dir - Vec3::new(1.0, 0.6, 1.4).normalize()).length() < 1e-5);
        }
        // Degenerate inputs still give a valid camera.
        let point = Bounds {
            min: Vec3::ONE,
            max: Vec3::ONE,
        };
        Camera::framing(&point, f32::NAN).validate().unwrap();
    }
}
