//! One shard: render its views, write each view file, then its `timings.jsonl`, then its
//! `manifest.jsonl` last, every file to a temporary name renamed into place
//! ([`crate::output::write_atomically`]). So a shard is finished exactly when its manifest
//! exists and verifies ([`verify`]): one line per view, each naming its file and the file's
//! SHA-256, all under the current spec's hash, and no temporary file left beside them. Anything
//! else (a run killed mid-shard, a deleted or truncated view file, a spec changed since) is
//! cleaned ([`clean`]) and the shard written again.

use super::plan::{self, Plan, ShardPlan};
use super::record::{self, camera_record, sha256_hex, truth_record, VERSION};
use super::spec::{Channel, Spec, Tracer};
use super::writer::{encode, Array};
use super::DatasetError;
use crate::bvh::BvhCache;
use crate::gpu::Gpu;
use crate::output::{srgb_to_linear, write_atomically};
use crate::pipeline::renderer::Renderer;
use crate::reference::gpu::GpuReferenceTracer;
use crate::reference::ground_truth::{render_reference, ReferenceSettings};
use crate::scene::{Camera, Scene};
use crate::settings::{AoSettings, Technique};
use crate::view::FrameView;
use serde_json::json;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// The shard's manifest: one JSON line per view.
pub const MANIFEST: &str = "manifest.jsonl";
/// The shard's timings: one JSON line per view (the only file that differs between runs).
pub const TIMINGS: &str = "timings.jsonl";

/// What [`run_shard`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShardStatus {
    /// Written, where nothing of it was before.
    Written,
    /// Written again over an unfinished or damaged copy.
    Redone,
    /// Already finished and verified: nothing written.
    Skipped,
}

/// The outcome of one shard (serde both ways: an executor in another process sends it back to
/// its driver as JSON, which gives it to [`super::finish`]).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct ShardReport {
    /// The shard's number.
    pub index: usize,
    /// What was done.
    pub status: ShardStatus,
    /// Its views.
    pub views: u32,
    /// Wall time, seconds.
    pub seconds: f64,
    /// Why it was redone (what [`verify`] found), for [`ShardStatus::Redone`].
    pub reason: Option<String>,
}

/// The view file of dataset view `id`, relative to the output folder.
pub fn view_file(spec: &Spec, shard: &ShardPlan, id: u64) -> String {
    format!("{}/view-{id:06}.{}", shard.name(), spec.format.extension())
}

/// Whether `name` is a temporary file of [`write_atomically`] (`.NAME.PID.partial.EXT`).
pub fn is_partial(name: &str) -> bool {
    name.starts_with('.') && name.contains(".partial.")
}

/// Checks that shard `shard` of `spec` is finished in `out`: `Err` says what is missing.
pub fn verify(spec: &Spec, shard: &ShardPlan, out: &Path) -> Result<(), String> {
    let dir = out.join(shard.name());
    let text =
        std::fs::read_to_string(dir.join(MANIFEST)).map_err(|_| "no manifest".to_string())?;
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() != shard.views as usize {
        return Err(format!(
            "manifest lists {} views of {}",
            lines.len(),
            shard.views
        ));
    }
    let hash = spec.hash();
    for (line, view) in lines.iter().zip(shard.view_indices()) {
        let record: serde_json::Value =
            serde_json::from_str(line).map_err(|e| format!("manifest line unreadable: {e}"))?;
        let id = shard.id_of(view);
        let file = view_file(spec, shard, id);
        if record["id"] != json!(id) || record["file"] != json!(file) {
            return Err(format!(
                "manifest line of view {id} does not match the plan"
            ));
        }
        if record["spec_sha256"] != json!(hash) {
            return Err("written under another spec".into());
        }
        let bytes = std::fs::read(out.join(&file)).map_err(|_| format!("{file} is missing"))?;
        if record["sha256"] != json!(sha256_hex(&bytes)) {
            return Err(format!("{file} does not match its hash"));
        }
    }
    if let Some(name) = partial_files(&dir).first() {
        return Err(format!("a temporary file is left: {name}"));
    }
    Ok(())
}

fn partial_files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| is_partial(n))
        .collect();
    names.sort();
    names
}

/// Removes what an unfinished copy of a shard left in `dir`: its manifest and timings first
/// (so it no longer counts as finished even if the rest fails), view files and temporary files.
/// Other files are not ours and stay. Returns whether anything was removed.
pub fn clean(dir: &Path) -> Result<bool, DatasetError> {
    let mut removed = false;
    let mut remove = |path: PathBuf| -> Result<(), DatasetError> {
        match std::fs::remove_file(&path) {
            Ok(()) => {
                removed = true;
                Ok(())
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
            Err(e) => Err(DatasetError::Run(format!(
                "cannot remove '{}' to redo its shard: {e}",
                path.display()
            ))),
        }
    };
    remove(dir.join(MANIFEST))?;
    remove(dir.join(TIMINGS))?;
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if is_partial(&name) || (name.starts_with("view-") && !entry.path().is_dir()) {
            remove(entry.path())?;
        }
    }
    Ok(removed)
}

/// Writes `bytes` to `path` atomically.
fn write_file(path: &Path, bytes: &[u8]) -> Result<(), DatasetError> {
    write_atomically(path, |tmp| {
        std::fs::write(tmp, bytes).map_err(|e| e.to_string())
    })
    .map_err(|e| DatasetError::Run(e.to_string()))
}

/// Runs shard `index` of `spec` on `gpu` into `out` (the dataset's folder), unless it is
/// finished there already: the unit of work an executor hands out (a thread of the local
/// executor, a Ray task). Self-contained: it needs nothing but the spec, so it runs in any
/// process; idempotent: running it again after a success skips, after a failure or a kill redoes
/// it; the same spec writes the same bytes (on the same kind of adapter). `progress(n)` is
/// called as views finish (`n` views at a time; all of them at once for a skipped shard).
pub fn run_shard(
    gpu: &Gpu,
    spec: &Spec,
    index: usize,
    out: &Path,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<ShardReport, DatasetError> {
    let start = Instant::now();
    let plan = Plan::new(spec);
    let shard = plan.shard(index)?.clone();
    let dir = out.join(shard.name());
    let report = |status, reason| ShardReport {
        index,
        status,
        views: shard.views,
        seconds: start.elapsed().as_secs_f64(),
        reason,
    };
    let reason = match verify(spec, &shard, out) {
        Ok(()) => {
            progress(u64::from(shard.views));
            return Ok(report(ShardStatus::Skipped, None));
        }
        Err(reason) => reason,
    };
    let status = if dir.is_dir() && clean(&dir)? {
        ShardStatus::Redone
    } else {
        ShardStatus::Written
    };
    std::fs::create_dir_all(&dir)
        .map_err(|e| DatasetError::Run(format!("cannot create '{}': {e}", dir.display())))?;
    write_views(gpu, spec, &shard, out, progress)?;
    Ok(report(
        status,
        (status == ShardStatus::Redone).then_some(reason),
    ))
}

thread_local! {
    /// The scene this thread loaded for its last shard, with its BVH ([`last_scene`]).
    static LAST_SCENE: RefCell<Option<(String, Arc<Scene>, BvhCache)>> = const { RefCell::new(None) };
}

/// Scene `index` of `spec` loaded, and a BVH cache for it: the ones this thread's previous
/// shard used when that shard was of the same scene (same source, options and, for a file, the
/// same size and modification time), else loaded now, replacing them. A scene's shards are
/// consecutive, and every executor runs a worker's shards on one thread (the local executor's
/// per-GPU threads, a Ray worker's task thread), so the scene is read and its BVH built about
/// once per worker instead of once per shard: with 32 views a shard on an H100 the load took
/// more time than the rays. A thread keeps one scene, until another replaces it.
fn last_scene(spec: &Spec, index: usize) -> Result<(Arc<Scene>, BvhCache), DatasetError> {
    let s = &spec.scenes[index];
    let stamp = std::fs::metadata(&s.source)
        .ok()
        .map(|m| (m.len(), m.modified().ok()));
    let key = format!(
        "{}|{}|{:?}|{:?}|{stamp:?}",
        s.source, s.allow_outside_files, s.sidedness, s.normals
    );
    if let Some((scene, bvh)) = LAST_SCENE.with_borrow(|last| {
        last.as_ref()
            .filter(|(k, _, _)| *k == key)
            .map(|(_, scene, bvh)| (scene.clone(), bvh.clone()))
    }) {
        return Ok((scene, bvh));
    }
    // Dropped first: two large scenes are never held at once.
    LAST_SCENE.set(None);
    let scene = Arc::new(plan::load_scene(spec, index)?);
    let bvh = BvhCache::new();
    LAST_SCENE.set(Some((key, scene.clone(), bvh.clone())));
    Ok((scene, bvh))
}

/// Renders and writes every view of `shard`, then its timings and manifest.
fn write_views(
    gpu: &Gpu,
    spec: &Spec,
    shard: &ShardPlan,
    out: &Path,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<(), DatasetError> {
    let load_start = Instant::now();
    let s = &spec.scenes[shard.scene];
    let (scene, bvh_cache) = last_scene(spec, shard.scene)?;
    let scene = &*scene;
    let bvh = bvh_cache.get(scene);
    let cameras = plan::cameras(spec, shard.scene, scene, &bvh, shard.view_indices())?;
    let (w, h, guard) = (spec.width, spec.height, spec.guard_band());
    // One renderer per stored row; without rows, one of VAO for the G-buffer channels.
    let mut row_settings = s.rows.clone();
    let gbuffer_only = row_settings.is_empty();
    let needs_gbuffer = spec
        .store
        .iter()
        .any(|c| matches!(c, Channel::Depth | Channel::Normals | Channel::Albedo));
    if gbuffer_only && needs_gbuffer {
        row_settings.push(
            AoSettings {
                technique: Technique::Vao,
                ..AoSettings::default()
            }
            .scaled(s.units_per_metre),
        );
    }
    let mut renderers = row_settings
        .iter()
        .map(|settings| Renderer::with_bvh_cache(gpu, scene, settings, w, h, guard, &bvh_cache))
        .collect::<Result<Vec<_>, _>>()?;
    let on_cpu = match spec.tracer {
        Tracer::Auto => gpu.summary.device_type == "Cpu",
        Tracer::Cpu => true,
        Tracer::Gpu => false,
    };
    let tracer = record::tracer_name(spec.tracer, on_cpu);
    // The scene and BVH go to the GPU and the tracer's shader is compiled once per shard, not
    // once per view.
    let gpu_tracer = if record::stores_truth(spec) && !on_cpu {
        Some(GpuReferenceTracer::new(gpu, scene, &bvh, s.truth.vao)?)
    } else {
        None
    };
    let load_ms = load_start.elapsed().as_secs_f64() * 1e3;
    let near = crate::view::near_plane(scene);
    let hash = spec.hash();
    let rows_record: serde_json::Map<String, serde_json::Value> = s
        .rows
        .iter()
        .map(|r| {
            (
                r.technique.name().to_string(),
                serde_json::to_value(r).expect("serialises"),
            )
        })
        .collect();
    // The GPU work of view n+1 overlaps the encoding, hashing and writing of view n: the
    // rendering loop below hands each view's arrays to this writer thread (at most two views
    // wait), which writes them in order and keeps the manifest and timings.
    let adapter = &gpu.summary.name;
    let write_one = |view: Rendered| -> Result<(String, String), DatasetError> {
        let Rendered {
            id,
            view,
            camera,
            arrays,
            truth,
            mut ms,
        } = view;
        let mut clock = Instant::now();
        let bytes = encode(spec.format, w, h, &arrays).map_err(DatasetError::Run)?;
        lap(&mut clock, "encode", &mut ms);
        let file = view_file(spec, shard, id);
        write_file(&out.join(&file), &bytes)?;
        lap(&mut clock, "write", &mut ms);
        let line = json!({
            "id": id,
            "shard": shard.index,
            "scene": s.source,
            "scene_index": shard.scene,
            "view": view,
            "file": file,
            "sha256": sha256_hex(&bytes),
            "bytes": bytes.len(),
            "size": [w, h],
            "guard_band": guard,
            "camera": camera_record(&camera, near),
            "arrays": record::array_names(spec),
            "truth": truth.map(|t| truth_record(&t, tracer)),
            "rows": rows_record,
            "adapter": adapter,
            "spec_sha256": hash,
            "obscura": VERSION,
        });
        let timing = json!({"id": id, "file": file, "ms": ms});
        Ok((line.to_string(), timing.to_string()))
    };
    let (manifest, mut timings) = std::thread::scope(|scope| {
        let (send, receive) = std::sync::mpsc::sync_channel::<Rendered>(2);
        let writer = scope.spawn(move || {
            let (mut manifest, mut timings) = (String::new(), String::new());
            for view in receive {
                let (line, timing) = write_one(view)?;
                manifest.push_str(&line);
                manifest.push('\n');
                timings.push_str(&timing);
                timings.push('\n');
                progress(1);
            }
            Ok::<_, DatasetError>((manifest, timings))
        });
        let rendered = (|| {
            for (camera, view) in cameras.iter().zip(shard.view_indices()) {
                let id = shard.id_of(view);
                let mut ms = serde_json::Map::new();
                let mut clock = Instant::now();
                let mut ao = Vec::new();
                for (renderer, settings) in renderers.iter_mut().zip(&row_settings) {
                    renderer.render(camera, None)?;
                    ao.push(renderer.read_ao()?);
                    lap(&mut clock, &format!("ao:{}", settings.technique), &mut ms);
                }
                let truth_settings = ReferenceSettings {
                    seed: plan::truth_seed(spec, shard.scene, view),
                    ..s.truth
                };
                let mut truth = if record::stores_truth(spec) {
                    let frame = FrameView::new(*camera, w, h, guard, near);
                    let image = match &gpu_tracer {
                        Some(tracer) => tracer.trace(frame, &truth_settings, &|_, _| {})?.0,
                        None => render_reference(scene, &bvh, frame, &truth_settings, &|_| {}),
                    };
                    lap(&mut clock, "truth", &mut ms);
                    image
                } else {
                    Vec::new()
                };
                let arrays = read_arrays(spec, &mut renderers, &row_settings, &mut ao, &mut truth)?;
                lap(&mut clock, "read", &mut ms);
                let view = Rendered {
                    id,
                    view,
                    camera: *camera,
                    arrays,
                    truth: record::stores_truth(spec).then_some(truth_settings),
                    ms,
                };
                if send.send(view).is_err() {
                    // The writer stopped on an error: it is returned below.
                    break;
                }
            }
            Ok::<_, DatasetError>(())
        })();
        drop(send);
        let written = writer.join().expect("the dataset writer thread panicked");
        rendered.and(written)
    })?;
    timings.push_str(&json!({"shard": shard.index, "load_ms": load_ms}).to_string());
    timings.push('\n');
    let dir = out.join(shard.name());
    write_file(&dir.join(TIMINGS), timings.as_bytes())?;
    // Last: its presence (verified) is what marks the shard finished.
    write_file(&dir.join(MANIFEST), manifest.as_bytes())
}

/// One view rendered and read back, on its way to the writer thread.
struct Rendered {
    id: u64,
    view: u32,
    camera: Camera,
    arrays: Vec<Array>,
    /// The truth's settings (its seed is the view's), when the spec stores it.
    truth: Option<ReferenceSettings>,
    /// Milliseconds per step so far.
    ms: serde_json::Map<String, serde_json::Value>,
}

/// Records the time since `clock` under `name` in `ms`, and restarts the clock.
fn lap(clock: &mut Instant, name: &str, ms: &mut serde_json::Map<String, serde_json::Value>) {
    ms.insert(name.into(), json!(clock.elapsed().as_secs_f64() * 1e3));
    *clock = Instant::now();
}

/// The arrays `spec` stores for one view, in its order: the G-buffer's channels read from the
/// first renderer (once for depth and normals both), `truth` and the rows' `ao` moved in.
fn read_arrays(
    spec: &Spec,
    renderers: &mut [Renderer],
    row_settings: &[AoSettings],
    ao: &mut [Vec<f32>],
    truth: &mut Vec<f32>,
) -> Result<Vec<Array>, DatasetError> {
    let (w, h, guard) = (spec.width, spec.height, spec.guard_band());
    let mut gbuffer = None;
    let mut arrays = Vec::new();
    for channel in &spec.store {
        let (components, values) = match channel {
            Channel::Depth | Channel::Normals => {
                if gbuffer.is_none() {
                    gbuffer = Some(renderers[0].read_gbuffer()?);
                }
                let g = gbuffer.as_ref().expect("read above");
                let depth = visible(&g.depth, g.width, guard, w, h);
                if *channel == Channel::Depth {
                    (1, depth)
                } else {
                    let normals = visible(&g.normals, g.width, guard, w, h);
                    // Background: no surface, no normal (the G-buffer's clear value).
                    let values = normals
                        .iter()
                        .zip(&depth)
                        .flat_map(|(n, &d)| if d > 0.0 { n.to_array() } else { [0.0; 3] })
                        .collect();
                    (3, values)
                }
            }
            Channel::Albedo => {
                let albedo = renderers[0].read_albedo()?;
                let values = albedo
                    .iter()
                    .flat_map(|c| [0, 1, 2].map(|i| srgb_to_linear(f32::from(c[i]) / 255.0)))
                    .collect();
                (3, values)
            }
            Channel::Truth => (1, std::mem::take(truth)),
            Channel::Ao(t) => {
                let i = row_settings
                    .iter()
                    .position(|r| r.technique == *t)
                    .expect("every ao row has a renderer");
                (1, std::mem::take(&mut ao[i]))
            }
        };
        arrays.push(Array {
            name: channel.array_name(),
            components,
            values,
        });
    }
    Ok(arrays)
}

/// The visible `w × h` of a framebuffer image `fw` wide with a guard band of `g`.
fn visible<T: Copy>(full: &[T], fw: u32, g: u32, w: u32, h: u32) -> Vec<T> {
    (0..h)
        .flat_map(|y| {
            let row = ((y + g) * fw + g) as usize;
            full[row..row + w as usize].iter().copied()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(normals: &str) -> Spec {
        Spec::from_toml_str(&format!(
            "size = [32, 24]\nstore = [\"depth\"]\n\n[[scenes]]\nname = \"stairs\"\nviews = 2\nnormals = \"{normals}\"\n"
        ))
        .unwrap()
    }

    #[test]
    fn a_threads_next_shard_of_the_same_scene_reuses_it_and_another_scene_replaces_it() {
        let (a, bvh) = last_scene(&spec("face"), 0).unwrap();
        let (b, _) = last_scene(&spec("face"), 0).unwrap();
        assert!(Arc::ptr_eq(&a, &b), "the same scene was loaded again");
        // The BVH cache comes along: built once for both shards.
        bvh.get(&a);
        let (_, bvh_again) = last_scene(&spec("face"), 0).unwrap();
        bvh_again.get(&a);
        assert_eq!(bvh_again.builds(), 1);
        // Other load options: another scene, loaded anew.
        let (c, _) = last_scene(&spec("shading"), 0).unwrap();
        assert!(!Arc::ptr_eq(&a, &c));
        // Another thread loads its own.
        let d = std::thread::spawn(|| last_scene(&spec("shading"), 0).unwrap().0)
            .join()
            .unwrap();
        assert!(!Arc::ptr_eq(&c, &d));
    }
}
