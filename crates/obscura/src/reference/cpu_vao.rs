//! The VAO kernel of `shaders/estimators/vao.wgsl` written again, plainly, on the CPU: a test oracle for the
//! GPU pass on a read-back G-buffer (seed 000 §3.1–3.5).

use super::vao_model::{column_visibility, kernel, snap, Accumulator, PixelFrame};
use crate::settings::VaoSettings;
use crate::view::ScreenGeometry;
use glam::{UVec2, Vec3};

/// A G-buffer read back to the CPU (whole framebuffer, guard band included, row-major).
pub struct GBufferImage {
    /// Framebuffer width in pixels, guard band included.
    pub width: u32,
    /// Framebuffer height in pixels, guard band included.
    pub height: u32,
    /// Linear depth, 0 = background.
    pub depth: Vec<f32>,
    /// View-space camera-facing normals.
    pub normals: Vec<Vec3>,
}

impl GBufferImage {
    /// Linear depth at framebuffer pixel `p` (0 = background).
    pub fn depth_at(&self, p: UVec2) -> f32 {
        self.depth[(p.y * self.width + p.x) as usize]
    }

    /// Linear depth of the visible region (guard band cropped), row-major.
    pub fn visible_depth(&self, guard_band: u32) -> Vec<f32> {
        let (w, h) = (self.width - 2 * guard_band, self.height - 2 * guard_band);
        (0..h)
            .flat_map(|y| (0..w).map(move |x| UVec2::new(x, y) + guard_band))
            .map(|p| self.depth_at(p))
            .collect()
    }
}

/// CPU VAO for every visible pixel (before blur).
pub struct CpuVao {
    /// AO per visible pixel, row-major, exponent applied (1 = unoccluded; background 1).
    pub ao: Vec<f32>,
    /// Pixels where some sample projects within `1e-3` px of a pixel edge: there float rounding
    /// may snap the GPU and the CPU to different neighbours, so the two may legitimately differ.
    pub ambiguous: Vec<bool>,
}

/// VAO of every visible pixel of `g` with settings `s`, as `vao.wgsl` computes it from the first
/// depth layer (no blur): the oracle the GPU `vao` pass is tested against.
pub fn cpu_vao(g: &GBufferImage, screen: &ScreenGeometry, s: &VaoSettings) -> CpuVao {
    cpu_vao_turned(g, screen, s, 0)
}

/// [`cpu_vao`] with the 4×4 rotation pattern turned by `pattern_offset` entries, as the GPU
/// turns it per frame under temporal accumulation (`pattern_index` in common/pattern.wgsl).
pub fn cpu_vao_turned(
    g: &GBufferImage,
    screen: &ScreenGeometry,
    s: &VaoSettings,
    pattern_offset: u32,
) -> CpuVao {
    cpu_vao_with(g, screen, s, pattern_offset, 0.0)
}

/// [`cpu_vao_turned`] with the radius capped at `max_radius_px` pixels on screen (0: no cap;
/// [`crate::AoSettings::max_radius_px`]): each pixel runs the kernel with its own R,
/// [`ScreenGeometry::capped_radius`], as `vao.wgsl` does.
pub fn cpu_vao_with(
    g: &GBufferImage,
    screen: &ScreenGeometry,
    s: &VaoSettings,
    pattern_offset: u32,
    max_radius_px: f32,
) -> CpuVao {
    let n_pixels = (screen.width * screen.height) as usize;
    let mut ao = vec![1.0; n_pixels];
    let mut ambiguous = vec![false; n_pixels];
    let kernel = kernel(s);
    for y in 0..screen.height {
        for x in 0..screen.width {
            let out = (y * screen.width + x) as usize;
            let pixel = UVec2::new(x, y) + screen.guard_band;
            let z = g.depth_at(pixel);
            if z <= 0.0 {
                continue;
            }
            let pos = screen.pixel_to_view(pixel.as_vec2() + 0.5, z);
            let s = &VaoSettings {
                radius: screen.capped_radius(s.radius, -pos.z, max_radius_px),
                ..*s
            };
            // The pattern entry this pixel uses, as the (x % 4, y % 4) that names it.
            let entry = (x % 4 + 4 * (y % 4) + pattern_offset) % 16;
            let frame = PixelFrame::new(
                pos,
                g.normals[(pixel.y * g.width + pixel.x) as usize],
                entry % 4,
                entry / 4,
            );
            let mut acc = Accumulator::default();
            for &k in &kernel {
                let Some(column) = frame.column(k, s, screen) else {
                    continue;
                };
                let (sample_pixel, edge) = snap(column.px, screen);
                ambiguous[out] |= edge;
                let mut free = column.start - column.end;
                if sample_pixel != pixel {
                    let sz = g.depth_at(sample_pixel);
                    if sz > 0.0 {
                        let occluder = screen.pixel_to_view(sample_pixel.as_vec2() + 0.5, sz);
                        free = column_visibility(
                            s,
                            frame.height(&column, occluder),
                            column.start,
                            column.end,
                        );
                    }
                }
                acc.add(&column, free);
            }
            ao[out] = acc.finish(s);
        }
    }
    CpuVao { ao, ambiguous }
}
