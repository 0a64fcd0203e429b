//! The dataset spec (docs/DATASETS.md): a TOML file parsed into [`Spec`], every value checked
//! before any work, each problem one [`DatasetError::Spec`] naming the field's path in the file
//! (`scenes[1].views`) and what to write instead.

use super::DatasetError;
use crate::reference::ground_truth::{ReferenceModel, ReferenceSettings};
use crate::scene::{Normals, Sidedness};
use crate::settings::{line_column, units_per_metre, AoSettings, Technique};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// Largest width or height of a view: datasets are many small images; the CLI's own limit is
/// 16384, far beyond what a dataset of thousands of views can hold on disk.
pub const MAX_SIZE: u32 = 8192;
/// Most views of one scene, and most scenes: a million views is already terabytes at 1080p.
pub const MAX_VIEWS: u32 = 1_000_000;
/// Most scenes in one spec.
pub const MAX_SCENES: usize = 10_000;
/// Most hemisphere rays per pixel of the ground truth (the CLI's `--spp` bound, 2^20).
pub const MAX_SPP: u32 = 1 << 20;
/// Most views in one shard: a shard is the unit of retry, and redoing more than this after a
/// failure wastes more than it saves in files.
pub const MAX_VIEWS_PER_SHARD: u32 = 10_000;

/// What a view file can hold (the spec's `store` list).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    /// `depth`: linear view depth (world units along −Z), 0 on background.
    Depth,
    /// `normals`: view-space unit normals facing the camera (x, y, z), 0 on background.
    Normals,
    /// `albedo`: the base colour, linear RGB.
    Albedo,
    /// `truth`: the ray-traced ground-truth AO of `[truth]`.
    Truth,
    /// `ao:NAME`: the AO of technique NAME.
    Ao(Technique),
}

impl Channel {
    /// Its name in `store` (`depth`, `ao:gtao`).
    pub fn name(self) -> String {
        match self {
            Channel::Depth => "depth".into(),
            Channel::Normals => "normals".into(),
            Channel::Albedo => "albedo".into(),
            Channel::Truth => "truth".into(),
            Channel::Ao(t) => format!("ao:{t}"),
        }
    }

    /// The array's name in a view file: `depth`, `normals`, `albedo`, `truth`, `ao.NAME`
    /// (EXR channels add `.X`/`.Y`/`.Z` or `.R`/`.G`/`.B` to the three-component ones).
    pub fn array_name(self) -> String {
        match self {
            Channel::Ao(t) => format!("ao.{t}"),
            other => other.name(),
        }
    }

    fn parse(text: &str) -> Result<Channel, String> {
        match text.trim() {
            "depth" => Ok(Channel::Depth),
            "normals" => Ok(Channel::Normals),
            "albedo" => Ok(Channel::Albedo),
            "truth" => Ok(Channel::Truth),
            other => match other.strip_prefix("ao:") {
                Some(name) => name
                    .parse()
                    .map(Channel::Ao)
                    .map_err(|e| format!("{e} (write \"ao:\" and a technique, e.g. \"ao:gtao\")")),
                None => Err(format!(
                    "'{other}' is not a channel: use depth, normals, albedo, truth or ao:TECHNIQUE \
                     (e.g. \"ao:vao\")"
                )),
            },
        }
    }
}

/// The view files' format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// One multi-channel 32-bit float OpenEXR file per view.
    Exr,
    /// One NumPy `.npz` archive per view (uncompressed, as `numpy.savez` writes).
    Npz,
}

impl Format {
    /// The file extension: `exr` or `npz`.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Exr => "exr",
            Format::Npz => "npz",
        }
    }
}

/// Where a scene's views look from.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraSource {
    /// Random views inside the scene's bounds (`camera_sampler`).
    Random {
        /// Least share of a view's 16×16 probe rays that must hit a surface.
        min_coverage: f32,
        /// Least distance from the eye to any surface, as a share of the bounds' diagonal.
        clearance: f32,
    },
    /// The scene's own named cameras, in order.
    Scene,
    /// Views spread evenly along one of the scene's camera paths, first and last included.
    Path(String),
}

/// Where the ground truth is traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tracer {
    /// The CPU tracer on a software (CPU) adapter, where it is faster; the GPU otherwise (the
    /// `reference` command's rule).
    Auto,
    /// The CPU tracer (the oracle).
    Cpu,
    /// The GPU compute traversal.
    Gpu,
}

impl Tracer {
    /// `auto`, `cpu` or `gpu`.
    pub fn name(self) -> &'static str {
        match self {
            Tracer::Auto => "auto",
            Tracer::Cpu => "cpu",
            Tracer::Gpu => "gpu",
        }
    }
}

/// One scene of the spec, resolved.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneSpec {
    /// A built-in scene name or a scene file's path (relative paths from the spec's folder).
    pub source: String,
    /// Let the scene file read files outside its folder.
    pub allow_outside_files: bool,
    /// World units per metre (`units`).
    pub units_per_metre: f32,
    /// Which faces count (`sides`).
    pub sidedness: Sidedness,
    /// Which normal (`normals`).
    pub normals: Normals,
    /// How many views.
    pub views: u32,
    /// Where the views look from.
    pub cameras: CameraSource,
    /// Vertical field of view in degrees; `None`: 60 for random views, else the camera's own.
    pub fov: Option<f32>,
    /// The settings of each `ao:` row of `store`, in this scene's units.
    pub rows: Vec<AoSettings>,
    /// The ground truth's settings in this scene's units (its seed is the spec's; each view
    /// derives its own from it).
    pub truth: ReferenceSettings,
}

/// A dataset spec, parsed and validated ([`Spec::from_toml_str`], [`Spec::from_path`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// The seed every random choice derives from (cameras, the truth's per-view seeds).
    pub seed: u64,
    /// Visible size of every view, in pixels.
    pub width: u32,
    /// Visible height.
    pub height: u32,
    /// Guard band in pixels; `None`: the library's default for the height.
    pub guard_band: Option<u32>,
    /// Views per shard (a shard holds views of one scene only).
    pub views_per_shard: u32,
    /// The view files' format.
    pub format: Format,
    /// What each view file holds, in the spec's order.
    pub store: Vec<Channel>,
    /// Where the ground truth is traced (`truth.tracer`).
    pub tracer: Tracer,
    /// The scenes.
    pub scenes: Vec<SceneSpec>,
    /// The spec as canonical JSON (every resolved value, sorted keys): what the spec's hash is
    /// taken over, so comments and spelling of the file do not change it.
    pub canonical: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SpecFile {
    seed: Option<u64>,
    size: Option<[i64; 2]>,
    guard_band: Option<i64>,
    views_per_shard: Option<i64>,
    format: Option<String>,
    store: Option<Vec<String>>,
    truth: Option<TruthFile>,
    settings: Option<BTreeMap<String, toml::Value>>,
    scenes: Option<Vec<SceneFile>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TruthFile {
    model: Option<String>,
    spp: Option<i64>,
    radius: Option<f64>,
    falloff: Option<bool>,
    seed: Option<u64>,
    tracer: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Option<String>,
    path: Option<String>,
    allow_outside_files: Option<bool>,
    units: Option<String>,
    sides: Option<String>,
    normals: Option<String>,
    views: Option<i64>,
    cameras: Option<String>,
    fov: Option<f64>,
    min_coverage: Option<f64>,
    clearance: Option<f64>,
}

/// Builds the one error of a spec: `field` its path in the file, `problem` what is wrong and
/// what to write.
struct Checker<'a> {
    origin: &'a str,
}

impl Checker<'_> {
    fn fail(&self, field: impl Into<String>, problem: impl Into<String>) -> DatasetError {
        DatasetError::Spec {
            origin: self.origin.to_string(),
            field: field.into(),
            problem: problem.into(),
        }
    }

    fn count(&self, field: &str, value: i64, min: i64, max: i64) -> Result<u32, DatasetError> {
        if value < min || value > max {
            return Err(self.fail(
                field,
                format!("{value} is out of range: give a whole number from {min} to {max}"),
            ));
        }
        Ok(value as u32)
    }

    fn fraction(&self, field: &str, value: f64, max: f64) -> Result<f32, DatasetError> {
        if !(value.is_finite() && (0.0..=max).contains(&value)) {
            return Err(self.fail(
                field,
                format!("{value} is out of range: give a number from 0 to {max}"),
            ));
        }
        Ok(value as f32)
    }
}

impl Spec {
    /// Reads and validates the spec file at `path`; relative scene paths in it are taken from
    /// the file's folder.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Spec, DatasetError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| DatasetError::Spec {
            origin: path.display().to_string(),
            field: "(file)".into(),
            problem: format!("cannot read it: {e}: check the path"),
        })?;
        let base = path.parent().unwrap_or(Path::new(""));
        Self::parse(&text, &path.display().to_string(), base)
    }

    /// Parses and validates a spec given as TOML text; relative scene paths are taken from the
    /// current folder.
    pub fn from_toml_str(text: &str) -> Result<Spec, DatasetError> {
        Self::parse(text, "", Path::new(""))
    }

    fn parse(text: &str, origin: &str, base: &Path) -> Result<Spec, DatasetError> {
        let check = Checker { origin };
        let file: SpecFile = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|s| line_column(text, s.start));
            check.fail(
                at.map_or("(file)".into(), |(l, c)| format!("line {l}, column {c}")),
                format!(
                    "{} (fix the file; its fields are listed in docs/DATASETS.md)",
                    e.message().trim().replace('\n', "; ")
                ),
            )
        })?;
        let [w, h] = file.size.ok_or_else(|| {
            check.fail(
                "size",
                "missing: give the views' size, e.g. size = [320, 240]",
            )
        })?;
        let max = i64::from(MAX_SIZE);
        let width = check.count("size[0]", w, 1, max)?;
        let height = check.count("size[1]", h, 1, max)?;
        let guard_band = file
            .guard_band
            .map(|g| check.count("guard_band", g, 0, max))
            .transpose()?;
        let views_per_shard = check.count(
            "views_per_shard",
            file.views_per_shard.unwrap_or(8),
            1,
            i64::from(MAX_VIEWS_PER_SHARD),
        )?;
        let format = match file.format.as_deref().unwrap_or("exr") {
            "exr" => Format::Exr,
            "npz" => Format::Npz,
            other => {
                return Err(check.fail(
                    "format",
                    format!("'{other}' is not a format: use \"exr\" or \"npz\""),
                ))
            }
        };
        let store_names = file
            .store
            .unwrap_or_else(|| vec!["depth".into(), "normals".into(), "truth".into()]);
        if store_names.is_empty() {
            return Err(check.fail(
                "store",
                "is empty: name what each view holds, e.g. store = [\"depth\", \"truth\"]",
            ));
        }
        let mut store = Vec::new();
        for (i, name) in store_names.iter().enumerate() {
            let channel = Channel::parse(name).map_err(|p| check.fail(format!("store[{i}]"), p))?;
            if store.contains(&channel) {
                return Err(check.fail(
                    format!("store[{i}]"),
                    format!("'{name}' is listed twice: name each once"),
                ));
            }
            store.push(channel);
        }
        let techniques: Vec<Technique> = store
            .iter()
            .filter_map(|c| match c {
                Channel::Ao(t) => Some(*t),
                _ => None,
            })
            .collect();
        let settings = file.settings.unwrap_or_default();
        for name in settings.keys() {
            let known = name
                .parse::<Technique>()
                .is_ok_and(|t| techniques.contains(&t));
            if !known && name != "vao" {
                return Err(check.fail(
                    format!("settings.{name}"),
                    format!(
                        "no row \"ao:{name}\" in store: settings tables are for the stored rows \
                         (and [settings.vao] for the truth's VAO kernel)"
                    ),
                ));
            }
        }
        let truth_file = file.truth;
        if truth_file.is_some() && !store.contains(&Channel::Truth) {
            return Err(check.fail(
                "truth",
                "is set but store has no \"truth\": add it to store, or remove [truth]",
            ));
        }
        let truth_file = truth_file.unwrap_or(TruthFile {
            model: None,
            spp: None,
            radius: None,
            falloff: None,
            seed: None,
            tracer: None,
        });
        let model: ReferenceModel = truth_file
            .model
            .as_deref()
            .unwrap_or("hemisphere")
            .parse()
            .map_err(|e: String| check.fail("truth.model", e))?;
        let spp = truth_file
            .spp
            .map(|s| check.count("truth.spp", s, 1, i64::from(MAX_SPP)))
            .transpose()?;
        if model != ReferenceModel::Hemisphere && (spp.is_some() || truth_file.falloff.is_some()) {
            return Err(check.fail(
                "truth",
                "spp and falloff apply to model \"hemisphere\" only (the vao models trace every \
                 sample column exactly): remove them or use model = \"hemisphere\"",
            ));
        }
        if let Some(r) = truth_file.radius {
            if !(r.is_finite() && r > 0.0 && (r as f32).is_finite()) {
                return Err(check.fail(
                    "truth.radius",
                    format!("{r}: give a positive number of world units, e.g. 0.5"),
                ));
            }
        }
        let tracer = match truth_file.tracer.as_deref().unwrap_or("auto") {
            "auto" => Tracer::Auto,
            "cpu" => Tracer::Cpu,
            "gpu" => Tracer::Gpu,
            other => {
                return Err(check.fail(
                    "truth.tracer",
                    format!("'{other}' is not a tracer: use \"auto\", \"cpu\" or \"gpu\""),
                ))
            }
        };
        let scene_files = file.scenes.unwrap_or_default();
        if scene_files.is_empty() {
            return Err(check.fail(
                "scenes",
                "no scenes: add at least one [[scenes]] table with name = \"stairs\" (a built-in \
                 scene) or path = \"file.glb\"",
            ));
        }
        if scene_files.len() > MAX_SCENES {
            return Err(check.fail("scenes", format!("more than {MAX_SCENES} scenes")));
        }
        let mut scenes = Vec::new();
        for (i, s) in scene_files.into_iter().enumerate() {
            let at = |f: &str| format!("scenes[{i}].{f}");
            let source = match (s.name, s.path) {
                (Some(name), None) => {
                    if !crate::scene::builtin_names().contains(&name.as_str()) {
                        return Err(check.fail(
                            at("name"),
                            format!(
                                "'{name}' is not a built-in scene: use one of {} (or path = \
                                 \"FILE\" for a scene file)",
                                crate::scene::builtin_names().join(", ")
                            ),
                        ));
                    }
                    name
                }
                (None, Some(path)) => {
                    let full = base.join(&path);
                    if !full.is_file() {
                        return Err(check.fail(
                            at("path"),
                            format!(
                                "'{}' is not a file: give a .gltf, .glb or .obj file (relative \
                                 to the spec's folder)",
                                full.display()
                            ),
                        ));
                    }
                    full.display().to_string()
                }
                _ => {
                    return Err(check.fail(
                        format!("scenes[{i}]"),
                        "give exactly one of name = \"BUILT-IN\" and path = \"FILE\"",
                    ))
                }
            };
            let units_per_metre = match &s.units {
                None => 1.0,
                Some(u) => units_per_metre(u)
                    .map_err(|rule| check.fail(at("units"), format!("'{u}': {rule}")))?,
            };
            let sidedness = match s.sides.as_deref().unwrap_or("authored") {
                "authored" => Sidedness::AsAuthored,
                "double" => Sidedness::DoubleSided,
                "cull-back" => Sidedness::CullBackFaces,
                other => {
                    return Err(check.fail(
                        at("sides"),
                        format!(
                            "'{other}': use \"authored\" (the file's), \"double\" or \"cull-back\""
                        ),
                    ))
                }
            };
            let normals: Normals = s
                .normals
                .as_deref()
                .unwrap_or("shading")
                .parse()
                .map_err(|e: String| check.fail(at("normals"), e))?;
            let views = check.count(&at("views"), s.views.unwrap_or(0), 1, i64::from(MAX_VIEWS))?;
            let cameras_text = s.cameras.unwrap_or_else(|| "random".into());
            let random = cameras_text == "random";
            if !random && (s.min_coverage.is_some() || s.clearance.is_some()) {
                return Err(check.fail(
                    at("cameras"),
                    "min_coverage and clearance apply to cameras = \"random\" only: remove them",
                ));
            }
            let cameras = if random {
                CameraSource::Random {
                    min_coverage: check.fraction(
                        &at("min_coverage"),
                        s.min_coverage.unwrap_or(0.5),
                        1.0,
                    )?,
                    clearance: check.fraction(
                        &at("clearance"),
                        s.clearance.unwrap_or(0.02),
                        0.5,
                    )?,
                }
            } else if cameras_text == "scene" {
                CameraSource::Scene
            } else if let Some(name) = cameras_text.strip_prefix("path:") {
                CameraSource::Path(name.to_string())
            } else {
                return Err(check.fail(
                    at("cameras"),
                    format!(
                        "'{cameras_text}': use \"random\", \"scene\" (the scene's own cameras) or \
                         \"path:NAME\" (views along one of its paths)"
                    ),
                ));
            };
            let fov = s
                .fov
                .map(|f| {
                    if f.is_finite() && f > 0.0 && f < 180.0 {
                        Ok(f as f32)
                    } else {
                        Err(check.fail(
                            at("fov"),
                            format!("{f}: give degrees between 0 and 180, e.g. 60"),
                        ))
                    }
                })
                .transpose()?;
            let base_settings = |technique: Technique| -> Result<AoSettings, DatasetError> {
                let defaults = AoSettings {
                    technique,
                    ..AoSettings::default()
                }
                .scaled(units_per_metre);
                let name = technique.name();
                let mut s = match settings.get(name) {
                    Some(table) => defaults
                        .with_toml_unvalidated(table.clone())
                        .map_err(|p| check.fail(format!("settings.{name}"), p))?,
                    None => defaults,
                };
                s.technique = technique;
                s.validate().map_err(|e| {
                    check.fail(
                        format!("settings.{name}"),
                        format!("{e} (scene {i}'s units applied)"),
                    )
                })?;
                Ok(s)
            };
            let rows = techniques
                .iter()
                .map(|&t| base_settings(t))
                .collect::<Result<Vec<_>, _>>()?;
            let mut vao = base_settings(Technique::Vao)?.vao;
            if let Some(r) = truth_file.radius {
                // The truth's radius is given in the scene's units, as settings are.
                vao.radius = r as f32;
            }
            let defaults = ReferenceSettings::default();
            let truth = ReferenceSettings {
                model,
                vao,
                spp: spp.unwrap_or(defaults.spp),
                falloff: truth_file.falloff.unwrap_or(false),
                seed: truth_file.seed.unwrap_or(defaults.seed),
            };
            truth
                .validate()
                .map_err(|p| check.fail("truth", format!("{p} (scene {i})")))?;
            scenes.push(SceneSpec {
                source,
                allow_outside_files: s.allow_outside_files.unwrap_or(false),
                units_per_metre,
                sidedness,
                normals,
                views,
                cameras,
                fov,
                rows,
                truth,
            });
        }
        let mut spec = Spec {
            seed: file.seed.unwrap_or(0),
            width,
            height,
            guard_band,
            views_per_shard,
            format,
            store,
            tracer,
            scenes,
            canonical: String::new(),
        };
        spec.canonical = super::record::canonical_spec(&spec).to_string();
        Ok(spec)
    }

    /// The SHA-256 of [`Spec::canonical`], hex: the dataset's identity, in `dataset.json` and
    /// every manifest line (a shard written under another spec is redone).
    pub fn hash(&self) -> String {
        super::record::sha256_hex(self.canonical.as_bytes())
    }

    /// Every view of every scene.
    pub fn total_views(&self) -> u64 {
        self.scenes.iter().map(|s| u64::from(s.views)).sum()
    }

    /// The guard band the views are rendered with.
    pub fn guard_band(&self) -> u32 {
        self.guard_band
            .unwrap_or_else(|| crate::view::default_guard_band(self.height))
    }
}
