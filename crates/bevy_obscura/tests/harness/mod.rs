//! A headless Bevy app on the test machine's adapter (lavapipe in CI), pumped frame by frame,
//! with obscura's built-in scenes turned into Bevy meshes and the render world in reach.

use bevy::app::PluginsState;
use bevy::asset::RenderAssetUsages;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::tonemapping::Tonemapping;
use bevy::image::Image;
use bevy::light::GlobalAmbientLight;
use bevy::mesh::Mesh;
use bevy::prelude::*;
use bevy::render::diagnostic::RenderDiagnosticsPlugin;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::renderer::RenderDevice;
use bevy::render::settings::{Backends, RenderCreation, WgpuSettings};
use bevy::render::sync_world::RenderEntity;
use bevy::render::{pipelined_rendering::PipelinedRenderingPlugin, RenderApp, RenderPlugin};
use bevy::window::{ExitCondition, WindowPlugin};
use bevy::winit::WinitPlugin;
use bevy_obscura::{read_target_rgba8, read_view_ao, ObscuraPlugin, ObscuraViewReport, ViewAo};
use obscura::scene::Scene;
use std::sync::Mutex;

/// One Bevy app at a time: each holds a lavapipe device, and the tests run on two cores.
pub static ONE_APP: Mutex<()> = Mutex::new(());

pub struct Harness {
    pub app: App,
}

impl Harness {
    /// An app with Bevy's default plugins (no window, no winit, no pipelined rendering) and
    /// obscura's plugin, a black clear colour and only ambient light, so that the lit frame is
    /// albedo × ambient × AO.
    pub fn new() -> Self {
        obscura::gpu::quiet_headless_vulkan();
        let mut app = App::new();
        let plugins = DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                render_creation: RenderCreation::Automatic(Box::new(WgpuSettings {
                    backends: Some(Backends::VULKAN),
                    ..default()
                })),
                ..default()
            })
            .disable::<WinitPlugin>()
            .disable::<PipelinedRenderingPlugin>();
        // Bevy's log goes to stderr with BEVY_OBSCURA_TEST_LOG set (its subscriber is global:
        // one per process, so off by default).
        if std::env::var_os("BEVY_OBSCURA_TEST_LOG").is_some() {
            app.add_plugins(plugins);
        } else {
            app.add_plugins(plugins.disable::<bevy::log::LogPlugin>());
        }
        app.add_plugins((ObscuraPlugin, RenderDiagnosticsPlugin))
            .insert_resource(ClearColor(Color::BLACK))
            .insert_resource(GlobalAmbientLight {
                color: Color::WHITE,
                brightness: 1000.0,
                ..default()
            });
        while app.plugins_state() == PluginsState::Adding {
            bevy::tasks::tick_global_task_pools_on_main_thread();
        }
        app.finish();
        app.cleanup();
        Self { app }
    }

    /// The scene's triangles as white meshes (`bevy_obscura::scene_meshes`), back faces culled
    /// where obscura counts only front faces.
    pub fn spawn_scene(&mut self, scene: &Scene) {
        for (mesh, double_sided) in bevy_obscura::scene_meshes(scene) {
            self.spawn_mesh_sided(mesh, Transform::IDENTITY, double_sided);
        }
    }

    /// A white, double-sided mesh.
    pub fn spawn_mesh(&mut self, mesh: Mesh, transform: Transform) -> Entity {
        self.spawn_mesh_sided(mesh, transform, true)
    }

    /// A white mesh, its back faces culled unless `double_sided`.
    pub fn spawn_mesh_sided(
        &mut self,
        mesh: Mesh,
        transform: Transform,
        double_sided: bool,
    ) -> Entity {
        let world = self.app.world_mut();
        let mesh = world.resource_mut::<Assets<Mesh>>().add(mesh);
        let material = world
            .resource_mut::<Assets<StandardMaterial>>()
            .add(StandardMaterial {
                base_color: Color::WHITE,
                perceptual_roughness: 1.0,
                reflectance: 0.0,
                double_sided,
                cull_mode: (!double_sided).then_some(bevy::render::render_resource::Face::Back),
                ..default()
            });
        world
            .spawn((Mesh3d(mesh), MeshMaterial3d(material), transform))
            .id()
    }

    /// A camera at obscura's `camera`, rendering into a new `width × height` image, with the
    /// given extra components (`ObscuraAo`, `ScreenSpaceAmbientOcclusion`, or none).
    pub fn spawn_camera(
        &mut self,
        camera: &obscura::scene::Camera,
        near: f32,
        (width, height): (u32, u32),
        extra: impl Bundle,
    ) -> (Entity, Handle<Image>) {
        let mut image = Image::new_uninit(
            Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::RENDER_WORLD,
        );
        image.texture_descriptor.usage |=
            TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
        let world = self.app.world_mut();
        let image = world.resource_mut::<Assets<Image>>().add(image);
        let eye = Vec3::from_array(camera.eye.to_array());
        let target = Vec3::from_array(camera.target.to_array());
        let up = Vec3::from_array(camera.up.to_array());
        let entity = world
            .spawn((
                Camera3d::default(),
                RenderTarget::Image(image.clone().into()),
                Projection::Perspective(PerspectiveProjection {
                    fov: camera.fov_y_deg.to_radians(),
                    near,
                    aspect_ratio: width as f32 / height as f32,
                    ..default()
                }),
                Transform::from_translation(eye).looking_at(target, up),
                Msaa::Off,
                Tonemapping::None,
                extra,
            ))
            .id();
        (entity, image)
    }

    /// Runs `n` frames, waiting for the GPU after each.
    pub fn frames(&mut self, n: u32) {
        for _ in 0..n {
            self.app.update();
            let device = self.app.world().resource::<RenderDevice>();
            device
                .wgpu_device()
                .poll(wgpu::PollType::wait_indefinitely())
                .expect("the GPU finished the frame");
        }
    }

    /// The render world's entity for a main-world camera.
    pub fn render_entity(&self, camera: Entity) -> Entity {
        self.app
            .world()
            .get::<RenderEntity>(camera)
            .expect("the camera is synced to the render world")
            .id()
    }

    pub fn render_world(&self) -> &World {
        self.app.sub_app(RenderApp).world()
    }

    /// The AO the camera's lighting read in the last frame.
    pub fn view_ao(&self, camera: Entity) -> ViewAo {
        read_view_ao(self.render_world(), self.render_entity(camera)).expect("the view's AO")
    }

    /// The camera's lit frame, RGBA8 (sRGB), as rendered in the last frame.
    pub fn lit_frame(&self, image: &Handle<Image>) -> Vec<[u8; 4]> {
        let (_, _, bytes) = read_target_rgba8(self.render_world(), image).expect("the frame");
        bytes
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect()
    }

    /// What the plugin reported on the camera in the last frame.
    pub fn report(&self, camera: Entity) -> ObscuraViewReport {
        self.render_world()
            .get::<ObscuraViewReport>(self.render_entity(camera))
            .cloned()
            .expect("the plugin reports on the camera")
    }
}

/// Mean absolute difference.
pub fn mae(a: &[f32], b: &[f32]) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum::<f32>() / a.len() as f32
}
