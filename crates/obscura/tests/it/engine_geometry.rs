//! `EngineGeometry`: the hidden-depth techniques over an engine's own vertex and index data give
//! the AO our renderer gives for the same triangles, whatever the layout (stride, offset, format,
//! 16- or 32-bit indices, transforms), follow moved meshes, and reject bad data by name.

use crate::common::*;
use glam::{Mat4, Vec3};
use obscura::reference::cpu_vao::GBufferImage;
use obscura::scene::Scene;
use obscura::{
    AmbientOcclusion, AoSettings, EngineGeometry, EngineMesh, FrameView, Gpu, IndexData, Renderer,
    Technique, VertexAttribute,
};

const W: u32 = 80;
const H: u32 = 60;
const BAND: u32 = 12;

fn rt_vao() -> AoSettings {
    technique_settings(Technique::RtVao, false)
}

/// Our renderer's frame of `scene` from `camera`: G-buffer, AO and view.
fn our_frame(
    gpu: &Gpu,
    scene: &Scene,
    camera: &obscura::scene::Camera,
) -> (GBufferImage, Vec<f32>, FrameView) {
    let mut r = Renderer::new(gpu, scene, &rt_vao(), W, H, BAND).unwrap();
    r.render(camera, None).unwrap();
    (
        r.read_gbuffer().unwrap(),
        r.read_ao().unwrap(),
        *r.view().unwrap(),
    )
}

fn texture(
    gpu: &Gpu,
    format: wgpu::TextureFormat,
    bytes: &[u8],
    texel: u32,
    g: &GBufferImage,
) -> wgpu::Texture {
    upload_texture(gpu, format, (g.width, g.height), bytes, texel)
}

/// `rt-vao` over `geometry`, the engine's camera given as matrices, the G-buffer `g` as its
/// depth and normals.
fn engine_ao(gpu: &Gpu, geometry: &EngineGeometry, view: &FrameView, g: &GBufferImage) -> Vec<f32> {
    let screen = view.screen();
    let camera = FrameView::from_matrices(view.view_matrix(), screen, view.near).unwrap();
    assert!(
        camera.view_matrix().abs_diff_eq(view.view_matrix(), 1e-5),
        "from_matrices keeps the view"
    );
    assert_eq!(camera.tan_half_fov, view.tan_half_fov);
    let ao = AmbientOcclusion::new(gpu, &rt_vao(), screen, geometry.resources()).unwrap();
    ao.set_camera(&gpu.queue, &camera);
    let depth = texture(
        gpu,
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(&g.depth),
        4,
        g,
    );
    let normals: Vec<[f32; 4]> = g.normals.iter().map(|n| n.extend(0.0).to_array()).collect();
    let normals = texture(
        gpu,
        wgpu::TextureFormat::Rgba32Float,
        bytemuck::cast_slice(&normals),
        16,
        g,
    );
    encode_and_submit(gpu, &ao, &depth, &normals).unwrap();
    ao.read_output().unwrap()
}

fn assert_same_ao(a: &[f32], b: &[f32], what: &str) {
    let worst = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f32::max);
    assert!(worst < 1e-4, "{what}: AO differs by up to {worst}");
}

fn f32_bytes(values: impl IntoIterator<Item = f32>) -> Vec<u8> {
    values.into_iter().flat_map(f32::to_le_bytes).collect()
}

#[test]
fn a_builtin_scene_through_engine_buffers_gives_our_ao() {
    let gpu = gpu();
    let scene = obscura::scene::builtin("colonnade").unwrap();
    let camera = scene.cameras[0].camera;
    let (g, ours, view) = our_frame(&gpu, &scene, &camera);
    // One mesh per material (its sides), 32-bit indices into one shared position buffer.
    let positions = f32_bytes(scene.positions.iter().flat_map(|p| p.to_array()));
    let per_material: Vec<Vec<u8>> = (0..scene.materials.len() as u32)
        .map(|m| {
            scene
                .triangles
                .iter()
                .zip(&scene.triangle_materials)
                .filter(|(_, &tm)| tm == m)
                .flat_map(|(t, _)| t.iter().flat_map(|i| i.to_le_bytes()))
                .collect()
        })
        .collect();
    let meshes: Vec<EngineMesh> = per_material
        .iter()
        .zip(&scene.materials)
        .filter(|(indices, _)| !indices.is_empty())
        .map(|(indices, material)| EngineMesh {
            positions: VertexAttribute {
                bytes: &positions,
                offset: 0,
                stride: 12,
                format: wgpu::VertexFormat::Float32x3,
            },
            indices: Some(IndexData {
                bytes: indices,
                format: wgpu::IndexFormat::Uint32,
            }),
            transform: Mat4::IDENTITY,
            double_sided: material.double_sided,
            alpha_mask: None,
        })
        .collect();
    let geometry = EngineGeometry::new(&gpu, &meshes, Technique::RtVao.needs()).unwrap();
    assert_eq!(geometry.scene().triangle_count(), scene.triangle_count());
    assert_same_ao(&engine_ao(&gpu, &geometry, &view, &g), &ours, "colonnade");
}

/// A 6 × 6 m floor and a 4 × 2 m wall, in the engine's own layouts.
struct Layouts {
    /// Floor: interleaved position (Float32x4) + normal + uv, 40-byte stride, 16-bit indices.
    floor: Vec<u8>,
    floor_indices: Vec<u8>,
    /// Wall: Float16x4 positions after a 4-byte header, no indices (a triangle list).
    wall: Vec<u8>,
}

fn layouts() -> Layouts {
    let corners = [
        [-3.0, 0.0, 3.0],
        [3.0, 0.0, 3.0],
        [3.0, 0.0, -3.0],
        [-3.0, 0.0, -3.0f32],
    ];
    let mut floor = Vec::new();
    for [x, y, z] in corners {
        floor.extend(f32_bytes([x, y, z, 1.0, 0.0, 1.0, 0.0, 0.5, 0.5, 7.0]));
    }
    let floor_indices = [0u16, 1, 2, 0, 2, 3]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    // The wall in object space: 4 m wide, 2 m high, facing +z, at the origin.
    let w = [
        [-2.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [-2.0, 2.0, 0.0f32],
    ];
    let mut wall = vec![0xAB; 4];
    for i in [0, 1, 2, 0, 2, 3] {
        let [x, y, z] = w[i];
        for v in [x, y, z, 1.0] {
            wall.extend(half::f16::from_f32(v).to_le_bytes());
        }
    }
    Layouts {
        floor,
        floor_indices,
        wall,
    }
}

fn meshes<'a>(l: &'a Layouts, wall_at: Mat4) -> [EngineMesh<'a>; 2] {
    [
        EngineMesh {
            positions: VertexAttribute {
                bytes: &l.floor,
                offset: 0,
                stride: 40,
                format: wgpu::VertexFormat::Float32x4,
            },
            indices: Some(IndexData {
                bytes: &l.floor_indices,
                format: wgpu::IndexFormat::Uint16,
            }),
            transform: Mat4::IDENTITY,
            double_sided: false,
            alpha_mask: None,
        },
        EngineMesh {
            positions: VertexAttribute {
                bytes: &l.wall,
                offset: 4,
                stride: 8,
                format: wgpu::VertexFormat::Float16x4,
            },
            indices: None,
            transform: wall_at,
            double_sided: false,
            alpha_mask: None,
        },
    ]
}

#[test]
fn layouts_transforms_and_moved_meshes() {
    let gpu = gpu();
    let l = layouts();
    let near_wall = Mat4::from_translation(Vec3::new(0.0, 0.0, -1.0));
    let mut geometry =
        EngineGeometry::new(&gpu, &meshes(&l, near_wall), Technique::RtVao.needs()).unwrap();
    let scene = geometry.scene().clone();
    assert_eq!(scene.triangle_count(), 4);
    // The wall's corners, moved by its transform.
    assert!(scene.positions.contains(&Vec3::new(2.0, 2.0, -1.0)));
    assert!(scene.positions.contains(&Vec3::new(-3.0, 0.0, -3.0)));
    // Looking at the foot of the wall: our renderer on the same triangles agrees.
    let camera = camera(Vec3::new(0.0, 1.5, 2.5), Vec3::new(0.0, 0.2, -0.8), 60.0);
    let (g, ours, view) = our_frame(&gpu, &scene, &camera);
    assert_same_ao(
        &engine_ao(&gpu, &geometry, &view, &g),
        &ours,
        "wall at z = -1",
    );
    assert!(ours.iter().any(|a| *a < 0.8), "the wall's foot is occluded");

    // The wall moves 20 m away: the same answer as our renderer on the moved triangles.
    let far = Mat4::from_translation(Vec3::new(0.0, 0.0, -20.0));
    geometry.set_transforms(&[Mat4::IDENTITY, far]).unwrap();
    assert!(geometry
        .scene()
        .positions
        .contains(&Vec3::new(2.0, 2.0, -20.0)));
    let (g, moved, view) = our_frame(&gpu, geometry.scene(), &camera);
    assert_same_ao(
        &engine_ao(&gpu, &geometry, &view, &g),
        &moved,
        "wall at z = -20",
    );
    assert!(moved != ours, "moving the wall changes the AO");

    let err = geometry.set_transforms(&[far]).unwrap_err().to_string();
    assert!(err.contains("1 transforms for 2 meshes"), "{err}");
}

#[test]
fn engine_buffers_are_read_back_and_bad_data_named() {
    let gpu = gpu();
    let l = layouts();
    // From a wgpu::Buffer with COPY_SRC: the bytes come back.
    use wgpu::util::DeviceExt;
    let buffer = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("engine vertices"),
            contents: &l.floor,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_SRC,
        });
    assert_eq!(
        EngineGeometry::buffer_bytes(&gpu, &buffer).unwrap(),
        l.floor
    );
    let vertex_only = gpu
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("engine vertices"),
            contents: &l.floor,
            usage: wgpu::BufferUsages::VERTEX,
        });
    let err = EngineGeometry::buffer_bytes(&gpu, &vertex_only)
        .unwrap_err()
        .to_string();
    assert!(err.contains("COPY_SRC"), "{err}");

    let needs = Technique::RtVao.needs();
    let fails = |meshes: &[EngineMesh], needle: &str| {
        let err = EngineGeometry::new(&gpu, meshes, needs)
            .err()
            .expect(needle)
            .to_string();
        assert!(err.contains(needle), "'{needle}' not in: {err}");
    };
    let [floor, wall] = meshes(&l, Mat4::IDENTITY);
    let mut m = floor;
    m.positions.stride = 8;
    fails(&[m], "stride 8 is smaller");
    let mut m = floor;
    m.positions.format = wgpu::VertexFormat::Uint32x3;
    fails(&[wall, m], "EngineMesh 1: positions in Uint32x3");
    let bad_indices = [0u16, 1, 9]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect::<Vec<u8>>();
    let mut m = floor;
    m.indices = Some(IndexData {
        bytes: &bad_indices,
        format: wgpu::IndexFormat::Uint16,
    });
    fails(&[m], "index 9 is out of range");
    let two = [0u16, 1]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect::<Vec<u8>>();
    m.indices = Some(IndexData {
        bytes: &two,
        format: wgpu::IndexFormat::Uint16,
    });
    fails(&[m], "not a triangle list");
    let nan = f32_bytes([f32::NAN, 0.0, 0.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0]);
    let m = EngineMesh {
        positions: VertexAttribute {
            bytes: &nan,
            offset: 0,
            stride: 12,
            format: wgpu::VertexFormat::Float32x3,
        },
        indices: None,
        ..floor
    };
    fails(&[m], "position 0 is not finite");
    fails(&[], "no triangles");
}
