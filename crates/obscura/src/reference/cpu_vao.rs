//! The VAO kernel of `shaders/estimators/vao.wgsl` written again, plainly, on the CPU: a test oracle for the
//! GPU pass on a read-back G-buffer (seed 000 §3.1–3.5).

use super::vao_model::{column_visibility, kernel, snap, Accumulator, PixelFrame};
// The read-back G-buffer the CPU mirrors take lives in `raster` (re-exported at its old path).
pub use crate::raster::GBufferImage;
use crate::settings::VaoSettings;
use crate::view::ScreenGeometry;
use glam::UVec2;

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
