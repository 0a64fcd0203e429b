//! Watertight ray/triangle intersection (Woop, Benthin, Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2(1), 2013), with the per-ray set-up shared by the box test.
//!
//! The ray is mapped to a space where it starts at the origin and runs along +z (translate, permute
//! axes so the largest direction component is z, shear x and y). A triangle is hit when the origin
//! lies inside its 2-D projection there, decided by the signs of three edge functions. Each edge
//! function is computed from two transformed vertices only, and a vertex's transformed position
//! does not depend on the triangle it belongs to, so two triangles sharing an edge get exactly
//! negated values: no ray passes between them. Where an edge function is exactly zero it is
//! recomputed in f64 (products of f32 are exact there), as the paper does, so the sign is exact
//! too.

use glam::{Mat3A, Vec3A, Vec3Swizzles, Vec4, Vec4Swizzles};

use super::{NodePair, Ray};

/// Per-ray constants for the box and triangle tests.
pub(super) struct RayPre {
    origin: Vec3A,
    /// Origin and `1 / dir` per axis, splatted for the 4-wide pair test (`1 / dir` is ±inf for a
    /// zero component; see `pair_entry`).
    origin4: [Vec4; 3],
    inv_dir4: [Vec4; 3],
    /// Per axis: the direction is negative, so the ray enters a slab through its `max` plane.
    negative: [bool; 3],
    /// Some direction component is exactly zero: slab distances can be `0 * inf = NaN`.
    zero_component: bool,
    /// Rows: translated vertex → sheared space (x, y: position of the vertex seen along the ray;
    /// z: scaled distance along the ray).
    shear: Mat3A,
}

/// Relative slack added to box exit distances and to the interval end used for culling, so that the
/// f32 rounding of the slab test never culls a box that holds a hit the triangle test would accept
/// (2·γ(3) in PBRT's notation is 3.6e-7; this is a little more).
pub(super) const T_SLACK: f32 = 4.0 * f32::EPSILON;

/// `t` moved up by a relative slack (also for negative `t`; ±inf stay as they are — written without
/// `t + |t| * k`, which is NaN for -inf).
#[inline(always)]
pub(super) fn loosen(t: f32) -> f32 {
    (t * (1.0 + T_SLACK)).max(t * (1.0 - T_SLACK))
}

/// A geometric hit before the scene's rules are applied.
#[derive(Clone, Copy, Debug)]
pub(super) struct TriHit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
    pub front_face: bool,
}

impl RayPre {
    /// `None` for rays that cannot hit anything: non-finite origin or direction, zero direction, or
    /// a direction so small that `1 / dir` overflows.
    pub fn new(ray: &Ray) -> Option<Self> {
        if !ray.origin.is_finite() || !ray.dir.is_finite() {
            return None;
        }
        let d = ray.dir.to_array();
        let ad = ray.dir.abs();
        let kz = if ad.x >= ad.y && ad.x >= ad.z {
            0
        } else if ad.y >= ad.z {
            1
        } else {
            2
        };
        let dz = d[kz];
        if dz == 0.0 {
            return None;
        }
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        // Swapping x and y for a negative z direction keeps the winding (and so the sign of the
        // determinant) the same for both directions along an axis.
        if dz < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let sz = 1.0 / dz;
        if !sz.is_finite() {
            return None;
        }
        let sx = d[kx] / dz;
        let sy = d[ky] / dz;
        let mut row_x = [0.0f32; 3];
        let mut row_y = [0.0f32; 3];
        let mut row_z = [0.0f32; 3];
        row_x[kx] = 1.0;
        row_x[kz] = -sx;
        row_y[ky] = 1.0;
        row_y[kz] = -sy;
        row_z[kz] = sz;
        // `shear * a` = (row_x·a, row_y·a, row_z·a). Each row has one zero entry, so every
        // component is a two-term sum and rounds exactly like the paper's `a[kx] - sx * a[kz]`.
        let shear = Mat3A::from_cols(row_x.into(), row_y.into(), row_z.into()).transpose();

        // 1 / -0.0 = -inf: the sign test below also classifies negative zeros correctly.
        let inv_dir = d.map(|x| 1.0 / x);
        Some(Self {
            origin: ray.origin.into(),
            origin4: ray.origin.to_array().map(Vec4::splat),
            inv_dir4: inv_dir.map(Vec4::splat),
            negative: inv_dir.map(|x| x < 0.0),
            zero_component: d.contains(&0.0),
            shear,
        })
    }

    /// Slab test of both boxes of a sibling pair against the interval `[t_lo, t_hi]`. Returns a
    /// bit mask (bit 0: left box overlaps, bit 1: right) and the entry distances.
    ///
    /// Robust in the PBRT sense: the exit distance gets a relative slack (`loosen`). A zero
    /// direction component with the origin exactly on one of that axis's planes gives
    /// `0 * inf = NaN`; the ray then lies in the slab's boundary, so that axis must not cull: NaN
    /// entries become -inf and NaN exits +inf. Entry and exit planes are picked by the direction's
    /// sign *before* the subtraction, so a NaN lands in the right slot to be replaced.
    #[inline(always)]
    pub fn pair_entry(&self, pair: &NodePair, t_lo: f32, t_hi: f32) -> (u32, [f32; 2]) {
        // Lanes: [entry_left, entry_right, exit_left, exit_right].
        let slab = |planes: Vec4, axis: usize| {
            // [min_l, min_r, max_l, max_r] → [max_l, max_r, min_l, min_r] for a negative direction.
            let planes = if self.negative[axis] {
                planes.zwxy()
            } else {
                planes
            };
            (planes - self.origin4[axis]) * self.inv_dir4[axis]
        };
        let mut tx = slab(pair.x, 0);
        let mut ty = slab(pair.y, 1);
        let mut tz = slab(pair.z, 2);
        if self.zero_component {
            let fix = Vec4::new(
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
                f32::INFINITY,
                f32::INFINITY,
            );
            tx = Vec4::select(tx.is_nan_mask(), fix, tx);
            ty = Vec4::select(ty.is_nan_mask(), fix, ty);
            tz = Vec4::select(tz.is_nan_mask(), fix, tz);
        }
        // No NaN is left, so min/max are well defined.
        let entry = tx.max(ty).max(tz).max(Vec4::splat(t_lo));
        let exit = tx.min(ty).min(tz).zwxy();
        let exit = (exit * (1.0 + T_SLACK))
            .max(exit * (1.0 - T_SLACK))
            .min(Vec4::splat(t_hi));
        let mask = entry.cmple(exit).bitmask() & 3;
        (mask, [entry.x, entry.y])
    }

    /// The watertight test. Returns the hit when `t` (in units of `ray.dir`) is in `[t_min,
    /// t_max]`. Degenerate triangles must be filtered out beforehand (see `is_valid_triangle`).
    #[inline(always)]
    pub fn intersect(&self, v: &[Vec3A; 3], t_min: f32, t_max: f32) -> Option<TriHit> {
        // Sheared vertices, transposed: rows are (x of a, b, c), (y of a, b, c), (z of a, b, c).
        let m = (self.shear
            * Mat3A::from_cols(v[0] - self.origin, v[1] - self.origin, v[2] - self.origin))
        .transpose();
        let (x, y, z) = (m.x_axis, m.y_axis, m.z_axis);
        // Scaled barycentrics of vertices 0, 1, 2, i.e. the edge functions of the opposite edges,
        // all three at once: e0 = c.x b.y - c.y b.x, e1 = a.x c.y - a.y c.x, e2 = b.x a.y - b.y
        // a.x.
        let mut e = x.zxy() * y.yzx() - y.zxy() * x.yzx();
        if e.cmpeq(Vec3A::ZERO).any() {
            // Exactly on an edge in f32: decide in f64, where the products are exact.
            let (x, y) = (x.as_dvec3(), y.as_dvec3());
            e = (x.zxy() * y.yzx() - y.zxy() * x.yzx()).as_vec3a();
        }
        // Inside when no edge function is negative or none is positive (either winding).
        if e.cmplt(Vec3A::ZERO).any() && e.cmpgt(Vec3A::ZERO).any() {
            return None;
        }
        let (e0, e1, e2) = (e.x, e.y, e.z);
        let det = e0 + e1 + e2;
        if det == 0.0 {
            // The ray runs in the triangle's plane (or the triangle projects to a point/segment).
            return None;
        }
        let t = (e0 * z.x + e1 * z.y + e2 * z.z) / det;
        // Written so that a NaN t fails.
        if !(t >= t_min && t <= t_max) {
            return None;
        }
        let inv_det = 1.0 / det;
        Some(TriHit {
            t,
            u: e1 * inv_det,
            v: e2 * inv_det,
            // det = -dot(n, dir) / |dir[kz]| with n = cross(p1-p0, p2-p0) (the x/y swap above keeps
            // the sign for negative directions), so det > 0 is a front face.
            front_face: det > 0.0,
        })
    }
}

/// Whether a triangle can ever be hit: finite vertices and a non-zero f32 cross product. Triangles
/// that fail are left out of the BVH (and out of the tests' brute force).
pub(super) fn is_valid_triangle(p: &[Vec3A; 3]) -> bool {
    p.iter().all(|v| v.is_finite()) && (p[1] - p[0]).cross(p[2] - p[0]) != Vec3A::ZERO
}
