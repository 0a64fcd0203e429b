//! The VAO kernel of `shaders/vao.wgsl` written again, plainly, on the CPU: a test oracle for the
//! GPU pass on a read-back G-buffer (seed 000 §3.1–3.5).

use crate::kernels::vao::{kernel_sample, orthonormal_basis, pixel_rotation, MIN_COLUMN_FRACTION};
use crate::settings::{Normalization, VaoSettings};
use crate::view::ScreenGeometry;
use glam::{UVec2, Vec2, Vec3};

/// A G-buffer read back to the CPU (whole framebuffer, guard band included, row-major).
pub struct GBufferImage {
    pub width: u32,
    pub height: u32,
    /// Linear depth, 0 = background.
    pub depth: Vec<f32>,
    /// View-space camera-facing normals.
    pub normals: Vec<Vec3>,
}

impl GBufferImage {
    fn depth_at(&self, p: UVec2) -> f32 {
        self.depth[(p.y * self.width + p.x) as usize]
    }
}

/// CPU VAO for every visible pixel (before blur).
pub struct CpuVao {
    pub ao: Vec<f32>,
    /// Pixels where some sample projects within `1e-3` px of a pixel edge: there float rounding
    /// may snap the GPU and the CPU to different neighbours, so the two may legitimately differ.
    pub ambiguous: Vec<bool>,
}

/// Free length of the column for an occluder at height `z` (mirrors `column_visibility`).
pub fn column_visibility(s: &VaoSettings, z: f32, start: f32, end: f32) -> f32 {
    let length = start - end;
    let sphere_vis = (start - end.max(z)).max(0.0);
    let halo_start = (1.0 + s.thickness) * s.radius;
    let halo_vis = ((z - halo_start) / length).clamp(0.0, 1.0) * length;
    sphere_vis + halo_vis
}

pub fn cpu_vao(g: &GBufferImage, screen: &ScreenGeometry, s: &VaoSettings) -> CpuVao {
    let n_pixels = (screen.width * screen.height) as usize;
    let mut ao = vec![1.0; n_pixels];
    let mut ambiguous = vec![false; n_pixels];
    let full = Vec2::new(screen.full_width() as f32, screen.full_height() as f32);
    let kernel: Vec<(Vec2, f32)> = (0..s.samples)
        .map(|i| kernel_sample(i, s.samples))
        .collect();
    let r = s.radius;
    for y in 0..screen.height {
        for x in 0..screen.width {
            let out = (y * screen.width + x) as usize;
            let pixel = UVec2::new(x, y) + screen.guard_band;
            let z = g.depth_at(pixel);
            if z <= 0.0 {
                continue;
            }
            let pos = screen.pixel_to_view(pixel.as_vec2() + 0.5, z);
            let n = g.normals[(pixel.y * g.width + pixel.x) as usize].normalize();
            let axis = -pos.normalize();
            let (t, b) = orthonormal_basis(axis);
            let n_local = Vec3::new(n.dot(t), n.dot(b), n.dot(axis));
            let n_z = if n_local.z >= 0.0 {
                n_local.z.max(1e-4)
            } else {
                n_local.z.min(-1e-4)
            };
            let rot = pixel_rotation(x, y);
            let mut sum = 0.0;
            let mut clipped_sum = 0.0;
            for &(k, kr) in &kernel {
                let dir = Vec2::new(k.x * rot.x - k.y * rot.y, k.x * rot.y + k.y * rot.x);
                let d = dir * (kr * r);
                let h = (r * r - d.dot(d)).max(0.0).sqrt();
                let z_i = (-d.dot(n_local.truncate()) / n_z).clamp(-h, h);
                let (start, end) = if n_local.z >= 0.0 {
                    (h, z_i)
                } else {
                    (z_i, -h)
                };
                if start - end < MIN_COLUMN_FRACTION * r {
                    continue;
                }
                let sample_pos = pos + t * d.x + b * d.y;
                let px = screen
                    .view_to_pixel(sample_pos)
                    .clamp(Vec2::ZERO, full - 0.5);
                let frac = px - px.floor();
                if frac.min_element() < 1e-3 || frac.max_element() > 1.0 - 1e-3 {
                    ambiguous[out] = true;
                }
                let sample_pixel = px.as_uvec2();
                let mut free = start - end;
                if sample_pixel != pixel {
                    let sz = g.depth_at(sample_pixel);
                    if sz > 0.0 {
                        let offset = screen.pixel_to_view(sample_pixel.as_vec2() + 0.5, sz) - pos;
                        let lateral = Vec2::new(offset.dot(t), offset.dot(b)) - d;
                        let height = offset.dot(axis) + lateral.dot(n_local.truncate()) / n_z;
                        free = column_visibility(s, height, start, end);
                    }
                }
                sum += free / (2.0 * h);
                clipped_sum += (start - end) / (2.0 * h);
            }
            let raw = match s.normalization {
                Normalization::Hemisphere => 2.0 * sum / s.samples as f32,
                Normalization::Clipped if clipped_sum > 0.0 => sum / clipped_sum,
                Normalization::Clipped => 1.0,
            };
            ao[out] = raw.clamp(0.0, 1.0).powf(s.exponent);
        }
    }
    CpuVao { ao, ambiguous }
}
