//! The G-buffer read back to the CPU ([`crate::pipeline::renderer::Renderer::read_gbuffer`]): what the
//! CPU mirrors of the GPU passes ([`crate::reference`], the estimators' `cpu_<name>`) and the tests
//! read.

use crate::estimators::mirror::MirrorGBuffer;
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
        self.visible_pixels(guard_band)
            .map(|p| self.depth_at(p))
            .collect()
    }

    /// View-space normals of the visible region (guard band cropped), row-major (zero on the
    /// background).
    pub fn visible_normals(&self, guard_band: u32) -> Vec<Vec3> {
        self.visible_pixels(guard_band)
            .map(|p| self.normals[(p.y * self.width + p.x) as usize])
            .collect()
    }

    /// The framebuffer pixels of the visible region, row by row.
    fn visible_pixels(&self, guard_band: u32) -> impl Iterator<Item = UVec2> {
        let (w, h) = (self.width - 2 * guard_band, self.height - 2 * guard_band);
        (0..h).flat_map(move |y| (0..w).map(move |x| UVec2::new(x, y) + guard_band))
    }
}

/// The estimators' mirrors read a G-buffer through this trait: they sit below `raster`.
impl MirrorGBuffer for GBufferImage {
    fn size(&self) -> UVec2 {
        UVec2::new(self.width, self.height)
    }

    fn depth_at(&self, p: UVec2) -> f32 {
        GBufferImage::depth_at(self, p)
    }

    fn normal_at(&self, p: UVec2) -> Vec3 {
        self.normals[(p.y * self.width + p.x) as usize]
    }
}
