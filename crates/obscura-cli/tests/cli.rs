//! The `obscura` binary end to end: good runs produce real files, bad input gives one clear
//! error, a non-zero exit, no panic, and never a (half-)written output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn obscura(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_obscura"))
        .args(args)
        .output()
        .expect("run obscura")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `obscura render` with `extra` arguments writing to a fresh `out.png` that already holds
/// old content; asserts failure with a message containing every `needle`, and that the old file
/// is untouched and no temporary file is left.
fn assert_render_fails(extra: &[&str], needles: &[&str]) {
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
    let b64 = base64(&bin);
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

fn base64(bytes: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(T[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
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
    let f = image::open(&exr).unwrap().to_rgb32f();
    assert!(f.pixels().all(|p| (0.0..=1.0).contains(&p[0])));
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
        ["stairs", "colonnade", "layers", "grass", "tower", "cornell"]
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
        "vao",
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
    assert_eq!(
        (v["width"].as_u64(), v["height"].as_u64()),
        (Some(64), Some(48))
    );
    assert_eq!(v["reference"]["model"], "vao");
    let results = v["results"].as_array().unwrap();
    assert_eq!(results.len(), 1);
    assert_eq!(results[0]["technique"], "vao");
    for key in ["mse", "mae", "psnr", "ssim", "halo_bright", "halo_dark"] {
        assert!(results[0].get(key).is_some(), "{key} missing");
    }
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
    let again: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    assert_eq!(again, v, "a cached reference gives the same report");
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
    let img = image::open(&exr).unwrap().to_rgb32f();
    assert_eq!((img.width(), img.height()), (48, 32));
    assert!(img.pixels().all(|p| (0.0..=1.0).contains(&p[0])));
    assert!(
        img.pixels().any(|p| p[0] < 0.9),
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
}

#[test]
fn ctrl_c_during_reference_leaves_no_file() {
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
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "interrupted runs exit with 130");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "files left after Ctrl-C: {left:?}");
}

#[test]
fn no_matching_adapter_says_how_to_get_one() {
    let o = obscura(&["info", "--adapter", "no-such-gpu-anywhere"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(
        err.contains("no-such-gpu-anywhere") && err.contains("mesa-vulkan-drivers"),
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
        !o.status.success() && stderr(&o).contains("rt-svao"),
        "{}",
        stderr(&o)
    );
}
