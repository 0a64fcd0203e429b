//! obscura's ambient occlusion in the Bevy engine (0.19), in place of Bevy's own SSAO.
//!
//! Add [`ObscuraPlugin`] to the app and [`ObscuraAo`] to a 3D camera. Each frame, after Bevy's
//! depth and normal prepass, the camera's row of obscura's technique table runs on Bevy's own
//! render device: Bevy's prepass depth (reversed-Z `Depth32Float`) and world-space normals go
//! through obscura's [`obscura::EngineInput`], the row writes its AO, and the AO is written into
//! the texture Bevy's PBR lighting reads for screen-space ambient occlusion. Bevy's three SSAO
//! passes do not run for that camera.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_obscura::{ObscuraAo, ObscuraPlugin};
//! use obscura::settings::Preset;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, ObscuraPlugin))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((
//!             Camera3d::default(),
//!             Msaa::Off,
//!             ObscuraAo::new("gtao".parse().unwrap(), Preset::High),
//!         ));
//!     })
//!     .run();
//! ```
//!
//! How it meets Bevy (see `render.rs` for the details):
//! - [`ObscuraAo`] requires Bevy's `ScreenSpaceAmbientOcclusion` on the camera. That component
//!   is what makes Bevy's PBR shaders read an AO texture and allocate it; the plugin then takes
//!   the camera's SSAO passes out of the frame and writes that texture itself. The cost left of
//!   Bevy's SSAO is its textures (five of the view's size) and its bind groups, made each frame
//!   on the CPU; no GPU pass.
//! - Like Bevy's SSAO, the camera needs `Msaa::Off` (the prepass is then single-sampled).
//! - The hidden-depth rows (`sd-*`, `rt-*`, `rtao`, …) see the scene's meshes: every entity
//!   with a `Mesh3d` (triangle lists), with its `GlobalTransform`, is handed to obscura's
//!   [`obscura::EngineGeometry`] and kept in step as meshes appear, vanish or move. Moving
//!   meshes rebuilds obscura's BVH on the CPU that frame (tens of milliseconds for a few hundred
//!   thousand triangles).
//! - The guard band is 0: Bevy renders no border around the frame, so AO within the radius of
//!   the image's edges sees less than it would with one.
//! - The row's GPU time is a Bevy diagnostic (`render/obscura_ao/elapsed_gpu`, with Bevy's
//!   `RenderDiagnosticsPlugin`).
//! - A setting that cannot run (an invalid value, a row this adapter cannot run) is logged as an
//!   error once per change, and Bevy's own SSAO runs for that camera meanwhile.

use bevy::app::{App, Plugin};
use bevy::ecs::component::Component;
use bevy::pbr::ScreenSpaceAmbientOcclusion;
use bevy::render::extract_component::{ExtractComponent, ExtractComponentPlugin};
use bevy::render::sync_component::SyncComponent;
pub use obscura;
use obscura::settings::{AoSettings, Preset};
use obscura::Technique;

mod convert;
mod geometry;
mod readback;
mod render;
mod scene;

pub use geometry::ObscuraIgnore;
pub use readback::{read_target_rgba8, read_view_ao, render_gpu, ViewAo};
pub use render::{ObscuraViewReport, Views};
pub use scene::scene_meshes;

/// Adds obscura's AO to every camera with [`ObscuraAo`]. Needs Bevy's `PbrPlugin` (part of
/// `DefaultPlugins`), which brings the SSAO texture the plugin writes.
pub struct ObscuraPlugin;

impl Plugin for ObscuraPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(ExtractComponentPlugin::<ObscuraAo>::default());
        geometry::build(app);
    }

    fn finish(&self, app: &mut App) {
        render::finish(app);
    }
}

/// obscura's AO for this camera, in place of Bevy's SSAO. Changing it at run time rebuilds the
/// row from the next frame on.
#[derive(Component, Clone, Debug, PartialEq)]
#[require(ScreenSpaceAmbientOcclusion)]
pub struct ObscuraAo {
    /// The row of obscura's technique table (`vao`, `gtao`, `sd-hbao+`, `rtao`, …).
    pub technique: Technique,
    /// The technique's preset (low, medium, high, ultra).
    pub preset: Preset,
    /// Every setting, when given: then it runs as it is, and `technique` and `preset` are not
    /// read (its own `technique` field says which row runs).
    pub settings: Option<AoSettings>,
}

impl ObscuraAo {
    /// A technique at a preset.
    pub fn new(technique: Technique, preset: Preset) -> Self {
        Self {
            technique,
            preset,
            settings: None,
        }
    }

    /// Every setting given (radius, samples, temporal accumulation, …).
    pub fn with_settings(settings: AoSettings) -> Self {
        Self {
            technique: settings.technique,
            preset: Preset::Medium,
            settings: Some(settings),
        }
    }

    /// The settings the row runs with.
    pub fn resolved(&self) -> AoSettings {
        self.settings
            .unwrap_or_else(|| AoSettings::preset(self.technique, self.preset))
    }
}

/// [`ObscuraAo`] as the render world has it: the settings the row runs with. A type of its own
/// because a component's required components come with it into any world: extracted as
/// `ObscuraAo`, it would bring a default `ScreenSpaceAmbientOcclusion` into the render world even
/// where Bevy leaves that out (a camera with MSAA, whose multisampled prepass Bevy's SSAO passes
/// cannot bind, which stops Bevy's rendering).
#[derive(Component, Clone, Debug, PartialEq)]
pub struct ExtractedObscuraAo {
    /// [`ObscuraAo::resolved`].
    pub settings: AoSettings,
}

impl SyncComponent for ObscuraAo {
    type Target = ExtractedObscuraAo;
}

impl ExtractComponent for ObscuraAo {
    type QueryData = &'static ObscuraAo;
    type QueryFilter = ();
    type Out = ExtractedObscuraAo;

    fn extract_component(ao: &ObscuraAo) -> Option<ExtractedObscuraAo> {
        Some(ExtractedObscuraAo {
            settings: ao.resolved(),
        })
    }
}

impl Default for ObscuraAo {
    /// `gtao` at its high preset: the closest of the screen-space rows to the ray-traced truth
    /// in obscura's measurements at about Bevy's high SSAO's cost.
    fn default() -> Self {
        Self::new(Technique::Gtao, Preset::High)
    }
}
