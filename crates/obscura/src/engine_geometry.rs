//! The hidden-depth techniques over an engine's own geometry: vertex positions and indices as the
//! engine stores them (byte slices, or its `wgpu::Buffer`s read back once), a transform per mesh,
//! sides and an optional alpha mask, turned into what the sources need (the triangles on the GPU
//! for the stochastic depth map, a BVH for column rays: [`SceneResources`]). When meshes move,
//! [`EngineGeometry::set_transforms`] rebuilds both.
//!
//! The BVH is built on the CPU (`crate::bvh`, SAH with a bounded depth), so a rebuild costs what
//! a build costs (Crytek Sponza, 262k triangles: about a second on two cores); refitting is not
//! offered yet.

use crate::bvh::{gpu::GpuBvh, Bvh};
use crate::error::Error;
use crate::gpu::Gpu;
use crate::raster::gpu_scene::GpuScene;
use crate::scene::{AlphaMode, Material, Scene, Texture};
use crate::sources::SceneResources;
use crate::technique::Needs;
use glam::{Mat4, Vec2, Vec3};

/// One vertex attribute in an engine's vertex buffer: `format` at `offset` bytes into each
/// `stride`-byte vertex of `bytes` (little-endian).
#[derive(Clone, Copy, Debug)]
pub struct VertexAttribute<'a> {
    /// The vertex buffer's contents (e.g. [`EngineGeometry::buffer_bytes`]).
    pub bytes: &'a [u8],
    /// Bytes from the start of a vertex to this attribute.
    pub offset: usize,
    /// Bytes from one vertex to the next (at least the attribute's size).
    pub stride: usize,
    /// Positions: `Float32x3`, `Float32x4` (w ignored) or `Float16x4` (w ignored); uvs:
    /// `Float32x2` or `Float16x2`.
    pub format: wgpu::VertexFormat,
}

/// An index buffer as the engine has it: `Uint16` or `Uint32`, little-endian, three per
/// triangle (a triangle list).
#[derive(Clone, Copy, Debug)]
pub struct IndexData<'a> {
    /// The index buffer's contents.
    pub bytes: &'a [u8],
    /// `Uint16` or `Uint32`.
    pub format: wgpu::IndexFormat,
}

/// An alpha-tested material: the texel alpha under the uv, times nothing else, is compared
/// with `cutoff` (glTF `MASK`), nearest texel, repeat wrapping, exactly as our own scenes.
#[derive(Clone, Copy, Debug)]
pub struct AlphaMask<'a> {
    /// One texture coordinate per vertex ((0, 0) = the texture's top-left corner, as glTF).
    pub uvs: VertexAttribute<'a>,
    /// RGBA8 texels (alpha in the fourth byte), row-major, top row first.
    pub rgba8: &'a [u8],
    /// Texture width in texels.
    pub width: u32,
    /// Texture height in texels.
    pub height: u32,
    /// Texels with alpha (0..1) below this are cut away.
    pub cutoff: f32,
}

/// One mesh: its triangles in object space, where it is, and which faces count.
#[derive(Clone, Copy, Debug)]
pub struct EngineMesh<'a> {
    /// Object-space vertex positions.
    pub positions: VertexAttribute<'a>,
    /// `None`: every three vertices are a triangle.
    pub indices: Option<IndexData<'a>>,
    /// Object to world.
    pub transform: Mat4,
    /// Back faces count (see [`crate::scene::Sidedness`]); alpha-masked meshes keep them anyway.
    pub double_sided: bool,
    /// An alpha-tested material, or `None` for an opaque mesh.
    pub alpha_mask: Option<AlphaMask<'a>>,
}

/// The engine's meshes as the hidden-depth sources take them.
pub struct EngineGeometry {
    gpu: Gpu,
    scene: Scene,
    /// Object-space positions and each mesh's vertex range, for [`Self::set_transforms`].
    object_positions: Vec<Vec3>,
    mesh_vertices: Vec<std::ops::Range<usize>>,
    needs: Needs,
    gpu_scene: GpuScene,
    bvh: Option<GpuBvh>,
}

impl EngineGeometry {
    /// Reads `meshes` (errors name the mesh and the fix) and uploads what `needs` asks for
    /// (e.g. `settings.technique.needs()`): the triangles, and a BVH when `needs.bvh`.
    pub fn new(gpu: &Gpu, meshes: &[EngineMesh], needs: Needs) -> Result<Self, Error> {
        let mut scene = Scene {
            name: "engine geometry".into(),
            ..Default::default()
        };
        let mut object_positions = Vec::new();
        let mut mesh_vertices = Vec::new();
        for (m, mesh) in meshes.iter().enumerate() {
            let fail = |why: String| Error::Input(format!("EngineMesh {m}: {why}"));
            let positions = read_positions(&mesh.positions).map_err(fail)?;
            let base = scene.positions.len();
            let n = positions.len();
            let triangles = read_triangles(mesh.indices.as_ref(), n).map_err(fail)?;
            let material = scene.materials.len() as u32;
            let mut material_desc = Material {
                name: format!("mesh {m}"),
                double_sided: mesh.double_sided,
                ..Material::default()
            };
            let uvs = match &mesh.alpha_mask {
                Some(mask) => {
                    let uvs = read_uvs(&mask.uvs).map_err(fail)?;
                    if uvs.len() != n {
                        return Err(fail(format!(
                            "the alpha mask has {} uvs for {n} positions (give one per vertex)",
                            uvs.len()
                        )));
                    }
                    if mask.rgba8.len() as u64 != 4 * u64::from(mask.width) * u64::from(mask.height)
                        || mask.width == 0
                    {
                        return Err(fail(format!(
                            "the alpha mask's texture has {} bytes for {}x{} RGBA8 texels",
                            mask.rgba8.len(),
                            mask.width,
                            mask.height
                        )));
                    }
                    material_desc.alpha_mode = AlphaMode::Mask {
                        cutoff: mask.cutoff,
                    };
                    material_desc.base_color_texture = Some(scene.textures.len() as u32);
                    scene.textures.push(Texture {
                        name: format!("mesh {m} alpha"),
                        width: mask.width,
                        height: mask.height,
                        rgba8: mask.rgba8.to_vec(),
                    });
                    uvs
                }
                None => vec![Vec2::ZERO; n],
            };
            scene.materials.push(material_desc);
            scene.uvs.extend(uvs);
            scene.positions.extend(
                positions
                    .iter()
                    .map(|p| mesh.transform.transform_point3(*p)),
            );
            scene
                .triangles
                .extend(triangles.iter().map(|t| t.map(|i| i + base as u32)));
            scene
                .triangle_materials
                .extend(std::iter::repeat_n(material, triangles.len()));
            object_positions.extend(positions);
            mesh_vertices.push(base..base + n);
        }
        scene
            .validate()
            .map_err(|e| Error::Input(format!("the engine meshes are not usable geometry: {e}")))?;
        let (gpu_scene, bvh) = upload(gpu, &scene, needs)?;
        Ok(Self {
            gpu: gpu.clone(),
            scene,
            object_positions,
            mesh_vertices,
            needs,
            gpu_scene,
            bvh,
        })
    }

    /// Moves the meshes (one object-to-world transform per mesh, in the order given to
    /// [`Self::new`]) and rebuilds the GPU triangles and the BVH.
    pub fn set_transforms(&mut self, transforms: &[Mat4]) -> Result<(), Error> {
        if transforms.len() != self.mesh_vertices.len() {
            return Err(Error::Input(format!(
                "{} transforms for {} meshes: give one per mesh",
                transforms.len(),
                self.mesh_vertices.len()
            )));
        }
        if let Some(i) = transforms.iter().position(|t| !t.is_finite()) {
            return Err(Error::Input(format!("transform {i} is not finite")));
        }
        for (range, transform) in self.mesh_vertices.iter().zip(transforms) {
            for i in range.clone() {
                self.scene.positions[i] = transform.transform_point3(self.object_positions[i]);
            }
        }
        let (gpu_scene, bvh) = upload(&self.gpu, &self.scene, self.needs)?;
        self.gpu_scene = gpu_scene;
        self.bvh = bvh;
        Ok(())
    }

    /// What [`crate::AmbientOcclusion::new`] takes. After [`Self::set_transforms`], make the
    /// `AmbientOcclusion` again: it binds the buffers it was given.
    pub fn resources(&self) -> SceneResources<'_> {
        SceneResources {
            scene: Some(&self.gpu_scene),
            bvh: self.bvh.as_ref(),
        }
    }

    /// The contents of one of the engine's buffers (vertex or index), to describe with a
    /// [`VertexAttribute`] or [`IndexData`]. The buffer needs the `COPY_SRC` usage. Waits for the
    /// GPU.
    pub fn buffer_bytes(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, Error> {
        if !buffer.usage().contains(wgpu::BufferUsages::COPY_SRC) {
            return Err(Error::Input(format!(
                "the buffer to read geometry from lacks the COPY_SRC usage (it has {:?}): \
                 create it with BufferUsages::COPY_SRC, or pass the bytes you uploaded",
                buffer.usage()
            )));
        }
        Ok(crate::gpu::read_buffer_copy(gpu, buffer)?)
    }

    /// The world-space triangles as a [`Scene`] (for a CPU reference, or a check).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }
}

fn upload(gpu: &Gpu, scene: &Scene, needs: Needs) -> Result<(GpuScene, Option<GpuBvh>), Error> {
    let gpu_scene = GpuScene::new(&gpu.device, &gpu.queue, scene, &gpu.device.limits())?;
    let bvh = needs
        .bvh
        .then(|| GpuBvh::new(&gpu.device, &Bvh::build(scene), scene))
        .transpose()?;
    Ok((gpu_scene, bvh))
}

/// The `i`-th element's bytes of `a` (`size` of them), or an error naming the overrun.
fn element<'b>(a: &VertexAttribute<'b>, i: usize, size: usize) -> Result<&'b [u8], String> {
    let start = a.offset + i * a.stride;
    a.bytes.get(start..start + size).ok_or_else(|| {
        format!(
            "vertex {i} reads bytes {start}..{} of a {}-byte buffer",
            start + size,
            a.bytes.len()
        )
    })
}

/// How many elements `a` holds: as many whole `size`-byte elements as fit at its stride.
fn count(a: &VertexAttribute, size: usize) -> Result<usize, String> {
    if a.stride < size {
        return Err(format!(
            "stride {} is smaller than one {:?} ({size} bytes)",
            a.stride, a.format
        ));
    }
    if a.bytes.len() < a.offset + size {
        return Ok(0);
    }
    Ok((a.bytes.len() - a.offset - size) / a.stride + 1)
}

fn f32_at(b: &[u8], k: usize) -> f32 {
    f32::from_le_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]])
}

fn f16_at(b: &[u8], k: usize) -> f32 {
    half::f16::from_le_bytes([b[2 * k], b[2 * k + 1]]).to_f32()
}

fn read_positions(a: &VertexAttribute) -> Result<Vec<Vec3>, String> {
    use wgpu::VertexFormat as F;
    let size = match a.format {
        F::Float32x3 => 12,
        F::Float32x4 => 16,
        F::Float16x4 => 8,
        other => {
            return Err(format!(
                "positions in {other:?} are not supported: use Float32x3, Float32x4 or Float16x4"
            ))
        }
    };
    (0..count(a, size)?)
        .map(|i| {
            let b = element(a, i, size)?;
            let p = match a.format {
                F::Float16x4 => Vec3::new(f16_at(b, 0), f16_at(b, 1), f16_at(b, 2)),
                _ => Vec3::new(f32_at(b, 0), f32_at(b, 1), f32_at(b, 2)),
            };
            if p.is_finite() {
                Ok(p)
            } else {
                Err(format!("position {i} is not finite ({p})"))
            }
        })
        .collect()
}

fn read_uvs(a: &VertexAttribute) -> Result<Vec<Vec2>, String> {
    use wgpu::VertexFormat as F;
    let size = match a.format {
        F::Float32x2 => 8,
        F::Float16x2 => 4,
        other => {
            return Err(format!(
                "alpha-mask uvs in {other:?} are not supported: use Float32x2 or Float16x2"
            ))
        }
    };
    (0..count(a, size)?)
        .map(|i| {
            let b = element(a, i, size)?;
            Ok(match a.format {
                F::Float16x2 => Vec2::new(f16_at(b, 0), f16_at(b, 1)),
                _ => Vec2::new(f32_at(b, 0), f32_at(b, 1)),
            })
        })
        .collect()
}

fn read_triangles(indices: Option<&IndexData>, vertices: usize) -> Result<Vec<[u32; 3]>, String> {
    let flat: Vec<u32> = match indices {
        None => (0..vertices as u32).collect(),
        Some(IndexData { bytes, format }) => match format {
            wgpu::IndexFormat::Uint16 => bytes
                .chunks_exact(2)
                .map(|c| u32::from(u16::from_le_bytes([c[0], c[1]])))
                .collect(),
            wgpu::IndexFormat::Uint32 => bytes
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect(),
        },
    };
    if !flat.len().is_multiple_of(3) {
        return Err(format!(
            "{} indices is not a triangle list (a multiple of 3)",
            flat.len()
        ));
    }
    if let Some(bad) = flat.iter().find(|&&i| i as usize >= vertices) {
        return Err(format!(
            "index {bad} is out of range: the mesh has {vertices} vertices"
        ));
    }
    Ok(flat.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect())
}
