//! Parsers and shared option groups for the subcommands.

use anyhow::{anyhow, bail, Context, Result};
use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::Args;
use glam::Vec3;
use obscura::scene::{self, Camera, Normals, Scene, Sidedness};
use obscura::settings::{
    AoSettings, Normalization, Preset, Resolution, SdMask, SdQuery, SdRasterizer, SdSelection,
    SectorActivation, SettingsError,
};
use obscura::Technique;
use std::path::PathBuf;

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
    /// The image's up direction x,y,z (with --eye; default +Y, or ∓Z looking straight down or
    /// up): 0,0,1 for a scene modelled Z up, as CAD and 3ds Max exports are.
    #[arg(long, value_parser = parse_vec3, requires = "eye", allow_hyphen_values = true)]
    pub up: Option<Vec3>,
    /// Vertical field of view of the visible image in degrees (default: the camera's, or 60).
    #[arg(long, allow_hyphen_values = true)]
    pub fov: Option<f32>,
    /// Count both sides of every triangle (G-buffer, stochastic depth map and rays alike). The
    /// default keeps what the file says: glTF's per-material doubleSided; OBJ is double-sided.
    #[arg(long, conflicts_with = "cull_back_faces")]
    pub double_sided: bool,
    /// Cull back faces of every material that is not alpha-tested, whatever the file says.
    #[arg(long)]
    pub cull_back_faces: bool,
    /// The normal AO is computed around, in the G-buffer and the reference alike: 'face' (the
    /// triangle's, as the papers do) or 'shading' (the file's vertex normals interpolated, as
    /// engines and offline renderers do; face normals where a mesh has none).
    #[arg(
        long,
        default_value = "face",
        value_parser = PossibleValuesParser::new(["face", "shading"])
            .map(|s| s.parse::<Normals>().expect("a listed value"))
    )]
    pub normals: Normals,
}

impl SceneArgs {
    pub fn load(&self) -> Result<Scene> {
        let mut scene = scene::load(&self.scene)?;
        scene.set_sidedness(self.sidedness());
        scene.set_normals(self.normals);
        Ok(scene)
    }

    fn sidedness(&self) -> Sidedness {
        match (self.double_sided, self.cull_back_faces) {
            (true, _) => Sidedness::DoubleSided,
            (_, true) => Sidedness::CullBackFaces,
            _ => Sidedness::AsAuthored,
        }
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
        // Coordinates too large for f32 are the scene's fault, not the (framed) camera's: say so
        // first. A zero extent is only a warning, which the renderer logs.
        scene.check_extent()?;
        let mut camera = match (&self.camera, self.eye, self.target) {
            (Some(name), _, _) => scene.camera(name)?,
            (None, Some(eye), Some(target)) => {
                let mut camera = Camera::new(eye, target, self.fov.unwrap_or(60.0))?;
                camera.up = self.up.unwrap_or(camera.up);
                camera
            }
            _ => scene.default_camera(aspect),
        };
        if let Some(fov) = self.fov {
            camera.fov_y_deg = fov;
        }
        camera.validate()?;
        Ok(camera)
    }
}

/// Each [`AoSettings`] field with the `AoArgs` flag that sets it (every field but `technique`,
/// which `--technique`/`--techniques` choose). Library errors name fields; the CLI names flags.
const FIELD_FLAGS: &[(&str, &str)] = &[
    ("vao.radius", "--radius"),
    ("vao.thickness", "--thickness"),
    ("vao.exponent", "--exponent"),
    ("vao.samples", "--samples"),
    ("vao.normalization", "--normalization"),
    ("blur.enabled", "--no-blur"),
    ("blur.radius", "--blur-radius"),
    ("blur.sharpness", "--blur-sharpness"),
    ("blur.sigma", "--blur-sigma"),
    ("peel_separation", "--peel-separation"),
    ("stochastic_depth.samples", "--sd-samples"),
    ("stochastic_depth.alpha", "--sd-alpha"),
    ("stochastic_depth.seed", "--sd-seed"),
    ("stochastic_depth.mask", "--sd-mask"),
    ("stochastic_depth.query", "--sd-query"),
    ("stochastic_depth.selection", "--sd-select"),
    ("stochastic_depth.rasterizer", "--sd-rasterizer"),
    ("stochastic_depth.compensation", "--sd-compensation"),
    ("ray_sd.reservoir", "--reservoir"),
    ("ray_sd.max_count", "--max-count"),
    ("ray_sd.z_cull", "--no-z-cull"),
    ("ray_sd.seed", "--ray-sd-seed"),
    ("ray_sd.resolution", "--ray-sd-res"),
    ("ray_sd.radius_cutoff", "--radius-cutoff"),
    ("ray_sd.guard_band", "--sd-guard-band"),
    ("stochastic_depth.guard_band", "--sd-map-guard-band"),
    ("ray_sd.intervals", "--no-intervals"),
    ("resolution", "--resolution"),
    ("max_radius_px", "--max-radius-px"),
    ("bent_normals", "--bent-normals"),
    ("multiview.angle", "--mv-angle"),
    ("multiview.focus", "--mv-focus"),
    ("multiview.resolution", "--mv-resolution"),
    ("temporal.enabled", "--temporal"),
    ("temporal.frames", "--temporal-frames"),
    ("temporal.depth_tolerance", "--temporal-depth-tolerance"),
    (
        "temporal.normal_tolerance_deg",
        "--temporal-normal-tolerance",
    ),
    ("temporal.clamp", "--temporal-no-clamp"),
    ("hbao.radius", "--horizon-radius"),
    ("hbao.angle_bias", "--horizon-bias"),
    ("hbao.exponent", "--horizon-exponent"),
    ("hbao.directions", "--horizon-directions"),
    ("hbao.steps", "--horizon-steps"),
    ("gtao.radius", "--gtao-radius"),
    ("gtao.thickness_blend", "--gtao-thickness-blend"),
    ("gtao.exponent", "--gtao-exponent"),
    ("gtao.slices", "--gtao-slices"),
    ("gtao.steps", "--gtao-steps"),
    ("pyramid.levels", "--pyramid-levels"),
    ("pyramid.factor", "--pyramid-factor"),
    ("pyramid_hbao.radius", "--phbao-radius"),
    ("pyramid_hbao.exponent", "--phbao-exponent"),
    ("pyramid_hbao.directions", "--phbao-directions"),
    ("pyramid_hbao.steps", "--phbao-steps"),
    ("ssao.radius", "--ssao-radius"),
    ("ssao.samples", "--ssao-samples"),
    ("ssao.intensity", "--ssao-intensity"),
    ("ssao.bias", "--ssao-bias"),
    ("ssao.contrast", "--ssao-contrast"),
    ("sao.radius", "--sao-radius"),
    ("sao.samples", "--sao-samples"),
    ("sao.spiral_turns", "--sao-turns"),
    ("sao.bias", "--sao-bias"),
    ("sao.intensity", "--sao-intensity"),
    ("hbao_plus.radius", "--hbao-radius"),
    ("hbao_plus.bias", "--hbao-bias"),
    ("hbao_plus.exponent", "--hbao-exponent"),
    ("hbao_plus.directions", "--hbao-directions"),
    ("hbao_plus.steps", "--hbao-steps"),
    ("gtao_vb.radius", "--vb-radius"),
    ("gtao_vb.thickness", "--vb-thickness"),
    ("gtao_vb.exponent", "--vb-exponent"),
    ("gtao_vb.slices", "--vb-slices"),
    ("gtao_vb.steps", "--vb-steps"),
    ("gtao_vb.activation", "--vb-activation"),
    ("gtao_vb.cosine_weighted", "--vb-cosine"),
];

/// The flag that sets a settings field: `flag_for_field("vao.radius") == Some("--radius")`.
pub fn flag_for_field(field: &str) -> Option<&'static str> {
    FIELD_FLAGS
        .iter()
        .find(|(f, _)| *f == field)
        .map(|(_, flag)| *flag)
}

/// A settings error as the CLI says it: an invalid or unsupported field named by its flag.
fn with_flags(e: SettingsError) -> anyhow::Error {
    match e {
        SettingsError::Invalid { field, value, rule } => match flag_for_field(field) {
            Some(flag) => anyhow!("invalid {flag} {value}: {rule}"),
            None => SettingsError::Invalid { field, value, rule }.into(),
        },
        SettingsError::Unsupported {
            field,
            value,
            adapter,
            reason,
        } => match flag_for_field(field) {
            Some(flag) => {
                anyhow!("{flag} {value} is not supported on adapter '{adapter}': {reason}")
            }
            None => SettingsError::Unsupported {
                field,
                value,
                adapter,
                reason,
            }
            .into(),
        },
        e => e.into(),
    }
}

/// Any error on its way to the user: a library settings error (from wherever it came, e.g. the
/// adapter refusing a sample count when the map is made) names the flag instead of the field.
pub fn for_user(e: anyhow::Error) -> anyhow::Error {
    match e.downcast::<obscura::Error>() {
        Ok(obscura::Error::Settings(s)) => with_flags(s),
        Ok(other) => other.into(),
        Err(e) => match e.downcast::<SettingsError>() {
            Ok(s) => with_flags(s),
            Err(e) => e,
        },
    }
}

/// Help text ending in the field's default, as [`AoSettings::default`] has it (no second copy
/// of the defaults here; a test checks that passing the stated defaults changes nothing).
fn help(text: &str, field: &str) -> String {
    let mut value = serde_json::to_value(AoSettings::default()).expect("settings serialise");
    for key in field.split('.') {
        value = value[key].take();
    }
    let shown = match &value {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Number(n) if n.is_u64() => n.to_string(),
        // An optional field left out: the library's rule (α: 1.5/S).
        serde_json::Value::Null => "auto".into(),
        // Through f32, so that 1.3 reads 1.3 (the field is an f32).
        serde_json::Value::Number(n) => (n.as_f64().unwrap_or(f64::NAN) as f32).to_string(),
        other => other.to_string(),
    };
    format!("{} [default: {shown}]", text.trim_end_matches('.'))
}

/// A flag that takes a value or `auto` (the library's default, `None`): `--sd-alpha`,
/// `--sd-guard-band`.
fn parse_or_auto<T: std::str::FromStr>(
    text: &str,
    field: &'static str,
    rule: &'static str,
) -> Result<Option<T>, SettingsError> {
    if text.trim().eq_ignore_ascii_case("auto") {
        return Ok(None);
    }
    text.trim()
        .parse::<T>()
        .map(Some)
        .map_err(|_| SettingsError::Invalid {
            field,
            value: text.to_string(),
            rule,
        })
}

/// Technique parameters. Precedence: defaults < `--preset` < `--settings FILE` < the other flags
/// (only the flags given are applied).
#[derive(Args, Clone, Debug)]
pub struct AoArgs {
    /// Quality preset for each technique (docs/SETTINGS.md lists what each sets; medium = the
    /// defaults).
    #[arg(long, value_parser = PossibleValuesParser::new(Preset::ALL.map(Preset::name))
        .map(|s| s.parse::<Preset>().expect("a listed preset")))]
    pub preset: Option<Preset>,
    /// Settings file, .toml or .json (docs/SETTINGS.md): applied over the preset; the flags
    /// below override it.
    #[arg(long, value_name = "FILE")]
    pub settings: Option<PathBuf>,
    /// One world radius R for every technique's estimator and for the ground truth (compare
    /// techniques at the same distance, or against an outside renderer's AO of that distance);
    /// each estimator reads R its own way (docs/SETTINGS.md). Applied over the preset and the
    /// file; the per-technique radius flags (--radius, --hbao-radius, …) override it.
    #[arg(long, allow_hyphen_values = true)]
    pub ao_radius: Option<f32>,
    /// The length of one world unit of the scene: metres as a number (0.0254 for inches), or
    /// m, cm, mm, km, in, ft. The defaults and presets assume metres (glTF's unit); with
    /// `--units cm` every one of their world lengths (the radii, thicknesses, SAO's bias and
    /// intensity; the blur's sharpness per world unit) is converted, so an outside scene in
    /// centimetres gets the same AO as in metres (`AoSettings::scaled`). A settings file and
    /// the flags below are read in the scene's own units, over the converted defaults.
    #[arg(long, value_name = "UNIT", allow_hyphen_values = true)]
    pub units: Option<String>,
    // Help texts name the defaults of AoSettings::default() (`help`).
    #[arg(long, allow_hyphen_values = true, help = help("VAO sphere radius R in world units.", "vao.radius"))]
    pub radius: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("HBAO+ radius R in world units.", "hbao_plus.radius"))]
    pub hbao_radius: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "HBAO+ angle bias: a sample occludes by saturate(N·V/|V| − bias).",
        "hbao_plus.bias"
    ))]
    pub hbao_bias: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("HBAO+ power applied to the final AO.", "hbao_plus.exponent"))]
    pub hbao_exponent: Option<f32>,
    #[arg(long, help = help("HBAO+ directions per pixel (directions × steps ≤ 32).", "hbao_plus.directions"))]
    pub hbao_directions: Option<u32>,
    #[arg(long, help = help("HBAO+ steps per direction.", "hbao_plus.steps"))]
    pub hbao_steps: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "HBAO (hbao, hbao-dual) radius R in world units; attenuation 1 − r/R.",
        "hbao.radius"
    ))]
    pub horizon_radius: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "HBAO angle bias in radians, added to the tangent elevation each direction starts from.",
        "hbao.angle_bias"
    ))]
    pub horizon_bias: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("HBAO power applied to the final AO.", "hbao.exponent"))]
    pub horizon_exponent: Option<f32>,
    #[arg(long, help = help("HBAO directions per pixel (1 to 64).", "hbao.directions"))]
    pub horizon_directions: Option<u32>,
    #[arg(long, help = help("HBAO steps per direction (1 to 128).", "hbao.steps"))]
    pub horizon_steps: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help("GTAO radius R in world units.", "gtao.radius"))]
    pub gtao_radius: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "GTAO thickness heuristic β in [0, 1]: how far a lower sample pulls the horizon down.",
        "gtao.thickness_blend"
    ))]
    pub gtao_thickness_blend: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("GTAO power applied to the final AO.", "gtao.exponent"))]
    pub gtao_exponent: Option<f32>,
    #[arg(long, help = help("GTAO slices per pixel (1 to 16).", "gtao.slices"))]
    pub gtao_slices: Option<u32>,
    #[arg(long, help = help("GTAO steps on each side of a slice (1 to 32).", "gtao.steps"))]
    pub gtao_steps: Option<u32>,
    #[arg(long, help = help(
        "Depth pyramid levels L, the depth buffer included (1 to 8): sao, pyramid-hbao.",
        "pyramid.levels"
    ))]
    pub pyramid_levels: Option<u32>,
    #[arg(long, help = help(
        "Depth pyramid factor K: each texel the mean of K × K below (2 to 4).",
        "pyramid.factor"
    ))]
    pub pyramid_factor: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help("Pyramid HBAO radius R in world units; attenuation 1 − r/R.", "pyramid_hbao.radius"))]
    pub phbao_radius: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("Pyramid HBAO power applied to the final AO.", "pyramid_hbao.exponent"))]
    pub phbao_exponent: Option<f32>,
    #[arg(long, help = help("Pyramid HBAO directions per pixel (1 to 32).", "pyramid_hbao.directions"))]
    pub phbao_directions: Option<u32>,
    #[arg(long, help = help("Pyramid HBAO steps on every pyramid level (1 to 16).", "pyramid_hbao.steps"))]
    pub phbao_steps: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help("SSAO (Alchemy) radius R in world units.", "ssao.radius"))]
    pub ssao_radius: Option<f32>,
    #[arg(long, help = help("SSAO samples per pixel (1 to 32).", "ssao.samples"))]
    pub ssao_samples: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help("SSAO intensity σ.", "ssao.intensity"))]
    pub ssao_intensity: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("SSAO bias β per world unit of depth.", "ssao.bias"))]
    pub ssao_bias: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("SSAO contrast k (power of the final AO).", "ssao.contrast"))]
    pub ssao_contrast: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("SAO radius R in world units.", "sao.radius"))]
    pub sao_radius: Option<f32>,
    #[arg(long, help = help("SAO taps per pixel (1 to 64).", "sao.samples"))]
    pub sao_samples: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help("SAO turns of the tap spiral.", "sao.spiral_turns"))]
    pub sao_turns: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("SAO bias β in world units.", "sao.bias"))]
    pub sao_bias: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("SAO intensity (scale of the obscurance), in world units as SAO's normalisation has it.", "sao.intensity"))]
    pub sao_intensity: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("GTAO-VB search radius R in world units.", "gtao_vb.radius"))]
    pub vb_radius: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "GTAO-VB constant thickness behind every depth sample, world units.",
        "gtao_vb.thickness"
    ))]
    pub vb_thickness: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("GTAO-VB power applied to the final AO.", "gtao_vb.exponent"))]
    pub vb_exponent: Option<f32>,
    #[arg(long, help = help("GTAO-VB slices per pixel (1 to 3).", "gtao_vb.slices"))]
    pub vb_slices: Option<u32>,
    #[arg(long, help = help(
        "GTAO-VB steps on each side of a slice (slices × 2 × steps ≤ 32).",
        "gtao_vb.steps"
    ))]
    pub vb_steps: Option<u32>,
    #[arg(long, help = help(
        "GTAO-VB sector activation: ceil (touched), round (half covered) or floor (covered).",
        "gtao_vb.activation"
    ))]
    pub vb_activation: Option<String>,
    /// GTAO-VB: weigh free sectors by the cosine to the normal, GTAO's integral (our extension;
    /// seed 003 counts sectors alike).
    #[arg(long)]
    pub vb_cosine: bool,
    #[arg(long, allow_hyphen_values = true, help = help(
        "VAO thickness τ (constant occluded area above the column, in units of R).",
        "vao.thickness"
    ))]
    pub thickness: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help("Power applied to the final AO.", "vao.exponent"))]
    pub exponent: Option<f32>,
    #[arg(long, help = help("Samples per pixel: 8, 16 or 32.", "vao.samples"))]
    pub samples: Option<u32>,
    #[arg(long, help = help(
        "VAO normalisation: clipped (exact 1 on planes) or hemisphere (the paper's 2/N).",
        "vao.normalization"
    ))]
    pub normalization: Option<String>,
    /// Skip the bilateral blur (blurred by default).
    #[arg(long)]
    pub no_blur: bool,
    #[arg(long, help = help("Bilateral blur taps on each side (1..16).", "blur.radius"))]
    pub blur_radius: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "Bilateral blur depth sharpness (per world unit of depth difference).",
        "blur.sharpness"
    ))]
    pub blur_sharpness: Option<f32>,
    /// σ in pixels of a natural Gaussian spatial weight (default: HBAO+'s weights); seed 004's
    /// filter is --blur-radius 2 --blur-sharpness 0 --blur-sigma 1.5.
    #[arg(long, allow_hyphen_values = true)]
    pub blur_sigma: Option<f32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "vao-dual, sd-vao, sd-svao: hidden layers start this many world units behind the first.",
        "peel_separation"
    ))]
    pub peel_separation: Option<f32>,
    #[arg(long, help = help(
        "sd-vao, sd-svao: stochastic depth samples per pixel (1, 2, 4, 8 or 16).",
        "stochastic_depth.samples"
    ))]
    pub sd_samples: Option<u32>,
    #[arg(long, allow_hyphen_values = true, help = help(
        "sd-vao, sd-svao: global transparency α in (0, 1], or auto = 1.5/S (the authors' 2024 \
         rule); a hidden fragment is kept in ⌊αS + ξ⌋ samples. 0.2 is the authors' 2022 value.",
        "stochastic_depth.alpha"
    ))]
    pub sd_alpha: Option<String>,
    #[arg(long, help = help(
        "sd-vao, sd-svao: seed of the stochastic depth map's hash.",
        "stochastic_depth.seed"
    ))]
    pub sd_seed: Option<u32>,
    #[arg(long, help = help(
        "sd-svao: limit the map to the requested pixels by 'depth' (default: the far plane \
         written into the map's depth test where nobody asked), 'stencil' (the paper's \
         full-screen copy into the stencil, then the stencil test) or 'discard' (the map's \
         fragment shader reads the request mask).",
        "stochastic_depth.mask"
    ))]
    pub sd_mask: Option<String>,
    #[arg(long, help = help(
        "Stochastic-depth techniques: read the map only where the first layer cannot decide \
         ('needed', seed 001 §3.3; SSAO and GTAO-VB also skip samples no deeper surface can change), \
         as the paper words it ('first-layer': the same image, more reads) or for every sample \
         ('always', to measure the difference).",
        "stochastic_depth.query"
    ))]
    pub sd_query: Option<String>,
    #[arg(long, help = help(
        "Raster stochastic depth map: which hidden fragments each pixel keeps in its S depths: \
         'stochastic' (default, seed 001 Alg. 1: a hashed subset, every layer has a chance) or \
         'nearest' (ours: the S nearest layers behind the first, exact where a pixel hides at \
         most S, steady in motion).",
        "stochastic_depth.selection"
    ))]
    pub sd_select: Option<String>,
    #[arg(long, help = help(
        "Raster stochastic depth map: what rasterises it: 'auto' (default: 'compute' where the \
         GPU binds its buffers and is not a CPU adapter, else 'hardware'), 'hardware' (the GPU's \
         rasteriser) or 'compute' (ours: compute passes clip, bin and rasterise the triangles; \
         the same map up to rounding).",
        "stochastic_depth.rasterizer"
    ))]
    pub sd_rasterizer: Option<String>,
    #[arg(long, help = help(
        "Stochastic-depth techniques: multiply the occlusion of stochastic samples by this \
         factor in [1, 8] (missing-occlusion compensation, seed 001 §4; 1 = off, the paper used 2).",
        "stochastic_depth.compensation"
    ))]
    pub sd_compensation: Option<f32>,
    #[arg(long, help = help(
        "Raster stochastic-depth techniques (sd-vao, sd-svao, sd-hbao, ...): rasterise the map \
         this many pixels beyond the framebuffer on every side (0 = off, at most 2048), so \
         samples off the framebuffer read it; the ray-traced map's band is --sd-guard-band.",
        "stochastic_depth.guard_band"
    ))]
    pub sd_map_guard_band: Option<u32>,
    #[arg(long, help = help(
        "ray-sd-vao: depth slots per pixel of the ray-traced stochastic depth map, N in [1, 8] \
         (seed 002 §3.1, reservoir sampling).",
        "ray_sd.reservoir"
    ))]
    pub reservoir: Option<u32>,
    #[arg(long, help = help(
        "ray-sd-vao: hits a ray of the ray-traced map handles before it stops (MAX_COUNT), in \
         [N, 64] (seed 002 §3.1).",
        "ray_sd.max_count"
    ))]
    pub max_count: Option<u32>,
    /// ray-sd-vao: plain reservoir sampling (every hit kept with probability N/count) instead of
    /// the paper's z-culling, which overwrites a slot only with a nearer depth.
    #[arg(long)]
    pub no_z_cull: bool,
    #[arg(long, help = help(
        "ray-sd-vao: seed of the ray-traced map's reservoir hash.",
        "ray_sd.seed"
    ))]
    pub ray_sd_seed: Option<u32>,
    #[arg(long, help = help(
        "ray-sd-vao: resolution divisor of the ray-traced map, 1, 2 or 4 (a ray per 1, 4 or 16 \
         pixels through a jittered point of its block, seed 002 §3.3).",
        "ray_sd.resolution"
    ))]
    pub ray_sd_res: Option<u32>,
    #[arg(long, help = help(
        "ray-sd-vao: samples nearer than this many pixels to their pixel keep the first layer's \
         answer and never request the ray-traced map (seed 002 §3.4 used 6; 0 = off).",
        "ray_sd.radius_cutoff"
    ))]
    pub radius_cutoff: Option<f32>,
    #[arg(long, help = help(
        "ray-sd-*: the ray-traced map's own guard band in pixels beyond the framebuffer, which \
         samples that fall off the framebuffer read (seed 002 §3.5), 0 = off, or auto = 512 px \
         at 1080p scaled with the height on two-phase rows and off on one-pass rows.",
        "ray_sd.guard_band"
    ))]
    pub sd_guard_band: Option<String>,
    /// ray-sd-vao: trace each ray of the ray-traced map from the first layer to the scene's end
    /// instead of over the depths phase 1's samples need (seed 002 §3.2's ray intervals, on by
    /// default).
    #[arg(long)]
    pub no_intervals: bool,
    #[arg(long, help = help(
        "Run the technique at 'full' resolution (default) or at 'half' (a quarter of the pixels, \
         seed 001 Tab. 1-2) with a depth-aware upsample; half needs an even size and guard band.",
        "resolution"
    ))]
    pub resolution: Option<String>,
    #[arg(long, help = help(
        "Cap the AO radius on screen at this many output pixels: a surface closer to the camera \
         runs with the radius that covers exactly that many (seed 002 §3.5; the authors used \
         512 at 1080p with a 512 px --sd-guard-band), 0 = no cap.",
        "max_radius_px"
    ))]
    pub max_radius_px: Option<f32>,
    /// Also compute the bent normal (seed 001 §4): the single-pass GTAO, GTAO-VB, VAO and HBAO+ rows;
    /// `render` writes it next to the AO as NAME.bent.png (view space, RGB = 0.5 n + 0.5) or
    /// NAME.bent.exr.
    #[arg(long)]
    pub bent_normals: bool,
    #[arg(long, help = help(
        "sd-hbao+-multiview: degrees the second view is swung about the camera's up axis around \
         the focus point, in (0, 60] (seed 001 §3.4).",
        "multiview.angle"
    ))]
    pub mv_angle: Option<f32>,
    /// sd-hbao+-multiview: distance (world units) from the camera to the point both views look
    /// at (default: along the view axis to the scene's bounding-box centre).
    #[arg(long)]
    pub mv_focus: Option<f32>,
    #[arg(long, help = help(
        "sd-hbao+-multiview: the second view's map and pass at 'full' or 'half' resolution \
         (seed 001 Tab. 3).",
        "multiview.resolution"
    ))]
    pub mv_resolution: Option<String>,
    /// Temporal accumulation: each pixel's AO averaged with its history over frames, reprojected
    /// by the camera motion and rejected where the surface differs; the estimators turn their
    /// 4×4 pattern per frame (docs/PATHS.md). For paths and the viewer.
    #[arg(long)]
    pub temporal: bool,
    #[arg(long, help = help(
        "--temporal: the most frames averaged (1..255).",
        "temporal.frames"
    ))]
    pub temporal_frames: Option<u32>,
    #[arg(long, help = help(
        "--temporal: relative depth difference within which the history is the same surface.",
        "temporal.depth_tolerance"
    ))]
    pub temporal_depth_tolerance: Option<f32>,
    #[arg(long, help = help(
        "--temporal: degrees between normals within which the history is the same surface.",
        "temporal.normal_tolerance_deg"
    ))]
    pub temporal_normal_tolerance: Option<f32>,
    /// --temporal: keep the history unclipped (by default it is clipped to the spread of this
    /// frame's AO around the pixel, which stops view-dependent occlusion from lagging).
    #[arg(long)]
    pub temporal_no_clamp: bool,
    /// Guard band in pixels around the visible image (default: 64 at 1080p, scaled).
    #[arg(long)]
    pub guard_band: Option<u32>,
}

/// `--units`: world units per metre, from one unit's length in metres or the unit's name
/// (in f64, so that `0.001` gives exactly 1000).
fn parse_units(units: &str) -> Result<f32> {
    let metres: f64 = match units.trim() {
        "m" => 1.0,
        "cm" => 0.01,
        "mm" => 0.001,
        "km" => 1000.0,
        "in" => 0.0254,
        "ft" => 0.3048,
        number => number.parse().unwrap_or(f64::NAN),
    };
    let per_metre = (1.0 / metres) as f32;
    if !(metres > 0.0 && per_metre.is_finite() && per_metre > 0.0) {
        bail!(
            "invalid --units {units}: give one world unit's length in metres (e.g. 0.01) or one \
             of m, cm, mm, km, in, ft"
        );
    }
    Ok(per_metre)
}

impl AoArgs {
    /// `--units` as world units per metre; 1 without it.
    pub fn units_per_metre(&self) -> Result<f32> {
        self.units.as_deref().map_or(Ok(1.0), parse_units)
    }

    /// The settings of `technique`: its preset (or the defaults), the settings file over it,
    /// then the flags given; validated, errors naming the flag (or the file's field).
    pub fn settings(&self, technique: Technique) -> Result<AoSettings> {
        let mut s = match self.preset {
            Some(preset) => AoSettings::preset(technique, preset),
            None => AoSettings {
                technique,
                ..AoSettings::default()
            },
        };
        if self.units.is_some() {
            s = s.scaled(self.units_per_metre()?);
        }
        if let Some(path) = &self.settings {
            s = s.with_file(path)?;
            if s.technique != technique {
                warn_once(format!(
                    "warning: settings file '{}' sets technique \"{}\", which is not used: the \
                     command line chooses techniques (--technique/--techniques); this run uses \
                     {technique}",
                    path.display(),
                    s.technique
                ));
                s.technique = technique;
            }
        }
        if let Some(r) = self.ao_radius {
            // Checked here: the fields it sets would name their own flags.
            if !(r.is_finite() && r > 0.0) {
                bail!(
                    "invalid --ao-radius {r}: must be a positive number of world units, e.g. 0.5"
                );
            }
            s.set_every_radius(r);
        }
        let v = &mut s.vao;
        set(&mut v.radius, self.radius);
        set(&mut v.thickness, self.thickness);
        set(&mut v.exponent, self.exponent);
        set(&mut v.samples, self.samples);
        if let Some(n) = &self.normalization {
            v.normalization = n.parse::<Normalization>().map_err(with_flags)?;
        }
        let h = &mut s.hbao;
        set(&mut h.radius, self.horizon_radius);
        set(&mut h.angle_bias, self.horizon_bias);
        set(&mut h.exponent, self.horizon_exponent);
        set(&mut h.directions, self.horizon_directions);
        set(&mut h.steps, self.horizon_steps);
        let g = &mut s.gtao;
        set(&mut g.radius, self.gtao_radius);
        set(&mut g.thickness_blend, self.gtao_thickness_blend);
        set(&mut g.exponent, self.gtao_exponent);
        set(&mut g.slices, self.gtao_slices);
        set(&mut g.steps, self.gtao_steps);
        set(&mut s.pyramid.levels, self.pyramid_levels);
        set(&mut s.pyramid.factor, self.pyramid_factor);
        let ph = &mut s.pyramid_hbao;
        set(&mut ph.radius, self.phbao_radius);
        set(&mut ph.exponent, self.phbao_exponent);
        set(&mut ph.directions, self.phbao_directions);
        set(&mut ph.steps, self.phbao_steps);
        let ss = &mut s.ssao;
        set(&mut ss.radius, self.ssao_radius);
        set(&mut ss.samples, self.ssao_samples);
        set(&mut ss.intensity, self.ssao_intensity);
        set(&mut ss.bias, self.ssao_bias);
        set(&mut ss.contrast, self.ssao_contrast);
        let sao = &mut s.sao;
        set(&mut sao.radius, self.sao_radius);
        set(&mut sao.samples, self.sao_samples);
        set(&mut sao.spiral_turns, self.sao_turns);
        set(&mut sao.bias, self.sao_bias);
        set(&mut sao.intensity, self.sao_intensity);
        let h = &mut s.hbao_plus;
        set(&mut h.radius, self.hbao_radius);
        set(&mut h.bias, self.hbao_bias);
        set(&mut h.exponent, self.hbao_exponent);
        set(&mut h.directions, self.hbao_directions);
        set(&mut h.steps, self.hbao_steps);
        let g = &mut s.gtao_vb;
        set(&mut g.radius, self.vb_radius);
        set(&mut g.thickness, self.vb_thickness);
        set(&mut g.exponent, self.vb_exponent);
        set(&mut g.slices, self.vb_slices);
        set(&mut g.steps, self.vb_steps);
        if let Some(a) = &self.vb_activation {
            g.activation = a.parse::<SectorActivation>().map_err(with_flags)?;
        }
        let b = &mut s.blur;
        if self.vb_cosine {
            s.gtao_vb.cosine_weighted = true;
        }
        if self.no_blur {
            b.enabled = false;
        }
        set(&mut b.radius, self.blur_radius);
        set(&mut b.sharpness, self.blur_sharpness);
        if let Some(sigma) = self.blur_sigma {
            b.sigma = Some(sigma);
        }
        set(&mut s.peel_separation, self.peel_separation);
        let sd = &mut s.stochastic_depth;
        set(&mut sd.samples, self.sd_samples);
        if let Some(alpha) = &self.sd_alpha {
            sd.alpha = parse_or_auto(
                alpha,
                "stochastic_depth.alpha",
                "must be a number in (0, 1], e.g. 0.375, or 'auto' for 1.5/S",
            )
            .map_err(with_flags)?;
        }
        set(&mut sd.seed, self.sd_seed);
        if let Some(m) = &self.sd_mask {
            sd.mask = m.parse::<SdMask>().map_err(with_flags)?;
        }
        if let Some(q) = &self.sd_query {
            sd.query = q.parse::<SdQuery>().map_err(with_flags)?;
        }
        if let Some(q) = &self.sd_select {
            sd.selection = q.parse::<SdSelection>().map_err(with_flags)?;
        }
        if let Some(r) = &self.sd_rasterizer {
            sd.rasterizer = r.parse::<SdRasterizer>().map_err(with_flags)?;
        }
        set(&mut sd.compensation, self.sd_compensation);
        set(&mut sd.guard_band, self.sd_map_guard_band);
        let ray = &mut s.ray_sd;
        set(&mut ray.reservoir, self.reservoir);
        set(&mut ray.max_count, self.max_count);
        if self.no_z_cull {
            ray.z_cull = false;
        }
        set(&mut ray.seed, self.ray_sd_seed);
        set(&mut ray.resolution, self.ray_sd_res);
        set(&mut ray.radius_cutoff, self.radius_cutoff);
        if let Some(band) = &self.sd_guard_band {
            ray.guard_band = parse_or_auto(
                band,
                "ray_sd.guard_band",
                "must be a whole number of pixels, e.g. 512, 0 (off) or 'auto'",
            )
            .map_err(with_flags)?;
        }
        if self.no_intervals {
            ray.intervals = false;
        }
        set(&mut s.max_radius_px, self.max_radius_px);
        if self.bent_normals {
            s.bent_normals = true;
        }
        set(&mut s.multiview.angle, self.mv_angle);
        if let Some(focus) = self.mv_focus {
            s.multiview.focus = Some(focus);
        }
        if let Some(r) = &self.mv_resolution {
            s.multiview.resolution = r.parse::<Resolution>().map_err(with_flags)?;
        }
        if let Some(r) = &self.resolution {
            s.resolution = r.parse::<Resolution>().map_err(with_flags)?;
        }
        if self.temporal {
            s.temporal.enabled = true;
        }
        set(&mut s.temporal.frames, self.temporal_frames);
        set(
            &mut s.temporal.depth_tolerance,
            self.temporal_depth_tolerance,
        );
        set(
            &mut s.temporal.normal_tolerance_deg,
            self.temporal_normal_tolerance,
        );
        if self.temporal_no_clamp {
            s.temporal.clamp = false;
        }
        // The preset and the file were valid: anything invalid now came from a flag.
        s.validate().map_err(with_flags)?;
        Ok(s)
    }

    pub fn guard_band(&self, height: u32) -> u32 {
        self.guard_band
            .unwrap_or_else(|| obscura::default_guard_band(height))
    }
}

fn set<T>(slot: &mut T, flag: Option<T>) {
    if let Some(v) = flag {
        *slot = v;
    }
}

/// `message` on stderr, once per run (settings are resolved once per technique).
fn warn_once(message: String) {
    static SAID: std::sync::Once = std::sync::Once::new();
    SAID.call_once(|| eprintln!("{message}"));
}

/// Comma-separated technique names, at least one: `--techniques`.
#[derive(Clone, Debug)]
pub struct TechniqueList(pub Vec<Technique>);

/// The value parser of `--techniques`: a bad name is a usage error (exit status 2), as it is for
/// `--technique`.
pub fn parse_technique_list(list: &str) -> Result<TechniqueList, String> {
    let techniques = list
        .split(',')
        .filter(|s| !s.trim().is_empty())
        .map(parse_technique)
        .collect::<Result<Vec<_>, String>>()?;
    if techniques.is_empty() {
        return Err("the list is empty: name at least one (e.g. --techniques vao)".into());
    }
    Ok(TechniqueList(techniques))
}

/// Help text of `--techniques`: every row of the technique table.
pub fn techniques_help() -> String {
    format!(
        "Comma-separated techniques: {}",
        obscura::technique::names_where(|_| true)
    )
}

/// Say so when rays of the last frame overflowed the GPU traversal stack (their AO may be too
/// bright): never silently wrong.
/// Makes `out` an existing, writable folder (created if missing) before any slow work; `holds`
/// says what goes into it, for the message when `out` is a file.
pub fn prepare_out_folder(out: &std::path::Path, holds: &str) -> Result<()> {
    if out.is_file() {
        anyhow::bail!(
            "--out '{}' is a file: give a folder for {holds}",
            out.display()
        );
    }
    std::fs::create_dir_all(out).with_context(|| {
        format!(
            "cannot create output folder '{}': check the path and permissions",
            out.display()
        )
    })?;
    let probe = out.join(format!(".obscura-write-test-{}", std::process::id()));
    std::fs::write(&probe, b"")
        .with_context(|| format!("output folder '{}' is not writable", out.display()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{CommandFactory, Parser};

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        ao: AoArgs,
    }

    fn ao(args: &[&str]) -> AoArgs {
        Cli::try_parse_from(std::iter::once("obscura").chain(args.iter().copied()))
            .unwrap_or_else(|e| panic!("{args:?}: {e}"))
            .ao
    }

    /// `--flag` → its help text.
    fn helps() -> Vec<(String, String)> {
        Cli::command()
            .get_arguments()
            .filter_map(|a| {
                let long = a.get_long()?;
                Some((format!("--{long}"), a.get_help()?.to_string()))
            })
            .collect()
    }

    #[derive(Parser)]
    struct SceneCli {
        #[command(flatten)]
        scene: SceneArgs,
    }

    #[test]
    fn up_sets_the_camera_s_up_direction() {
        let camera = |args: &[&str]| {
            let cli =
                SceneCli::try_parse_from(std::iter::once("obscura").chain(args.iter().copied()))
                    .unwrap_or_else(|e| panic!("{args:?}: {e}"));
            let scene = obscura::scene::builtin("stairs").unwrap();
            cli.scene.camera(&scene, 1.0).unwrap()
        };
        let view = ["--eye", "5,1,0", "--target", "0,1,0"];
        assert_eq!(camera(&view).up, Vec3::Y);
        let z_up = [&view[..], &["--up", "0,0,1"]].concat();
        assert_eq!(camera(&z_up).up, Vec3::Z);
    }

    #[test]
    fn units_convert_the_defaults_world_lengths_and_flags_stay_in_scene_units() {
        let settings = |args: &[&str]| ao(args).settings(Technique::Vao).unwrap();
        let metres = settings(&[]);
        let cm = settings(&["--units", "cm"]);
        assert_eq!(cm, metres.scaled(100.0));
        assert!((cm.vao.radius - 50.0).abs() < 1e-4, "{}", cm.vao.radius);
        assert!((cm.sao.intensity - 100.0).abs() < 1e-3);
        assert!((cm.blur.sharpness - metres.blur.sharpness / 100.0).abs() < 1e-9);
        assert_eq!(settings(&["--units", "0.001"]), metres.scaled(1000.0));
        assert_eq!(settings(&["--units", "m"]), metres);
        // A radius flag is in the scene's units, over the converted defaults.
        let flagged = settings(&["--units", "cm", "--radius", "20"]);
        assert_eq!(flagged.vao.radius, 20.0);
        assert_eq!(flagged.gtao.radius, cm.gtao.radius);
        for bad in ["0", "-1", "furlong", "inf", ""] {
            let err = ao(&["--units", bad])
                .settings(Technique::Vao)
                .unwrap_err()
                .to_string();
            assert!(
                err.contains("--units") && err.contains("metres"),
                "{bad}: {err}"
            );
        }
    }

    #[test]
    fn every_settings_field_has_an_existing_flag() {
        let flags: Vec<String> = helps().into_iter().map(|(f, _)| f).collect();
        let fields = AoSettings::field_paths();
        for field in &fields {
            if field == "technique" {
                continue; // --technique / --techniques, per command
            }
            let flag = flag_for_field(field).unwrap_or_else(|| panic!("{field} has no flag"));
            assert!(
                flags.iter().any(|f| f == flag),
                "{field}: {flag} is no flag"
            );
        }
        for (field, _) in FIELD_FLAGS {
            assert!(fields.iter().any(|f| f == field), "{field} is no field");
        }
        assert_eq!(flag_for_field("vao.radius"), Some("--radius"));
        assert_eq!(flag_for_field("stochastic_depth.alpha"), Some("--sd-alpha"));
    }

    #[test]
    fn the_defaults_the_help_states_are_the_library_defaults() {
        let mut stated = 0;
        for (flag, help) in helps() {
            let Some((_, rest)) = help.split_once("[default: ") else {
                continue;
            };
            let value = rest.trim_end_matches(']');
            if flag == "--guard-band" {
                continue;
            }
            assert!(
                FIELD_FLAGS.iter().any(|(_, f)| *f == flag),
                "{flag} states a default but sets no field"
            );
            stated += 1;
            // Passing the stated default explicitly changes nothing, for every technique.
            let a = ao(&[&flag, value]);
            for t in Technique::all() {
                let want = AoSettings {
                    technique: t,
                    ..AoSettings::default()
                };
                assert_eq!(a.settings(t).unwrap(), want, "{flag} {value}");
            }
        }
        // Every field but the switches' blur.enabled (--no-blur), gtao_vb.cosine_weighted
        // (--vb-cosine), bent_normals (--bent-normals), ray_sd.z_cull (--no-z-cull),
        // ray_sd.intervals (--no-intervals), temporal.enabled (--temporal) and temporal.clamp
        // (--temporal-no-clamp), and blur.sigma (--blur-sigma) and multiview.focus (--mv-focus),
        // whose defaults are to be left out.
        assert_eq!(stated, FIELD_FLAGS.len() - 9);
        for t in Technique::all() {
            assert_eq!(
                ao(&[]).settings(t).unwrap(),
                AoSettings::preset(t, Preset::Medium)
            );
        }
    }

    #[test]
    fn preset_then_file_then_flags() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("s.toml");
        std::fs::write(
            &file,
            "[vao]\nsamples = 16\nradius = 0.75\n[stochastic_depth]\nalpha = 0.5\n",
        )
        .unwrap();
        let f = file.to_str().unwrap();
        let t = Technique::SdSvao;
        let ultra = AoSettings::preset(t, Preset::Ultra);
        assert_eq!(ao(&["--preset", "ultra"]).settings(t).unwrap(), ultra);
        // The file over the preset: its fields win, the others stay the preset's.
        let s = ao(&["--preset", "ultra", "--settings", f])
            .settings(t)
            .unwrap();
        let mut want = ultra;
        want.vao.samples = 16;
        want.vao.radius = 0.75;
        want.stochastic_depth.alpha = Some(0.5);
        assert_eq!(s, want);
        // Flags over the file.
        let s = ao(&[
            "--settings",
            f,
            "--preset",
            "ultra",
            "--samples",
            "8",
            "--blur-radius",
            "3",
            "--sd-mask",
            "discard",
            "--no-blur",
        ])
        .settings(t)
        .unwrap();
        want.vao.samples = 8;
        want.blur.radius = 3;
        want.blur.enabled = false;
        want.stochastic_depth.mask = SdMask::Discard;
        assert_eq!(s, want);
        // No preset: the file over the defaults.
        let s = ao(&["--settings", f]).settings(Technique::Vao).unwrap();
        assert_eq!((s.vao.samples, s.vao.radius, s.blur.radius), (16, 0.75, 4));
        // The command line chooses the technique, not the file.
        let other = dir.path().join("t.json");
        std::fs::write(&other, r#"{"technique": "rt-vao"}"#).unwrap();
        let s = ao(&["--settings", other.to_str().unwrap()])
            .settings(Technique::Vao)
            .unwrap();
        assert_eq!(s.technique, Technique::Vao);
    }

    #[test]
    fn one_radius_for_every_estimator_under_the_per_technique_flags() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("s.toml");
        std::fs::write(&file, "[vao]\nradius = 0.75\n[gtao]\nradius = 0.25\n").unwrap();
        let f = file.to_str().unwrap();
        // Over the preset and the file; under --hbao-radius.
        let args = ao(&[
            "--preset",
            "high",
            "--settings",
            f,
            "--ao-radius",
            "2",
            "--hbao-radius",
            "3",
        ]);
        for t in Technique::all() {
            let s = args.settings(t).unwrap();
            let want = if t.estimator() == obscura::technique::Estimator::HbaoPlus {
                3.0
            } else {
                2.0
            };
            assert_eq!(s.radius(), want, "{t}");
            // The ground truth's radius (`reference` and `compare` take `vao.radius`).
            assert_eq!(s.vao.radius, 2.0, "{t}");
        }
        for bad in ["0", "-1", "inf", "NaN"] {
            let e = ao(&["--ao-radius", bad])
                .settings(Technique::Gtao)
                .unwrap_err();
            let e = e.to_string();
            assert!(
                e.starts_with(&format!("invalid --ao-radius {bad}:")),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn errors_name_flags_for_flags_and_fields_for_files() {
        let e = ao(&["--radius", "-1"])
            .settings(Technique::Vao)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid --radius -1: must be a positive number of world units, e.g. 0.5"
        );
        let e = ao(&["--sd-alpha", "2"])
            .settings(Technique::SdVao)
            .unwrap_err();
        assert!(e.to_string().starts_with("invalid --sd-alpha 2:"), "{e}");
        let e = ao(&["--normalization", "flat"])
            .settings(Technique::Vao)
            .unwrap_err();
        assert!(
            e.to_string().starts_with("invalid --normalization flat:"),
            "{e}"
        );
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("bad.toml");
        std::fs::write(&file, "[blur]\nradius = 40\n").unwrap();
        let e = ao(&["--settings", file.to_str().unwrap()])
            .settings(Technique::Vao)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("bad.toml") && e.contains("blur.radius 40") && !e.contains("--"),
            "{e}"
        );
        assert!(Cli::try_parse_from(["obscura", "--preset", "max"]).is_err());
    }
}
