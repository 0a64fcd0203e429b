//! A camera for a scene that names none (issue 62): framing the bounds from outside, as
//! [`Camera::framing`] does, shows an interior (a cathedral, an atrium) as its outer walls, where
//! there is nothing to occlude: an all-white AO image. So the scene is first probed with rays
//! through the BVH: when the centre of the bounds is enclosed (nearly every direction from it hits
//! a surface) and those surfaces face it (front faces: it is in a room, not inside a solid), the
//! camera goes inside, on the longer horizontal axis, where its view hits the most geometry at a
//! useful distance. A room with one open side (more than a hemisphere of the probes hit, not all)
//! is seen through its opening. Otherwise the outside framing stays. Y is up, as for
//! [`Camera::framing`].
//!
//! Ours: a heuristic, not from a paper; it only chooses a starting view, printed so that it can
//! be kept or changed (`--eye`, `--target`).

use super::{Bvh, Ray};
use crate::scene::{Camera, Scene};
use glam::Vec3;

/// Directions probed from the centre of the bounds (a Fibonacci sphere).
const PROBE_RAYS: usize = 128;
/// Fraction of probe rays that must hit for the centre to count as enclosed.
const ENCLOSED_HITS: f32 = 0.85;
/// Fraction of probe rays that must hit for the centre to count as a room with an open side (more
/// than a hemisphere closed: a floor alone hits half).
const OPEN_ROOM_HITS: f32 = 0.6;
/// Fraction of those hits that must be front faces for the centre to be in a room, not a solid.
const ROOM_FRONT_FACES: f32 = 0.6;
/// The inside camera looks this far below the horizon (degrees), so floors and their contact
/// shadows are in view.
const TILT_DOWN_DEG: f32 = 10.0;
/// Rays across each candidate view (columns × rows) that score it.
const VIEW_RAYS: (usize, usize) = (9, 5);

/// Where an automatic camera was put (its [`Placement::name`] reads "an automatic camera NAME the
/// scene").
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Placement {
    /// Outside the bounds, framing all of them ([`Camera::framing`]).
    Outside,
    /// Inside: the centre of the bounds is enclosed by surfaces that face it.
    Inside,
    /// Outside an open side of a room, looking in through it.
    Opening,
}

impl Placement {
    /// "outside", "inside" or "looking into".
    pub fn name(self) -> &'static str {
        match self {
            Placement::Outside => "outside",
            Placement::Inside => "inside",
            Placement::Opening => "looking into",
        }
    }
}

/// The camera a view of `scene` starts from when none is asked for (the CLI's without `--camera`
/// or `--eye`, the web page's): the scene's first named camera, else [`auto_camera`] (building
/// the BVH it traces), whose placement is returned to be reported.
pub fn default_camera(scene: &Scene, aspect: f32) -> (Camera, Option<Placement>) {
    match scene.cameras.first() {
        Some(named) => (named.camera, None),
        None => {
            let (camera, placement) = auto_camera(scene, &Bvh::build(scene), aspect);
            (camera, Some(placement))
        }
    }
}

/// An automatic camera for `scene` (traced with `bvh`, built from it) and an image of aspect
/// ratio `aspect`: inside when the scene is a room around its centre, otherwise the outside
/// framing. Deterministic.
pub fn auto_camera(scene: &Scene, bvh: &Bvh, aspect: f32) -> (Camera, Placement) {
    let bounds = scene.bounds();
    let outside = Camera::framing(&bounds, aspect);
    let diagonal = bounds.diagonal();
    if !(diagonal.is_finite() && diagonal > 0.0) || bvh.triangle_count() == 0 {
        return (outside, Placement::Outside);
    }
    let centre = bounds.center();
    let t_min = 1e-5 * diagonal;
    let t_max = 2.0 * diagonal;
    let (mut hits, mut front, mut escape) = (0usize, 0usize, Vec3::ZERO);
    for i in 0..PROBE_RAYS {
        let dir = fibonacci(i, PROBE_RAYS);
        match bvh.closest_hit(scene, &Ray::new(centre, dir), t_min, t_max) {
            Some(hit) => {
                hits += 1;
                front += usize::from(hit.front_face);
            }
            None => escape += dir,
        }
    }
    let share = hits as f32 / PROBE_RAYS as f32;
    if (front as f32) < ROOM_FRONT_FACES * hits as f32 || share < OPEN_ROOM_HITS {
        return (outside, Placement::Outside);
    }
    if share < ENCLOSED_HITS {
        // A room with an open side (a Cornell box, a stage): look in through the opening, from
        // as far as the outside framing would stand.
        let Some(opening) = escape.try_normalize() else {
            return (outside, Placement::Outside);
        };
        let distance = (outside.eye - outside.target).length();
        return match Camera::new(centre + opening * distance, centre, outside.fov_y_deg) {
            Ok(camera) => (camera, Placement::Opening),
            Err(_) => (outside, Placement::Outside),
        };
    }
    // Candidates: along either horizontal axis, either way, backed off from the centre by a
    // share of the free distance behind; the longer axis first, so that it wins ties.
    let extent = bounds.max - bounds.min;
    let axes = if extent.x >= extent.z {
        [Vec3::X, Vec3::Z]
    } else {
        [Vec3::Z, Vec3::X]
    };
    let tilt = TILT_DOWN_DEG.to_radians();
    let mut best: Option<(f32, Camera)> = None;
    for axis in axes {
        for forward in [axis, -axis] {
            let behind = bvh
                .closest_hit(scene, &Ray::new(centre, -forward), t_min, t_max)
                .map_or(0.5 * extent.dot(axis), |h| h.t);
            for back in [0.8, 0.6, 0.4, 0.2, 0.0] {
                let eye = centre - forward * (back * behind);
                let look = (forward * tilt.cos() - Vec3::Y * tilt.sin()).normalize();
                let camera = Camera {
                    eye,
                    target: eye + look * (0.25 * diagonal),
                    up: Vec3::Y,
                    fov_y_deg: outside.fov_y_deg,
                };
                let score = view_score(scene, bvh, &camera, aspect, diagonal);
                if best.as_ref().is_none_or(|(s, _)| score > *s) {
                    best = Some((score, camera));
                }
            }
        }
    }
    match best {
        Some((_, camera)) => (camera, Placement::Inside),
        None => (outside, Placement::Outside),
    }
}

/// How much a view shows: the share of its rays that hit a front face, times how far its median
/// hit is against a quarter of the diagonal (capped at 1): a view that hits everything but only a
/// pillar in front of the eye scores low, as does one into open space.
/// `diagonal`: the scene's bounds' (rays run from 1e-5 of it to twice it, as the probes do).
fn view_score(scene: &Scene, bvh: &Bvh, camera: &Camera, aspect: f32, diagonal: f32) -> f32 {
    let (t_min, t_max) = (1e-5 * diagonal, 2.0 * diagonal);
    let (columns, rows) = VIEW_RAYS;
    let mut distances = Vec::with_capacity(columns * rows);
    for dir in view_ray_grid(camera, aspect, columns, rows) {
        match bvh.closest_hit(scene, &Ray::new(camera.eye, dir.normalize()), t_min, t_max) {
            Some(hit) if hit.front_face => distances.push(hit.t),
            _ => {}
        }
    }
    if distances.is_empty() {
        return 0.0;
    }
    let hit_share = distances.len() as f32 / (columns * rows) as f32;
    distances.sort_by(f32::total_cmp);
    let median = distances[distances.len() / 2];
    hit_share * (median / (0.25 * diagonal)).min(1.0)
}

/// Directions (not normalised) through the centres of a `columns` × `rows` grid over the image
/// of `camera` at aspect ratio `aspect`, row by row from the bottom: a coarse view of what the
/// camera sees, for scoring views on the CPU.
pub fn view_ray_grid(
    camera: &Camera,
    aspect: f32,
    columns: usize,
    rows: usize,
) -> impl Iterator<Item = Vec3> {
    let forward = camera.forward();
    let right = forward.cross(camera.up).normalize();
    let up = right.cross(forward);
    let tan_y = (0.5 * camera.fov_y_deg.to_radians()).tan();
    let tan_x = tan_y * aspect;
    (0..rows).flat_map(move |r| {
        (0..columns).map(move |c| {
            let x = (2.0 * (c as f32 + 0.5) / columns as f32 - 1.0) * tan_x;
            let y = (2.0 * (r as f32 + 0.5) / rows as f32 - 1.0) * tan_y;
            forward + right * x + up * y
        })
    })
}

/// The `i`-th of `n` directions spread evenly over the sphere (golden-angle spiral).
pub fn fibonacci(i: usize, n: usize) -> Vec3 {
    let n = n as f32;
    let z = 1.0 - 2.0 * (i as f32 + 0.5) / n;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = i as f32 * std::f32::consts::PI * (3.0 - 5f32.sqrt());
    Vec3::new(r * phi.cos(), z, r * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Material;

    /// A box of half extents `half` around the origin, its faces turned inward (a room) or outward
    /// (a solid), without the faces whose outward normal is in `open`.
    fn boxed(half: Vec3, inward: bool, double_sided: bool, open: &[Vec3]) -> Scene {
        let mut scene = Scene {
            name: "box".into(),
            materials: vec![Material {
                double_sided,
                ..Material::default()
            }],
            ..Scene::default()
        };
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            for outward in [axis, -axis] {
                if open.contains(&outward) {
                    continue;
                }
                let u = outward.any_orthonormal_vector();
                let w = outward.cross(u);
                let corner = |a: f32, b: f32| (outward + u * a + w * b) * half;
                let quad = [
                    corner(-1., -1.),
                    corner(1., -1.),
                    corner(1., 1.),
                    corner(-1., 1.),
                ];
                for [i, j, k] in [[0, 1, 2], [0, 2, 3]] {
                    let (a, mut b, mut c) = (quad[i], quad[j], quad[k]);
                    let faces_out = (b - a).cross(c - a).dot(outward) > 0.0;
                    if faces_out == inward {
                        std::mem::swap(&mut b, &mut c);
                    }
                    let base = scene.positions.len() as u32;
                    scene.positions.extend([a, b, c]);
                    scene.uvs.extend([glam::Vec2::ZERO; 3]);
                    scene.triangles.push([base, base + 1, base + 2]);
                    scene.triangle_materials.push(0);
                }
            }
        }
        scene
    }

    fn placed(scene: &Scene) -> (Camera, Placement) {
        auto_camera(scene, &Bvh::build(scene), 16.0 / 9.0)
    }

    #[test]
    fn a_room_is_seen_from_inside_along_its_length() {
        let half = Vec3::new(10.0, 2.0, 3.0);
        let room = boxed(half, true, false, &[]);
        let (camera, placement) = placed(&room);
        assert_eq!(placement, Placement::Inside);
        assert!(
            camera.eye.abs().cmplt(half).all(),
            "eye {} outside the room",
            camera.eye
        );
        let forward = camera.forward();
        assert!(
            forward.x.abs() > 0.9,
            "looks along {forward}, not the room's length"
        );
        camera.validate().unwrap();
    }

    #[test]
    fn a_solid_is_framed_from_outside_whichever_its_sides() {
        for double_sided in [false, true] {
            let solid = boxed(Vec3::ONE, false, double_sided, &[]);
            let (camera, placement) = placed(&solid);
            assert_eq!(placement, Placement::Outside, "double-sided {double_sided}");
            assert_eq!(camera, Camera::framing(&solid.bounds(), 16.0 / 9.0));
        }
    }

    #[test]
    fn a_room_open_on_one_side_is_seen_through_it() {
        let open = boxed(Vec3::ONE, true, true, &[Vec3::Z]);
        let (camera, placement) = placed(&open);
        assert_eq!(placement, Placement::Opening);
        assert!(camera.eye.z > 1.0 && camera.eye.x.abs() < 0.2 && camera.eye.y.abs() < 0.2);
        assert!(camera.forward().z < -0.99);
    }

    #[test]
    fn a_floor_alone_and_an_empty_scene_keep_the_outside_framing() {
        let floor = boxed(
            Vec3::new(5.0, 0.1, 5.0),
            true,
            true,
            &[Vec3::X, -Vec3::X, Vec3::Z, -Vec3::Z, Vec3::Y],
        );
        assert_eq!(placed(&floor).1, Placement::Outside);
        assert_eq!(placed(&Scene::default()).1, Placement::Outside);
    }
}
