//! Datasets (issue 59, docs/DATASETS.md): many views of many scenes rendered into files for
//! training and evaluation: G-buffer channels, any technique's AO and the ray-traced ground
//! truth, described by a TOML spec.
//!
//! The run is split into shards ([`Plan`]), each a self-contained unit of work
//! ([`run_shard`]: one process or thread, one device) written atomically, its manifest last; the
//! same spec writes the same bytes (timings apart, which go to their own files), a rerun skips
//! finished shards and redoes damaged ones. Executors: [`run_local`] (a thread per device of
//! this machine); any other (Ray) calls [`init_out_dir`], then [`run_shard`] for every shard
//! index wherever it likes, then [`finish`].
//!
//! - `spec.rs`: the spec's fields and their checks;
//! - `plan.rs`: shards, scenes, each view's camera and seeds;
//! - `camera_sampler.rs`: random views inside a scene;
//! - `writer.rs`: EXR and NPZ bytes;
//! - `record.rs`: manifest and `dataset.json` records, hashes;
//! - `shard.rs`: one shard: render, write, verify, clean;
//! - `local.rs`: the local executor and the steps around the shards.

pub mod camera_sampler;
mod local;
mod plan;
mod record;
mod shard;
mod spec;
mod writer;

pub use local::{finish, init_out_dir, run_local, Summary, DATASET_JSON, SUMMARY_JSON};
pub use plan::{cameras, check_cameras, load_scene, truth_seed, Plan, ShardPlan};
pub use record::{sha256_hex, VERSION};
pub use shard::{
    clean, is_partial, run_shard, verify, view_file, ShardReport, ShardStatus, MANIFEST, TIMINGS,
};
pub use spec::{
    CameraSource, Channel, Format, SceneSpec, Spec, Tracer, MAX_SCENES, MAX_SIZE, MAX_SPP,
    MAX_VIEWS, MAX_VIEWS_PER_SHARD,
};

/// What can go wrong with a dataset.
#[derive(Debug, thiserror::Error)]
pub enum DatasetError {
    /// The spec is wrong (found before any work): `field` is its path in the spec
    /// (`scenes[1].views`), `problem` what is wrong and what to write instead.
    #[error("dataset spec{}: {field}: {problem}", if origin.is_empty() { String::new() } else { format!(" '{origin}'") })]
    Spec {
        /// The spec file, or empty for a spec given as text.
        origin: String,
        /// The field's path in the spec (or where the parser stopped).
        field: String,
        /// What is wrong, and the fix.
        problem: String,
    },
    /// Rendering or writing failed.
    #[error(transparent)]
    Obscura(#[from] crate::error::Error),
    /// Anything else while running (a folder that cannot be written, a shard that does not
    /// exist), with what to do.
    #[error("{0}")]
    Run(String),
}
