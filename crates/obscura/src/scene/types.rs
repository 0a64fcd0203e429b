//! Scene data shared by every loader, the G-buffer rasteriser and the CPU BVH.
//!
//! One flat triangle soup in world space: loaders apply node transforms, so nothing downstream
//! needs a scene graph. Conventions (docs/ARCHITECTURE.md): right-handed, +Y up, metres for
//! built-in scenes.

use glam::{Vec2, Vec3};

/// How a material's alpha is used (glTF 2.0 `alphaMode`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    /// Fully opaque; alpha ignored.
    Opaque,
    /// Alpha-tested: a fragment/hit is kept when `base_color.a * texture.a >= cutoff`.
    Mask {
        /// The alpha threshold, glTF `alphaCutoff` (0.5 where the file leaves it out).
        cutoff: f32,
    },
    /// Blended in glTF; AO treats it as opaque (no order-independent transparency here).
    Blend,
}

/// A material as far as AO and the colour composite need it.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The file's material name (glTF: `material{i}` where unnamed), for messages.
    pub name: String,
    /// Base colour factor, linear RGBA.
    pub base_color: [f32; 4],
    /// Index into [`Scene::textures`] of the base-colour texture (its alpha drives `Mask`).
    pub base_color_texture: Option<u32>,
    /// How alpha is used: alpha-tested materials are cut out and keep their back faces.
    pub alpha_mode: AlphaMode,
    /// Back faces are kept (rasteriser: no culling; rays: back-face hits count). glTF's
    /// `doubleSided`; true for every OBJ material (OBJ has no culling flag); see [`Sidedness`] for
    /// overriding it scene-wide.
    pub double_sided: bool,
}

/// Which faces of a scene count, for the G-buffer, the stochastic depth map and every ray alike.
///
/// Renderers that produce ground-truth AO (Blender Cycles among them) count both sides of every
/// triangle; real-time engines cull back faces where a material says it may. An open mesh, a leaf
/// or a wall seen from behind occludes only if its back faces count, so the default keeps what the
/// file says: glTF's per-material `doubleSided`, and double-sided for OBJ, which has no such flag.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sidedness {
    /// Each material as its file says (glTF `doubleSided`; OBJ double-sided).
    #[default]
    AsAuthored,
    /// Every material double-sided.
    DoubleSided,
    /// Back faces culled on every material that is not alpha-tested (alpha-tested materials keep
    /// them, as in the authors' code, docs/AUTHORS_CODE.md §1.6: a foliage card is seen from both
    /// sides).
    CullBackFaces,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: [0.8, 0.8, 0.8, 1.0],
            base_color_texture: None,
            alpha_mode: AlphaMode::Opaque,
            double_sided: false,
        }
    }
}

/// Which normal AO is computed around, in the G-buffer and the reference alike.
///
/// Engines' G-buffers and offline renderers (Blender Cycles among them) use the shading normal
/// interpolated from the vertex normals, and so does obscura by default where the file has vertex
/// normals (issue 62: on Crytek Sponza it halved the ground truth's error against Cycles, MAE
/// 0.0187 → 0.0097). The papers' kernels and the authors' code use the flat face normal, which the
/// scripts reproducing the papers' tables ask for (`--normals face`). A scene without vertex
/// normals (the built-in procedural scenes) gets face normals either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Normals {
    /// The triangle's geometric normal (the papers' choice).
    Face,
    /// The vertex normals interpolated across the triangle, turned to the side the geometric
    /// normal faces; the face normal where a triangle lacks vertex normals (the default).
    #[default]
    Shading,
}

impl Normals {
    /// The name reports use (`face`, `shading`).
    pub fn name(self) -> &'static str {
        match self {
            Normals::Face => "face",
            Normals::Shading => "shading",
        }
    }
}

impl Sidedness {
    /// The name reports use.
    pub fn name(self) -> &'static str {
        match self {
            Sidedness::AsAuthored => "as authored",
            Sidedness::DoubleSided => "double-sided",
            Sidedness::CullBackFaces => "back faces culled",
        }
    }
}

impl std::str::FromStr for Normals {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "face" => Ok(Normals::Face),
            "shading" => Ok(Normals::Shading),
            _ => Err(format!(
                "'{s}' is not a normal choice: use 'shading' (default: interpolated vertex \
                 normals where the file has them) or 'face' (the papers')"
            )),
        }
    }
}

/// An RGBA8 texture (sRGB-encoded colour, linear alpha), row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// The image's name or file name, for messages.
    pub name: String,
    /// Width in texels (at most [`crate::scene::MAX_TEXTURE_SIZE`] for loaded images).
    pub width: u32,
    /// Height in texels (at most [`crate::scene::MAX_TEXTURE_SIZE`] for loaded images).
    pub height: u32,
    /// `width × height × 4` bytes, RGBA per texel.
    pub rgba8: Vec<u8>,
}

/// A pinhole camera. `fov_y_deg` is the vertical field of view of the *visible* image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Camera position, world space.
    pub eye: Vec3,
    /// The point looked at, world space: only its direction from `eye` matters.
    pub target: Vec3,
    /// Up direction, world space: any length, but not zero or along the view direction.
    pub up: Vec3,
    /// Vertical field of view of the visible image, degrees, strictly between 0 and 180.
    pub fov_y_deg: f32,
}

/// A camera a scene names (a glTF file's cameras, the built-ins' `closeup` and `overview`).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedCamera {
    /// The name [`Scene::camera`] looks it up by.
    pub name: String,
    /// The camera.
    pub camera: Camera,
}

/// Axis-aligned bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// The lowest x, y and z, world units.
    pub min: Vec3,
    /// The highest x, y and z, world units.
    pub max: Vec3,
}

/// A triangle soup in world space with materials and named cameras.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The scene's name in messages and reports: a built-in's name, or the file's path.
    pub name: String,
    /// World-space vertex positions.
    pub positions: Vec<Vec3>,
    /// Texture coordinates, one per position (zero where the source has none).
    pub uvs: Vec<Vec2>,
    /// Vertex (shading) normals, unit length, one per position, or empty when the source has
    /// none; a zero vector marks a vertex without one. Used only with [`Normals::Shading`].
    pub normals: Vec<Vec3>,
    /// Which normal AO is computed around (default: the shading normal where the scene has vertex
    /// normals, else the face normal).
    pub normal_mode: Normals,
    /// The last [`Sidedness`] applied to the materials ([`Scene::set_sidedness`]).
    pub sidedness: Sidedness,
    /// Counter-clockwise front faces (glTF/OBJ convention), indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Material index (into `materials`) of each triangle.
    pub triangle_materials: Vec<u32>,
    /// The materials `triangle_materials` indexes.
    pub materials: Vec<Material>,
    /// The base-colour textures [`Material::base_color_texture`] indexes.
    pub textures: Vec<Texture>,
    /// Named cameras; the first one is the default (for built-ins: the close-up).
    pub cameras: Vec<NamedCamera>,
    /// Camera paths ([`crate::scene::CameraPath`]): the built-ins' (each moves past the scene's
    /// occluders) and a glTF file's animated cameras; a scene without any gets an automatic
    /// orbit ([`Scene::path`]).
    pub paths: Vec<super::CameraPath>,
    /// Where this scene's coordinates have their origin in its file's coordinates: a point at
    /// `p` in the scene is at `origin + p` in the file. Zero unless the scene lay so far from its
    /// file's origin, for its size, that 32-bit floats could not hold it ([`Scene::recentre`]);
    /// points given in the file's coordinates (`--eye`, `--target`) go through
    /// [`Scene::from_file_point`].
    pub origin: glam::DVec3,
}

impl Texture {
    /// Alpha (0..1) of the texel under `uv`, nearest texel, repeat wrapping, LOD 0.
    ///
    /// This is *the* alpha-test lookup: the G-buffer shader (`textureLoad` of the same texel) and
    /// the CPU BVH both use it, so rasterised and ray-traced alpha masks agree texel for texel.
    /// `uv` follows glTF: (0,0) is the top-left corner of the image.
    pub fn alpha_at(&self, uv: Vec2) -> f32 {
        let (x, y) = self.texel_at(uv);
        f32::from(self.rgba8[((y * self.width + x) * 4 + 3) as usize]) / 255.0
    }

    /// Integer texel coordinates under `uv` (nearest, repeat wrapping).
    pub fn texel_at(&self, uv: Vec2) -> (u32, u32) {
        let f = uv - uv.floor();
        let x = ((f.x * self.width as f32) as u32).min(self.width - 1);
        let y = ((f.y * self.height as f32) as u32).min(self.height - 1);
        (x, y)
    }
}

impl Material {
    /// Whether a surface point with texture coordinate `uv` is kept by the alpha test.
    /// Always true for `Opaque`/`Blend` materials.
    pub fn passes_alpha_test(&self, textures: &[Texture], uv: Vec2) -> bool {
        match self.alpha_mode {
            AlphaMode::Mask { cutoff } => {
                let texel = self
                    .base_color_texture
                    .and_then(|t| textures.get(t as usize))
                    .map_or(1.0, |t| t.alpha_at(uv));
                self.base_color[3] * texel >= cutoff
            }
            AlphaMode::Opaque | AlphaMode::Blend => true,
        }
    }

    /// The material has an alpha test (`AlphaMode::Mask`): some of its texels may be cut away.
    pub fn is_alpha_tested(&self) -> bool {
        matches!(self.alpha_mode, AlphaMode::Mask { .. })
    }

    /// Back faces count (rasteriser does not cull them, rays hit them): double-sided or
    /// alpha-tested materials, as in the authors' code (docs/AUTHORS_CODE.md §1.6).
    pub fn keeps_back_faces(&self) -> bool {
        self.double_sided || self.is_alpha_tested()
    }
}
