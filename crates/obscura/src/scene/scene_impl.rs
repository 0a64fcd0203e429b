//! `Scene` methods: validation, bounds and camera lookup.
//!
//! `validate` is the single gate between loaders (or hand-built scenes) and the GPU: everything
//! downstream indexes `positions`, `uvs`, `materials` and `textures` without further checks.

use glam::Vec3;

use super::{AlphaMode, Bounds, Camera, Normals, Scene, SceneError, Sidedness};

impl Scene {
    /// Checks everything downstream code relies on when it indexes the scene's arrays.
    ///
    /// Rejects: no triangles; non-finite positions or uvs; vertex indices out of range; one uv per
    /// position violated; one material per triangle violated; material or texture indices out of
    /// range; texture data not `width * height * 4` bytes; invalid named cameras. Degenerate
    /// (zero-area) triangles are allowed: real scenes contain them and they are harmless.
    pub fn validate(&self) -> Result<(), SceneError> {
        let fail = |problem: String| {
            Err(SceneError::Invalid {
                scene: self.name.clone(),
                problem,
            })
        };
        if self.triangles.is_empty() {
            return fail("it has no triangles: give a file with triangle meshes".into());
        }
        if let Some(i) = self.positions.iter().position(|p| !p.is_finite()) {
            return fail(format!(
                "vertex {i} has a non-finite position {}: fix or re-export the model",
                self.positions[i]
            ));
        }
        if self.uvs.len() != self.positions.len() {
            return fail(format!(
                "it has {} texture coordinates for {} vertices (must be one per vertex)",
                self.uvs.len(),
                self.positions.len()
            ));
        }
        if !self.normals.is_empty() && self.normals.len() != self.positions.len() {
            return fail(format!(
                "it has {} vertex normals for {} positions (give one per position, or none)",
                self.normals.len(),
                self.positions.len()
            ));
        }
        if let Some(i) = self.normals.iter().position(|n| !n.is_finite()) {
            return fail(format!(
                "vertex normal {i} is not finite ({}): use a zero vector for 'no normal'",
                self.normals[i]
            ));
        }
        if let Some(i) = self.uvs.iter().position(|uv| !uv.is_finite()) {
            return fail(format!(
                "vertex {i} has a non-finite texture coordinate {}: fix or re-export the model",
                self.uvs[i]
            ));
        }
        let n = self.positions.len();
        for (t, tri) in self.triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
                return fail(format!(
                    "triangle {t} uses vertex index {v} but there are only {n} vertices: the index \
                     data is corrupt; re-export the model"
                ));
            }
        }
        if self.triangle_materials.len() != self.triangles.len() {
            return fail(format!(
                "it has {} triangle material indices for {} triangles (must be one per triangle)",
                self.triangle_materials.len(),
                self.triangles.len()
            ));
        }
        let m = self.materials.len();
        if let Some(t) = self
            .triangle_materials
            .iter()
            .position(|&i| i as usize >= m)
        {
            return fail(format!(
                "triangle {t} uses material {} but there are only {m} materials",
                self.triangle_materials[t]
            ));
        }
        for mat in &self.materials {
            if let Some(tex) = mat.base_color_texture {
                if tex as usize >= self.textures.len() {
                    return fail(format!(
                        "material '{}' uses texture {tex} but there are only {} textures",
                        mat.name,
                        self.textures.len()
                    ));
                }
            }
        }
        for tex in &self.textures {
            let expected = u64::from(tex.width) * u64::from(tex.height) * 4;
            if tex.width == 0 || tex.height == 0 || tex.rgba8.len() as u64 != expected {
                return fail(format!(
                    "texture '{}' is {}x{} but holds {} bytes (expected {expected} RGBA8 bytes, \
                     and a non-empty image)",
                    tex.name,
                    tex.width,
                    tex.height,
                    tex.rgba8.len()
                ));
            }
        }
        for cam in &self.cameras {
            if let Err(e) = cam.camera.validate() {
                return fail(format!("named camera '{}': {e}", cam.name));
            }
        }
        Ok(())
    }

    /// The scene point at `file_point`, given in the file's coordinates (see [`Scene::origin`]),
    /// computed in f64 so that a point far from the file's origin keeps its precision.
    pub fn from_file_point(&self, file_point: glam::DVec3) -> Vec3 {
        (file_point - self.origin).as_vec3()
    }

    /// Re-centres a scene that lies far from its origin for its size (issue 62, defect 4): 32-bit
    /// floats there cannot tell eye from target or one vertex from its neighbour. The vertices,
    /// named cameras and camera paths move by the centre of the bounds, which [`Scene::origin`]
    /// keeps. A scene near its origin is left alone. Loaders that read f64 re-centre before
    /// their coordinates become f32 (obj_loader); this one starts from the f32 positions, so it
    /// keeps what they hold.
    pub fn recentre(&mut self) {
        let offset = super::far_origin(self.positions.iter().map(|p| p.as_dvec3()));
        if offset == glam::DVec3::ZERO {
            return;
        }
        let shift = |p: Vec3| (p.as_dvec3() - offset).as_vec3();
        for p in &mut self.positions {
            *p = shift(*p);
        }
        for c in &mut self.cameras {
            c.camera.eye = shift(c.camera.eye);
            c.camera.target = shift(c.camera.target);
        }
        for path in &mut self.paths {
            path.move_points(shift);
        }
        self.origin += offset;
    }

    /// Axis-aligned bounds of all vertex positions (a zero box at the origin when there are none).
    pub fn bounds(&self) -> Bounds {
        if self.positions.is_empty() {
            return Bounds {
                min: Vec3::ZERO,
                max: Vec3::ZERO,
            };
        }
        let (min, max) = self.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        Bounds { min, max }
    }

    /// Whether obscura can work with the scene's coordinates: an error naming the bounds when they
    /// are not finite or too large for 32-bit floats ([`super::MAX_EXTENT`]), and a warning when
    /// every vertex is at one point (nothing can occlude anything there: usually a scale of 0).
    /// [`crate::Renderer::new`] checks this and logs the warning.
    pub fn check_extent(&self) -> Result<Option<String>, super::error::ExtentError> {
        let b = self.bounds();
        let limit = super::error::MAX_EXTENT;
        let inside = |v: Vec3| v.is_finite() && v.abs().max_element() <= limit;
        let usable = self.positions.is_empty() || (inside(b.min) && inside(b.max));
        if !usable {
            return Err(super::error::ExtentError {
                name: self.name.clone(),
                min: b.min,
                max: b.max,
            });
        }
        if !self.triangles.is_empty() && b.min == b.max {
            let warning = format!(
                "scene '{}' has zero extent: all {} vertices are at {}, so nothing can occlude \
                 anything; check the scene's scale",
                self.name,
                self.positions.len(),
                b.min
            );
            return Ok(Some(warning));
        }
        Ok(None)
    }

    /// The named camera `name`; an unknown name gives an error listing the available names.
    pub fn camera(&self, name: &str) -> Result<Camera, SceneError> {
        self.cameras
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.camera)
            .ok_or_else(|| SceneError::UnknownCamera {
                scene: self.name.clone(),
                name: name.to_string(),
                available: self.cameras.iter().map(|c| c.name.clone()).collect(),
            })
    }

    /// The first named camera (for built-ins: the close-up), else a camera framing the bounds.
    pub fn default_camera(&self, aspect: f32) -> Camera {
        self.cameras
            .first()
            .map_or_else(|| Camera::framing(&self.bounds(), aspect), |c| c.camera)
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Applies a scene-wide choice of which faces count (see [`Sidedness`]) to every material.
    /// `AsAuthored` leaves the materials as loaded.
    pub fn set_sidedness(&mut self, sidedness: Sidedness) {
        self.sidedness = sidedness;
        let double_sided = match sidedness {
            Sidedness::AsAuthored => return,
            Sidedness::DoubleSided => true,
            Sidedness::CullBackFaces => false,
        };
        for m in &mut self.materials {
            m.double_sided = double_sided;
        }
    }

    /// The normal AO is computed around at barycentric (`u`, `v`) of `triangle`, on the side
    /// `toward` points to (e.g. the direction back to the camera): the face normal, or with
    /// [`Normals::Shading`] the interpolated vertex normals, turned to the face normal's side
    /// (a double-sided surface seen from behind). Zero for a zero-area triangle.
    pub fn surface_normal(&self, triangle: u32, u: f32, v: f32, toward: Vec3) -> Vec3 {
        let corners = self.triangles[triangle as usize];
        let [a, b, c] = corners.map(|i| self.positions[i as usize]);
        let mut face = (b - a).cross(c - a).normalize_or_zero();
        if face.dot(toward) < 0.0 {
            face = -face;
        }
        if self.normal_mode == Normals::Face || self.normals.is_empty() {
            return face;
        }
        let [n0, n1, n2] = corners.map(|i| self.normals[i as usize]);
        if [n0, n1, n2].contains(&Vec3::ZERO) {
            return face;
        }
        let shading = (n0 * (1.0 - u - v) + n1 * u + n2 * v).normalize_or_zero();
        if shading == Vec3::ZERO || face == Vec3::ZERO {
            face
        } else if shading.dot(face) < 0.0 {
            -shading
        } else {
            shading
        }
    }

    /// Chooses which normal AO is computed around ([`Normals`]).
    pub fn set_normals(&mut self, normals: Normals) {
        self.normal_mode = normals;
    }

    /// Whether rendering uses vertex normals: [`Normals::Shading`] and the scene has some.
    pub fn uses_shading_normals(&self) -> bool {
        self.normal_mode == Normals::Shading && !self.normals.is_empty()
    }

    /// The scene-wide choices a comparison depends on, for reports: sides and normals (face
    /// normals where shading normals, the default, find no vertex normals in the scene).
    pub fn options_description(&self) -> String {
        let normals = match (self.normal_mode, self.normals.is_empty()) {
            (Normals::Shading, true) => "face (no vertex normals)",
            (mode, _) => mode.name(),
        };
        format!("sides {}, normals {normals}", self.sidedness.name())
    }

    /// A 64-bit fingerprint of everything that decides AO: positions, uvs, triangles, their
    /// materials (colour, alpha mode, sides), texture texels and, where used, the vertex normals;
    /// names and cameras are left out.
    /// Keys the reference cache, so a scene loaded with other options (e.g. [`Sidedness`]) or an
    /// edited file is a different scene.
    pub fn fingerprint(&self) -> u64 {
        // Over the raw bytes, fast enough (about 1 GB/s) for scenes with large textures.
        let mut hash = crate::hash::Fnv1a::default();
        hash.bytes(bytemuck::cast_slice(&self.positions));
        hash.bytes(bytemuck::cast_slice(&self.uvs));
        hash.bytes(bytemuck::cast_slice(&self.triangles));
        hash.bytes(bytemuck::cast_slice(&self.triangle_materials));
        if self.uses_shading_normals() {
            hash.bytes(b"shading normals");
            hash.bytes(bytemuck::cast_slice(&self.normals));
        }
        for m in &self.materials {
            hash.bytes(bytemuck::cast_slice(&m.base_color));
            hash.bytes(&m.base_color_texture.map_or(-1i64, i64::from).to_le_bytes());
            let cutoff = match m.alpha_mode {
                AlphaMode::Opaque => -1.0,
                AlphaMode::Blend => -2.0,
                AlphaMode::Mask { cutoff } => cutoff,
            };
            hash.bytes(&cutoff.to_le_bytes());
            hash.bytes(&[u8::from(m.double_sided)]);
        }
        for t in &self.textures {
            hash.bytes(&t.width.to_le_bytes());
            hash.bytes(&t.height.to_le_bytes());
            hash.bytes(&t.rgba8);
        }
        hash.0
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::super::{Material, NamedCamera, Texture};
    use super::*;

    fn tiny() -> Scene {
        Scene {
            name: "tiny".into(),
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            uvs: vec![Vec2::ZERO; 3],
            triangles: vec![[0, 1, 2]],
            triangle_materials: vec![0],
            materials: vec![Material::default()],
            textures: vec![],
            cameras: vec![],
            ..Default::default()
        }
    }

    fn problem(s: &Scene) -> String {
        let e = s.validate().unwrap_err();
        assert!(matches!(e, SceneError::Invalid { .. }));
        let msg = e.to_string();
        assert!(msg.contains("'tiny'"), "{msg}");
        msg
    }

    #[test]
    fn accepts_a_minimal_scene_and_degenerate_triangles() {
        let mut s = tiny();
        s.validate().unwrap();
        s.triangles.push([0, 0, 0]);
        s.triangle_materials.push(0);
        s.validate().unwrap();
        assert_eq!(s.triangle_count(), 2);
    }

    #[test]
    fn rejects_each_broken_invariant() {
        let mut s = tiny();
        s.triangles.clear();
        s.triangle_materials.clear();
        assert!(problem(&s).contains("no triangles"));

        let mut s = tiny();
        s.positions[1].y = f32::NAN;
        assert!(problem(&s).contains("vertex 1"));

        let mut s = tiny();
        s.uvs[2].x = f32::INFINITY;
        assert!(problem(&s).contains("texture coordinate"));

        let mut s = tiny();
        s.uvs.pop();
        assert!(problem(&s).contains("2 texture coordinates for 3 vertices"));

        let mut s = tiny();
        s.triangles[0] = [0, 1, 3];
        assert!(problem(&s).contains("vertex index 3"));

        let mut s = tiny();
        s.triangles[0] = [0, 1, u32::MAX];
        assert!(problem(&s).contains(&u32::MAX.to_string()));

        let mut s = tiny();
        s.triangle_materials.push(0);
        assert!(problem(&s).contains("material indices"));

        let mut s = tiny();
        s.triangle_materials[0] = 1;
        assert!(problem(&s).contains("material 1"));

        let mut s = tiny();
        s.materials[0].base_color_texture = Some(0);
        assert!(problem(&s).contains("texture 0"));

        let mut s = tiny();
        s.materials[0].base_color_texture = Some(0);
        s.textures.push(Texture {
            name: "t".into(),
            width: 2,
            height: 2,
            rgba8: vec![0; 15],
        });
        assert!(problem(&s).contains("15 bytes"));

        let mut s = tiny();
        s.cameras.push(NamedCamera {
            name: "bad".into(),
            camera: Camera {
                eye: Vec3::ZERO,
                target: Vec3::ZERO,
                up: Vec3::Y,
                fov_y_deg: 60.0,
            },
        });
        assert!(problem(&s).contains("'bad'"));
    }

    #[test]
    fn camera_lookup_lists_available_names() {
        let mut s = tiny();
        let err = s.camera("x").unwrap_err().to_string();
        assert!(err.contains("'x'") && err.contains("none"), "{err}");
        let cam = Camera::new(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 50.0).unwrap();
        for name in ["front", "side"] {
            s.cameras.push(NamedCamera {
                name: name.into(),
                camera: cam,
            });
        }
        assert_eq!(s.camera("side").unwrap(), cam);
        let err = s.camera("top").unwrap_err().to_string();
        assert!(
            err.contains("'top'") && err.contains("front, side"),
            "{err}"
        );
        assert_eq!(s.default_camera(1.0), cam);
    }

    #[test]
    fn extent_checks_name_the_bounds() {
        assert_eq!(tiny().check_extent(), Ok(None));
        let mut huge = tiny();
        huge.positions[1] = Vec3::new(1e30, 0.0, 0.0);
        let err = huge.check_extent().unwrap_err().to_string();
        assert!(
            err.contains("1.000e30") && err.contains("scale the scene down"),
            "{err}"
        );
        let mut nan = tiny();
        nan.positions[2] = Vec3::new(f32::NAN, 0.0, 0.0);
        assert!(nan.check_extent().is_err());
        let mut point = tiny();
        point.positions = vec![Vec3::ONE; 3];
        let warning = point.check_extent().unwrap().expect("a warning");
        assert!(warning.contains("zero extent"), "{warning}");
    }

    #[test]
    fn bounds_and_default_framing() {
        let s = tiny();
        let b = s.bounds();
        assert_eq!(b.min, Vec3::ZERO);
        assert_eq!(b.max, Vec3::new(1.0, 1.0, 0.0));
        let c = s.default_camera(1.5);
        assert_eq!(c, Camera::framing(&b, 1.5));
        assert_eq!(Scene::default().bounds().diagonal(), 0.0);
    }

    #[test]
    fn sidedness_overrides_every_material_and_changes_the_fingerprint() {
        let mut s = tiny();
        s.materials.push(Material {
            double_sided: true,
            ..Material::default()
        });
        let authored = s.fingerprint();
        let mut renamed = s.clone();
        renamed.name = "other".into();
        assert_eq!(renamed.fingerprint(), authored, "names do not decide AO");

        s.set_sidedness(Sidedness::AsAuthored);
        assert_eq!(s.fingerprint(), authored);
        s.set_sidedness(Sidedness::DoubleSided);
        assert!(s.materials.iter().all(|m| m.double_sided));
        let double = s.fingerprint();
        assert_ne!(double, authored);
        s.set_sidedness(Sidedness::CullBackFaces);
        assert!(s.materials.iter().all(|m| !m.double_sided));
        assert_eq!(
            s.options_description(),
            "sides back faces culled, normals face (no vertex normals)"
        );
        s.set_normals(Normals::Face);
        assert_eq!(
            s.options_description(),
            "sides back faces culled, normals face"
        );
        assert!(![double, authored].contains(&s.fingerprint()));

        let mut moved = tiny();
        moved.positions[1].x = 1.0 + f32::EPSILON;
        assert_ne!(moved.fingerprint(), tiny().fingerprint());
    }

    #[test]
    fn surface_normal_faces_the_viewer_and_falls_back_to_the_face() {
        // tiny() lies in z = 0 with face normal +z; its vertex normals lean towards +x.
        let mut s = tiny();
        let lean = Vec3::new(1.0, 0.0, 1.0).normalize();
        s.normals = vec![lean; 3];
        let (u, v) = (0.25, 0.25);
        assert!(s.uses_shading_normals(), "shading by default");
        s.set_normals(Normals::Face);
        assert_eq!(s.surface_normal(0, u, v, Vec3::Z), Vec3::Z, "face asked");
        s.set_normals(Normals::Shading);
        assert!(s.surface_normal(0, u, v, Vec3::Z).distance(lean) < 1e-6);
        // Seen from behind (a double-sided surface): both turn to the viewer's side.
        assert!(s.surface_normal(0, u, v, Vec3::NEG_Z).distance(-lean) < 1e-6);
        // Interpolated, then normalised.
        s.normals = vec![Vec3::Z, Vec3::X, Vec3::Z];
        let expected = (Vec3::Z * 0.5 + Vec3::X * 0.5).normalize();
        assert!(s.surface_normal(0, 0.5, 0.0, Vec3::Z).distance(expected) < 1e-6);
        // A corner without a normal: the face normal.
        s.normals[2] = Vec3::ZERO;
        assert_eq!(s.surface_normal(0, u, v, Vec3::Z), Vec3::Z);
        s.normals.clear();
        assert!(!s.uses_shading_normals());
        assert_eq!(s.surface_normal(0, u, v, Vec3::Z), Vec3::Z);
    }

    #[test]
    fn vertex_normals_are_validated() {
        let mut s = tiny();
        s.normals = vec![Vec3::Z; 2];
        assert!(problem(&s).contains("2 vertex normals for 3 positions"));
        s.normals = vec![Vec3::Z, Vec3::NAN, Vec3::Z];
        assert!(problem(&s).contains("vertex normal 1 is not finite"));
        s.normals = vec![Vec3::Z, Vec3::ZERO, Vec3::Z];
        s.validate().unwrap();
    }
}
