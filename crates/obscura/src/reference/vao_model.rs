//! The VAO sample geometry of seed 000 §3.1–3.3 on the CPU, shared by the kernel's CPU mirror
//! ([`super::cpu_vao`], occluders from a depth buffer) and the ray-traced `vao` reference
//! ([`super::ground_truth`], occluders from every ray hit). It mirrors `shaders/estimators/vao.wgsl`.

use crate::estimators::vao::{
    kernel_sample, orthonormal_basis, pixel_rotation, MIN_COLUMN_FRACTION,
};
use crate::settings::{Normalization, VaoSettings};
use crate::view::ScreenGeometry;
use glam::{UVec2, Vec2, Vec3};

/// Free length of the column `[end, start]` for an occluder at height `z` (Fig. 4 / Eq. 8).
pub fn column_visibility(s: &VaoSettings, z: f32, start: f32, end: f32) -> f32 {
    let length = start - end;
    let sphere_vis = (start - end.max(z)).max(0.0);
    let halo_start = (1.0 + s.thickness) * s.radius;
    let halo_vis = ((z - halo_start) / length).clamp(0.0, 1.0) * length;
    sphere_vis + halo_vis
}

/// One line sample: its hemisphere-clipped column and where it falls on screen.
pub struct Column {
    /// Lateral offset in the sample disc (tangent, bitangent), world units.
    pub d: Vec2,
    /// Half height of the full column.
    pub h: f32,
    /// Top of the clipped column: height along the view axis from the pixel's surface point,
    /// world units.
    pub start: f32,
    /// Bottom of the clipped column (where the tangent plane cuts it, or −`h`); `start − end` is
    /// its length.
    pub end: f32,
    /// Unclamped framebuffer pixel coordinates of the sample point.
    pub px: Vec2,
}

/// A visible pixel's sample frame: position, view axis, disc basis, normal in that frame.
pub struct PixelFrame {
    /// The pixel's surface point, view space.
    pub pos: Vec3,
    /// Unit view axis from the point towards the camera: the columns' direction.
    pub axis: Vec3,
    /// First axis of the sample disc, perpendicular to `axis`.
    pub tangent: Vec3,
    /// Second axis of the sample disc, perpendicular to `axis` and `tangent`.
    pub bitangent: Vec3,
    n_local: Vec3,
    inv_n_z: f32,
    rotation: Vec2,
}

impl PixelFrame {
    /// `pos`: view-space surface point; `n`: its view-space normal facing the camera;
    /// `x`, `y`: the visible pixel (selects the 4×4 rotation).
    pub fn new(pos: Vec3, n: Vec3, x: u32, y: u32) -> Self {
        let n = n.normalize();
        let axis = -pos.normalize();
        let (tangent, bitangent) = orthonormal_basis(axis);
        let n_local = Vec3::new(n.dot(tangent), n.dot(bitangent), n.dot(axis));
        let n_z = if n_local.z >= 0.0 {
            n_local.z.max(1e-4)
        } else {
            n_local.z.min(-1e-4)
        };
        Self {
            pos,
            axis,
            tangent,
            bitangent,
            n_local,
            inv_n_z: 1.0 / n_z,
            rotation: pixel_rotation(x, y),
        }
    }

    /// Sample `k` (unit direction before rotation, radius fraction) of the kernel, or `None` when
    /// its clipped column is too short to count (seed 000 §3.2: a_i = 0).
    pub fn column(
        &self,
        k: (Vec2, f32),
        s: &VaoSettings,
        screen: &ScreenGeometry,
    ) -> Option<Column> {
        let (dir, kr) = k;
        let rot = self.rotation;
        let dir = Vec2::new(dir.x * rot.x - dir.y * rot.y, dir.x * rot.y + dir.y * rot.x);
        let r = s.radius;
        let d = dir * (kr * r);
        let h = (r * r - d.dot(d)).max(0.0).sqrt();
        let z_i = (-d.dot(self.n_local.truncate()) * self.inv_n_z).clamp(-h, h);
        let (start, end) = if self.n_local.z >= 0.0 {
            (h, z_i)
        } else {
            (z_i, -h)
        };
        if start - end < MIN_COLUMN_FRACTION * r {
            return None;
        }
        let sample_pos = self.pos + self.tangent * d.x + self.bitangent * d.y;
        Some(Column {
            d,
            h,
            start,
            end,
            px: screen.view_to_pixel(sample_pos),
        })
    }

    /// Height of view-space point `p` in `column`'s frame: its height along the view axis,
    /// corrected along the tangent plane for its lateral offset from the column (vao.wgsl).
    pub fn height(&self, column: &Column, p: Vec3) -> f32 {
        let offset = p - self.pos;
        let lateral = Vec2::new(offset.dot(self.tangent), offset.dot(self.bitangent)) - column.d;
        offset.dot(self.axis) + lateral.dot(self.n_local.truncate()) * self.inv_n_z
    }

    /// How fast [`Self::height`] grows along view-space direction `d` (its linear part; vao.wgsl
    /// `column_height_slope`). Not the difference of two heights: that loses the slope to
    /// rounding where the heights are large next to it (a scene far from its camera in world
    /// units; tests/it/scale_invariance.rs).
    pub fn height_slope(&self, d: Vec3) -> f32 {
        let lateral = Vec2::new(d.dot(self.tangent), d.dot(self.bitangent));
        d.dot(self.axis) + lateral.dot(self.n_local.truncate()) * self.inv_n_z
    }
}

/// The per-pixel sums of free and clipped column fractions.
#[derive(Default)]
pub struct Accumulator {
    sum: f32,
    clipped_sum: f32,
}

impl Accumulator {
    /// Add one column: its free length `free` and its clipped length, each over its full length 2h.
    pub fn add(&mut self, column: &Column, free: f32) {
        let inv_2h = 0.5 / column.h;
        self.sum += free * inv_2h;
        self.clipped_sum += (column.start - column.end) * inv_2h;
    }

    /// Final AO with the normalisation and exponent of `s`.
    pub fn finish(&self, s: &VaoSettings) -> f32 {
        let raw = match s.normalization {
            Normalization::Hemisphere => 2.0 * self.sum / s.samples as f32,
            Normalization::Clipped if self.clipped_sum > 0.0 => self.sum / self.clipped_sum,
            Normalization::Clipped => 1.0,
        };
        raw.clamp(0.0, 1.0).powf(s.exponent)
    }
}

/// The kernel's samples for `s` (before rotation).
pub fn kernel(s: &VaoSettings) -> Vec<(Vec2, f32)> {
    (0..s.samples)
        .map(|i| kernel_sample(i, s.samples))
        .collect()
}

/// The framebuffer pixel a sample reads, and whether its projection lies within 1e-3 px of a
/// pixel edge (there float rounding may snap two implementations to different pixels).
pub fn snap(px: Vec2, screen: &ScreenGeometry) -> (UVec2, bool) {
    let full = Vec2::new(screen.full_width() as f32, screen.full_height() as f32);
    let px = px.clamp(Vec2::ZERO, full - 0.5);
    let frac = px - px.floor();
    let ambiguous = frac.min_element() < 1e-3 || frac.max_element() > 1.0 - 1e-3;
    (px.as_uvec2(), ambiguous)
}
