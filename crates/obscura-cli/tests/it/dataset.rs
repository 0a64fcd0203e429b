//! `obscura dataset` end to end (issue 59): the example spec renders, a rerun skips every shard,
//! an interrupted run resumed writes only the missing shard, and a bad spec fails with one error
//! before anything is written.

use crate::cli::{obscura, stderr};
use std::path::Path;

fn example() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/datasets/small.toml")
        .display()
        .to_string()
}

#[test]
fn the_example_spec_renders_and_a_rerun_writes_only_what_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ds");
    let out_arg = out.to_str().unwrap();
    let o = obscura(&["dataset", &example(), "--out", out_arg]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("8 views in 4 shards (4 written, 0 redone, 0 skipped)"),
        "{}",
        stderr(&o)
    );
    let manifest = std::fs::read_to_string(out.join("manifest.jsonl")).unwrap();
    assert_eq!(manifest.lines().count(), 8);

    // An interrupted run: the last shard never got its manifest.
    std::fs::remove_file(out.join("shard-00003/manifest.jsonl")).unwrap();
    std::fs::remove_file(out.join("manifest.jsonl")).unwrap();
    let o = obscura(&["dataset", &example(), "--out", out_arg]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("(0 written, 1 redone, 3 skipped)"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("manifest.jsonl")).unwrap(),
        manifest
    );
}

#[test]
fn a_bad_spec_fails_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("bad.toml");
    std::fs::write(
        &spec,
        "size = [64, 48]\n[[scenes]]\nname = \"stairs\"\nviews = 2\ncameras = \"orbit\"\n",
    )
    .unwrap();
    let out = dir.path().join("never");
    let o = obscura(&[
        "dataset",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("scenes[0].cameras") && err.contains("path:NAME"),
        "{err}"
    );
    assert_eq!(err.matches("error").count(), 1, "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists());
}
