//! The local executor, and the steps before and after the shards that any executor shares:
//! [`init_out_dir`] (check the spec's scenes and cameras, write `dataset.json`),
//! [`finish`] (the merged `manifest.jsonl` and `summary.json`). Between them the shards can run
//! anywhere: [`run_local`] gives them to one thread per device of this machine; a Ray driver
//! submits [`super::run_shard`] calls as tasks.

use super::plan::{check_cameras, Plan};
use super::record::{canonical_spec, VERSION};
use super::shard::{is_partial, run_shard, verify, ShardReport, ShardStatus, MANIFEST};
use super::spec::Spec;
use super::DatasetError;
use crate::gpu::{Gpu, GpuOptions};
use crate::output::write_atomically;
use serde_json::json;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// The dataset's description in its folder: the spec, its hash and the plan.
pub const DATASET_JSON: &str = "dataset.json";
/// The end-of-run summary (counts and throughput; differs between runs).
pub const SUMMARY_JSON: &str = "summary.json";

/// What a run did.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Summary {
    /// Shards in the plan.
    pub shards: usize,
    /// Shards written where nothing was.
    pub written: usize,
    /// Shards written again over an unfinished or damaged copy.
    pub redone: usize,
    /// Shards found finished and skipped.
    pub skipped: usize,
    /// Views rendered and written in this run.
    pub views_written: u64,
    /// Views of skipped shards.
    pub views_skipped: u64,
    /// Wall time of the run, seconds.
    pub seconds: f64,
    /// Views written per second of wall time.
    pub views_per_second: f64,
    /// The adapters the shards ran on, one per worker.
    pub devices: Vec<String>,
    /// Every shard's report, in shard order.
    pub reports: Vec<ShardReport>,
}

impl Summary {
    /// The summary of `reports` (any order) over `seconds` of wall time.
    pub fn of(mut reports: Vec<ShardReport>, seconds: f64, devices: Vec<String>) -> Summary {
        reports.sort_by_key(|r| r.index);
        let count = |s| reports.iter().filter(|r| r.status == s).count();
        let views = |pred: &dyn Fn(ShardStatus) -> bool| {
            reports
                .iter()
                .filter(|r| pred(r.status))
                .map(|r| u64::from(r.views))
                .sum::<u64>()
        };
        let views_written = views(&|s| s != ShardStatus::Skipped);
        Summary {
            shards: reports.len(),
            written: count(ShardStatus::Written),
            redone: count(ShardStatus::Redone),
            skipped: count(ShardStatus::Skipped),
            views_written,
            views_skipped: views(&|s| s == ShardStatus::Skipped),
            seconds,
            views_per_second: views_written as f64 / seconds.max(1e-9),
            devices,
            reports,
        }
    }
}

/// Prepares `out` for `spec`, before any GPU work: loads every scene and finds every view's
/// camera ([`check_cameras`]: a scene that fails or a view without a camera is an error here),
/// refuses a folder that holds another spec's dataset, removes temporary files a killed run
/// left at its top, and writes `dataset.json` (the canonical spec, its hash, the plan).
/// Returns the plan. Call it once per run, in the driver, before handing out shards.
pub fn init_out_dir(spec: &Spec, out: &Path) -> Result<Plan, DatasetError> {
    check_cameras(spec)?;
    let plan = Plan::new(spec);
    let hash = spec.hash();
    let path = out.join(DATASET_JSON);
    if let Ok(text) = std::fs::read_to_string(&path) {
        let existing: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
        if existing["spec_sha256"] != json!(hash) {
            return Err(DatasetError::Run(format!(
                "'{}' holds another dataset (its dataset.json has another spec hash): give a new \
                 --out folder, or delete that one to start over",
                out.display()
            )));
        }
    }
    std::fs::create_dir_all(out).map_err(|e| {
        DatasetError::Run(format!(
            "cannot create output folder '{}': {e}: check the path and permissions",
            out.display()
        ))
    })?;
    for entry in std::fs::read_dir(out).into_iter().flatten().flatten() {
        if is_partial(&entry.file_name().to_string_lossy()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
    let shards: Vec<_> = plan
        .shards
        .iter()
        .map(|s| {
            json!({
                "index": s.index,
                "name": s.name(),
                "scene": s.scene,
                "first_view": s.first_view,
                "views": s.views,
                "first_id": s.first_id,
            })
        })
        .collect();
    let record = json!({
        "obscura": VERSION,
        "spec_sha256": hash,
        "spec": canonical_spec(spec),
        "views": spec.total_views(),
        "shards": shards,
    });
    let text = serde_json::to_string_pretty(&record).expect("JSON") + "\n";
    write_atomically(&path, |tmp| {
        std::fs::write(tmp, &text).map_err(|e| e.to_string())
    })
    .map_err(|e| DatasetError::Run(e.to_string()))?;
    Ok(plan)
}

/// After every shard ran: verifies each, writes the merged `manifest.jsonl` (every shard's
/// manifest in shard order: every view once, the same bytes on every run) and `summary.json`.
/// An unfinished shard is an error naming it (and the merged manifest is not written).
pub fn finish(
    spec: &Spec,
    out: &Path,
    reports: Vec<ShardReport>,
    seconds: f64,
    devices: Vec<String>,
) -> Result<Summary, DatasetError> {
    let plan = Plan::new(spec);
    let mut merged = String::new();
    for shard in &plan.shards {
        verify(spec, shard, out).map_err(|why| {
            DatasetError::Run(format!(
                "shard {} is not finished ({why}): run the dataset again to finish it",
                shard.index
            ))
        })?;
        let text = std::fs::read_to_string(out.join(shard.name()).join(MANIFEST))
            .map_err(|e| DatasetError::Run(e.to_string()))?;
        merged.push_str(&text);
    }
    let write = |name: &str, text: &str| {
        write_atomically(&out.join(name), |tmp| {
            std::fs::write(tmp, text).map_err(|e| e.to_string())
        })
        .map_err(|e| DatasetError::Run(e.to_string()))
    };
    write(MANIFEST, &merged)?;
    let summary = Summary::of(reports, seconds, devices);
    let mut text = serde_json::to_string_pretty(&summary).expect("JSON");
    text.push('\n');
    write(SUMMARY_JSON, &text)?;
    Ok(summary)
}

/// Runs the whole dataset on this machine: [`init_out_dir`], then every shard on one worker
/// thread per device ([`Gpu::all`] with `options`, at most `max_devices` of them), each taking
/// the next shard not yet taken, then [`finish`]. `progress(n)` is called from the workers as
/// views finish or are found finished. The first failing shard stops the others from taking new
/// shards; its error is returned after they finish the one they hold.
pub fn run_local(
    spec: &Spec,
    out: &Path,
    options: &GpuOptions,
    max_devices: Option<usize>,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<Summary, DatasetError> {
    let start = Instant::now();
    let plan = init_out_dir(spec, out)?;
    let mut gpus = Gpu::all(options).map_err(crate::error::Error::from)?;
    gpus.truncate(max_devices.unwrap_or(usize::MAX).max(1));
    let devices: Vec<String> = gpus.iter().map(|g| g.summary.name.clone()).collect();
    let next = AtomicUsize::new(0);
    let failed = AtomicBool::new(false);
    let reports = Mutex::new(Vec::new());
    let error: Mutex<Option<DatasetError>> = Mutex::new(None);
    std::thread::scope(|scope| {
        for gpu in &gpus {
            scope.spawn(|| loop {
                if failed.load(Ordering::SeqCst) {
                    break;
                }
                let index = next.fetch_add(1, Ordering::SeqCst);
                if index >= plan.shards.len() {
                    break;
                }
                match run_shard(gpu, spec, index, out, progress) {
                    Ok(report) => reports.lock().unwrap().push(report),
                    Err(e) => {
                        failed.store(true, Ordering::SeqCst);
                        error
                            .lock()
                            .unwrap()
                            .get_or_insert(DatasetError::Run(format!("shard {index}: {e}")));
                        break;
                    }
                }
            });
        }
    });
    if let Some(e) = error.into_inner().unwrap() {
        return Err(e);
    }
    let reports = reports.into_inner().unwrap();
    finish(spec, out, reports, start.elapsed().as_secs_f64(), devices)
}
