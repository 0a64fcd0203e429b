//! Parsers and shared option groups for the subcommands.

pub use crate::setting_flags::for_user;
use crate::setting_flags::{named, SettingFlags};
use anyhow::{bail, Context, Result};
use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::Args;
use glam::{DVec3, Vec3};
use obscura::scene::{self, Camera, Normals, Scene, Sidedness};
use obscura::settings::{AoSettings, Preset, SettingsError};
use obscura::Technique;
use std::path::PathBuf;

/// Most frames any `--frames`, `--warmup`, `--timing-frames` or `--offscreen-frames` takes: more
/// than an hour of frames at 30 per second, far beyond any timing or path, and small enough that
/// counts derived from it (warm-up plus timed frames, one record per frame) cannot overflow or
/// fill memory (issue 62, defect 5: `path --frames 1000000000` aborted allocating).
pub const MAX_FRAME_COUNT: i64 = 100_000;

/// Most rays per pixel `--spp` takes (2^20): a thousand times the default of 1024, hours of
/// tracing already at small sizes.
pub const MAX_SPP: i64 = 1 << 20;

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
    parse_dvec3(s).map(|v| v.as_vec3())
}

/// [`parse_vec3`] in f64: a point given in a scene file's coordinates, which may lie too far from
/// its origin for f32 to hold (the scene is then re-centred: `Scene::from_file_point`).
pub fn parse_dvec3(s: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("'{s}' is not x,y,z (e.g. 0,1.5,4)"));
    }
    let mut v = [0.0f64; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        // Finite in f32 too: every point ends up in f32.
        *slot = p
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite() && (*x as f32).is_finite())
            .ok_or_else(|| format!("'{p}' in '{s}' is not a finite number"))?;
    }
    Ok(DVec3::from_array(v))
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

/// `--help` headings of the options every command that renders shares (set per field: a
/// struct's `next_help_heading` would carry over to the command's own options after it).
const SCENE_HEADING: &str = "Scene and camera";
const SETTINGS_HEADING: &str = "Presets, settings files and units";

/// Which scene and from where.
#[derive(Args, Clone, Debug)]
pub struct SceneArgs {
    /// Built-in scene name (see `obscura scenes`) or a .gltf/.glb/.obj file.
    #[arg(long, default_value = "stairs", help_heading = SCENE_HEADING)]
    pub scene: String,
    /// A named camera of the scene (default: its first, the close-up).
    #[arg(long, conflicts_with_all = ["eye", "target"], help_heading = SCENE_HEADING)]
    pub camera: Option<String>,
    /// Camera position x,y,z (with --target), in the scene file's coordinates.
    #[arg(long, value_parser = parse_dvec3, requires = "target", allow_hyphen_values = true,
          help_heading = SCENE_HEADING)]
    pub eye: Option<DVec3>,
    /// Point looked at x,y,z (with --eye), in the scene file's coordinates.
    #[arg(long, value_parser = parse_dvec3, requires = "eye", allow_hyphen_values = true,
          help_heading = SCENE_HEADING)]
    pub target: Option<DVec3>,
    /// The image's up direction x,y,z (with --eye; default +Y, or ∓Z looking straight down or
    /// up): 0,0,1 for a scene modelled Z up, as CAD and 3ds Max exports are.
    #[arg(long, value_parser = parse_vec3, requires = "eye", allow_hyphen_values = true,
          help_heading = SCENE_HEADING)]
    pub up: Option<Vec3>,
    /// Vertical field of view of the visible image in degrees (default: the camera's, or 60).
    #[arg(long, allow_hyphen_values = true, help_heading = SCENE_HEADING)]
    pub fov: Option<f32>,
    /// Count both sides of every triangle (G-buffer, stochastic depth map and rays alike). The
    /// default keeps what the file says: glTF's per-material doubleSided; OBJ is double-sided.
    #[arg(long, conflicts_with = "cull_back_faces", help_heading = SCENE_HEADING)]
    pub double_sided: bool,
    /// Cull back faces of every material that is not alpha-tested, whatever the file says.
    #[arg(long, help_heading = SCENE_HEADING)]
    pub cull_back_faces: bool,
    /// The normal AO is computed around, in the G-buffer and the reference alike: 'shading' (the
    /// file's vertex normals interpolated, as engines and offline renderers do; face normals
    /// where a mesh has none, as the built-in scenes) or 'face' (the triangle's, as the papers
    /// and their tables do).
    #[arg(
        long,
        default_value = "shading",
        value_parser = PossibleValuesParser::new(["face", "shading"])
            .map(|s| s.parse::<Normals>().expect("a listed value")),
        help_heading = SCENE_HEADING
    )]
    pub normals: Normals,
    /// Let the scene file read the files it refers to (glTF buffers and images, OBJ material
    /// libraries and textures) outside its own folder. Off by default, so that a scene from
    /// elsewhere reads nothing but what came with it.
    #[arg(long, help_heading = SCENE_HEADING)]
    pub allow_outside_files: bool,
}

impl SceneArgs {
    pub fn load(&self) -> Result<Scene> {
        let options = scene::LoadOptions {
            allow_outside_files: self.allow_outside_files,
        };
        let mut scene = scene::load_with(&self.scene, &options)?;
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
                // The file's coordinates: a scene far from its origin was re-centred on load.
                let (eye, target) = (scene.from_file_point(eye), scene.from_file_point(target));
                let mut camera = Camera::new(eye, target, self.fov.unwrap_or(60.0))?;
                camera.up = self.up.unwrap_or(camera.up);
                camera
            }
            _ => match obscura::bvh::framing::default_camera(scene, aspect) {
                (camera, Some(placement)) => say_auto_camera(scene, &camera, placement),
                (camera, None) => camera,
            },
        };
        if let Some(fov) = self.fov {
            camera.fov_y_deg = fov;
        }
        camera.validate()?;
        Ok(camera)
    }
}

/// The camera of a scene that names none ([`obscura::bvh::framing::auto_camera`]: inside a room,
/// otherwise framing the bounds), said on stderr in the file's coordinates so that it can be kept
/// or changed with `--eye`/`--target`.
fn say_auto_camera(
    scene: &Scene,
    camera: &Camera,
    placement: obscura::bvh::framing::Placement,
) -> Camera {
    // Shortest round-trip digits, so that passing them back gives this very camera.
    let file = |p: glam::Vec3| {
        if scene.origin == DVec3::ZERO {
            format!("{},{},{}", p.x, p.y, p.z)
        } else {
            let q = scene.origin + p.as_dvec3();
            format!("{},{},{}", q.x, q.y, q.z)
        }
    };
    eprintln!(
        "note: '{}' names no camera: an automatic camera {} it, --eye {} --target {} --fov {}",
        scene.name,
        placement.name(),
        file(camera.eye),
        file(camera.target),
        camera.fov_y_deg
    );
    *camera
}

/// Technique parameters. Precedence: defaults < `--preset` < `--settings FILE` < the other flags
/// (only the flags given are applied).
#[derive(Args, Clone, Debug)]
pub struct AoArgs {
    /// Quality preset for each technique (docs/SETTINGS.md lists what each sets; medium = the
    /// defaults).
    #[arg(long, value_parser = PossibleValuesParser::new(Preset::ALL.map(Preset::name))
        .map(|s| s.parse::<Preset>().expect("a listed preset")),
        help_heading = SETTINGS_HEADING)]
    pub preset: Option<Preset>,
    /// Settings file, .toml or .json (docs/SETTINGS.md): applied over the preset; the flags
    /// below override it.
    #[arg(long, value_name = "FILE", help_heading = SETTINGS_HEADING)]
    pub settings: Option<PathBuf>,
    /// One world radius R for every technique's estimator and for the ground truth (compare
    /// techniques at the same distance, or against an outside renderer's AO of that distance);
    /// each estimator reads R its own way (docs/SETTINGS.md). Applied over the preset and the
    /// file; the per-technique radius flags (--radius, --hbao-radius, …) override it.
    #[arg(long, allow_hyphen_values = true, help_heading = SETTINGS_HEADING)]
    pub ao_radius: Option<f32>,
    /// The length of one world unit of the scene: metres as a number (0.0254 for inches), or
    /// m, cm, mm, km, in, ft. The defaults and presets assume metres (glTF's unit); with
    /// `--units cm` every one of their world lengths (the radii, thicknesses, SAO's bias; the
    /// blur's sharpness per world unit) is converted, so an outside scene in
    /// centimetres gets the same AO as in metres (`AoSettings::scaled`). A settings file and
    /// the flags below are read in the scene's own units, over the converted defaults.
    #[arg(long, value_name = "UNIT", allow_hyphen_values = true,
          help_heading = SETTINGS_HEADING)]
    pub units: Option<String>,
    /// Every settings field's flag (made from the library's knobs: `setting_flags`).
    #[command(flatten)]
    pub fields: SettingFlags,
    /// Guard band in pixels around the visible image (default: 64 at 1080p, scaled).
    #[arg(long, help_heading = SETTINGS_HEADING)]
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
        self.fields.apply(&mut s)?;
        // The preset and the file were valid: anything invalid now came from a flag (a rule
        // between fields), named as it was typed.
        s.validate().map_err(|e| {
            let flag = match &e {
                SettingsError::Invalid { field, .. } => self.fields.given_for(field),
                _ => None,
            };
            named(e, flag)
        })?;
        Ok(s)
    }

    pub fn guard_band(&self, height: u32) -> u32 {
        self.guard_band
            .unwrap_or_else(|| obscura::default_guard_band(height))
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
/// The warning every command that shows timings gives on a CPU (software) adapter, such as
/// Mesa's lavapipe: its numbers are the CPU's and rank nothing about a GPU.
pub fn software_timings_warning(gpu: &obscura::Gpu) -> Option<String> {
    (gpu.summary.device_type == "Cpu").then(|| {
        format!(
            "adapter '{}' is a CPU (software) device: these are not GPU timings; run on a GPU \
             for numbers worth reporting",
            gpu.summary.name
        )
    })
}

/// Makes `out` an existing, writable folder (created if missing) before any slow work; `holds`
/// says what goes into it, for the message when `out` is a file. The folders it had to create are
/// removed again, if still empty, when the returned guard is dropped before [`OutFolder::keep`]:
/// a run that fails on its input (a scene, a camera, a reference image) leaves no empty folder.
pub fn prepare_out_folder(out: &std::path::Path, holds: &str) -> Result<OutFolder> {
    if out.is_file() {
        anyhow::bail!(
            "--out '{}' is a file: give a folder for {holds}",
            out.display()
        );
    }
    // The folders create_dir_all will make, deepest first.
    let created: Vec<std::path::PathBuf> = out
        .ancestors()
        .take_while(|p| !p.as_os_str().is_empty() && !p.exists())
        .map(|p| p.to_path_buf())
        .collect();
    std::fs::create_dir_all(out).with_context(|| {
        format!(
            "cannot create output folder '{}': check the path and permissions",
            out.display()
        )
    })?;
    let folder = OutFolder { created };
    let probe = out.join(format!(".obscura-write-test-{}", std::process::id()));
    std::fs::write(&probe, b"")
        .with_context(|| format!("output folder '{}' is not writable", out.display()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(folder)
}

/// The output folders a command created; see [`prepare_out_folder`].
#[must_use = "dropping it removes the folders it created: call keep() once the output is written"]
pub struct OutFolder {
    created: Vec<std::path::PathBuf>,
}

impl OutFolder {
    /// The command wrote its output: the folders stay.
    pub fn keep(mut self) {
        self.created.clear();
    }
}

impl Drop for OutFolder {
    fn drop(&mut self) {
        // remove_dir removes empty folders only: whatever was written stays.
        for dir in &self.created {
            if std::fs::remove_dir(dir).is_err() {
                break;
            }
        }
    }
}

/// Renders one frame of a frame loop (`path`, `bench`'s warm-up, `compare`'s timed frames,
/// the viewer). Under a time budget (`hemisphere.time_budget`) the frame is timed and the ray
/// budget follows its GPU time ([`obscura::TimeBudget`]); its timings are returned then.
pub fn render_frame(
    gpu: &obscura::Gpu,
    renderer: &mut obscura::Renderer,
    camera: &obscura::scene::Camera,
) -> Result<Option<obscura::gpu::FrameTimings>> {
    let settings = renderer.settings();
    if !(settings.hemisphere.time_budget > 0.0 && settings.ray_budget_active()) {
        renderer.render(camera, None)?;
        return Ok(None);
    }
    let mut profiler = obscura::PassProfiler::new(gpu, 1).map_err(|e| {
        anyhow::anyhow!(
            "--time-budget follows the GPU's timestamps, and {e}: use --ray-budget (rays a \
             frame) instead"
        )
    })?;
    renderer.render(camera, Some(&mut profiler))?;
    let timings = profiler.read(gpu)?.pop().unwrap_or_default();
    if let Some(ao) = renderer.ambient_occlusion() {
        ao.follow_time_budget(&timings)?;
    }
    Ok(Some(timings))
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
#[path = "args_tests.rs"]
mod tests;
