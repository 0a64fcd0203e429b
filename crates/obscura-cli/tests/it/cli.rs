//! The `obscura` binary end to end: good runs produce real files, bad input gives one clear
//! error, a non-zero exit, no panic, and never a (half-)written output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the binary with `args` (also used by the other modules).
pub(crate) fn obscura(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(args)
        .output()
        .expect("run obscura")
}

pub(crate) fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `obscura render` with `extra` arguments writing to a fresh `out.png` that already holds
/// old content; asserts failure with a message containing every `needle`, and that the old file
/// is untouched and no temporary file is left. Returns the message.
fn assert_render_fails(extra: &[&str], needles: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out.png");
    std::fs::write(&out, b"old").unwrap();
    let out_s = out.to_str().unwrap();
    let mut args = vec!["render", "--out", out_s];
    if !extra.contains(&"--size") {
        args.extend(["--size", "64x48"]);
    }
    args.extend_from_slice(extra);
    let o = obscura(&args);
    let err = stderr(&o);
    assert!(!o.status.success(), "{extra:?} should fail");
    assert!(!err.contains("panicked"), "{extra:?} panicked: {err}");
    for needle in needles {
        assert!(
            err.to_lowercase().contains(&needle.to_lowercase()),
            "{extra:?}: '{needle}' not in: {err}"
        );
    }
    assert_eq!(
        std::fs::read(&out).unwrap(),
        b"old",
        "{extra:?} damaged the output"
    );
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(leftovers.len(), 1, "{extra:?} left files: {leftovers:?}");
    err
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// A .gltf with one triangle whose third index is `bad_index`, positions `p`.
fn gltf_triangle(positions: [[f32; 3]; 3], third_index: u16) -> String {
    let mut bin = Vec::new();
    for p in positions {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u16, 1, third_index] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    bin.extend_from_slice(&[0, 0]);
    let b64 = base64::encode(&bin);
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream;base64,{b64}"}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
                     {{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}]}}"#,
        len = bin.len()
    )
}

#[test]
fn render_writes_png_exr_and_composite() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ao.png");
    let o = obscura(&[
        "render",
        "--scene",
        "stairs",
        "--size",
        "80x48",
        "--out",
        png.to_str().unwrap(),
        "--composite",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (80, 48));
    let luma = img.to_luma8();
    assert!(
        luma.pixels().any(|p| p[0] < 230),
        "the close-up must show occlusion"
    );
    let composite = image::open(dir.path().join("ao.composite.png")).unwrap();
    assert_eq!((composite.width(), composite.height()), (80, 48));
    // The background is transparent, the geometry opaque.
    let alpha: Vec<u8> = img.to_luma_alpha8().pixels().map(|p| p[1]).collect();
    assert!(
        alpha.contains(&0) && alpha.contains(&255),
        "background not marked"
    );
    assert!(alpha.iter().all(|&a| a == 0 || a == 255));
    let exr = dir.path().join("ao.exr");
    let o = obscura(&[
        "render",
        "--scene",
        "cornell",
        "--size",
        "64x64",
        "--out",
        exr.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // One float channel, Y.
    let file = exr::prelude::read_first_flat_layer_from_file(&exr).unwrap();
    let channels = &file.layer_data.channel_data.list;
    assert_eq!(channels.len(), 1);
    assert_eq!(channels[0].name.to_string(), "Y");
    let back = obscura::output::read_ao(&exr).unwrap();
    assert_eq!((back.width, back.height), (64, 64));
    assert!(back.values.iter().all(|v| (0.0..=1.0).contains(v)));
}

#[test]
fn lit_composite_shades_the_model_and_leaves_the_background_transparent() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("ao.png");
    let o = obscura(&[
        "render",
        "--scene",
        "stairs",
        "--size",
        "80x48",
        "--lit",
        "--opaque-background",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(image::open(&png).unwrap().color(), image::ColorType::L8);
    let lit = image::open(dir.path().join("ao.lit.png"))
        .unwrap()
        .to_rgba8();
    let (covered, empty): (Vec<&image::Rgba<u8>>, Vec<_>) = lit.pixels().partition(|p| p[3] == 255);
    assert!(
        !covered.is_empty() && !empty.is_empty(),
        "stairs close-up shows both"
    );
    assert!(empty.iter().all(|p| p[3] == 0));
    // Lit surfaces are not flat: faces turned to the sun and away from it differ.
    let lum = |p: &&image::Rgba<u8>| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]);
    let (lo, hi) = (covered.iter().map(lum).min(), covered.iter().map(lum).max());
    assert!(hi.unwrap() > lo.unwrap() + 150, "{lo:?}..{hi:?}");
}

#[test]
fn scenes_and_info_print_json() {
    let o = obscura(&["scenes", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let names: Vec<&str> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "stairs",
            "colonnade",
            "layers",
            "grass",
            "tower",
            "cornell",
            "grazing"
        ]
    );
    for s in v.as_array().unwrap() {
        assert!(s["cameras"].as_array().unwrap().len() >= 2, "{s}");
    }
    let o = obscura(&["info", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["name"].as_str().is_some_and(|n| !n.is_empty()));
}

#[test]
fn bad_scene_files_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let missing = d.join("missing.glb");
    assert_render_fails(&["--scene", missing.to_str().unwrap()], &["missing.glb"]);
    let truncated = write(
        d,
        "truncated.glb",
        b"glTF\x02\x00\x00\x00\xff\x00\x00\x00JSON",
    );
    assert_render_fails(
        &["--scene", truncated.to_str().unwrap()],
        &["truncated.glb"],
    );
    let invalid = write(d, "invalid.gltf", b"{ \"asset\": { \"version\": \"2.0\" ");
    assert_render_fails(&["--scene", invalid.to_str().unwrap()], &["invalid.gltf"]);
    let gltf = gltf_triangle([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], 7);
    let out_of_range = write(d, "oob.gltf", gltf.as_bytes());
    assert_render_fails(&["--scene", out_of_range.to_str().unwrap()], &["oob.gltf"]);
    let gltf = gltf_triangle([[0.0; 3], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]], 2);
    let nan = write(d, "nan.gltf", gltf.as_bytes());
    assert_render_fails(&["--scene", nan.to_str().unwrap()], &["nan.gltf"]);
    let random: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    let garbage = write(d, "random.obj", &random);
    assert_render_fails(&["--scene", garbage.to_str().unwrap()], &["random.obj"]);
    let obj = write(d, "oob.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    assert_render_fails(&["--scene", obj.to_str().unwrap()], &["oob.obj"]);
    let empty = write(d, "empty.obj", b"v 0 0 0\nv 1 0 0\n");
    assert_render_fails(&["--scene", empty.to_str().unwrap()], &["triangle"]);
    let nan_obj = write(d, "nan.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    assert_render_fails(&["--scene", nan_obj.to_str().unwrap()], &["nan.obj"]);
    let txt = write(d, "scene.txt", b"hello");
    assert_render_fails(&["--scene", txt.to_str().unwrap()], &["scene.txt"]);
}

#[test]
fn bad_options_are_clear_errors() {
    assert_render_fails(&["--scene", "nosuchscene"], &["nosuchscene", "stairs"]);
    assert_render_fails(&["--camera", "nosuchcamera"], &["nosuchcamera"]);
    assert_render_fails(
        &["--technique", "nosuchtechnique"],
        &["nosuchtechnique", "vao"],
    );
    assert_render_fails(
        &["--eye", "0,1,2", "--target", "0,0,0", "--fov", "0"],
        &["field of view"],
    );
    assert_render_fails(
        &["--eye", "0,1,2", "--target", "0,0,0", "--fov", "180"],
        &["field of view"],
    );
    assert_render_fails(&["--eye", "1,1,1", "--target", "1,1,1"], &["eye"]);
    assert_render_fails(&["--eye", "1,x,1", "--target", "0,0,0"], &["x"]);
    assert_render_fails(
        &["--eye", "0,0,5", "--target", "0,0,0", "--up", "0,0,1"],
        &["up"],
    );
    assert_render_fails(&["--up", "0,0,1"], &["--eye"]);
    let view = [
        "view", "--eye", "1,1,1", "--target", "0,0,0", "--up", "0,0,1",
    ];
    let o = obscura(&[&view[..], &["--offscreen-frames", "1"]].concat());
    assert!(!o.status.success() && stderr(&o).contains("fly camera keeps +Y up"));
    assert_render_fails(&["--radius", "-0.5"], &["radius"]);
    assert_render_fails(&["--thickness", "-1"], &["thickness"]);
    assert_render_fails(&["--samples", "12"], &["sample"]);
    assert_render_fails(&["--size", "0x48"], &["size"]);
    assert_render_fails(&["--size", "big"], &["big"]);
    assert_render_fails(
        &["--size", "16000x16000", "--guard-band", "1000"],
        &["limit"],
    );
}

#[test]
fn output_in_a_missing_directory_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("no/such/dir/ao.png");
    let o = obscura(&["render", "--size", "64x48", "--out", out.to_str().unwrap()]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("does not exist") && !err.contains("panicked"),
        "{err}"
    );
    let o = obscura(&[
        "render",
        "--size",
        "64x48",
        "--out",
        dir.path().join("ao.bmp").to_str().unwrap(),
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains(".png"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn bench_reports_every_pass() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("bench.json");
    let o = obscura(&[
        "bench",
        "--scene",
        "cornell",
        "--size",
        "64x48",
        "--techniques",
        "vao,sd-svao",
        "--frames",
        "5",
        "--warmup",
        "1",
        "--json",
        json.to_str().unwrap(),
    ]);
    let info: serde_json::Value =
        serde_json::from_slice(&obscura(&["info", "--json"]).stdout).unwrap();
    if info["timestamp_queries"] == false {
        // Not every adapter can time passes; then bench must say so clearly.
        assert!(
            !o.status.success() && stderr(&o).contains("timestamp"),
            "{}",
            stderr(&o)
        );
        return;
    }
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(v["adapter"].is_string() && v["driver"].is_string());
    let r = &v["results"][0];
    assert_eq!(r["technique"], "vao");
    // Raster passes count their fragments where the adapter can: the G-buffer shades every
    // covered pixel at least once (the close-up covers most of the frame).
    if info["pipeline_statistics"] == true {
        let g = &r["fragments"]["gbuffer"];
        let per_pixel = g["per_pixel"]
            .as_f64()
            .expect("fragments.gbuffer.per_pixel");
        assert!(
            g["invocations"].as_u64().unwrap() > 0 && per_pixel > 0.3,
            "{r}"
        );
        assert!(
            r["fragments"].get("vao").is_none(),
            "compute passes have no fragments"
        );
    } else {
        assert!(r.get("fragments").is_none(), "{r}");
    }
    assert_eq!(
        (
            r["width"].as_u64(),
            r["height"].as_u64(),
            r["frames"].as_u64()
        ),
        (Some(64), Some(48), Some(5))
    );
    for pass in ["gbuffer", "vao", "blur_x", "blur_y", "blur"] {
        assert!(
            r["passes"][pass].as_f64().is_some_and(|ms| ms >= 0.0),
            "{pass} missing in {r}"
        );
    }
    assert!(r["total_ms"].as_f64().is_some_and(|t| t > 0.0));
    assert!(r["span_ms"].as_f64().is_some_and(|t| t > 0.0));
    // Every record holds the whole settings struct, as a settings file would.
    assert_eq!(r["settings"]["technique"], "vao");
    assert_eq!(r["settings"]["vao"]["samples"].as_u64(), Some(8));
    assert_eq!(r["settings"]["blur"]["radius"].as_u64(), Some(4));
    assert!(r.get("layout").is_none(), "vao has no SD map: {r}");
    // A stochastic-depth technique records its settings and layout and times its raster passes.
    let r = &v["results"][1];
    assert_eq!(r["technique"], "sd-svao");
    let sd = &r["settings"]["stochastic_depth"];
    assert_eq!(
        (
            sd["samples"].as_u64(),
            sd["alpha"].as_f64(),
            sd["mask"].as_str()
        ),
        // α as it ran: the default 1.5/S written out.
        (Some(4), Some(0.375), Some("depth"))
    );
    let layout = &r["layout"];
    assert_eq!(
        layout["maps"].as_u64().unwrap() * layout["samples_per_map"].as_u64().unwrap(),
        4,
        "{r}"
    );
    // The map's own passes are the rasteriser's that `auto` chose.
    let map_passes: &[&str] = match sd["rasterizer"].as_str() {
        Some("hardware") => &["sd_reset", "sd_map"],
        Some("compute") => &["sd_bin", "sd_tiles", "sd_map"],
        other => panic!("rasterizer {other:?} in {r}"),
    };
    let passes = [
        "gbuffer",
        "sd_request_clear",
        "sd_clear",
        "svao_phase1",
        "svao_phase2",
        "blur",
    ];
    for pass in passes.iter().chain(map_passes) {
        assert!(
            r["passes"][pass].as_f64().is_some_and(|ms| ms >= 0.0),
            "{pass} missing in {r}"
        );
    }
}

fn obscura_cached(args: &[&str], cache: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(args)
        .env("OBSCURA_CACHE_DIR", cache)
        .output()
        .expect("run obscura")
}

#[test]
fn compare_writes_a_report_and_reuses_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let out = dir.path().join("report");
    let args = [
        "compare",
        "--scene",
        "cornell",
        "--size",
        "64x48",
        "--techniques",
        "vao",
        "--reference-model",
        "vao",
        "--out",
        out.to_str().unwrap(),
    ];
    let o = obscura_cached(&args, &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("rays/s"),
        "the first run computes: {}",
        stderr(&o)
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(v["scene"], "cornell");
    // A built-in scene has no vertex normals: face normals under the shading default.
    assert_eq!(
        v["scene_options"],
        "sides as authored, normals face (no vertex normals)"
    );
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(64), Some(48))
    );
    assert_eq!(v["reference"]["model"], "vao");
    // The ground truth's R: VAO's radius, the default here.
    assert_eq!(v["reference"]["radius"], 0.5);
    let results = v["results"].as_array().unwrap();
    assert_eq!(results.len(), 1);
    assert_eq!(results[0]["technique"], "vao");
    for key in ["mse", "mae", "psnr", "ssim", "halo_bright", "halo_dark"] {
        assert!(results[0].get(key).is_some(), "{key} missing");
    }
    // The settings it was rendered with, as the settings struct serialises them.
    let settings: obscura::AoSettings =
        serde_json::from_value(results[0]["settings"].clone()).expect("settings in report.json");
    assert_eq!(settings.technique, obscura::Technique::Vao);
    assert_eq!(settings.vao, obscura::AoSettings::default().vao);
    let mse = results[0]["mse"].as_f64().unwrap();
    assert!((0.0..0.1).contains(&mse), "mse {mse}");
    for f in [
        "report.md",
        "index.html",
        "reference.png",
        "vao.png",
        "vao.diff.png",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    // Same scene, camera, size and model: the reference comes from the cache.
    let o = obscura_cached(&args, &cache);
    assert!(
        o.status.success() && stderr(&o).contains("reused"),
        "{}",
        stderr(&o)
    );
    let mut again: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    // Everything but the measured times, which vary from run to run.
    let mut v = v.clone();
    for report in [&mut again, &mut v] {
        let timed = report["results"][0].as_object_mut().unwrap();
        assert!(timed
            .remove("gpu_ms")
            .is_some_and(|ms| ms.as_f64() > Some(0.0)));
    }
    assert_eq!(again, v, "a cached reference gives the same report");
}

#[test]
fn compare_builds_the_bvh_once_for_its_rows_and_the_reference() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let o = obscura_cached(
        &[
            "compare",
            "--scene",
            "cornell",
            "--size",
            "64x48",
            "--techniques",
            "rt-vao,vao,rt-svao",
            "--reference-model",
            "vao",
            "--no-cache",
            "--timing-frames",
            "0",
            "--out",
            out.to_str().unwrap(),
        ],
        &dir.path().join("cache"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    // The reference traces the tree the first ray-traced row built.
    assert!(stderr(&o).contains("(BVH reused)"), "{}", stderr(&o));
}

#[test]
fn reference_writes_a_float_image() {
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("ref.exr");
    let o = obscura_cached(
        &[
            "reference",
            "--scene",
            "cornell",
            "--size",
            "48x32",
            "--model",
            "hemisphere",
            "--spp",
            "16",
            "--out",
            exr.to_str().unwrap(),
        ],
        &dir.path().join("cache"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let img = obscura::output::read_ao(&exr).unwrap();
    assert_eq!((img.width, img.height), (48, 32));
    assert!(img.values.iter().all(|v| (0.0..=1.0).contains(v)));
    assert!(
        img.values.iter().any(|v| *v < 0.9),
        "the Cornell box has occluded corners"
    );
}

#[test]
fn compare_and_reference_reject_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let out_s = out.to_str().unwrap();
    let o = obscura(&[
        "compare",
        "--size",
        "64x48",
        "--reference-model",
        "photon",
        "--out",
        out_s,
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("photon"),
        "{}",
        stderr(&o)
    );
    let o = obscura(&[
        "compare",
        "--size",
        "64x48",
        "--reference-model",
        "hemisphere",
        "--spp",
        "0",
        "--out",
        out_s,
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("spp"),
        "{}",
        stderr(&o)
    );
    let o = obscura(&[
        "reference",
        "--size",
        "64x48",
        "--model",
        "hemisphere",
        "--spp",
        "0",
        "--out",
        "x.exr",
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("spp"),
        "{}",
        stderr(&o)
    );
    // An output folder that cannot be created: its parent is a file.
    let file = write(dir.path(), "file", b"x");
    let blocked = file.join("sub");
    let o = obscura(&[
        "compare",
        "--size",
        "64x48",
        "--out",
        blocked.to_str().unwrap(),
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("output folder"),
        "{}",
        stderr(&o)
    );
    assert!(!stderr(&o).contains("panicked"));
    // Input found bad after the folder was made (a scene that is not there, an unknown camera, a
    // reference image that is not one) leaves no folder behind, nor the missing parents it made;
    // an existing folder stays.
    let existing = dir.path().join("existing");
    std::fs::create_dir(&existing).unwrap();
    let new = dir.path().join("new").join("report");
    for out in [&new, &existing] {
        for bad in [
            &["--scene", "missing.glb"][..],
            &["--camera", "nowhere"],
            &["--reference-image", file.to_str().unwrap()],
        ] {
            let mut args = vec!["compare", "--size", "64x48", "--techniques", "vao"];
            args.extend_from_slice(bad);
            args.extend(["--out", out.to_str().unwrap()]);
            let o = obscura(&args);
            assert!(!o.status.success(), "{bad:?} should fail");
            assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
        }
    }
    assert!(
        !dir.path().join("new").exists(),
        "a failed compare left its folder"
    );
    assert!(existing.is_dir());
}

#[test]
fn ctrl_c_during_reference_leaves_no_file() {
    interrupted_reference_leaves_no_file("-INT");
}

/// Issue 62, defect 3: `kill` (SIGTERM) runs the same clean-up as Ctrl-C.
#[test]
fn sigterm_during_reference_leaves_no_file() {
    interrupted_reference_leaves_no_file("-TERM");
}

fn interrupted_reference_leaves_no_file(signal: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ref.exr");
    let mut child = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args([
            "reference",
            "--scene",
            "grass",
            "--size",
            "320x240",
            "--model",
            "hemisphere",
            "--spp",
            "100000",
        ])
        .args(["--no-cache", "--out", out.to_str().unwrap()])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(800));
    let killed = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert_eq!(
        status.code(),
        Some(130),
        "interrupted runs ({signal}) exit with 130"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "files left after {signal}: {left:?}");
}

#[test]
fn no_matching_adapter_says_how_to_get_one() {
    // Where adapters exist, the message lists them (telling to install a driver would be wrong).
    let o = obscura(&["info", "--adapter", "no-such-gpu-anywhere"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("no-such-gpu-anywhere") && err.contains("adapters here are"),
        "{err}"
    );
    let o = obscura(&["info", "--backend", "glide"]);
    assert!(
        !o.status.success() && stderr(&o).contains("glide"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn debug_out_shows_the_ray_traced_map() {
    // ray-sd-vao at 1/2 resolution: the map's layers at the framebuffer's size, its hits per ray
    // at the map's (each between 1 and MAX_COUNT where a ray met a surface), and the request.
    let dir = tempfile::tempdir().unwrap();
    let stats = sd_debug(
        "ray-sd-vao",
        dir.path(),
        &[
            "--guard-band",
            "8",
            "--ray-sd-res",
            "2",
            "--sd-guard-band",
            "12",
        ],
    );
    let debug = dir.path().join("ray-sd-vao");
    assert_eq!(stats["ray_sd"]["resolution"], 2);
    // The framebuffer 112×80 at 1/2, and 6 texels of the map's own band on each side.
    assert_eq!(
        (
            stats["map_width"].as_u64(),
            stats["map_height"].as_u64(),
            stats["map_guard_band_texels"].as_u64()
        ),
        (Some(68), Some(52), Some(6))
    );
    let mean = stats["hits_per_ray_mean"].as_f64().unwrap();
    assert!((1.0..=8.0).contains(&mean), "{stats}");
    assert!(stats["requested_pixels"].as_u64().unwrap() > 0, "{stats}");
    for (file, size) in [
        ("sd_layer.png", (112, 80)),
        ("sd_counts.png", (112, 80)),
        ("sd_request.png", (112, 80)),
        ("sd_hits.png", (68, 52)),
        ("sd_request_map.png", (68, 52)),
        ("sd_intervals.png", (112, 80)),
        ("samples.png", (96, 64)),
    ] {
        let img = image::open(debug.join(file)).unwrap();
        assert_eq!((img.width(), img.height()), size, "{file}");
    }
    // Ray intervals (seed 002 Fig. 12): only where a sample asked, each a stretch of depth no
    // longer than the longest, which is what the image is scaled by.
    let pixels = stats["interval_pixels"].as_u64().unwrap();
    assert!(
        pixels > 0 && pixels <= stats["requested_pixels"].as_u64().unwrap(),
        "{stats}"
    );
    let (mean, longest) = (
        stats["interval_mean_length"].as_f64().unwrap(),
        stats["interval_longest"].as_f64().unwrap(),
    );
    assert!(mean > 0.0 && mean <= longest, "{stats}");
    let img = image::open(debug.join("sd_intervals.png"))
        .unwrap()
        .to_luma8();
    assert_eq!(img.pixels().map(|p| p.0[0]).max(), Some(255));
    // Without ray intervals there is no such image.
    let plain = dir.path().join("no-intervals");
    std::fs::create_dir_all(&plain).unwrap();
    let stats = sd_debug(
        "ray-sd-vao",
        &plain,
        &["--guard-band", "8", "--no-intervals"],
    );
    assert!(stats.get("interval_pixels").is_none(), "{stats}");
}

#[test]
fn debug_out_shows_the_raster_maps_own_band() {
    // sd-svao with the raster map's own 16 px band on the stairs close-up: the request mask over
    // the whole map, the band's requests counted apart from the framebuffer's pixels.
    let dir = tempfile::tempdir().unwrap();
    let stats = sd_debug(
        "sd-svao",
        dir.path(),
        &["--guard-band", "8", "--sd-map-guard-band", "16"],
    );
    let debug = dir.path().join("sd-svao");
    // The framebuffer 112×80, and 16 px on each side.
    let (w, h, request) = grey(&debug.join("sd_request_map.png"));
    assert_eq!((w, h), (144, 112));
    let inside = |x: u32, y: u32| (16..128).contains(&x) && (16..96).contains(&y);
    let white = |keep: &dyn Fn(u32, u32) -> bool| {
        (0..w * h)
            .filter(|&i| keep(i % w, i / w) && request[i as usize] == 255)
            .count() as u64
    };
    let band = stats["guard_band_texels_requested"].as_u64().unwrap();
    assert!(band > 0, "samples leave the close-up's frame: {stats}");
    assert_eq!(band, white(&|x, y| !inside(x, y)));
    assert_eq!(
        stats["requested_pixels"].as_u64().unwrap(),
        white(&|x, y| inside(x, y))
    );
    // Without its band the raster map has no such image.
    let plain = dir.path().join("no-band");
    std::fs::create_dir_all(&plain).unwrap();
    let stats = sd_debug(
        "sd-svao",
        &plain,
        &["--guard-band", "8", "--sd-map-guard-band", "0"],
    );
    assert!(
        stats.get("guard_band_texels_requested").is_none(),
        "{stats}"
    );
    assert!(!plain.join("sd-svao").join("sd_request_map.png").exists());
    // By default it has one: 512 px at 1080p scaled with the visible 64 px, rounded up to a
    // multiple of 4: 32 px on each side of the 112×80 framebuffer.
    let default = dir.path().join("default-band");
    std::fs::create_dir_all(&default).unwrap();
    let stats = sd_debug("sd-svao", &default, &["--guard-band", "8"]);
    assert!(stats["guard_band_texels_requested"].as_u64().unwrap() > 0);
    let (w, h, _) = grey(&default.join("sd-svao").join("sd_request_map.png"));
    assert_eq!((w, h), (176, 144));
}

#[test]
fn debug_out_shows_the_flagged_samples() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ao.png");
    let debug = dir.path().join("debug");
    let o = obscura(&[
        "render",
        "--scene",
        "stairs",
        "--size",
        "96x64",
        "--technique",
        "rt-svao",
        "--out",
        out.to_str().unwrap(),
        "--debug-out",
        debug.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(debug.join("stats.json")).unwrap()).unwrap();
    let (pixels, flagged, rays) = (
        stats["pixels"].as_u64().unwrap(),
        stats["flagged_pixels"].as_u64().unwrap(),
        stats["rays_traced"].as_u64().unwrap(),
    );
    assert_eq!(pixels, 96 * 64);
    // The close-up has hidden geometry behind the figure: some, not all, pixels need rays, and
    // each flagged pixel traces between 1 and 8 rays.
    assert!(flagged > 0 && flagged < pixels, "{stats}");
    assert!(rays >= flagged && rays <= 8 * flagged, "{stats}");
    assert_eq!(stats["stack_overflows"], 0);
    let img = image::open(debug.join("samples.png")).unwrap();
    assert_eq!((img.width(), img.height()), (96, 64));
    let o = obscura(&[
        "render",
        "--size",
        "64x48",
        "--out",
        out.to_str().unwrap(),
        "--debug-out",
        debug.to_str().unwrap(),
    ]);
    assert!(
        !o.status.success() && stderr(&o).contains("rt-svao") && stderr(&o).contains("sd-svao"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn debug_out_shows_the_estimators_image() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ao.png");
    let debug = dir.path().join("debug");
    let o = obscura(&[
        "render",
        "--scene",
        "stairs",
        "--size",
        "64x40",
        "--technique",
        "gtao-vb",
        "--out",
        out.to_str().unwrap(),
        "--debug-out",
        debug.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("occupancy"), "{}", stderr(&o));
    let img = image::open(debug.join("sectors.png")).unwrap();
    assert_eq!((img.width(), img.height()), (64, 40));
}

fn info_json() -> serde_json::Value {
    let o = obscura(&["info", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// Ours is one line; Mesa's Vulkan WSI adds its own when XDG_RUNTIME_DIR is unset (the README
/// test command may run without it), which is not our message.
fn one_line(err: &str) {
    let ours = err
        .trim()
        .lines()
        .filter(|l| !l.contains("XDG_RUNTIME_DIR"))
        .count();
    assert_eq!(ours, 1, "one message: {err}");
}

#[test]
fn stochastic_depth_options_are_clear_errors() {
    let sd = ["--technique", "sd-vao"];
    let err = assert_render_fails(
        &[&sd[..], &["--sd-samples", "3"]].concat(),
        &["3", "1, 2, 4, 8 or 16"],
    );
    one_line(&err);
    for alpha in ["0", "1.5"] {
        let err = assert_render_fails(
            &[&sd[..], &["--sd-alpha", alpha]].concat(),
            &[alpha, "(0, 1]"],
        );
        one_line(&err);
    }
    assert_render_fails(
        &["--technique", "sd-svao", "--sd-mask", "stencils"],
        &["stencils", "'stencil'", "'discard'"],
    );
    let err = assert_render_fails(
        &[&sd[..], &["--sd-rasterizer", "software"]].concat(),
        &["software", "--sd-rasterizer", "'hardware'", "'compute'"],
    );
    one_line(&err);
    // The map is a storage buffer: every S runs on every adapter, as `obscura info` says; on
    // lavapipe (CI) also with early tests and the stencil.
    let info = info_json();
    let accepted: Vec<u64> = info["sd_sample_counts"]
        .as_array()
        .expect("info --json lists sd_sample_counts")
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(accepted, [1, 2, 4, 8, 16], "{info}");
    if info["name"]
        .as_str()
        .is_some_and(|n| n.contains("llvmpipe"))
    {
        assert_eq!(info["sd_early_tests"], true, "{info}");
        assert_eq!(info["visibility_words"], true, "{info}");
        assert_eq!(info["sd_compute_rasterizer"], true, "{info}");
    }
}

/// `--sd-rasterizer compute` renders the image `hardware` does (the same map up to rounding:
/// within 1e-3 everywhere; the library's tests hold the maps themselves), and `bench` times its
/// passes; left to `auto`, it names the rasteriser it chose.
#[test]
fn the_compute_rasterizer_renders_the_hardware_image() {
    let dir = tempfile::tempdir().unwrap();
    let image = |rasterizer: &str| {
        let out = dir.path().join(format!("{rasterizer}.exr"));
        let o = obscura(&[
            "render",
            "--scene",
            "colonnade",
            "--size",
            "96x64",
            "--technique",
            "sd-vao",
            "--sd-rasterizer",
            rasterizer,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        out
    };
    let (hardware, compute) = (image("hardware"), image("compute"));
    let o = obscura(&[
        "diff",
        hardware.to_str().unwrap(),
        compute.to_str().unwrap(),
        "--max-abs",
        "1e-3",
    ]);
    assert!(
        o.status.success(),
        "{}{}",
        stderr(&o),
        String::from_utf8_lossy(&o.stdout)
    );
    // `bench` of sd-vao on colonnade with `rasterizer` (`auto` when none): its JSON report and
    // its text.
    let json = dir.path().join("bench.json");
    let bench = |rasterizer: Option<&str>| {
        let mut args = vec![
            "bench",
            "--scene",
            "colonnade",
            "--size",
            "64x48",
            "--techniques",
            "sd-vao",
            "--frames",
            "2",
            "--warmup",
            "1",
            "--json",
            json.to_str().unwrap(),
        ];
        if let Some(r) = rasterizer {
            args.extend(["--sd-rasterizer", r]);
        }
        let o = obscura(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        (report, String::from_utf8_lossy(&o.stdout).into_owned())
    };
    let rasterizer = |report: &serde_json::Value| {
        report["results"][0]["settings"]["stochastic_depth"]["rasterizer"].clone()
    };
    let (report, _) = bench(Some("compute"));
    let passes = &report["results"][0]["passes"];
    for pass in ["sd_clear", "sd_bin", "sd_tiles", "sd_map"] {
        assert!(passes[pass].as_f64().is_some(), "{pass}: {report}");
    }
    // The compute passes count the fragments they shade; none is left to the hardware here.
    let fragments = &report["results"][0]["fragments"];
    let made = |pass: &str| fragments[pass]["invocations"].as_u64();
    assert!(
        made("sd_tiles").is_some_and(|n| n > 0) && made("sd_bin").is_some(),
        "{report}"
    );
    assert_eq!(made("sd_map"), Some(0), "{report}");
    assert_eq!(rasterizer(&report), "compute", "{report}");
    // Left to `auto`, the report names the rasteriser chosen, in the JSON and the text.
    let (report, text) = bench(None);
    let chosen = rasterizer(&report);
    assert!(chosen == "hardware" || chosen == "compute", "{report}");
    let named = format!("{} rasteriser", chosen.as_str().unwrap());
    assert!(text.contains(&named), "{text}");
}

/// Grey levels of an 8-bit PNG.
fn grey(path: &Path) -> (u32, u32, Vec<u8>) {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let (w, h) = (img.width(), img.height());
    (w, h, img.to_luma8().into_raw())
}

/// `render --debug-out` for one technique on the stairs close-up at 96x64; returns stats.json.
fn sd_debug(technique: &str, dir: &Path, extra: &[&str]) -> serde_json::Value {
    let out = dir.join(format!("{technique}.png"));
    let debug = dir.join(technique);
    let mut args = vec![
        "render",
        "--scene",
        "stairs",
        "--size",
        "96x64",
        "--technique",
        technique,
        "--out",
        out.to_str().unwrap(),
        "--debug-out",
        debug.to_str().unwrap(),
    ];
    args.extend(extra);
    let o = obscura(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    serde_json::from_str(&std::fs::read_to_string(debug.join("stats.json")).unwrap()).unwrap()
}

#[test]
fn debug_out_shows_the_stochastic_depth_map() {
    let dir = tempfile::tempdir().unwrap();
    let stats = sd_debug("sd-svao", dir.path(), &[]);
    let debug = dir.path().join("sd-svao");
    assert_eq!(
        (stats["sd_samples"].as_u64(), stats["sd_alpha"].as_f64()),
        (Some(4), Some(0.375))
    );
    let layout = &stats["layout"];
    assert_eq!(
        layout["maps"].as_u64().unwrap() * layout["samples_per_map"].as_u64().unwrap(),
        4,
        "{stats}"
    );
    // The SD images cover the framebuffer: the visible 96x64 plus the guard band on each side.
    let g = stats["guard_band"].as_u64().unwrap() as u32;
    let (fw, fh) = (96 + 2 * g, 64 + 2 * g);
    assert_eq!(
        (
            stats["framebuffer_width"].as_u64(),
            stats["framebuffer_height"].as_u64()
        ),
        (Some(u64::from(fw)), Some(u64::from(fh)))
    );
    let f = |key: &str| {
        stats[key]
            .as_f64()
            .unwrap_or_else(|| panic!("{key} in {stats}"))
    };
    let n = |key: &str| {
        stats[key]
            .as_u64()
            .unwrap_or_else(|| panic!("{key} in {stats}"))
    };
    // Hidden geometry behind the figure: some of the map is stored and requested, not all.
    let stored = f("stored_fraction");
    assert!(stored > 0.0 && stored <= 1.0, "{stats}");
    let requested = f("requested_fraction");
    assert!(requested > 0.0 && requested < 1.0, "{stats}");
    assert_eq!(
        n("requested_pixels"),
        (requested * f64::from(fw * fh)).round() as u64
    );
    assert_eq!(n("pixels"), 96 * 64);
    let (flagged, samples) = (n("flagged_pixels"), n("samples_flagged"));
    assert!(flagged > 0 && flagged < 96 * 64, "{stats}");
    assert!(samples >= flagged && samples <= 8 * flagged, "{stats}");

    // The images agree with the numbers.
    let (w, h, request) = grey(&debug.join("sd_request.png"));
    assert_eq!((w, h), (fw, fh));
    assert!(request.iter().all(|&v| v == 0 || v == 255));
    assert_eq!(
        request.iter().filter(|&&v| v == 255).count() as u64,
        n("requested_pixels")
    );
    let (w, h, counts) = grey(&debug.join("sd_counts.png"));
    assert_eq!((w, h), (fw, fh));
    let mean = counts.iter().map(|&v| f64::from(v) / 255.0).sum::<f64>() / counts.len() as f64;
    assert!(
        (mean - stored).abs() < 0.005,
        "sd_counts mean {mean} vs stored_fraction {stored}"
    );
    let (w, h, layer) = grey(&debug.join("sd_layer.png"));
    assert_eq!((w, h), (fw, fh));
    assert!(layer.iter().any(|&v| v > 0), "layer 0 stores something");
    for i in 0..layer.len() {
        // A stored sample is never black (the farthest maps to grey 0.25) and lies in a pixel
        // that stores at least one sample, which sd-svao only does where it was requested.
        assert!(layer[i] == 0 || layer[i] >= 63, "pixel {i}: {}", layer[i]);
        if layer[i] > 0 {
            assert!(counts[i] > 0 && request[i] == 255, "pixel {i}");
        }
    }
    let (w, h, _) = grey(&debug.join("samples.png"));
    assert_eq!((w, h), (96, 64));

    // sd-vao: the same map everywhere (no request mask, no phase 1), so at least what the
    // stenciled map stored.
    let full = sd_debug("sd-vao", dir.path(), &[]);
    let debug = dir.path().join("sd-vao");
    assert!(debug.join("sd_layer.png").is_file() && debug.join("sd_counts.png").is_file());
    assert!(!debug.join("sd_request.png").exists() && !debug.join("samples.png").exists());
    assert!(full.get("requested_fraction").is_none(), "{full}");
    assert!(
        full["stored_samples"].as_u64() >= stats["stored_samples"].as_u64(),
        "sd-vao {full} vs sd-svao {stats}"
    );
}

/// `obscura render` of the stairs close-up at 64x48 with `extra` into `dir/name`; its grey levels.
fn render_grey(dir: &Path, name: &str, extra: &[&str]) -> Vec<u8> {
    let out = dir.join(name);
    let mut args = vec!["render", "--size", "64x48", "--out", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = obscura(&args);
    assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
    grey(&out).2
}

#[test]
fn settings_files_and_presets_change_the_image_and_flags_win() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let toml = write(d, "wide.toml", b"# a larger sphere\n[vao]\nradius = 1.5\n");
    let json = write(d, "wide.json", br#"{"vao": {"radius": 1.5}}"#);
    let default = render_grey(d, "default.png", &[]);
    let flag = render_grey(d, "flag.png", &["--radius", "1.5"]);
    assert_ne!(default, flag, "--radius 1.5 changes the image");
    let from_toml = render_grey(d, "toml.png", &["--settings", toml.to_str().unwrap()]);
    assert_eq!(from_toml, flag, "the file's radius is --radius 1.5");
    let from_json = render_grey(d, "json.png", &["--settings", json.to_str().unwrap()]);
    assert_eq!(from_json, flag);
    // An explicit flag beats the file.
    let both = render_grey(
        d,
        "both.png",
        &["--settings", toml.to_str().unwrap(), "--radius", "0.5"],
    );
    assert_eq!(both, default, "--radius 0.5 over the file's 1.5");
    // Presets: medium is the defaults; high (16 samples) is another image, the same as the flag.
    let medium = render_grey(d, "medium.png", &["--preset", "medium"]);
    assert_eq!(medium, default);
    let high = render_grey(d, "high.png", &["--preset", "high"]);
    assert_ne!(high, default);
    assert_eq!(high, render_grey(d, "16.png", &["--samples", "16"]));
}

#[test]
fn bad_settings_files_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let typo = write(d, "typo.toml", b"[vao]\nradius = 1.0\nsampels = 16\n");
    let err = assert_render_fails(
        &["--settings", typo.to_str().unwrap()],
        &["typo.toml", "line 3", "sampels"],
    );
    one_line(&err);
    let syntax = write(d, "syntax.json", b"{\"vao\": {\"radius\": 1.0,}}");
    one_line(&assert_render_fails(
        &["--settings", syntax.to_str().unwrap()],
        &["syntax.json", "line 1"],
    ));
    // A valid file with an invalid value names the file and the field (not a flag).
    let invalid = write(d, "invalid.toml", b"[stochastic_depth]\nalpha = 1.5\n");
    let err = assert_render_fails(
        &["--settings", invalid.to_str().unwrap()],
        &["invalid.toml", "stochastic_depth.alpha", "(0, 1]"],
    );
    one_line(&err);
    let missing = d.join("missing.toml");
    one_line(&assert_render_fails(
        &["--settings", missing.to_str().unwrap()],
        &["missing.toml", "cannot read"],
    ));
    let yaml = write(d, "s.yaml", b"vao: {}\n");
    one_line(&assert_render_fails(
        &["--settings", yaml.to_str().unwrap()],
        &["s.yaml", ".toml", ".json"],
    ));
    // A flag's invalid value names the flag.
    let err = assert_render_fails(&["--blur-radius", "0"], &["--blur-radius 0", "1 and 16"]);
    one_line(&err);
}

#[test]
fn scenes_too_large_for_floats_or_of_zero_extent_are_named() {
    let dir = tempfile::tempdir().unwrap();
    // Coordinates of 1e30 (e.g. a node scaled by 1e30): the error names the scene's bounds, not
    // the camera framed from them.
    let huge = dir.path().join("huge.obj");
    std::fs::write(&huge, "v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n").unwrap();
    let err = assert_render_fails(
        &["--scene", huge.to_str().unwrap()],
        &["spans", "scale the scene down"],
    );
    assert!(!err.contains("camera eye"), "{err}");
    one_line(&err);
    // Every vertex at one point (a scale of 0): rendered, with a warning.
    let point = dir.path().join("point.obj");
    std::fs::write(&point, "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n").unwrap();
    let out = dir.path().join("point.png");
    let o = obscura(&[
        "render",
        "--scene",
        point.to_str().unwrap(),
        "--eye",
        "0,0,5",
        "--target",
        "0,0,0",
        "--size",
        "32x32",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("zero extent"), "{}", stderr(&o));
}

#[test]
fn no_vulkan_window_system_noise_without_xdg_runtime_dir() {
    // Mesa's WSI complains on stderr when XDG_RUNTIME_DIR is unset; obscura gives it a private
    // directory, so a headless run prints only its own output.
    let o = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(["render", "--scene", "cornell", "--size", "16x16", "--out"])
        .arg(tempfile::tempdir().unwrap().path().join("a.png"))
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("XDG_RUNTIME_DIR"), "{}", stderr(&o));
    // An empty value is as invalid to Mesa as none.
    let o = Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(["info"])
        .env("XDG_RUNTIME_DIR", "")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("XDG_RUNTIME_DIR"), "{}", stderr(&o));
}

#[test]
fn rough_edges_give_clear_messages() {
    // An adapter name that matches nothing lists the adapters that exist.
    let o = obscura(&["--adapter", "no-such-gpu-xyz", "info"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("no-such-gpu-xyz") && err.contains("adapters here are"),
        "{err}"
    );
    one_line(&err);
    // `compare --out` naming an existing file says so.
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("report.json");
    std::fs::write(&file, b"keep").unwrap();
    let o = obscura(&[
        "compare",
        "--techniques",
        "vao",
        "--size",
        "32x32",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("is a file"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&file).unwrap(), b"keep");
    // `reference --help` says where it traces.
    let o = obscura(&["--help"]);
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(out.contains("on the GPU; --cpu"), "{out}");
}

#[test]
fn exit_status_2_for_usage_errors_1_for_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.png");
    let out = out.to_str().unwrap();
    let code = |args: &[&str]| obscura(args).status.code();
    // The command line cannot be parsed.
    assert_eq!(
        code(&["render", "--technique", "ssdo", "--out", out]),
        Some(2)
    );
    assert_eq!(
        code(&["compare", "--techniques", "vao,foo", "--out", out]),
        Some(2)
    );
    assert_eq!(
        code(&["bench", "--techniques", ",", "--size", "8x8"]),
        Some(2)
    );
    assert_eq!(
        code(&["render", "--size", "100000x100000", "--out", out]),
        Some(2)
    );
    assert_eq!(code(&["render", "--eye", "0,0,1", "--out", out]), Some(2));
    // Parsed, but wrong.
    assert_eq!(code(&["render", "--radius", "-1", "--out", out]), Some(1));
    assert_eq!(
        code(&["render", "--scene", "/no/such.obj", "--out", out]),
        Some(1)
    );
    assert!(!dir.path().join("a.png").exists());
}

#[test]
fn options_that_do_not_apply_are_refused() {
    // The vao reference model traces every column exactly: hemisphere options make no sense.
    // (The demo takes them: they go to its hemisphere reference.)
    let dir = tempfile::tempdir().unwrap();
    for args in [
        vec![
            "reference",
            "--model",
            "vao",
            "--spp",
            "4",
            "--out",
            "x.exr",
        ],
        vec!["compare", "--reference-model", "vao", "--seed", "3"],
    ] {
        let mut args = args.clone();
        let out = dir.path().join("out");
        if args[0] != "reference" {
            args.extend(["--out", out.to_str().unwrap()]);
        }
        let o = obscura(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("hemisphere"),
            "{args:?}: {}",
            stderr(&o)
        );
        one_line(&stderr(&o));
        assert!(!out.exists(), "{args:?} wrote output");
    }
}

#[test]
fn the_reference_traces_on_the_cpu_when_the_adapter_is_software() {
    let info = info_json();
    let software = info["device_type"] == "Cpu";
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ref.exr");
    let o = obscura(&[
        "reference",
        "--scene",
        "cornell",
        "--size",
        "32x24",
        "--no-cache",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    // Where it traced is said either way.
    assert_eq!(err.contains("on the CPU"), software, "{err}");
    assert_eq!(err.contains("on the GPU"), !software, "{err}");
}

#[test]
fn the_malformed_input_corpus_gives_clean_outcomes() {
    // tests/corpus (made by scripts/make-corpus.py; its README lists every file): broken and
    // degenerate scene files as real ones are. Each either renders (with the warning named) or
    // fails with one line naming the problem; never a panic, never an output file on failure.
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let manifest: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(corpus.join("manifest.json")).unwrap())
            .unwrap();
    assert!(manifest.len() >= 30, "{} corpus files", manifest.len());
    let dir = tempfile::tempdir().unwrap();
    for case in &manifest {
        let file = case["file"].as_str().unwrap();
        let (outcome, needle) = (
            case["outcome"].as_str().unwrap(),
            case["needle"].as_str().unwrap(),
        );
        let out = dir.path().join(format!("{file}.png"));
        let start = std::time::Instant::now();
        let o = obscura(&[
            "render",
            "--scene",
            corpus.join(file).to_str().unwrap(),
            "--size",
            "32x32",
            "--out",
            out.to_str().unwrap(),
        ]);
        let seconds = start.elapsed().as_secs_f64();
        let err = stderr(&o);
        assert!(!err.contains("panicked"), "{file}: {err}");
        assert!(seconds < 10.0, "{file}: {seconds:.1} s");
        assert!(err.contains(needle), "{file}: '{needle}' not in: {err}");
        match outcome {
            "ok" => assert!(o.status.success() && out.exists(), "{file}: {err}"),
            _ => {
                assert_eq!(o.status.code(), Some(1), "{file}: {err}");
                one_line(&err);
                assert!(!out.exists(), "{file}: output written");
            }
        }
    }
}

#[test]
fn obj_is_double_sided_unless_back_faces_are_culled() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A floor and, above it, a ceiling whose front faces up: the camera below sees its back face.
    let obj = write(
        d,
        "open.obj",
        b"v -20 0 20\nv 20 0 20\nv 20 0 -20\nv -20 0 -20\n\
          v -5 0.5 -5\nv -5 0.5 3\nv 5 0.5 3\nv 5 0.5 -5\n\
          f 1 2 3 4\nf 5 6 7 8\n",
    );
    let scene = ["--scene", obj.to_str().unwrap()];
    let view = ["--eye", "0,0.3,2", "--target", "0,0,-1"];
    let args = |extra: &[&'static str]| -> Vec<&str> {
        let mut a = scene.to_vec();
        a.extend(view);
        a.extend(extra);
        a
    };
    let default = render_grey(d, "default.png", &args(&[]));
    let double = render_grey(d, "double.png", &args(&["--double-sided"]));
    let culled = render_grey(d, "culled.png", &args(&["--cull-back-faces"]));
    assert_eq!(default, double, "OBJ counts both sides by default");
    let mean = |g: &[u8]| g.iter().map(|&v| f64::from(v)).sum::<f64>() / g.len() as f64;
    assert!(
        mean(&default) + 40.0 < mean(&culled),
        "the back face darkens the floor: {} vs culled {}",
        mean(&default),
        mean(&culled)
    );
    let both = obscura(&[
        "render",
        "--double-sided",
        "--cull-back-faces",
        "--out",
        d.join("x.png").to_str().unwrap(),
    ]);
    assert_eq!(both.status.code(), Some(2), "{}", stderr(&both));
    assert!(
        stderr(&both).contains("cannot be used with"),
        "{}",
        stderr(&both)
    );
}

#[test]
fn normals_shading_uses_the_file_s_vertex_normals() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // A floor whose vertex normals lean 60° towards +x, and the same floor without them.
    let floor = "v -9 0 9\nv 9 0 9\nv 9 0 -9\nv -9 0 -9\n";
    let with = write(
        d,
        "lean.obj",
        format!("{floor}vn 0.866 0.5 0\nf 1//1 2//1 3//1 4//1\n").as_bytes(),
    );
    let without = write(d, "flat.obj", format!("{floor}f 1 2 3 4\n").as_bytes());
    let view = ["--eye", "0,2,3", "--target", "0,0,0", "--technique", "vao"];
    let render = |name: &str, scene: &Path, extra: &[&str]| {
        let mut a = vec!["--scene", scene.to_str().unwrap()];
        a.extend(view);
        a.extend(extra);
        render_grey(d, name, &a)
    };
    let flat = render("flat.png", &without, &[]);
    assert_eq!(
        render("face.png", &with, &["--normals", "face"]),
        flat,
        "--normals face ignores the vertex normals"
    );
    assert_eq!(
        render("flat-shading.png", &without, &["--normals", "shading"]),
        flat,
        "no vertex normals: face normals"
    );
    let shading = render("shading.png", &with, &["--normals", "shading"]);
    assert_ne!(shading, flat, "the leaning normals change the AO");
    // Issue 62: shading normals are the default where the file has vertex normals.
    assert_eq!(
        render("default.png", &with, &[]),
        shading,
        "shading normals by default"
    );
    let bad = obscura(&[
        "render",
        "--normals",
        "smooth",
        "--out",
        d.join("x.png").to_str().unwrap(),
    ]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("face, shading"), "{}", stderr(&bad));
}

#[test]
fn demo_page_scores_each_family_against_its_own_reference() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo");
    let o = obscura(&[
        "demo",
        "--size",
        "64x48",
        "--timing-frames",
        "1",
        "--spp",
        "16",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let scenes: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    assert_eq!(scenes.len(), 7, "every built-in scene");
    let info = info_json();
    let techniques = info["techniques"].as_array().unwrap();
    // One grid row per technique and one per reference (two), per scene; one table row per
    // technique per scene.
    assert_eq!(
        html.matches("<div class=\"label\">").count(),
        scenes.len() * (techniques.len() + 2),
        "grid rows"
    );
    assert_eq!(
        html.matches("<tr><td class=\"text\">").count(),
        scenes.len() * techniques.len()
    );
    // One heat-map scale for the page, stated once; every report was written with it.
    assert_eq!(html.matches("uses one scale").count(), 1);
    for scene in &scenes {
        let mut rows = 0;
        for model in ["vao", "hemisphere"] {
            let path = scene.join(model).join("report.json");
            let report: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
            assert_eq!(report["diff_scale"], 0.2, "{}", path.display());
            assert_eq!(report["reference"]["model"], model);
            // Each row is scored against its estimator's model: VAO's rows against vao.
            for r in report["results"].as_array().unwrap() {
                let name = r["technique"].as_str().unwrap();
                let row = techniques.iter().find(|t| t["name"] == name).unwrap();
                assert_eq!(
                    row["estimator"] == "vao",
                    model == "vao",
                    "{name} against {model}"
                );
                assert!(r["gpu_ms"].is_f64());
                rows += 1;
            }
            assert!(scene.join(model).join("cost.svg").is_file());
        }
        assert_eq!(rows, techniques.len());
    }
    assert_eq!(html.matches("class=\"verdict\"").count(), 7);
    // (Cells print rounded; their sort keys, `data-v="-0.00002"`, keep full precision.)
    assert!(!html.contains(">-0.0000<"), "negative zeros printed");
    // lavapipe is a CPU adapter: its times are marked, and said not to rank GPU cost.
    assert!(html.contains("ms (CPU)") && !html.contains("CPU) ms"));
    assert!(html.contains("do not rank GPU cost"));
}

#[test]
fn seed_001_options_are_clear_errors() {
    // Half resolution needs even sizes; bent normals need an estimator that reports them and full
    // resolution; the multi-view angle and compensation have ranges. Each fails with one line
    // naming the input, a non-zero exit and the old output untouched.
    for (extra, needles) in [
        (
            &["--resolution", "half", "--size", "65x48"][..],
            &["even", "65x48"][..],
        ),
        (&["--resolution", "quarter"], &["quarter", "'half'"]),
        (
            &["--technique", "hbao", "--bent-normals"],
            &["'hbao'", "bent normals", "gtao"],
        ),
        (
            &[
                "--technique",
                "gtao",
                "--bent-normals",
                "--resolution",
                "half",
            ],
            &["full resolution", "--bent-normals"],
        ),
        (
            &["--technique", "sd-hbao+-multiview", "--mv-angle", "75"],
            &["--mv-angle", "75", "(0, 60]"],
        ),
        (
            &["--technique", "sd-hbao+", "--sd-compensation", "0.5"],
            &["--sd-compensation", "0.5", "[1, 8]"],
        ),
    ] {
        one_line(&assert_render_fails(extra, needles));
    }
}

#[test]
fn bent_normals_are_written_next_to_the_ao() {
    // `render --bent-normals` writes NAME.bent.png: RGBA8, RGB = 0.5·n + 0.5 of the view-space
    // bent normal, alpha 255 on geometry. On `stairs` the close-up shows geometry everywhere, and
    // view-space normals face the camera (+z), so every blue channel is above the middle.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ao.png");
    let o = obscura(&[
        "render",
        "--scene",
        "stairs",
        "--technique",
        "gtao",
        "--bent-normals",
        "--size",
        "64x48",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bent = image::open(dir.path().join("ao.bent.png"))
        .unwrap()
        .to_rgba8();
    assert_eq!(bent.dimensions(), (64, 48));
    let covered: Vec<_> = bent.pixels().filter(|p| p[3] == 255).collect();
    assert!(
        covered.len() > 64 * 48 / 2,
        "{} covered pixels",
        covered.len()
    );
    assert!(
        covered.iter().all(|p| p[2] > 128),
        "a bent normal faces away from the camera"
    );
}

#[test]
fn compare_takes_an_outside_renderers_image_as_its_reference() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let view = [
        "--scene",
        "stairs",
        "--size",
        "64x40",
        "--timing-frames",
        "0",
    ];
    let techniques = ["--techniques", "vao,gtao-vb"];
    // The "outside" image: our own hemisphere ground truth of the view, as a file.
    let image = dir.path().join("outside.exr");
    let hemisphere = ["--model", "hemisphere", "--spp", "64"];
    let args = [
        &["reference"][..],
        &view[..4],
        &hemisphere,
        &["--out", image.to_str().unwrap()],
    ];
    let o = obscura_cached(&args.concat(), &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    let report = |out: &Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap()
    };
    // `compare` against `file` (with `extra` flags) into `name`: its stderr and report.
    let compare_with = |file: &Path, extra: &[&str], name: &str| {
        let out = dir.path().join(name);
        let args = [
            &["compare"][..],
            &view,
            &techniques,
            &["--reference-image", file.to_str().unwrap()],
            extra,
            &["--out", out.to_str().unwrap()],
        ];
        let o = obscura_cached(&args.concat(), &cache);
        assert!(o.status.success(), "{}", stderr(&o));
        (stderr(&o), report(&out))
    };
    // compare against the image and against the same ground truth traced by compare itself:
    // the same numbers for every technique.
    let (_, a) = compare_with(&image, &[], "with-image");
    let traced = dir.path().join("traced");
    let args = [
        &["compare"][..],
        &view,
        &techniques,
        &["--reference-model", "hemisphere", "--spp", "64"],
        &["--out", traced.to_str().unwrap()],
    ];
    let o = obscura_cached(&args.concat(), &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    let b = report(&traced);
    assert_eq!(a["reference"]["model"], "image 'outside.exr'");
    assert_eq!(b["reference"]["model"], "hemisphere");
    // An outside image's distance is not known here; the traced one's is VAO's radius.
    assert!(a["reference"]["radius"].is_null());
    assert_eq!(b["reference"]["radius"], 0.5);
    let rb = b["results"].as_array().unwrap();
    let same_numbers = |a: &serde_json::Value| {
        let ra = a["results"].as_array().unwrap();
        assert_eq!(ra.len(), 2);
        for (x, y) in ra.iter().zip(rb) {
            for key in ["mse", "mae", "ssim", "halo_bright", "halo_dark"] {
                let (x, y) = (x[key].as_f64().unwrap(), y[key].as_f64().unwrap());
                assert!(
                    (x - y).abs() <= 1e-9 * y.abs().max(1e-9),
                    "{key}: {x} vs {y}"
                );
            }
        }
    };
    same_numbers(&a);
    // The same image with its background (no geometry: alpha 0 in a PNG render of the view)
    // set to 0, as some renderers write it: the same numbers, and a note saying how many
    // background pixels were taken as 1.
    let render_png = dir.path().join("coverage.png");
    let args = [
        &["render"][..],
        &view[..4],
        &["--out", render_png.to_str().unwrap()],
    ];
    let o = obscura_cached(&args.concat(), &cache);
    assert!(o.status.success(), "{}", stderr(&o));
    let coverage = image::open(&render_png).unwrap().to_luma_alpha8();
    let linear = obscura::output::read_ao(&image).unwrap();
    let mut black_background = linear.values.clone();
    let mut background = 0;
    for (v, p) in black_background.iter_mut().zip(coverage.pixels()) {
        if p[1] == 0 {
            *v = 0.0;
            background += 1;
        }
    }
    assert!(background > 0, "the view has no background to test");
    let black = dir.path().join("outside-black-background.exr");
    obscura::output::write_ao(&black, 64, 40, &black_background).unwrap();
    let (err, with_black) = compare_with(&black, &[], "with-black");
    assert!(
        err.contains(&format!("{background} background pixels")),
        "{err}"
    );
    same_numbers(&with_black);
    // The same image as a 16-bit PNG through the sRGB transfer (as a renderer's display
    // output): with --reference-srgb the numbers are the traced ones up to the PNG's
    // quantisation; read as linear, the reference is brighter and the MSE off.
    let encode = |v: f32| {
        let v = v.clamp(0.0, 1.0);
        let e = if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        (e * 65535.0).round() as u16
    };
    let png = dir.path().join("outside-srgb.png");
    image::ImageBuffer::<image::Luma<u16>, _>::from_raw(
        64,
        40,
        linear.values.iter().map(|&v| encode(v)).collect::<Vec<_>>(),
    )
    .unwrap()
    .save(&png)
    .unwrap();
    let (_, decoded) = compare_with(&png, &["--reference-srgb"], "srgb");
    assert_eq!(
        decoded["reference"]["model"],
        "image 'outside-srgb.png' (sRGB decoded)"
    );
    let (_, as_linear) = compare_with(&png, &[], "srgb-as-linear");
    for ((x, y), z) in decoded["results"]
        .as_array()
        .unwrap()
        .iter()
        .zip(rb)
        .zip(as_linear["results"].as_array().unwrap())
    {
        let (x, y, z) = (
            x["mse"].as_f64().unwrap(),
            y["mse"].as_f64().unwrap(),
            z["mse"].as_f64().unwrap(),
        );
        // 16 bits: each decoded value within 2e-5 of the EXR's.
        assert!((x - y).abs() <= 1e-3 * y + 1e-7, "mse {x} vs {y}");
        // Undecoded, the encoding moves the MSE by more than 5 % (18 % here when written).
        assert!(
            (z - y).abs() > 0.05 * y,
            "read as linear: mse {z} against {y}"
        );
    }
    // Wrong size, a path, a model alongside, sRGB decoding of an EXR, or values that are not
    // numbers: one clear error each, and no report.
    let nan = dir.path().join("nan.exr");
    let mut values = vec![1.0f32; 64 * 40];
    values[100] = f32::NAN;
    obscura::output::write_ao(&nan, 64, 40, &values).unwrap();
    let out = dir.path().join("bad");
    let args = [
        &["compare"][..],
        &view[..4],
        &[
            "--reference-image",
            nan.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    ];
    let o = obscura(&args.concat());
    assert!(
        !o.status.success() && stderr(&o).contains("1 of its 2560 values are NaN or infinite"),
        "{}",
        stderr(&o)
    );
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &["--size", "64x40", "--reference-srgb"],
            &["--reference-srgb", "linear values", "outside.exr"],
        ),
        (
            &["--size", "64x48"],
            &["--reference-image", "64x40", "--size 64x40"],
        ),
        (
            &["--size", "64x40", "--path", "dolly"],
            &["--reference-image", "--path"],
        ),
        (
            &["--size", "64x40", "--reference-model", "vao"],
            &["--reference-image", "--reference-model"],
        ),
    ];
    for (extra, needles) in cases {
        let out = dir.path().join("bad");
        let args = [
            &[
                "compare",
                "--scene",
                "stairs",
                "--reference-image",
                image.to_str().unwrap(),
            ][..],
            extra,
            &["--out", out.to_str().unwrap()],
        ];
        let o = obscura(&args.concat());
        let err = stderr(&o);
        assert!(!o.status.success(), "{extra:?} was accepted");
        for n in needles {
            assert!(err.contains(n), "{extra:?}: {err}");
        }
        assert!(
            !err.contains("panicked") && !out.join("report.json").exists(),
            "{err}"
        );
    }
}

/// Issue 62: a settings file's invalid value is said once (it was the error's source too, and the
/// chain printed it twice), a `nan` in it is reported as written (not "null"), `diff --max-abs`
/// takes only a finite threshold of 0 or more, and frame and ray counts have upper bounds.
#[test]
fn issue_62_messages_are_said_once_and_bounds_are_clear() {
    let dir = tempfile::tempdir().unwrap();
    let bad = write(dir.path(), "bad.toml", b"[vao]\nradius = -1\n");
    let err = assert_render_fails(
        &["--scene", "stairs", "--settings", bad.to_str().unwrap()],
        &["bad.toml", "vao.radius -1"],
    );
    assert_eq!(err.matches("vao.radius -1").count(), 1, "{err}");
    one_line(&err);
    let err = assert_render_fails(&["--scene", "stairs", "--radius", "-1"], &["--radius -1"]);
    assert_eq!(err.matches("--radius -1").count(), 1, "{err}");
    one_line(&err);
    let nan = write(dir.path(), "nan.toml", b"[vao]\nradius = nan\n");
    let err = assert_render_fails(
        &["--scene", "stairs", "--settings", nan.to_str().unwrap()],
        &["nan.toml", "vao.radius nan"],
    );
    assert!(!err.contains("null"), "{err}");
    // Thresholds: refused by the parser, before any image is read.
    for bad in ["NaN", "inf", "-1"] {
        let o = obscura(&["diff", "a.exr", "b.exr", "--max-abs", bad]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("--max-abs") && err.contains("finite"), "{err}");
    }
    // Counts: clap's bounds, named with the range.
    for args in [
        &["bench", "--scene", "stairs", "--frames", "1000000000"][..],
        &["bench", "--scene", "stairs", "--warmup", "4294967295"],
        &[
            "reference",
            "--scene",
            "stairs",
            "--model",
            "hemisphere",
            "--spp",
            "4294967295",
        ],
        &["compare", "--scene", "stairs", "--timing-frames", "1000000"],
    ] {
        let o = obscura(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains("is not in"), "{args:?}: {err}");
    }
}

/// Issue 62: a size whose buffers exceed the device's storage-binding limit (8K on lavapipe's
/// 128 MiB) is one message naming the buffer, the limit, the technique and the fix; it was
/// wgpu's validation error, printed three times. A device that binds that much renders it.
#[test]
fn a_size_over_the_devices_buffer_limits_is_one_message() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.png");
    let o = obscura(&[
        "render",
        "--scene",
        "stairs",
        "--size",
        "7680x4320",
        "--technique",
        "sd-vao",
        "--out",
        out.to_str().unwrap(),
    ]);
    if o.status.success() {
        return;
    }
    let err = stderr(&o);
    one_line(&err);
    for needle in [
        "7680x4320",
        "sd-vao",
        "max_storage_buffer_binding_size",
        "--size",
    ] {
        assert!(err.contains(needle), "{needle:?} not in: {err}");
    }
    assert!(!err.contains("Validation Error"), "{err}");
}

#[test]
fn a_scene_without_cameras_gets_a_printed_automatic_camera_inside_a_room() {
    // A room 8 × 3 × 4 with a pillar, its faces wound to face the inside: the camera goes in
    // (outside, its walls would show no occlusion at all), and the camera it prints renders the
    // same image when passed back.
    let dir = tempfile::tempdir().unwrap();
    let mut obj = String::new();
    for (x, y, z) in [(-4, 0, -2), (4, 0, -2), (4, 3, -2), (-4, 3, -2)] {
        obj += &format!("v {x} {y} {z}\n");
    }
    for (x, y, z) in [(-4, 0, 2), (4, 0, 2), (4, 3, 2), (-4, 3, 2)] {
        obj += &format!("v {x} {y} {z}\n");
    }
    obj += "v 0.5 0 -0.3\nv 0.9 0 -0.3\nv 0.9 0 0.1\nv 0.5 0 0.1\n";
    obj += "v 0.5 3 -0.3\nv 0.9 3 -0.3\nv 0.9 3 0.1\nv 0.5 3 0.1\n";
    // Room (inward): floor, ceiling, four walls; pillar (outward): four sides.
    obj += "f 5 6 2 1\nf 3 7 8 4\nf 2 3 4 1\nf 8 7 6 5\nf 4 8 5 1\nf 6 7 3 2\n";
    obj += "f 13 14 10 9\nf 14 15 11 10\nf 15 16 12 11\nf 16 13 9 12\n";
    let scene = write(dir.path(), "room.obj", obj.as_bytes());
    let render = |out: &Path, camera: &[&str]| {
        let mut args = vec![
            "render",
            "--scene",
            scene.to_str().unwrap(),
            "--size",
            "64x48",
        ];
        args.extend_from_slice(camera);
        args.extend(["--technique", "vao", "--out", out.to_str().unwrap()]);
        let o = obscura(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    let auto = dir.path().join("auto.png");
    let note = render(&auto, &[]);
    assert!(note.contains("an automatic camera inside it"), "{note}");
    let value = |flag: &str| {
        let rest = &note[note
            .find(flag)
            .unwrap_or_else(|| panic!("{flag} in {note}"))
            + flag.len()..];
        rest.split_whitespace().next().unwrap().to_string()
    };
    let (eye, target, fov) = (value("--eye "), value("--target "), value("--fov "));
    let eye_x: f32 = eye.split(',').next().unwrap().parse().unwrap();
    assert!(eye_x.abs() < 4.0, "eye {eye} outside the room");
    let again = dir.path().join("again.png");
    let note = render(&again, &["--eye", &eye, "--target", &target, "--fov", &fov]);
    assert!(!note.contains("automatic"), "{note}");
    let (_, _, a) = grey(&auto);
    let (_, _, b) = grey(&again);
    assert!(a == b, "the printed camera renders another image");
    // Inside, the room's corners and the pillar occlude: not an all-white image.
    assert!(
        a.iter().any(|&v| v < 200),
        "no occlusion in the automatic view"
    );
}
