//! `obscura dataset SPEC --out DIR`: render a dataset (docs/DATASETS.md) with the library's
//! local executor, one worker per GPU; progress and a summary on stderr.

use anyhow::Result;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use obscura::dataset::{self, Spec};
use std::path::PathBuf;

#[derive(Args)]
pub struct DatasetArgs {
    /// The dataset spec (TOML; docs/DATASETS.md lists its fields).
    spec: PathBuf,
    /// Output folder: dataset.json, shard-NNNNN/ folders, manifest.jsonl and summary.json. A
    /// rerun into the same folder skips finished shards and redoes unfinished ones.
    #[arg(long)]
    out: PathBuf,
    /// Use at most this many GPUs (default: every GPU of the kind `--adapter` selects).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    devices: Option<u32>,
}

pub fn run(options: &obscura::GpuOptions, args: &DatasetArgs) -> Result<()> {
    // The spec and its scenes and cameras are checked before the output folder or a GPU.
    let spec = Spec::from_path(&args.spec)?;
    if args.out.is_file() {
        anyhow::bail!(
            "--out '{}' is a file: give a folder for the dataset",
            args.out.display()
        );
    }
    let bar = ProgressBar::new(spec.total_views());
    bar.set_style(
        ProgressStyle::with_template(
            "dataset [{bar:30}] {pos}/{len} views {per_sec} {elapsed_precise} eta {eta}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    let summary = dataset::run_local(
        &spec,
        &args.out,
        options,
        args.devices.map(|n| n as usize),
        &|n| bar.inc(n),
    );
    bar.finish_and_clear();
    let summary = summary?;
    eprintln!(
        "dataset: {} views in {} shards ({} written, {} redone, {} skipped) on {}: {} views \
         written in {:.1} s = {:.2} views/s; {}",
        summary.views_written + summary.views_skipped,
        summary.shards,
        summary.written,
        summary.redone,
        summary.skipped,
        summary.devices.join(", "),
        summary.views_written,
        summary.seconds,
        summary.views_per_second,
        args.out.join(dataset::MANIFEST).display()
    );
    Ok(())
}
