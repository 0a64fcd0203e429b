//! A [`Scene`] uploaded for the GPU: storage buffers the G-buffer pulls vertices from (and that
//! later GPU ray tracing can share), materials, and one texture array holding every base-colour
//! texture (alpha test + colour).

use super::chunks;
use crate::gpu::GpuError;
use crate::scene::{AlphaMode, Scene};
use glam::{Vec2, Vec3};

/// GPU mirror of `Material` in `shaders/raster/gbuffer.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuMaterial {
    base_color: [f32; 4],
    /// Texture array layer, or -1 for none.
    texture_layer: i32,
    /// Alpha-test cutoff, or -1 when the material is not alpha-tested.
    alpha_cutoff: f32,
    texture_size: [u32; 2],
    /// Bit 0: back faces count (double-sided or alpha-tested; `Material::keeps_back_faces`).
    flags: u32,
    _pad: [u32; 3],
}

/// A [`Scene`] in GPU buffers: what the G-buffer, the stochastic depth map and the BVH passes
/// read. Cheap to clone (wgpu handles).
#[derive(Clone)]
pub struct GpuScene {
    /// World-space vertex positions, `vec4<f32>` each (w = 1).
    pub positions: wgpu::Buffer,
    /// Per vertex `(u, v, normal)`, the normal octahedral-encoded (`encode_normal`,
    /// `shaders/common/vertex_normal.wgsl`); "none" everywhere unless the scene
    /// [uses shading normals](Scene::uses_shading_normals).
    pub attributes: wgpu::Buffer,
    /// The scene uses its vertex normals (the G-buffer interpolates them).
    pub shading_normals: bool,
    /// `(i0, i1, i2, material)` per triangle: back-face-culled triangles first, then double-sided
    /// ones without an alpha test, then the alpha-tested ones; within each group in the scene's
    /// order.
    pub triangles: wgpu::Buffer,
    /// The same triangles, each group along a Morton curve of their centroids: the order of
    /// [`GpuScene::chunks`] ([`GpuScene::draw_ordered`]).
    draw_triangles: wgpu::Buffer,
    /// One `Material` of `shaders/raster/gbuffer.wgsl` per scene material (colour, texture layer, alpha
    /// cutoff, back-face flag).
    pub materials: wgpu::Buffer,
    /// Every base-colour texture as one `Rgba8Unorm` 2D array, one layer each (smaller ones in the
    /// top-left corner of their layer).
    pub textures: wgpu::TextureView,
    /// Triangles `0..culled_count` are drawn with back-face culling, the rest without.
    pub culled_count: u32,
    /// Triangles `0..opaque_count` are never alpha-tested (no fragment of theirs is discarded).
    pub opaque_count: u32,
    /// Number of triangles in `triangles`.
    pub triangle_count: u32,
    /// The scene's axis-aligned bounds (min, max corner), world units.
    pub bounds: (glam::Vec3, glam::Vec3),
    /// The triangles of [`GpuScene::draw_ordered`] in chunks ([`chunks`]), none crossing a group
    /// of [`GpuScene::visibility_ranges`].
    pub chunks: std::sync::Arc<Vec<chunks::Chunk>>,
}

impl GpuScene {
    /// This scene with [`GpuScene::triangles`] in the chunks' order: for the raster passes that
    /// draw chunks (the G-buffer, depth peeling, the stochastic depth map) and what reads their
    /// triangle indices.
    pub fn draw_ordered(&self) -> GpuScene {
        GpuScene {
            triangles: self.draw_triangles.clone(),
            ..self.clone()
        }
    }

    /// The back-face-culled triangles, the double-sided ones without an alpha test, the
    /// alpha-tested ones.
    pub fn visibility_ranges(&self) -> [std::ops::Range<u32>; 3] {
        [
            0..self.culled_count,
            self.culled_count..self.opaque_count,
            self.opaque_count..self.triangle_count,
        ]
    }

    /// Uploads `scene`. Errors when a buffer or the texture count is over the adapter's `limits`.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        limits: &wgpu::Limits,
    ) -> Result<Self, GpuError> {
        // Before anything is made: 16 bytes a vertex (position; uv and normal) and a triangle
        // (indices and material), in each of these buffers.
        let sixteen = |n: usize| n as u64 * 16;
        crate::gpu::check_scene_buffers(
            limits,
            &scene.name,
            &[
                ("positions", sixteen(scene.positions.len())),
                ("vertex attributes", sixteen(scene.positions.len())),
                ("triangles", sixteen(scene.triangles.len())),
            ],
        )?;
        let positions: Vec<[f32; 4]> = scene
            .positions
            .iter()
            .map(|p| p.extend(1.0).to_array())
            .collect();
        let shading_normals = scene.uses_shading_normals();
        let attributes: Vec<[f32; 4]> = (0..scene.positions.len())
            .map(|i| {
                let normal = match shading_normals {
                    true => encode_normal(scene.normals[i]),
                    false => NO_NORMAL,
                };
                scene.uvs[i].extend(normal.x).extend(normal.y).to_array()
            })
            .collect();
        // Stable partition into contiguous draws: culled triangles (never alpha-tested), then
        // double-sided ones without an alpha test, then the alpha-tested ones.
        let material = |t: usize| &scene.materials[scene.triangle_materials[t] as usize];
        let group = |t: usize| match material(t) {
            m if m.is_alpha_tested() => 2,
            m if m.keeps_back_faces() => 1,
            _ => 0,
        };
        let corners = |t: usize| scene.triangles[t].map(|i| scene.positions[i as usize]);
        let bounds = scene.positions.iter().fold(
            (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let mut file_order: Vec<usize> = (0..scene.triangles.len()).collect();
        file_order.sort_by_key(|&t| group(t));
        let count = |g| file_order.iter().filter(|&&t| group(t) < g).count() as u32;
        let (culled_count, opaque_count) = (count(1), count(2));
        // Within each group along a space-filling curve: the chunks of the depth-tested passes
        // (raster::chunks).
        let mut draw_order = file_order.clone();
        chunks::sort_within_groups(&mut draw_order, group, corners, bounds);
        let ordered_corners: Vec<_> = draw_order.iter().map(|&t| corners(t)).collect();
        let chunks = chunks::chunks(&ordered_corners, &[culled_count, opaque_count]);
        let triangle_records = |order: &[usize]| -> Vec<[u32; 4]> {
            order
                .iter()
                .map(|&t| {
                    let [a, b, c] = scene.triangles[t];
                    [a, b, c, scene.triangle_materials[t]]
                })
                .collect()
        };
        let triangles = triangle_records(&file_order);
        let draw_triangles = triangle_records(&draw_order);

        // Textures share one array; smaller ones occupy the top-left corner of their layer.
        let (width, height) = scene
            .textures
            .iter()
            .fold((1, 1), |(w, h), t| (w.max(t.width), h.max(t.height)));
        let layers = scene.textures.len().max(1) as u32;
        if layers > limits.max_texture_array_layers {
            return Err(GpuError::Other(format!(
                "scene '{}' has {layers} textures, over this adapter's {} texture array layers",
                scene.name, limits.max_texture_array_layers
            )));
        }
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("base colour textures"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        for (layer, t) in scene.textures.iter().enumerate() {
            queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: 0,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: layer as u32,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                &t.rgba8,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * t.width),
                    rows_per_image: Some(t.height),
                },
                wgpu::Extent3d {
                    width: t.width,
                    height: t.height,
                    depth_or_array_layers: 1,
                },
            );
        }
        let textures = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });

        let materials: Vec<GpuMaterial> = scene
            .materials
            .iter()
            .map(|m| {
                let texture = m.base_color_texture.map(|t| &scene.textures[t as usize]);
                GpuMaterial {
                    base_color: m.base_color,
                    texture_layer: m.base_color_texture.map_or(-1, |t| t as i32),
                    alpha_cutoff: match m.alpha_mode {
                        AlphaMode::Mask { cutoff } => cutoff,
                        AlphaMode::Opaque | AlphaMode::Blend => -1.0,
                    },
                    texture_size: texture.map_or([1, 1], |t| [t.width, t.height]),
                    flags: u32::from(m.keeps_back_faces()),
                    _pad: [0; 3],
                }
            })
            .collect();

        let storage =
            |label, contents: &[u8]| crate::gpu::storage_buffer_init(device, label, contents);
        Ok(Self {
            positions: storage("positions", bytemuck::cast_slice(&positions)),
            attributes: storage("vertex attributes", bytemuck::cast_slice(&attributes)),
            shading_normals,
            triangles: storage("triangles", bytemuck::cast_slice(&triangles)),
            draw_triangles: storage(
                "triangles, draw order",
                bytemuck::cast_slice(&draw_triangles),
            ),
            materials: storage("materials", bytemuck::cast_slice(&materials)),
            textures,
            culled_count,
            opaque_count,
            triangle_count: triangles.len() as u32,
            bounds,
            chunks: std::sync::Arc::new(chunks),
        })
    }
}

/// The encoding of "no normal at this vertex" (shaders/common/vertex_normal.wgsl: x > 1.5).
const NO_NORMAL: Vec2 = Vec2::new(2.0, 2.0);

/// Octahedral encoding of a unit vector (Cigolle et al., JCGT 3(2) 2014, §3.2): two floats in
/// [−1, 1], decoded by `decode_vertex_normal` in shaders/common/vertex_normal.wgsl; the zero
/// vector ("no normal") becomes [`NO_NORMAL`].
pub(crate) fn encode_normal(n: Vec3) -> Vec2 {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    if l1.is_nan() || l1 <= 0.0 {
        return NO_NORMAL;
    }
    let p = Vec2::new(n.x, n.y) / l1;
    if n.z >= 0.0 {
        return p;
    }
    // The lower half folds over the diagonals; a zero coordinate counts as positive.
    let sign = Vec2::new(1f32.copysign(p.x), 1f32.copysign(p.y));
    (Vec2::ONE - Vec2::new(p.y.abs(), p.x.abs())) * sign
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The WGSL decoder, written again here to check the encoding round-trips.
    fn decode(e: Vec2) -> Vec3 {
        let mut n = Vec3::new(e.x, e.y, 1.0 - e.x.abs() - e.y.abs());
        let t = (-n.z).max(0.0);
        n.x += if n.x >= 0.0 { -t } else { t };
        n.y += if n.y >= 0.0 { -t } else { t };
        n.normalize()
    }

    #[test]
    fn octahedral_normals_round_trip() {
        let mut worst = 0.0f32;
        for i in 0..2000 {
            // A spread over the sphere, poles and axes included.
            let z = 1.0 - 2.0 * i as f32 / 1999.0;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - z * z).max(0.0).sqrt();
            for n in [
                Vec3::new(r * phi.cos(), r * phi.sin(), z),
                Vec3::X,
                Vec3::NEG_Y,
                Vec3::NEG_Z,
            ] {
                let e = encode_normal(n);
                assert!(e.abs().max_element() <= 1.0, "{n} -> {e}");
                worst = worst.max(decode(e).angle_between(n));
            }
        }
        assert!(worst < 1e-3, "worst round-trip error {worst} rad");
        assert_eq!(encode_normal(Vec3::ZERO), NO_NORMAL);
    }
}
