//! Random views of a scene (`cameras = "random"`, docs/DATASETS.md "Random cameras").
//!
//! Each view draws from its own stream, seeded by (spec seed, scene index, view index) alone, so
//! a view's camera does not depend on which shard, thread or machine computes it, nor on the
//! other views. A candidate is kept when it passes three tests on the CPU BVH:
//! 1. **Eye inside the bounds**: uniform in the scene's bounds shrunk by 5% of each extent on
//!    every side (a camera on the bounding box looks at the outside of the walls).
//! 2. **Eye in free space**: of [`PROBE_RAYS`] rays from the eye spread over the sphere, none
//!    hits a surface closer than `clearance` × the bounds' diagonal (no surface fills the view or
//!    cuts the near plane), and at most half of those that hit see a back face (an eye inside a
//!    closed mesh sees only back faces; one in a room sees front faces).
//! 3. **Enough to see**: a direction drawn uniformly over the sphere, at most 60° from the
//!    horizon (a view straight up or down has no defined roll with +Y up), whose
//!    [`COVERAGE_RAYS`]² rays through the image hit a surface for at least `min_coverage` of
//!    them (an empty view trains nothing).
//!
//! [`DIRECTIONS_PER_EYE`] directions are tried per eye and [`MAX_EYES`] eyes per view; then the
//! view fails with an error that says what to loosen. Ours: a heuristic, not from a paper.

use crate::bvh::framing::{fibonacci, view_ray_grid};
use crate::bvh::{Bvh, Ray};
use crate::hash::{pcg_hash, Fnv1a};
use crate::scene::{Camera, Scene};
use glam::Vec3;

/// Probe rays from a candidate eye (a Fibonacci sphere).
pub const PROBE_RAYS: usize = 64;
/// Rays per side of the coverage test's grid.
pub const COVERAGE_RAYS: usize = 16;
/// Directions tried from one eye.
pub const DIRECTIONS_PER_EYE: u32 = 8;
/// Eyes tried for one view before giving up.
pub const MAX_EYES: u32 = 256;
/// Largest angle between a view direction and the horizon, degrees.
const MAX_PITCH_DEG: f32 = 60.0;
/// Share of each extent the bounds shrink by on every side.
const BOUNDS_MARGIN: f32 = 0.05;

/// A stream of uniform numbers: the PCG hash ([`pcg_hash`]) of a counter mixed with a 64-bit
/// key. Written out (not the `rand` crate) because it is three lines and its numbers must never
/// change with a dependency's version: they decide the bytes of a dataset.
struct Stream {
    key: u64,
    counter: u32,
}

impl Stream {
    fn new(seed: u64, scene: usize, view: u32) -> Self {
        let mut h = Fnv1a::default();
        h.bytes(b"obscura.dataset.camera");
        h.bytes(&seed.to_le_bytes());
        h.bytes(&(scene as u64).to_le_bytes());
        h.bytes(&view.to_le_bytes());
        Self {
            key: h.0,
            counter: 0,
        }
    }

    /// Uniform in [0, 1), 24 bits.
    fn next(&mut self) -> f32 {
        let lo = self.key as u32;
        let hi = (self.key >> 32) as u32;
        let v = pcg_hash(pcg_hash(self.counter ^ lo).wrapping_add(hi));
        self.counter += 1;
        (v >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// Why no camera was found (the caller names the scene and the view).
#[derive(Debug)]
pub struct NoCamera {
    /// What to loosen.
    pub message: String,
}

/// The random camera of view `view` of scene number `scene_index` (`spec_seed` the spec's
/// seed), for an image of aspect `aspect` and vertical field of view `fov_y_deg`.
pub fn random_camera(
    scene: &Scene,
    bvh: &Bvh,
    (spec_seed, scene_index, view): (u64, usize, u32),
    aspect: f32,
    fov_y_deg: f32,
    (min_coverage, clearance): (f32, f32),
) -> Result<Camera, NoCamera> {
    let bounds = scene.bounds();
    let diagonal = bounds.diagonal();
    if !(diagonal.is_finite() && diagonal > 0.0) || bvh.triangle_count() == 0 {
        return Err(NoCamera {
            message: "the scene is empty or has no extent: use a scene with geometry".into(),
        });
    }
    let extent = bounds.max - bounds.min;
    let (lo, hi) = (
        bounds.min + extent * BOUNDS_MARGIN,
        bounds.max - extent * BOUNDS_MARGIN,
    );
    let mut stream = Stream::new(spec_seed, scene_index, view);
    let (mut crowded, mut sparse) = (0u32, 0u32);
    for _ in 0..MAX_EYES {
        let u = Vec3::new(stream.next(), stream.next(), stream.next());
        let eye = lo + (hi - lo) * u;
        if !free_space(scene, bvh, eye, clearance * diagonal, diagonal) {
            crowded += 1;
            // The directions' numbers are drawn anyway, so that every eye starts at the same
            // place in the stream whatever the tests decided.
            for _ in 0..2 * DIRECTIONS_PER_EYE {
                stream.next();
            }
            continue;
        }
        for _ in 0..DIRECTIONS_PER_EYE {
            let (a, b) = (stream.next(), stream.next());
            let max_sin = MAX_PITCH_DEG.to_radians().sin();
            // Uniform over the sphere's band within MAX_PITCH_DEG of the horizon.
            let y = (2.0 * a - 1.0) * max_sin;
            let r = (1.0 - y * y).sqrt();
            let phi = std::f32::consts::TAU * b;
            let dir = Vec3::new(r * phi.cos(), y, r * phi.sin());
            let Ok(camera) = Camera::new(eye, eye + dir * (0.25 * diagonal), fov_y_deg) else {
                continue;
            };
            if coverage(scene, bvh, &camera, aspect, diagonal) >= min_coverage {
                return Ok(camera);
            }
            sparse += 1;
        }
    }
    Err(NoCamera {
        message: format!(
            "no random camera passed after {MAX_EYES} eyes × {DIRECTIONS_PER_EYE} directions \
             ({crowded} eyes too close to a surface or inside a solid, {sparse} views covering \
             less than min_coverage {min_coverage}): lower min_coverage or clearance, or use \
             cameras = \"scene\""
        ),
    })
}

/// Test 2: no surface within `clearance` of `eye` and not inside a closed mesh.
fn free_space(scene: &Scene, bvh: &Bvh, eye: Vec3, clearance: f32, diagonal: f32) -> bool {
    let (mut hits, mut back) = (0usize, 0usize);
    for i in 0..PROBE_RAYS {
        let ray = Ray::new(eye, fibonacci(i, PROBE_RAYS));
        if let Some(hit) = bvh.closest_hit(scene, &ray, 0.0, 2.0 * diagonal) {
            if hit.t < clearance {
                return false;
            }
            hits += 1;
            back += usize::from(!hit.front_face);
        }
    }
    2 * back <= hits
}

/// Test 3: the share of a grid of rays through the image that hit a surface.
fn coverage(scene: &Scene, bvh: &Bvh, camera: &Camera, aspect: f32, diagonal: f32) -> f32 {
    let n = COVERAGE_RAYS;
    let hits = view_ray_grid(camera, aspect, n, n)
        .filter(|&dir| bvh.any_hit(scene, &Ray::new(camera.eye, dir), 0.0, 4.0 * diagonal))
        .count();
    hits as f32 / (n * n) as f32
}
