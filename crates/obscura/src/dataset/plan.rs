//! The plan: which views go into which shard, and each view's camera. The split is arithmetic
//! on the spec alone (scenes in order, each cut into runs of `views_per_shard`; a shard never
//! holds two scenes, so it loads one); a view's camera depends only on the spec, its scene and
//! its index, so a shard computed alone in another process gets the cameras the whole plan has.

use super::camera_sampler::random_camera;
use super::spec::{CameraSource, Spec};
use super::DatasetError;
use crate::bvh::Bvh;
use crate::hash::Fnv1a;
use crate::scene::{self, Camera, Scene};

/// One shard: views `first_view .. first_view + views` of scene `scene`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardPlan {
    /// Its number, from 0, over the whole dataset.
    pub index: usize,
    /// The scene's index in the spec.
    pub scene: usize,
    /// The scene's first view in it.
    pub first_view: u32,
    /// How many views.
    pub views: u32,
    /// The dataset-wide number of its first view (view files are named by it).
    pub first_id: u64,
}

impl ShardPlan {
    /// Its folder's name: `shard-00003`.
    pub fn name(&self) -> String {
        format!("shard-{:05}", self.index)
    }

    /// The scene's view indices it holds.
    pub fn view_indices(&self) -> std::ops::Range<u32> {
        self.first_view..self.first_view + self.views
    }

    /// The dataset-wide number of the scene's view `view`.
    pub fn id_of(&self, view: u32) -> u64 {
        self.first_id + u64::from(view - self.first_view)
    }
}

/// Every shard of a spec, in order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Plan {
    /// The shards.
    pub shards: Vec<ShardPlan>,
}

impl Plan {
    /// The split of `spec` into shards (no scene is loaded: [`check_cameras`] does that).
    pub fn new(spec: &Spec) -> Plan {
        let mut shards = Vec::new();
        let mut id = 0u64;
        for (scene, s) in spec.scenes.iter().enumerate() {
            let mut first = 0;
            while first < s.views {
                let views = spec.views_per_shard.min(s.views - first);
                shards.push(ShardPlan {
                    index: shards.len(),
                    scene,
                    first_view: first,
                    views,
                    first_id: id,
                });
                first += views;
                id += u64::from(views);
            }
        }
        Plan { shards }
    }

    /// Shard `index`, or an error naming how many there are.
    pub fn shard(&self, index: usize) -> Result<&ShardPlan, DatasetError> {
        self.shards.get(index).ok_or_else(|| {
            DatasetError::Run(format!(
                "shard {index} does not exist: the spec has {} shards (0 to {})",
                self.shards.len(),
                self.shards.len().saturating_sub(1)
            ))
        })
    }
}

/// Scene `index` of `spec`, loaded with its options; errors name the spec's field.
pub fn load_scene(spec: &Spec, index: usize) -> Result<Scene, DatasetError> {
    let s = &spec.scenes[index];
    let options = scene::LoadOptions {
        allow_outside_files: s.allow_outside_files,
    };
    let fail = |problem: String| DatasetError::Spec {
        origin: String::new(),
        field: format!("scenes[{index}]"),
        problem,
    };
    let mut loaded = scene::load_with(&s.source, &options).map_err(|e| fail(e.to_string()))?;
    loaded.set_sidedness(s.sidedness);
    loaded.set_normals(s.normals);
    loaded.check_extent().map_err(|e| fail(e.to_string()))?;
    Ok(loaded)
}

/// The cameras of `views` of scene `index` (loaded as `scene`, its BVH `bvh`).
pub fn cameras(
    spec: &Spec,
    index: usize,
    scene: &Scene,
    bvh: &Bvh,
    views: std::ops::Range<u32>,
) -> Result<Vec<Camera>, DatasetError> {
    let s = &spec.scenes[index];
    let aspect = spec.width as f32 / spec.height as f32;
    let fail = |field: &str, problem: String| DatasetError::Spec {
        origin: String::new(),
        field: format!("scenes[{index}].{field}"),
        problem,
    };
    let with_fov = |mut camera: Camera| {
        if let Some(fov) = s.fov {
            camera.fov_y_deg = fov;
        }
        camera
    };
    match &s.cameras {
        CameraSource::Random {
            min_coverage,
            clearance,
        } => views
            .map(|v| {
                random_camera(
                    scene,
                    bvh,
                    (spec.seed, index, v),
                    aspect,
                    s.fov.unwrap_or(60.0),
                    (*min_coverage, *clearance),
                )
                .map_err(|e| fail("cameras", format!("view {v}: {}", e.message)))
            })
            .collect(),
        CameraSource::Scene => {
            if s.views as usize > scene.cameras.len() {
                return Err(fail(
                    "views",
                    format!(
                        "{} views, but scene '{}' has {} cameras ({}): give views = {} or fewer, \
                         or cameras = \"random\"",
                        s.views,
                        scene.name,
                        scene.cameras.len(),
                        scene
                            .cameras
                            .iter()
                            .map(|c| c.name.as_str())
                            .collect::<Vec<_>>()
                            .join(", "),
                        scene.cameras.len()
                    ),
                ));
            }
            Ok(views
                .map(|v| with_fov(scene.cameras[v as usize].camera))
                .collect())
        }
        CameraSource::Path(name) => {
            let path = scene
                .path(name, aspect)
                .map_err(|e| fail("cameras", e.to_string()))?;
            let samples = path
                .sample(s.views)
                .map_err(|e| fail("cameras", e.to_string()))?;
            Ok(views.map(|v| with_fov(samples[v as usize].1)).collect())
        }
    }
}

/// Loads every scene and finds every view's camera, before any GPU work: a scene that fails to
/// load, has too few cameras or no random camera that passes is an error here.
pub fn check_cameras(spec: &Spec) -> Result<(), DatasetError> {
    for index in 0..spec.scenes.len() {
        let scene = load_scene(spec, index)?;
        let bvh = Bvh::build(&scene);
        let views = spec.scenes[index].views;
        for camera in cameras(spec, index, &scene, &bvh, 0..views)? {
            camera.validate().map_err(|e| DatasetError::Spec {
                origin: String::new(),
                field: format!("scenes[{index}].cameras"),
                problem: e.to_string(),
            })?;
        }
    }
    Ok(())
}

/// The ground truth's seed for view `view` of scene `scene`: each view its own, so that the
/// hemisphere's per-pixel rotations differ between views (the same pattern in every image would
/// be a structure a model can learn).
pub fn truth_seed(spec: &Spec, scene: usize, view: u32) -> u64 {
    let mut h = Fnv1a::default();
    h.bytes(b"obscura.dataset.truth");
    h.bytes(&spec.seed.to_le_bytes());
    h.bytes(&spec.scenes[scene].truth.seed.to_le_bytes());
    h.bytes(&(scene as u64).to_le_bytes());
    h.bytes(&view.to_le_bytes());
    h.0
}
