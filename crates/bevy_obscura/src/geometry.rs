//! The scene's meshes for the hidden-depth rows: gathered in the main world from every visible
//! `Mesh3d` (its triangles, `GlobalTransform`, sidedness and alpha mask), handed to the render
//! world, and there turned into obscura's `EngineGeometry`, made again when meshes appear,
//! vanish or change and moved when only transforms change.

use crate::ObscuraAo;
use bevy::app::{App, PostUpdate};
use bevy::asset::{AssetId, Assets};
use bevy::camera::visibility::InheritedVisibility;
use bevy::ecs::prelude::*;
use bevy::image::Image;
use bevy::log::warn;
use bevy::mesh::{Indices, Mesh, Mesh3d, PrimitiveTopology, VertexAttributeValues};
use bevy::pbr::{MeshMaterial3d, StandardMaterial};
use bevy::render::extract_resource::{ExtractResource, ExtractResourcePlugin};
use bevy::transform::components::GlobalTransform;
use bevy::transform::TransformSystems;
use obscura::technique::Needs;
use obscura::{AlphaMask, EngineGeometry, EngineMesh, Gpu, IndexData, VertexAttribute};
use std::sync::Arc;

/// Keeps a mesh entity out of obscura's hidden-depth rows (a sky dome, a gizmo, glass): they
/// trace and rasterise every other visible `Mesh3d`, on screen or not.
#[derive(Component, Clone, Copy, Debug, Default)]
pub struct ObscuraIgnore;

pub(crate) fn build(app: &mut App) {
    app.init_resource::<GatheredGeometry>()
        .add_plugins(ExtractResourcePlugin::<GatheredGeometry>::default())
        .add_systems(PostUpdate, gather.after(TransformSystems::Propagate));
}

/// One mesh as obscura reads it: object-space triangles.
pub(crate) struct MeshTriangles {
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    double_sided: bool,
    mask: Option<MaskTexels>,
}

/// An alpha-tested material's texture and uvs.
struct MaskTexels {
    uvs: Vec<[f32; 2]>,
    rgba8: Vec<u8>,
    width: u32,
    height: u32,
    cutoff: f32,
}

/// What the main world saw this frame, for the render world.
#[derive(Resource, Clone, Default, ExtractResource)]
pub(crate) struct GatheredGeometry {
    /// Whether any camera's row reads geometry; nothing is gathered otherwise.
    pub wanted: bool,
    /// Changes whenever the meshes do (one added, removed, or its asset or material changed).
    pub layout: u64,
    pub meshes: Arc<Vec<MeshTriangles>>,
    /// Changes whenever a transform does.
    pub placement: u64,
    pub transforms: Arc<Vec<glam::Mat4>>,
}

/// Who a mesh is, for noticing change: the entity, its mesh asset and material, and whether the
/// asset had loaded.
type LayoutKey = Vec<(
    Entity,
    AssetId<Mesh>,
    Option<AssetId<StandardMaterial>>,
    bool,
)>;

#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn gather(
    cameras: Query<&ObscuraAo>,
    meshes: Query<
        (
            Entity,
            &Mesh3d,
            &GlobalTransform,
            &InheritedVisibility,
            Option<&MeshMaterial3d<StandardMaterial>>,
        ),
        Without<ObscuraIgnore>,
    >,
    mesh_assets: Res<Assets<Mesh>>,
    materials: Res<Assets<StandardMaterial>>,
    images: Res<Assets<Image>>,
    mut mesh_events: MessageReader<bevy::asset::AssetEvent<Mesh>>,
    mut gathered: ResMut<GatheredGeometry>,
    mut last_layout: Local<LayoutKey>,
    mut kept: Local<Vec<usize>>,
    mut warned: Local<bool>,
) {
    let wanted = cameras
        .iter()
        .any(|c| reads_geometry(c.resolved().technique.needs()));
    let assets_changed = mesh_events.read().count() > 0;
    if !wanted {
        if gathered.wanted {
            *gathered = GatheredGeometry {
                layout: gathered.layout + 1,
                ..Default::default()
            };
            last_layout.clear();
        }
        return;
    }
    let mut visible: Vec<_> = meshes.iter().filter(|m| m.3.get()).collect();
    visible.sort_by_key(|m| m.0);
    let layout: LayoutKey = visible
        .iter()
        .map(|(e, mesh, _, _, material)| {
            let id = mesh.id();
            (*e, id, material.map(|m| m.id()), mesh_assets.contains(id))
        })
        .collect();
    if !gathered.wanted || layout != *last_layout || assets_changed {
        let mut list = Vec::new();
        kept.clear();
        for (i, (_, mesh, _, _, material)) in visible.iter().enumerate() {
            let Some(mesh) = mesh_assets.get(mesh.id()) else {
                continue;
            };
            let material = material.and_then(|m| materials.get(m.id()));
            match triangles(mesh, material, &images) {
                Ok(Some(t)) => {
                    list.push(t);
                    kept.push(i);
                }
                Ok(None) => {}
                Err(why) => {
                    if !*warned {
                        warn!("obscura: a mesh is left out of the hidden-depth rows: {why}");
                        *warned = true;
                    }
                }
            }
        }
        gathered.wanted = true;
        gathered.layout += 1;
        gathered.meshes = Arc::new(list);
        gathered.transforms = Arc::new(Vec::new());
        *last_layout = layout;
    }
    // `kept`: which of the sorted visible meshes are in the layout (the rest have no triangles
    // yet or cannot be read), so that transforms line up with meshes.
    let transforms: Vec<glam::Mat4> = kept
        .iter()
        .map(|&i| crate::convert::mat4(visible[i].2.to_matrix()))
        .collect();
    if *gathered.transforms != transforms {
        gathered.placement += 1;
        gathered.transforms = Arc::new(transforms);
    }
}

/// Whether a row with these needs reads the scene's meshes.
pub(crate) fn reads_geometry(needs: Needs) -> bool {
    needs.triangles || needs.bvh || needs.second_layer || needs.stochastic_depth_map
}

/// A mesh's triangles, `None` for one that draws no triangles (lines, points).
fn triangles(
    mesh: &Mesh,
    material: Option<&StandardMaterial>,
    images: &Assets<Image>,
) -> Result<Option<MeshTriangles>, String> {
    if mesh.primitive_topology() != PrimitiveTopology::TriangleList {
        return Ok(None);
    }
    let positions = match mesh.attribute(Mesh::ATTRIBUTE_POSITION) {
        Some(VertexAttributeValues::Float32x3(p)) => p.clone(),
        Some(other) => {
            return Err(format!(
                "its positions are {:?}, not Float32x3",
                other.enum_variant_name()
            ))
        }
        None => return Err("it has no positions (or its data lives only on the GPU)".into()),
    };
    let indices = match mesh.indices() {
        Some(Indices::U16(i)) => i.iter().map(|&i| u32::from(i)).collect(),
        Some(Indices::U32(i)) => i.clone(),
        None => (0..positions.len() as u32).collect(),
    };
    // Faces count from both sides unless the material culls back faces, as Bevy draws them.
    let double_sided = material.is_none_or(|m| m.cull_mode.is_none());
    let mask = material.and_then(|m| alpha_mask(mesh, m, images));
    Ok(Some(MeshTriangles {
        positions,
        indices,
        double_sided,
        mask,
    }))
}

/// An alpha-masked material's texels, where its texture is RGBA8 and still in main memory.
fn alpha_mask(
    mesh: &Mesh,
    material: &StandardMaterial,
    images: &Assets<Image>,
) -> Option<MaskTexels> {
    let bevy::prelude::AlphaMode::Mask(cutoff) = material.alpha_mode else {
        return None;
    };
    let image = images.get(material.base_color_texture.as_ref()?)?;
    let rgba8 = matches!(
        image.texture_descriptor.format,
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb
    );
    let data = image.data.as_ref().filter(|_| rgba8)?;
    let Some(VertexAttributeValues::Float32x2(uvs)) = mesh.attribute(Mesh::ATTRIBUTE_UV_0) else {
        return None;
    };
    Some(MaskTexels {
        uvs: uvs.clone(),
        rgba8: data.clone(),
        width: image.width(),
        height: image.height(),
        cutoff,
    })
}

/// The render world's `EngineGeometry`, made from the gathered meshes.
#[derive(Default)]
pub(crate) struct RenderGeometry {
    layout: u64,
    placement: u64,
    needs: Needs,
    geometry: Option<EngineGeometry>,
}

impl RenderGeometry {
    /// The geometry for `gathered`, made or moved as needed for a row that needs `needs`.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        gathered: &GatheredGeometry,
        needs: Needs,
    ) -> Result<&EngineGeometry, String> {
        let union = Needs {
            triangles: self.needs.triangles || needs.triangles,
            bvh: self.needs.bvh || needs.bvh,
            second_layer: self.needs.second_layer || needs.second_layer,
            stochastic_depth_map: self.needs.stochastic_depth_map || needs.stochastic_depth_map,
        };
        let stale =
            self.geometry.is_none() || self.layout != gathered.layout || union != self.needs;
        if stale {
            self.geometry = None;
            let arrays: Vec<EngineMesh> = gathered
                .meshes
                .iter()
                .zip(gathered.transforms.iter())
                .map(|(m, t)| engine_mesh(m, *t))
                .collect();
            let geometry = EngineGeometry::new(gpu, &arrays, union).map_err(|e| e.to_string())?;
            self.geometry = Some(geometry);
            self.layout = gathered.layout;
            self.placement = gathered.placement;
            self.needs = union;
        } else if self.placement != gathered.placement {
            let geometry = self.geometry.as_mut().expect("made above");
            geometry
                .set_transforms(&gathered.transforms)
                .map_err(|e| e.to_string())?;
            self.placement = gathered.placement;
        }
        Ok(self.geometry.as_ref().expect("made above"))
    }

    /// What `AmbientOcclusion::new` takes (empty before the first `update`).
    pub fn resources(&self) -> obscura::SceneResources<'_> {
        self.geometry
            .as_ref()
            .map(EngineGeometry::resources)
            .unwrap_or_default()
    }

    /// Which layout and placement the geometry shows (a view's row is made again when it moves).
    pub fn version(&self) -> (u64, u64) {
        (self.layout, self.placement)
    }
}

fn engine_mesh(m: &MeshTriangles, transform: glam::Mat4) -> EngineMesh<'_> {
    EngineMesh {
        positions: VertexAttribute {
            bytes: bytemuck::cast_slice(&m.positions),
            offset: 0,
            stride: 12,
            format: wgpu::VertexFormat::Float32x3,
        },
        indices: Some(IndexData {
            bytes: bytemuck::cast_slice(&m.indices),
            format: wgpu::IndexFormat::Uint32,
        }),
        transform,
        double_sided: m.double_sided,
        alpha_mask: m.mask.as_ref().map(|mask| AlphaMask {
            uvs: VertexAttribute {
                bytes: bytemuck::cast_slice(&mask.uvs),
                offset: 0,
                stride: 8,
                format: wgpu::VertexFormat::Float32x2,
            },
            rgba8: &mask.rgba8,
            width: mask.width,
            height: mask.height,
            cutoff: mask.cutoff,
        }),
    }
}
