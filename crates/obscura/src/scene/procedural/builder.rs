//! The geometry helper every built-in scene uses: rectangles, closed boxes, cylinders and shells.
//!
//! All faces are counter-clockwise seen from their front (outside of solids, inside of an
//! inward-facing wall). Closed solids are recorded as [`Solid`]s so tests can check that no
//! camera sits inside one.

use std::f32::consts::TAU;

use glam::{Quat, Vec2, Vec3};

use super::super::{Camera, CameraPath, Interpolation, Keyframe, Material, NamedCamera, Scene};

/// A closed solid the builder emitted (used by tests: cameras must not be inside one).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Solid {
    /// A box rotated by `yaw` radians about +Y around its centre.
    Box { center: Vec3, half: Vec3, yaw: f32 },
    /// An upright capped cylinder standing on `base`.
    Cylinder {
        base: Vec3,
        radius: f32,
        height: f32,
    },
}

impl Solid {
    pub(crate) fn contains(&self, p: Vec3) -> bool {
        match *self {
            Solid::Box { center, half, yaw } => {
                let local = Quat::from_rotation_y(-yaw) * (p - center);
                local.abs().cmplt(half).all()
            }
            Solid::Cylinder {
                base,
                radius,
                height,
            } => {
                let d = p - base;
                d.y > 0.0 && d.y < height && Vec2::new(d.x, d.z).length() < radius
            }
        }
    }
}

/// Which side of a cylinder wall is its front.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Facing {
    Outward,
    Inward,
}

/// An upright cylinder wall, optionally partial (an arc), wavy (cloth folds) and capped.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cylinder {
    pub base: Vec3,
    pub radius: f32,
    pub height: f32,
    /// Segments around a full turn (an arc gets a proportional share).
    pub segments: u32,
    /// Rows of quads along the height.
    pub rows: u32,
    /// Start angle and sweep of the wall, radians; angle 0 is +X, τ/4 is +Z.
    pub arc: (f32, f32),
    /// Radial amplitude (m) and angular frequency of a sinusoidal fold: r(θ) = r + a·sin(fθ).
    pub wobble: (f32, f32),
    pub facing: Facing,
    /// Top and bottom discs (only for a full, outward cylinder: it becomes a closed solid).
    pub caps: bool,
}

impl Cylinder {
    /// A closed, outward-facing solid cylinder.
    pub(crate) fn solid(base: Vec3, radius: f32, height: f32, segments: u32) -> Self {
        Cylinder {
            base,
            radius,
            height,
            segments,
            rows: 1,
            arc: (0.0, TAU),
            wobble: (0.0, 0.0),
            facing: Facing::Outward,
            caps: true,
        }
    }

    /// An open shell (no caps), e.g. a double-sided cloth layer.
    pub(crate) fn shell(base: Vec3, radius: f32, height: f32, segments: u32, rows: u32) -> Self {
        Cylinder {
            rows,
            caps: false,
            ..Self::solid(base, radius, height, segments)
        }
    }

    fn point(&self, theta: f32, y: f32) -> Vec3 {
        let r = self.radius + self.wobble.0 * (self.wobble.1 * theta).sin();
        self.base + Vec3::new(r * theta.cos(), y, r * theta.sin())
    }
}

/// Accumulates a [`Scene`] and the solids it contains.
pub(crate) struct Builder {
    scene: Scene,
    solids: Vec<Solid>,
}

impl Builder {
    pub(crate) fn new(name: &str) -> Self {
        Builder {
            scene: Scene {
                name: name.to_string(),
                ..Scene::default()
            },
            solids: Vec::new(),
        }
    }

    /// Adds a material (linear RGB, opaque) and returns its index.
    pub(crate) fn material(&mut self, name: &str, rgb: [f32; 3], double_sided: bool) -> u32 {
        self.scene.materials.push(Material {
            name: name.to_string(),
            base_color: [rgb[0], rgb[1], rgb[2], 1.0],
            double_sided,
            ..Material::default()
        });
        (self.scene.materials.len() - 1) as u32
    }

    /// One triangle, counter-clockwise seen from its front.
    pub(crate) fn triangle(&mut self, mat: u32, p: [Vec3; 3], uv: [Vec2; 3]) {
        let base = self.scene.positions.len() as u32;
        self.scene.positions.extend(p);
        self.scene.uvs.extend(uv);
        self.scene.triangles.push([base, base + 1, base + 2]);
        self.scene.triangle_materials.push(mat);
    }

    /// A planar quad `p0 p1 p2 p3`, counter-clockwise seen from its front (two triangles).
    pub(crate) fn quad(&mut self, mat: u32, p: [Vec3; 4]) {
        let base = self.scene.positions.len() as u32;
        self.scene.positions.extend(p);
        // glTF uv convention: (0,0) top-left, p0 is the bottom-left corner.
        self.scene.uvs.extend([
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 0.0),
        ]);
        self.scene.triangles.push([base, base + 1, base + 2]);
        self.scene.triangles.push([base, base + 2, base + 3]);
        self.scene.triangle_materials.extend([mat, mat]);
    }

    /// A rectangle centred at `c` spanning ±`u` and ±`v`; its front faces `u × v`.
    pub(crate) fn rect(&mut self, mat: u32, c: Vec3, u: Vec3, v: Vec3) {
        self.quad(mat, [c - u - v, c + u - v, c + u + v, c - u + v]);
    }

    /// A closed box (all 6 faces, outward), rotated by `yaw` radians about +Y.
    pub(crate) fn cuboid(&mut self, mat: u32, center: Vec3, half: Vec3, yaw: f32) {
        let q = Quat::from_rotation_y(yaw);
        let (x, y, z) = (q * Vec3::X * half.x, Vec3::Y * half.y, q * Vec3::Z * half.z);
        // (normal, u, v) with u × v along the normal.
        for (n, u, v) in [
            (x, y, z),
            (-x, z, y),
            (y, z, x),
            (-y, x, z),
            (z, x, y),
            (-z, y, x),
        ] {
            self.rect(mat, center + n, u, v);
        }
        self.solids.push(Solid::Box { center, half, yaw });
    }

    /// An axis-aligned closed box from `min` to `max`.
    pub(crate) fn aabb(&mut self, mat: u32, min: Vec3, max: Vec3) {
        self.cuboid(mat, 0.5 * (min + max), 0.5 * (max - min), 0.0);
    }

    /// Records a solid whose faces were emitted by hand (e.g. the straight staircase).
    pub(crate) fn add_solid(&mut self, solid: Solid) {
        self.solids.push(solid);
    }

    /// A cylinder wall (see [`Cylinder`]).
    pub(crate) fn cylinder(&mut self, mat: u32, c: &Cylinder) {
        let (start, sweep) = c.arc;
        let n = ((c.segments as f32 * sweep / TAU).ceil() as u32).max(1);
        let rows = c.rows.max(1);
        for i in 0..n {
            let (t0, t1) = (
                start + sweep * i as f32 / n as f32,
                start + sweep * (i + 1) as f32 / n as f32,
            );
            for j in 0..rows {
                let (y0, y1) = (
                    c.height * j as f32 / rows as f32,
                    c.height * (j + 1) as f32 / rows as f32,
                );
                let (b0, b1, u0, u1) = (
                    c.point(t0, y0),
                    c.point(t1, y0),
                    c.point(t0, y1),
                    c.point(t1, y1),
                );
                match c.facing {
                    Facing::Outward => self.quad(mat, [b1, b0, u0, u1]),
                    Facing::Inward => self.quad(mat, [b0, b1, u1, u0]),
                }
            }
        }
        let closed = c.caps && c.facing == Facing::Outward && sweep >= TAU;
        if !closed {
            return;
        }
        let (bottom, top) = (c.base, c.base + Vec3::Y * c.height);
        for i in 0..n {
            let (t0, t1) = (
                start + sweep * i as f32 / n as f32,
                start + sweep * (i + 1) as f32 / n as f32,
            );
            let (p0, p1) = (c.point(t0, 0.0), c.point(t1, 0.0));
            let (q0, q1) = (c.point(t0, c.height), c.point(t1, c.height));
            let uv = [Vec2::splat(0.5), Vec2::ZERO, Vec2::X];
            self.triangle(mat, [top, q1, q0], uv);
            self.triangle(mat, [bottom, p0, p1], uv);
        }
        self.solids.push(Solid::Cylinder {
            base: c.base,
            radius: c.radius,
            height: c.height,
        });
    }

    /// A named camera; the first one added is the scene's default.
    pub(crate) fn camera(&mut self, name: &str, eye: Vec3, target: Vec3, fov_y_deg: f32) {
        // A bad built-in camera is kept as given: `validate` (run on every built-in) reports it
        // with the camera's name instead of a panic here.
        let camera = Camera::new(eye, target, fov_y_deg).unwrap_or(Camera {
            eye,
            target,
            up: Vec3::Y,
            fov_y_deg,
        });
        self.scene.cameras.push(NamedCamera {
            name: name.to_string(),
            camera,
        });
    }

    /// A named camera path through `(time, eye, target, fov)` keyframes (Catmull–Rom). A bad
    /// built-in path is a bug: the scene tests build every path.
    pub(crate) fn path(&mut self, name: &str, keys: &[(f32, Vec3, Vec3, f32)]) {
        let keyframes = keys
            .iter()
            .map(|&(time, eye, target, fov)| Keyframe {
                time,
                eye,
                target,
                fov,
            })
            .collect();
        match CameraPath::new(name, Interpolation::CatmullRom, keyframes) {
            Ok(path) => self.scene.paths.push(path),
            Err(e) => log::error!("built-in scene '{}': {e}", self.scene.name),
        }
    }

    pub(crate) fn finish(self) -> (Scene, Vec<Solid>) {
        (self.scene, self.solids)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every face of a closed solid points away from `inside`.
    fn assert_outward(scene: &Scene, inside: Vec3) {
        for t in &scene.triangles {
            let [a, b, c] = t.map(|i| scene.positions[i as usize]);
            let n = (b - a).cross(c - a);
            let centroid = (a + b + c) / 3.0;
            assert!(n.dot(centroid - inside) > 0.0, "inward face {t:?}");
        }
    }

    #[test]
    fn boxes_are_closed_and_outward() {
        let mut b = Builder::new("t");
        let m = b.material("m", [1.0; 3], false);
        let center = Vec3::new(1.0, 2.0, 3.0);
        b.cuboid(m, center, Vec3::new(0.5, 1.0, 2.0), 0.7);
        let (scene, solids) = b.finish();
        assert_eq!(scene.triangle_count(), 12);
        assert_outward(&scene, center);
        assert!(solids[0].contains(center));
        assert!(!solids[0].contains(center + Vec3::Y * 1.01));
        // Extents survive the rotation: the box spans exactly ±1 in y.
        let b = scene.bounds();
        assert!((b.max.y - 3.0).abs() < 1e-5 && (b.min.y - 1.0).abs() < 1e-5);
        scene.validate().unwrap();
    }

    #[test]
    fn cylinders_face_the_requested_way() {
        let mut b = Builder::new("t");
        let m = b.material("m", [1.0; 3], false);
        b.cylinder(m, &Cylinder::solid(Vec3::ZERO, 1.0, 2.0, 16));
        let (scene, solids) = b.finish();
        assert_eq!(scene.triangle_count(), 16 * 2 + 16 * 2);
        assert_outward(&scene, Vec3::Y);
        assert!(solids[0].contains(Vec3::new(0.5, 1.0, 0.5)));
        assert!(!solids[0].contains(Vec3::new(0.8, 1.0, 0.8)));

        let mut b = Builder::new("t");
        let m = b.material("m", [1.0; 3], false);
        let wall = Cylinder {
            facing: Facing::Inward,
            ..Cylinder::shell(Vec3::ZERO, 3.0, 2.0, 32, 2)
        };
        b.cylinder(m, &wall);
        let (scene, solids) = b.finish();
        assert_eq!(scene.triangle_count(), 32 * 2 * 2);
        assert!(solids.is_empty());
        // Inward: every face points towards the axis.
        for t in &scene.triangles {
            let [a, b2, c] = t.map(|i| scene.positions[i as usize]);
            let n = (b2 - a).cross(c - a);
            let centroid = (a + b2 + c) / 3.0;
            assert!(n.dot(Vec3::new(centroid.x, 0.0, centroid.z)) < 0.0);
        }
    }

    #[test]
    fn arcs_cover_their_sweep_only() {
        let mut b = Builder::new("t");
        let m = b.material("m", [1.0; 3], true);
        let half = Cylinder {
            arc: (0.0, TAU / 2.0),
            ..Cylinder::shell(Vec3::ZERO, 1.0, 1.0, 32, 1)
        };
        b.cylinder(m, &half);
        let (scene, _) = b.finish();
        assert_eq!(scene.triangle_count(), 16 * 2);
        assert!(scene.positions.iter().all(|p| p.z >= -1e-5));
    }
}
