//! Datasets (issue 59): a spec's mistakes are one error naming the field before any work; the
//! same spec writes the same bytes; a rerun skips finished shards and redoes only damaged ones;
//! the merged manifest lists every view once; NPZ archives hold what numpy reads.

use obscura::dataset::{self, ShardStatus, Spec};
use obscura::GpuOptions;
use std::collections::BTreeMap;
use std::path::Path;

/// 2 built-in scenes × 4 views in shards of 2, everything stored: the issue's test size.
const SMALL: &str = r#"
seed = 3
size = [64, 48]
views_per_shard = 2
store = ["depth", "normals", "albedo", "truth", "ao:vao"]
[truth]
spp = 8
radius = 0.5
[[scenes]]
name = "stairs"
views = 4
[[scenes]]
name = "cornell"
views = 4
cameras = "path:pan"
"#;

fn run(spec: &Spec, out: &Path) -> dataset::Summary {
    dataset::run_local(spec, out, &GpuOptions::default(), Some(1), &|_| {}).unwrap()
}

/// Every file under `dir` (relative path → bytes), but the two that hold timings.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
                if !rel.ends_with(dataset::TIMINGS) && rel != dataset::SUMMARY_JSON {
                    out.insert(rel, std::fs::read(&p).unwrap());
                }
            }
        }
    }
    out
}

fn spec_error(text: &str) -> String {
    Spec::from_toml_str(text).unwrap_err().to_string()
}

#[test]
fn a_bad_spec_is_one_error_naming_the_field() {
    let ok = "size = [64, 48]\n[[scenes]]\nname = \"stairs\"\nviews = 2\n";
    Spec::from_toml_str(ok).unwrap();
    for (text, needles) in [
        (format!("{ok}colour = 1\n"), vec!["unknown field `colour`"]),
        (
            ok.replace("[64, 48]", "[0, 48]"),
            vec!["size[0]", "from 1 to 8192"],
        ),
        (
            ok.replace("views = 2", "views = 0"),
            vec!["scenes[0].views"],
        ),
        (
            format!("store = [\"depth\", \"ao:vaoo\"]\n{ok}"),
            vec!["store[1]", "vaoo"],
        ),
        (
            format!("store = [\"depth\"]\n{ok}[truth]\nspp = 4\n"),
            vec!["truth", "add it to store"],
        ),
        (
            format!("{ok}[truth]\nspp = 2000000\n"),
            vec!["truth.spp", "1048576"],
        ),
        (
            ok.replace("\"stairs\"", "\"stair\""),
            vec!["scenes[0].name", "stairs"],
        ),
        (format!("format = \"png\"\n{ok}"), vec!["format", "npz"]),
        (
            format!("{ok}units = \"furlong\"\n"),
            vec!["scenes[0].units"],
        ),
        (
            format!("store = [\"ao:gtao\"]\n{ok}[settings.gtao]\ngtao.slices = 99\n"),
            vec!["settings.gtao", "gtao.slices"],
        ),
        (
            format!("store = [\"ao:gtao\"]\n{ok}[settings.hbao]\n"),
            vec!["settings.hbao", "no row"],
        ),
    ] {
        let err = spec_error(&text);
        for n in needles {
            assert!(err.contains(n), "'{n}' not in: {err}");
        }
    }
    // Found by loading the scene, still before any GPU work: the Cornell box has 2 cameras.
    let three = ok
        .replace("stairs", "cornell")
        .replace("views = 2", "views = 3\ncameras = \"scene\"");
    let spec = Spec::from_toml_str(&three).unwrap();
    let err = dataset::check_cameras(&spec).unwrap_err().to_string();
    assert!(
        err.contains("scenes[0].views") && err.contains("2 cameras"),
        "{err}"
    );
}

#[test]
fn random_cameras_are_deterministic_and_see_the_scene() {
    let spec = Spec::from_toml_str(SMALL).unwrap();
    let scene = dataset::load_scene(&spec, 0).unwrap();
    let bvh = obscura::bvh::Bvh::build(&scene);
    let all = dataset::cameras(&spec, 0, &scene, &bvh, 0..4).unwrap();
    // A view's camera does not depend on the others computed with it (shards compute theirs
    // alone).
    let alone = dataset::cameras(&spec, 0, &scene, &bvh, 2..3).unwrap();
    assert_eq!(all[2], alone[0]);
    let bounds = scene.bounds();
    for c in &all {
        assert!(
            c.eye.cmpge(bounds.min).all() && c.eye.cmple(bounds.max).all(),
            "{c:?}"
        );
    }
    assert_ne!(all[0], all[1]);
}

#[test]
fn same_spec_same_bytes_and_a_rerun_redoes_only_damaged_shards() {
    let spec = Spec::from_toml_str(SMALL).unwrap();
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let first = run(&spec, a.path());
    assert_eq!(
        (first.shards, first.written, first.views_written),
        (4, 4, 8)
    );
    run(&spec, b.path());
    let written = files(a.path());
    assert_eq!(written, files(b.path()), "two runs of one spec differ");

    // The merged manifest: every view once, in order, each file's hash right.
    let manifest = std::fs::read_to_string(a.path().join(dataset::MANIFEST)).unwrap();
    let lines: Vec<serde_json::Value> = manifest
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let ids: Vec<u64> = lines.iter().map(|l| l["id"].as_u64().unwrap()).collect();
    assert_eq!(ids, (0..8).collect::<Vec<_>>());
    for l in &lines {
        let bytes = &written[l["file"].as_str().unwrap()];
        assert_eq!(l["sha256"], dataset::sha256_hex(bytes).as_str());
        assert_eq!(l["obscura"], dataset::VERSION);
        assert_eq!(l["truth"]["spp"], 8);
    }
    // The view file holds the stored arrays as EXR channels, at the spec's size.
    let exr =
        exr::prelude::read_all_flat_layers_from_file(a.path().join("shard-00000/view-000000.exr"))
            .unwrap();
    let layer = &exr.layer_data[0];
    let names: Vec<String> = layer
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    for n in ["depth", "normals.X", "albedo.R", "truth", "ao.vao"] {
        assert!(names.contains(&n.to_string()), "{n} not in {names:?}");
    }
    assert_eq!((layer.size.width(), layer.size.height()), (64, 48));
    let channel = |name: &str| -> Vec<f32> {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .unwrap();
        c.sample_data.values_as_f32().collect()
    };
    // The random view sees the scene (the sampler's coverage rule), and the truth there is not
    // all unoccluded.
    let (depth, truth) = (channel("depth"), channel("truth"));
    let covered: Vec<f32> = truth
        .iter()
        .zip(&depth)
        .filter(|(_, &d)| d > 0.0)
        .map(|(&t, _)| t)
        .collect();
    assert!(
        covered.len() > depth.len() / 4,
        "{} of {} covered",
        covered.len(),
        depth.len()
    );
    assert!(covered.iter().sum::<f32>() / (covered.len() as f32) < 0.99);

    // Damage three shards: a view file deleted, one truncated, a temporary file left behind
    // (as a killed run leaves it). Shard 0 stays finished.
    let untouched = a.path().join("shard-00000").join(dataset::MANIFEST);
    let before = std::fs::metadata(&untouched).unwrap().modified().unwrap();
    std::fs::remove_file(a.path().join("shard-00001/view-000002.exr")).unwrap();
    let truncated = a.path().join("shard-00002/view-000005.exr");
    let len = std::fs::metadata(&truncated).unwrap().len();
    std::fs::OpenOptions::new()
        .write(true)
        .open(&truncated)
        .unwrap()
        .set_len(len / 2)
        .unwrap();
    let stray = a
        .path()
        .join("shard-00003/.view-000006.exr.999.partial.exr");
    std::fs::write(&stray, b"half").unwrap();
    let again = run(&spec, a.path());
    let status: Vec<ShardStatus> = again.reports.iter().map(|r| r.status).collect();
    assert_eq!(
        status,
        [
            ShardStatus::Skipped,
            ShardStatus::Redone,
            ShardStatus::Redone,
            ShardStatus::Redone
        ]
    );
    assert_eq!((again.views_written, again.views_skipped), (6, 2));
    assert!(again.reports[1]
        .reason
        .as_deref()
        .unwrap()
        .contains("missing"));
    assert!(again.reports[2].reason.as_deref().unwrap().contains("hash"));
    assert!(again.reports[3]
        .reason
        .as_deref()
        .unwrap()
        .contains("temporary"));
    assert!(!stray.exists());
    assert_eq!(
        std::fs::metadata(&untouched).unwrap().modified().unwrap(),
        before
    );
    assert_eq!(
        files(a.path()),
        written,
        "the redone shards differ from the first run"
    );

    // A third run finds everything finished.
    let third = run(&spec, a.path());
    assert_eq!((third.skipped, third.views_written), (4, 0));
}

#[test]
fn a_shard_runs_alone_and_a_killed_one_is_redone_without_leftovers() {
    let spec = Spec::from_toml_str(&SMALL.replace("\"ao:vao\"]", "\"ao:vao\"]\nformat = \"npz\""))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path();
    dataset::init_out_dir(&spec, out).unwrap();
    let gpu = obscura::Gpu::new(&GpuOptions::default()).unwrap();
    // What a task killed mid-shard leaves: one view file, a temporary file, no manifest.
    let shard = out.join("shard-00002");
    std::fs::create_dir_all(&shard).unwrap();
    std::fs::write(shard.join("view-000004.npz"), b"old").unwrap();
    std::fs::write(shard.join(".view-000005.npz.4242.partial.npz"), b"half").unwrap();
    let report = dataset::run_shard(&gpu, &spec, 2, out, &|_| {}).unwrap();
    assert_eq!(report.status, ShardStatus::Redone);
    let mut names: Vec<String> = std::fs::read_dir(&shard)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "manifest.jsonl",
            "timings.jsonl",
            "view-000004.npz",
            "view-000005.npz"
        ]
    );
    // Again: finished, skipped; the same bytes as a second folder's copy of that shard.
    let again = dataset::run_shard(&gpu, &spec, 2, out, &|_| {}).unwrap();
    assert_eq!(again.status, ShardStatus::Skipped);
    let other = tempfile::tempdir().unwrap();
    dataset::run_shard(&gpu, &spec, 2, other.path(), &|_| {}).unwrap();
    for name in ["manifest.jsonl", "view-000004.npz", "view-000005.npz"] {
        assert_eq!(
            std::fs::read(shard.join(name)).unwrap(),
            std::fs::read(other.path().join("shard-00002").join(name)).unwrap(),
            "{name}"
        );
    }
    // The archive: one .npy per stored array, shapes (H, W) and (H, W, 3), float32.
    let file = std::fs::File::open(shard.join("view-000004.npz")).unwrap();
    let mut zip = zip::ZipArchive::new(file).unwrap();
    let mut entries: Vec<String> = zip.file_names().map(|n| n.unwrap().into_owned()).collect();
    entries.sort();
    assert_eq!(
        entries,
        [
            "albedo.npy",
            "ao.vao.npy",
            "depth.npy",
            "normals.npy",
            "truth.npy"
        ]
    );
    let mut npy = Vec::new();
    std::io::Read::read_to_end(&mut zip.by_name("normals.npy").unwrap(), &mut npy).unwrap();
    let header_len = u16::from_le_bytes([npy[8], npy[9]]) as usize;
    let header = std::str::from_utf8(&npy[10..10 + header_len]).unwrap();
    assert!(
        header.contains("'descr': '<f4'") && header.contains("(48, 64, 3)"),
        "{header}"
    );
    assert_eq!((10 + header_len) % 64, 0);
    assert_eq!(npy.len(), 10 + header_len + 48 * 64 * 3 * 4);
    // A shard index the plan lacks is an error, not a panic.
    let err = dataset::run_shard(&gpu, &spec, 9, out, &|_| {}).unwrap_err();
    assert!(err.to_string().contains("shard 9 does not exist"), "{err}");
}
