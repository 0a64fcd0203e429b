//! The frame's geometry: visible image, guard band and the widened projection.
//!
//! A guard band of `g` pixels is rendered around the visible `W×H` image so that AO samples that
//! leave the visible frame still find depth. The framebuffer is `(W+2g)×(H+2g)` and the vertical
//! field of view is widened so the visible part keeps the requested framing (seed 002 §3.5,
//! docs/AUTHORS_CODE.md §2.1: `fov' = 2·atan(tan(fov/2)·(H/2+g)/(H/2))`). Pixels keep a square
//! footprint, so the horizontal widening follows from the aspect ratio.

use crate::estimators::mirror::MirrorScreen;
use crate::scene::Camera;
use glam::{Mat4, UVec2, Vec2, Vec3};

/// Default guard band for a visible height: 64 px at 1080p scaled with the height and rounded up
/// to a multiple of 16 (64 at 1080p, 96 at 1440p, 128 at 4K; docs/ARCHITECTURE.md
/// "Conventions").
pub fn default_guard_band(height: u32) -> u32 {
    let scaled = 64.0 * f64::from(height) / 1080.0;
    ((scaled / 16.0).ceil() as u32).max(1) * 16
}

/// The vertical field of view, radians, that an engine's projection needs so that a framebuffer
/// with a guard band of `guard_band` pixels around a visible image `height` pixels tall keeps the
/// visible image's own field of view `visible_fov_y` (radians): `2·atan(tan(fov/2)·(H + 2g)/H)`
/// (the module comment). The aspect ratio of that projection is the framebuffer's,
/// `(W + 2g) / (H + 2g)`; pixels stay square. With a guard band of 0 it is `visible_fov_y`.
///
/// ```
/// use glam::camera::rh::proj::directx::perspective_infinite_reverse;
/// use obscura::{guard_banded_fov_y, ScreenGeometry};
///
/// // The game shows 1920×1080 at 60° and renders its depth prepass 64 px wider on every side.
/// let (w, h, g) = (1920, 1080, 64);
/// let fov = guard_banded_fov_y(60f32.to_radians(), h, g);
/// let aspect = (w + 2 * g) as f32 / (h + 2 * g) as f32;
/// let projection = perspective_infinite_reverse(fov, aspect, 0.1);
/// let screen = ScreenGeometry::from_projection(projection, w, h, g)?;
/// // The visible image keeps its 60°: one visible pixel spans 2·tan(30°)/1080.
/// let pixel = 2.0 * screen.tan_half_fov.y / screen.full_height() as f32;
/// assert!((pixel - 2.0 * 30f32.to_radians().tan() / 1080.0).abs() < 1e-7);
/// # Ok::<(), obscura::Error>(())
/// ```
pub fn guard_banded_fov_y(visible_fov_y: f32, height: u32, guard_band: u32) -> f32 {
    let widen = (height + 2 * guard_band) as f32 / height.max(1) as f32;
    2.0 * ((visible_fov_y * 0.5).tan() * widen).atan()
}

/// The near plane used for a scene: linear depth does not depend on it, so it only has to be
/// small against the scene (1e-5 of its diagonal, whatever the scene's units: a fixed floor
/// would clip a scene in kilometres or of a few millimetres in metres;
/// tests/it/scale_invariance.rs), and 1e-5 for a scene without extent.
pub fn near_plane(scene: &crate::scene::Scene) -> f32 {
    let diagonal = scene.bounds().diagonal();
    if diagonal > 0.0 && diagonal.is_finite() {
        diagonal * 1e-5
    } else {
        1e-5
    }
}

/// Everything a pass needs to go between pixels and view space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameView {
    /// The camera; its `fov_y_deg` frames the visible image, not the whole framebuffer.
    pub camera: Camera,
    /// Visible image size.
    pub width: u32,
    /// Visible image height in pixels (guard band excluded).
    pub height: u32,
    /// Guard band in pixels on every side: the framebuffer is `(width + 2g) × (height + 2g)`.
    pub guard_band: u32,
    /// `tan` of half the field of view of the whole framebuffer (x, y).
    pub tan_half_fov: Vec2,
    /// Near plane of the (reversed, infinite) projection; linear depth does not depend on it.
    pub near: f32,
}

impl FrameView {
    /// The view of `camera` for a visible `width`×`height` image with `guard_band` pixels on every
    /// side: the field of view is widened so that the visible part keeps the camera's framing.
    /// `near` is the projection's near plane ([`near_plane`]).
    pub fn new(camera: Camera, width: u32, height: u32, guard_band: u32, near: f32) -> Self {
        let tan_y_visible = (camera.fov_y_deg.to_radians() * 0.5).tan();
        // One visible pixel spans 2·tan(fov/2)/H; the guard band adds g such pixels per side.
        let pixel = 2.0 * tan_y_visible / height as f32;
        let (fw, fh) = (width + 2 * guard_band, height + 2 * guard_band);
        Self {
            camera,
            width,
            height,
            guard_band,
            tan_half_fov: Vec2::new(0.5 * pixel * fw as f32, 0.5 * pixel * fh as f32),
            near,
        }
    }

    /// The view of an engine's camera: its view matrix (world to view, rigid) and the screen
    /// geometry of its projection ([`ScreenGeometry::from_projection`]), for the sources that
    /// trace or rasterise hidden depth from the camera (`AmbientOcclusion::set_camera`). `near`:
    /// where camera rays start (the engine's near plane). Orthographic screens have no camera
    /// position: an error, as is a view matrix that scales or shears.
    pub fn from_matrices(
        view: Mat4,
        screen: ScreenGeometry,
        near: f32,
    ) -> Result<Self, crate::error::Error> {
        let bad = |why: String| Err(crate::error::Error::Input(why));
        if screen.orthographic {
            return bad(
                "an orthographic screen has no camera position: the hidden-depth sources need a \
                 perspective projection"
                    .into(),
            );
        }
        let to_world = view.inverse();
        let axes = [to_world.x_axis, to_world.y_axis, to_world.z_axis].map(|a| a.truncate());
        let rigid = axes.iter().all(|a| (a.length() - 1.0).abs() < 1e-4)
            && axes[0].dot(axes[1]).abs() < 1e-4
            && axes[1].dot(axes[2]).abs() < 1e-4
            && axes[0].dot(axes[2]).abs() < 1e-4;
        if !view.is_finite() || !rigid {
            return bad(format!(
                "view matrix {view:?} is not a rigid transform (rotation and translation): pass \
                 the camera's world-to-view matrix without scale"
            ));
        }
        if !(near > 0.0 && near.is_finite()) {
            return bad(format!("near plane {near} must be positive"));
        }
        let eye = to_world.w_axis.truncate();
        let tan_y_visible =
            screen.tan_half_fov.y * screen.height as f32 / screen.full_height() as f32;
        let camera = Camera {
            eye,
            target: eye - axes[2],
            up: axes[1],
            fov_y_deg: 2.0 * tan_y_visible.atan().to_degrees(),
        };
        Ok(Self {
            camera,
            width: screen.width,
            height: screen.height,
            guard_band: screen.guard_band,
            tan_half_fov: screen.tan_half_fov,
            near,
        })
    }

    /// Framebuffer width in pixels: the visible width plus the guard band on both sides.
    pub fn full_width(&self) -> u32 {
        self.width + 2 * self.guard_band
    }

    /// Framebuffer height in pixels: the visible height plus the guard band on both sides.
    pub fn full_height(&self) -> u32 {
        self.height + 2 * self.guard_band
    }

    /// Vertical field of view of the whole framebuffer, radians.
    pub fn full_fov_y(&self) -> f32 {
        2.0 * self.tan_half_fov.y.atan()
    }

    /// World space to view space (right-handed, looking down −Z): the camera's look-at matrix.
    pub fn view_matrix(&self) -> Mat4 {
        self.camera.view_matrix()
    }

    /// Reversed-Z infinite projection of the whole framebuffer (depth 1 at near, 0 at infinity).
    pub fn projection(&self) -> Mat4 {
        glam::camera::rh::proj::directx::perspective_infinite_reverse(
            self.full_fov_y(),
            self.tan_half_fov.x / self.tan_half_fov.y,
            self.near,
        )
    }

    /// Framebuffer pixel coordinates of a world-space point.
    pub fn view_to_pixel_world(&self, p: Vec3) -> Vec2 {
        self.screen()
            .view_to_pixel(self.view_matrix().transform_point3(p))
    }

    /// The same view at half the resolution (`resolution = "half"`): half the visible size and
    /// guard band, the same frustum. The caller checks [`ScreenGeometry::half`] first (even
    /// sizes).
    pub fn half(&self) -> Self {
        Self {
            width: self.width / 2,
            height: self.height / 2,
            guard_band: self.guard_band / 2,
            ..*self
        }
    }

    /// The same camera with `extra` more pixels of guard band on every side: the frustum widened
    /// so that every pixel of this view keeps its place, `extra` pixels in (the raster stochastic
    /// depth map's own guard band). `extra` = 0: this view.
    pub fn widened(&self, extra: u32) -> Self {
        if extra == 0 {
            return *self;
        }
        let (fw, fh) = (self.full_width() as f32, self.full_height() as f32);
        let grow = |full: f32| (full + 2.0 * extra as f32) / full;
        Self {
            guard_band: self.guard_band + extra,
            tan_half_fov: Vec2::new(
                self.tan_half_fov.x * grow(fw),
                self.tan_half_fov.y * grow(fh),
            ),
            ..*self
        }
    }

    /// What screen-space passes need of this view.
    pub fn screen(&self) -> ScreenGeometry {
        ScreenGeometry {
            width: self.width,
            height: self.height,
            guard_band: self.guard_band,
            tan_half_fov: self.tan_half_fov,
            orthographic: false,
        }
    }
}

/// The projection as screen-space passes see it: the visible size, the guard band and the field
/// of view of the whole framebuffer. This (not a camera) is what an engine hands to
/// [`crate::AmbientOcclusion`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenGeometry {
    /// Visible image width in pixels (guard band excluded): the size of the AO output.
    pub width: u32,
    /// Visible image height in pixels (guard band excluded).
    pub height: u32,
    /// Guard band in pixels on every side: the inputs are `(width + 2g) × (height + 2g)`.
    pub guard_band: u32,
    /// `tan` of half the field of view of the whole framebuffer, guard band included (x, y); for
    /// an orthographic projection, half the framebuffer's extent in world units.
    pub tan_half_fov: Vec2,
    /// Parallel view rays along −Z (an orthographic camera). Screen-space techniques only: the
    /// hidden-depth sources that trace or rasterise from a camera need a perspective one.
    pub orthographic: bool,
}

impl ScreenGeometry {
    /// The pipeline constants that the shared view helpers (`common/view.wgsl`) read: every
    /// pass that places pixels in view space sets them, filters included.
    pub(crate) fn view_constants(&self) -> Vec<(&'static str, f64)> {
        match self.orthographic {
            true => vec![("ORTHOGRAPHIC", 1.0)],
            false => Vec::new(),
        }
    }

    /// The geometry of an engine's projection matrix (OpenGL/Vulkan/D3D conventions alike: clip
    /// space from a right-handed view space looking down −Z, any depth range, reversed-Z or not,
    /// finite or infinite far plane), perspective or orthographic, for a framebuffer of
    /// `width + 2·guard_band` × `height + 2·guard_band` pixels.
    ///
    /// The frustum must be centred: an off-centre shift of up to 2 pixels (TAA jitter) is
    /// ignored (AO does not need sub-pixel registration); a larger one is an error, as is a
    /// matrix that is neither a perspective nor an orthographic projection.
    ///
    /// ```
    /// use glam::camera::rh::proj::directx::{orthographic, perspective_infinite_reverse};
    /// use obscura::ScreenGeometry;
    ///
    /// // 1920×1080 with a 64 px guard band: the engine renders depth at 2048×1208.
    /// let (fw, fh) = (2048.0, 1208.0);
    /// let reversed = perspective_infinite_reverse(60f32.to_radians(), fw / fh, 0.1);
    /// let screen = ScreenGeometry::from_projection(reversed, 1920, 1080, 64)?;
    /// assert!(!screen.orthographic);
    /// assert!((screen.tan_half_fov.y - 30f32.to_radians().tan()).abs() < 1e-6);
    ///
    /// let ortho = orthographic(-8.0, 8.0, -4.5, 4.5, 0.1, 100.0);
    /// let screen = ScreenGeometry::from_projection(ortho, 1920, 1080, 0)?;
    /// assert!(screen.orthographic);
    /// assert_eq!(screen.tan_half_fov, glam::Vec2::new(8.0, 4.5)); // half extents, world units
    /// # Ok::<(), obscura::Error>(())
    /// ```
    pub fn from_projection(
        projection: glam::Mat4,
        width: u32,
        height: u32,
        guard_band: u32,
    ) -> Result<Self, crate::error::Error> {
        let p = projection;
        let bad = |why: &str| {
            Err(crate::error::Error::Input(format!(
                "projection matrix {p:?} {why}: pass the camera's projection (clip from view \
                 space, the camera looking down -Z)"
            )))
        };
        if !p.is_finite() || p.x_axis.x == 0.0 || p.y_axis.y == 0.0 {
            return bad("is not finite or has a zero x or y scale");
        }
        // Perspective: clip w = −z_view; orthographic: clip w = 1.
        let orthographic = match (p.z_axis.w, p.w_axis.w) {
            (w_z, w_1) if (w_z + 1.0).abs() < 1e-6 && w_1.abs() < 1e-6 => false,
            (w_z, w_1) if w_z.abs() < 1e-6 && (w_1 - 1.0).abs() < 1e-6 => true,
            _ => return bad("is neither perspective (w = -z) nor orthographic (w = 1)"),
        };
        let offset = if orthographic {
            Vec2::new(p.w_axis.x, p.w_axis.y)
        } else {
            Vec2::new(p.z_axis.x, p.z_axis.y)
        };
        let (fw, fh) = (
            (width + 2 * guard_band) as f32,
            (height + 2 * guard_band) as f32,
        );
        let pixels = offset.abs() * Vec2::new(fw, fh) * 0.5;
        if pixels.max_element() > 2.0 {
            return bad(&format!(
                "is off-centre by {pixels} pixels (asymmetric frusta are not supported; up to \
                 2 px of jitter is ignored)"
            ));
        }
        let y_sign = p.y_axis.y.signum();
        if y_sign < 0.0 {
            return bad("flips y (a negative y scale): pass the projection before any y flip");
        }
        Ok(Self {
            width,
            height,
            guard_band,
            tan_half_fov: Vec2::new(1.0 / p.x_axis.x.abs(), 1.0 / p.y_axis.y),
            orthographic,
        })
    }

    /// Framebuffer width in pixels: the visible width plus the guard band on both sides.
    pub fn full_width(&self) -> u32 {
        self.width + 2 * self.guard_band
    }

    /// Framebuffer height in pixels: the visible height plus the guard band on both sides.
    pub fn full_height(&self) -> u32 {
        self.height + 2 * self.guard_band
    }

    /// The same frustum at half the resolution (`resolution = "half"`): every half-resolution
    /// pixel covers 2×2 pixels of this one exactly, so the visible size and the guard band must
    /// be even (an error naming them otherwise).
    pub fn half(&self) -> Result<Self, crate::error::Error> {
        if ![self.width, self.height, self.guard_band]
            .iter()
            .all(|v| v.is_multiple_of(2))
        {
            return Err(crate::error::Error::Input(format!(
                "resolution 'half' needs an even visible size and guard band (each half pixel \
                 covers 2x2 pixels), got {}x{} with a {} px guard band: use e.g. {}x{} and {}",
                self.width,
                self.height,
                self.guard_band,
                self.width + self.width % 2,
                self.height + self.height % 2,
                self.guard_band + self.guard_band % 2
            )));
        }
        Ok(Self {
            width: self.width / 2,
            height: self.height / 2,
            guard_band: self.guard_band / 2,
            ..*self
        })
    }

    /// View-space point of framebuffer pixel coordinates `px` (pixel centres at +0.5) at linear
    /// depth `z`. Mirrors `pixel_to_view` in `shaders/common/view.wgsl`.
    pub fn pixel_to_view(&self, px: Vec2, z: f32) -> Vec3 {
        let u = self.uniform();
        let ndc = Vec2::new(
            px.x * u.ndc_per_pixel[0] - 1.0,
            1.0 - px.y * u.ndc_per_pixel[1],
        );
        let scale = if self.orthographic { 1.0 } else { z };
        (ndc * self.tan_half_fov * scale).extend(-z)
    }

    /// Pixels per world unit across the view at linear depth `z`. Mirrors `pixels_per_unit`
    /// in WGSL.
    pub fn pixels_per_unit(&self, z: f32) -> Vec2 {
        let depth = if self.orthographic { 1.0 } else { z };
        Vec2::from(self.uniform().projection_scale) / depth
    }

    /// The world radius a shading point at linear depth `z` uses when the AO radius `radius` is
    /// capped at `max_radius_px` pixels on screen (0: no cap; seed 002 §3.5,
    /// [`crate::AoSettings::max_radius_px`]): `radius`, or the radius that covers exactly
    /// `max_radius_px` pixels. Mirrors `capped_radius` in WGSL, operation for operation.
    pub fn capped_radius(&self, radius: f32, z: f32, max_radius_px: f32) -> f32 {
        if max_radius_px > 0.0 {
            let per_unit = self.pixels_per_unit(z).y;
            if radius * per_unit > max_radius_px {
                return max_radius_px / per_unit;
            }
        }
        radius
    }

    /// Framebuffer pixel coordinates of a view-space point. Mirrors `view_to_pixel` in WGSL.
    pub fn view_to_pixel(&self, p: Vec3) -> Vec2 {
        let u = self.uniform();
        let depth = if self.orthographic { 1.0 } else { -p.z };
        let s = p.truncate() * (Vec2::from(u.projection_scale) / depth);
        let half = 0.5 * Vec2::new(self.full_width() as f32, self.full_height() as f32);
        Vec2::new(half.x + s.x, half.y - s.y)
    }

    /// The uniform block of `shaders/common/view.wgsl`.
    pub fn uniform(&self) -> ViewUniform {
        let size = Vec2::new(self.full_width() as f32, self.full_height() as f32);
        ViewUniform {
            full_size: [self.full_width(), self.full_height()],
            visible_size: [self.width, self.height],
            tan_half_fov: self.tan_half_fov.to_array(),
            guard_band: self.guard_band,
            orthographic: u32::from(self.orthographic),
            ndc_per_pixel: (2.0 / size).to_array(),
            projection_scale: (0.5 * size / self.tan_half_fov).to_array(),
            pattern_offset: 0,
            frame: 0,
            near: 0.0,
            _pad: 0,
        }
    }
}

/// The estimators' mirrors read the screen through this trait: they sit below `view`.
impl MirrorScreen for ScreenGeometry {
    fn visible_size(&self) -> UVec2 {
        UVec2::new(self.width, self.height)
    }

    fn guard_band(&self) -> u32 {
        self.guard_band
    }

    fn projection_scale(&self) -> Vec2 {
        Vec2::from(self.uniform().projection_scale)
    }

    fn pixel_to_view(&self, px: Vec2, z: f32) -> Vec3 {
        ScreenGeometry::pixel_to_view(self, px, z)
    }

    fn view_to_pixel(&self, p: Vec3) -> Vec2 {
        ScreenGeometry::view_to_pixel(self, p)
    }

    fn capped_radius(&self, radius: f32, z: f32, max_radius_px: f32) -> f32 {
        ScreenGeometry::capped_radius(self, radius, z, max_radius_px)
    }
}

/// GPU mirror of `struct View` in `shaders/common/view.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewUniform {
    /// Framebuffer size in pixels, guard band included (`full_width`, `full_height`).
    pub full_size: [u32; 2],
    /// Visible image size in pixels.
    pub visible_size: [u32; 2],
    /// As [`ScreenGeometry::tan_half_fov`]: `tan` of half the whole framebuffer's field of view,
    /// or half its extent in world units when orthographic.
    pub tan_half_fov: [f32; 2],
    /// Guard band in pixels on every side.
    pub guard_band: u32,
    /// 1 for an orthographic projection (parallel view rays along −Z), else 0.
    pub orthographic: u32,
    /// `2 / full_size`: normalised device coordinates per pixel.
    pub ndc_per_pixel: [f32; 2],
    /// `0.5 · full_size / tan_half_fov`: pixels per unit of x/z (y/z) from the image centre.
    pub projection_scale: [f32; 2],
    /// How far the estimators' 4×4 pattern is turned this frame (0 to 15; 0 unless temporal
    /// accumulation is on).
    pub pattern_offset: u32,
    /// The frame number (0 unless temporal accumulation is on, which counts frames): the
    /// `hemisphere` estimator seeds each frame's rays with it.
    pub frame: u32,
    /// The camera's near plane where the renderer knows its camera (`set_camera`), else 0: what
    /// lies nearer is never in the depth buffer (phase 1 of `rtao-two-phase` needs it).
    pub near: f32,
    /// Padding to the WGSL struct's 64 bytes.
    pub _pad: u32,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guard_band_defaults_follow_design() {
        assert_eq!(default_guard_band(1080), 64);
        assert_eq!(default_guard_band(1440), 96);
        assert_eq!(default_guard_band(2160), 128);
    }

    #[test]
    fn widened_fov_keeps_visible_framing() {
        let camera = Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            fov_y_deg: 60.0,
        };
        let plain = FrameView::new(camera, 320, 180, 0, 0.01);
        let banded = FrameView::new(camera, 320, 180, 32, 0.01);
        // The seed's formula for the widened fov.
        let h = 180.0 + 64.0;
        let expected = 2.0 * ((h / 2.0) * (30f32.to_radians()).tan() / (h / 2.0 - 32.0)).atan();
        assert!((banded.full_fov_y() - expected).abs() < 1e-6);
        // A point projects to the same visible pixel with and without the band.
        let p = Vec3::new(0.3, -0.2, -2.0);
        let (plain, banded) = (plain.screen(), banded.screen());
        let a = plain.view_to_pixel(p);
        let b = banded.view_to_pixel(p) - Vec2::splat(32.0);
        assert!((a - b).length() < 1e-3, "{a} vs {b}");
        let back = banded.pixel_to_view(banded.view_to_pixel(p), 2.0);
        assert!((back - p).length() < 1e-5);
    }

    #[test]
    fn a_widened_view_keeps_every_pixel_in_place() {
        let camera = Camera {
            eye: Vec3::new(1.0, 2.0, 3.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov_y_deg: 50.0,
        };
        let view = FrameView::new(camera, 320, 180, 16, 0.01);
        assert_eq!(view.widened(0), view);
        let wide = view.widened(40);
        assert_eq!((wide.full_width(), wide.full_height()), (432, 292));
        // The same as asking for the wider band in the first place.
        let direct = FrameView::new(camera, 320, 180, 56, 0.01);
        assert!((wide.tan_half_fov - direct.tan_half_fov).length() < 1e-6);
        let p = Vec3::new(0.4, 0.1, -0.5);
        let a = view.view_to_pixel_world(p);
        let b = wide.view_to_pixel_world(p) - Vec2::splat(40.0);
        assert!((a - b).length() < 1e-3, "{a} vs {b}");
    }
}
