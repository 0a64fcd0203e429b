//! The render world: per camera, obscura's `EngineInput` and `AmbientOcclusion` made (again when
//! the settings, the projection, the size or the geometry change), run between Bevy's prepass
//! and its main pass, and written into the SSAO texture Bevy's PBR shaders read.
//!
//! Order within a frame:
//! 1. `prepare` (`RenderSystems::PrepareResources`): make or keep each camera's row, give it
//!    the camera.
//! 2. `hand_over_ao` (`RenderSystems::PrepareBindGroups`, before Bevy's mesh view bind groups
//!    are made): puts the row's output texture in the place of the SSAO texture Bevy allocated,
//!    so Bevy's lighting reads obscura's AO where it is written (no copy).
//! 3. `skip_bevy_ssao` (`RenderSystems::Render`, before Bevy's render system): takes Bevy's SSAO
//!    bind groups off each camera whose row is ready, so Bevy's `ssao` system, which needs them,
//!    passes that camera over.
//! 4. `encode` (the `Core3d` schedule, after the prepass, before the main pass): the row's
//!    passes.

use crate::convert::mat4;
use crate::geometry::{reads_geometry, GatheredGeometry, RenderGeometry};
use crate::ExtractedObscuraAo;
use bevy::app::App;
use bevy::core_pipeline::prepass::ViewPrepassTextures;
use bevy::core_pipeline::schedule::{Core3d, Core3dSystems};
use bevy::ecs::prelude::*;
use bevy::log::error;
use bevy::pbr::{
    prepare_mesh_view_bind_groups, ScreenSpaceAmbientOcclusionResources, SsaoBindGroups,
};
use bevy::render::camera::ExtractedCamera;
use bevy::render::diagnostic::RecordDiagnostics;
use bevy::render::renderer::{
    render_system, RenderAdapter, RenderContext, RenderDevice, RenderQueue, ViewQuery,
};
use bevy::render::texture::CachedTexture;
use bevy::render::view::{ExtractedView, Msaa};
use bevy::render::{Render, RenderApp, RenderSystems};
use obscura::settings::AoSettings;
use obscura::{
    AmbientOcclusion, EngineFrame, EngineInput, EngineNormals, FrameView, Gpu, NormalEncoding,
    ScreenGeometry,
};
use std::collections::HashMap;

pub(crate) fn finish(app: &mut App) {
    let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
        return;
    };
    render_app
        .init_resource::<Views>()
        .add_systems(Render, prepare.in_set(RenderSystems::PrepareResources))
        .add_systems(
            Render,
            hand_over_ao
                .in_set(RenderSystems::PrepareBindGroups)
                .before(prepare_mesh_view_bind_groups),
        )
        .add_systems(
            Render,
            skip_bevy_ssao
                .in_set(RenderSystems::Render)
                .before(render_system),
        )
        .add_systems(
            Core3d,
            encode
                .after(Core3dSystems::Prepass)
                .before(Core3dSystems::MainPass),
        );
}

/// What one camera ran last frame, in the render world (read it from
/// `app.sub_app(RenderApp).world()`, as the tests do).
#[derive(Component, Clone, Debug, Default)]
pub struct ObscuraViewReport {
    /// The settings the row was made with.
    pub settings: Option<AoSettings>,
    /// Why the row could not be made or run, if it could not: Bevy's SSAO ran instead, except on
    /// a camera with MSAA, where neither runs.
    pub error: Option<String>,
}

/// Every camera's row, and what they share.
#[derive(Resource, Default)]
pub struct Views {
    gpu: Option<Gpu>,
    geometry: RenderGeometry,
    rows: HashMap<Entity, Row>,
}

impl Views {
    /// obscura's handle on Bevy's device (for tests that read obscura's textures back).
    pub fn gpu(&self) -> Option<&Gpu> {
        self.gpu.as_ref()
    }

    /// A camera's AO as obscura wrote it (R32Float, the view's size), if its row ran.
    pub fn output(&self, view: Entity) -> Option<&wgpu::Texture> {
        match &self.rows.get(&view)?.made {
            Ok(made) => Some(made.ao.output()),
            Err(_) => None,
        }
    }
}

/// One camera's row: what it was made for, and the result.
struct Row {
    key: RowKey,
    made: Result<Made, String>,
    /// Set by `prepare` when the view was seen this frame.
    seen: bool,
}

#[derive(PartialEq)]
struct RowKey {
    settings: AoSettings,
    projection: glam::Mat4,
    size: (u32, u32),
    /// The camera's MSAA sample count (only 1 can run).
    samples: u32,
    /// The geometry's (layout, placement), for the rows that read it.
    geometry: Option<(u64, u64)>,
}

struct Made {
    input: EngineInput,
    ao: AmbientOcclusion,
    /// `ao`'s output as Bevy's lighting binds it (its sample type is unfilterable float, so
    /// obscura's R32Float fits as it is).
    for_bevy: CachedTexture,
    projection: glam::Mat4,
    view_from_world: glam::Mat4,
}

#[allow(clippy::too_many_arguments)]
fn prepare(
    mut commands: Commands,
    mut views: ResMut<Views>,
    adapter: Res<RenderAdapter>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    gathered: Option<Res<GatheredGeometry>>,
    cameras: Query<(
        Entity,
        &ExtractedObscuraAo,
        &ExtractedView,
        &ExtractedCamera,
        Option<&Msaa>,
    )>,
) {
    let views = &mut *views;
    let gpu = views
        .gpu
        .get_or_insert_with(|| crate::readback::sharing(&adapter, &device, &queue))
        .clone();
    for row in views.rows.values_mut() {
        row.seen = false;
    }
    for (entity, ao, view, camera, msaa) in &cameras {
        let Some(size) = camera.physical_viewport_size else {
            continue;
        };
        let settings = ao.settings;
        let projection = mat4(view.clip_from_view);
        let view_from_world = mat4(view.world_from_view.to_matrix().inverse());
        let needs = settings.technique.needs();
        let mut geometry_error = None;
        let geometry = if reads_geometry(needs) {
            match gathered.as_deref() {
                Some(gathered) if gathered.wanted => {
                    match views.geometry.update(&gpu, gathered, needs) {
                        Ok(_) => Some(views.geometry.version()),
                        Err(e) => {
                            geometry_error = Some(format!("the scene's meshes: {e}"));
                            None
                        }
                    }
                }
                _ => None,
            }
        } else {
            None
        };
        let key = RowKey {
            settings,
            projection,
            size: (size.x, size.y),
            samples: msaa.map_or(1, Msaa::samples),
            geometry,
        };
        let row = views.rows.get(&entity);
        if row.is_none_or(|r| r.key != key) {
            let made = match geometry_error {
                // As Bevy's own SSAO: its prepass is multisampled otherwise.
                _ if key.samples != 1 => Err(format!(
                    "ObscuraAo needs Msaa::Off on its camera, as Bevy's SSAO does (this one has \
                     {} samples): add Msaa::Off to the camera",
                    key.samples
                )),
                Some(e) => Err(e),
                None => make(&gpu, &key, &views.geometry),
            };
            if let Err(e) = &made {
                let instead = if key.samples == 1 {
                    "Bevy's SSAO runs instead"
                } else {
                    "no AO runs (Bevy's SSAO needs Msaa::Off too)"
                };
                error!("obscura: camera {entity}: {e}; {instead}");
            }
            views.rows.insert(
                entity,
                Row {
                    key,
                    made,
                    seen: true,
                },
            );
        }
        let row = views.rows.get_mut(&entity).expect("inserted above");
        row.seen = true;
        if let Ok(made) = &mut row.made {
            made.view_from_world = view_from_world;
            // Orthographic views have no camera position; their (screen-space) rows need none.
            if let Ok(frame_view) =
                FrameView::from_matrices(view_from_world, made.input.screen(), near(projection))
            {
                made.ao.set_camera(&gpu.queue, &frame_view);
            }
        }
        commands.entity(entity).insert(ObscuraViewReport {
            settings: Some(settings),
            error: row.made.as_ref().err().cloned(),
        });
    }
    views.rows.retain(|_, row| row.seen);
}

/// The near plane of a projection (Bevy's perspective: infinite reversed-Z, `near` at [3][2]).
fn near(projection: glam::Mat4) -> f32 {
    projection.w_axis.z.abs().max(1e-6)
}

/// Makes a camera's row, with obscura's set-up errors caught by an error scope (they must not
/// reach Bevy's device-error handler, which would start its render recovery).
fn make(gpu: &Gpu, key: &RowKey, geometry: &RenderGeometry) -> Result<Made, String> {
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let made = (|| {
        let screen = ScreenGeometry::from_projection(key.projection, key.size.0, key.size.1, 0)
            .map_err(|e| e.to_string())?;
        let resources = match key.geometry {
            Some(_) => geometry.resources(),
            None => Default::default(),
        };
        let ao = AmbientOcclusion::new(gpu, &key.settings, screen, resources)
            .map_err(|e| e.to_string())?;
        let input = EngineInput::new(gpu, screen);
        let output = ao.output().clone();
        let for_bevy = CachedTexture {
            default_view: output.create_view(&Default::default()).into(),
            texture: output.into(),
        };
        Ok(Made {
            input,
            ao,
            for_bevy,
            projection: key.projection,
            view_from_world: glam::Mat4::IDENTITY,
        })
    })();
    let raised = pollster::block_on(scope.pop());
    match (made, raised) {
        (Ok(made), None) => Ok(made),
        (Err(e), _) => Err(e),
        (Ok(_), Some(e)) => {
            gpu.forget_kept();
            Err(format!("the GPU refused a pass: {e}"))
        }
    }
}

/// Gives Bevy's lighting each ready row's output texture in place of the SSAO texture Bevy
/// allocated (Bevy's `prepare_ssao_textures` sets it every frame, before this runs).
fn hand_over_ao(
    views: Res<Views>,
    mut cameras: Query<
        (Entity, &mut ScreenSpaceAmbientOcclusionResources),
        With<ExtractedObscuraAo>,
    >,
) {
    for (entity, mut ssao) in &mut cameras {
        if let Some(Ok(made)) = views.rows.get(&entity).map(|r| &r.made) {
            ssao.screen_space_ambient_occlusion_texture = made.for_bevy.clone();
        }
    }
}

/// Takes Bevy's SSAO bind groups off the cameras whose obscura row is ready: Bevy's `ssao`
/// system needs them, so its three passes skip those cameras.
fn skip_bevy_ssao(
    mut commands: Commands,
    views: Res<Views>,
    cameras: Query<Entity, (With<SsaoBindGroups>, With<ExtractedObscuraAo>)>,
) {
    for entity in &cameras {
        if views.rows.get(&entity).is_some_and(|r| r.made.is_ok()) {
            commands.entity(entity).remove::<SsaoBindGroups>();
        }
    }
}

/// The row's passes, writing the texture Bevy's lighting reads (`hand_over_ao`).
fn encode(
    view: ViewQuery<(&ExtractedObscuraAo, &ViewPrepassTextures)>,
    views: Res<Views>,
    mut ctx: RenderContext,
) {
    let entity = view.entity();
    let (_, prepass) = view.into_inner();
    let Some(Ok(made)) = views.rows.get(&entity).map(|r| &r.made) else {
        return;
    };
    let (Some(depth), Some(normals)) = (prepass.depth.as_ref(), prepass.normal.as_ref()) else {
        return;
    };
    let diagnostics = ctx.diagnostic_recorder();
    let diagnostics = diagnostics.as_deref();
    // The whole row, and inside it obscura's input conversion and the row's own passes
    // (`render/obscura_ao/{input,row}/elapsed_gpu`).
    let span = diagnostics.time_span(ctx.command_encoder(), "obscura_ao");
    let frame = EngineFrame {
        depth: &depth.texture.texture,
        projection: made.projection,
        normals: EngineNormals::World {
            texture: &normals.texture.texture,
            // Bevy's prepass writes n * 0.5 + 0.5 into an Rgb10a2Unorm target.
            encoding: NormalEncoding::Biased,
            view_from_world: made.view_from_world,
        },
    };
    let part = diagnostics.time_span(ctx.command_encoder(), "input");
    let textures = made.input.encode(ctx.command_encoder(), &frame);
    part.end(ctx.command_encoder());
    let ran = textures.and_then(|textures| {
        let part = diagnostics.time_span(ctx.command_encoder(), "row");
        let ran = made.ao.encode(ctx.command_encoder(), textures, None);
        part.end(ctx.command_encoder());
        ran
    });
    if let Err(e) = ran {
        error!("obscura: camera {entity}: {e}");
    }
    span.end(ctx.command_encoder());
}
