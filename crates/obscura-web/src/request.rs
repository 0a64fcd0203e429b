//! What the page asks a frame of, as the JSON it passes (`viewer.render({...})`), and how it
//! becomes the library's settings and camera: the CLI's precedence (defaults < preset <
//! settings), through the library's own functions.

use obscura::scene::{Camera, Scene};
use obscura::settings::SettingsFormat;
use obscura::{AoSettings, Preset, Technique};
use serde::Deserialize;
use std::path::Path;

/// One frame's request. Only `technique`, `width` and `height` are required.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct RenderRequest {
    /// A row's name, as the CLI's `--technique` takes it (`vao`, `gtao`, `hbao+`, …).
    pub technique: String,
    /// Visible image size in pixels (the guard band is extra).
    pub width: u32,
    /// See `width`.
    pub height: u32,
    /// `low`, `medium`, `high` or `ultra` (`--preset`).
    #[serde(default)]
    pub preset: Option<String>,
    /// A settings file's fields as JSON (`--settings`), over the preset.
    #[serde(default)]
    pub settings: Option<serde_json::Value>,
    /// Guard band in pixels (`--guard-band`); by default the CLI's for this height.
    #[serde(default)]
    pub guard_band: Option<u32>,
    /// The camera; by default the scene's first camera or the automatic one, as the CLI's.
    #[serde(default)]
    pub camera: Option<CameraRequest>,
    /// Also read depth, normals and base colour back (the page's other views).
    #[serde(default)]
    pub gbuffer: bool,
    /// Time the passes with timestamp queries, where the device has them.
    #[serde(default)]
    pub timings: bool,
}

/// A camera in the scene's coordinates.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
pub struct CameraRequest {
    /// Position.
    pub eye: [f32; 3],
    /// Point looked at.
    pub target: [f32; 3],
    /// Up direction; +Y by default.
    #[serde(default)]
    pub up: Option<[f32; 3]>,
    /// Vertical field of view, degrees; 60 by default (`--fov`).
    #[serde(default)]
    pub fov: Option<f32>,
}

impl RenderRequest {
    /// The request from the page's object, JSON-encoded by the caller. A field the request does
    /// not know is an error (a typo would otherwise be ignored silently).
    pub fn parse(json: &str) -> Result<Self, String> {
        serde_json::from_str(json).map_err(|e| format!("render request: {e}"))
    }

    /// The settings it asks for, validated, as `obscura render --technique T --preset P
    /// --settings FILE` resolves them.
    pub fn settings(&self) -> Result<AoSettings, String> {
        let technique: Technique = self.technique.parse().map_err(|e| format!("{e}"))?;
        let mut settings = match &self.preset {
            Some(name) => {
                let preset: Preset = name.parse().map_err(|e| format!("{e}"))?;
                AoSettings::preset(technique, preset)
            }
            None => AoSettings {
                technique,
                ..AoSettings::default()
            },
        };
        if let Some(fields) = &self.settings {
            settings = settings
                .with_text(
                    &fields.to_string(),
                    SettingsFormat::Json,
                    Path::new("settings"),
                )
                .map_err(|e| e.to_string())?;
            // The request's technique rules, as the CLI's flag does over a file's.
            settings.technique = technique;
        }
        settings.validate().map_err(|e| e.to_string())?;
        Ok(settings)
    }

    /// The guard band: the request's, else the CLI's default for this height.
    pub fn guard_band(&self) -> u32 {
        self.guard_band
            .unwrap_or_else(|| obscura::default_guard_band(self.height))
    }

    /// The camera it asks for, validated; without one the scene's default (as the CLI's).
    pub fn camera(&self, scene: &Scene) -> Result<Camera, String> {
        scene.check_extent().map_err(|e| e.to_string())?;
        let camera = match self.camera {
            Some(c) => {
                let mut camera = Camera::new(c.eye.into(), c.target.into(), c.fov.unwrap_or(60.0))
                    .map_err(|e| e.to_string())?;
                if let Some(up) = c.up {
                    camera.up = up.into();
                }
                camera
            }
            None => {
                let aspect = self.width as f32 / self.height.max(1) as f32;
                obscura::bvh::framing::default_camera(scene, aspect).0
            }
        };
        camera.validate().map_err(|e| e.to_string())?;
        Ok(camera)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preset_then_settings_as_the_cli() {
        let r = RenderRequest::parse(
            r#"{"technique":"gtao","width":64,"height":32,"preset":"high",
                "settings":{"blur":{"enabled":false}}}"#,
        )
        .unwrap();
        let s = r.settings().unwrap();
        let high = AoSettings::preset(Technique::Gtao, Preset::High);
        assert_eq!(s.technique, Technique::Gtao);
        assert!(!s.blur.enabled);
        assert_eq!(s.gtao, high.gtao);
        assert_eq!(r.guard_band(), obscura::default_guard_band(32));
    }

    #[test]
    fn errors_carry_the_library_messages() {
        let bad_row = RenderRequest::parse(r#"{"technique":"vao2","width":8,"height":8}"#)
            .unwrap()
            .settings()
            .unwrap_err();
        assert!(bad_row.contains("vao2"), "{bad_row}");
        let typo = RenderRequest::parse(r#"{"technique":"vao","width":8,"hieght":8}"#).unwrap_err();
        assert!(typo.contains("hieght"), "{typo}");
        let bad_field =
            RenderRequest::parse(r#"{"technique":"vao","width":8,"height":8,"settings":{"x":1}}"#)
                .unwrap()
                .settings()
                .unwrap_err();
        assert!(bad_field.contains('x'), "{bad_field}");
    }

    #[test]
    fn default_camera_is_the_scenes() {
        let scene = obscura::scene::load("stairs").unwrap();
        let r = RenderRequest::parse(r#"{"technique":"vao","width":64,"height":36}"#).unwrap();
        let expected = obscura::bvh::framing::default_camera(&scene, 64.0 / 36.0).0;
        assert_eq!(r.camera(&scene).unwrap(), expected);
    }
}
