//! What the estimators' CPU mirrors share. Each estimator's module holds its mirror (`cpu_<name>`):
//! the WGSL estimator written again as plain Rust per pixel, which the tests run on a read-back
//! G-buffer to hold the GPU pass to the same numbers. Here are the pieces several mirrors use once:
//! what a mirror reads ([`MirrorGBuffer`], [`MirrorScreen`]), the screen-space pixel set-up, where
//! a sample reads, the depth pyramid's levels and GTAO's slice integrals.
//!
//! The estimators sit below the view and the raster layers, so the mirrors name what they read as
//! traits; `raster::GBufferImage` and `view::ScreenGeometry` implement them.

use glam::{UVec2, Vec2, Vec3};

/// The G-buffer a mirror reads: the whole framebuffer, guard band included.
pub trait MirrorGBuffer {
    /// Framebuffer size in pixels, guard band included.
    fn size(&self) -> UVec2;
    /// Linear depth at framebuffer pixel `p` (0 = background).
    fn depth_at(&self, p: UVec2) -> f32;
    /// The view-space normal at framebuffer pixel `p`, as stored (not renormalised).
    fn normal_at(&self, p: UVec2) -> Vec3;
}

/// The screen geometry a mirror reads (`shaders/common/view.wgsl`'s view block and functions).
pub trait MirrorScreen {
    /// Visible image size in pixels (guard band excluded): the mirrors' output size.
    fn visible_size(&self) -> UVec2;
    /// Guard band in pixels on every side.
    fn guard_band(&self) -> u32;
    /// Pixels per unit of x/z (y/z) from the image centre (the view block's `projection_scale`).
    fn projection_scale(&self) -> Vec2;
    /// View-space point of framebuffer pixel coordinates `px` at linear depth `z`.
    fn pixel_to_view(&self, px: Vec2, z: f32) -> Vec3;
    /// Framebuffer pixel coordinates of view-space point `p`.
    fn view_to_pixel(&self, p: Vec3) -> Vec2;
    /// The world radius at linear depth `z` with the radius capped at `max_radius_px` pixels on
    /// screen (0: no cap).
    fn capped_radius(&self, radius: f32, z: f32, max_radius_px: f32) -> f32;

    /// Framebuffer size in pixels: the visible size plus the guard band on both sides.
    fn full_size(&self) -> UVec2 {
        self.visible_size() + 2 * self.guard_band()
    }
}

/// A mirror's image: `shade(x, y)` for every visible pixel, row-major, as (AO, whether a sample
/// lay where the GPU and the CPU may snap to different pixels).
pub fn per_visible_pixel(
    screen: &dyn MirrorScreen,
    mut shade: impl FnMut(u32, u32) -> (f32, bool),
) -> (Vec<f32>, Vec<bool>) {
    let size = screen.visible_size();
    let (mut ao, mut ambiguous) = (Vec::new(), Vec::new());
    for y in 0..size.y {
        for x in 0..size.x {
            let (a, edge) = shade(x, y);
            ao.push(a);
            ambiguous.push(edge);
        }
    }
    (ao, ambiguous)
}

/// A visible pixel as the screen-space estimators set it up (`screen_space.wgsl`).
pub struct PixelSetup {
    /// The surface point, view space.
    pub pos: Vec3,
    /// Unit vector from the point to the camera.
    pub v: Vec3,
    /// Unit view-space normal.
    pub n: Vec3,
    /// The pixel's centre, framebuffer pixel coordinates.
    pub centre: Vec2,
    /// The framebuffer pixel.
    pub pixel: UVec2,
    /// The radius in pixels at the point's depth.
    pub radius_px: f32,
}

/// [`per_visible_pixel`] over the pixels that shade: `shade(x, y, set-up)` for every visible pixel
/// with a surface whose `radius` covers a pixel at least on screen; the others (background, or a
/// radius under a pixel, where the kernels return before sampling) are unoccluded.
pub fn per_shaded_pixel(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    radius: f32,
    mut shade: impl FnMut(u32, u32, &PixelSetup) -> (f32, bool),
) -> (Vec<f32>, Vec<bool>) {
    per_visible_pixel(screen, |x, y| match pixel_setup(g, screen, x, y, radius) {
        Some(p) if p.radius_px >= 1.0 => shade(x, y, &p),
        _ => (1.0, false),
    })
}

/// Visible pixel (`x`, `y`) of `g` set up for a world `radius` (None for background).
pub fn pixel_setup(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    x: u32,
    y: u32,
    radius: f32,
) -> Option<PixelSetup> {
    let pixel = UVec2::new(x, y) + screen.guard_band();
    let z = g.depth_at(pixel);
    if z.is_nan() || z <= 0.0 {
        return None;
    }
    let centre = pixel.as_vec2() + 0.5;
    let pos = screen.pixel_to_view(centre, z);
    Some(PixelSetup {
        pos,
        v: (-pos).normalize(),
        n: g.normal_at(pixel).normalize(),
        centre,
        pixel,
        radius_px: radius * screen.projection_scale().y / z,
    })
}

/// The framebuffer pixel a sample at `px` reads for shading pixel `own` (framebuffer pixels of a
/// `full` framebuffer), and whether `px` lies within 1e-3 px of where the choice flips. Single and
/// two-phase schedules: the pixel `px` falls in, clamped into the framebuffer. Interleaved: the
/// pixel of `own`'s residue class mod 4 nearest to `px` (shaders/schedules/interleaved.wgsl),
/// clamped into the class's quarter-resolution layer.
pub fn sample_cell(px: Vec2, own: UVec2, full: Vec2, interleaved: bool) -> (UVec2, bool) {
    if !interleaved {
        let f = px.fract();
        let edge = f.min_element() < 1e-3 || f.max_element() > 1.0 - 1e-3;
        return (px.clamp(Vec2::ZERO, full - 0.5).floor().as_uvec2(), edge);
    }
    let residue = own % 4;
    let t = (px - 0.5 - residue.as_vec2()) / 4.0;
    let f = t.fract();
    let edge = (f - 0.5).abs().min_element() < 1e-3 / 4.0;
    let size = (full / 4.0).ceil();
    let cell = t.round().clamp(Vec2::ZERO, size - 1.0).as_uvec2();
    (cell * 4 + residue, edge)
}

/// The view-space surface a sample at framebuffer position `px` of pixel `p` finds (the pixel the
/// schedule reads there, [`sample_cell`]), or None for the shading pixel itself or background;
/// and whether `px` lies where the GPU and the CPU may snap to different pixels.
pub fn surface_at(
    g: &dyn MirrorGBuffer,
    screen: &dyn MirrorScreen,
    p: &PixelSetup,
    px: Vec2,
    interleaved: bool,
) -> (Option<Vec3>, bool) {
    let (cell, edge) = sample_cell(px, p.pixel, g.size().as_vec2(), interleaved);
    if cell == p.pixel {
        return (None, edge);
    }
    let z = g.depth_at(cell);
    if z.is_nan() || z <= 0.0 {
        return (None, edge);
    }
    (Some(screen.pixel_to_view(cell.as_vec2() + 0.5, z)), edge)
}

/// The depth pyramid as the pyramid estimators' mirrors read it: level 0 is the G-buffer's depth,
/// levels 1 … L − 1 the read-back pyramid, each row-major over its own size
/// ([`super::pyramid_level_size`]).
pub struct Levels<'a> {
    /// The G-buffer (level 0, and every shading point).
    pub g: &'a dyn MirrorGBuffer,
    /// The view the G-buffer was drawn with.
    pub screen: &'a dyn MirrorScreen,
    /// Levels 1 … L − 1.
    pub pyramid: &'a [Vec<f32>],
    /// The pyramid's factor K.
    pub factor: u32,
}

impl Levels<'_> {
    /// The view-space surface a sample at framebuffer position `px` of shading pixel `pixel`
    /// finds on `level` (0: the G-buffer's depth, clamped and snapped, the shading pixel and
    /// background giving none; l ≥ 1: the pyramid texel's mean depth at the texel block's
    /// centre), as sources/depth_pyramid.wgsl reads it; and whether `px` lies within 1e-3 texel
    /// of a texel edge (GPU and CPU may snap apart).
    pub fn surface(&self, pixel: UVec2, px: Vec2, level: u32) -> (Option<Vec3>, bool) {
        let full = self.g.size();
        let scale = self.factor.pow(level) as f32;
        let (w, h) = super::pyramid_level_size((full.x, full.y), self.factor, level);
        let t = px / scale;
        let f = t.fract();
        let edge = f.min_element() < 1e-3 || f.max_element() > 1.0 - 1e-3;
        let texel = t
            .clamp(Vec2::ZERO, Vec2::new(w as f32, h as f32) - 0.5)
            .floor()
            .as_uvec2();
        let z = if level == 0 {
            if texel == pixel {
                return (None, edge);
            }
            self.g.depth_at(texel)
        } else {
            self.pyramid[level as usize - 1][(texel.y * w + texel.x) as usize]
        };
        if z.is_nan() || z <= 0.0 {
            return (None, edge);
        }
        let centre = (texel.as_vec2() + 0.5) * scale;
        (Some(self.screen.pixel_to_view(centre, z)), edge)
    }
}

/// ¼ (−cos(2h − γ) + cos γ + 2h sin γ): the visible weight between V and a horizon at angle `h`
/// in a slice whose projected normal lies at angle `gamma` (slice_visibility.wgsl).
pub fn side_visibility(h: f32, gamma: f32) -> f32 {
    0.25 * (-(2.0 * h - gamma).cos() + gamma.cos() + 2.0 * h * gamma.sin())
}

/// ∫_a^b cos(θ − γ)|sin θ| dθ: the visible weight of a slice's directions between angles `a` ≤
/// `b` (slice_visibility.wgsl's `span_visibility`).
pub fn span_visibility(a: f32, b: f32, gamma: f32) -> f32 {
    b.signum() * side_visibility(b, gamma) - a.signum() * side_visibility(a, gamma)
}

/// The weight of a slice's whole hemisphere, cos γ + γ sin γ (slice_visibility.wgsl).
pub fn open_slice_visibility(gamma: f32) -> f32 {
    gamma.cos() + gamma * gamma.sin()
}
