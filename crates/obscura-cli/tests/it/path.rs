//! `obscura path` and `compare --path` end to end (issue 13): frames, animations and per-frame
//! JSON land where documented, a still camera gives no temporal error, bad paths are clear
//! errors.

use std::path::Path;
use std::process::{Command, Output};

fn obscura(args: &[&str], cache: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(args)
        .env("OBSCURA_CACHE_DIR", cache)
        .output()
        .expect("run obscura")
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn fails_with(o: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "should fail: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "'{n}' not in: {err}");
    }
}

fn json(file: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap()
}

#[test]
fn path_writes_frames_animations_and_temporal_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = obscura(
        &[
            "path",
            "--scene",
            "cornell",
            "--frames",
            "3",
            "--size",
            "64x48",
            "--techniques",
            "vao,sd-vao",
            "--with-reference",
            "--exr",
            "--out",
            out.to_str().unwrap(),
        ],
        dir.path(),
    );
    ok(&o);
    for name in ["vao", "sd-vao", "reference"] {
        for k in 0..3 {
            assert!(out.join(format!("{name}/frame_{k:04}.png")).is_file());
            assert!(out.join(format!("{name}/frame_{k:04}.exr")).is_file());
        }
        let gif = std::fs::read(out.join(format!("{name}/animation.gif"))).unwrap();
        assert!(gif.starts_with(b"GIF89a"));
    }
    let j = json(&out.join("path.json"));
    assert_eq!(j["path"]["name"], "pan");
    let frames = j["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 3);
    assert_eq!(frames[0]["time"], 0.0);
    assert_eq!(frames[2]["time"], 2.0);
    // The pan moves the eye; consecutive frames still share most of the view.
    assert_ne!(frames[0]["eye"], frames[2]["eye"]);
    assert!(
        frames[1]["matched"].as_f64().unwrap() > 0.5,
        "{}",
        frames[1]
    );
    for t in j["techniques"].as_array().unwrap() {
        let temporal = &t["temporal"];
        let te = temporal["temporal_error"].as_f64().unwrap();
        assert!((0.0..0.2).contains(&te), "{t}");
        assert_eq!(temporal["pairs"].as_array().unwrap().len(), 2);
        assert_eq!(t["mse"].as_array().unwrap().len(), 3);
        assert_eq!(t["mean_ao"].as_array().unwrap().len(), 3);
    }
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("| `sd-vao` |"), "{stdout}");
}

#[test]
fn a_still_path_has_no_temporal_error() {
    // Every keyframe the same camera, or one keyframe: the frames are identical, so nothing
    // changes between them, for the technique as for the reference. One keyframe is said.
    let dir = tempfile::tempdir().unwrap();
    let keyframe = r#"{"eye": [0.75, 0.5, 1.6], "target": [-0.1, 0.55, -0.5], "fov": 45"#;
    for (name, keyframes) in [
        (
            "still",
            format!(r#"{keyframe}, "time": 0}}, {keyframe}, "time": 1}}"#),
        ),
        ("one", format!(r#"{keyframe}, "time": 0}}"#)),
    ] {
        let file = dir.path().join(format!("{name}.json"));
        let json_text = format!(r#"{{"name": "{name}", "keyframes": [{keyframes}]}}"#);
        std::fs::write(&file, json_text).unwrap();
        let out = dir.path().join(name);
        let o = obscura(
            &[
                "path",
                "--scene",
                "cornell",
                "--path",
                file.to_str().unwrap(),
                "--frames",
                "3",
                "--size",
                "64x48",
                "--techniques",
                "vao",
                "--with-reference",
                "--out",
                out.to_str().unwrap(),
            ],
            dir.path(),
        );
        ok(&o);
        let warned =
            String::from_utf8_lossy(&o.stderr).contains("has one keyframe: a still camera");
        assert_eq!(warned, name == "one", "{name}");
        let j = json(&out.join("path.json"));
        assert_eq!(j["path"]["name"], name);
        let temporal = &j["techniques"][0]["temporal"];
        assert!(
            temporal["temporal_error"].as_f64().unwrap() < 1e-6,
            "{temporal}"
        );
        assert_eq!(temporal["popping"], 0.0);
        assert!(j["frames"][1]["matched"].as_f64().unwrap() > 0.99);
    }
}

#[test]
fn compare_along_a_path_adds_the_temporal_section() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    ok(&obscura(
        &[
            "compare",
            "--scene",
            "grazing",
            "--path",
            "pan",
            "--frames",
            "3",
            "--size",
            "64x48",
            "--techniques",
            "vao,hbao",
            "--timing-frames",
            "0",
            "--out",
            out.to_str().unwrap(),
        ],
        dir.path(),
    ));
    let r = json(&out.join("report.json"));
    assert!(
        r["camera"]
            .as_str()
            .unwrap()
            .contains("path pan, frame 1 of 3"),
        "{}",
        r["camera"]
    );
    let t = &r["temporal"];
    assert_eq!(t["path"], "pan");
    assert_eq!(t["times"].as_array().unwrap().len(), 3);
    let results = t["results"].as_array().unwrap();
    assert_eq!(results.len(), 2);
    assert_eq!(results[1]["technique"], "hbao");
    assert_eq!(results[0]["mse"].as_array().unwrap().len(), 3);
    for file in [
        "temporal-mse.svg",
        "temporal-error.svg",
        "vao.gif",
        "hbao.gif",
        "reference.gif",
    ] {
        assert!(out.join(file).is_file(), "{file}");
    }
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.contains("Along the camera path"));
}

#[test]
fn bad_paths_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out_s = out.to_str().unwrap();
    let base = [
        "path", "--scene", "stairs", "--size", "64x48", "--out", out_s,
    ];
    let with = |extra: &[&str]| {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        obscura(&args, dir.path())
    };
    fails_with(
        &with(&["--path", "orbit"]),
        &["no camera path 'orbit'", "dolly"],
    );
    fails_with(&with(&["--frames", "1"]), &["--frames 1", "at least 2"]);
    // Issue 62, defect 5: a billion frames aborted allocating; now clap's bound refuses it, and
    // frames × size beyond memory is refused before anything is rendered.
    fails_with(
        &with(&["--frames", "1000000000"]),
        &["--frames", "1000000000", "0..=100000"],
    );
    fails_with(
        &with(&["--frames", "100000"]),
        &[
            "--frames 100000 at --size 64x48",
            "GiB",
            "limit of 8 GiB",
            "at most",
        ],
    );
    fails_with(&with(&["--camera", "side"]), &["--camera", "camera path"]);
    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, "[{\"time\": 0, \"eye\": [0, 1, 2]}]").unwrap();
    fails_with(
        &with(&["--path", bad.to_str().unwrap()]),
        &["bad.json", "target"],
    );
    fails_with(
        &with(&["--path", "/nonexistent/walk.json"]),
        &["/nonexistent/walk.json"],
    );
    assert!(!out.exists(), "nothing written on bad input");
}

#[test]
fn scenes_list_their_paths() {
    let dir = tempfile::tempdir().unwrap();
    let o = obscura(&["scenes", "--json"], dir.path());
    ok(&o);
    let list: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for s in list.as_array().unwrap() {
        assert!(!s["paths"].as_array().unwrap().is_empty(), "{s}");
    }
    assert_eq!(list[0]["paths"][0], "dolly");
}

#[test]
fn bench_along_a_path_reports_the_spread() {
    let dir = tempfile::tempdir().unwrap();
    let json_file = dir.path().join("bench.json");
    let o = obscura(
        &[
            "bench",
            "--scene",
            "layers",
            "--path",
            "orbit",
            "--size",
            "64x48",
            "--frames",
            "4",
            "--warmup",
            "1",
            "--techniques",
            "vao",
            "--temporal",
            "--json",
            json_file.to_str().unwrap(),
        ],
        dir.path(),
    );
    ok(&o);
    let r = &json(&json_file)["results"][0];
    assert_eq!(r["camera"], "path orbit");
    let path = &r["path"];
    assert_eq!(path["times"].as_array().unwrap().len(), 4);
    assert_eq!(path["times"][3], 3.0);
    assert_eq!(path["totals"].as_array().unwrap().len(), 4);
    for pass in ["vao", "temporal", "blur_x"] {
        let [lo, hi] = [0, 1].map(|i| path["spread"][pass][i].as_f64().unwrap());
        let median = r["passes"][pass].as_f64().unwrap();
        assert!(lo <= median && median <= hi, "{pass}: {lo} {median} {hi}");
    }
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("along the path"), "{stdout}");
}
