//! Parsers and shared option groups for the subcommands.

use anyhow::{anyhow, bail, Result};
use clap::Args;
use glam::Vec3;
use obscura::scene::{self, Camera, Scene};
use obscura::settings::{AoSettings, Normalization};
use obscura::Technique;

/// `WxH`, both positive.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{s}' is not WIDTHxHEIGHT (e.g. 1280x720)"))?;
    let parse = |v: &str, what: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("{what} '{v}' in '{s}' is not a whole number (e.g. 1280x720)"))
    };
    let (w, h) = (parse(w, "width")?, parse(h, "height")?);
    if w == 0 || h == 0 {
        return Err(format!(
            "size '{s}' is empty: width and height must be at least 1"
        ));
    }
    if w > 16384 || h > 16384 {
        return Err(format!("size '{s}' is over 16384 px on a side"));
    }
    Ok((w, h))
}

/// `x,y,z` of finite numbers.
pub fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("'{s}' is not x,y,z (e.g. 0,1.5,4)"));
    }
    let mut v = [0.0f32; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = p
            .trim()
            .parse::<f32>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("'{p}' in '{s}' is not a finite number"))?;
    }
    Ok(Vec3::from_array(v))
}

pub fn parse_technique(s: &str) -> Result<Technique, String> {
    s.parse()
        .map_err(|e: obscura::technique::UnknownTechnique| e.to_string())
}

/// Help text of `--technique`: every row of the technique table.
pub fn technique_help() -> String {
    format!(
        "AO technique: {} (see `obscura info --json` for each one's estimator, source and schedule)",
        obscura::technique::names_where(|_| true)
    )
}

/// Which scene and from where.
#[derive(Args, Clone, Debug)]
pub struct SceneArgs {
    /// Built-in scene name (see `obscura scenes`) or a .gltf/.glb/.obj file.
    #[arg(long, default_value = "stairs")]
    pub scene: String,
    /// A named camera of the scene (default: its first, the close-up).
    #[arg(long, conflicts_with_all = ["eye", "target"])]
    pub camera: Option<String>,
    /// Camera position x,y,z (with --target).
    #[arg(long, value_parser = parse_vec3, requires = "target", allow_hyphen_values = true)]
    pub eye: Option<Vec3>,
    /// Point looked at x,y,z (with --eye).
    #[arg(long, value_parser = parse_vec3, requires = "eye", allow_hyphen_values = true)]
    pub target: Option<Vec3>,
    /// Vertical field of view of the visible image in degrees (default: the camera's, or 60).
    #[arg(long, allow_hyphen_values = true)]
    pub fov: Option<f32>,
}

impl SceneArgs {
    pub fn load(&self) -> Result<Scene> {
        Ok(scene::load(&self.scene)?)
    }

    /// The name reports use for the camera these options describe.
    pub fn camera_name(&self, scene: &Scene) -> String {
        match (&self.camera, self.eye) {
            (Some(name), _) => name.clone(),
            (None, Some(_)) => "custom".into(),
            _ => scene
                .cameras
                .first()
                .map_or("auto".into(), |c| c.name.clone()),
        }
    }

    /// The camera these options describe, validated.
    pub fn camera(&self, scene: &Scene, aspect: f32) -> Result<Camera> {
        let mut camera = match (&self.camera, self.eye, self.target) {
            (Some(name), _, _) => scene.camera(name)?,
            (None, Some(eye), Some(target)) => Camera::new(eye, target, self.fov.unwrap_or(60.0))?,
            _ => scene.default_camera(aspect),
        };
        if let Some(fov) = self.fov {
            camera.fov_y_deg = fov;
        }
        camera.validate()?;
        Ok(camera)
    }
}

/// Technique parameters.
#[derive(Args, Clone, Debug)]
pub struct AoArgs {
    /// VAO sphere radius R in world units.
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub radius: f32,
    /// VAO thickness τ (constant occluded area above the column, in units of R).
    #[arg(long, default_value_t = 0.5, allow_hyphen_values = true)]
    pub thickness: f32,
    /// Power applied to the final AO.
    #[arg(long, default_value_t = 1.3, allow_hyphen_values = true)]
    pub exponent: f32,
    /// Samples per pixel: 8, 16 or 32.
    #[arg(long, default_value_t = 8)]
    pub samples: u32,
    /// VAO normalisation: clipped (exact 1 on planes) or hemisphere (the paper's 2/N).
    #[arg(long, default_value = "clipped")]
    pub normalization: String,
    /// Skip the bilateral blur.
    #[arg(long)]
    pub no_blur: bool,
    /// Bilateral blur taps on each side (1..16).
    #[arg(long, default_value_t = 4)]
    pub blur_radius: u32,
    /// Bilateral blur depth sharpness (per world unit of depth difference).
    #[arg(long, default_value_t = 16.0, allow_hyphen_values = true)]
    pub blur_sharpness: f32,
    /// vao-dual, sd-vao, sd-svao: hidden layers start this many world units behind the first.
    #[arg(long, default_value_t = 0.01, allow_hyphen_values = true)]
    pub peel_separation: f32,
    /// sd-vao, sd-svao: stochastic depth samples per pixel (1, 2, 4, 8 or 16; counts one target
    /// cannot hold on this adapter are stacked maps; `obscura info` lists them).
    #[arg(long, default_value_t = 4)]
    pub sd_samples: u32,
    /// sd-vao, sd-svao: global transparency α in (0, 1]; a hidden fragment is kept in
    /// ⌊αS + ξ⌋ samples. 0.2 is the authors' 2022 value, their 2024 code used 1.5/S.
    #[arg(long, default_value_t = 0.2, allow_hyphen_values = true)]
    pub sd_alpha: f32,
    /// sd-vao, sd-svao: seed of the stochastic depth map's hash.
    #[arg(long, default_value_t = 0)]
    pub sd_seed: u32,
    /// sd-svao: limit the map to the requested pixels by 'stencil' (the paper's full-screen
    /// copy into the stencil, then the stencil test) or 'discard' (the map's fragment shader
    /// reads the request mask; no copy pass).
    #[arg(long, default_value = "stencil")]
    pub sd_mask: obscura::settings::SdMask,
    /// Guard band in pixels around the visible image (default: 64 at 1080p, scaled).
    #[arg(long)]
    pub guard_band: Option<u32>,
}

impl AoArgs {
    pub fn settings(&self, technique: Technique) -> Result<AoSettings> {
        let mut settings = AoSettings {
            technique,
            ..Default::default()
        };
        settings.vao.radius = self.radius;
        settings.vao.thickness = self.thickness;
        settings.vao.exponent = self.exponent;
        settings.vao.samples = self.samples;
        settings.vao.normalization = self.normalization.parse::<Normalization>()?;
        settings.blur.enabled = !self.no_blur;
        settings.blur.radius = self.blur_radius;
        settings.blur.sharpness = self.blur_sharpness;
        settings.peel_separation = self.peel_separation;
        settings.stochastic_depth = obscura::settings::StochasticDepthSettings {
            samples: self.sd_samples,
            alpha: self.sd_alpha,
            seed: self.sd_seed,
            mask: self.sd_mask,
        };
        settings.validate()?;
        Ok(settings)
    }

    pub fn guard_band(&self, height: u32) -> u32 {
        self.guard_band
            .unwrap_or_else(|| obscura::default_guard_band(height))
    }
}

/// Comma-separated technique names, at least one.
pub fn parse_techniques(list: &str) -> Result<Vec<Technique>> {
    let techniques = list
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| parse_technique(s).map_err(|e| anyhow!(e)))
        .collect::<Result<Vec<_>>>()?;
    if techniques.is_empty() {
        bail!("--techniques is empty: name at least one (e.g. --techniques vao)");
    }
    Ok(techniques)
}

/// Say so when rays of the last frame overflowed the GPU traversal stack (their AO may be too
/// bright): never silently wrong.
pub fn warn_stack_overflows(renderer: &obscura::Renderer) -> Result<()> {
    let overflows = renderer.read_stack_overflows()?;
    if overflows > 0 {
        eprintln!(
            "warning: {overflows} rays overflowed the GPU BVH traversal stack ({} entries); their \
             occlusion may be incomplete",
            obscura::bvh::gpu::STACK_SIZE
        );
    }
    Ok(())
}
